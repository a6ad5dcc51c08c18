"""tools/eqtools/thermal_screening.py: the elastic screening length at
T > 0 (shared/notes/thermal-aging.md (e) and check (f) 8; paper scr.eq01-10).

Conventions (those of the note): 1D chain of blocks one lambda_c apart,
nearest neighbours Pi1 = Pi0/2 (Pi0 the sum over the nu = 2 neighbours),
Gamma(eps) = r((1 + eps) v)/v with r(w) = w Gamma_s(w) of eqtools.thermal
(uniform thresholds [0.75, 1.25], omega = 1, p = q = 0), one pinned block.

- athermal limit: Gamma = (1 + eps)/x_c: seed and linearised lengths
  coincide, the lattice equals eqtools.meso.screening_lattice and its
  decay meso.chain_decay;
- the rate and its derivative: r equals thermal.steady_force's rate, r'
  equals an independent Richardson difference in ln w;
- the note's numbers at theta = 0.05, Pi0 = 0.3, v = 1e-12;
- check (f) 8: the seed formula's slope -1/2 in ln v, the finite
  linearised length, and the nonlinear lattice's decay length equal to the
  linearised lattice value at several v and theta.
"""
import math

import numpy as np
import pytest

from eqtools import meso, thermal as th
from eqtools import thermal_screening as ts

PI0 = 0.3


# ---------------------------------------------------------- athermal limit
@pytest.mark.parametrize("Pi0", [0.3, 0.6])
def test_athermal_limit_seed_equals_linearised_and_meso_lattice(Pi0):
    """Gamma = (1 + eps)/x_c: c = Pi0, eps0 = Pi0/(1 - Pi0) at every v, so
    the seed's (eps0/2)^1/2 equals the linearised continuum length; the
    linearised lattice length is meso.chain_decay's; the nonlinear solver
    (then linear) gives meso.screening_lattice's eps on every block and
    its fitted decay the exact lattice one."""
    ath = ts.AthermalRate()
    M = 61
    for v in (1e-12, 1e-2):
        e0 = ts.eps0(v, Pi0=Pi0, model=ath)
        assert e0 == pytest.approx(Pi0 / (1 - Pi0), rel=1e-14)
        assert ts.c_factor(v, Pi0=Pi0, model=ath) == pytest.approx(Pi0, rel=1e-14)
        seed = ts.lambda_seed(v, Pi0=Pi0, model=ath)
        assert ts.lambda_linear_continuum(v, Pi0=Pi0, model=ath) == pytest.approx(seed, rel=1e-13)
        ref_eps0, ref_rho, ref_ell, ref_lam = meso.chain_decay(0.5 * Pi0)
        assert seed == pytest.approx(ref_lam, rel=1e-13)
        ell, rho, _ = ts.lambda_linear_lattice(v, Pi0=Pi0, model=ath, full=True)
        assert rho == pytest.approx(ref_rho, rel=1e-13)
        assert ell == pytest.approx(ref_ell, rel=1e-13)

        sol = ts.chain_lattice(v, Pi0=Pi0, M=M, model=ath)
        sites = np.arange(M, dtype=float)[:, None]
        ref, _ = meso.screening_lattice(sites, [float(M)], sol["sliding"], 1.0,
                                        lambda r: 0.5 * Pi0)
        assert np.max(np.abs(sol["eps"] - ref)) < 1e-12 * (1 + e0)
        assert ts.lattice_decay(v, Pi0=Pi0, M=M, model=ath) == pytest.approx(ref_ell, rel=1e-6)
    # the thermal model at theta = 0 is the same law (r = w / <x_s>, <x_s> = 1)
    w = np.array([1e-12, 1e-6, 1e-2])
    assert np.allclose(ts.rate(w, 0.0), w, rtol=1e-13, atol=0)
    assert np.allclose(ts.rate_derivative(w, 0.0), 1.0, rtol=1e-13, atol=0)
    assert ts.lambda_seed(1e-8, 0.0, Pi0) == pytest.approx(ts.lambda_linear_continuum(1e-8, 0.0, Pi0),
                                                          rel=1e-12)


# ---------------------------------------------------------- the rate
@pytest.mark.parametrize("theta", [0.02, 0.05])
def test_rate_and_derivative(theta):
    """r(w) = w Gamma_s(w) equals thermal.steady_force's 'rate' (the same
    quadrature) to rounding; the analytic r' equals the central difference
    of r in ln w (Richardson, steps 2e-3 and 1e-3) within 1e-6 relative,
    the stated error estimate below that; r' > 0 and r'(w) < r(w)/w
    (Gamma_s falls with w, dL/dw > 0)."""
    w = np.array([1e-12, 5.6e-7, 1e-4, 1e-2])
    r = ts.rate(w, theta)
    ref = [th.steady_force(x, theta=theta, full=True)["rate"] for x in w]
    assert np.allclose(r, ref, rtol=1e-12, atol=0)
    d, err = ts.rate_derivative(w, theta, error=True)
    fd = (ts.rate(w * math.exp(1e-3), theta) - ts.rate(w * math.exp(-1e-3), theta)) / 2e-3 / w
    fd2 = (ts.rate(w * math.exp(2e-3), theta) - ts.rate(w * math.exp(-2e-3), theta)) / 4e-3 / w
    rich = (4 * fd - fd2) / 3
    assert np.all(np.abs(d - rich) < 1e-6 * d)
    assert np.all(err < 1e-6 * d)
    assert np.all(d > 0) and np.all(d < r / w)


# ---------------------------------------------------------- the note's numbers
def test_note_numbers_theta005_v1e12():
    """theta = 0.05, Pi0 = 0.3, 1D chain, one pinned block, v = 1e-12:
    lattice decay 1.856 blocks, linearised 1.856 (lattice) / 1.83
    (continuum), seed formula 529 (tolerance: half a unit of the last
    quoted digit).  Also the uniform state solves its equation and the
    solver's residual is at rounding."""
    v, theta = 1e-12, 0.05
    e0 = ts.eps0(v, theta, PI0)
    mdl = ts.rate_model(theta)
    assert abs(e0 - PI0 * float(ts.load_gamma(e0, v, mdl))) < 1e-12 * e0
    assert abs(ts.lambda_seed(v, theta, PI0) - 529) <= 0.5
    assert abs(ts.lambda_linear_continuum(v, theta, PI0) - 1.83) <= 0.005
    assert abs(ts.lambda_linear_lattice(v, theta, PI0) - 1.856) <= 0.0005
    d = ts.lattice_decay(v, theta, PI0, M=201, full=True)
    assert abs(d["ell"] - 1.856) <= 0.0005
    assert d["solution"]["residual"] < 1e-12
    # the seed formula is 285 times the screening length here
    assert ts.lambda_seed(v, theta, PI0) / d["ell"] > 250


# ---------------------------------------------------------- check (f) 8
def test_seed_slope_and_finite_linearised_length():
    """theta = 0.05, Pi0 = 0.3, v = 1e-14..1e-10: d ln lambda_seed / d ln v
    = -0.500 +- 0.005 (eps0 ~ 1/v as r stays finite), while the linearised
    lengths stay put (relative change < 1e-3 over the four decades)."""
    vs = np.logspace(-14, -10, 5)
    assert ts.seed_slope(vs, 0.05, PI0) == pytest.approx(-0.5, abs=0.005)
    lat = [ts.lambda_linear_lattice(v, 0.05, PI0) for v in vs]
    cont = [ts.lambda_linear_continuum(v, 0.05, PI0) for v in vs]
    assert max(lat) / min(lat) - 1 < 1e-3
    assert max(cont) / min(cont) - 1 < 1e-3


@pytest.mark.parametrize("theta", [0.02, 0.05])
def test_lattice_decay_equals_linearised_lattice(theta):
    """The nonlinear chain (M = 101, one pinned block, Newton to 1e-12)
    decays away from the pinned block with the linearised lattice length
    -1/ln rho to 1e-3 relative (measured: ~1e-6) at v = 1e-12, 1e-8, 1e-4,
    1e-2; the local ratio delta_{n+1}/delta_n over the fitted tail agrees
    too."""
    for v in (1e-12, 1e-8, 1e-4, 1e-2):
        lin = ts.lambda_linear_lattice(v, theta, PI0)
        d = ts.lattice_decay(v, theta, PI0, M=101, window=(1e-8, 1e-4), full=True)
        assert len(d["k"]) >= 4
        assert d["ell"] == pytest.approx(lin, rel=1e-3), (theta, v)
        assert np.allclose(d["local"], lin, rtol=1e-3), (theta, v)
