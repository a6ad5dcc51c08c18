"""Elastic screening length at T > 0: an independent reference
(spec: shared/notes/thermal-aging.md, (e) and check (f) 8; paper Sec.
"Elastic screening length", Eqs. scr.eq01-scr.eq10).

Load factor and rate
--------------------
A contact in a block with load factor eps feels its forces scaled by
1 + eps, i.e. it is loaded at velocity w = (1 + eps) v while the block
slides at v.  With r(w) = w Gamma_s(w) the steady breaking rate per contact
per unit TIME of contacts loaded at w (Gamma_s from the renewal quadrature
of eqtools.thermal, per unit of loading travel), the breaks per contact per
unit of the BLOCK's travel are

    Gamma(eps) = r((1 + eps) v) / v,          dGamma/deps = r'((1 + eps) v),

and eps_n = x_c sum_m Gamma(eps_m) Pi_mn (scr.eq01/scr.eq04).  At T = 0,
Gamma_s = 1/<x_s> = 1/x_c, so r(w) = w/x_c and Gamma(eps) = (1 + eps)/x_c,
the paper's steady state (scr.eq08, eqtools.meso.screening_lattice).

Conventions of the 1D chain (the ones that reproduce the note's numbers)
------------------------------------------------------------------------
* Blocks one lambda_c apart: lambda_c = one block spacing, lengths in
  blocks.
* Nearest neighbours only (the paper's scr.eq09), nu = 2 neighbours,
  Pi_{n,n+-1} = Pi1 = Pi0/2 (Pi0 = nu Pi(lambda_c) = the SUM over the
  neighbours), no other Pi_mn; a pinned block (Gamma = 0) loads no one.
  Periodic chain of M blocks (a ring, as meso.screening_lattice's box).
* Uniform state: eps0 = Pi0 x_c Gamma(eps0) = Pi0 x_c r((1 + eps0) v)/v.
* Linearised around eps0 (eps_n = eps0 + delta_n, c = Pi0 x_c r'(w0),
  w0 = (1 + eps0) v):
      lattice:    delta_n = (c/2) (delta_{n-1} + delta_{n+1})
                  -> delta_n ~ rho^|n|, rho + 1/rho = 2/c,
                  rho = (1 - sqrt(1 - c^2))/c, ell = -1/ln rho
                  = 1/arccosh(1/c) blocks;
      continuum:  delta_{n+-1} = delta +- delta' + delta''/2 gives
                  delta = c (delta + delta''/2), lambda^2 = (lambda_c^2/2) c/(1 - c);
      seed:       lambda_s = lambda_c (eps0/2)^{1/2} (scr.eq10), which
                  presumes Gamma = (1 + eps)/x_c (then c = Pi0, c/(1 - c) = eps0
                  and the two coincide).
* At T > 0 r(w) stays finite as v -> 0, so eps0 ~ 1/v and the seed formula
  grows as v^{-1/2}, while c (hence both linearised lengths) stays finite.

Rates
-----
ThermalRate evaluates r and r' on the quadrature of
eqtools.thermal.steady_force (the same panels and thresholds): without
threshold aging the grid in s = y/y* does not depend on the velocity, the
cumulative hazard scales as H = H0/w (H0 = int nu dy), so
    <L>(w) = sum_k W_k exp(-H0_k/w),   d<L>/dw = sum_k W_k exp(-H0_k/w) H0_k/w^2,
    r = w/(<L> + w tau),   r' = (<L> - w d<L>/dw)/(<L> + w tau)^2
for many w at once and analytically (equal to steady_force's 'rate' to
rounding).  With threshold aging the grid depends on w: r comes from
steady_force per w and r' from a Richardson finite difference in ln w.
AthermalRate is r = w/x_c exactly.

Only numpy (and eqtools.thermal / eqtools.meso) is used.
"""
import math

import numpy as np

from . import thermal as _th
from .meso import fit_decay

__all__ = ["ThermalRate", "AthermalRate", "rate_model", "rate", "rate_derivative",
           "load_velocity", "load_gamma", "load_gamma_derivative", "eps0", "c_factor",
           "lambda_seed", "lambda_linear_continuum", "lambda_linear_lattice",
           "chain_lattice", "lattice_decay", "seed_slope"]


# ------------------------------------------------------------------ rate models

class AthermalRate:
    """T = 0: r(w) = w/x_c (Gamma = (1 + eps)/x_c, the paper's scr.eq08)."""

    def __init__(self, x_c=1.0):
        self.x_c = float(x_c)

    def r(self, w):
        return np.asarray(w, float) / self.x_c

    def dr(self, w):
        return np.full_like(np.asarray(w, float), 1.0 / self.x_c)

    def r_dr(self, w):
        return self.r(w), self.dr(w)


class ThermalRate:
    """r(w) = w Gamma_s(w) of eqtools.thermal (params as thermal.make_params;
    n, res, nthr: its quadrature's order, panel density, threshold nodes)."""

    def __init__(self, params=None, n=16, res=1, nthr=16, **kw):
        prm = _th.make_params(params, **kw)
        self.prm, self.x_c = prm, prm.x_c
        self.n, self.res, self.nthr = n, res, nthr
        self.tau = prm.tau_mean
        self.fast = prm.aging is None or prm.beta == 0.0
        if not self.fast:
            return
        xs0, wthr = _th.threshold_nodes(prm, n=nthr)
        # at v = 1 the cumulative hazard of the quadrature is H0 = int nu dy
        sv = _th._Survival(1.0, prm, xs0, n=n, res=res)
        W = wthr[:, None, None] * sv.ystar[:, None, None] * \
            (sv.half[:, None] * sv.leg.w[None, :])[None]
        H0 = np.broadcast_to(sv.H, W.shape).ravel()
        order = np.argsort(H0, kind="stable")
        self.H0, self.W = H0[order], W.ravel()[order]

    def _moments(self, w):
        """(<L>, d<L>/dw) at the velocities w (1-d array)."""
        w = np.asarray(w, float)
        order = np.argsort(w)
        L = np.empty(len(w))
        dL = np.empty(len(w))
        for a in range(0, len(w), 16):
            sel = order[a:a + 16]
            ww = w[sel, None]
            # terms with H0/w > 745 underflow to 0 for every w of the chunk
            k = int(np.searchsorted(self.H0, 745.0 * ww.max(), side="right"))
            H0, W = self.H0[:k], self.W[:k]
            S = np.exp(-H0[None, :] / ww) * W[None, :]
            L[sel] = S.sum(axis=1)
            dL[sel] = (S @ H0) / ww[:, 0] ** 2
        return L, dL

    def r(self, w):
        w = np.asarray(w, float)
        flat = np.atleast_1d(w).ravel()
        if self.fast:
            L, _ = self._moments(flat)
            out = flat / (L + flat * self.tau)
        else:
            out = np.array([_th.steady_force(x, self.prm, n=self.n, res=self.res,
                                             nthr=self.nthr, full=True)["rate"] for x in flat])
        return out.reshape(w.shape)

    def dr(self, w):
        return self.r_dr(w)[1]

    def r_dr(self, w):
        """(r(w), r'(w)) from one pass over the quadrature."""
        w = np.asarray(w, float)
        flat = np.atleast_1d(w).ravel()
        if self.fast:
            L, dL = self._moments(flat)
            den = L + flat * self.tau
            r, d = flat / den, (L - flat * dL) / den ** 2
        else:
            r = self.r(flat)
            d = _fd_dr(self.r, flat)[0]
        return r.reshape(w.shape), d.reshape(w.shape)


def _fd_dr(rfun, w, h=2e-3):
    """r'(w) by central differences in ln w, Richardson-extrapolated from
    steps h and h/2: (r', error estimate = |D(h/2) - D(h)|/3, the size of
    the leading error removed)."""
    w = np.asarray(w, float)

    def D(step):
        return (rfun(w * math.exp(step)) - rfun(w * math.exp(-step))) / (2.0 * step)

    d1, d2 = D(h), D(0.5 * h)
    rich = (4.0 * d2 - d1) / 3.0
    return rich / w, np.abs(d2 - d1) / 3.0 / w


_CACHE = {}


def rate_model(theta=None, params=None, model=None, **kw):
    """The rate model: `model` if given, else the (cached) ThermalRate of
    thermal.make_params(params, theta=theta, **kw) (quadrature keywords n,
    res, nthr allowed in kw)."""
    if model is not None:
        return model
    quad = {k: kw.pop(k) for k in ("n", "res", "nthr") if k in kw}
    if theta is not None:
        kw["theta"] = theta
    prm = _th.make_params(params, **kw)
    key = (prm, tuple(sorted(quad.items())))
    if key not in _CACHE:
        _CACHE[key] = ThermalRate(prm, **quad)
    return _CACHE[key]


def rate(w, theta=None, params=None, model=None, **kw):
    """r(w) = w Gamma_s(w): breaks per contact per unit time of contacts
    loaded at velocity w."""
    return rate_model(theta, params, model, **kw).r(w)


def rate_derivative(w, theta=None, params=None, model=None, error=False, **kw):
    """r'(w) = dr/dw (analytic without threshold aging, else Richardson in
    ln w).  error=True returns (r', estimate of its absolute error): the
    difference from the independent finite difference in ln w (analytic
    case) or the Richardson estimate (finite-difference case), plus the
    rounding of the difference quotient."""
    mdl = rate_model(theta, params, model, **kw)
    d = mdl.dr(w)
    if not error:
        return d
    fd, est = _fd_dr(mdl.r, w)
    rnd = 1e-15 * np.abs(mdl.r(w)) / (2e-3 * np.asarray(w, float))
    if isinstance(mdl, ThermalRate) and not mdl.fast:
        return d, est + rnd
    return d, np.abs(d - fd) + est + rnd


# ------------------------------------------------------------------ load factor

def load_velocity(eps, v):
    """The load factor: contacts of a block sliding at v with load factor
    eps are loaded at w = (1 + eps) v."""
    return (1.0 + np.asarray(eps, float)) * v


def load_gamma(eps, v, model):
    """Gamma(eps) = r((1 + eps) v)/v: breaks per contact per unit travel of
    a block sliding at v whose contacts are loaded with factor 1 + eps."""
    return model.r(load_velocity(eps, v)) / v


def _gamma_and_derivative(eps, v, model):
    """(Gamma(eps), dGamma/deps = r'((1 + eps) v)) in one evaluation
    (d load_velocity/d eps = v cancels the 1/v)."""
    r, d = model.r_dr(load_velocity(eps, v))
    return r / v, d


def load_gamma_derivative(eps, v, model):
    """dGamma/deps = r'((1 + eps) v)."""
    return _gamma_and_derivative(eps, v, model)[1]


def eps0(v, theta=None, Pi0=0.3, params=None, model=None, **kw):
    """The uniform self-consistent load factor: eps0 = Pi0 x_c Gamma(eps0).
    Solved for w0 = (1 + eps0) v from h(ln w) = 1 - v/w - Pi0 x_c Gamma_s(w)
    = 0 (h(v) < 0; h increases while Gamma_s decreases) by bracketing and
    bisection/secant (Illinois) in ln w to rounding, then eps0 = w0/v - 1
    polished by Newton steps on the eps equation."""
    mdl = rate_model(theta, params, model, **kw)
    v = float(v)
    xc = mdl.x_c

    def h(lw):
        # (eps - Pi0 x_c Gamma(eps)) / (1 + eps) at eps = w/v - 1
        w = math.exp(lw)
        e = w / v - 1.0
        return (e - Pi0 * xc * float(load_gamma(e, v, mdl))) * (v / w)

    a = math.log(v)
    fa = h(a)
    if fa >= 0:
        raise ValueError("no load at w = v: Pi0 r(v) must be > 0")
    b, fb = a + 1.0, h(a + 1.0)
    while fb <= 0:
        a, fa = b, fb
        b += 2.0
        if b - math.log(v) > 200:
            raise ValueError("no uniform screened state (Pi0 x_c Gamma_s must stay < 1)")
        fb = h(b)
    side = 0
    for _ in range(300):
        c = (a * fb - b * fa) / (fb - fa)
        fc = h(c)
        if fc == 0 or abs(b - a) < 4e-16 * max(1.0, abs(c)):
            a = b = c
            break
        if (fc > 0) == (fb > 0):
            b, fb = c, fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
    e = math.exp(0.5 * (a + b)) / v - 1.0
    for _ in range(3):     # Newton polish on f(eps) = eps - Pi0 x_c Gamma(eps)
        f = e - Pi0 * xc * float(load_gamma(e, v, mdl))
        df = 1.0 - Pi0 * xc * float(load_gamma_derivative(e, v, mdl))
        step = -f / df
        if not abs(step) <= 1e-6 * (1.0 + abs(e)):
            break
        e += step
    return e


def c_factor(v, theta=None, Pi0=0.3, params=None, model=None, **kw):
    """c = Pi0 x_c r'(w0), w0 = (1 + eps0) v: the gain of the linearised
    equations (c = Pi0 at T = 0)."""
    mdl = rate_model(theta, params, model, **kw)
    e = eps0(v, Pi0=Pi0, model=mdl)
    return Pi0 * mdl.x_c * float(load_gamma_derivative(e, v, mdl))


def lambda_seed(v, theta=None, Pi0=0.3, params=None, model=None, **kw):
    """The seed's lambda_s/lambda_c = (eps0/2)^{1/2} (scr.eq10)."""
    return math.sqrt(0.5 * eps0(v, theta, Pi0, params, model, **kw))


def lambda_linear_continuum(v, theta=None, Pi0=0.3, params=None, model=None, **kw):
    """Linearised continuum length / lambda_c: (c/(2(1 - c)))^{1/2}."""
    c = c_factor(v, theta, Pi0, params, model, **kw)
    if not 0 < c < 1:
        raise ValueError("c = %g outside (0, 1): no screened decay" % c)
    return math.sqrt(0.5 * c / (1.0 - c))


def lambda_linear_lattice(v, theta=None, Pi0=0.3, params=None, model=None, full=False, **kw):
    """Decay length (blocks) of the linearised chain equations,
    delta_n = (c/2)(delta_{n-1} + delta_{n+1}): -1/ln rho, rho = (1 -
    sqrt(1 - c^2))/c.  full=True: (ell, rho, c)."""
    c = c_factor(v, theta, Pi0, params, model, **kw)
    if not 0 < c < 1:
        raise ValueError("c = %g outside (0, 1): no screened decay" % c)
    rho = c / (1.0 + math.sqrt((1.0 - c) * (1.0 + c)))      # = (1 - sqrt(1 - c^2))/c
    ell = -1.0 / math.log(rho)
    return (ell, rho, c) if full else ell


# ------------------------------------------------------------------ the lattice

def chain_lattice(v, theta=None, Pi0=0.3, M=201, pinned=None, params=None, model=None,
                  tol=1e-12, maxiter=40, **kw):
    """The full nonlinear steady screening of a periodic chain of M blocks,
    nearest neighbours Pi1 = Pi0/2, the blocks in `pinned` (default: the
    middle one) not sliding (Gamma = 0):
        eps_n = Pi1 x_c sum_{m = n +- 1, m sliding} Gamma(eps_m),
    Gamma(eps) = r((1 + eps) v)/v.  Newton from eps = eps0 (step halved
    while it would make 1 + eps <= 0 or not lower the max residual), until
    the step is below tol (1 + eps0); the residual is checked.  Returns a dict: eps, eps0,
    delta = eps - eps0, residual (max |eps_n - rhs_n| / (1 + eps0)),
    iterations, sliding (bool mask)."""
    mdl = rate_model(theta, params, model, **kw)
    if M < 3:
        raise ValueError("M >= 3")
    if pinned is None:
        pinned = (M // 2,)
    e0 = eps0(v, Pi0=Pi0, model=mdl)
    sliding = np.ones(M, bool)
    sliding[list(pinned)] = False
    A = np.zeros((M, M))
    idx = np.arange(M)
    A[idx, (idx + 1) % M] += 0.5 * Pi0
    A[idx, (idx - 1) % M] += 0.5 * Pi0
    K = mdl.x_c * A * sliding[None, :]
    # mirror symmetry about the first pinned block, if the pinned set has
    # it: Gamma evaluated once per mirror pair (the costly part) and eps
    # kept exactly symmetric
    p0 = pinned[0]
    mirror = (2 * p0 - idx) % M
    sym = set(int(m) for m in mirror[list(pinned)]) == set(int(q) for q in pinned)
    rep = np.minimum(idx, mirror) if sym else idx
    reps, inv = np.unique(rep, return_inverse=True)
    scale = 1.0 + abs(e0)
    eps = np.full(M, e0)

    def gamma(e):
        g, dg = _gamma_and_derivative(e[reps], v, mdl)
        return g[inv], dg[inv]

    G, dG = gamma(eps)
    F = eps - K @ G
    Fn = np.max(np.abs(F))
    for it in range(1, maxiter + 1):
        J = np.eye(M) - K * dG[None, :]
        d = np.linalg.solve(J, -F)
        if sym:
            d = 0.5 * (d + d[mirror])
        # backtracking: keep 1 + eps > 0 and decrease the residual
        t = 1.0
        while True:
            trial = eps + t * d
            if np.all(1.0 + trial > 0.0):
                Gt, dGt = gamma(trial)
                Ft = trial - K @ Gt
                Ftn = np.max(np.abs(Ft))
                if Ftn <= (1.0 - 1e-4 * t) * Fn or Ftn <= tol * scale or t < 1e-6:
                    break
            t *= 0.5
        eps, G, dG, F, Fn = trial, Gt, dGt, Ft, Ftn
        if np.max(np.abs(t * d)) <= tol * scale:
            break
    else:
        raise RuntimeError("chain_lattice: Newton did not converge")
    res = float(np.max(np.abs(F)) / scale)
    if res > 10 * tol:
        raise RuntimeError("chain_lattice: residual %g" % res)
    return dict(eps=eps, eps0=e0, delta=eps - e0, residual=res, iterations=it,
                sliding=sliding)


def lattice_decay(v, theta=None, Pi0=0.3, M=201, params=None, model=None,
                  window=(1e-10, 1e-4), full=False, **kw):
    """Decay length (blocks) of delta_n = eps_n - eps0 on one side of the
    pinned block of chain_lattice: least-squares fit of ln|delta_n| over the
    tail points with window[0] < |delta_n|/(1 + eps0) < window[1] (linear
    regime, above the solver's precision), by meso.fit_decay.  Raises if
    the ring is too short for the window (the other image of the pinned
    block above 1e-6 of delta at the window's end).  full=True:
    dict with ell, its fit error, the local lengths -1/ln(delta_{n+1}/delta_n)
    over the window, the points used and the lattice solution."""
    mdl = rate_model(theta, params, model, **kw)
    sol = chain_lattice(v, Pi0=Pi0, M=M, model=mdl)
    p = M // 2
    k = np.arange(1, M - p)
    dlt = sol["delta"][p + k]
    rel = np.abs(dlt) / (1.0 + abs(sol["eps0"]))
    use = (rel > window[0]) & (rel < window[1])
    # contiguous run from the first point in the window
    if use.sum() < 3:
        raise RuntimeError("fewer than 3 tail points in the window")
    first = int(np.argmax(use))
    last = first
    while last + 1 < len(use) and use[last + 1]:
        last += 1
    kk, dd = k[first:last + 1], dlt[first:last + 1]
    ell, err = fit_decay(kk, dd)
    # the ring's other image of the pinned block, at distance M - k, adds
    # ~ exp(-(M - 2k)/ell) relative to delta_k: keep it below 1e-6
    if not (ell > 0 and (M - 2 * kk[-1]) / ell > 6.0 * math.log(10.0)):
        raise RuntimeError("chain too short for the window: M = %d, last k = %d, ell = %g"
                           % (M, kk[-1], ell))
    if not full:
        return ell
    local = -1.0 / np.log(dd[1:] / dd[:-1])
    return dict(ell=ell, err=err, local=local, k=kk, delta=dd, solution=sol)


def seed_slope(vs, theta=None, Pi0=0.3, params=None, model=None, **kw):
    """Least-squares slope d ln lambda_seed / d ln v over the velocities vs."""
    mdl = rate_model(theta, params, model, **kw)
    lv = np.log(np.asarray(vs, float))
    ll = np.log([lambda_seed(v, Pi0=Pi0, model=mdl) for v in vs])
    return float(np.polyfit(lv, ll, 1)[0])
