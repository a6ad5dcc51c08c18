"""Interacting contacts (pair eq/elastic, k = ftilde/r up to lambda_c = 3a)
against the mean-field master equation of paper Sec. IV.

References, all independent of the EQ code:
* beta = 1 + kappa S with S = sum_j a/r_j over the lattice (mean-field
  narrowing of the thresholds; S = 19.0 for lambda_c = 3a) -- the EQ run's
  Q_s is fitted by the effective-distribution ME and its beta compared;
* the ME (eq-me) with the paper's effective distributions (b1..b4): the
  L1 distance int |Q_EQ - Q_ME| dx must stay within the statistical floor
  (measured in the same test at kappa = 0, where the ME is exact) plus the
  model allowance 0.03 (the paper's "perfect fit"), at kappa = 0.02, 0.06
  and 0.1 (run_steady.py, X in [2, 8]: 0.019, 0.036, 0.043 against the
  floor 0.016); at kappa = 0.5 the paper's linear forms fail (L1 0.29),
  which is tested as a limit;
* the ME with the paper's onset forms (c1, c2, kappa_c): RMS of F/(N k_c)
  over the first drop at kappa = 0.01 and 0.03, and their failure at 0.07;
* the breakdown strength kappa_c ~ 0.074 of the paper: below it the onset
  avalanches are small, above it one avalanche breaks every contact.
"""
import math

import numpy as np
import pytest

import eqtools
from conftest import ROOT
from eqtools import meanfield as mf

INPUT = ROOT / "examples" / "eq-interact" / "in.eq-interact"
N = 4080
MODEL_ALLOWANCE = 0.03


def steady_hist(tmp, kappa, seed=4711, xmax=5.0, xhist=2.0, lam=3.0, crossing="exact"):
    d = tmp / ("k%g_l%g_%s" % (kappa, lam, crossing))
    d.mkdir(parents=True, exist_ok=True)
    eqtools.run_lammps(INPUT, {"kappa": kappa, "seed": seed, "Xmax": xmax, "Xhist": xhist,
                               "lam": lam, "crossing": crossing, "out": d}, cwd=d)
    c, n, tot = eqtools.read_histo(d / "Qs.dat")
    return c, n / tot / (c[1] - c[0])


@pytest.fixture(scope="module")
def floor(tmp_path_factory):
    """Statistical floor of the short runs (X in [2, 5], one seed): L1 at
    kappa = 0 against the exact non-interacting ME (measured 0.026 for
    seeds 4711, 11, 12)."""
    tmp = tmp_path_factory.mktemp("floor")
    c0, q0 = steady_hist(tmp, 0.0)
    x0, qme0, _ = mf.solve_steady(0.0, tmp / "me")
    return mf.l1_distance(c0, q0, x0, qme0)


@pytest.mark.parametrize("kappa", [0.02, 0.1])
def test_steady_state_paper_b_second_kappa(tmp_path, floor, kappa):
    """The paper's b1..b4 (alpha, beta, gamma linear in kappa) at two more
    kappas: L1 within floor + MODEL_ALLOWANCE.  Measured (X in [2, 5],
    seeds 4711, 11, 12): 0.024-0.026 at 0.02, 0.041 at 0.1, floor 0.026;
    the per-kappa fitted closed form reaches 0.021 and 0.010, so at 0.1 the
    paper's forms carry a model error of ~0.03 above the noise (the
    bound is the one of the kappa = 0.06 test)."""
    assert floor < 0.05, floor
    c, q = steady_hist(tmp_path, kappa)
    x, qme, _ = mf.solve_steady(kappa, tmp_path / "me")
    l1 = mf.l1_distance(c, q, x, qme)
    assert l1 < floor + MODEL_ALLOWANCE, (kappa, l1, floor)


def test_steady_state_paper_b_fails_at_kappa_05(tmp_path, floor):
    """A measured limit of the paper's linear forms: at kappa = 0.5 the
    ME with the paper's b1..b4 misses the EQ distribution by far more than
    the statistical floor (L1 0.29 in run_steady.py, X in [2, 8]; 0.292
    here, X in [2, 5], floor 0.026), while the closed form with alpha, beta,
    gamma fitted to the run still matches it (0.031)."""
    c, q = steady_hist(tmp_path, 0.5)
    x, qme, _ = mf.solve_steady(0.5, tmp_path / "me")
    l1 = mf.l1_distance(c, q, x, qme)
    assert l1 > 5 * floor, (l1, floor)
    a, b, g = mf.steady_params(0.5)
    fit, _ = mf.fit_steady(c, q, [a, b, max(g, 5e-3)])
    xf = np.linspace(-0.3, 1.6, 8001)
    l1_fit = mf.l1_distance(c, q, xf, mf.steady_closed_form(xf, *fit))
    assert l1_fit < floor + MODEL_ALLOWANCE, (l1_fit, floor)
    # with the reset of induced breaks (crossing step) the paper's forms
    # come far closer (here 0.075 against 0.292; run_steady.py, X in [2, 8]:
    # 0.076 against 0.29)
    cs, qs = steady_hist(tmp_path, 0.5, crossing="step")
    l1_reset = mf.l1_distance(cs, qs, x, qme)
    assert l1_reset < 0.5 * l1, (l1_reset, l1)


def test_lattice_sum():
    # shells 1 (6), sqrt3 (6), 2 (6), sqrt7 (12), 3 (6)
    exact = 6 + 6 / math.sqrt(3) + 6 / 2 + 12 / math.sqrt(7) + 6 / 3
    assert abs(mf.lattice_sum(3.0) - exact) < 1e-12


def test_steady_state_mean_field(tmp_path):
    # statistical floor: kappa = 0 against the exact (non-interacting) ME
    c0, q0 = steady_hist(tmp_path, 0.0)
    x0, qme0, _ = mf.solve_steady(0.0, tmp_path / "me")
    floor = mf.l1_distance(c0, q0, x0, qme0)
    assert floor < 0.05, floor    # a broken run would not reach this

    kappa = 0.06
    c, q = steady_hist(tmp_path, kappa)
    x, qme, _ = mf.solve_steady(kappa, tmp_path / "me")
    l1 = mf.l1_distance(c, q, x, qme)
    assert l1 < floor + MODEL_ALLOWANCE, (l1, floor)
    # without the interaction the distribution would be far away
    assert mf.l1_distance(c, q, x0, qme0) > 10 * (floor + MODEL_ALLOWANCE)

    # fitted effective parameters: beta against the mean-field 1 + kappa S
    a, b, g = mf.steady_params(kappa)
    (fa, fb, fg), _ = mf.fit_steady(c, q, [a, b, g])
    beta_mf = 1.0 + kappa * mf.lattice_sum(3.0)
    assert abs(fb / beta_mf - 1.0) < 0.03, (fb, beta_mf)
    # the re-forming shift alpha = kappa S <x> / beta, <x> the mean stretch
    xmean = float(np.sum(c * q) / np.sum(q))
    assert abs(fa / (kappa * mf.lattice_sum(3.0) * xmean / fb) - 1.0) < 0.05


def test_steady_state_mean_field_lambda5(tmp_path):
    """lambda_c = rcut = 5a (88 neighbours): the fitted narrowing beta and
    shift alpha follow the mean field with the lattice sum of that radius,
    S = sum_j a/r_j = 32.13 (measured at kappa = 0.03: beta 1.9671 vs
    1.9639, alpha 0.2544 vs 0.2522).  Bounds as for lambda_c = 3a."""
    kappa, S5 = 0.03, mf.lattice_sum(5.0)
    c, q = steady_hist(tmp_path, kappa, lam=5.0)
    # start from the paper's forms at the same mean-field strength
    a, b, g = mf.steady_params(kappa * S5 / mf.lattice_sum(3.0))
    (fa, fb, fg), _ = mf.fit_steady(c, q, [a, b, g])
    beta_mf = 1.0 + kappa * S5
    assert abs(fb / beta_mf - 1.0) < 0.03, (fb, beta_mf)
    xmean = float(np.sum(c * q) / np.sum(q))
    assert abs(fa / (kappa * S5 * xmean / fb) - 1.0) < 0.05
    # lambda_c = 3a at the same kappa would be far narrower than the fit says
    assert abs(fb / (1.0 + kappa * mf.lattice_sum(3.0)) - 1.0) > 0.1


def test_onset_and_breakdown(tmp_path):
    def onset(kappa):
        d = tmp_path / ("onset%g" % kappa)
        d.mkdir()
        eqtools.run_lammps(INPUT, {"kappa": kappa, "Xmax": 1.3, "dX": 0.005, "out": d}, cwd=d)
        F = eqtools.load(d / "F.dat")
        av = np.atleast_2d(np.loadtxt(d / "avalanches.dat"))
        return F[:, 1], F[:, 2], av

    # weak interaction: the paper's P_ci describes the first drop
    X, F, av = onset(0.01)
    Xm, Fm, _ = mf.solve_onset(0.01, tmp_path / "me", xmax=1.3)
    m = (X >= 0.7) & (X <= 1.1)
    rms = float(np.sqrt(np.mean((F[m] - np.interp(X[m], Xm, Fm)) ** 2)))
    assert rms < 0.05, rms          # measured 0.033 (paper c1, c2, kappa_c)
    # ... and better than the non-interacting ME (measured 0.097) by more
    # than 5 standard errors of F/(N k_c), sd(x) / sqrt(N) with sd(x) at
    # most that of the thresholds, 0.5 / sqrt(12)
    Xm0, Fm0, _ = mf.solve_onset(0.0, tmp_path / "me0", xmax=1.3)
    rms0 = float(np.sqrt(np.mean((F[m] - np.interp(X[m], Xm0, Fm0)) ** 2)))
    assert rms0 - rms > 5 * 0.5 / math.sqrt(12 * N), (rms0, rms)
    assert av[:, 1].max() < 0.01 * N
    # below kappa_c ~ 0.074: avalanches stay small against N ...
    _, F5, av5 = onset(0.05)
    assert av5[:, 1].max() < 0.1 * N
    # ... above it one avalanche breaks (almost) every contact: F drops abruptly
    _, F10, av10 = onset(0.1)
    assert av10[:, 1].max() >= 0.9 * N
    assert np.max(-np.diff(F10)) > 0.2
    assert np.max(-np.diff(F5)) < 0.05


def _run_onset_module():
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "eq_interact_run_onset", ROOT / "examples" / "eq-interact" / "run_onset.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_onset_paper_c_second_kappa_and_failure_near_kappa_c(tmp_path):
    """The paper's c1, c2, kappa_c (onset thresholds P_ci, Eq. mf.eq15) at
    kappa = 0.03 and their failure near kappa_c, measured as in
    run_onset.py (RMS of F/(N k_c) from X = 0.7 to the first minimum after
    the peak).  Floor: kappa = 0 against the exact ME in the same window
    (measured 0.0084, to X = 1.25: the standard error
    sd(x)/sqrt(N) of F).  Measured with the paper's c: 0.058 at 0.03, 0.21 at
    0.07 (run_onset.py --kappas 0.03 0.07 --nofit)."""
    ro = _run_onset_module()

    def rms(kappa):
        X, F, _ = ro.run_eq(kappa, tmp_path, xmax=1.3)
        Xm, Fm, _ = mf.solve_onset(kappa, tmp_path / "me", xmax=1.3)
        return ro.onset_rms(X, F, Xm, Fm, ro.first_minimum(X, F))[0]

    floor = rms(0.0)
    assert floor < 0.02, floor
    r03 = rms(0.03)
    assert r03 < floor + 0.08, (r03, floor)
    r07 = rms(0.07)
    assert r07 > max(0.15, 10 * floor), (r07, floor)     # the paper's forms fail near kappa_c
