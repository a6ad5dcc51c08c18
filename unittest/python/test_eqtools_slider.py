"""tools/eqtools/slider.py: the master equation in time for a spring-driven
slider, against independent references: the athermal first-generation
closed form and renewal transient, the constant-velocity transient at T > 0
of eqtools.thermal (lattice renewal equation, Richardson-extrapolated to
dX -> 0), conservation, grid convergence, and stick-slip vs steady sliding.
Small grids; all fast (no LAMMPS)."""
import numpy as np
import pytest

from eqtools import slider, thermal

LO, HI = 0.75, 1.25


def renewal_reference(theta, v, Xend, d=1e-3):
    """F(X) at constant velocity v from rest (continuous time): the lattice
    renewal equation of eqtools.thermal at steps d and d/2, Richardson-
    extrapolated (its bias is linear in the step).  Returns (X, F, the size
    of the extrapolation, a bound on its own error)."""
    n = int(round(Xend / d))
    X1, F1, _ = thermal.discrete_transient_force(v, d, n, theta=theta)
    _, F2, _ = thermal.discrete_transient_force(v, d / 2, 2 * n, theta=theta)
    F2 = F2[::2]
    return X1, 2.0 * F2 - F1, np.abs(F2 - F1)


def first_generation(X):
    """Athermal F(X) for X < 2 lo (no re-formed contact has broken yet):
    X P(x_s > X) + int_lo^min(X,hi) (X - y) dy/(hi - lo)."""
    S = np.clip((HI - X) / (HI - LO), 0.0, 1.0)
    b = np.clip(X, LO, HI)
    return X * S + ((X - LO) ** 2 - (X - b) ** 2) / (2.0 * (HI - LO))


def label_width(n):
    return (HI - LO) / n


# ------------------------------------------------- 1. athermal, quasi-static

def test_athermal_quasistatic_follows_the_me_curve():
    K, v, slow, dA, nl = 3.0, 1e-4, 1e-3, 4e-3, 16          # K > K* = 1.5
    r = slider.slider_me(K, v, 0.0, slow=slow, dX=2e-4, Xend=2.4, dA=dA, n_labels=nl, every=5)
    X, F = r["X"], r["F"]
    assert np.all(np.abs(r["attached"] - 1.0) < 1e-12)
    assert np.all(np.diff(X) > 0)                               # no back-slip: F(X) is path-free
    # before any re-formed contact breaks the initial contacts are exact
    # (anchor exactly 0, uniform threshold panels): only the crossing's
    # position within a step (midpoint) enters
    first = X < 2 * LO - 0.02
    np.testing.assert_allclose(F[first], first_generation(X[first]), atol=1e-7)
    assert np.abs(F[X <= LO] - X[X <= LO]).max() < 1e-9
    # the whole curve: renewal reference; grid error second order, measured
    # max |err| ~ 1.0 dA^2 at the kinks (dA = 1e-3 .. 4e-3): tolerance 3 dA^2
    Xr, Fr, dr = renewal_reference(0.0, v, 2.4)
    err = F - np.interp(X, Xr, Fr)
    assert np.abs(err).max() < 3 * dA ** 2 + 2e-6        # + reference error (O(d^2))
    # quasi-static: the spring balances friction + damping; inertia m X''
    # = slow^2 d2X/dstage2 is ~ slow x (change of X'/v at a kink of F(X))
    bal = K * (r["stage"] - X) - F - 2.0 * slow * r["V_over_v"]
    assert np.abs(bal).max() < 5 * slow
    # and the slider speed follows K/(K + F'(X)), F' = 1 - 2X on [lo, hi]
    sel = (X > 0.9) & (X < 1.2)
    np.testing.assert_allclose(r["V_over_v"][sel], K / (K + 1.0 - 2.0 * X[sel]), rtol=0.02)
    m = slider.slip_metrics(r)
    assert m["largest_jump"] == 0.0 and m["max_V_over_v"] < 3.0


# ----------------------------------------- 2. stiff spring: thermal transient

@pytest.mark.parametrize("theta", [0.02, 0.05])
def test_stiff_spring_matches_constant_velocity_transient(theta):
    v, dA, nl = 1e-4, 4e-3, 16
    r = slider.slider_me(1e3, v, theta, slow=1e-2, dX=4e-4, Xend=1.2, dA=dA, n_labels=nl, every=5)
    Xr, Fr, dr = renewal_reference(theta, v, 1.2)
    sel = r["stage"] > 0.05                                   # after the start-up (travel ~ slow)
    X, F = r["X"][sel], r["F"][sel]
    assert np.abs(r["V_over_v"][r["stage"] > 0.2] - 1.0).max() < 0.02
    err = F - np.interp(X, Xr, Fr)
    # error budget: threshold panels of width h (rate at the panel midpoint):
    # measured max |err| = 0.015 h^2/theta at three grids, second order;
    # anchors: dA^2; tolerance 3x that
    h = label_width(nl)
    tol = 3 * (0.015 * h * h / theta + dA ** 2)
    assert np.abs(err).max() < tol, (np.abs(err).max(), tol)
    # thermal activation matters here: the athermal curve is far away
    Xa, Fa, _ = renewal_reference(0.0, v, 1.2)
    assert np.abs(F - np.interp(X, Xa, Fa)).max() > 20 * tol
    # breaking rate: attached = 1, so after the start the broken mass per time
    # is what leaves: it must be positive and O(v / <L>)
    late = r["stage"] > 0.9
    assert np.all(r["rate"][late] > 0) and np.all(r["rate"][late] < 20 * v)


# ------------------------------------------ 3. conservation and convergence

def test_conservation_and_second_order_convergence():
    kw = dict(slow=1e-3, dX=4e-4, Xend=1.1, every=5)
    runs = [slider.slider_me(2.0, 1e-4, 0.02, dA=dA, n_labels=nl, **kw)
            for dA, nl in ((8e-3, 8), (4e-3, 16), (2e-3, 32))]
    for r in runs:
        assert np.abs(r["attached"] - 1.0).max() < 1e-12
    d1 = np.abs(runs[0]["F"] - runs[2]["F"]).max()
    d2 = np.abs(runs[1]["F"] - runs[2]["F"]).max()
    # second order: (1 - 1/16)/(1/4 - 1/16) = 5 (first order would give 3)
    assert d1 / d2 > 3.6, (d1, d2)
    assert d2 < 1e-3


def test_delay_conserves_absent_plus_attached():
    tau = 500.0                                               # v tau = 0.05
    r = slider.slider_me(2.0, 1e-4, 0.02, slow=1e-3, dX=4e-4, Xend=1.5, dA=4e-3,
                         n_labels=16, every=5, tau=tau)
    assert np.all(r["attached"] <= 1.0 + 1e-12)
    late = r["stage"] > 1.2
    # absent fraction = breaks during the last tau (rate x tau), approx.
    absent = 1.0 - r["attached"][late]
    assert np.all(absent > 0) and np.all(absent < 20 * 1e-4 * tau)


# ---------------------------------------------------------- 4. stick-slip

def test_slip_for_soft_spring_and_none_for_stiff():
    soft = slider.slip_metrics(slider.slider_me(0.6, 1e-2, 0.01, dX=4e-4, Xend=2.2, dA=4e-3, n_labels=16))
    assert soft["max_V_over_v"] > 30 and soft["largest_jump"] > 0.1
    stiff = slider.slip_metrics(slider.slider_me(2.0, 1e-4, 0.05, dX=4e-4, Xend=1.5, dA=4e-3,
                                                 n_labels=16))
    assert stiff["max_V_over_v"] < 3 and stiff["largest_jump"] == 0.0


def test_slip_metrics_from_rows():
    r = {"V_over_v": np.array([0, 1, 5, 8, 1, 1]), "X": np.array([0, 0.1, 0.5, 0.9, 1.0, 1.0]),
         "stage": np.array([0, 0.1, 0.2, 0.3, 0.4, 0.5])}
    m = slider.slip_metrics(r)
    assert m["max_V_over_v"] == 8
    assert m["largest_jump"] == pytest.approx((1.0 - 0.1) - (0.4 - 0.1))
