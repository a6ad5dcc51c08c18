"""Formation delays in the exact event-driven Monte Carlo of interacting
contacts at T > 0 (tools/eqtools/interact_thermal.py, simulate_delay();
pure Python, no LAMMPS).  fix eq/contacts refuses *delay* with pair
eq/elastic today; this is the independent reference waiting for it.

The model (the module docstring, "Formation delays"): a broken contact
waits tau (*fixed*) or tau Exp(1) (*exp*) carrying no force and outside
the field of its partners, then re-forms relaxed in the field of the
attached ones (total force k r, mirrored to the side of its break) with
the threshold drawn at the break and a fresh thermal life; a leave or a
join can start an avalanche at that instant, resolved in synchronous
rounds (|e| >= x_s breaks; e may be negative).

- without coupling the contacts are independent renewal processes with a
  delay: F(X) from rest against the lattice renewal equation of
  eqtools.thermal (extrapolated to dX -> 0), the steady F, break rate and
  attached fraction against its quadrature (theta = 0.05) and the closed
  form (theta = 0), for fixed and exponential delays; the hazard of paths
  through e < 0 and its inverse against quadrature;
- with coupling, after every event: the field kept incrementally equals
  the field of the attached contacts from scratch, no attached contact is
  over its threshold, the attached count is N less the waiting ones,
  every wait is tau (fixed) or exponential of mean tau, a contact re-forms
  at its time with force k r on its side, F is the sum of the attached
  springs;
- the delay matters with coupling (steady F far from the run without
  delay and from independent contacts with the delay);
- the numbers the LAMMPS test of the future will compare with (printed).
"""
import math
import os
from functools import lru_cache

import numpy as np
import pytest
from scipy import integrate, stats

from eqtools import interact_thermal as itm
from eqtools import thermal as th

V = 0.01
TAU = 10.0                                   # v tau = 0.1 x_c
XS = np.round(np.arange(81) * 0.05, 12)      # the LAMMPS input's thermo samples, X in [0, 4]
Z_MAX = 4.5


def independent(n):
    """n contacts without partners (kappa = 0)."""
    return np.zeros((n, 0), int), np.zeros((n, 0))


@lru_cache(maxsize=None)
def renewal(theta, delay):
    """Expected F(X) / (N k) of independent contacts from rest on XS: the
    lattice renewal equation of the discrete rule at dX = 2e-3 and 1e-3,
    extrapolated to 0 (first-order error; the extrapolations from (4e-3,
    2e-3) and (2e-3, 1e-3) differ by < 6e-5 at every X, measured)."""
    kw = dict(theta=theta, delay=delay, tau=TAU)
    _, F1, _ = th.discrete_transient_force(V, 2e-3, 2000, **kw)
    _, F2, _ = th.discrete_transient_force(V, 1e-3, 4000, **kw)
    return 2.0 * F2[::50] - F1[::25]


def zmean(a, ref):
    a = np.asarray(a, float)
    return (a.mean() - ref) / (a.std(ddof=1) / math.sqrt(len(a)))


# ------------------------------------------------------------------ hazard

def test_hazard_of_paths_through_negative_stretch():
    """The rate depends on |e|: the closed-form hazard of a path from e0 < 0
    (split at e = 0) against adaptive quadrature of thermal.rate(|e|) to
    1e-12 (measured 1.4e-14), and break_stretch() from e0 < 0 inverts it
    (the budget used up on the negative side, a break at e < 0, or on the
    positive side with the rest) to 1e-10 (measured 1e-9 for budgets of
    1e-3 at theta = 0.3, the same conditioning as from e0 >= 0; budgets
    ~ Exp(1) here: measured 2.4e-12 at theta = 0.05, 9e-12 at 0.3); paths
    from e0 >= 0 are the old ones, to the bit."""
    for kw in (dict(theta=0.05), dict(theta=0.05, p=2.0, q=0.25), dict(theta=0.01, q=0.25),
               dict(theta=0.3, p=2.0)):
        prm = th.make_params(**kw)
        for xs in (0.75, 1.0, 1.25):
            for e0, e1 in ((-xs, xs), (-0.5 * xs, 0.3), (-0.9 * xs, -0.2),
                           (-0.999 * xs, -0.99 * xs), (-0.3, 0.0), (-1e-3, 0.9 * xs)):
                H = float(itm.hazard(e0, e1, xs, V, prm))
                Hq = integrate.quad(lambda e: th.rate(abs(e), xs, prm) / V, e0, e1,
                                    points=[0.0] if e0 < 0.0 < e1 else None, epsabs=0.0,
                                    epsrel=1e-13, limit=400)[0]
                assert H == pytest.approx(Hq, rel=1e-12, abs=1e-300), (kw, xs, e0, e1)
                # mirror symmetry of a path on the negative side
                if e1 <= 0.0:
                    assert H == float(itm.hazard(-e1, -e0, xs, V, prm))
            B = np.random.default_rng(1).exponential(1.0, 200)
            for e0 in (-0.2, -0.6 * xs, -0.99 * xs, -xs):
                eb = itm.break_stretch(e0, B, xs, V, prm)
                Hmax = float(itm.hazard(e0, xs, xs, V, prm))
                Hneg = float(itm.hazard(e0, 0.0, xs, V, prm))
                inner = B < Hmax
                assert np.all(eb[~inner] == xs) and np.all(eb[inner] < xs)
                assert np.all((eb < 0.0) == (B < Hneg)) and np.all(eb >= e0)
                assert np.allclose(itm.hazard(e0, eb[inner], xs, V, prm), B[inner],
                                   rtol=1e-10, atol=0.0), (kw, xs, e0)
    # vectorised: mixed signs give each element its own answer
    prm = th.make_params(theta=0.05)
    e0 = np.array([-0.6, 0.3, -0.2, 0.0])
    B = np.array([0.5, 0.5, 2.0, 2.0])
    one = [float(itm.break_stretch(a, b, 1.0, V, prm)) for a, b in zip(e0, B)]
    assert np.array_equal(itm.break_stretch(e0, B, 1.0, V, prm), one)
    with pytest.raises(ValueError):
        itm.hazard(-1.1, 0.0, 1.0, V, prm)
    # theta = 0: the athermal break at +x_s from either side
    assert itm.break_stretch(-0.5, 0.5, 1.1, V, theta=0.0) == 1.1


# ------------------------------------------------------------------ kappa = 0

CASES = [(0.0, "fixed"), (0.0, "exp"), (0.05, "fixed"), (0.05, "exp")]


@pytest.mark.parametrize("theta,delay", CASES)
def test_without_coupling_transient_is_the_renewal_with_delay(theta, delay):
    """kappa = 0, 32 contacts x 512 replicas from rest: every window mean
    (0.25 x_c, 15 windows in X in (0.25, 4]) within Z_MAX standard errors
    of the renewal equation with the delay (measured |z| <= 2.6); windows
    without scatter (theta = 0, X < 0.75: F = X) equal to rounding.  The
    other delay law with the same mean is seen (a window off by > 8
    standard errors; measured 15-23): the comparison can fail."""
    nbr, kij = independent(32)
    r = itm.simulate(XS, nbr, kij, V, th.make_params(theta=theta, delay=delay, tau=TAU),
                     replicas=512, seed=7)
    F = r["F"]
    other = "exp" if delay == "fixed" else "fixed"
    worst = {delay: 0.0, other: 0.0}
    for d in (delay, other):
        ref = renewal(theta, d)
        for j in range(5, 80, 5):
            m = F[:, j + 1:j + 6].mean(1)
            rm = ref[j + 1:j + 6].mean()
            if m.std() < 1e-12:
                assert abs(m.mean() - rm) < 1e-12
                continue
            worst[d] = max(worst[d], abs(zmean(m, rm)))
            if d == delay:
                assert abs(zmean(m, rm)) < Z_MAX, (XS[j], m.mean(), rm, zmean(m, rm))
    print(f"theta {theta} {delay}: max |z| {worst[delay]:.2f}, against {other} {worst[other]:.1f}")
    assert worst[other] > 8.0
    # every contact broke at least twice by X = 4; at theta = 0 none waits
    # before the lowest threshold
    assert r["breaks"][:, -1].min() >= 2 * 32
    if theta == 0.0:
        assert np.all(r["attached"][:, XS < 0.75 - 1e-9] == 1.0)
    assert np.array_equal(r["attached"], 1.0 - (r["breaks"] - r["joins"]) / 32.0)


@pytest.mark.parametrize("theta,delay", CASES)
def test_without_coupling_steady_state_with_delay(theta, delay):
    """kappa = 0, 16 contacts x 512 replicas, X up to 30: the time averages
    over X in [15, 30] (sampled every 0.01) of F / (N k), of the attached
    fraction and the breaks per contact per unit travel against the
    renewal quadrature thermal.steady_force(full=True) (F_k, n_a,
    gamma_s; only the mean delay enters), at theta = 0 F_k also against
    the closed form force_T0_delay.  The start from rest leaves a bias of
    the window mean below 2.3e-5 (the renewal transient, measured), a
    tenth of a standard error: |z| < Z_MAX (measured <= 1.2).  Without
    the delay F_k is far off (0.510 and 0.395 against 0.464 and 0.346)."""
    prm = th.make_params(theta=theta, delay=delay, tau=TAU)
    nbr, kij = independent(16)
    Xg = np.round(np.arange(1500, 3001) * 0.01, 10)
    r = itm.simulate(Xg, nbr, kij, V, prm, replicas=512, seed=5)
    ref = th.steady_force(V, prm, full=True)
    if theta == 0.0:
        assert ref["F"] == pytest.approx(th.force_T0_delay(V, prm), rel=1e-12)
    Fm = r["F"].mean(1)
    rate = (r["breaks"][:, -1] - r["breaks"][:, 0]) / 16.0 / (Xg[-1] - Xg[0])
    att = r["attached"].mean(1)
    z = (zmean(Fm, ref["F"]), zmean(rate, ref["gamma_s"]), zmean(att, ref["n_a"]))
    print(f"theta {theta} {delay}: F {Fm.mean():.5f} (ref {ref['F']:.5f}), rate "
          f"{rate.mean():.5f} ({ref['gamma_s']:.5f}), attached {att.mean():.5f} "
          f"({ref['n_a']:.5f}); z {np.round(z, 2)}")
    assert np.all(np.abs(z) < Z_MAX), z
    nodelay = th.steady_force(V, theta=theta)
    assert abs(zmean(Fm, nodelay)) > 50


# ------------------------------------------------------------------ coupled: invariants

SMALL = itm.hex_lattice(8, 4)                # 64 sites, box 8 x 6.93 > 2 r_c
WIDE = ("uniform", 0.05, 1.95)
INVARIANT_CASES = {
    # the coupling of the LAMMPS input
    "k0.06 exp": (0.06, dict(theta=0.05, delay="exp", tau=TAU)),
    "k0.06 fixed": (0.06, dict(theta=0.05, delay="fixed", tau=TAU)),
    "k0.06 fixed T0": (0.06, dict(theta=0.0, delay="fixed", tau=TAU)),
    # strong coupling, wide thresholds, r > 0: e < 0, breaks on the negative side
    "k2 exp": (2.0, dict(theta=0.3, delay="exp", tau=TAU, thresholds=WIDE, x_r=0.02)),
    "k2 fixed": (2.0, dict(theta=0.3, delay="fixed", tau=TAU, thresholds=WIDE, x_r=0.02)),
    "k2 fixed T0": (2.0, dict(theta=0.0, delay="fixed", tau=TAU, thresholds=WIDE, x_r=0.02)),
}


class Checker:
    """The observer of simulate_delay(): after every iteration recomputes
    from scratch what the Monte Carlo keeps incrementally, and follows
    every contact from one iteration to the next."""

    def __init__(self, nbr, kij, prm):
        N = len(nbr)
        self.K = np.zeros((N, N))
        for i in range(N):
            np.add.at(self.K[i], nbr[i], kij[i])
        assert np.allclose(self.K, self.K.T)
        self.prm = prm
        self.prev = None
        self.worst = dict(field=0.0, over=-np.inf, join=0.0, sched=0.0)
        self.field_all = 0.0       # the field with the waiting contacts counted
        self.waits = []
        self.cover = dict(negative=0, negside=0, cojoins=0, rounds=0, joins=0, thermal_neg=0)
        self.samples = []          # (replica, t, sum of attached springs / N, attached fraction)

    def __call__(self, st):
        a = st.active
        R, N = st.att.shape
        t = st.t
        att = st.att
        s = st.so + st.v * t[:, None]
        e = st.so + st.h / st.k + st.v * t[:, None]
        # the field of the attached partners, from scratch
        Ka = self.K[None, :, :] * att[:, None, :]
        h = s * Ka.sum(2) - np.einsum("rij,rj->ri", Ka, s)
        dh = np.where(att, np.abs(h - st.h), 0.0)[a]
        self.worst["field"] = max(self.worst["field"], dh.max(initial=0.0))
        hall = s * self.K.sum(1) - s @ self.K.T
        dall = np.where(att, np.abs(hall - st.h), 0.0)[a]
        self.field_all = max(self.field_all, dall.max(initial=0.0))
        # no attached contact over its threshold; the next break ahead, on
        # schedule (e reaches eb at tev), within the thresholds
        ea = np.where(att, np.abs(e) - st.xs, -np.inf)[a]
        self.worst["over"] = max(self.worst["over"], ea.max(initial=-np.inf))
        sched = np.where(att, np.abs(e + st.v * (st.tev - t[:, None]) - st.eb), 0.0)[a]
        self.worst["sched"] = max(self.worst["sched"], sched.max(initial=0.0))
        assert np.all(st.tev[a] >= t[a, None])
        assert np.all(np.where(att, (st.eb >= e - 1e-12) & (np.abs(st.eb) <= st.xs), True))
        # attached = N - waiting = N - (breaks - joins)
        assert np.array_equal(att.sum(1), N - (st.breaks - st.joins))
        self.cover["negative"] += int((att & (e < -0.02))[a].sum())
        for r in np.nonzero(a)[0]:
            self.samples.append((r, t[r], s[r, att[r]].sum() / N, att[r].mean()))
        p = self.prev
        if p is not None:
            for r in np.nonzero(a)[0]:
                self._follow(st, r, p, e)
        self.prev = dict(att=att.copy(), tev=st.tev.copy(), eb=st.eb.copy(), side=st.side.copy(),
                         breaks=st.breaks.copy(), joins=st.joins.copy())

    def _follow(self, st, r, p, e):
        t = st.t[r]
        was, now = p["att"][r], st.att[r]
        # contacts due now: attached ones at their break point, waiting ones
        # at the end of their wait; nothing else happened before its time
        due = p["tev"][r] == t
        assert np.all(p["tev"][r] >= t)
        joined = ~was & (now | (st.tev[r] != p["tev"][r]))     # re-formed at t (maybe left again)
        left = ~now & (was | (st.tev[r] != p["tev"][r]))        # left at t
        assert np.all(due[joined]), "a contact re-formed before or after its time"
        assert np.all(was[due] | joined[due]), "a waiting contact missed its re-formation"
        assert np.all(left[due & was]), "an attached contact passed its break point"
        # each leave starts a wait of tau (fixed) or Exp(tau)
        w = st.tev[r][left] - t
        self.waits += list(w)
        # the side of a break at the scheduled point is the sign of its e
        trig = due & was
        assert np.all(st.side[r][trig] == np.where(p["eb"][r][trig] < 0.0, -1.0, 1.0))
        self.cover["negside"] += int((st.side[r][left] < 0).sum())
        self.cover["thermal_neg"] += int((p["eb"][r][trig] < 0).sum())
        nj = int(joined.sum())
        self.cover["joins"] += nj
        self.cover["cojoins"] += nj > 1
        nb = int(st.breaks[r] - p["breaks"][r])
        self.cover["rounds"] += nb > 1
        assert nb == left.sum() and st.joins[r] - p["joins"][r] == nj
        if nj and nb == 0:
            # the joiners re-formed with force k r on the side of their break
            # in the field of the contacts attached before, and nothing left:
            # with one joiner its e is exactly r_i; co-joiners pull each other
            i = np.nonzero(joined)[0]
            K = self.K[np.ix_(i, i)]
            s = st.so[r] + st.v * t
            pull = (K * (s[i][:, None] - s[i][None, :])).sum(1) / st.k
            target = st.side[r][i] * self.prm.x_r + pull
            self.worst["join"] = max(self.worst["join"], np.abs(e[r, i] - target).max())


@pytest.mark.parametrize("case", list(INVARIANT_CASES))
def test_coupled_invariants_after_every_event(case):
    """64 contacts, 4 replicas, X up to 3, after every event: the field
    kept incrementally equals the field of the attached contacts from
    scratch to 1e-12 (and is far from the field with the waiting ones
    counted: the check can fail); no attached contact at or over its
    threshold (|e| < x_s); attached = N - (breaks - joins); every contact's
    next break on schedule; re-formations exactly at their times, every
    fixed wait tau to rounding, exponential waits of mean tau (z) and
    law (Kolmogorov-Smirnov); a lone joiner at e = +-r (its side), co-joiners
    at +-r plus their mutual pull; F(X) and the attached fraction are the
    sums over the attached contacts.  Each case shows what it is meant to
    exercise (negative e, breaks on the negative side, co-joins, avalanches
    of more than one break)."""
    kappa, kw = INVARIANT_CASES[case]
    prm = th.make_params(**kw)
    nbr, kij = itm.couplings(*SMALL, kappa, 3.0, 3.0)
    N = len(nbr)
    chk = Checker(nbr, kij, prm)
    X = np.round(np.arange(61) * 0.05, 12)
    r = itm.simulate(X, nbr, kij, V, prm, replicas=4, seed=3, observer=chk)
    print(case, {k: float("%.3g" % v) for k, v in chk.worst.items()}, chk.cover,
          "field with the waiting ones: %.3g" % chk.field_all)
    assert chk.worst["field"] < 1e-12
    assert chk.field_all > 1e-3
    assert chk.worst["over"] < 0.0
    assert chk.worst["sched"] < 1e-9
    assert chk.worst["join"] < 1e-12
    w = np.array(chk.waits)
    assert len(w) == r["breaks"][:, -1].sum() and len(w) > 4 * N
    if kw["delay"] == "fixed":
        assert np.abs(w - TAU).max() < 1e-12 * 400.0
        if kw["theta"] == 0.0 or kappa == 2.0:      # avalanches: co-joins after tau
            assert chk.cover["cojoins"] > 0
    else:
        assert abs(zmean(w, TAU)) < Z_MAX
        assert stats.kstest(w / TAU, "expon").pvalue > 1e-3
    if kw["theta"] == 0.0:
        assert chk.cover["rounds"] > 0 and r["thermal"].max() == 0
    if kappa == 2.0:
        assert chk.cover["negative"] > 0 and chk.cover["negside"] > 0
        if kw["theta"] > 0.0:
            assert chk.cover["thermal_neg"] > 0
    # the output: F = sum of the attached springs / N at X (the state after
    # the last event at t <= X/v), the attached fraction, the counts
    assert np.array_equal(r["attached"], 1.0 - (r["breaks"] - r["joins"]) / N)
    smp = chk.samples
    for rep in range(4):
        tt = np.array([0.0] + [x[1] for x in smp if x[0] == rep])
        ss = np.array([0.0] + [x[2] for x in smp if x[0] == rep])
        aa = np.array([1.0] + [x[3] for x in smp if x[0] == rep])
        j = np.searchsorted(tt, X / V, side="right") - 1
        F = ss[j] + (X - V * tt[j]) * aa[j]
        assert np.allclose(r["F"][rep], F, rtol=0, atol=1e-12)
        assert np.array_equal(r["attached"][rep], aa[j])


def test_field_from_scratch():
    """itm.field() (the from-scratch field) against a dense sum."""
    nbr, kij = itm.couplings(*SMALL, 0.3, 3.0, 3.0)
    rng = np.random.default_rng(2)
    s = rng.normal(size=(3, len(nbr)))
    att = rng.random((3, len(nbr))) < 0.7
    K = np.zeros((len(nbr), len(nbr)))
    for i in range(len(nbr)):
        np.add.at(K[i], nbr[i], kij[i])
    want = np.array([[sum(K[i, j] * (s[r, i] - s[r, j]) for j in range(len(nbr)) if att[r, j])
                      for i in range(len(nbr))] for r in range(3)])
    assert np.allclose(itm.field(s, att, nbr, kij), want, rtol=0, atol=1e-13)


def test_delay_arguments():
    """delay with tau = 0 is the model without delay (bit for bit); the
    observer needs a delay; aging is not modelled."""
    nbr, kij = itm.couplings(*SMALL, 0.06, 3.0, 3.0)
    X = np.array([0.0, 1.0, 1.5])
    a = itm.simulate(X, nbr, kij, V, th.make_params(theta=0.05), replicas=2, seed=1)
    b = itm.simulate(X, nbr, kij, V, th.make_params(theta=0.05, delay="exp", tau=0.0),
                     replicas=2, seed=1)
    assert set(a) == set(b) and all(np.array_equal(a[k], b[k]) for k in a)
    with pytest.raises(ValueError):
        itm.simulate(X, nbr, kij, V, th.make_params(theta=0.05), observer=print)
    with pytest.raises(ValueError):
        itm.simulate_delay(X, nbr, kij, V, th.make_params(theta=0.05))
    with pytest.raises(ValueError):
        itm.simulate(X, nbr, kij, V, th.make_params(delay="exp", tau=1.0, aging="log", beta=0.1))


# ------------------------------------------------------------------ the LAMMPS case

KAPPA = 0.06
LATTICE = itm.hex_lattice(20, 12)            # unittest/python/inputs/in.interact-thermal
# replicas of the printed reference.  With FEQ_DELAY_REPLICAS=64 (219 s on a
# loaded machine; seeds 21, 22, 23), steady F/(N k_c) over X in [2, 4],
# breaks (thermal) and re-formations up to X = 4, attached fraction over
# X in [2, 4], +- standard errors:
#   delay exp 10.0    0.33371 +- 0.00026, 3310.1 +- 2.5 (3287.0 +- 2.7), 3216.5 +- 2.6,
#                     0.8064 +- 0.0004
#   delay fixed 10.0  0.33420 +- 0.00021, 3254.8 +- 1.9 (3229.4 +- 2.0), 3164.3 +- 1.8,
#                     0.8050 +- 0.0001
#   no delay          0.41768 +- 0.00021, 4519.4 +- 2.0 (4447.3 +- 2.5)
#   (test_eq_interact_thermal.py: 0.41752 +- 0.00009, 4517.3 +- 1.0, 256 replicas)
# One run's scatter of the steady F: 0.0021 (exp), 0.0017 (fixed).
REPLICAS = int(os.environ.get("FEQ_DELAY_REPLICAS", "8"))
LAMMPS_CASES = {"delay exp 10.0": dict(theta=0.05, delay="exp", tau=TAU),
                "delay fixed 10.0": dict(theta=0.05, delay="fixed", tau=TAU),
                "no delay": dict(theta=0.05)}


@pytest.fixture(scope="module")
def lattice_runs():
    nbr, kij = itm.couplings(*LATTICE, KAPPA, 3.0, 3.0)
    return {name: itm.simulate(XS, nbr, kij, V, th.make_params(**kw), replicas=REPLICAS,
                               seed=21 + n)
            for n, (name, kw) in enumerate(LAMMPS_CASES.items())}


def steady(r):
    return r["F"][:, XS >= 2.0 - 1e-9].mean(1)


def test_delay_matters_with_coupling(lattice_runs):
    """kappa = 0.06, theta = 0.05, v = 0.01, 480 contacts: the steady F/(N
    k_c) over X in [2, 4] with delay exp 10 (0.3337) and fixed 10 (0.3342)
    is many standard errors below the run without delay (0.4177): |z| > 20,
    measured 123 and 161 with 8 replicas (254 and 284 with 64); and below
    the same observable of independent contacts with the same delay (the
    renewal equation: 0.3485 and 0.3496): |z| > 10, measured 24 and 40 (58
    and 75 with 64)."""
    base = steady(lattice_runs["no delay"])
    for name in ("delay exp 10.0", "delay fixed 10.0"):
        F = steady(lattice_runs[name])
        se = math.sqrt(F.var(ddof=1) / len(F) + base.var(ddof=1) / len(base))
        z = (F.mean() - base.mean()) / se
        ref0 = renewal(0.05, LAMMPS_CASES[name]["delay"])[XS >= 2.0 - 1e-9].mean()
        z0 = zmean(F, ref0)
        print(f"{name}: {F.mean():.5f} against no delay {base.mean():.5f} (z {z:.0f}) and "
              f"kappa = 0 {ref0:.5f} (z {z0:.0f})")
        assert z < -20 and abs(z0) > 10


def test_print_the_reference_for_lammps(lattice_runs):
    """The numbers the LAMMPS test will compare with (printed, not
    asserted): the input in.interact-thermal (hex_lattice(20, 12), kappa =
    0.06, v = 0.01, thermal 0.05 1.0 1.0, reform delta 0.0) with delay exp
    10.0 and fixed 10.0: the steady F/(N k_c) over X in [2, 4], the breaks
    (thermal among them) and re-formations up to X = 4, the attached
    fraction over X in [2, 4], with standard errors between replicas.
    FEQ_DELAY_REPLICAS sets the replicas (default 8)."""
    for name, r in lattice_runs.items():
        F = steady(r)
        out = [f"F {F.mean():.5f} +- {F.std(ddof=1) / math.sqrt(len(F)):.5f}"]
        for key in ("breaks", "thermal", "joins"):
            if key in r:
                b = r[key][:, -1].astype(float)
                out.append(f"{key} {b.mean():.1f} +- {b.std(ddof=1) / math.sqrt(len(b)):.1f}")
        if "attached" in r:
            a = r["attached"][:, XS >= 2.0 - 1e-9].mean(1)
            out.append(f"attached {a.mean():.4f} +- {a.std(ddof=1) / math.sqrt(len(a)):.4f}")
        print(f"{name} ({len(F)} replicas): " + ", ".join(out))
