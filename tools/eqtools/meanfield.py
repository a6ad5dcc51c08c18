"""Mean-field master equation of interacting contacts (paper Sec. IV).

The EQ model with the elastic interaction k_ij = ftilde/r_ij (r <= lambda_c)
is compared with the non-interacting ME solved with *effective*
distributions:

* steady sliding (Eqs. mf.eq09-mf.eq11):
    R(x)   = G(x - alpha x_c, gamma x_c),
    P_c(x) = P_h (x) G(., gamma sqrt(2) x_c),
    P_h(x) = beta P_c0[beta (x - alpha x_c)],
  with beta = 1 + b1 kappa, alpha = b2 kappa / beta,
  gamma = b3 alpha - b4 alpha^2;
* onset of sliding (Eq. mf.eq15): thresholds
    P_ci(x) = N x^eps0 P_c0[beta0 (x - alpha0 x_c)],
  beta0 = 1 + c1 kappa / (1 - kappa/kappa_c), eps0 = c2 (beta0 - 1),
  alpha0 = (x_L / x_c)(1 - 1/beta0), and R as above.

Distributions are written as tables in the package's threshold-table
format and solved by eq-me.  Only numpy is needed.
"""
import math
from pathlib import Path

import numpy as np

from . import load, run_eqme

# the paper's coefficients (Sec. IV, rectangular P_c0 with x_s = 1,
# Delta x_s = 0.25, lambda_c = 3a)
PAPER_B = (18.0, 9.6, 0.142, 0.232)
PAPER_C = (33.9, 3.0, 0.074)

XS, DXS = 1.0, 0.25          # P_c0 uniform on [XS - DXS, XS + DXS]
XC = XS                      # mean threshold


def steady_params(kappa, b=PAPER_B):
    b1, b2, b3, b4 = b
    beta = 1.0 + b1 * kappa
    alpha = b2 * kappa / beta
    gamma = b3 * alpha - b4 * alpha ** 2
    return alpha, beta, gamma


def onset_params(kappa, c=PAPER_C, xl=XS - DXS):
    c1, c2, kc = c
    beta0 = 1.0 + c1 * kappa / (1.0 - kappa / kc)
    eps0 = c2 * (beta0 - 1.0)
    alpha0 = (xl / XC) * (1.0 - 1.0 / beta0)
    return alpha0, beta0, eps0


def _ncdf(z):
    return 0.5 * (1.0 + np.vectorize(math.erf)(z / math.sqrt(2.0)))


def smeared_uniform(x, lo, hi, sigma):
    """Density of U(lo, hi) convolved with G(0, sigma)."""
    if sigma <= 0:
        return np.where((x >= lo) & (x <= hi), 1.0 / (hi - lo), 0.0)
    return (_ncdf((x - lo) / sigma) - _ncdf((x - hi) / sigma)) / (hi - lo)


def steady_threshold_density(x, kappa, b=PAPER_B):
    alpha, beta, gamma = steady_params(kappa, b)
    lo = alpha * XC + (XS - DXS) / beta
    hi = alpha * XC + (XS + DXS) / beta
    return smeared_uniform(x, lo, hi, gamma * math.sqrt(2.0) * XC)


def onset_threshold_density(x, kappa, c=PAPER_C):
    alpha0, beta0, eps0 = onset_params(kappa, c)
    lo = alpha0 * XC + (XS - DXS) / beta0
    hi = alpha0 * XC + (XS + DXS) / beta0
    p = np.where((x >= lo) & (x <= hi), np.power(np.maximum(x, 1e-300), eps0), 0.0)
    norm = np.trapz(p, x)
    return p / norm


def write_table(path, keyword, x, p, comment=""):
    with open(path, "w") as f:
        f.write("# %s\n%s\nN %d\n\n" % (comment or "FRICTION-EQ effective thresholds", keyword, len(x)))
        for i, (a, b) in enumerate(zip(x, p)):
            f.write("%d %.12g %.12g\n" % (i + 1, a, b))


def reform_args(kappa, b=PAPER_B):
    alpha, beta, gamma = steady_params(kappa, b)
    if alpha <= 0 or gamma <= 0:
        return ["reform", "delta", 0.0]
    return ["reform", "gaussian", alpha * XC, gamma * XC]


def solve_steady(kappa, workdir, b=PAPER_B, dx=0.002):
    """ME Q_s(x) with the steady effective distributions: (x, Q_s)."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    tag = "k%g" % kappa
    alpha, beta, gamma = steady_params(kappa, b)
    sig = gamma * math.sqrt(2.0) * XC
    lo = alpha * XC + (XS - DXS) / beta - 8 * sig - 1e-3
    hi = alpha * XC + (XS + DXS) / beta + 8 * sig + 1e-3
    x = np.linspace(max(lo, 1e-6), hi, 2001)
    table = workdir / ("pc_%s.table" % tag)
    write_table(table, "PC", x, steady_threshold_density(x, kappa, b))
    qs = workdir / ("qs_%s.dat" % tag)
    s = run_eqme(["threshold", "table", table, "PC"] + reform_args(kappa, b) +
                 ["dx", dx, "xmax", 4.0, "steady", qs], cwd=workdir)
    d = load(qs)
    return d[:, 0], d[:, 1], s


def solve_onset(kappa, workdir, b=PAPER_B, c=PAPER_C, dx=0.002, xmax=3.0, beta_eps=None):
    """ME F(X)/(N k_c) with the onset thresholds P_ci: (X, F).  beta_eps =
    (beta0, eps0) overrides the c1, c2, kappa_c forms."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    tag = "k%g" % kappa
    if beta_eps is None:
        alpha0, beta0, eps0 = onset_params(kappa, c)
    else:
        beta0, eps0 = beta_eps
        alpha0 = ((XS - DXS) / XC) * (1.0 - 1.0 / beta0)
    lo = alpha0 * XC + (XS - DXS) / beta0
    hi = alpha0 * XC + (XS + DXS) / beta0
    x = np.linspace(lo, hi, 2001)
    p = np.power(x, eps0)
    p /= np.trapz(p, x)
    table = workdir / ("pci_%s.table" % tag)
    write_table(table, "PCI", x, p)
    ff = workdir / ("F_%s.dat" % tag)
    s = run_eqme(["threshold", "table", table, "PCI"] + reform_args(kappa, b) +
                 ["dx", dx, "xmax", xmax, "force", ff], cwd=workdir)
    d = load(ff)
    return d[:, 0], d[:, 1], s


def onset_defined(kappa, c=PAPER_C):
    """P_ci exists below the breakdown strength kappa_c only."""
    return kappa < c[2]


# ------------------------------------------------------------ closed forms
# (used to fit the effective parameters quickly; the comparisons quoted in
# the docs use eq-me)

def steady_closed_form(x, alpha, beta, gamma):
    """Stationary ME solution for the effective distributions, by
    quadrature: Q_s(x) = J(x) int_{-inf}^x R(xi) / J(xi) dxi / norm, where
    J is the survival function of the thresholds (a re-formed contact's
    threshold lies above its stretch)."""
    x = np.asarray(x, float)
    sig = gamma * math.sqrt(2.0) * XC
    lo = alpha * XC + (XS - DXS) / beta
    hi = alpha * XC + (XS + DXS) / beta
    pc = smeared_uniform(x, lo, hi, sig)
    dx = x[1] - x[0]
    cdf = np.concatenate([[0.0], np.cumsum(0.5 * (pc[1:] + pc[:-1]) * dx)])
    surv = np.clip(1.0 - cdf / cdf[-1], 1e-300, None)
    if gamma > 0:
        r = np.exp(-0.5 * ((x - alpha * XC) / (gamma * XC)) ** 2)
    else:
        r = np.zeros_like(x)
        r[np.argmin(np.abs(x - alpha * XC))] = 1.0 / dx
    r /= r.sum() * dx
    inner = np.cumsum(r / surv) * dx
    q = surv * inner
    q[surv < 1e-250] = 0.0
    return q / (q.sum() * dx)


def bin_average(xf, qf, edges):
    """Average of a fine-grid density over histogram bins."""
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (qf[1:] + qf[:-1]) * np.diff(xf))])
    ce = np.interp(edges, xf, cum, left=0.0, right=cum[-1])
    return np.diff(ce) / np.diff(edges)


def fit_steady(centers, q_eq, start):
    """Fit (alpha, beta, gamma) of the steady effective distributions to an
    EQ histogram density (least squares over the bins)."""
    from scipy.optimize import minimize
    w = centers[1] - centers[0]
    edges = np.concatenate([centers - 0.5 * w, [centers[-1] + 0.5 * w]])
    xf = np.linspace(edges[0], edges[-1], 8001)

    def cost(p):
        a, b, g = p
        if b < 1.0 or g < 1e-4 or a < 0:
            return 1e9
        qm = bin_average(xf, steady_closed_form(xf, a, b, g), edges)
        return float(np.sum((qm - q_eq) ** 2) * w)

    res = minimize(cost, start, method="Nelder-Mead",
                   options={"xatol": 1e-5, "fatol": 1e-10, "maxiter": 2000})
    return res.x, res.fun


def fit_b_global(kappas, hists, start=PAPER_B):
    """b1..b4 fitted to all EQ histograms at once: the sum of the L1 distances of
    Q_s(x; alpha, beta, gamma(b, kappa)) over all bins and kappas
    (hists: list of (centers, density))."""
    from scipy.optimize import minimize
    prep = []
    for (c, q) in hists:
        w = c[1] - c[0]
        edges = np.concatenate([c - 0.5 * w, [c[-1] + 0.5 * w]])
        prep.append((edges, np.linspace(edges[0], edges[-1], 8001), q, w))

    def cost(b):
        tot = 0.0
        for k, (edges, xf, q, w) in zip(kappas, prep):
            a, be, g = steady_params(k, b)
            if be < 1.0 or a < 0 or g <= 1e-4:
                return 1e9
            qm = bin_average(xf, steady_closed_form(xf, a, be, g), edges)
            tot += float(np.sum(np.abs(qm - q)) * w)
        return tot

    res = minimize(cost, start, method="Nelder-Mead",
                   options={"xatol": 1e-5, "fatol": 1e-12, "maxiter": 4000})
    return tuple(float(v) for v in res.x)


def fit_b(kappas, alphas, betas, gammas):
    """b1..b4 from per-kappa fits: beta = 1 + b1 kappa, alpha beta = b2 kappa
    (least squares through the origin), gamma = b3 alpha - b4 alpha^2."""
    k = np.asarray(kappas, float)
    a = np.asarray(alphas, float)
    b = np.asarray(betas, float)
    g = np.asarray(gammas, float)
    b1 = float(np.sum(k * (b - 1.0)) / np.sum(k * k))
    b2 = float(np.sum(k * a * b) / np.sum(k * k))
    A = np.vstack([a, -a * a]).T
    b3, b4 = np.linalg.lstsq(A, g, rcond=None)[0]
    return (b1, b2, float(b3), float(b4))


def l1_distance(centers, q_eq, x_me, q_me):
    """int |Q_EQ - Q_ME| dx over the histogram (ME averaged over the bins)."""
    w = centers[1] - centers[0]
    edges = np.concatenate([centers - 0.5 * w, [centers[-1] + 0.5 * w]])
    qm = bin_average(np.asarray(x_me, float), np.asarray(q_me, float), edges)
    return float(np.sum(np.abs(q_eq - qm)) * w)


def lattice_sum(lam, power=1.0):
    """S = sum over the triangular lattice (a = 1) of 1/r^power for
    0 < r <= lam: the mean-field coupling sum_j k_ij / (ftilde)."""
    n = int(lam) + 2
    tot = 0.0
    for i in range(-2 * n, 2 * n + 1):
        for j in range(-2 * n, 2 * n + 1):
            x = i + 0.5 * j
            y = j * math.sqrt(3.0) / 2.0
            r = math.hypot(x, y)
            if 0 < r <= lam * (1 + 1e-12):
                tot += r ** -power
    return tot
