"""FK-ME chain of lambda_c-contacts: the frictional crack as a solitary wave
(paper Sec. V B, Eqs. crack.eqi00 - crack.v1a).

Blocks n = 0..N-1 on a periodic chain, displacement u_n:

    m u_n'' + m eta u_n' = g (u_{n+1} + u_{n-1} - 2 u_n) - F_s(u_n) - K u_n + f,

f(t) = K X_s(t) the driving force of a stage moving at velocity v,
F_s(u) = kc_n phi(u mod uc) (phi periodically prolonged with period uc):

* ``"sawtooth"``: phi(s) = s on [0, uc)  (Eq. crack.eqi08),
* ``"smooth"``:   phi(s) = tanh(s) + 1.5 exp(-s) sin(3 s) on [0, uc)
  (Fig. crack.A03ab, s in the units of u).

Overdamped limit: m eta u' = right-hand side (m u'' dropped).

The module has four parts, plain numpy (matplotlib only for the plot):

1. continuum-limit closed forms for the sawtooth (``f_min``, ``vk_overdamped``
   = Eq. crack.eqi04, its inertia-corrected form, the low- and high-velocity
   limits, the kink profile) plus two exact results for the *discrete*
   overdamped chain: the pinning range of a static kink
   (``discrete_depinning_force``) and the steady kink velocity
   (``vk_discrete``, a one-dimensional integral);
2. ``simulate``: an independent reference integrator of the chain (RK4 with
   the sawtooth discontinuities located as events, 4th order in dt);
3. readers of LAMMPS ``dump custom`` files, log thermo blocks and
   ``fix ave/time`` files;
4. kink analysis: centres from velocity maxima, tracking, velocities,
   v_k(f) from the mean chain velocity, space-time maps.

Derivation of the continuum results (a = 1; kappa = kc + K).  With
F(u) = F_s(u) + K u - f a travelling wave u(x - v_k t) of the overdamped
chain obeys  g u'' + m eta v_k u' = F(u).  For the sawtooth F is linear on
each branch: F = kappa (u - u_R) where u < uc (ahead of a right-moving kink)
and F = kappa (u - u_L) where u > uc (behind it), u_R = f/kappa,
u_L = (f + kc uc)/kappa.  Putting u = uc at x = 0,

    u = u_R + (uc - u_R) exp(l1 x)  (x > 0),  u = u_L + (uc - u_L) exp(l2 x)  (x < 0),
    l1,2 = [-p -+ D]/(2g),  p = m eta v_k,  D = sqrt(p^2 + 4 g kappa).

Continuity of u' at x = 0 gives p (A + B) = D (B - A), A = uc - u_R,
B = u_L - uc, i.e.  p kc uc = 2 D (f - f_min),  f_min = (kc/2 + K) uc.
Squaring and writing f/uc = K + kc/beta:  p^2 = g kappa (2 - beta)^2/(beta - 1)
(Eq. crack.eqi04), real for beta > 1, i.e. f < f_max = kappa uc, and with
p > 0 for f > f_min.  Inertia adds m v_k^2 u'' to the left-hand side, i.e.
g -> g (1 - v_k^2/c0^2), c0 = sqrt(g/m); solving for v_k:
v_k^2 = g kappa X / (m^2 eta^2 + m kappa X), X = (2 - beta)^2/(beta - 1).
Near f_min: 2 - beta ~ 4 (f - f_min)/(kc uc), so p ~ 4 sqrt(g kappa)
(f - f_min)/(kc uc) = m (f - f_min)/m_k  (Eq. crack.v1a).  Near f_max:
beta - 1 ~ (f_max - f)/(kc uc), X ~ kc uc/(f_max - f).
"""
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

# ====================================================================== shapes


def phi_sawtooth(s):
    """Sawtooth shape phi(s) = s (Eq. crack.eqi08)."""
    return s


def phi_smooth(s):
    """Smooth shape of Fig. crack.A03ab: tanh(s) + 1.5 exp(-s) sin(3 s)."""
    return np.tanh(s) + 1.5 * np.exp(-s) * np.sin(3.0 * s)


SHAPES = {"sawtooth": phi_sawtooth, "smooth": phi_smooth}


def _shape(shape):
    if callable(shape):
        return shape
    try:
        return SHAPES[shape]
    except KeyError:
        raise ValueError("unknown shape %r (have %s or a callable)" % (shape, sorted(SHAPES)))


def substrate_force(u, kc=1.0, uc=1.0, shape="sawtooth"):
    """F_s(u) = kc phi(u mod uc), phi periodically prolonged with period uc."""
    u = np.asarray(u, float)
    return np.asarray(kc, float) * _shape(shape)(np.mod(u, uc))


# ============================================================ continuum theory

def f_min(kc=1.0, uc=1.0, K=0.0):
    """Griffith threshold f_min = (kc/2 + K) uc: lowest force of a moving kink."""
    return (0.5 * kc + K) * uc


def f_max(kc=1.0, uc=1.0, K=0.0):
    """f_max = (kc + K) uc: above it the unrelaxed state u_R does not exist."""
    return (kc + K) * uc


def uniform_positions(f, kc=1.0, uc=1.0, K=0.0):
    """Force-balance positions of the uniform chain (sawtooth), Eqs.
    crack.eqi09-10: (u_R, u_L) = (f/(kc+K), (f + kc uc)/(kc+K))."""
    f = np.asarray(f, float)
    return f / (kc + K), (f + kc * uc) / (kc + K)


def kink_jump(kc=1.0, uc=1.0, K=0.0):
    """u_L - u_R = kc uc/(kc+K): displacement of a block when a kink passes."""
    return kc * uc / (kc + K)


def beta(f, kc=1.0, uc=1.0, K=0.0):
    """beta = kc/(k_* - K), k_* = f/uc (Eq. crack.eqi04)."""
    f = np.asarray(f, float)
    with np.errstate(divide="ignore"):
        return kc / (f / uc - K)


def _X(f, kc, uc, K):
    """X = (2-beta)^2/(beta-1) on [f_min, f_max), nan elsewhere."""
    f = np.asarray(f, float)
    b = beta(f, kc, uc, K)
    ok = (f >= f_min(kc, uc, K)) & (f < f_max(kc, uc, K))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ok, (2.0 - b) ** 2 / (b - 1.0), np.nan)


def vk_overdamped(f, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0, a=1.0):
    """Continuum kink velocity of the overdamped chain, Eq. crack.eqi04:
    (m eta v_k)^2 = g a^2 (kc+K) (2-beta)^2/(beta-1).  Zero at f_min, nan
    for f < f_min and f >= f_max (no solitary wave there)."""
    return np.sqrt(g * a * a * (kc + K) * _X(f, kc, uc, K)) / (m * eta)


def vk_inertial(f, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0, a=1.0):
    """Kink velocity with inertia (g -> g (1 - v^2/c0^2) in Eq. crack.eqi04):
    v^2 = g a^2 kappa X/(m^2 eta^2 + m kappa X); tends to c0 at f_max."""
    kx = (kc + K) * _X(f, kc, uc, K)
    return np.sqrt(g * a * a * kx / (m * m * eta * eta + m * kx))


def sound_speed(g, m=1.0, a=1.0):
    """c0 = sqrt(g a^2/m)."""
    return math.sqrt(g * a * a / m)


def kink_mass(m, g, kc=1.0, uc=1.0, K=0.0, a=1.0):
    """Kink (crack) mass, Eq. crack.v1a: m_k = m / [(4a/uc) sqrt((g/kc)(1+K/kc))]."""
    return m / (4.0 * a / uc * math.sqrt(g / kc * (1.0 + K / kc)))


def vk_low(f, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0, a=1.0):
    """Low-velocity law v_k = (f - f_min)/(m_k eta), Eq. crack.v1 (the first
    order of Eq. crack.eqi04 at f_min)."""
    f = np.asarray(f, float)
    return (f - f_min(kc, uc, K)) / (kink_mass(m, g, kc, uc, K, a) * eta)


def vk_high_overdamped(f, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0, a=1.0):
    """Overdamped limit f -> f_max:
    m eta v_k = sqrt(g kc (kc+K) a^2 uc/(f_max - f))."""
    f = np.asarray(f, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.sqrt(g * kc * (kc + K) * a * a * uc / (f_max(kc, uc, K) - f)) / (m * eta)


def vk_high_inertial(f, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0, a=1.0):
    """Inertial limit f -> f_max:
    v_k = c0 / sqrt(1 + m eta^2 (f_max - f)/(kc (kc+K) uc))."""
    f = np.asarray(f, float)
    return sound_speed(g, m, a) / np.sqrt(
        1.0 + m * eta * eta * (f_max(kc, uc, K) - f) / (kc * (kc + K) * uc))


def kink_profile(x, f, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0, inertia=False):
    """Continuum profile u(x) of a right-moving sawtooth kink centred at x = 0
    (u = uc there, relaxed u_L for x -> -inf, unrelaxed u_R for x -> +inf);
    see the module docstring for the derivation.  With inertia the profile
    uses g_eff = g (1 - v_k^2/c0^2)."""
    x = np.asarray(x, float)
    if inertia:
        v = float(vk_inertial(f, g, kc, uc, K, m, eta))
        geff = g * (1.0 - v * v * m / g)
    else:
        v = float(vk_overdamped(f, g, kc, uc, K, m, eta))
        geff = g
    if not np.isfinite(v):
        raise ValueError("no solitary wave at f = %g (f_min %g, f_max %g)"
                         % (f, f_min(kc, uc, K), f_max(kc, uc, K)))
    kap = kc + K
    p = m * eta * v
    d = math.sqrt(p * p + 4.0 * geff * kap)
    l1, l2 = (-p - d) / (2.0 * geff), (-p + d) / (2.0 * geff)
    ur, ul = uniform_positions(f, kc, uc, K)
    with np.errstate(over="ignore"):
        return np.where(x > 0, ur + (uc - ur) * np.exp(l1 * np.maximum(x, 0.0)),
                        ul + (uc - ul) * np.exp(l2 * np.minimum(x, 0.0)))


def discrete_depinning_force(g, kc=1.0, uc=1.0, K=0.0):
    """Range (f_-, f_+) of forces where a *static* sawtooth kink exists in the
    discrete chain (Peierls-Nabarro pinning); outside it the kink moves
    forward (f > f_+) or backward (f < f_-).

    Derivation: static kink with blocks n <= 0 relaxed (branch 1) and n >= 1
    unrelaxed (branch 0).  On each side g (u_{n+1} + u_{n-1} - 2 u_n) =
    kappa (u_n - u_{R,L}), solved by r^|n| with r + 1/r = 2 + kappa/g, r < 1.
    Matching the two sides at n = 0, 1 gives u_1 = u_R + D r/(1+r) and
    u_0 = u_R + D/(1+r), D = u_L - u_R = kc uc/kappa.  The configuration is
    consistent while u_1 < uc <= u_0, i.e.
        uc (K + kc r/(1+r)) <= f < uc (K + kc/(1+r)).
    For g -> inf, r -> 1 and both ends tend to f_min."""
    kap = kc + K
    q = 1.0 + kap / (2.0 * g)
    r = q - math.sqrt(q * q - 1.0)
    return uc * (K + kc * r / (1.0 + r)), uc * (K + kc / (1.0 + r))


def _digamma(w):
    """Digamma function of complex w with Re w >= 0 (recurrence to |w| >= 10,
    then the asymptotic series; relative error ~1e-15)."""
    w = np.asarray(w, complex)
    acc = np.zeros_like(w)
    for _ in range(10):
        acc -= 1.0 / w
        w = w + 1.0
    w2 = 1.0 / (w * w)
    series = w2 * (1.0 / 12 - w2 * (1.0 / 120 - w2 * (1.0 / 252 - w2 * (
        1.0 / 240 - w2 * (1.0 / 132 - w2 * 691.0 / 32760)))))
    return acc + np.log(w) - 0.5 / w - series


_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)


def _discrete_integral(p, g, kap, panels=240):
    """J(p) = (p/pi) int_0^inf dth / ([kap + 4 g sin^2(th/2)]^2 + p^2 th^2).
    The sum over periods th = psi + 2 pi k is done in closed form,
    sum_k 1/((k + z)^2 + b^2) = Im digamma(z + i b)/b, and the remaining
    integral over psi in [0, 2 pi) by composite Gauss-Legendre on panels
    graded geometrically towards psi = 0, where the k = 0 term has width
    kappa/p (resolved for p < 1e12)."""
    edges = np.concatenate([[0.0], 2.0 * np.pi * np.logspace(-14.0, 0.0, panels)])
    half = 0.5 * np.diff(edges)
    psi = (half[:, None] * _GL_X[None, :] + (0.5 * (edges[1:] + edges[:-1]))[:, None]).ravel()
    w = (half[:, None] * _GL_W[None, :]).ravel()
    a = kap + 4.0 * g * np.sin(0.5 * psi) ** 2
    s = 2.0 * np.pi * p
    b = a / s
    summed = np.imag(_digamma(psi / (2.0 * np.pi) + 1j * b)) / b / (s * s)
    return p / np.pi * np.sum(w * summed)


def vk_discrete(f, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0):
    """Steady velocity of a sawtooth kink in the *discrete* overdamped chain
    (exact travelling wave u_n(t) = U(t - n/v_k)).

    Derivation: on the branch before (after) its crossing of uc at tau = 0 a
    block obeys m eta U' = g [U(tau+T) + U(tau-T) - 2U] - kappa U + f
    + kc uc H(tau), T = 1/v_k, H the step function.  Fourier transforming,
    U(0) = u_R + kc uc int_{-inf}^0 G, G^(w) = 1/L(w),
    L = kappa + 2g (1 - cos wT) + i m eta w, and U(0) = uc gives
        (p/pi) int_0^inf dth / ([kappa + 4g sin^2(th/2)]^2 + p^2 th^2)
            = (f - f_min)/(kc uc kappa),      p = m eta v_k.
    For g -> inf (4g sin^2 -> g th^2) the integral is pi/(2 kappa D),
    D = sqrt(p^2 + 4 g kappa), which is Eq. crack.eqi04.  The left-hand side
    rises from 1/(2 sqrt(kappa (kappa + 4g))) at p = 0 -- exactly the
    static depinning force f_+ of ``discrete_depinning_force`` -- to
    1/(2 kappa) (f_max) for p -> inf.  Returns 0 for f_- <= f <= f_+
    (pinned), nan for f < f_- (the kink moves backwards) or f >= f_max."""
    f_arr = np.atleast_1d(np.asarray(f, float))
    kap = kc + K
    fm, fp = discrete_depinning_force(g, kc, uc, K)
    out = np.full(f_arr.shape, np.nan)
    for i, fi in enumerate(f_arr):
        if fm <= fi <= fp:
            out[i] = 0.0
            continue
        if not fp < fi < f_max(kc, uc, K):
            continue
        rhs = (fi - f_min(kc, uc, K)) / (kc * uc * kap)
        lo, hi = -30.0, 25.0                     # bisection in ln p
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if _discrete_integral(math.exp(mid), g, kap) < rhs:
                lo = mid
            else:
                hi = mid
            if hi - lo < 1e-13:
                break
        out[i] = math.exp(0.5 * (lo + hi)) / (m * eta)
    return out.reshape(np.shape(f)) if np.ndim(f) else float(out[0])


def background_velocity(vb, kc=1.0, K=0.0):
    """vbar = du_{L,R}/dt = v_b K/(kc+K): velocity of the uniform parts of a
    chain whose stage moves at v_b."""
    return vb * K / (kc + K)


def kink_velocity_from_mean(mean_udot, N, n_k, vbar, jump):
    """Kink velocity from the mean chain velocity <u_dot> = N^-1 sum u_dot:
    v_k = N (<u_dot> - vbar)/(n_k jump).

    Each passage of a kink over a block moves it by jump = u_L - u_R =
    kc uc/(kc+K) (``kink_jump``), so d/dt sum u = N vbar + n_k v_k jump.
    The paper's formula v_k = N (<u_dot> - vbar)/n_k is jump = 1 (uc = 1,
    K << kc); for K = 0.07 it underestimates v_k by the factor 1/1.07."""
    return N * (np.asarray(mean_udot, float) - vbar) / (n_k * jump)


def vk_curve_from_mean(f, mean_udot, N, n_k, vbar, jump, nbins=None):
    """v_k(f) from time series of the driving force and the mean chain
    velocity (a stage moving back, Fig. crack.A05).  With nbins, averages in
    nbins equal bins of f (empty bins dropped).  Returns (f, v_k)."""
    f = np.asarray(f, float)
    vk = kink_velocity_from_mean(mean_udot, N, n_k, vbar, jump)
    if not nbins:
        return f, vk
    edges = np.linspace(f.min(), f.max(), nbins + 1)
    i = np.clip(np.searchsorted(edges, f, side="right") - 1, 0, nbins - 1)
    cnt = np.bincount(i, minlength=nbins)
    ok = cnt > 0
    fb = np.bincount(i, weights=f, minlength=nbins)[ok] / cnt[ok]
    vb = np.bincount(i, weights=vk, minlength=nbins)[ok] / cnt[ok]
    return fb, vb


# ================================================================ integrator

def rk4_stable_dt(g, kc=1.0, K=0.0, m=1.0, eta=1.0, overdamped=True, slope=1.0):
    """Largest stable RK4 step for the chain linearised about a uniform state:
    modes with stiffness k_q = 4 g sin^2(q/2) + slope*kc + K (slope = max
    phi', 1 for the sawtooth) must have h*lambda inside the RK4 region
    |1 + z + z^2/2 + z^3/6 + z^4/24| <= 1."""
    ks = np.linspace(K, 4.0 * g + slope * np.max(kc) + K, 64)
    if overdamped:
        lam = -ks / (m * eta) + 0j
    else:
        disc = np.sqrt(eta * eta / 4.0 - ks / m + 0j)
        lam = np.concatenate([-eta / 2.0 + disc, -eta / 2.0 - disc])

    def ok(h):
        z = h * lam
        return np.all(np.abs(1 + z + z * z / 2 + z ** 3 / 6 + z ** 4 / 24) <= 1.0 + 1e-12)

    lo, hi = 0.0, 10.0 / np.max(np.abs(lam))
    while ok(hi):
        lo, hi = hi, 2 * hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return lo


def _max_slope(phi, uc):
    s = np.linspace(0.0, uc, 2001)
    return float(np.max(np.gradient(phi(s), s)))


def uniform_equilibrium(f, kc=1.0, uc=1.0, K=0.0, shape="sawtooth", branch=0):
    """Position u of a uniform chain in force balance kc phi(u - j uc) + K u = f
    on branch j (the lowest root in [j uc, (j+1) uc), bisection on the first
    sign change); nan where the branch has no root."""
    phi = _shape(shape)
    s = np.linspace(0.0, uc, 4001)[:-1]
    h = kc * phi(s) + K * (s + branch * uc) - f
    idx = np.nonzero((h[:-1] <= 0) & (h[1:] > 0))[0]
    if h[0] == 0:
        return branch * uc
    if len(idx) == 0:
        return math.nan
    lo, hi = s[idx[0]], s[idx[0] + 1]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if kc * phi(mid) + K * (mid + branch * uc) - f > 0:
            hi = mid
        else:
            lo = mid
    return branch * uc + 0.5 * (lo + hi)


def seeded_chain(N, f, kc=1.0, uc=1.0, K=0.0, width=10, center=None, shape="sawtooth"):
    """Initial displacements at constant force f: the unrelaxed uniform state
    u_R with `width` blocks around `center` (default N//2) pre-displaced to
    the relaxed state u_L (one period further); the patch opens into two
    kinks moving apart when f is above the PN threshold."""
    ur = uniform_equilibrium(f, kc, uc, K, shape, 0)
    ul = uniform_equilibrium(f, kc, uc, K, shape, 1)
    u = np.full(N, ur)
    c = N // 2 if center is None else center
    idx = (c - width // 2 + np.arange(width)) % N
    u[idx] = ul
    return u


def weak_center_kc(N, kc=1.0, kc_weak=0.5, nweak=2, center=None):
    """Per-block kc with `nweak` weak blocks (kc_weak) in the middle of the
    chain: the paper's nucleation (Figs. crack.A03ab, crack.A04a)."""
    a = np.full(N, float(kc))
    c = N // 2 if center is None else center
    a[(c - nweak // 2 + np.arange(nweak)) % N] = kc_weak
    return a


@dataclass
class SimResult:
    """Output of ``simulate``.  Time series at every `every` steps: t, f,
    vmean (<u_dot>), kinks (list of arrays of kink centres, sites).
    Snapshots (if snap_every): snap_t, snap_u, snap_udot [nsnap, N].
    crossings: array [n, 3] of (time, block, direction +-1) of the events
    where a block passed a discontinuity u = j uc of F_s.  Final state:
    u, udot, t_end."""
    t: np.ndarray
    f: np.ndarray
    vmean: np.ndarray
    kinks: list
    snap_t: np.ndarray
    snap_u: np.ndarray
    snap_udot: np.ndarray
    crossings: np.ndarray
    u: np.ndarray
    udot: np.ndarray
    t_end: float
    nsteps: int = 0
    nevents: int = 0
    params: dict = field(default_factory=dict)


class _Chain:
    """State and right-hand side of the periodic chain.  The branch of each
    block (its base j uc of F_s) is frozen during an RK4 step, so the RHS is
    smooth inside a step; crossings of u = j uc are handled as events."""

    def __init__(self, N, g, kc, uc, K, m, eta, shape, overdamped, f0, v, t0):
        self.N, self.g, self.uc, self.K = N, float(g), float(uc), float(K)
        self.m, self.eta, self.overdamped = float(m), float(eta), overdamped
        self.set_kc(kc)
        self.phi = _shape(shape)
        self.f_ref, self.t_ref, self.v = float(f0), float(t0), float(v)
        self.base = None
        self._pad = np.empty(N + 2)

    def set_kc(self, kc):
        kc = np.asarray(kc, float)
        self.kc = np.broadcast_to(kc, (self.N,)).copy()

    def force_at(self, t):
        return self.f_ref + self.K * self.v * (t - self.t_ref)

    def set_v(self, t, v):
        self.f_ref, self.t_ref, self.v = self.force_at(t), t, float(v)

    def total_force(self, t, u):
        p = self._pad
        p[1:-1] = u
        p[0] = u[-1]
        p[-1] = u[0]
        return (self.g * (p[2:] + p[:-2] - 2.0 * u) - self.kc * self.phi(u - self.base)
                - self.K * u + self.force_at(t))

    def deriv(self, t, y):
        if self.overdamped:
            return self.total_force(t, y) / (self.m * self.eta)
        return np.stack([y[1], self.total_force(t, y[0]) / self.m - self.eta * y[1]])

    def pos(self, y):
        return y if self.overdamped else y[0]

    def vel(self, y, k):
        """Block velocities for state y with derivative k."""
        return k if self.overdamped else y[1]

    def rk4(self, t, y, h, k1):
        k2 = self.deriv(t + 0.5 * h, y + 0.5 * h * k1)
        k3 = self.deriv(t + 0.5 * h, y + 0.5 * h * k2)
        k4 = self.deriv(t + h, y + h * k3)
        return y + (h / 6.0) * (k1 + 2.0 * (k2 + k3) + k4)


def _hermite_root(u0, d0, u1, d1, h, b):
    """theta in [0, 1] where the cubic Hermite interpolant through (u0, d0),
    (u1, d1) over a step h equals b (bracketed Newton, vectorised)."""
    lo, hi = np.zeros_like(u0), np.ones_like(u0)
    s0 = np.sign(u0 - b)
    th = np.clip((b - u0) / (u1 - u0), 0.0, 1.0)
    for _ in range(50):
        t2, t3 = th * th, th * th * th
        H = ((2 * t3 - 3 * t2 + 1) * u0 + (t3 - 2 * t2 + th) * h * d0
             + (-2 * t3 + 3 * t2) * u1 + (t3 - t2) * h * d1)
        dH = ((6 * t2 - 6 * th) * u0 + (3 * t2 - 4 * th + 1) * h * d0
              + (-6 * t2 + 6 * th) * u1 + (3 * t2 - 2 * th) * h * d1)
        r = H - b
        same = np.sign(r) == s0
        lo = np.where(same, th, lo)
        hi = np.where(same, hi, th)
        with np.errstate(divide="ignore", invalid="ignore"):
            tn = th - r / dH
        bad = ~np.isfinite(tn) | (tn <= lo) | (tn >= hi)
        tn = np.where(bad, 0.5 * (lo + hi), tn)
        done = np.max(np.abs(tn - th)) < 1e-15
        th = tn
        if done:
            break
    return th


def find_kinks(v, threshold=0.0, min_separation=0.0):
    """Kink centres on a periodic chain: local maxima of the block velocity
    v (length N) above `threshold`, located with sub-site precision by the
    parabola through the maximum and its two (periodic) neighbours.  Maxima
    closer than `min_separation` sites to a higher one are dropped.  Returns
    the sorted positions in [0, N).  A 2-d v [nsnap, N] gives a list."""
    v = np.asarray(v, float)
    if v.ndim == 2:
        return [find_kinks(row, threshold, min_separation) for row in v]
    N = len(v)
    vl, vr = np.roll(v, 1), np.roll(v, -1)
    i = np.nonzero((v > threshold) & (v >= vl) & (v > vr))[0]
    if len(i) == 0:
        return np.zeros(0)
    den = vl[i] - 2.0 * v[i] + vr[i]
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.where(den < 0, 0.5 * (vl[i] - vr[i]) / den, 0.0)
    x = np.mod(i + np.clip(d, -0.5, 0.5), N)
    if min_separation > 0 and len(x) > 1:
        order = np.argsort(-v[i])
        keep = []
        for j in order:
            if all(periodic_distance(x[j], x[k], N) >= min_separation for k in keep):
                keep.append(j)
        x = x[keep]
    return np.sort(x)


def simulate(N, g, kc=1.0, uc=1.0, K=0.0, m=1.0, eta=1.0, f0=0.0, v=0.0, u0=None,
             udot0=None, shape="sawtooth", overdamped=True, dt=0.1, t_end=100.0,
             every=10, snap_every=0, schedule=(), kink_threshold=None,
             kink_separation=3.0, stop=None, t0=0.0):
    """Integrate the periodic FK-ME chain (Eq. crack.eqi00).

    Parameters: N blocks, coupling g, kc (scalar or per-block array), uc,
    stage spring K, mass m, damping eta; the driving force starts at f0 and
    changes at the rate K v (stage velocity v); initial displacements u0
    (default: unrelaxed uniform equilibrium at f0) and, underdamped,
    velocities udot0 (default 0); shape "sawtooth", "smooth" or a callable
    phi(s) on [0, uc); overdamped (m eta u' = force) or full dynamics.

    dt is the step of the output grid t0 + k dt, run until t_end.  `every`:
    time series stride (steps), `snap_every`: snapshot stride (0: none).
    schedule: sequence of (when, changes), when a time (the step is cut to
    land on it) or a callable when(t, u, udot) -> bool checked after each
    step; changes a dict with "v" (new stage velocity) and/or "kc" (new kc).
    Each entry fires once.  stop(t, u, udot) -> bool ends the run (checked
    every `every` steps, every step if every = 0).  kink_threshold: velocity above which a maximum is a
    kink (default 1e-2 max(kc) uc/(m eta)); kink_separation: maxima closer
    than this to a higher one are dropped (in a discrete sawtooth chain the
    block that crossed last and the one crossing next are briefly both
    maxima).

    Scheme: classical RK4 with the branch j of F_s = kc phi(u - j uc) frozen
    inside a step.  F_s jumps where a block crosses u = j uc; after each step
    the blocks that left their branch are detected, the crossing time of the
    earliest is found on the cubic Hermite interpolant of the step (error
    O(dt^4)), the step is redone up to that time, the block is put on the
    boundary, switched to the next branch and the rest of the step
    integrated.  Between events the RHS is smooth, so the global error is
    O(dt^4) (verified in the tests); dt must stay below ``rk4_stable_dt``.
    """
    phi = _shape(shape)
    ch = _Chain(N, g, kc, uc, K, m, eta, phi, overdamped, f0, v, t0)
    hmax = rk4_stable_dt(g, ch.kc, K, m, eta, overdamped, _max_slope(phi, uc))
    if dt > hmax:
        warnings.warn("dt = %g above the RK4 stability limit %g" % (dt, hmax))
    if u0 is None:
        u = np.full(N, uniform_equilibrium(f0, np.max(ch.kc), uc, K, phi, 0))
    else:
        u = np.array(u0, float)
    ch.base = np.floor(u / uc) * uc
    if overdamped:
        y = u.copy()
    else:
        y = np.stack([u, np.zeros(N) if udot0 is None else np.asarray(udot0, float)])
    if kink_threshold is None:
        kink_threshold = 1e-2 * np.max(ch.kc) * uc / (m * eta) if m * eta > 0 else 0.0
    pending = list(schedule)

    out_t, out_f, out_v, out_k = [], [], [], []
    snaps_t, snaps_u, snaps_v = [], [], []
    cross = []
    nsteps = int(math.ceil((t_end - t0) / dt - 1e-9))
    t = t0
    k1 = ch.deriv(t, y)
    nevents = 0

    def record(istep, t, y, k1):
        vel = ch.vel(y, k1)
        if every and istep % every == 0:
            out_t.append(t)
            out_f.append(ch.force_at(t))
            out_v.append(vel.mean())
            out_k.append(find_kinks(vel, kink_threshold, kink_separation))
        if snap_every and istep % snap_every == 0:
            snaps_t.append(t)
            snaps_u.append(ch.pos(y).copy())
            snaps_v.append(np.array(vel))

    record(0, t, y, k1)
    istep = 0
    for istep in range(1, nsteps + 1):
        t_target = t0 + istep * dt
        nev_step = 0
        while t < t_target:
            # a timed schedule entry inside the step: land on it first
            t_stop = t_target
            for when, _ in pending:
                if not callable(when) and t < when < t_stop:
                    t_stop = when
            h = t_stop - t
            ynew = ch.rk4(t, y, h, k1)
            knew = ch.deriv(t + h, ynew)
            unew = ch.pos(ynew)
            s = unew - ch.base
            up, down = s > uc, s < 0.0
            crossed = np.nonzero(up | down)[0]
            if len(crossed) == 0:
                t, y, k1 = t_stop, ynew, knew
                if t_stop < t_target:      # landed on a timed schedule entry
                    k1 = _fire(ch, pending, t, y, k1, timed=True)
            else:
                nev_step += 1
                if nev_step > 10 * N + 10:
                    raise RuntimeError("event loop does not advance at t = %g" % t)
                i = crossed
                b = np.where(up[i], ch.base[i] + uc, ch.base[i])
                vel0, vel1 = ch.vel(y, k1), ch.vel(ynew, knew)
                th = _hermite_root(ch.pos(y)[i], vel0[i], unew[i], vel1[i], h, b)
                thmin = th.min()
                sel = th <= thmin + 1e-10
                he = thmin * h
                if he > 1e-13 * h:
                    y = ch.rk4(t, y, he, k1)
                    t = t + he
                ue = ch.pos(y)
                ue[i[sel]] = b[sel]
                ch.base[i[sel]] = np.where(up[i[sel]], b[sel], b[sel] - uc)
                for j in i[sel]:
                    cross.append((t, j, 1 if up[j] else -1))
                nevents += int(sel.sum())
                k1 = ch.deriv(t, y)
        t = t_target
        k1 = _fire(ch, pending, t, y, k1, timed=True)
        k1 = _fire(ch, pending, t, y, k1, timed=False)
        record(istep, t, y, k1)
        if stop is not None and (not every or istep % every == 0) \
                and stop(t, ch.pos(y), ch.vel(y, k1)):
            break

    return SimResult(
        t=np.array(out_t), f=np.array(out_f), vmean=np.array(out_v), kinks=out_k,
        snap_t=np.array(snaps_t), snap_u=np.array(snaps_u).reshape(-1, N),
        snap_udot=np.array(snaps_v).reshape(-1, N),
        crossings=np.array(cross, float).reshape(-1, 3), u=ch.pos(y).copy(),
        udot=np.array(ch.vel(y, k1)), t_end=t, nsteps=istep, nevents=nevents,
        params=dict(N=N, g=g, kc=ch.kc.copy(), uc=uc, K=K, m=m, eta=eta, shape=shape,
                    overdamped=overdamped, dt=dt, v=ch.v))


def _fire(ch, pending, t, y, k1, timed):
    """Apply the schedule entries due at t; returns the (possibly new) RHS."""
    changed = False
    for entry in list(pending):
        when, changes = entry
        if timed and not callable(when) and when <= t + 1e-12 * max(1.0, abs(t)):
            due = True
        elif not timed and callable(when) and when(t, ch.pos(y), ch.vel(y, k1)):
            due = True
        else:
            due = False
        if due:
            pending.remove(entry)
            if "v" in changes:
                ch.set_v(t, changes["v"])
            if "kc" in changes:
                ch.set_kc(changes["kc"])
            changed = True
    return ch.deriv(t, y) if changed else k1


def single_block_exact(t, kc=1.0, uc=1.0, K=1.0, m_eta=1.0, v=1.0, u0=0.0):
    """Exact solution of one overdamped block pulled over the sawtooth,
    m eta u' = -kc (u mod uc) - K (u - v t), u(0) = u0 in [0, uc).

    On branch j (u in [j uc, (j+1) uc)) the equation is linear,
    u' = -a u + (kc j uc + K v t)/(m eta), a = (kc+K)/(m eta), so from
    (t_s, u_s):  u(t) = P_j(t) + (u_s - P_j(t_s)) exp(-a (t - t_s)) with the
    particular solution P_j(t) = (kc j uc + K v t)/(kc+K) - K v/((kc+K) a).
    The block leaves branch j when u = (j+1) uc; that time is the root of a
    monotone function (bisection to machine precision; v >= 0, so u is
    convex on a branch and crosses once).  Returns u(t) for the sorted
    times t and the list of crossing times."""
    t = np.asarray(t, float)
    kap = kc + K
    a = kap / m_eta

    def P(j, tt):
        return (kc * j * uc + K * v * tt) / kap - K * v / (kap * a)

    out = np.empty_like(t)
    ts, us, j = 0.0, float(u0), int(math.floor(u0 / uc))
    crossings = []
    tcur = 0.0
    for k, tk in enumerate(t):
        while True:
            def u_at(tt):
                return P(j, tt) + (us - P(j, ts)) * math.exp(-a * (tt - ts))
            if u_at(tk) < (j + 1) * uc:
                out[k] = u_at(tk)
                break
            lo, hi = max(ts, tcur), tk           # u crosses (j+1) uc in (lo, hi]
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if u_at(mid) < (j + 1) * uc:
                    lo = mid
                else:
                    hi = mid
                if hi - lo <= 4e-16 * max(1.0, hi):
                    break
            tc = 0.5 * (lo + hi)
            crossings.append(tc)
            ts, us, j = tc, (j + 1) * uc, j + 1
        tcur = tk
    return out, crossings


# ================================================================== readers

def read_dump(path, columns=None):
    """LAMMPS ``dump custom`` text file -> (steps, {column: array[nsnap, natoms]})
    with the atoms of each snapshot sorted by id (an ``id`` column is
    required).  `columns` restricts the columns kept.  Also returns the box
    bounds under the key "box" as [nsnap, 3, 2 or 3]."""
    steps, data, boxes = [], {}, []
    names = None
    with open(path) as fh:
        lines = iter(fh)
        for line in lines:
            if not line.startswith("ITEM:"):
                continue
            item = line[5:].strip()
            if item.startswith("TIMESTEP"):
                steps.append(int(next(lines).split()[0]))
            elif item.startswith("NUMBER OF ATOMS"):
                natoms = int(next(lines).split()[0])
            elif item.startswith("BOX BOUNDS"):
                boxes.append([[float(x) for x in next(lines).split()] for _ in range(3)])
            elif item.startswith("ATOMS"):
                hdr = item.split()[1:]
                if names is None:
                    names = hdr
                    if "id" not in names:
                        raise ValueError("dump %s has no id column" % path)
                    keep = [c for c in names if columns is None or c in columns or c == "id"]
                    data = {c: [] for c in keep}
                elif hdr != names:
                    raise ValueError("dump %s: columns change between snapshots" % path)
                rows = np.array([next(lines).split() for _ in range(natoms)], dtype=float)
                rows = rows.reshape(natoms, len(names))
                order = np.argsort(rows[:, names.index("id")], kind="stable")
                for c in data:
                    data[c].append(rows[order, names.index(c)])
    out = {}
    for c, v in data.items():
        if len({len(a) for a in v}) > 1:
            raise ValueError("dump %s: the number of atoms changes" % path)
        out[c] = np.array(v)
    if "id" in out:
        out["id"] = out["id"].astype(np.int64)
    if boxes:
        out["box"] = np.array(boxes)
    return np.array(steps, dtype=np.int64), out


def _is_number(w):
    try:
        float(w)
        return True
    except ValueError:
        return False


def read_log_blocks(path):
    """Thermo blocks of a LAMMPS log: for each run, the lines from the header
    (first word "Step") to "Loop time" (or the end of a truncated log), as a
    dict of float arrays by column name.  Lines inside a block that are not
    rows of numbers of the header's length (warnings) are skipped."""
    blocks, cur, names = [], None, None
    for line in Path(path).read_text().splitlines():
        w = line.split()
        if cur is None:
            if w and w[0] == "Step" and len(w) > 1:
                names, cur = w, []
            continue
        if line.startswith("Loop time"):
            blocks.append((names, cur))
            cur = None
            continue
        if len(w) == len(names) and all(_is_number(x) for x in w):
            cur.append([float(x) for x in w])
    if cur is not None:
        blocks.append((names, cur))
    return [{n: np.array(rows, float).reshape(-1, len(names))[:, i] for i, n in enumerate(names)}
            for names, rows in blocks]


def read_log(path, block=None):
    """Thermo output of a LAMMPS log as a dict of arrays: block i, or
    (block None) all blocks concatenated (they must have the same columns;
    the step shared by consecutive runs appears twice)."""
    blocks = read_log_blocks(path)
    if block is not None:
        return blocks[block]
    if not blocks:
        return {}
    keys = list(blocks[0])
    if any(list(b) != keys for b in blocks):
        raise ValueError("thermo columns differ between runs in %s: pass block=" % path)
    return {k: np.concatenate([b[k] for b in blocks]) for k in keys}


def read_ave_time(path):
    """``fix ave/time`` output.  Scalar mode (header '# TimeStep c1 c2 ...'):
    {name: array}.  Vector mode (headers '# TimeStep Number-of-rows' and
    '# Row c1 ...'): {"TimeStep": [nblocks], name: [nblocks, nrows]}."""
    comments, rows = [], []
    for line in Path(path).read_text().splitlines():
        if line.startswith("#"):
            comments.append(line[1:].split())
        elif line.strip():
            rows.append([float(x) for x in line.split()])
    if not comments or not comments[-1]:
        raise ValueError("%s: no '# TimeStep ...' header" % path)
    vector = len(comments) >= 2 and comments[-1][0] == "Row"
    if not vector:
        names = comments[-1]
        a = np.array(rows, float).reshape(-1, len(names))
        return {n: a[:, i] for i, n in enumerate(names)}
    names = comments[-1]
    steps, blocks, k = [], [], 0
    while k < len(rows):
        step, nrow = rows[k][0], int(rows[k][1])
        steps.append(step)
        blocks.append(rows[k + 1:k + 1 + nrow])
        k += 1 + nrow
    a = np.array(blocks, float)          # [nblocks, nrows, ncols]
    out = {"TimeStep": np.array(steps)}
    for i, n in enumerate(names):
        out[n] = a[:, :, i]
    return out


# ============================================================ kink analysis

def periodic_distance(x, y, N):
    """|x - y| on a ring of N sites."""
    d = np.mod(np.asarray(x, float) - np.asarray(y, float), N)
    return np.minimum(d, N - d)


def track_kinks(times, positions, N, max_jump=2.0, max_gap=2):
    """Link kink centres of successive frames into trajectories.

    times: frame times; positions: per frame an array of centres in [0, N).
    Greedy nearest-neighbour matching with the periodic distance: pairs
    (track, centre) are taken in order of increasing distance while both are
    free and the distance is <= max_jump (sites per frame; times the number
    of frames since the track was last seen).  A track unseen for more than
    max_gap frames ends; unmatched centres start new tracks.
    Returns a list of (t, x) array pairs (x wrapped in [0, N))."""
    tracks, active = [], []            # active: [t list, x list, last frame]
    for fr, (t, xs) in enumerate(zip(times, positions)):
        xs = np.asarray(xs, float)
        active = [a for a in active if fr - a[2] <= max_gap + 1]
        pairs = []
        for ia, a in enumerate(active):
            lim = max_jump * (fr - a[2])
            d = periodic_distance(a[1][-1], xs, N)
            for ix in np.nonzero(d <= lim)[0]:
                pairs.append((d[ix], ia, ix))
        pairs.sort()
        used_a, used_x = set(), set()
        for d, ia, ix in pairs:
            if ia in used_a or ix in used_x:
                continue
            used_a.add(ia)
            used_x.add(ix)
            active[ia][0].append(t)
            active[ia][1].append(xs[ix])
            active[ia][2] = fr
        for ix in range(len(xs)):
            if ix not in used_x:
                a = [[t], [xs[ix]], fr]
                active.append(a)
                tracks.append(a)
    return [(np.array(a[0]), np.array(a[1])) for a in tracks]


def unwrap_positions(x, N):
    """Undo the periodic wrapping of a trajectory (steps < N/2 per frame)."""
    x = np.asarray(x, float)
    if len(x) < 2:
        return x.copy()
    d = np.diff(x)
    d -= N * np.round(d / N)
    return np.concatenate([[x[0]], x[0] + np.cumsum(d)])


def kink_velocity(t, x, N, tmin=-np.inf, tmax=np.inf):
    """Kink velocity (sites per time) of a trajectory: least-squares slope of
    the unwrapped position over tmin <= t <= tmax."""
    t = np.asarray(t, float)
    xu = unwrap_positions(x, N)
    sel = (t >= tmin) & (t <= tmax)
    if sel.sum() < 2:
        return math.nan
    return float(np.polyfit(t[sel], xu[sel], 1)[0])


def crossing_velocity(crossings, nmin, nmax, direction=1):
    """Kink velocity from the event list of ``simulate`` (time, block, dir):
    slope of the block index against its crossing time for the blocks
    nmin <= n <= nmax (a kink moving to smaller n gives a negative value).
    In a steady state of the discrete chain the crossing times are exactly
    equidistant, so this is free of the PN oscillation within the window."""
    c = np.asarray(crossings, float)
    sel = (c[:, 1] >= nmin) & (c[:, 1] <= nmax) & (c[:, 2] == direction)
    if sel.sum() < 2:
        return math.nan
    return float(np.polyfit(c[sel, 0], c[sel, 1], 1)[0])


def spacetime_map(snap_t, snap_v):
    """Space-time array (n, t) of block velocities for imshow: returns
    (array [N, nsnap], extent (t0, t1, -0.5, N - 0.5))."""
    v = np.asarray(snap_v, float)
    t = np.asarray(snap_t, float)
    return v.T.copy(), (t[0], t[-1], -0.5, v.shape[1] - 0.5)


def plot_spacetime(snap_t, snap_v, ax=None, cmap="viridis", vmax=None, kinks=None,
                   title=None):
    """Colour map of block velocities (n vertical, t horizontal) like Fig.
    crack.A03ab; `kinks` (list of (t, x) trajectories) drawn on top.
    Returns the matplotlib Figure (created without pyplot if ax is None)."""
    arr, extent = spacetime_map(snap_t, snap_v)
    if ax is None:
        from matplotlib.figure import Figure
        fig = Figure(figsize=(6, 4))
        ax = fig.add_subplot(1, 1, 1)
    else:
        fig = ax.figure
    im = ax.imshow(arr, origin="lower", aspect="auto", extent=extent, cmap=cmap,
                   vmin=0.0 if vmax is None else None, vmax=vmax, interpolation="nearest")
    fig.colorbar(im, ax=ax, label=r"$\dot u_n$")
    for t, x in kinks or ():
        ax.plot(t, x, ".", ms=1, color="w")
    ax.set_xlabel("t")
    ax.set_ylabel("n")
    if title:
        ax.set_title(title)
    return fig
