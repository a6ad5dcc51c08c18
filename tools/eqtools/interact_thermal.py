"""Interacting EQ contacts at T > 0 on a rigid slider: an exact, event-driven
(continuous-time) Monte Carlo reference for fix eq/contacts with pair_style
eq/elastic and *thermal* / *barrier* (issue 23).

Independence
------------
This module is derived from the documentation of the model only:
doc/src/fix_eq_contacts.rst ("Interacting contacts", *reform_as force*,
"Breaks within an avalanche", "Temperature, velocity and aging",
"Interacting contacts at T > 0 and with aging"), doc/src/pair_eq_elastic.rst
(the field and its kernel) and shared/notes/thermal-aging.md (the rate law).
The rate law itself is eqtools.thermal.rate() (the package's independent
Python reference, tested against closed forms).  It neither reads nor calls
the package's C++ code, and it uses another algorithm than the fix: the fix
advances the slider by steps, samples each contact's thermal breaks along
the step by thinning in the field of the step's start and resolves the
step's avalanche in synchronous rounds; here the slider moves continuously
from one break to the next, each contact's next thermal break is found by
inverting its integrated hazard in closed form, and an avalanche happens at
one instant.  The fix's discrete rule approaches this process as its step
dX -> 0 (its documented error is of order nu dt per life).

The model (k_c = k_i = k for every contact; units of the docs)
-------------------------------------------------------------
Contact i sits at a lattice site; its spring has stretch s_i and its
threshold x_si is drawn from P_c (here via eqtools.thermal.draw_thresholds).
The elastic field of its partners (pair_style eq/elastic) is

    h_i = sum_j k_ij (s_i - s_j),     k_ij = k(r_ij),
    k(r) = ftilde / r (r <= lambda_c),  ftilde lambda_c^2 / r^3 (lambda_c < r <= r_c),

r_ij the distance of the sites (minimum image in the periodic box;
distances within a relative 1e-8 of r_c count as inside).  The force that
decides whether i breaks is f_i = k s_i + h_i, its effective stretch
e_i = f_i / k = s_i + h_i / k.  The friction force is F = sum_i k s_i =
sum_i f_i (sum_i h_i = 0), so F / (N k) = mean_i e_i.

* Loading.  A rigid slider at velocity v moves every s_i at rate v and
  leaves h unchanged (h depends on differences only): every e_i grows at
  rate v.
* Athermal break.  |e_i| reaches x_si.
* Thermal break.  Below its threshold a contact breaks at the rate
      nu(e_i; x_si) = omega u^q exp(-(x_si / x_c)^p u^{3/2} / theta),
      u = 1 - |e_i| / x_si
  (thermal.rate(), with x_c the mean of P_c).
* Re-formation (*reform_as force*, *crossing exact*).  A contact that breaks
  re-forms at once with total force k r (r from R; r = x_r >= 0 here, on the
  side of its e_i: -k r if it broke with e_i < 0), a new threshold drawn
  from P_c, and "the rest of that load", f_i - k x_si, goes to the new
  contact: a contact pushed past its threshold (by the slider or by a jump
  of its field) drops its force by exactly k (x_si - r) however far it went
  past; a thermal break at e_i < x_si drops it by k (e_i - r) (nothing goes
  past: it breaks where it is).  Its spring changes by
  ds_i = -D_i k / (k + K_i), K_i = sum_j k_ij, D_i the drop of e_i, and the
  field of each partner j rises: e_j += k_ij D_i / (k + K_i).
* Avalanche.  The partners over their thresholds break in turn, at the same
  slider position (no time passes: no thermal break within an avalanche).
  Every drop is fixed in advance and breaks only raise other forces, so the
  cascade is Abelian (the docs): the final state does not depend on the
  order; this module resolves it in synchronous rounds.  A re-formed contact
  whose carried rest exceeds its new threshold breaks again.

With r >= 0 and v > 0 no e_i ever becomes negative (a break leaves
e_i >= r, partners only gain), so only the side e >= 0 is needed; this is
asserted.  Aging and per-contact stiffness are not modelled; delays are
(simulate_delay(), next section).

Formation delays (simulate_delay(); fix eq/contacts *delay* with the pair
style, not implemented in the fix yet: this is the reference waiting for it)
---------------------------------------------------------------------------
*delay fixed tau* / *delay exp tau* (doc/src/fix_eq_contacts.rst,
shared/notes/thermal-aging.md): a contact that breaks (at its threshold or
thermally) waits a time w (w = tau, or w ~ tau Exp(1)), carries no force
while it waits, and then re-forms with force k r, on the side where it
broke, with the threshold drawn at the break and a fresh thermal life (a
new Exp(1) budget).  Nothing of the load at the break survives the wait:
the drop is not fixed in advance as above, there is no carry.  With the
pair style, "contacts that are not attached do not interact":

* The field counts attached partners only: h_j = sum over attached l of
  k_jl (s_j - s_l), K_j = sum over attached l of k_jl.
* Leave.  A contact i that breaks leaves the field: each attached partner
  j loses k_ji (s_j - s_i) from h_j (e_j changes by -k_ji (s_j - s_i)/k,
  up or down) and k_ji from K_j.  Its own spring no longer counts.
* Join.  When its wait is over, i re-forms in the field of the contacts
  attached at that instant: s_i = (k r_i + sum_j k_ij s_j)/(k + K_i)
  (r_i = +-r, the side of its break), so that k s_i + h_i = k r_i, and its
  partners gain k_ji (s_j - s_i).  Contacts whose waits end at the same
  instant (a fixed delay after one avalanche: they broke at one instant)
  re-form together, each in the field of the contacts attached before
  that instant, not of each other (the synchronous rule of the rounds;
  their partners then see all of them, and so do they: their e_i is r_i
  plus sum over co-joiners j of k_ij (s_i - s_j) / k).
* Avalanche.  A leave or a join changes e of the partners; at the same
  instant, in synchronous rounds, every attached contact with |e| >= x_s
  at a round's start breaks (leaves) together, the field is updated, until
  none is over.  The order matters now (a leave can lower a partner's e):
  the cascade is not Abelian, and the rounds are the rule.  Breaks that
  reach their break point at the same instant leave first, then the
  contacts whose waits end then join, then the rounds run (coincidences
  of the two kinds have probability 0).
* e may be negative (a partner leaving can lower e_j below 0): the
  athermal break is at |e| >= x_s, the thermal rate is nu(|e|), a break at
  e < 0 re-forms mirrored (-r).  A path from e0 < 0 rising at v has the
  hazard of the mirrored path on its part below 0 (hazard() and
  break_stretch() split it at e = 0; checked against quadrature in
  unittest/python/test_eqtools_interact_delay.py, with the model's
  invariants after every event).
* Only attached contacts have a hazard.  The joiners draw fresh budgets,
  and so does every attached partner of a contact that left or joined
  (its path changed; memoryless, as at the field jumps above).
* F / (N k) = sum over attached contacts of s_i / N (still the mean of
  k s_i + h_i over the attached ones, sum h_i = 0 among them); the
  fraction attached is returned too.

A delay with tau = 0 is no delay (simulate() takes the model above).  The
tau -> 0 limit of the delayed model is not that model: there a contact
that breaks loses its whole load e_i - r (no carry: one pushed past x_s
by a field jump loses its overshoot, as with *crossing step*) and re-forms
only after the avalanche of its instant is over.

Exact sampling of the thermal breaks
------------------------------------
Between two events every e_i is linear in time, de/dt = v, so the hazard
along the path, H = (1/v) int nu de, has a closed form: with
a = (x_s/x_c)^p / theta, w = a u^{3/2} and s = (2q + 2)/3,

    int_{e0}^{e1} nu de = omega x_s (2/3) a^{-s} Gamma(s) [P(s, w0) - P(s, w1)]
                       = omega x_s (2/3) a^{-s} Gamma(s) [Q(s, w1) - Q(s, w0)],

P, Q the regularized lower and upper incomplete gamma functions (scipy's
gammainc / gammaincc, each used where it is precise).  A contact whose e
path starts anew (formed, or its field jumped) draws a budget B ~ Exp(1);
its thermal break is where H reaches B (gammaincinv / gammainccinv), or
none before the threshold if H up to x_s is below B.  Since the process is
Markov in (e, x_s) and H of a surviving contact is memoryless, drawing a
fresh budget whenever a contact's path changes (at events: stopping times)
is exact, and a contact whose path did not change keeps its break point.
All e_i move together, so the next event of a replica is the contact with
the smallest (e_break - e)/v.  hazard() is checked against quadrature in
unittest/python/test_eq_interact_thermal.py.

Replicas are simulated in lock-step (one event of every replica per
iteration, numpy over replicas x contacts); the output is F(X)/(N k) and
the cumulative break count at the requested slider positions, the state
after every event with slider position <= X (the fix's thermo output after
its step's avalanche).
"""
import math

import numpy as np
from scipy import special

from . import thermal as th

__all__ = ["hex_lattice", "couplings", "hazard", "break_stretch", "simulate",
           "simulate_delay", "field"]


# ------------------------------------------------------------------ lattice

def hex_lattice(nx, ny, a=1.0):
    """Sites of LAMMPS' 2d 'lattice hex' with nearest-neighbour distance a
    (reduced density 2/(sqrt(3) a^2), e.g. 1.1547005383792515 for a = 1)
    in 'region block 0 nx 0 ny' (lattice units), periodic.  Returns
    (positions (N, 2), box (Lx, Ly)); N = 2 nx ny.  Basis (0, 0) and
    (1/2, 1/2) of the cell a x sqrt(3) a."""
    b = math.sqrt(3.0) * a
    ix, iy = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    p0 = np.stack([ix.ravel() * a, iy.ravel() * b], 1)
    p1 = p0 + np.array([0.5 * a, 0.5 * b])
    return np.concatenate([p0, p1]), (nx * a, ny * b)


def couplings(pos, box, ftilde, lambda_c, rc, rtol=1e-8):
    """Partners and k_ij of every site (pair_style eq/elastic's crossover
    kernel): returns (nbr, kij), arrays (N, m) padded with the site itself
    and k = 0 (m = 0 for ftilde = 0).  Minimum image; the box must exceed 2 rc along each side
    (one image of a partner at most)."""
    pos = np.asarray(pos, float)
    L = np.asarray(box, float)
    if np.any(L <= 2.0 * rc * (1.0 + rtol)):
        raise ValueError("box shorter than twice the cutoff")
    d = pos[None, :, :] - pos[:, None, :]
    d -= L * np.round(d / L)
    r = np.sqrt((d * d).sum(-1))
    np.fill_diagonal(r, np.inf)
    inside = r <= rc * (1.0 + rtol)
    with np.errstate(divide="ignore"):
        k = np.where(r <= lambda_c, ftilde / r, ftilde * lambda_c ** 2 / r ** 3)
    inside &= k > 0.0                       # ftilde = 0: no partners
    k = np.where(inside, k, 0.0)
    m = int(inside.sum(1).max()) if len(pos) else 0
    N = len(pos)
    nbr = np.repeat(np.arange(N)[:, None], m, 1)
    kij = np.zeros((N, m))
    for i in range(N):
        j = np.nonzero(inside[i])[0]
        nbr[i, :len(j)] = j
        kij[i, :len(j)] = k[i, j]
    return nbr, kij


# ------------------------------------------------------------------ hazard

def _consts(xs, v, prm):
    """a, s and the prefactor C of the hazard (see the module docstring):
    H(e0 -> e1) = C [P(s, w0) - P(s, w1)], w = a (1 - e/x_s)^{3/2}."""
    a = (xs / prm.x_c) ** prm.p / prm.theta if prm.p != 0.0 else np.full_like(xs, 1.0 / prm.theta)
    s = (2.0 * prm.q + 2.0) / 3.0
    C = prm.omega * xs * (2.0 / 3.0) * a ** (-s) * special.gamma(s) / v
    return a, s, C


def _w(e, xs, a):
    u = np.clip(1.0 - e / xs, 0.0, 1.0)
    return a * u * np.sqrt(u)


def _hazard_up(e0, e1, xs, v, prm):
    """hazard() of paths with 0 <= e0 <= e1 <= x_s (theta > 0)."""
    a, s, C = _consts(xs, v, prm)
    w0, w1 = _w(e0, xs, a), _w(e1, xs, a)          # w1 <= w0
    # the difference of whichever tail is small at w1 (no cancellation)
    big = w1 > s
    dQ = special.gammaincc(s, w1) - special.gammaincc(s, w0)
    dP = special.gammainc(s, w0) - special.gammainc(s, w1)
    return C * np.where(big, dQ, dP)


def hazard(e0, e1, xs, v, params=None, **kw):
    """Integrated hazard (1/v) int_{e0}^{e1} nu(e; x_s) de of a contact whose
    effective stretch goes linearly from e0 to e1 (-x_s <= e0 <= e1 <= x_s)
    at speed v; closed form (incomplete gamma functions).  The rate depends
    on |e|: a path through e = 0 is split there, its part at e < 0 is the
    mirrored path from |e1| (or 0) up to |e0|."""
    prm = th.make_params(params, **kw)
    e0, e1, xs = np.broadcast_arrays(*(np.asarray(z, float) for z in (e0, e1, xs)))
    if np.any(e0 < -xs) or np.any(e1 < e0) or np.any(e1 > xs):
        raise ValueError("need -x_s <= e0 <= e1 <= x_s")
    if prm.theta == 0.0:
        return np.zeros(e0.shape)
    neg = e0 < 0.0
    if not neg.any():
        return _hazard_up(e0, e1, xs, v, prm)
    # e >= 0 part: [max(e0, 0), max(e1, 0)]; e < 0 part: |e| in
    # [max(-e1, 0), -e0] (empty, 0 to 0, where e0 >= 0)
    up = _hazard_up(np.maximum(e0, 0.0), np.maximum(e1, 0.0), xs, v, prm)
    down = _hazard_up(np.where(neg, np.maximum(-e1, 0.0), 0.0), np.where(neg, -e0, 0.0), xs, v, prm)
    return up + np.where(neg, down, 0.0)


def _break_up(e0, budget, xs, v, prm):
    """break_stretch() of starts 0 <= e0 <= x_s (theta > 0)."""
    a, s, C = _consts(xs, v, prm)
    w0 = _w(e0, xs, a)
    b = budget / C
    # solve P(s, w1) = P(s, w0) - b  <=>  Q(s, w1) = Q(s, w0) + b, each
    # tail where it is small (precise); none if P(s, w0) <= b
    eb = xs.copy()
    hiw = w0 > s
    Q0 = special.gammaincc(s, w0[hiw])
    P0 = special.gammainc(s, w0[~hiw])
    tQ = np.empty(w0.shape)
    tP = np.empty(w0.shape)
    tQ[hiw] = Q0 + b[hiw]
    tP[hiw] = (1.0 - Q0) - b[hiw]           # tP > 1/2 - b here: needed only for its sign
    tP[~hiw] = P0 - b[~hiw]
    tQ[~hiw] = 1.0                          # w1 < w0 <= s: P is the small tail
    thermal = tP > 0.0
    useQ = thermal & (tQ < 0.5)
    useP = thermal & ~useQ
    w1 = np.zeros(w0.shape)
    w1[useQ] = special.gammainccinv(s, tQ[useQ])
    w1[useP] = special.gammaincinv(s, tP[useP])
    eb[thermal] = xs[thermal] * (1.0 - (w1[thermal] / a[thermal]) ** (2.0 / 3.0))
    return np.clip(eb, e0, xs)


def _break_down(m, budget, xs, v, prm):
    """|e| where a contact whose |e| falls from m (0 < m <= x_s) towards 0
    (e < 0 rising) has used its budget (< hazard(0, m): it breaks on the
    way): the y with hazard(y, m) = budget.  w = a (1 - y/x_s)^{3/2} rises
    from w0 = w(m): P(s, w) = P(s, w0) + b, Q(s, w) = Q(s, w0) - b, b =
    budget / C, the inverse of whichever tail is below 1/2."""
    a, s, C = _consts(xs, v, prm)
    w0 = _w(m, xs, a)
    b = budget / C
    tQ = special.gammaincc(s, w0) - b
    tP = special.gammainc(s, w0) + b
    useQ = tQ < 0.5
    w1 = np.empty(w0.shape)
    w1[useQ] = special.gammainccinv(s, np.maximum(tQ[useQ], 0.0))
    w1[~useQ] = special.gammaincinv(s, tP[~useQ])
    y = xs * (1.0 - np.minimum(w1 / a, 1.0) ** (2.0 / 3.0))
    return np.clip(y, 0.0, m)


def break_stretch(e0, budget, xs, v, params=None, **kw):
    """Where a contact starting at effective stretch e0 (-x_s <= e0 <= x_s)
    and loaded at speed v breaks, given its hazard budget: the e with
    hazard(e0, e) = budget, or x_s (the athermal break) if the hazard up to
    x_s is below the budget.  Exact inverse of hazard().  From e0 < 0 the
    path is split at e = 0: with H- = hazard(e0, 0) a budget below H- is
    used up at the e < 0 with hazard(e0, e) = budget (a thermal break on the
    negative side, returned negative), a larger one goes on from 0 with the
    budget less H-."""
    prm = th.make_params(params, **kw)
    e0, budget, xs = np.broadcast_arrays(*(np.asarray(z, float) for z in (e0, budget, xs)))
    if prm.theta == 0.0:
        return xs.copy()
    neg = e0 < 0.0
    if not neg.any():
        return _break_up(e0, budget, xs, v, prm)
    eb = np.empty(e0.shape)
    pos = ~neg
    eb[pos] = _break_up(e0[pos], budget[pos], xs[pos], v, prm)
    m, B, x = -e0[neg], budget[neg], xs[neg]
    if np.any(m > x):
        raise ValueError("need -x_s <= e0 <= x_s")
    Hn = _hazard_up(np.zeros(m.shape), m, x, v, prm)
    inner = B < Hn
    out = np.empty(m.shape)
    out[inner] = -_break_down(m[inner], B[inner], x[inner], v, prm)
    out[~inner] = _break_up(np.zeros(int((~inner).sum())), B[~inner] - Hn[~inner],
                            x[~inner], v, prm)
    eb[neg] = out
    return eb


# ------------------------------------------------------------------ Monte Carlo


def _checked(X, nbr, kij, v, prm):
    """The samples, neighbours and couplings of simulate() and
    simulate_delay() as arrays, after the checks they share."""
    if prm.x_r < 0.0 or v <= 0.0:
        raise ValueError("need x_r >= 0 and v > 0")
    X = np.asarray(X, float)
    if np.any(np.diff(X) < 0) or np.any(X < 0):
        raise ValueError("X must be sorted and >= 0")
    return X, np.asarray(nbr), np.asarray(kij, float)

def simulate(X, nbr, kij, v, params=None, replicas=64, seed=0, k=1.0, observer=None, **kw):
    """Event-driven Monte Carlo of `replicas` independent copies of the
    interacting contacts (sites given by nbr, kij of couplings()), all
    formed relaxed (s = h = e = 0) at slider position 0, driven at velocity
    v.  params: an eqtools.thermal.Params (theta, p, q, omega, x_c,
    thresholds, x_r = the re-forming stretch r >= 0, delay and tau; aging
    not supported).  Returns a dict with
      F       (replicas, len(X)): F(X) / (N k) = mean effective stretch
      breaks  (replicas, len(X)): breaks since X = 0 (a contact each time)
      thermal (replicas, len(X)): of these, the thermal ones (below x_s)
      events  iterations of the lock-step loop.
    With a delay (params.delay "fixed" or "exp", tau > 0) the model of
    "Formation delays" in the module docstring (simulate_delay()): F(X) /
    (N k) = sum of the attached springs / N, and the dict has two more
    entries, joins (re-formations since X = 0) and attached (the fraction
    of contacts attached); observer is passed on to it.  A delay with
    tau = 0 is no delay (re-formation at once, the rest of the load
    carried: this function's model without delay)."""
    prm = th.make_params(params, **kw)
    if prm.aging is not None and prm.beta > 0.0:
        raise ValueError("aging is not modelled")
    if prm.delay is not None and prm.tau > 0.0:
        return simulate_delay(X, nbr, kij, v, prm, replicas=replicas, seed=seed, k=k,
                              observer=observer)
    if observer is not None:
        raise ValueError("observer: only with a delay")
    X, nbr, kij = _checked(X, nbr, kij, v, prm)
    N, m = nbr.shape
    R = int(replicas)
    rng = np.random.default_rng(seed)
    K = kij.sum(1)
    wgt = kij / (k + K)[:, None]            # e_j gains wgt[i, .] * D_i when i drops by D_i
    xr = prm.x_r
    tmax = X[-1] / v if len(X) else 0.0

    eo = np.zeros((R, N))                   # e - v t (t: the replica's time)
    xs = th.draw_thresholds(rng, (R, N), prm)
    eb = break_stretch(0.0, rng.exponential(1.0, (R, N)), xs, v, prm)
    tev = (eb - eo) / v
    t = np.zeros(R)
    nb = np.zeros(R, np.int64)
    nth = np.zeros(R, np.int64)
    eo_f, xs_f, eb_f, tev_f = (z.reshape(-1) for z in (eo, xs, eb, tev))
    hist_t, hist_m, hist_n, hist_th = [], [], [], []
    ar = np.arange(R)

    def brk(flat, D):
        """Contacts flat (unique) drop their e by D; partners gain."""
        r = flat // N
        i = flat - r * N
        eo_f[flat] -= D
        pf = (r[:, None] * N + nbr[i]).reshape(-1)
        np.add.at(eo_f, pf, (wgt[i] * D[:, None]).reshape(-1))
        xs_f[flat] = th.draw_thresholds(rng, len(flat), prm)
        np.add.at(nb, r, 1)
        return pf

    while True:
        ia = np.argmin(tev, 1)
        tn = tev[ar, ia]
        hist_t.append(tn.copy())
        hist_m.append(eo.mean(1))
        hist_n.append(nb.copy())
        hist_th.append(nth.copy())
        act = np.nonzero(tn <= tmax)[0]
        if len(act) == 0:
            break
        t[act] = tn[act]
        trig = act * N + ia[act]
        e_trig = eb_f[trig]
        np.add.at(nth, act[e_trig < xs_f[trig]], 1)
        touched = [trig, brk(trig, e_trig - xr)]
        cand = touched[-1]
        while True:
            cand = np.unique(cand)
            e = eo_f[cand] + v * t[cand // N]
            over = cand[e >= xs_f[cand]]
            if len(over) == 0:
                break
            # pushed past x_s: the drop is x_s - r, the rest is carried
            pf = brk(over, xs_f[over] - xr)
            touched += [over, pf]
            cand = np.concatenate([over, pf])
        tch = np.unique(np.concatenate(touched))
        tt = t[tch // N]
        e = eo_f[tch] + v * tt
        if np.any(e < -1e-12):
            raise AssertionError("negative effective stretch")
        e = np.maximum(e, 0.0)
        eb_f[tch] = break_stretch(e, rng.exponential(1.0, len(tch)), xs_f[tch], v, prm)
        tev_f[tch] = tt + (eb_f[tch] - e) / v

    ht, hm = np.array(hist_t), np.array(hist_m)
    hn, hth = np.array(hist_n), np.array(hist_th)
    F = np.empty((R, len(X)))
    B = np.empty((R, len(X)), np.int64)
    T = np.empty((R, len(X)), np.int64)
    for r in range(R):
        # the state after the events at t <= X/v is recorded before the
        # first event later than X/v
        j = np.searchsorted(ht[:, r], X / v, side="right")
        F[r] = hm[j, r] + X
        B[r] = hn[j, r]
        T[r] = hth[j, r]
    return dict(F=F, breaks=B, thermal=T, events=len(ht))


# ------------------------------------------------------------------ with delays

def field(s, att, nbr, kij):
    """The elastic field of the attached contacts, from scratch: h_i =
    sum over attached partners j of k_ij (s_i - s_j) (s: (..., N) springs,
    att: (..., N) attached; for a waiting i the field it would see)."""
    s = np.asarray(s, float)
    a = np.asarray(att, bool)
    kk = kij * a[..., nbr]
    return (kk * (s[..., :, None] - s[..., nbr])).sum(-1)


def simulate_delay(X, nbr, kij, v, params=None, replicas=64, seed=0, k=1.0, observer=None,
                   **kw):
    """simulate() with formation delays (params.delay "fixed" or "exp",
    params.tau > 0 its (mean) in time units): the model of "Formation
    delays" in the module docstring.  Returns a dict with
      F        (replicas, len(X)): F(X) / (N k) = sum over attached contacts
               of s_i / N (waiting contacts carry no force)
      attached (replicas, len(X)): fraction of the contacts attached
      breaks   (replicas, len(X)): breaks since X = 0 (each one a leave)
      thermal  (replicas, len(X)): of these, the thermal ones (|e| < x_s)
      joins    (replicas, len(X)): re-formations since X = 0
      events   iterations of the lock-step loop.
    observer(st), if given, is called with the initial state and after
    every iteration (every replica whose next event time is <= X[-1]/v has
    resolved the events of one instant, avalanche included) with a
    SimpleNamespace st of the live state (read only; arrays (replicas, N)
    unless said):
      t (replicas) the replica's time; active (replicas) its events were
      resolved in this iteration; att attached; so spring offset, s_i =
      so_i + v t for attached contacts (undefined for waiting ones); h the
      field kept incrementally (for attached contacts); xs the threshold
      (of the next life while waiting); tev the next event (the break
      time of an attached contact, the re-formation of a waiting one); eb
      the effective stretch of an attached contact's next break (x_s:
      athermal); side +-1, the side of the last break; breaks, thermal,
      joins (replicas) the counts so far; k, v, nbr, kij."""
    import types
    prm = th.make_params(params, **kw)
    if prm.aging is not None and prm.beta > 0.0:
        raise ValueError("aging is not modelled")
    if prm.delay is None or not prm.tau > 0.0:
        raise ValueError("simulate_delay needs delay 'fixed' or 'exp' with tau > 0")
    X, nbr, kij = _checked(X, nbr, kij, v, prm)
    N, m = nbr.shape
    R = int(replicas)
    rng = np.random.default_rng(seed)
    xr, tau = prm.x_r, prm.tau
    tmax = X[-1] / v if len(X) else 0.0

    so = np.zeros((R, N))                   # s - v t of attached contacts
    h = np.zeros((R, N))                    # their field (constant between events)
    att = np.ones((R, N), bool)
    side = np.ones((R, N))
    xs = th.draw_thresholds(rng, (R, N), prm)
    eb = break_stretch(0.0, rng.exponential(1.0, (R, N)), xs, v, prm)
    tev = eb / v
    t = np.zeros(R)
    nb = np.zeros(R, np.int64)
    nth = np.zeros(R, np.int64)
    nj = np.zeros(R, np.int64)
    so_f, h_f, att_f, side_f, xs_f, eb_f, tev_f = (
        z.reshape(-1) for z in (so, h, att, side, xs, eb, tev))
    hist = dict(t=[], m=[], a=[], n=[], th=[], j=[])
    st = types.SimpleNamespace(t=t, att=att, so=so, h=h, xs=xs, tev=tev, eb=eb, side=side,
                               breaks=nb, thermal=nth, joins=nj, k=k, v=v, nbr=nbr, kij=kij,
                               active=np.zeros(R, bool))

    def partners(flat):
        r = flat // N
        i = flat - r * N
        return r, i, r[:, None] * N + nbr[i]

    def leave(flat):
        """Contacts flat (unique, attached) break together: they leave the
        field (each attached partner j loses k_ji (s_j - s_i)), draw their
        next threshold and their wait."""
        r, i, pf = partners(flat)
        att_f[flat] = False
        a = att_f[pf]
        dh = -kij[i] * (so_f[pf] - so_f[flat][:, None])
        np.add.at(h_f, pf[a], dh[a])
        xs_f[flat] = th.draw_thresholds(rng, len(flat), prm)
        w = np.full(len(flat), tau) if prm.delay == "fixed" else rng.exponential(tau, len(flat))
        tev_f[flat] = t[r] + w
        np.add.at(nb, r, 1)
        return pf[a]

    def join(flat):
        """Waiting contacts flat (unique) re-form together, each with total
        force k r (mirrored to the side of its break) in the field of the
        contacts attached before (not of each other), then join the field."""
        r, i, pf = partners(flat)
        a = att_f[pf]
        ka = kij[i] * a
        sj = so_f[pf]
        snew = (k * (side_f[flat] * xr - v * t[r]) + (ka * sj).sum(1)) / (k + ka.sum(1))
        so_f[flat] = snew
        np.add.at(h_f, pf[a], (kij[i] * (sj - snew[:, None]))[a])
        att_f[flat] = True
        a2 = att_f[pf]                      # co-joiners included
        h_f[flat] = (kij[i] * a2 * (snew[:, None] - so_f[pf])).sum(1)
        np.add.at(nj, r, 1)
        return pf[a2]

    def estretch(flat):
        return so_f[flat] + h_f[flat] / k + v * t[flat // N]

    if observer is not None:
        observer(st)                        # the initial state (no replica active)
    while True:
        tn = tev.min(1)
        hist["t"].append(tn.copy())
        hist["m"].append(np.where(att, so, 0.0).mean(1))
        hist["a"].append(att.mean(1))
        hist["n"].append(nb.copy())
        hist["th"].append(nth.copy())
        hist["j"].append(nj.copy())
        active = tn <= tmax
        if not active.any():
            break
        t[active] = tn[active]
        trig = np.nonzero(active[:, None] & (tev == tn[:, None]))
        trig = trig[0] * N + trig[1]
        brk = trig[att_f[trig]]
        jn = trig[~att_f[trig]]
        touched = []
        if len(brk):
            # at its break point: thermal (|e| < x_s, either side) or at x_s
            e_b = eb_f[brk]
            np.add.at(nth, brk[e_b < xs_f[brk]] // N, 1)
            side_f[brk] = np.where(e_b < 0.0, -1.0, 1.0)
            touched += [leave(brk)]
        if len(jn):
            touched += [jn, join(jn)]
        cand = np.concatenate(touched) if touched else trig[:0]
        while True:
            cand = np.unique(cand)
            cand = cand[att_f[cand]]
            e = estretch(cand)
            ov = np.abs(e) >= xs_f[cand]
            over = cand[ov]
            if len(over) == 0:
                break
            side_f[over] = np.where(e[ov] < 0.0, -1.0, 1.0)
            cand = leave(over)
            touched.append(cand)
        if touched:
            tch = np.unique(np.concatenate(touched))
            tch = tch[att_f[tch]]
            e = estretch(tch)
            eb_f[tch] = break_stretch(e, rng.exponential(1.0, len(tch)), xs_f[tch], v, prm)
            tev_f[tch] = t[tch // N] + (eb_f[tch] - e) / v
        if observer is not None:
            st.active[:] = active
            observer(st)

    ht, hm, ha = np.array(hist["t"]), np.array(hist["m"]), np.array(hist["a"])
    hn, hth, hj = np.array(hist["n"]), np.array(hist["th"]), np.array(hist["j"])
    F = np.empty((R, len(X)))
    A = np.empty((R, len(X)))
    B = np.empty((R, len(X)), np.int64)
    T = np.empty((R, len(X)), np.int64)
    J = np.empty((R, len(X)), np.int64)
    for r in range(R):
        j = np.searchsorted(ht[:, r], X / v, side="right")
        A[r] = ha[j, r]
        F[r] = hm[j, r] + X * ha[j, r]
        B[r] = hn[j, r]
        T[r] = hth[j, r]
        J[r] = hj[j, r]
    return dict(F=F, attached=A, breaks=B, thermal=T, joins=J, events=len(ht))
