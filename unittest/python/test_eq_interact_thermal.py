"""Interacting contacts (pair eq/elastic) at T > 0 and with aging (issue
23, item 1 for the interacting path; fix eq/contacts thermal, barrier,
aging, rest with pair eq/elastic).

Each step first samples the thermal breaks of the formed contacts along
their effective stretch e = s + h/k, linear from the end of the last step
to the new positions in the field of the step's start
(ContactModel::probe(), the thinning sampler of the plain path, up to the
aged threshold); the thermally broken contacts break in the avalanche's
first round, at the |e| where they broke, the motion since carried; the
avalanche tests the aged thresholds x_s0 A(age).  References:

- without coupling (kappa = 0) the path is the plain thermal fix
  (tested against the master equation in test_eq_thermal.py), the same
  draws: F(X) within one standard deviation of F for N contacts, the
  breaks within 1 %;
- at theta = 0 with vanishing aging the thermo output is the athermal
  interacting fix's, character for character;
- 1, 2, 4 ranks: the same breaks of every contact, values to rounding;
  a run split by a restart continues it the same way;
- with coupling, F_k falls as v falls (thermal creep: velocity
  strengthening), by far more than its scatter;
- with a delay, 1, 2, 4 ranks and a restart as above; contacts that
  wait in a restart file continued without a delay re-form at the set-up;
- quantitatively (the tests after "Exact reference"): F(X) from rest and
  the breaks at kappa = 0.06, theta = 0.05 (also with barrier 2 0.25),
  extrapolated linearly to dX -> 0 from dX = 0.002 and 0.001, against the
  exact event-driven Monte Carlo of tools/eqtools/interact_thermal.py
  (derived from the docs, not from the C++), within z-scores from the
  scatter of both; at theta = 0 the field and the athermal runs against
  the same Monte Carlo; with delays (the tests after "Formation delays")
  against its simulate_delay().
"""
import math
import time

import numpy as np
import pytest

import eqtools
from conftest import ROOT
from eqtools import interact_thermal as itm
from eqtools import thermal as th

INPUT = ROOT / "unittest" / "python" / "inputs" / "in.interact-thermal"
N = 480


def thermo(log):
    """Rows step X F/(N k_c) breaks rounds of the run."""
    rows = []
    for line in log.splitlines():
        parts = line.split()
        if len(parts) == 5:
            try:
                rows.append([float(x) for x in parts])
            except ValueError:
                pass
    return np.array(rows)


def run(d, nprocs=1, **var):
    d.mkdir(parents=True, exist_ok=True)
    return eqtools.run_lammps(INPUT, dict(var, out=d), nprocs=nprocs, cwd=d)


def state(d):
    text = (d / "state.dump").read_text().split("ITEM: ATOMS")[-1].splitlines()[1:]
    return np.array([[float(x) for x in l.split()] for l in text if l.strip()])


@pytest.mark.parametrize("extra", ["thermal 0.03 1.0 1.0",
                                   "thermal 0.05 1.0 1.0 barrier 2 0.25",
                                   "thermal 0.03 1.0 1.0 aging log 0.05 1.0 rest 10"])
def test_without_coupling_it_is_the_plain_thermal_path(tmp_path, extra):
    """kappa = 0: pair eq/elastic with no interaction against the fix
    without a pair style.  Both draw the same numbers; they differ where
    the plain path samples a new life over the rest of its step (the
    interacting one from the next step) and, with aging, where a crossing
    of the aged threshold is placed (within the step, or at its end).
    Bound: max |dF| below 1/sqrt(N) (0.046; F's standard deviation for N
    contacts is about 0.25/sqrt(N)), the mean below a quarter of that,
    the breaks within 1 % (measured: max 3.4e-3, 2.0e-3, 7.3e-3 and mean
    3.4e-4, 3.2e-4, 8.8e-4 over the samples every 0.05 x_c; the breaks
    equal to +-2)."""
    a = thermo(run(tmp_path / "pair", kappa=0.0, extra=extra))
    b = thermo(run(tmp_path / "plain", pair="no", extra=extra))
    assert a.shape == b.shape and a[-1, 1] == pytest.approx(4.0)
    dF = np.abs(a[:, 2] - b[:, 2])
    assert dF.max() < 1.0 / np.sqrt(N), dF.max()
    assert dF.mean() < 0.25 / np.sqrt(N), dF.mean()
    assert abs(a[-1, 3] - b[-1, 3]) <= 0.01 * b[-1, 3]
    assert b[-1, 3] > 3 * N    # each contact broke several times
    # the keywords matter: the athermal run is off by more than 5 standard
    # deviations of F somewhere
    c = thermo(run(tmp_path / "athermal", kappa=0.0, more=""))
    assert np.abs(a[:, 2] - c[:, 2]).max() > 5 * 0.25 / np.sqrt(N), np.abs(a[:, 2] - c[:, 2]).max()


def test_vanishing_aging_at_zero_temperature_is_the_athermal_path(tmp_path):
    """theta = 0 with aging of strength 1e-300 takes the thermal layout and
    the probe (ages, aged thresholds A = 1 to the bit) and must give the
    athermal interacting run to the last printed digit."""
    a = run(tmp_path / "aged", extra="aging log 1e-300 1.0", Xmax=2.0)
    b = run(tmp_path / "plain", Xmax=2.0, more="")
    ta, tb = thermo(a), thermo(b)
    assert ta.shape == tb.shape and ta[-1, 3] > N
    assert np.array_equal(ta, tb)


@pytest.mark.parametrize("extra", ["thermal 0.03 1.0 1.0 aging log 0.05 1.0 rest 10",
                                   "thermal 0.03 1.0 1.0 delay exp 5.0"])
def test_ranks_and_restart(tmp_path, extra):
    """kappa = 0.06, theta = 0.03, aging after a rest (or delays, whose
    waiting contacts leave the field and join it again): 1, 2, 4 ranks give
    every contact's break count exactly and its stretch, threshold,
    anchor, field, budget and age to 1e-9 (the field is a sum whose order
    follows the neighbour lists: rounding; test_eq_interact_parallel.py);
    a run split by write_restart/read_restart on 2 -> 4 ranks continues
    it the same way."""
    more = "f_c[8] f_c[9] f_c[10] f_c[11]"    # budget's run-out, formation, wait, pending
    data = tmp_path / "contacts.data"    # the same atom IDs at the same sites
    (tmp_path / "in.data").write_text(
        "units lj\ndimension 2\natom_style atomic\nboundary p p p\n"
        "lattice hex 1.1547005383792515\nregion box block 0 20 0 12 -0.5 0.5\n"
        "create_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\nwrite_data %s\n" % data)
    eqtools.run_lammps(tmp_path / "in.data", {}, cwd=tmp_path)
    ref = None
    for n in (1, 2, 4):
        d = tmp_path / f"np{n}"
        run(d, nprocs=n, extra=extra, Xmax=2.0, start="data", file=str(data), more=more)
        got = state(d)
        if ref is None:
            ref = got
            assert ref[:, 3].sum() > N    # breaks
            if "delay" in extra:
                assert (ref[:, 8] > 0).sum() > N / 20    # contacts waiting at the end
        else:
            assert np.array_equal(got[:, [0, 3]], ref[:, [0, 3]]), n
            assert np.allclose(got, ref, rtol=1e-9, atol=1e-9), n
    d = tmp_path / "split"
    run(d, nprocs=2, extra=extra, Xmax=1.0, wr="half.restart", start="data", file=str(data),
        more=more)
    run(d, nprocs=4, extra=extra, Xmax=2.0, start="restart", file="half.restart", more=more)
    got = state(d)
    assert np.array_equal(got[:, [0, 3]], ref[:, [0, 3]])
    assert np.allclose(got, ref, rtol=1e-9, atol=1e-9)


def test_friction_falls_with_velocity(tmp_path):
    """kappa = 0.06, theta = 0.03: the mean F/(N k_c) over X in [2, 4] at
    v = 0.1, 0.01, 0.001 decreases (thermal breaks below the thresholds
    grow as loading slows), each time by more than 0.02.  Measured (seeds
    11, 12, 13, 4711): 0.504-0.508, 0.452-0.456, 0.399-0.402 (standard
    deviation between seeds 0.0015, so the bound is 13 of them; the
    athermal run 0.534)."""
    means = []
    for v in (0.1, 0.01, 0.001):
        t = thermo(run(tmp_path / f"v{v}", v=v, extra="thermal 0.03 1.0 1.0"))
        means.append(t[t[:, 1] >= 2.0, 2].mean())
    assert means[0] - means[1] > 0.02 and means[1] - means[2] > 0.02, means


def test_waiting_contacts_of_a_restart_reform(tmp_path):
    """A restart file of independent contacts with a delay (86 of the
    480 waiting at X = 1) continued with the pair style, whose contacts take no
    delay: the waiting ones re-form at the set-up, so that after one step
    none waits and every contact carries force again (F far above the
    waiting state's)."""
    extra = "thermal 0.03 1.0 1.0"
    run(tmp_path, pair="no", extra=extra + " delay exp 10.0", Xmax=1.0, wr="w.restart",
        more="f_c[10]")
    waiting = state(tmp_path)[:, -1]
    assert (waiting > 0).sum() > N / 10    # many wait
    t = thermo(run(tmp_path, extra=extra, Xmax=1.002, start="restart", file="w.restart",
                   more="f_c[10]"))
    assert (state(tmp_path)[:, -1] == 0.0).all()
    assert np.isfinite(t[:, 2]).all()


# ======================================================================
# Exact reference: event-driven Monte Carlo (tools/eqtools/interact_thermal.py)
# ======================================================================
#
# The model of the docs (fix eq/contacts "Interacting contacts", reform_as
# force, crossing exact, "Temperature, velocity and aging"; pair eq/elastic
# k(r) = ftilde/r within lambda_c = r_c = 3, shells at exactly r_c included)
# in continuous time: every effective stretch e_i = s_i + h_i/k grows at v,
# contact i breaks thermally at the rate nu(e_i; x_si) (its next break found
# by inverting the closed-form hazard) or when e_i reaches x_si; a break
# re-forms it with force k r (r = 0), the rest of a load past x_s carried,
# and raises its partners' e_j by k_ij D_i/(k + K_i); avalanches take no time.
# The fix approaches it as dX -> 0 (docs: an error of order nu dt per life).
#
# Statistics.  LAMMPS: SEEDS seeds (-var seed) at DXS = 0.002 and 0.001, the
# same seeds at both (paired: the draws are keyed by seed, atom and break
# count, so the two runs of a seed are correlated, 0.8 for the steady F),
# each run's observable extrapolated linearly to dX = 0,
# o_0 = 2 o(0.001) - o(0.002) (the docs: an error of order nu dt per life,
# first order in dX; measured linear, below).  Monte Carlo: RMC replicas.  An
# observable's z = (mean_EQ - mean_MC) / sqrt(var_EQ/S + var_MC/R) with the
# variances between runs of each side; |z| < Z_MAX = 4.5 for every one
# (t with S - 1 = 23 degrees of freedom: P(|t| > 4.5) = 1.6e-4 for one
# observable, < 4e-3 for the 20-odd of a case; the runs use fixed seeds).
#
# Measured with many more runs (64 LAMMPS seeds, 256 MC replicas; theta =
# 0.05, kappa = 0.06, v = 0.01), mean F/(N k_c) over X in [2, 4]:
#   MC 0.41752 +- 0.00009 (one run's scatter 0.0014)
#   EQ dX 0.005 0.42006, 0.002 0.41853, 0.001 0.41803 (+- 0.00017 each):
#   linear in dX, slope +0.50 x_c per unit dX (paired difference of 0.002
#   and 0.001: 0.00050 +- 0.00010); extrapolated 0.41753 +- 0.00023, z = 0.05.
#   Breaks up to X = 4: MC 4517.3 +- 1.0, EQ (dX 0.001) 4519.6 +- 2.1.
# With barrier 2 0.25: MC 0.44115 +- 0.00012, EQ 0.44164 (0.002), 0.44121
# (0.001), extrapolated 0.44078 +- 0.00029 (z = -1.2); breaks 4368.0 +- 1.1
# against 4366.2 +- 2.5.  At theta = 0: MC 0.52037 +- 0.00011, EQ (any dX)
# 0.52007 +- 0.00020 (z = -1.3).
V = 0.01
KAPPA = 0.06            # pair_coeff ftilde = kappa k_c x_c (k_c = 1, x_c = <x_s> = 1)
XS = np.round(np.arange(81) * 0.05, 12)     # the input's thermo samples, X in [0, 4]
DXS = (0.002, 0.001)
SEEDS = tuple(range(1, 25))
RMC = 48
Z_MAX = 4.5
CASES = {"bare": ("thermal 0.05 1.0 1.0", dict(theta=0.05)),
         "barrier": ("thermal 0.05 1.0 1.0 barrier 2 0.25", dict(theta=0.05, p=2.0, q=0.25))}
# the input's lattice: hex 1.1547005383792515 (nearest neighbours at 1),
# region 0 20 0 12 in lattice units, periodic: 480 sites, 36 partners each
POS, BOX = itm.hex_lattice(20, 12)


def loop_input(d):
    """The test input for every value of -var seed in one process (one
    start-up instead of one per seed; the same thermo as a run per seed:
    test_athermal_interacting_runs_against_the_monte_carlo)."""
    d.mkdir(parents=True, exist_ok=True)
    f = d / "in.loop"
    f.write_text("label seeds\nclear\ninclude %s\nnext seed\njump SELF seeds\n" % INPUT)
    return f


def runs(d, seeds, **var):
    """Thermo rows (step X F/(N k_c) breaks rounds) of one run per seed:
    array (seeds, 81, 5)."""
    log = eqtools.run_lammps(loop_input(d), dict(var, out=d, more=""), cwd=d,
                             extra=["-var", "seed"] + [str(s) for s in seeds])
    t = thermo(log)
    t = t.reshape(len(seeds), -1, 5)
    assert t.shape[1] == len(XS) and np.allclose(t[:, :, 1], XS)
    return t


def observables(F, B):
    """Per run (rows): the mean F over 15 windows of 0.25 x_c in X in
    (0.25, 4], the sampled peak (max over X in [0.4, 0.8]) and dip (min over
    [0.6, 1.0]) of the first slip, the steady mean over X in [2, 4], and the
    breaks up to X = 4 and between X = 2 and 4 (a rate).  Returns a dict of
    arrays (runs,) or (runs, 15)."""
    F = np.asarray(F, float)
    B = np.asarray(B, float)
    win = np.stack([F[:, j + 1:j + 6].mean(1) for j in range(5, 80, 5)], 1)
    sel = lambda a, b: (XS >= a - 1e-9) & (XS <= b + 1e-9)
    return dict(windows=win, peak=F[:, sel(0.4, 0.8)].max(1), dip=F[:, sel(0.6, 1.0)].min(1),
                steady=F[:, sel(2.0, 4.0)].mean(1), breaks=B[:, -1],
                rate=B[:, -1] - B[:, 40])


def zscore(a, b):
    """z of the difference of the means of two independent samples (first
    axis: runs), from their variances."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    var = a.var(0, ddof=1) / len(a) + b.var(0, ddof=1) / len(b)
    return (a.mean(0) - b.mean(0)) / np.sqrt(var), np.sqrt(var)


def mc(theta_kw, kappa=KAPPA, replicas=RMC, seed=1):
    nbr, kij = itm.couplings(POS, BOX, kappa, 3.0, 3.0)
    return itm.simulate(XS, nbr, kij, V, th.make_params(**theta_kw), replicas=replicas, seed=seed)


@pytest.fixture(scope="module")
def thermal_runs(tmp_path_factory):
    """LAMMPS (SEEDS x DXS) and the Monte Carlo of both cases; also prints
    the time they took."""
    out = {}
    for name, (extra, kw) in CASES.items():
        t0 = time.time()
        eq = {dX: runs(tmp_path_factory.mktemp(f"{name}{dX}"), SEEDS, extra=extra, dX=dX)
              for dX in DXS}
        t1 = time.time()
        ref = mc(kw, seed=11 if name == "bare" else 12)
        print(f"{name}: LAMMPS {t1 - t0:.1f} s, Monte Carlo {time.time() - t1:.1f} s")
        out[name] = (eq, ref)
    return out


@pytest.fixture(scope="module")
def athermal_runs(tmp_path_factory):
    eq = runs(tmp_path_factory.mktemp("athermal"), SEEDS, extra="", dX=0.002)
    return eq, mc(dict(theta=0.0), replicas=64, seed=13)


def test_hazard_closed_form_against_quadrature():
    """The integrated hazard of a linear path (incomplete gamma functions)
    against adaptive quadrature of thermal.rate() to 1e-12 relative
    (measured: 6e-14; quadrature at relative 1e-13; a path of 1e-7 would
    lose 1e-9 to the difference of two tails, not tested), and its inverse
    to 1e-11 (measured 4.5e-13: scipy's inverses give w to ~1e-14, and a
    hazard of ~0.01 of the tail P(s, w0) amplifies that 100-fold)."""
    from scipy import integrate
    for kw in (dict(theta=0.05), dict(theta=0.05, p=2.0, q=0.25), dict(theta=0.01, q=0.25),
               dict(theta=0.3, p=2.0)):
        prm = th.make_params(**kw)
        for xs in (0.75, 1.0, 1.25):
            for e0, e1 in ((0.0, xs), (0.0, 0.5), (0.3, 0.9 * xs), (0.9 * xs, xs),
                           (0.999 * xs, xs)):
                H = float(itm.hazard(e0, e1, xs, V, prm))
                Hq = integrate.quad(lambda e: th.rate(e, xs, prm) / V, e0, e1, epsabs=0.0,
                                    epsrel=1e-13, limit=200)[0]
                assert H == pytest.approx(Hq, rel=1e-12, abs=1e-300), (kw, xs, e0, e1)
            # the inverse: hazard(e0, break_stretch(e0, B)) = B, or x_s when
            # the budget exceeds the hazard up to the threshold
            B = np.random.default_rng(1).exponential(1.0, 200)
            eb = itm.break_stretch(0.2, B, xs, V, prm)
            Hmax = float(itm.hazard(0.2, xs, xs, V, prm))
            inner = B < Hmax
            assert np.all(eb[~inner] == xs) and np.all(eb[inner] < xs)
            assert np.allclose(itm.hazard(0.2, eb[inner], xs, V, prm), B[inner],
                               rtol=1e-11, atol=0.0)
    # theta = 0: no hazard, the break at the threshold
    assert itm.hazard(0.0, 0.9, 1.0, V, theta=0.0) == 0.0
    assert itm.break_stretch(0.0, 0.5, 1.1, V, theta=0.0) == 1.1


def test_monte_carlo_without_coupling_is_the_renewal_process():
    """kappa = 0: independent contacts, whose expected F(X) from rest is
    the renewal equation of eqtools.thermal (the discrete rule's lattice
    renewal at dX = 2e-3 and 1e-3, extrapolated to 0: its error is first
    order, the rest O(dX^2) ~ 1e-6).  Every window mean of 64 replicas
    within Z_MAX of it (se from the replicas; measured |z| <= 2.0)."""
    ref_mc = mc(dict(theta=0.05), kappa=0.0, replicas=64, seed=3)
    _, F1, _ = th.discrete_transient_force(V, 2e-3, 2000, theta=0.05)
    _, F2, _ = th.discrete_transient_force(V, 1e-3, 4000, theta=0.05)
    ref = 2.0 * F2[::50] - F1[::25]
    F = ref_mc["F"]
    for j in range(5, 80, 5):
        m = F[:, j + 1:j + 6].mean(1)
        z = (m.mean() - ref[j + 1:j + 6].mean()) / (m.std(ddof=1) / math.sqrt(len(m)))
        assert abs(z) < Z_MAX, (XS[j], m.mean(), ref[j + 1:j + 6].mean(), z)
    # the break count: each contact at least three lives in X = 4
    assert ref_mc["breaks"][:, -1].min() > 3 * N


def test_field_is_the_lattice_kernel(tmp_path):
    """The Monte Carlo's lattice and k_ij are those of the input: LAMMPS'
    sites are hex_lattice()'s, and the field h_i = sum_j k_ij (s_i - s_j)
    computed from the stretches and positions LAMMPS writes (after the
    first avalanches, X = 1, theta = 0) equals its f_c[7] to rounding
    (measured 1.1e-14 of max |h|).  With the shell at r = 3 left out the
    field is off by far more (the check can fail)."""
    tail = ("write_dump all custom ${out}/xy.dump id x y f_c[1] f_c[7] "
            "modify sort id format float %.17g\n")
    d = tmp_path
    f = d / "in.xy"
    f.write_text("include %s\n%s" % (INPUT, tail))
    eqtools.run_lammps(f, dict(out=d, extra="", more="", Xmax=1.0), cwd=d)
    text = (d / "xy.dump").read_text().split("ITEM: ATOMS")[-1].splitlines()[1:]
    a = np.array([[float(x) for x in l.split()] for l in text if l.strip()])
    s, h = a[:, 3], a[:, 4]
    assert np.ptp(s) > 0.1                      # contacts broke: stretches differ
    # the sites are itm.hex_lattice(20, 12) in the same box, translated
    # rigidly (the slider moved): one site each, to 1e-9
    d = a[None, :, 1:3] - a[0, 1:3] + POS[0] - POS[:, None, :]
    d -= np.array(BOX) * np.round(d / np.array(BOX))
    hit = np.sqrt((d * d).sum(-1)) < 1e-9
    assert (hit.sum(0) == 1).all() and (hit.sum(1) == 1).all()
    nbr, kij = itm.couplings(a[:, 1:3], BOX, KAPPA, 3.0, 3.0)
    assert nbr.shape == (N, 36)
    hm = (kij * (s[:, None] - s[nbr])).sum(1)
    print("field: max |h_MC - h_LAMMPS| / max |h|", np.abs(hm - h).max() / np.abs(h).max())
    assert np.abs(hm - h).max() < 1e-12 * np.abs(h).max(), np.abs(hm - h).max()
    nbr2, kij2 = itm.couplings(a[:, 1:3], BOX, KAPPA, 3.0, 2.99)
    hm2 = (kij2 * (s[:, None] - s[nbr2])).sum(1)
    assert np.abs(hm2 - h).max() > 1e-3 * np.abs(h).max()


def test_athermal_interacting_runs_against_the_monte_carlo(athermal_runs, tmp_path):
    """theta = 0, kappa = 0.06: the fix is exact at every step end for any
    dX (docs, crossing exact + reform_as force: Abelian), so dX = 0.002
    against the Monte Carlo without extrapolation.  Before the first
    threshold (X < 0.75) F = X exactly; then every observable within
    Z_MAX (measured with 64 seeds / 256 replicas: steady 0.52007 +-
    0.00020 against 0.52037 +- 0.00011)."""
    eq, ref = athermal_runs
    # the loop over seeds in one process is the run of one seed
    one = thermo(run(tmp_path, seed=SEEDS[1], extra="", more="", dX=0.002))
    assert np.array_equal(one, eq[1])
    early = XS < 0.75 - 1e-9
    assert np.allclose(eq[:, early, 2], XS[early], atol=1e-12, rtol=0)
    assert np.allclose(ref["F"][:, early], XS[early], atol=1e-12, rtol=0)
    a = observables(eq[:, :, 2], eq[:, :, 3])
    b = observables(ref["F"], ref["breaks"])
    for key in a:
        with np.errstate(invalid="ignore", divide="ignore"):
            z, se = zscore(a[key], b[key])
        z, se = np.atleast_1d(z), np.atleast_1d(se)
        # no scatter (windows below X = 0.75, the peak F(0.75) = 0.75): equal
        same = se < 1e-12
        assert np.allclose(np.atleast_1d(a[key].mean(0))[same],
                           np.atleast_1d(b[key].mean(0))[same], atol=1e-12, rtol=0), key
        print(f"athermal {key}: EQ {np.round(a[key].mean(0), 5)} MC {np.round(b[key].mean(0), 5)} "
              f"z {np.round(np.where(same, 0.0, z), 2)}")
        assert np.all(np.abs(z[~same]) < Z_MAX), (key, a[key].mean(0), b[key].mean(0), z)


@pytest.mark.parametrize("case", list(CASES))
def test_thermal_interacting_runs_against_the_monte_carlo(thermal_runs, case):
    """theta = 0.05, kappa = 0.06, v = 0.01 (bare, and barrier 2 0.25):
    every observable (15 window means of F, the first slip's peak and dip,
    the steady mean over X in [2, 4], the breaks and their rate), each run
    extrapolated to dX = 0 from 0.002 and 0.001, within Z_MAX of the Monte
    Carlo (numbers in the comment above the tests: steady z = 0.05 and
    -1.2 with 64 seeds).  The step error itself, the steady F of dX =
    0.002 less that of 0.001 (measured 0.00050 +- 0.00010 and 0.00043 +-
    0.00010 with 64 seeds; 0.00016 with these 24), within -0.0005 and
    0.002: a slope below 2 x_c per unit dX (4 times the measured one)."""
    eq, ref = thermal_runs[case]
    b = observables(ref["F"], ref["breaks"])
    oa = observables(eq[DXS[0]][:, :, 2], eq[DXS[0]][:, :, 3])
    ob = observables(eq[DXS[1]][:, :, 2], eq[DXS[1]][:, :, 3])
    r = DXS[1] / (DXS[0] - DXS[1])              # o_0 = o(b) + (o(b) - o(a)) dX_b/(dX_a - dX_b)
    for key in b:
        x = ob[key] + (ob[key] - oa[key]) * r
        z, se = zscore(x, b[key])
        print(f"{case} {key}: EQ(0) {np.round(x.mean(0), 5)} MC {np.round(b[key].mean(0), 5)} "
              f"z {np.round(z, 2)}")
        assert np.all(np.abs(z) < Z_MAX), (key, x.mean(0), b[key].mean(0), z)
    step = oa["steady"] - ob["steady"]
    assert -0.0005 < step.mean() < 0.002, step.mean()


def test_the_comparison_can_fail(thermal_runs, athermal_runs):
    """The reference of another model is many standard errors off: the
    coupled thermal runs (extrapolated) against the Monte Carlo at theta =
    0 (steady F 0.520 against 0.4175, breaks 3580 against 4518) and at
    kappa = 0 (independent contacts: 0.395, 2296 breaks): |z| > 20 for the
    steady F and the breaks (measured ~ 200 and ~ 50 for F, several
    hundred for the breaks); the athermal runs against the thermal Monte
    Carlo likewise.  A weaker or stronger coupling is seen too (256/64 MC
    replicas, not run here): kappa = 0.05 and 0.07 give steady F 0.41410
    and 0.42092 (+-0.00017) and 4155 and 4877 breaks, i.e. z ~ 8 and ~ 75
    at the se of test_thermal_interacting_runs_against_the_monte_carlo
    (0.00043 and ~5 breaks)."""
    eq, ref = thermal_runs["bare"]
    oa = observables(eq[DXS[0]][:, :, 2], eq[DXS[0]][:, :, 3])
    ob = observables(eq[DXS[1]][:, :, 2], eq[DXS[1]][:, :, 3])
    t0 = observables(athermal_runs[1]["F"], athermal_runs[1]["breaks"])
    k0 = mc(dict(theta=0.05), kappa=0.0, replicas=32, seed=14)
    k0 = observables(k0["F"], k0["breaks"])
    for key in ("steady", "breaks"):
        x = 2.0 * ob[key] - oa[key]
        for other in (t0, k0):
            z, _ = zscore(x, other[key])
            print(f"can fail: {key} {x.mean():.5f} against {other[key].mean():.5f}: z {z:.1f}")
            assert abs(z) > 20, (key, z)
        z, _ = zscore(observables(athermal_runs[0][:, :, 2], athermal_runs[0][:, :, 3])[key],
                      observables(ref["F"], ref["breaks"])[key])
        print(f"can fail: athermal runs against the thermal MC, {key}: z {z:.1f}")
        assert abs(z) > 20, (key, z)


# ======================================================================
# Formation delays with the field (fix eq/contacts delay with pair
# eq/elastic): against eqtools.interact_thermal.simulate_delay
# ======================================================================
#
# The model of the docs: a broken contact leaves the field (its partners
# lose k_ij (s_j - s_i) and K_j loses k_ij) and waits tau (fixed) or an
# Exp(tau) time; it re-forms with total force k r (r = 0 here) in the field
# of the contacts attached then, and joins the field, which may start an
# avalanche.  The fix counts the waits down by whole steps and re-forms a
# contact at the instant its wait ends (crossing exact), the motion since
# carried; breaks in an avalanche start their waits at the end of the step,
# and contacts that join in one step see each other at their stretch before
# the field: errors of first order in dX, extrapolated out as above.
#
# Measured with 64 replicas (9f25524, theta = 0.05, kappa = 0.06, v = 0.01,
# tau = 10), steady F/(N k_c) over X in [2, 4]: delay exp 0.33371 +-
# 0.00026, fixed 0.33420 +- 0.00021 (no delay 0.41768 +- 0.00021).
DELAYS = {"exp": "thermal 0.05 1.0 1.0 delay exp 10.0",
          "fixed": "thermal 0.05 1.0 1.0 delay fixed 10.0"}


@pytest.mark.parametrize("rule", ["force", "stretch"])
def test_delayed_contacts_reform_by_their_rule(tmp_path, rule):
    """reform delta 0.3, delay fixed 2, crossing step, dX = 0.0005, every
    contact's row written at each of 160 steps after X = 1: the contacts
    that re-formed after their wait in that step (age 0, attached) have
    s = +-0.3 to rounding with reform_as stretch, every one; with
    reform_as force e = s + h/k = +-0.3, placed in their partners' field
    (so s != +-0.3), unless a partner broke later in the same step's
    avalanche or re-formed with it (most keep +-0.3: more than half is
    asserted; measured 100 of 120).  No waiting contact carries a stretch
    or a force (per-atom columns 1 and 3)."""
    extra = f"reform_as {rule} thermal 0.05 1.0 1.0 delay fixed 2.0 crossing step"
    d = tmp_path
    (d / "in.base").write_text(INPUT.read_text().replace("reform delta 0.0", "reform delta 0.3"))
    f = d / "in.rule"
    # per-atom column 9 is the time a contact formed, on the fix's clock
    # (global entry 9): a contact of age 0 formed at the dump's step.  (The
    # clock reaches the dump through an equal-style variable, which LAMMPS
    # passes on with 15 digits: ages below 1e-9 are 0, the next is dt = 0.05)
    f.write_text("include %s\nvariable clock equal f_c[9]\nvariable clk atom v_clock\n"
                 "dump d all custom 1 ${out}/rule.*.dump id f_c[1] f_c[2] f_c[3] "
                 "f_c[7] f_c[9] f_c[10] v_clk\ndump_modify d sort id format float %%.17g\n"
                 "run 160\n" % (d / "in.base"))
    eqtools.run_lammps(f, dict(out=d, extra=extra, more="", Xmax=1.0, dX=0.0005), cwd=d)
    exact_e = exact_s = joined = waiting = 0
    for dump in sorted(d.glob("rule.*.dump")):
        text = dump.read_text().split("ITEM: ATOMS")[-1].splitlines()[1:]
        a = np.array([[float(x) for x in l.split()] for l in text if l.strip()])
        s, force, h, wait = a[:, 1], a[:, 3], a[:, 4], a[:, 6]
        age = a[:, 7] - a[:, 5]
        w = wait > 0
        assert (s[w] == 0).all() and (force[w] == 0).all(), dump
        waiting += w.sum()
        j = ~w & (np.abs(age) < 1e-9)
        joined += j.sum()
        exact_e += (np.abs(np.abs(s[j] + h[j]) - 0.3) < 1e-12).sum()
        exact_s += (np.abs(np.abs(s[j]) - 0.3) < 1e-12).sum()
    print(f"reform_as {rule}: {joined} re-formed, |e| = 0.3: {exact_e}, |s| = 0.3: {exact_s}; "
          f"{waiting} contact-steps waiting")
    assert joined >= 40 and waiting > 160 * 10
    if rule == "force":
        assert exact_e > joined / 2 and exact_s == 0
    else:
        assert exact_s == joined and exact_e < joined / 10


@pytest.fixture(scope="module")
def delay_runs(tmp_path_factory):
    out = {}
    for law, extra in DELAYS.items():
        t0 = time.time()
        eq = {dX: runs(tmp_path_factory.mktemp(f"delay{law}{dX}"), SEEDS, extra=extra, dX=dX)
              for dX in DXS}
        t1 = time.time()
        nbr, kij = itm.couplings(POS, BOX, KAPPA, 3.0, 3.0)
        ref = itm.simulate_delay(XS, nbr, kij, V, th.make_params(theta=0.05, delay=law, tau=10.0),
                                 replicas=RMC, seed=21 if law == "exp" else 22)
        print(f"delay {law}: LAMMPS {t1 - t0:.1f} s, Monte Carlo {time.time() - t1:.1f} s")
        out[law] = (eq, ref)
    return out


def extrapolated(eq):
    """Per run, every observable extrapolated linearly to dX = 0 from DXS;
    and the step error of the steady F (dX = 0.002 less 0.001)."""
    oa = observables(eq[DXS[0]][:, :, 2], eq[DXS[0]][:, :, 3])
    ob = observables(eq[DXS[1]][:, :, 2], eq[DXS[1]][:, :, 3])
    r = DXS[1] / (DXS[0] - DXS[1])
    return {key: ob[key] + (ob[key] - oa[key]) * r for key in ob}, oa["steady"] - ob["steady"]


@pytest.mark.parametrize("law", list(DELAYS))
def test_delayed_interacting_runs_against_the_monte_carlo(delay_runs, law):
    """theta = 0.05, kappa = 0.06, v = 0.01, delay exp or fixed 10: every
    observable of test_thermal_interacting_runs_against_the_monte_carlo,
    each run extrapolated to dX = 0, within Z_MAX of the Monte Carlo; the
    step error of the steady F below 0.01 (5 x_c per unit dX)."""
    eq, ref = delay_runs[law]
    x, step = extrapolated(eq)
    b = observables(ref["F"], ref["breaks"])
    for key in b:
        z, se = zscore(x[key], b[key])
        print(f"delay {law} {key}: EQ(0) {np.round(x[key].mean(0), 5)} "
              f"MC {np.round(b[key].mean(0), 5)} z {np.round(z, 2)}")
        assert np.all(np.abs(z) < Z_MAX), (key, x[key].mean(0), b[key].mean(0), z)
    print(f"delay {law}: step error of the steady F (0.002 - 0.001) {step.mean():.5f} "
          f"+- {step.std(ddof=1) / math.sqrt(len(step)):.5f}")
    assert abs(step.mean()) < 0.01, step.mean()


def test_the_delay_comparison_can_fail(delay_runs):
    """The delay law is seen: the runs of one law against the Monte Carlo
    of the other fail the comparison's bound in the breaks (Monte Carlo up
    to X = 4: 3307.5 with exp, 3258.2 with fixed, a difference that is
    about 8 of the comparison's standard errors); and the waiting contacts
    are seen: without a delay the steady F is far higher (0.4175 against
    0.334)."""
    for law, other in (("exp", "fixed"), ("fixed", "exp")):
        x, _ = extrapolated(delay_runs[law][0])
        ref = delay_runs[other][1]
        z, _ = zscore(x["breaks"], observables(ref["F"], ref["breaks"])["breaks"])
        print(f"can fail: delay {law} runs against the {other} Monte Carlo, breaks: z {z:.1f}")
        assert abs(z) > Z_MAX, (law, z)
        assert x["steady"].mean() < 0.40


REPORT = (r"pair eq/elastic: .*?(?:, (\d+) recomputed for a new set of coupled atoms)?; \d+ "
          r"coordinate changes scattered on all ranks(?:; (\d+) contacts joined or left the "
          r"field, followed by their partners)?; (\d+) drift checks: max \|h_incremental - "
          r"h_full\| = (\S+) \(scale of h: (\S+)\), max \|K_incremental - K_full\| = (\S+) "
          r"\(scale of K: (\S+)\)")


@pytest.mark.parametrize("nprocs", [1, 2])
@pytest.mark.parametrize("reform", ["delta 0.0", "none"])
def test_contacts_join_and_leave_the_field_by_their_partners(tmp_path, nprocs, reform):
    """With a delay (or reform none) a broken contact leaves the field and
    joins it again: pair eq/elastic follows each join and leave by the
    partners' share (no recompute of the field).  Reference: the same run
    with `check 1`, where every update of the field is compared with one
    computed from scratch over all pairs, which replaces it: the drift
    of h and of K stays at rounding (1e-12 of their scales), no update was a
    recompute for a new set of coupled atoms, and the thermo output (F,
    breaks, rounds) of the run without the check equals it (F to 1e-12,
    the breaks exactly), on 1 and 2 ranks.  X up to 2: some 2000 joins
    and leaves with delay exp 10 (with reform none each contact leaves
    once: 480)."""
    import re
    base = INPUT.read_text().replace("reform delta 0.0", "reform " + reform)
    outs = {}
    for check in ("", " check 1"):
        d = tmp_path / ("check" if check else "plain")
        d.mkdir()
        f = d / "in.members"
        f.write_text(base.replace("pair_style eq/elastic 3.0", "pair_style eq/elastic 3.0" + check))
        log = eqtools.run_lammps(f, dict(out=d, extra="thermal 0.05 1.0 1.0 delay exp 10.0",
                                         Xmax=2.0), nprocs=nprocs, cwd=d)
        m = re.search(REPORT, log)
        assert m, log[-2000:]
        outs[check] = (thermo(log), m)
    (plain, mp), (checked, mc) = outs[""], outs[" check 1"]
    recomputed, moved, nchecks, drift, scale, kdrift, kscale = mc.groups()
    print(f"reform {reform}, {nprocs} ranks: {moved} joins and leaves, {nchecks} drift checks, "
          f"max drift {drift} (scale {scale}), of K {kdrift} (scale {kscale}); without the "
          f"check: {mp.group(2)}")
    assert recomputed is None and mp.group(1) is None
    assert int(moved) > (400 if reform == "none" else 1000) and mp.group(2) == moved
    assert int(nchecks) > 900 and float(drift) <= 1e-12 * float(scale)
    assert float(kdrift) <= 1e-12 * float(kscale)
    assert plain.shape == checked.shape and len(plain) == 41
    assert np.array_equal(plain[:, 3], checked[:, 3]) and np.array_equal(plain[:, 4], checked[:, 4])
    assert np.abs(plain[:, 2] - checked[:, 2]).max() < 1e-12
