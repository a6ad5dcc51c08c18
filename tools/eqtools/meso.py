"""Far zone (paper Sec. "Far zone" and "Elastic screening length"):
independent references for fix eq/meso.

- screening_lattice(): the self-consistent screening of Eq. scr.eq08 on a
  lattice of lambda_c blocks, solved as a linear system.  In steady
  sliding with contacts re-forming unstretched, the master equation with
  the forces scaled by 1 + eps has Gamma = (1 + eps)/x_c exactly, so
  eps_n = x_c sum_m Gamma_m Pi_mn becomes
      eps_n = sum_{m sliding} Pi_mn (1 + eps_m),
  a pinned block (Gamma = 0) contributing nothing.
- stripe_decay(): the decay of Delta eps = eps - eps0 away from a pinned
  stripe on a square lattice with nearest-neighbour Pi1 (nu = 4): the
  exact lattice ratio per block and the continuum screening length of the
  Taylor expansion (scr.eq09 with the stripe's factor 1/4 instead of the
  chain's 1/2: lambda_s^2 = eps0/4).
- chain_decay(): the same for a 1D chain (nu = 2, the paper's factor 1/2).
"""
import math

import numpy as np


def pi_kernel(nlam, kappa, lam=1.0):
    """Pi(r) = N_lambda kappa (lambda_c / r)^3 (Eq. scr.eq01Pi)."""
    return lambda r: nlam * kappa * (lam / r) ** 3


def lattice_pairs(sites, box, rcut, kernel):
    """Sparse Pi_nm over all periodic images within rcut (minimum image
    does not suffice when rcut > L/2): list of (n, m, Pi)."""
    sites = np.asarray(sites, float)
    box = np.asarray(box, float)
    dim = sites.shape[1]
    reach = [int(math.ceil(rcut / box[k])) if box[k] > 0 else 0 for k in range(dim)]
    shifts = np.array(np.meshgrid(*[np.arange(-r, r + 1) for r in reach], indexing="ij")).reshape(dim, -1).T
    pairs = []
    cut2 = rcut * rcut * (1 + 2e-12)
    for n in range(len(sites)):
        for s in shifts:
            d = sites - sites[n] + s * box
            r2 = np.sum(d * d, axis=1)
            for m in np.nonzero((r2 > 0) & (r2 <= cut2))[0]:
                pairs.append((n, m, kernel(math.sqrt(r2[m]))))
    return pairs


def screening_lattice(sites, box, sliding, rcut, kernel):
    """eps of every block from eps_n = sum_{m sliding} Pi_nm (1 + eps_m)
    (dense solve; sites: (N, d), box: periodic lengths, sliding: bool (N))."""
    n = len(sites)
    P = np.zeros((n, n))
    for a, b, p in lattice_pairs(sites, box, rcut, kernel):
        P[a, b] += p
    s = np.asarray(sliding, bool).astype(float)
    A = np.eye(n) - P * s[None, :]
    rhs = P @ s
    return np.linalg.solve(A, rhs), P.sum(axis=1)


def stripe_decay(pi1):
    """Square lattice, nearest neighbours, stripe geometry (translation
    invariant along the stripe): returns (eps0, exact ratio per block,
    exact decay length, continuum lambda_s)."""
    pi0 = 4.0 * pi1
    eps0 = pi0 / (1.0 - pi0)
    # Pi1 lam^2 - (1 - 2 Pi1) lam + Pi1 = 0, the root below 1
    b = 1.0 - 2.0 * pi1
    lam = (b - math.sqrt(b * b - 4.0 * pi1 * pi1)) / (2.0 * pi1)
    return eps0, lam, -1.0 / math.log(lam), math.sqrt(eps0 / 4.0)


def chain_decay(pi1):
    """1D chain, nearest neighbours (nu = 2): (eps0, ratio, decay length,
    the paper's lambda_s = (eps0/2)^(1/2))."""
    pi0 = 2.0 * pi1
    eps0 = pi0 / (1.0 - pi0)
    # e(x) - 1 = Pi1 (e(x-1) + e(x+1)):  Pi1 lam^2 - lam + Pi1 = 0
    lam = (1.0 - math.sqrt(1.0 - 4.0 * pi1 * pi1)) / (2.0 * pi1)
    return eps0, lam, -1.0 / math.log(lam), math.sqrt(eps0 / 2.0)


def fit_decay(x, deps):
    """Least-squares fit of log|Delta eps| = c - x/ell over the given
    points: (ell, standard error of ell)."""
    x = np.asarray(x, float)
    y = np.log(np.abs(np.asarray(deps, float)))
    A = np.vstack([np.ones_like(x), -x]).T
    coef, res, _, _ = np.linalg.lstsq(A, y, rcond=None)
    slope = coef[1]
    dof = max(len(x) - 2, 1)
    s2 = float(res[0]) / dof if len(res) else 0.0
    cov = s2 * np.linalg.inv(A.T @ A)
    ell = 1.0 / slope
    return ell, math.sqrt(cov[1, 1]) / slope ** 2
