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
asserted.  Aging, delays and per-contact stiffness are not modelled.

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

__all__ = ["hex_lattice", "couplings", "hazard", "break_stretch", "simulate"]


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


def hazard(e0, e1, xs, v, params=None, **kw):
    """Integrated hazard (1/v) int_{e0}^{e1} nu(e; x_s) de of a contact whose
    effective stretch goes linearly from e0 to e1 (0 <= e0 <= e1 <= x_s) at
    speed v; closed form (incomplete gamma functions)."""
    prm = th.make_params(params, **kw)
    e0, e1, xs = np.broadcast_arrays(*(np.asarray(z, float) for z in (e0, e1, xs)))
    if np.any(e0 < 0) or np.any(e1 < e0) or np.any(e1 > xs):
        raise ValueError("need 0 <= e0 <= e1 <= x_s")
    if prm.theta == 0.0:
        return np.zeros(e0.shape)
    a, s, C = _consts(xs, v, prm)
    w0, w1 = _w(e0, xs, a), _w(e1, xs, a)          # w1 <= w0
    # the difference of whichever tail is small at w1 (no cancellation)
    big = w1 > s
    dQ = special.gammaincc(s, w1) - special.gammaincc(s, w0)
    dP = special.gammainc(s, w0) - special.gammainc(s, w1)
    return C * np.where(big, dQ, dP)


def break_stretch(e0, budget, xs, v, params=None, **kw):
    """Where a contact starting at effective stretch e0 (0 <= e0 <= x_s)
    and loaded at speed v breaks, given its hazard budget: the e with
    hazard(e0, e) = budget, or x_s (the athermal break) if the hazard up to
    x_s is below the budget.  Exact inverse of hazard()."""
    prm = th.make_params(params, **kw)
    e0, budget, xs = np.broadcast_arrays(*(np.asarray(z, float) for z in (e0, budget, xs)))
    if prm.theta == 0.0:
        return xs.copy()
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


# ------------------------------------------------------------------ Monte Carlo

def simulate(X, nbr, kij, v, params=None, replicas=64, seed=0, k=1.0, **kw):
    """Event-driven Monte Carlo of `replicas` independent copies of the
    interacting contacts (sites given by nbr, kij of couplings()), all
    formed relaxed (s = h = e = 0) at slider position 0, driven at velocity
    v.  params: an eqtools.thermal.Params (theta, p, q, omega, x_c,
    thresholds, x_r = the re-forming stretch r >= 0; aging and delay not
    supported).  Returns a dict with
      F       (replicas, len(X)): F(X) / (N k) = mean effective stretch
      breaks  (replicas, len(X)): breaks since X = 0 (a contact each time)
      thermal (replicas, len(X)): of these, the thermal ones (below x_s)
      events  iterations of the lock-step loop."""
    prm = th.make_params(params, **kw)
    if prm.aging is not None and prm.beta > 0.0 or prm.delay is not None:
        raise ValueError("aging and delays are not modelled")
    if prm.x_r < 0.0 or v <= 0.0:
        raise ValueError("need x_r >= 0 and v > 0")
    X = np.asarray(X, float)
    if np.any(np.diff(X) < 0) or np.any(X < 0):
        raise ValueError("X must be sorted and >= 0")
    nbr = np.asarray(nbr)
    kij = np.asarray(kij, float)
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
