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


def solve_onset(kappa, workdir, b=PAPER_B, c=PAPER_C, dx=0.002, xmax=3.0):
    """ME F(X)/(N k_c) with the onset thresholds P_ci: (X, F)."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    tag = "k%g" % kappa
    alpha0, beta0, eps0 = onset_params(kappa, c)
    lo = alpha0 * XC + (XS - DXS) / beta0
    hi = alpha0 * XC + (XS + DXS) / beta0
    x = np.linspace(lo, hi, 2001)
    p = onset_threshold_density(x, kappa, c)
    table = workdir / ("pci_%s.table" % tag)
    write_table(table, "PCI", x, p)
    ff = workdir / ("F_%s.dat" % tag)
    s = run_eqme(["threshold", "table", table, "PCI"] + reform_args(kappa, b) +
                 ["dx", dx, "xmax", xmax, "force", ff], cwd=workdir)
    d = load(ff)
    return d[:, 0], d[:, 1], s
