"""examples/eq-fkme2d: the 2d FK-ME interface and thermal creep of pinned
kinks (beyond the paper), on small systems with the examples' own
functions (run.py, run_creep.py):

* a straight front in 2d is the kink of the 1d chain: it runs at the exact
  discrete-chain velocity fkme.vk_discrete;
* PN pinning: straight fronts stay put below f_+ (fkme.discrete_depinning_force)
  and run above it;
* quenched disorder (d_n gaussian, sd w): at a force where the ordered
  interface stays pinned, the fronts of a disordered one advance and are
  arrested again (an arrested avalanche);
* creep: the barrier dE of a PN-pinned kink from the constrained saddle is
  positive, kinks hop at T = dE/3 and not at T = dE/30, and the Arrhenius
  fit of the hop rate gives dE.
"""
import importlib.util
import math

import numpy as np

from conftest import ROOT, load_example
from eqtools import fkme

run = load_example("eq-fkme2d")
_spec = importlib.util.spec_from_file_location("example_eq_fkme2d_creep",
                                               ROOT / "examples" / "eq-fkme2d" / "run_creep.py")
creep = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(creep)

KC, UC, K = 1.0, 1.0, 0.07


def test_straight_front_in_2d_runs_at_the_discrete_chain_velocity(tmp_path):
    """L = 128, 48 columns slipped, f = 0.75, fix brownian dt = 0.2.
    Tolerance 1 %: the integrator's first-order error 6.6e-3 dt = 1.3e-3
    (doc of fix eq/substrate), the column times quantized to dt = 0.2 over a
    period 1/v = 27 (< 1e-3 on the slope fitted over ~20 columns), and the
    transient of the sharp initial step after 8 skipped columns (< 3e-3
    measured at f = 0.75 and 0.9).  Fronts that came closer than ~4 widths
    would speed up by several %: the run stops 30 columns apart."""
    f = 0.75
    st = run.run_straight(tmp_path, f0=f, skip=8)
    assert len(st["ks"]) >= 10
    assert abs(st["v"] / st["vk_discrete"] - 1) < 0.01, (st["v"], st["vk_discrete"])
    # and the continuum Eq. crack.eqi04 is 9 % off: the test can tell them apart
    assert abs(st["v"] / st["vk_continuum"] - 1) > 0.05


def _band(tmp, f, g=25.0, w=0.0, L=64, tmax=1500.0):
    """Band of L/2 slipped columns at constant force f; slipped fraction and
    max velocity at the end."""
    run.lammps(tmp, L=L, g=g, w=w, f0=f, init="band", band=L // 2, mode="run", tmax=tmax,
               every=10 ** 9, thermo=500)
    ser = fkme.read_ave_time(tmp / "series.dat")
    return ser["v_frac"], ser["v_vmx"]


def test_straight_fronts_pinned_below_f_plus_and_running_above(tmp_path):
    """g = 25: f_+ = 0.6214.  0.01 below it the two fronts of the band do
    not move in 1500 time units; 0.01 above it they run at v_k ~ 0.0069
    (one column per 145 time units: ~10 columns in 1500)."""
    fm, fp = fkme.discrete_depinning_force(25.0, KC, UC, K)
    assert abs(fp - 0.6215) < 1e-3
    frac, vmax = _band(tmp_path / "below", fp - 0.01)
    assert np.all(np.abs(frac - 0.5) < 1e-12), frac
    assert vmax[-1] < 1e-6
    frac, _ = _band(tmp_path / "above", fp + 0.01)
    vk = fkme.vk_discrete(fp + 0.01, 25.0, KC, UC, K, 1.0, 100.0)
    cols = (frac[-1] - 0.5) * 64 / 2         # columns advanced per front
    assert cols >= 0.5 * vk * 1500, (cols, vk * 1500)


def test_disorder_lets_fronts_advance_and_arrests_them(tmp_path):
    """g = 5 (f_+ = 0.6827), f = 0.64: the ordered interface is pinned
    (slipped fraction stays 1/2); with d_n gaussian(1, 0.2) the fronts pass
    their weak spots, advance by an avalanche and are arrested by strong
    ones: the slipped fraction ends above 1/2 and below 1, with every block
    at rest.  (In this model disorder lowers the depinning force of a
    straight front, f_c - f_+ ~ -0.14 kc w for g = 5, examples/eq-fkme2d.)"""
    fm, fp = fkme.discrete_depinning_force(5.0, KC, UC, K)
    assert abs(fp - 0.6827) < 1e-3
    f = 0.64
    frac0, _ = _band(tmp_path / "w0", f, g=5.0, w=0.0, tmax=3000.0)
    assert np.all(np.abs(frac0 - 0.5) < 1e-12)
    frac, vmax = _band(tmp_path / "w02", f, g=5.0, w=0.2, tmax=3000.0)
    assert 0.5 + 10 / 64 ** 2 < frac[-1] < 0.9, frac[-1]
    assert vmax[-1] < 1e-5, vmax[-1]
    assert frac[-1] == frac[-2]              # arrested: no slip in the last 100 time units


def test_creep_of_a_pinned_kink_pair(tmp_path):
    """N = 128, f = 0.59 (f_- = 0.519 < f < f_+ = 0.621): the saddle of a
    hop (the block ahead of the kink held at the cusp, the rest minimized) is
    above the static state; at T = dE/3 the kinks hop (transition-state
    theory: 2 A e^-3 t ~ 20 hops in t = 400 per kink pair, A = 0.51) and at
    T = dE/30 none in t = 2000 (expected 1e-10).  The Arrhenius fit over
    T = dE/3, dE/4, dE/5 (40, 40, 30 hops: sd(E)/dE ~ 15 %) must give dE
    within 35 %: 2 sd plus the bias of the prefactor, which is below TST by
    the friction's recrossings at the cusp (0.5-0.9 of A measured, slowly
    varying with T)."""
    N, n0, n1 = 128, 48, 80
    sad = creep.saddle(tmp_path / "saddle", f=0.59, N=N, n0=n0, n1=n1)
    assert sad["dE"] > 1e-3, sad
    assert abs(sad["u_b"] - 1.0) < 1e-9
    runs = [creep.creep(tmp_path / ("T%d" % i), sad["dE"] / x, f=0.59, N=N, n0=n0, n1=n1,
                        seed=4711 + i, tmax=8000.0, nhop=nh)
            for i, (x, nh) in enumerate([(3.0, 40), (4.0, 40), (5.0, 30)])]
    assert runs[0]["n"] >= 10 and runs[0]["tend"] < 8000.0
    assert all(r["n"] >= 10 for r in runs)
    # forward hops only: f is far above the backward depinning force f_-
    assert all(r["nback"] == 0 for r in runs)
    cold = creep.creep(tmp_path / "cold", sad["dE"] / 30.0, f=0.59, N=N, n0=n0, n1=n1,
                       seed=9, tmax=2000.0, nhop=5)
    assert cold["n"] == 0
    fit = creep.fit_arrhenius(runs)
    assert abs(fit["E"] / sad["dE"] - 1) < 0.35, (fit, sad["dE"])
    # the rate is below the TST bound and within a factor 3 of it
    A = creep.tst_prefactor(25.0, N)
    for r in runs:
        ratio = r["rate"] / (A * math.exp(-sad["dE"] / r["T"]))
        assert 0.33 < ratio < 1.3, (r["T"], ratio)


def test_random_state_nucleates_several_fronts(tmp_path):
    """The example's random initial state (L = 128, f = 0.75, a random 25 %
    of the blocks one period ahead): isolated pre-slipped blocks fall back,
    clusters above the critical size grow as closed fronts, several of
    them (5 in the example), and their fronts slip the whole interface
    (at t = 1375 in the example).  f = 0.75 is below f_max = k_c + K, so
    the unslipped interface is stable: the fronts do the slipping.  The
    slipped fraction first falls (blocks falling back) and then grows."""
    assert 0.75 < fkme.f_max(KC, UC, K)
    r = run.run_fronts(tmp_path, tmax=1600.0)
    assert r["nuclei"] >= 2, r["nuclei"]
    assert r["t_full"] < 1600.0
    frac = r["frac"]
    k0 = r["k0"]
    assert frac[k0] < 0.25                      # the isolated blocks fell back
    assert np.all(np.diff(frac[k0:]) >= 0)      # then the fronts only advance
