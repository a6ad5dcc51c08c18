#!/usr/bin/python3
"""The screening length lambda_s(v) at T > 0 measured with fix eq/meso
thermal (spec shared/notes/thermal-aging.md (e), check (f) 8), against the
references of tools/eqtools/thermal_screening.py.

A ring of M lambda_c blocks, nearest neighbours Pi_{n,n+-1} = Pi0/2, slides
rigidly at v with block 0 pinned (in.eq-thermal-screen).  In the steady
state eps_n = eps0 + delta_n; the measured length is the fit of

    eps_n = e0 + A (rho^n + rho^(M - n)),   lambda_s = -1/ln rho  (blocks),

over n = 2 .. M - 2 (the ring's two images of the pinned block; residuals
relative to |eps_n - e0|), and the same fit of the nonlinear lattice
solution of the same ring (thermal_screening.chain_lattice) is the
reference it must match.  Also printed: the lattice's asymptotic decay
(lattice_decay, a 201-ring's linear tail), the linearised lattice length
1/arccosh(1/c), the linearised continuum length and the seed formula
lambda_c (eps0/2)^1/2.

The grid resolves the screened thresholds: du = sd/(cells (1 + eps0)),
eps0 from the reference, half a grid step per time step (dX = du/2; dX =
du is 1 % shorter on lambda_s), rate window 0.5 x_c (stable; 0.3 x_c
oscillates), run long enough for eps to settle: Xmax = 8 window/(1 - c)
+ 5 x_c (c the linear gain; eps relaxes by e per window/(1 - c)).  The
steadiness: the same fit on eps averaged over the third quarter of the
run against the last quarter; what is left of that difference at the end
is q/(1 - q) of it, q = exp(-(Xmax/4)(1 - c)/window).

python3 screening.py [--quick] [--plot FILE]   (lmp from FEQ_LMP or ../../build/lmp)
"""
import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
from eqtools import run_lammps  # noqa: E402
from eqtools import thermal_screening as ts  # noqa: E402

INPUT = HERE / "in.eq-thermal-screen"
SD = 0.5 / math.sqrt(12.0)    # thresholds uniform [0.75, 1.25] x_c


def settings(v, theta=0.05, Pi0=0.6, cells=4.0, window=1.0):
    """Grid, step and run length for velocity v (units of x_c)."""
    e0 = ts.eps0(v, theta=theta, Pi0=Pi0)
    c = ts.c_factor(v, theta=theta, Pi0=Pi0)
    du = SD / (cells * (1.0 + e0))
    xmax = 8.0 * window / (1.0 - c) + 5.0
    return dict(eps0=e0, c=c, grid=du, dX=0.5 * du, Xmax=xmax, window=window)


def read_eps(path):
    """eps of every block, by id (block 0 = id 1 pinned)."""
    text = Path(path).read_text().split("ITEM: ATOMS")[-1].splitlines()[1:]
    rows = np.array([[float(x) for x in line.split()] for line in text if line.strip()])
    rows = rows[np.argsort(rows[:, 0])]
    return rows[:, 2]


def steadiness(ell, ell_mid, s):
    """What the fit at the end may still lack of the steady state."""
    q = math.exp(-0.25 * s["Xmax"] * (1.0 - s["c"]) / s["window"])
    return abs(ell - ell_mid) * q / (1.0 - q)


def run(v, workdir, M=24, theta=0.05, Pi0=0.6, cells=4.0, labels=16, window=1.0, nprocs=1,
        xmax=None, extra_vars=None):
    """Run the ring at v; returns dict(eps, eps_mid, settings)."""
    s = settings(v, theta, Pi0, cells, window)
    if xmax is not None:
        s["Xmax"] = xmax
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    var = dict(M=M, pi0=Pi0, T=theta, v=v, grid=repr(s["grid"]), dX=repr(s["dX"]),
               Xmax=repr(s["Xmax"]), window=window, labels=labels, out=workdir)
    var.update(extra_vars or {})
    log = run_lammps(INPUT, var, nprocs=nprocs, cwd=workdir)
    return dict(eps=read_eps(workdir / "eps.dump"), eps_mid=read_eps(workdir / "eps_mid.dump"),
                settings=s, log=log)


def fit_length(eps, n0=2):
    """lambda_s (blocks) and e0 of eps_n = e0 + A (rho^n + rho^(M-n)),
    n = n0 .. M - n0 (block 0 pinned), residuals relative to |eps_n - e0|
    (a floor of 1e-9 (1 + e0)): rho by golden-section search, e0 and A
    by weighted linear least squares at each rho."""
    eps = np.asarray(eps, float)
    M = len(eps)
    n = np.arange(n0, M - n0 + 1)
    y = eps[n]

    def solve(rho):
        g = rho ** n + rho ** (M - n)
        e0, A = y[len(y) // 2], 0.0
        for _ in range(4):    # reweighting: relative residuals
            w = 1.0 / (np.abs(y - e0) + 1e-9 * (1.0 + abs(e0)))
            X = np.stack([np.ones_like(g), g], axis=1) * w[:, None]
            (e0, A), *_ = np.linalg.lstsq(X, y * w, rcond=None)
        w = 1.0 / (np.abs(y - e0) + 1e-9 * (1.0 + abs(e0)))
        r = (y - e0 - A * g) * w
        return float(r @ r), e0, A

    a, b = 0.05, 0.95
    gr = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = b - gr * (b - a), a + gr * (b - a)
    fc, fd = solve(c)[0], solve(d)[0]
    for _ in range(80):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - gr * (b - a)
            fc = solve(c)[0]
        else:
            a, c, fc = c, d, fd
            d = a + gr * (b - a)
            fd = solve(d)[0]
    rho = 0.5 * (a + b)
    _, e0, A = solve(rho)
    return -1.0 / math.log(rho), e0


def references(v, M=24, theta=0.05, Pi0=0.6):
    """The reference lengths at v: lattice (the same fit of the nonlinear
    ring solution), lattice_tail (its asymptotic decay), linear (lattice),
    continuum, seed; eps0 and c."""
    sol = ts.chain_lattice(v, theta=theta, Pi0=Pi0, M=M, pinned=(0,))
    return dict(lattice=fit_length(sol["eps"])[0], eps_lattice=sol["eps"],
                lattice_tail=ts.lattice_decay(v, theta=theta, Pi0=Pi0),
                linear=ts.lambda_linear_lattice(v, theta=theta, Pi0=Pi0),
                continuum=ts.lambda_linear_continuum(v, theta=theta, Pi0=Pi0),
                seed=ts.lambda_seed(v, theta=theta, Pi0=Pi0),
                eps0=sol["eps0"], c=ts.c_factor(v, theta=theta, Pi0=Pi0))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="v = 1e-1 .. 1e-3 only")
    ap.add_argument("--plot", default=str(HERE.parents[1] / "doc" / "src" / "img" /
                                          "eq_thermal_screening.png"))
    ap.add_argument("--cells", type=float, default=4.0)
    ap.add_argument("--labels", type=int, default=16)
    args = ap.parse_args()
    vs = [1e-1, 1e-2, 1e-3] if args.quick else [1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    rows = []
    print("theta = 0.05, Pi0 = 0.6, ring of 24 blocks, grid sd/(%g (1 + eps0)), %d panels"
          % (args.cells, args.labels))
    print("%8s %8s %8s %8s | %9s %9s %9s %9s %9s %9s" % (
        "v", "eps0", "eps0_run", "steady", "measured", "lattice", "tail", "linear", "contin.",
        "seed"))
    with tempfile.TemporaryDirectory() as tmp:
        for v in vs:
            r = run(v, Path(tmp) / ("v%g" % v), cells=args.cells, labels=args.labels)
            ell, e0 = fit_length(r["eps"])
            ell_mid, _ = fit_length(r["eps_mid"])
            ref = references(v)
            st = steadiness(ell, ell_mid, r["settings"])
            rows.append((v, ref, ell, e0, st))
            print("%8.0e %8.4f %8.4f %8.1e | %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f" % (
                v, ref["eps0"], e0, st, ell, ref["lattice"], ref["lattice_tail"],
                ref["linear"], ref["continuum"], ref["seed"]), flush=True)
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        v = np.array([r[0] for r in rows])
        fig, ax = plt.subplots(figsize=(5.5, 4))
        vv = np.logspace(math.log10(v.min()), math.log10(v.max()), 40)
        ax.loglog(vv, [ts.lambda_seed(x, theta=0.05, Pi0=0.6) for x in vv], "k:",
                  label=r"seed $\lambda_c(\epsilon_0/2)^{1/2}$")
        ax.loglog(vv, [ts.lambda_linear_lattice(x, theta=0.05, Pi0=0.6) for x in vv], "k-",
                  label=r"linearised lattice $1/\mathrm{arccosh}(1/c)$")
        ax.loglog(v, [r[1]["lattice"] for r in rows], "bs", mfc="none",
                  label="nonlinear lattice (same fit)")
        ax.loglog(v, [r[2] for r in rows], "ro", label="fix eq/meso thermal")
        from matplotlib.ticker import FixedLocator, NullFormatter, ScalarFormatter
        ax.yaxis.set_major_locator(FixedLocator([0.8, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0]))
        ax.yaxis.set_major_formatter(ScalarFormatter())
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel(r"$v$ ($x_c\,\omega$)")
        ax.set_ylabel(r"$\lambda_s/\lambda_c$")
        ax.set_title(r"screening length at $\theta = 0.05$, $\Pi_0 = 0.6$")
        ax.legend(fontsize=8)
        fig.tight_layout()
        Path(args.plot).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.plot, dpi=120)
        print("wrote", args.plot)


if __name__ == "__main__":
    main()
