"""fix eq/substrate thermal: thermally activated hops of FK-ME blocks
between the wells of the sawtooth substrate (the law of fix eq/contacts,
lib/eq_thermal), against independent references.

* independent blocks held at a fixed stretch s0: the hop times are
  exponential with the rate nu(s0) = omega u^q exp(-(1 - s0/u_c)^(3/2)/theta)
  written out here (Kolmogorov-Smirnov band and the rate estimate, both
  with tolerances from the number of blocks);
* creep of an arrested kink (g = 25, f = 0.57 < f_+ = 0.6214): the hops
  counted against the renewal prediction along the exact (linear) relaxation
  of the chain after a hop (examples/eq-thermal/creep.py), with Poisson
  tolerances, and the Arrhenius slope -eps_a (1 - u_1/u_c)^(3/2) of
  ln v_creep against 1/T, u_1 from the static kink;
* theta = 1e-3 above f_+: the kink velocity of the keyword-off run, to the
  advance that the hops near the threshold allow (derived from the front
  block's velocity at the threshold);
* 1, 2 and 4 MPI ranks and a restart: the same hops, budgets and positions;
* errors: bad values, the keywords of fix eq/contacts this fix does not
  take, the shape and reverse mode, seed, restart layouts.
"""
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from eqtools import RunError, fkme, run_lammps

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("eq_thermal_creep",
                                               ROOT / "examples" / "eq-thermal" / "creep.py")
creep = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(creep)

BLOCKS = """
units           lj
dimension       2
atom_style      atomic
atom_modify     map array
boundary        p p p
lattice         sq 1.0
region          box block 0 ${N} 0 1 -0.5 0.5
create_box      1 box
create_atoms    1 box
mass            1 1.0
fix             sub all eq/substrate 1.0 sawtooth 1.0 reverse break ${args}
displace_atoms  all move ${s0} 0 0 units box
timestep        ${dt}
fix             hp all print 1 "$(step) $(f_sub[11]:%.0f)" file hops.dat screen no
thermo          100
run             ${steps}
"""


def blocks(tmp_path, args, N=4000, s0=0.6, dt=1.0, steps=600, check=True):
    inp = tmp_path / "in.blocks"
    inp.write_text(BLOCKS)
    return run_lammps(inp, variables=dict(N=N, s0=s0, dt=dt, steps=steps, args=args),
                      cwd=tmp_path, check=check)


# ------------------------------------------------- 1. independent blocks
@pytest.mark.parametrize("q", [0.0, 1.5])
def test_hop_times_of_held_blocks_are_exponential(tmp_path, q):
    """4000 immobile blocks (no integrator) at s0 = 0.6: the number that
    have hopped by step k is the empirical distribution function of their
    hop times at t_k (a block's first hop is at the time its budget b runs
    out, t = b / nu; its next well is at |s| = 0.4, whose rate is
    exp(-21) smaller).  KS band at significance 1e-3, 1.95/sqrt(N), and the
    rate from hops over exposure within 4 standard errors."""
    N, s0, theta, dt, steps = 4000, 0.6, 0.01, 1.0, 600
    omega = 1e9
    nu = omega * (1 - s0) ** q * math.exp(-(1 - s0) ** 1.5 / theta)
    blocks(tmp_path, f"thermal {theta} 1.0 {omega} barrier 0 {q} seed 12345", N=N, s0=s0, dt=dt,
           steps=steps)
    d = np.loadtxt(tmp_path / "hops.dat")
    k, n = d[:, 0], d[:, 1]
    assert n[0] == 0 and n[-1] <= N
    F = 1 - np.exp(-nu * k * dt)
    D = np.max(np.abs(n / N - F))
    assert D < 1.95 / math.sqrt(N), (D, nu)
    # rate: hops over the time the blocks spent unhopped (those hopping in a
    # step counted for half of it: an error nu dt / 12 relative)
    dn = np.diff(n)
    exposure = np.sum((N - n[:-1] - 0.5 * dn) * dt)
    nu_hat = n[-1] / exposure
    assert abs(nu_hat / nu - 1) < 4 / math.sqrt(n[-1]) + nu * dt / 12, (nu_hat, nu)


def test_no_hops_without_time_and_at_zero_temperature(tmp_path):
    """thermal 0 ...: no hop in 600 steps, even at a rate omega of 1e9 with
    no barrier left (u = 1 - 0.999); and the minimization of the creep input
    (thousands of force evaluations) at theta = 0.05, where a block of the
    kink would hop within a few time units: no hop, no well moved, the
    budgets as drawn (time passes only in a run)."""
    blocks(tmp_path, "thermal 0 1.0 1e9 seed 3", N=100, s0=0.999, steps=600)
    assert np.loadtxt(tmp_path / "hops.dat")[:, 1].max() == 0
    run_lammps(creep.INPUT, variables=dict(N=60, seed0=20, seed1=40, f=0.57, T=0.05, steps=0,
                                           dumpevery=1, out="."), cwd=tmp_path)
    d = dump_last(tmp_path / "creep.dump")
    assert d["f_sub[11]"].max() == 0 and np.array_equal(d["f_sub[10]"], d["f_sub[6]"])
    slipped = (d["id"] > 20) & (d["id"] <= 40)
    assert np.array_equal(d["f_sub[6]"], np.where(slipped, 1.0, 0.0))


# -------------------------------------------- 2. creep of an arrested kink
def test_arrested_kink_creeps_at_the_predicted_rate(tmp_path):
    """f = 0.57 < f_+: the kinks do not move at T = 0 (test_eq_substrate);
    at theta = b_1/x, x = 6, 7, 8 (b_1 = (1 - u_1)^(3/2) = 0.0105, u_1 =
    0.9519 of the static kink, omega = 1) the kinks advance by hops of their
    front blocks.  The mean time per hop and front W (88 hops of two fronts)
    against the renewal prediction W = 1/nu(u_1) + dead time of the exact
    relaxation (creep.predicted_wait; the hop of the front during the
    relaxation of the last one, a chance (W - 1/nu)/W, is what the renewal
    integral neglects at second order): within 3.5/sqrt(n) (Poisson; the
    renewal process is more regular).  Then ln(1/(W - dead time)) against
    1/theta: the Arrhenius slope -b_1 within 3.5 standard errors of the
    weighted fit.  Each temperature has its own seed (independent budgets:
    with one seed the same blocks draw the same budgets at every
    temperature, and the three counts share one fluctuation)."""
    f = 0.57
    u1 = creep.front_stretch(f)
    assert abs(u1 - 0.95192) < 1e-5
    assert f < fkme.discrete_depinning_force(25.0, 1.0, 1.0, 0.07)[1]
    rows = [creep.measure(f, x, tmp_path / f"x{x}") for x in (6.0, 7.0, 8.0)]
    for r in rows:
        assert r["n"] == creep.MAX_HOPS, r
        assert abs(r["W_meas"] / r["W"] - 1) < 3.5 / math.sqrt(r["n"]), r
    xinv = np.array([1 / r["theta"] for r in rows])
    dead = np.array([r["W"] - r["inv_nu"] for r in rows])
    Wm = np.array([r["W_meas"] for r in rows])
    y = -np.log(Wm - dead)
    sig = Wm / (Wm - dead) / np.sqrt([r["n"] for r in rows])
    wts = 1 / sig ** 2
    A = np.vstack([xinv, np.ones_like(xinv)]).T
    cov = np.linalg.inv(A.T @ (A * wts[:, None]))
    slope = (cov @ (A.T @ (wts * y)))[0]
    b1 = (1 - u1) ** 1.5
    assert abs(slope + b1) < 3.5 * math.sqrt(cov[0, 0]), (slope, -b1, math.sqrt(cov[0, 0]))
    assert math.sqrt(cov[0, 0]) < 0.3 * b1    # the fit resolves the slope


# ------------------------------------------------ 3. T -> 0 above f_+
def crossing_times(track, ids):
    t = track[:, 0]
    out, rates = [], []
    for k, ident in enumerate(ids):
        u = track[:, k + 1] - (ident - 1)
        j = np.nonzero(u >= 1.0)[0][0]
        out.append(t[j - 1] + (1.0 - u[j - 1]) / (u[j] - u[j - 1]) * (t[j] - t[j - 1]))
        rates.append((u[j - 1] - u[j - 2]) / (t[j - 1] - t[j - 2]))
    return np.array(out), np.array(rates)


def test_kink_velocity_at_vanishing_temperature(tmp_path):
    """f = 0.70 > f_+, theta = 1e-5, omega = 1: the kink runs as without the
    keyword.  A front block approaching u_c at speed w (0.0011 here: the
    front creeps up to the threshold) can hop only where the barrier is
    within a few theta of 0: with tau the time left until it reaches u_c,
    the hop comes earlier by E = int_0^inf (1 - exp(-G(tau))) dtau on
    average, G(tau) = int_tau^inf omega exp(-(w tau'/u_c)^(3/2)/theta)
    dtau' the hazard taken before, w from the keyword-off run; the kink
    velocity grows by about E v per site.  Bound 2 E v (w varies near u_c);
    the bound itself is below 1 % (at theta = 1e-3 it would be 25 %: the
    slow approach makes hops near u_c likely).  A hop only advances a slip
    and the overdamped chain keeps the order of configurations (no-passing):
    the kink is not slower."""
    f, theta = 0.70, 1e-5
    ids = list(range(150, 155))
    common = dict(N=200, seed0=80, seed1=120, f=f, T=theta, minimize=0, steps=16000, track=150,
                  every=1000)
    creep_run = lambda d, **v: run_lammps(creep.INPUT, variables=dict(common, out=".", **v),
                                          cwd=d)
    for name, th in (("off", "no"), ("on", "yes")):
        (tmp_path / name).mkdir()
        creep_run(tmp_path / name, thermal=th)
    t_off, w = crossing_times(np.loadtxt(tmp_path / "off" / "track.dat"), ids)
    t_on, _ = crossing_times(np.loadtxt(tmp_path / "on" / "track.dat"), ids)
    v_off = (ids[-1] - ids[0]) / (t_off[-1] - t_off[0])
    v_on = (ids[-1] - ids[0]) / (t_on[-1] - t_on[0])
    assert abs(v_off / fkme.vk_discrete(f, 25.0, 1.0, 1.0, 0.07, 1.0, 100.0) - 1) < 0.02
    wmin = w.min()
    assert wmin > 0
    tau = np.linspace(0, 50 * theta ** (2 / 3) / wmin, 20001)
    rate = np.exp(-(wmin * tau) ** 1.5 / theta)
    H = np.concatenate([[0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(tau))])
    G = H[-1] - H
    E = np.trapz(1 - np.exp(-G), tau)
    bound = 2 * E * v_off
    assert bound < 0.01
    assert -1e-6 <= v_on / v_off - 1 <= bound, (v_on, v_off, E)


# ------------------------------------------------ 4. ranks and restart
def dump_last(path):
    steps, cols = fkme.read_dump(path)
    return {k: v[-1] for k, v in cols.items() if k != "box"}


def test_ranks_and_restart_give_the_same_hops(tmp_path):
    """The creep run (f = 0.57, x = 6: ~20 hops in 60000 steps) on 1, 2 and 4
    ranks: the same wells, hop counts and lives (exactly: the budgets are
    keyed by seed, atom ID and life, not by rank), the budgets left and the
    positions to rounding (pair sums in another order); run 30000 +
    write_restart + read_restart + run 30000 on 1 rank: bit for bit, the
    budgets left included; read on 2 ranks: as the 2-rank run."""
    f = 0.57
    theta = (1 - creep.front_stretch(f)) ** 1.5 / 6
    # neighbor lists every step: with 'check yes' the lists of a restarted
    # run are built at other steps, and the pair sums round differently
    # (with or without thermal)
    common = dict(N=200, seed0=68, seed1=132, f=f, T=theta, every=1000, out=".", ncheck="no")
    cols = ["f_sub[6]", "f_sub[9]", "f_sub[10]", "f_sub[11]"]
    res = {}
    for p in (1, 2, 4):
        d = tmp_path / f"p{p}"
        d.mkdir()
        run_lammps(creep.INPUT, variables=dict(common, steps=60000, dumpevery=60000), nprocs=p,
                   cwd=d)
        res[p] = dump_last(d / "creep.dump")
    assert res[1]["f_sub[11]"].sum() >= 10
    assert len(set(res[4]["proc"])) == 4
    exact = ["f_sub[6]", "f_sub[10]", "f_sub[11]"]    # wells, lives, hops
    for p in (2, 4):
        for c in exact:
            assert np.array_equal(res[1][c], res[p][c]), (p, c)
        # the budgets left: the hazard of stretches equal to rounding
        assert np.allclose(res[1]["f_sub[9]"], res[p]["f_sub[9]"], rtol=1e-9, atol=1e-12), p
        assert np.abs(res[1]["x"] - res[p]["x"]).max() < 1e-10
    d = tmp_path / "split"
    d.mkdir()
    (d / "r1").mkdir()
    (d / "r2").mkdir()
    run_lammps(creep.INPUT, variables=dict(common, steps=30000, restartfile="half"), cwd=d)
    for p in (1, 2):
        run_lammps(creep.INPUT, variables=dict(common, steps=30000, readrestart="half",
                                               dumpevery=30000, out=f"r{p}"), nprocs=p, cwd=d)
    r1 = dump_last(d / "r1" / "creep.dump")
    r2 = dump_last(d / "r2" / "creep.dump")
    for c in cols + ["x"]:
        assert np.array_equal(res[1][c], r1[c]), c
    for c in exact:
        assert np.array_equal(res[1][c], r2[c]), c
    assert np.allclose(res[1]["f_sub[9]"], r2["f_sub[9]"], rtol=1e-9, atol=1e-12)
    assert np.abs(res[1]["x"] - r2["x"]).max() < 1e-10


def test_restart_layouts_must_agree(tmp_path):
    """A restart file written with the thermal keyword read by a fix without
    it, and the reverse: an error naming the keyword."""
    f = 0.57
    common = dict(N=60, seed0=20, seed1=40, f=f, T=0.001, steps=10, out=".", minimize=0)
    run_lammps(creep.INPUT, variables=dict(common, restartfile="with"), cwd=tmp_path)
    run_lammps(creep.INPUT, variables=dict(common, restartfile="without", thermal="no"),
               cwd=tmp_path)
    for rf, th in (("with", "no"), ("without", "yes")):
        out = run_lammps(creep.INPUT, variables=dict(common, readrestart=rf, thermal=th),
                         cwd=tmp_path, check=False)
        assert "ERROR" in out and "the keyword thermal adds 3 values per block" in out, out[-2000:]


# ------------------------------------------------------------ 5. errors
@pytest.mark.parametrize("args, message", [
    ("thermal 0.1 1 1 seed 1 aging log 0.1 1", "keyword 'aging' is one of fix eq/contacts"),
    ("thermal 0.1 1 1 seed 1 delay fixed 1", "keyword 'delay' is one of fix eq/contacts"),
    ("rest 5", "keyword 'rest' is one of fix eq/contacts"),
    ("thermal -1 1 1 seed 1", "thermal T: must be >= 0"),
    ("thermal 0.1 0 1 seed 1", "thermal eps_a: must be > 0"),
    ("thermal 0.1 1 0 seed 1", "thermal omega: must be > 0"),
    ("thermal 0.1 1 1 seed 1 barrier -1 0", "barrier p: must be >= 0"),
    ("thermal 0.1 1", "thermal"),
    ("thermal 0.1 1 1", "thermal: needs 'seed S'"),
    ("thermal 0.1 1 1 seed 0", "seed must be a positive integer"),
    ("thermal 0.1 1 1 seed 1.5", "seed must be a positive integer"),
    ("seed 4", "seed: the seed keys the budgets of thermal hops and needs the thermal keyword"),
    ("barrier 1 1", "barrier: needs the thermal keyword"),
])
def test_bad_thermal_input_is_an_error(tmp_path, args, message):
    out = blocks(tmp_path, args, N=10, steps=1, check=False)
    assert "ERROR" in out and "eq/substrate" in out and message in out, out[-1500:]


def test_thermal_needs_sawtooth_and_reverse_break(tmp_path):
    inp = tmp_path / "in.b"
    inp.write_text(BLOCKS.replace("sawtooth 1.0 reverse break", "${shape}"))
    for shape, message in (("smooth 1.0 reverse break", "thermal: needs the sawtooth shape"),
                           ("sawtooth 1.0", "thermal: needs 'reverse break'")):
        out = run_lammps(inp, variables=dict(N=10, s0=0.1, dt=1, steps=1, shape=shape,
                                             args="thermal 0.1 1 1 seed 3"),
                         cwd=tmp_path, check=False)
        assert "ERROR" in out and message in out, out[-1500:]
