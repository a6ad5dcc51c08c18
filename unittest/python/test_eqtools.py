"""tools/eqtools: the statistics the physics tests rely on, against closed
forms."""
import math

import numpy as np

import eqtools


def test_chi2_survival_closed_forms():
    # dof 2: P(chi2 > x) = exp(-x/2); dof 1: erfc(sqrt(x/2))
    for x in (0.1, 1.0, 5.0, 30.0, 80.0):
        assert abs(eqtools.chi2_sf(x, 2) - math.exp(-x / 2)) < 1e-13 * max(1, math.exp(-x / 2)) + 1e-300
        assert abs(eqtools.chi2_sf(x, 1) - math.erfc(math.sqrt(x / 2))) < 1e-12
    # dof 4: exp(-x/2) (1 + x/2)
    for x in (0.5, 3.0, 20.0):
        assert abs(eqtools.chi2_sf(x, 4) - math.exp(-x / 2) * (1 + x / 2)) < 1e-12


def test_chi2_histogram_merges_small_bins_and_is_calibrated():
    rng = np.random.default_rng(1)
    probs = np.array([1e-4, 0.2, 0.3, 0.2, 0.2, 0.0999])
    pvals = []
    for _ in range(400):
        counts = rng.multinomial(2000, probs / probs.sum())
        chi2, dof, p = eqtools.chi2_histogram(counts, probs)
        assert dof == 4        # the first bin (expected 0.2 counts) merged
        pvals.append(p)
    pvals = np.array(pvals)
    # p-values of a correct model are uniform: KS distance, n = 400
    s = np.sort(pvals)
    d = np.max(np.abs(s - (np.arange(1, 401) - 0.5) / 400))
    assert d < 1.95 / math.sqrt(400)     # KS at 1e-3


def test_bin_probabilities_exact_for_piecewise_linear_density():
    x = np.linspace(0.0, 1.25, 2001)
    q = np.where(x < 0.75, 1.0, (1.25 - x) / 0.5)     # Q_s of uniform [0.75,1.25]
    edges = np.linspace(-0.05, 1.3, 55)
    p = eqtools.bin_probabilities(x, q, edges)
    assert abs(p.sum() - 1.0) < 1e-12
    assert p[0] == 0.0 and p[1] == 0.0                  # nothing below x = 0
    # exact cumulative of the density
    cum = np.where(edges <= 0, 0, np.where(edges <= 0.75, edges,
                   np.where(edges <= 1.25, 0.75 + (edges - 0.75) * (1.25 - 0.5 * (edges + 0.75)) / 0.5,
                            1.0)))
    assert np.max(np.abs(p - np.diff(cum))) < 1e-9


def test_zscores_skip_points_without_a_normal_limit():
    n = 1000
    z = eqtools.zscores([1.0, 1.0], [0.0, 0.0], [1.0, 1.0], n, skew=[0.1, 100.0])
    assert abs(z[0] - math.sqrt(n)) < 1e-12 and z[1] == 0.0
