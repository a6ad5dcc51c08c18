"""Thermally activated breaking and aging of EQ contacts: an independent
reference (spec: shared/notes/thermal-aging.md).

This module was written apart from the package's C++ code (it does not read
or call it), only from the model's definition, so that the two can be tested
against each other.  Only numpy is used.

Model (units k_c = 1, so a contact's force is its stretch; x_c = <x_s0> = 1;
attempt frequency omega = 1, times in 1/omega)
--------------------------------------------------------------------------
A contact on a rigid slider moving at velocity v forms with stretch x_r
(default 0), a threshold x_s0 drawn from P_c and age t_w (0 after a break);
its stretch grows as x = x_r + v * (time since formation), its age t by the
same time.

* Aging of the threshold:  x_s(t) = x_s0 A(t),
      A = 1 + beta ln(1 + t/tau_a)          (aging="log")
      A = 1 + beta (1 - exp(-t/tau_a))      (aging="exp"),   A = 1 if None.
* Thermal breaking at x < x_s(t): barrier E = eps_a (x_s/x_c)^p u^{3/2},
  u = 1 - x/x_s, rate  nu = omega u^q exp(-(x_s/x_c)^p u^{3/2} / theta),
  theta = k_B T / eps_a.  x >= x_s(t) breaks at once.
* Formation delay: a broken contact is absent for tau (delay="fixed") or an
  exponential time of mean tau (delay="exp"), then re-forms with stretch x_r,
  age 0 and a fresh threshold (delay=None: at once).

Steady state (rigid slider, independent contacts = renewal processes), with
y = x - x_r the slider travel since formation:
    S(y | x_s0) = [y < y*(x_s0)] exp(-(1/v) int_0^y nu(x_r + y'; x_s0 A(y'/v)) dy'),
y* the first passage of x_r + y above x_s0 A(y/v) (A increases and is
concave, so x_s0 A(y/v) - x_r - y has one zero),
    <L> = <int S dy>,   F_k / (N k_c) = <int (x_r + y) S dy> / (<L> + v tau),
    Gamma_s = 1/(<L> + v tau) (breaks per contact per unit slider travel),
    n_a = <L> Gamma_s (attached fraction),
<.> the average over x_s0 ~ P_c.  steady_force() evaluates this by composite
Gauss-Legendre quadrature: in x_s0 on panels of the threshold distribution;
in y on [0, y*] mapped to s = y/y* in [0, 1] with panels geometric in
1 - s (down to 1e-14: the barrier vanishes at the threshold, and at small
theta the survival drops over a width ~ theta u^{-1/2} in u around the break
point u* ~ [theta ln(omega x_c/v)]^{2/3}) and geometric in s near 0 (the
aging factor varies on the scale y ~ v tau_a); the cumulative hazard inside a
panel by the exact integration matrix of the panel's Legendre interpolant.
Doubling the panel density or the order changes F_k by < 1e-9
(checked in the tests).

Discrete rule of the EQ fix (transient_force_mc and discrete_*)
--------------------------------------------------------------
The slider advances by dX per step (dt = dX / v).  For an attached contact
with stretch x0 -> x1 = x0 + dX and age a0 -> a1 = a0 + dt:
  1. it breaks if x1 >= x_s0 A(a1);
  2. else (theta > 0) its hazard increment
        dH = dt/6 [nu(x0, a0) + 4 nu(xm, am) + nu(x1, a1)]   (Simpson; xm, am
     the midpoints, the threshold x_s0 A(age) in nu) is subtracted from its
     budget E ~ Exp(1), drawn when it formed; it breaks if E <= 0.
A contact that broke in a step re-forms at the END of that step (stretch x_r,
age 0, fresh threshold and budget) without delay; with a delay W (= tau or
Exp(mean tau)) it re-forms at the end of the first step m >= 0 steps after
the end of the step it broke at which m dt >= W (within 1e-9 dt of
rounding), i.e. after D = ceil(W/dt) steps.  F(X) = (sum of the stretches
of the attached contacts) / N, sampled at the step ends (X = 0 included).

Since the budget test is exact when dH is, a contact that would break at
travel L in continuous time breaks in step k = ceil(L/dX) of its life (a
contact reaching x1 = x_s exactly breaks: S counts y < y* only), and the
discrete process is again a renewal process on the step lattice: the
stretches it shows at step ends are x_r + m dX, m = 0..k-1, then D absent
samples, with P(k > m) = S(m dX).  Hence the exact steady value of the rule
(discrete_steady_force)
    F(dX) = sum_m (x_r + m dX) S(m dX) / (sum_m S(m dX) + E[D]),
and, by Euler-Maclaurin (S(0) = 1; x_r = 0, M0 = <L>, M1 = <int y S dy>),
    F(dX) = M1 / (M0 + dX (1/2 + E[D])) + O(dX^2).
With E[D] dX = v tau + c_D dX (c_D = 0 without delay; -> 1/2 for an
exponential delay with dt << tau, E[D] = 1/(1 - exp(-dt/tau)); ceil(v tau/dX)
- v tau/dX for a fixed one) the slope is -F_k (1/2 + c_D)/(<L> + v tau):
-F_k/(2<L>) without delay, 49/192 = 0.2552 at T = 0 for uniform [0.75, 1.25].
S on a lattice comes from survival(); the transient from rest is the lattice
renewal equation (discrete_transient_force).  transient_force_mc and
steady_force_mc simulate the rule itself.
"""
import math
from dataclasses import dataclass, replace, fields

import numpy as np
from numpy.polynomial import legendre as _leg

__all__ = ["Params", "make_params", "aging_factor", "rate", "threshold_nodes",
           "threshold_moments", "draw_thresholds", "break_point", "survival", "steady_force",
           "force_T0_delay", "force_aging_one_threshold", "creep_force",
           "fitted_slope", "mean_delay_steps", "discrete_steady_force",
           "discrete_transient_force", "transient_force_mc", "steady_force_mc"]


# ------------------------------------------------------------------ parameters

@dataclass(frozen=True)
class Params:
    """Model parameters (defaults: T = 0, no aging, no delay, uniform
    thresholds on [0.75, 1.25]).

    theta      k_B T / eps_a (0: athermal)
    p, q       barrier ~ (x_s/x_c)^p u^{3/2}; prefactor u^q
    omega      attempt frequency
    x_c        the barrier's reference threshold (the mean threshold)
    aging      None, "log" or "exp";  beta, tau_a its amplitude and time
    delay      None, "fixed" or "exp"; tau the (mean) delay
    thresholds ("uniform", lo, hi), ("gaussian", mean, sd) (truncated to
               x_r < x_s0 < mean + 10 sd and mean - 10 sd < x_s0, renormalised;
               the MC redraws x_s0 <= x_r) or ("delta", x_s0) (one value)
    x_r        stretch at formation (must be below every threshold)
    """
    theta: float = 0.0
    p: float = 0.0
    q: float = 0.0
    omega: float = 1.0
    x_c: float = 1.0
    aging: object = None
    beta: float = 0.0
    tau_a: float = 1.0
    delay: object = None
    tau: float = 0.0
    thresholds: tuple = ("uniform", 0.75, 1.25)
    x_r: float = 0.0

    def __post_init__(self):
        if self.aging not in (None, "log", "exp"):
            raise ValueError("aging must be None, 'log' or 'exp'")
        if self.delay not in (None, "fixed", "exp"):
            raise ValueError("delay must be None, 'fixed' or 'exp'")
        if self.theta < 0 or self.tau < 0 or self.beta < 0 or self.tau_a <= 0:
            raise ValueError("theta, tau, beta must be >= 0 and tau_a > 0")
        kind = self.thresholds[0]
        if kind not in ("uniform", "gaussian", "delta"):
            raise ValueError("thresholds: ('uniform', lo, hi), ('gaussian', mean, sd) or ('delta', x)")
        lowest = {"uniform": lambda t: t[1], "gaussian": lambda t: 0.0,
                  "delta": lambda t: t[1]}[kind](self.thresholds)
        if kind != "gaussian" and lowest <= self.x_r:
            raise ValueError("thresholds must exceed the formation stretch x_r")

    @property
    def tau_mean(self):
        return self.tau if self.delay else 0.0


def make_params(params=None, **kw):
    """A Params from an existing one (or the defaults) with fields replaced."""
    names = {f.name for f in fields(Params)}
    bad = set(kw) - names
    if bad:
        raise TypeError("unknown parameters: %s" % sorted(bad))
    if params is None:
        return Params(**kw)
    return replace(params, **kw) if kw else params


# ------------------------------------------------------------------ the law

def aging_factor(t, params=None, **kw):
    """A(t): the threshold of a contact of age t is x_s0 A(t)."""
    return _aging(t, make_params(params, **kw))


def _aging(t, prm):
    t = np.asarray(t, float)
    if prm.aging is None or prm.beta == 0.0:
        return np.ones_like(t)
    if prm.aging == "log":
        # log(1 + .) rather than log1p (2.5x faster here): A - 1 is only
        # needed to ~1e-16 absolute
        return 1.0 + prm.beta * np.log(1.0 + t / prm.tau_a)
    return 1.0 - prm.beta * np.expm1(-t / prm.tau_a)


def rate(x, xs, params=None, **kw):
    """nu(x; x_s) = omega u^q exp(-(x_s/x_c)^p u^{3/2}/theta), u = 1 - x/x_s,
    for x < x_s; +inf for x >= x_s (immediate break); 0 at theta = 0."""
    return _nu(x, xs, make_params(params, **kw))


def _nu(x, xs, prm):
    x, xs = np.broadcast_arrays(np.asarray(x, float), np.asarray(xs, float))
    u = 1.0 - x / xs
    below = u > 0
    if prm.theta == 0.0:
        return np.where(below, 0.0, np.inf)
    uu = np.where(below, u, 1.0)
    barrier = uu * np.sqrt(uu) / prm.theta
    if prm.p != 0.0:
        barrier = barrier * (xs / prm.x_c) ** prm.p
    nu = prm.omega * np.exp(-barrier)
    if prm.q != 0.0:
        nu = nu * uu ** prm.q
    return np.where(below, nu, np.inf)


# ------------------------------------------------------------------ thresholds

def _gl_panels(a, b, npanel, n):
    t, w = _leg.leggauss(n)
    edges = np.linspace(a, b, npanel + 1)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    return (mid[:, None] + half[:, None] * t).ravel(), (half[:, None] * w).ravel()


def threshold_nodes(params=None, n=16, npanel=4, **kw):
    """Quadrature nodes and weights (summing to 1) of P_c(x_s0)."""
    prm = make_params(params, **kw)
    kind = prm.thresholds[0]
    if kind == "delta":
        return np.array([float(prm.thresholds[1])]), np.array([1.0])
    if kind == "uniform":
        lo, hi = map(float, prm.thresholds[1:3])
        x, w = _gl_panels(lo, hi, npanel, n)
        return x, w / (hi - lo)
    lo, hi, dens = _domain(prm)
    x, w = _gl_panels(lo, hi, 2 * npanel, n)
    w = w * dens(x)
    return x, w / w.sum()


def threshold_moments(params=None, **kw):
    """(<x_s0>, <x_s0^2>) in closed form (gaussian: untruncated)."""
    prm = make_params(params, **kw)
    kind = prm.thresholds[0]
    if kind == "delta":
        x = float(prm.thresholds[1])
        return x, x * x
    if kind == "uniform":
        lo, hi = map(float, prm.thresholds[1:3])
        return 0.5 * (lo + hi), (lo * lo + lo * hi + hi * hi) / 3.0
    m, sd = map(float, prm.thresholds[1:3])
    return m, m * m + sd * sd


def draw_thresholds(rng, size, prm):
    """size thresholds x_s0 ~ P_c from the numpy Generator rng."""
    kind = prm.thresholds[0]
    if kind == "delta":
        return np.full(size, float(prm.thresholds[1]))
    if kind == "uniform":
        return rng.uniform(prm.thresholds[1], prm.thresholds[2], size)
    m, sd = prm.thresholds[1], prm.thresholds[2]
    out = rng.normal(m, sd, size)
    bad = out <= prm.x_r
    while bad.any():                       # truncated at x_s0 > x_r
        out[bad] = rng.normal(m, sd, bad.sum())
        bad = out <= prm.x_r
    return out


# ------------------------------------------------------------------ break point

def break_point(xs0, v, params=None, t_w=0.0, **kw):
    """Travel y* at which x_r + y first reaches x_s0 A(t_w + y/v)
    (A increasing and concave: one crossing).  Bisection to rounding."""
    prm = make_params(params, **kw)
    xs0 = np.atleast_1d(np.asarray(xs0, float))
    if prm.aging is None or prm.beta == 0.0:
        return xs0 - prm.x_r

    def g(y):
        return xs0 * aging_factor(t_w + y / v, prm) - prm.x_r - y

    lo = np.maximum(xs0 * aging_factor(t_w, prm) - prm.x_r, 0.0)     # g(lo) >= 0
    hi = np.maximum(2.0 * lo, 1e-300)
    for _ in range(2000):
        neg = g(hi) < 0
        if neg.all():
            break
        hi = np.where(neg, hi, 2.0 * hi)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        pos = g(mid) >= 0
        lo, hi = np.where(pos, mid, lo), np.where(pos, hi, mid)
        if np.all(hi - lo <= 4e-16 * hi):
            break
    return 0.5 * (lo + hi)


# ------------------------------------------------------------------ quadrature

class _Legendre:
    """n-point Gauss-Legendre rule on [-1, 1] and the cumulative integration
    weights of its interpolant: int_{-1}^{t} f = sum_k C_k(t) f(t_k), exact
    for polynomials of degree < n."""

    def __init__(self, n):
        self.n = n
        self.t, self.w = _leg.leggauss(n)
        # l_k(t) = sum_{m<n} c[m,k] P_m(t), c[m,k] = (2m+1)/2 w_k P_m(t_k)
        V = _leg.legvander(self.t, n - 1)               # (n, n): P_m(t_k)
        self.c = (V * self.w[:, None]).T * ((2 * np.arange(n) + 1) / 2.0)[:, None]
        self.Q = self.cumweights(self.t)                # (n, n)

    def cumweights(self, t):
        t = np.asarray(t, float)
        P = _leg.legvander(t, self.n)                   # P_0..P_n at t
        I = np.empty(t.shape + (self.n,))
        I[..., 0] = t + 1.0
        m = np.arange(1, self.n)
        I[..., 1:] = (P[..., 2:] - P[..., :-2]) / (2 * m + 1)
        return I @ self.c                               # (..., n)


_LEG = {}


def _legendre(n):
    if n not in _LEG:
        _LEG[n] = _Legendre(n)
    return _LEG[n]


def _s_edges(res=1):
    """Panel edges in s = y/y* on [0, 1]: geometric in 1 - s (16*res per
    decade from 1 to 1e-14) and in s (4*res per decade from 1e-13 to 0.1)."""
    u = 10.0 ** (-np.arange(0, 14 * 16 * res + 1) / (16.0 * res))
    s_hi = 1.0 - u
    s_lo = 10.0 ** (-np.arange(4 * res, 13 * 4 * res + 1) / (4.0 * res))
    e = np.unique(np.concatenate([[0.0, 1.0], s_hi, s_lo]))
    # drop edges closer than rounding
    keep = np.concatenate([[True], np.diff(e) > 1e-16])
    e = e[keep]
    e[-1] = 1.0
    return e


class _Survival:
    """Cumulative hazard of contacts with thresholds xs0 (one row each) on the
    panels of s = y/y* in [0, 1]."""

    def __init__(self, v, prm, xs0, t_w=0.0, n=16, res=1):
        self.v, self.prm, self.t_w = float(v), prm, float(t_w)
        self.xs0 = np.asarray(xs0, float)
        self.ystar = break_point(self.xs0, v, prm, t_w=t_w)
        self.leg = _legendre(n)
        self.edges = _s_edges(res)
        a, b = self.edges[:-1], self.edges[1:]
        self.half = 0.5 * (b - a)
        s = (0.5 * (a + b))[:, None] + self.half[:, None] * self.leg.t      # (P, n)
        self.s = s
        y = self.ystar[:, None, None] * s[None]                             # (I, P, n)
        if prm.theta > 0.0:
            # dH/ds = y* nu / v
            self.g = self.ystar[:, None, None] * self._hazard_rate(y, self.xs0[:, None, None])
        else:
            self.g = np.zeros_like(y)
        inc = self.half[None, :, None] * (self.g @ self.leg.Q.T)            # partial, (I, P, n)
        tot = self.half[None, :] * (self.g @ self.leg.w)                    # (I, P)
        self.before = np.concatenate([np.zeros((len(self.xs0), 1)),
                                      np.cumsum(tot, axis=1)[:, :-1]], axis=1)
        self.H = self.before[:, :, None] + inc
        self.S = np.exp(-self.H)

    def _hazard_rate(self, y, xs0):
        prm = self.prm
        xs = xs0 * aging_factor(self.t_w + y / self.v, prm)
        with np.errstate(over="ignore", invalid="ignore"):
            nu = rate(prm.x_r + y, xs, prm)
        return np.where(np.isfinite(nu), nu, 0.0) / self.v   # s = 1 exactly: measure 0

    def moments(self):
        """(int_0^y* S dy, int_0^y* y S dy) per threshold."""
        wS = self.S * (self.half[:, None] * self.leg.w)[None]
        m0 = self.ystar * wS.sum(axis=(1, 2))
        m1 = self.ystar ** 2 * (wS * self.s[None]).sum(axis=(1, 2))
        return m0, m1


def _domain(prm):
    """Integration domain of the thresholds and the (unnormalised) density."""
    kind = prm.thresholds[0]
    if kind == "uniform":
        lo, hi = map(float, prm.thresholds[1:3])
        return lo, hi, lambda x: np.ones_like(x)
    m, sd = map(float, prm.thresholds[1:3])
    return max(m - 10.0 * sd, prm.x_r), m + 10.0 * sd, lambda x: np.exp(-0.5 * ((x - m) / sd) ** 2)


def _grid_hazard(v, prm, xs0, y, t_w, ngl=4, h_max=2e-3, chunk=64):
    """exp(-H(y_m | x_k)) on the sorted grid y for thresholds xs0, 0 where
    y_m >= y*(x_k).  H by ngl-point Gauss-Legendre on the grid's intervals,
    refined to width <= h_max (and geometrically towards y = 0, down to
    1e-6 v tau_a, with threshold aging)."""
    y = np.asarray(y, float)
    ystar = break_point(xs0, v, prm, t_w=t_w)
    alive = y[None, :] < ystar[:, None]
    if prm.theta == 0.0:
        return alive.astype(float)
    pts = [np.array([0.0]), y]
    yy = np.unique(np.concatenate(pts))
    gaps = np.diff(yy)
    extra = [yy]
    for i in np.nonzero(gaps > h_max)[0]:
        k = int(math.ceil(gaps[i] / h_max))
        extra.append(yy[i] + gaps[i] * np.arange(1, k) / k)
    if prm.aging is not None and prm.beta > 0 and len(yy) > 1:
        y1 = min(yy[1], h_max)
        lo = max(1e-6 * v * (prm.tau_a + t_w), 1e-300)
        if lo < y1:
            extra.append(np.geomspace(lo, y1, max(2, int(4 * math.log10(y1 / lo)) + 1)))
    yq = np.unique(np.concatenate(extra))
    idx = np.searchsorted(yq, y)
    t, w = _leg.leggauss(ngl)
    half = 0.5 * np.diff(yq)
    Y = (0.5 * (yq[1:] + yq[:-1]))[:, None] + half[:, None] * t            # (Q-1, ngl)
    out = np.zeros((len(xs0), len(y)))
    order = np.argsort(ystar)            # chunks of similar y*: stop at the chunk's last y*
    for c0 in range(0, len(xs0), chunk):
        rows = order[c0:c0 + chunk]
        nq = min(int(np.searchsorted(yq, ystar[rows].max(), side="right")), len(yq) - 1)
        xk = np.asarray(xs0, float)[rows][:, None, None]
        Yc = Y[:nq]
        xs = xk * aging_factor(t_w + Yc / v, prm)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            nu = rate(prm.x_r + Yc, xs, prm)
        nu = np.where(np.isfinite(nu), nu, 0.0)          # beyond y*: masked below
        inc = (nu @ w) * half[:nq] / v                      # (chunk, nq)
        H = np.concatenate([np.zeros((len(rows), 1)), np.cumsum(inc, axis=1)], axis=1)
        out[rows] = np.exp(-H[:, np.minimum(idx, nq)])
    return np.where(alive, out, 0.0)


def survival(y, v, params=None, t_w=0.0, ng=2, ngl=4, h_max=2e-3, **kw):
    """S(y) = P(a contact formed at travel 0 with age t_w is still attached
    after travel y) on a sorted grid y >= 0, averaged over the thresholds.

    S(y | x_s0) jumps to 0 at y*(x_s0), so the threshold integral is split
    at the thresholds whose y* is a grid point, x_s0 = (x_r + y)/A(t_w + y/v)
    (y* increases with x_s0), with ng-point Gauss-Legendre between them;
    the hazard on the grid by _grid_hazard (accurate while h_max is well
    below the width theta x_s u^{-1/2} of the breaking region)."""
    prm = make_params(params, **kw)
    y = np.asarray(y, float)
    if y.ndim != 1 or np.any(np.diff(y) < 0) or np.any(y < 0):
        raise ValueError("y must be a sorted 1-d grid of travels >= 0")
    if prm.thresholds[0] == "delta":
        xs0, wt = np.array([float(prm.thresholds[1])]), np.array([1.0])
    else:
        a, b, dens = _domain(prm)
        xj = (prm.x_r + y) / aging_factor(t_w + y / v, prm)
        # base panels: S(y | x_s0) varies with x_s0 over ~ theta x_s0 u^{-1/2}
        width = (b - a) / 16.0 if prm.theta == 0 else min((b - a) / 16.0, 0.5 * prm.theta * prm.x_c)
        base = np.linspace(a, b, int(math.ceil((b - a) / width)) + 1)
        cuts = np.unique(np.clip(np.concatenate([base, xj]), a, b))
        t, w = _leg.leggauss(ng)
        half = 0.5 * np.diff(cuts)
        xs0 = ((0.5 * (cuts[1:] + cuts[:-1]))[:, None] + half[:, None] * t).ravel()
        wt = (half[:, None] * w).ravel() * dens(xs0)
        wt = wt / wt.sum()
    return wt @ _grid_hazard(v, prm, xs0, y, t_w, ngl=ngl, h_max=h_max)


def steady_force(v, params=None, n=16, res=1, nthr=16, full=False, **kw):
    """Steady kinetic friction per contact F_k/(N k_c) at slider velocity v
    (renewal quadrature, see the module docstring).  n, res: the grid along
    a life; nthr: threshold nodes per panel (16 are 1e-8 off where a life's
    length has a kink in x_s0, x_r close to the thresholds, or varies
    steeply with it, creep with barrier p > 0: use 128-256 there, see
    test_threshold_nodes_of_the_reference).  With full=True returns a
    dict: F (F_k per contact), L (<L>, mean travel of a contact's life),
    L2 (<L^2>), gamma_s (breaks per contact per unit travel), n_a (attached
    fraction), rate (breaks per contact per unit time, v gamma_s)."""
    prm = make_params(params, **kw)
    xs0, w = threshold_nodes(prm, n=nthr)
    m0, m1 = _Survival(v, prm, xs0, n=n, res=res).moments()
    L, M1 = w @ m0, w @ m1
    denom = L + v * prm.tau_mean
    F = (prm.x_r * L + M1) / denom
    if not full:
        return F
    return dict(F=F, L=L, L2=2.0 * M1, gamma_s=1.0 / denom, n_a=L / denom,
                rate=v / denom)


# ------------------------------------------------------------------ closed forms

def force_T0_delay(v, params=None, **kw):
    """T = 0, no threshold aging: (<x_s^2> - x_r^2) / (2 (<x_s> - x_r + v tau))."""
    prm = make_params(params, **kw)
    m1, m2 = threshold_moments(prm)
    return (m2 - prm.x_r ** 2) / (2.0 * (m1 - prm.x_r + v * prm.tau_mean))


def force_aging_one_threshold(v, xs0, beta, tau_a=1.0, law="log", x_r=0.0):
    """T = 0, one threshold x_s0, no delay: the stretch grows linearly over
    each life, so F_k = x_r + y*/2 (= x*/2 for x_r = 0), y* the travel that
    solves x_r + y = x_s0 A(y/v).  Solved by Newton's method from above
    (g = x_s0 A - x_r - y is concave: monotone convergence), independently
    of break_point's bisection."""
    def A(t):
        return 1 + beta * (math.log1p(t / tau_a) if law == "log" else -math.expm1(-t / tau_a))

    def dA(t):
        return beta * (1.0 / (tau_a + t) if law == "log" else math.exp(-t / tau_a) / tau_a)

    def g(y):
        return xs0 * A(y / v) - x_r - y

    y = max(xs0 - x_r, 1e-300)
    while g(y) >= 0:
        y *= 2.0
    for _ in range(200):
        step = g(y) / (xs0 * dA(y / v) / v - 1.0)
        y -= step
        if abs(step) <= 1e-15 * y:
            break
    return x_r + 0.5 * y


def creep_force(v, theta, tau_mean=0.0, omega=1.0):
    """Creep limit v << omega x_c e^{-1/theta}: (v/nu0)/(1 + nu0 tau), nu0 =
    omega e^{-1/theta} (p = q = 0, x_c = 1)."""
    nu0 = omega * math.exp(-1.0 / theta)
    return (v / nu0) / (1.0 + nu0 * tau_mean)


def fitted_slope(v, F):
    """Least-squares slope of F against ln v."""
    lv = np.log(np.asarray(v, float))
    return float(np.polyfit(lv, np.asarray(F, float), 1)[0])


# ------------------------------------------------------------------ discrete rule

_TOL = 1e-9     # a waiting time elapsed if within _TOL dt of it


def _delay_steps_dist(dt, prm, dmax):
    """P(D = d), d = 0..dmax, D = ceil(W/dt) (the number of steps a broken
    contact stays away)."""
    pd = np.zeros(dmax + 1)
    if prm.delay is None or prm.tau == 0.0:
        pd[0] = 1.0
    elif prm.delay == "fixed":
        d = int(math.ceil(prm.tau / dt - _TOL))
        if d <= dmax:
            pd[d] = 1.0
    else:
        a = dt / prm.tau
        d = np.arange(1, dmax + 1)
        pd[1:] = np.exp(-(d - 1) * a) * -np.expm1(-a)
    return pd


def mean_delay_steps(dt, params=None, **kw):
    """E[D], D = ceil(W/dt)."""
    prm = make_params(params, **kw)
    if prm.delay is None or prm.tau == 0.0:
        return 0.0
    if prm.delay == "fixed":
        return float(math.ceil(prm.tau / dt - _TOL))
    return 1.0 / -math.expm1(-dt / prm.tau)


def _lattice_survival(v, dX, prm, t_w):
    """S(m dX), m = 0..mmax, with S(mmax dX) = 0."""
    ymax = break_point(np.array([_domain(prm)[1] if prm.thresholds[0] != "delta"
                                 else float(prm.thresholds[1])]), v, prm, t_w=t_w)[0]
    mmax = int(math.floor(ymax / dX)) + 2
    return survival(dX * np.arange(mmax + 1), v, prm, t_w=t_w, h_max=min(dX, 2e-3))


def discrete_steady_force(v, dX, params=None, **kw):
    """Exact steady F of the discrete rule at step dX (module docstring):
    sum_m (x_r + m dX) S(m dX) / (sum_m S(m dX) + E[D])."""
    prm = make_params(params, **kw)
    S = _lattice_survival(v, dX, prm, 0.0)
    m = np.arange(len(S))
    ED = mean_delay_steps(dX / v, prm)
    return float(((prm.x_r + m * dX) * S).sum() / (S.sum() + ED))


def discrete_transient_force(v, dX, nsteps, params=None, t_w=0.0, **kw):
    """Expected F(X_j) and E[(stretch)^2 1_attached] of one contact at the
    step ends j = 0..nsteps of the discrete rule, all contacts formed at
    X = 0 with age t_w (lattice renewal equation).  Returns (X, F, F2)."""
    prm = make_params(params, **kw)
    S1 = _lattice_survival(v, dX, prm, t_w)
    S = S1 if t_w == 0.0 else _lattice_survival(v, dX, prm, 0.0)

    def pad(a):
        out = np.zeros(nsteps + 1)
        k = min(len(a), nsteps + 1)
        out[:k] = a[:k]
        return out

    S1, S = pad(S1), pad(S)
    # attached part lasts k samples, P(k > m) = S(m dX); f(k) = S(k-1) - S(k)
    f1 = np.concatenate([[0.0], S1[:-1] - S1[1:]])
    f = np.concatenate([[0.0], S[:-1] - S[1:]])
    pd = _delay_steps_dist(dX / v, prm, nsteps)
    g1 = np.convolve(f1, pd)[:nsteps + 1]              # first cycle's length
    g = np.convolve(f, pd)[:nsteps + 1]
    u = np.zeros(nsteps + 1)                           # P(a re-formation at step j)
    for j in range(1, nsteps + 1):
        u[j] = g1[j] + np.dot(u[1:j], g[j - 1:0:-1])
    m = np.arange(nsteps + 1)
    st = prm.x_r + m * dX
    a1, a2 = st * S, st * st * S                       # age-m contributions
    F = st * S1 + np.convolve(u, a1)[:nsteps + 1]
    F2 = st * st * S1 + np.convolve(u, a2)[:nsteps + 1]
    return m * dX, F, F2


# ------------------------------------------------------------------ Monte Carlo

class _MC:
    """N independent contacts under the discrete rule (vectorised)."""

    def __init__(self, v, dX, N, prm, t_w, seed):
        self.v, self.dX, self.N, self.prm = float(v), float(dX), int(N), prm
        self.dt = dX / v
        self.rng = np.random.default_rng(seed)
        self.att = np.ones(N, bool)
        self.x = np.full(N, prm.x_r)
        self.age = np.full(N, float(t_w))
        self.xs0 = draw_thresholds(self.rng, N, prm)
        self.E = self.rng.exponential(1.0, N)
        self.wait = np.zeros(N)
        self.thermal = prm.theta > 0.0
        self.aging = prm.aging is not None and prm.beta > 0.0
        self.nu = self._rate(self.x, self._xs(self.age)) if self.thermal else None

    def _xs(self, age, xs0=None):
        xs0 = self.xs0 if xs0 is None else xs0
        return xs0 * _aging(age, self.prm) if self.aging else xs0

    def _rate(self, x, xs):
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            return _nu(x, xs, self.prm)

    def step(self):
        """One step; returns the mask of the contacts that re-formed at its end."""
        prm, dX, dt = self.prm, self.dX, self.dt
        att = self.att
        x1 = self.x + dX
        a1 = self.age + dt
        xs1 = self._xs(a1)
        brk = att & (x1 >= xs1)
        if self.thermal:
            live = att & ~brk
            num = self._rate(self.x + 0.5 * dX, self._xs(self.age + 0.5 * dt))
            nu1 = self._rate(x1, xs1)
            dH = dt / 6.0 * (self.nu + 4.0 * num + nu1)
            with np.errstate(invalid="ignore"):
                self.E = np.where(live, self.E - dH, self.E)
            brk |= live & (self.E <= 0.0)
            self.nu = np.where(live, nu1, self.nu)
        self.x = np.where(att, x1, self.x)
        self.age = np.where(att, a1, self.age)
        # contacts away since an earlier step wait one more step
        self.wait = np.where(att, self.wait, self.wait - dt)
        nb = int(brk.sum())
        if nb:
            if prm.delay is None:
                self.wait[brk] = 0.0
            elif prm.delay == "fixed":
                self.wait[brk] = prm.tau
            else:
                self.wait[brk] = self.rng.exponential(prm.tau, nb)
        self.att = att & ~brk
        ref = ~self.att & (self.wait <= _TOL * dt)
        nr = int(ref.sum())
        if nr:
            self.att[ref] = True
            self.x[ref] = prm.x_r
            self.age[ref] = 0.0
            self.xs0[ref] = draw_thresholds(self.rng, nr, prm)
            self.E[ref] = self.rng.exponential(1.0, nr)
            self.wait[ref] = 0.0
            if self.thermal:
                self.nu[ref] = self._rate(self.x[ref], self._xs(0.0, self.xs0[ref]))
        return ref

    def stretch(self):
        return np.where(self.att, self.x, 0.0)


def transient_force_mc(v, dX, nsteps, N=20000, params=None, t_w=0.0, seed=0, **kw):
    """Monte Carlo of N independent contacts under the discrete rule (module
    docstring), all formed at X = 0 with stretch x_r and age t_w.
    Returns (X, F): X = j dX and F = sum of attached stretches / N at the
    step ends j = 0..nsteps."""
    prm = make_params(params, **kw)
    mc = _MC(v, dX, N, prm, t_w, seed)
    F = np.empty(nsteps + 1)
    F[0] = mc.stretch().sum() / N
    for j in range(1, nsteps + 1):
        mc.step()
        F[j] = mc.stretch().sum() / N
    return dX * np.arange(nsteps + 1), F


def steady_force_mc(v, dX, N=20000, params=None, method="cycles", cycles=2,
                    x_transient=None, x_total=None, nbatch=20, seed=0, max_steps=10 ** 7, **kw):
    """Steady F_k per contact from the Monte Carlo of the discrete rule, with
    its standard error.  Returns (F, se).

    method="time": the time average of F(X) over X in [x_transient, x_total]
    after a start from fresh contacts, se from nbatch batch means (batches
    must be longer than the correlation length, a few <L> + v tau; all
    contacts start in phase, and the oscillation of F(X) decays only as
    exp(-2 pi^2 cv^2) per life, cv the relative spread of the life, so
    x_transient must be ~ 10-20 lives).

    method="cycles" (no transient): contacts formed fresh at X = 0 start a
    renewal cycle (life + absence), and cycles are i.i.d., so F = sum of
    the stretches shown at step ends over each contact's first `cycles`
    complete cycles / the number of those step ends (renewal-reward); the
    contacts are independent units, se by the delta method of the ratio."""
    prm = make_params(params, **kw)
    mc = _MC(v, dX, N, prm, 0.0, seed)
    if method == "time":
        if x_transient is None or x_total is None:
            raise ValueError("method='time' needs x_transient and x_total")
        j0 = int(round(x_transient / dX))
        j1 = int(round(x_total / dX))
        F = np.empty(j1 - j0)
        for j in range(1, j1 + 1):
            mc.step()
            if j > j0:
                F[j - j0 - 1] = mc.stretch().sum() / N
        b = np.array([c.mean() for c in np.array_split(F, nbatch)])
        return float(F.mean()), float(b.std(ddof=1) / math.sqrt(nbatch))
    if method != "cycles":
        raise ValueError("method must be 'cycles' or 'time'")
    r = np.zeros(N)              # current cycle: sum of stretches shown, samples
    c = np.ones(N)               # the formation sample at X = 0 (stretch x_r)
    r += prm.x_r
    R = np.zeros(N)              # totals over the completed cycles counted
    C = np.zeros(N)
    done = np.zeros(N, int)
    for _ in range(max_steps):
        ref = mc.step()
        fin = ref & (done < cycles)
        R[fin] += r[fin]
        C[fin] += c[fin]
        done[ref] += 1
        if (done >= cycles).all():
            break
        st = mc.stretch()
        r = np.where(ref, st, r + st)
        c = np.where(ref, 1.0, c + 1.0)
    else:
        raise RuntimeError("not every contact completed %d cycles" % cycles)
    F = R.sum() / C.sum()
    d = R - F * C
    se = math.sqrt(d.var(ddof=1) / N) / C.mean()
    return float(F), float(se)
