#!/usr/bin/python3
"""Thermal creep of PN-pinned kinks in the FK-ME chain (paper Sec. V,
Discussion: arrested kinks "will slowly move (creep) due to thermally
activated jumps"), measured against Arrhenius / transition-state theory.

    /usr/bin/python3 run_creep.py [--f 0.59] [--x 4 5 6 7] [--out out/creep] ...

in.eq-fkme-creep: a periodic chain of N blocks (g = 25, sawtooth
k_c = u_c = 1, K = 0.07) at constant driving force f inside the pinning
range f_- < f < f_+ of a static kink (fkme.discrete_depinning_force) holds a
kink-antikink pair (a slipped band), relaxed by minimization.  At T = 0
the kinks never move.

1. mode saddle: E_static and the energy with the first unslipped block
   ahead of the kink held at the cusp u = u_c, the rest minimized (the
   saddle of the sawtooth landscape: the block must pass the cusp to hop).
   Barrier dE = E_saddle - E_static.
2. mode creep at temperatures T = dE/x (fix langevin, damping eta = 10,
   fix nve): the total slip count grows by one per hop of either kink
   (both kinks hop by the same barrier, by mirror symmetry).  Rate per kink
   k = n_hops/(2 t), Poisson error sqrt(n)/(2 t).
3. Fit ln k = ln A - E_fit/T (weighted by the Poisson errors) and compare
   E_fit with dE (z = (E_fit - dE)/sd).  Transition-state theory for the
   sawtooth (a cusp saddle, harmonic wells of the same Hessian H on both
   sides) gives A_TST = (2 pi)^-1 [det H/(m det H')]^(1/2), H' = H without
   the row and column of the hopping block; for a long chain
   det H/det H' = 1/(H^-1)_bb = sqrt(kappa (kappa + 4 g)), kappa = k_c + K.
   A T = dE/30 run checks that no hop happens (k_TST t exp(-30) << 1).

Writes out/creep/creep.png and out/creep/summary_creep.txt.
"""
import argparse
import math
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import numpy as np  # noqa: E402

import eqtools  # noqa: E402
from eqtools import fkme  # noqa: E402

INPUT = HERE / "in.eq-fkme-creep"
KC, UC, K = 1.0, 1.0, 0.07


def lammps(out, **var):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    var.setdefault("out", ".")
    return eqtools.run_lammps(INPUT, var, cwd=out, log="log.lammps")


def saddle(out, f=0.59, g=25.0, N=128, n0=48, n1=80):
    """Static and saddle energies (mode saddle); returns a dict."""
    txt = lammps(out, mode="saddle", f=f, g=g, N=N, n0=n0, n1=n1)
    res = {}
    for line in txt.splitlines():
        w = line.split()
        if line.startswith("CREEP E_static"):
            res["E_static"], res["slips_static"] = float(w[2]), float(w[4])
        elif line.startswith("CREEP E_saddle"):
            res["E_saddle"], res["u_b"], res["slips_saddle"] = float(w[2]), float(w[4]), float(w[6])
    res["dE"] = res["E_saddle"] - res["E_static"]
    res["band"] = n1 - n0
    return res


def tst_prefactor(g, N=None, m=1.0):
    """A_TST = (2 pi)^-1 sqrt(det H/(m det H')) for the sawtooth chain:
    1/(H^-1)_bb of the periodic chain Hessian H = kappa + g (2 - shift -
    shift^-1) (numerically for N blocks, or sqrt(kappa (kappa + 4g)) for
    N -> inf)."""
    kap = KC + K
    if N is None:
        ratio = math.sqrt(kap * (kap + 4.0 * g))
    else:
        H = np.diag(np.full(N, kap + 2.0 * g))
        i = np.arange(N)
        H[i, (i + 1) % N] -= g
        H[i, (i - 1) % N] -= g
        ratio = 1.0 / np.linalg.inv(H)[0, 0]
    return math.sqrt(ratio / m) / (2.0 * math.pi)


def creep(out, T, f=0.59, g=25.0, N=128, n0=48, n1=80, seed=4711, tmax=4000.0, nhop=40,
          eta=10.0, dt=0.05, every=100):
    """One creep run; returns dict with time series, hops and rate per kink."""
    out = Path(out)
    lammps(out, mode="creep", T=T, f=f, g=g, N=N, n0=n0, n1=n1, seed=seed, tmax=tmax,
           nhop=nhop, eta=eta, dt=dt, every=every)
    d = np.atleast_2d(np.loadtxt(out / "slips.dat"))
    t, s = d[:, 0], d[:, 1]
    s0 = s[0]
    n = float(s[-1] - s0)                     # net hops (forward - backward)
    tend = float(t[-1])
    # hop times: first time the count reaches s0 + k
    hop_t = [float(t[np.argmax(s >= s0 + k)]) for k in range(1, int(round(n)) + 1)]
    nback = int(np.sum(np.clip(-np.diff(s), 0, None)))
    return {"T": T, "t": t, "s": s - s0, "n": n, "tend": tend, "hop_t": np.array(hop_t),
            "nback": nback, "rate": n / (2.0 * tend), "rate_err": math.sqrt(max(n, 1.0)) / (2.0 * tend)}


def fit_arrhenius(runs):
    """Weighted least squares of ln k = ln A - E/T over runs with n >= 3.
    Returns E, sd(E), ln A, sd(ln A), chi2, dof."""
    sel = [r for r in runs if r["n"] >= 3]
    if len(sel) < 2:
        return None
    x = np.array([1.0 / r["T"] for r in sel])
    y = np.array([math.log(r["rate"]) for r in sel])
    w = np.array([r["n"] for r in sel])          # 1/var(ln k) = n (Poisson)
    A = np.column_stack([np.ones_like(x), -x])
    Aw = A * np.sqrt(w)[:, None]
    yw = y * np.sqrt(w)
    coef, *_ = np.linalg.lstsq(Aw, yw, rcond=None)
    cov = np.linalg.inv(Aw.T @ Aw)
    chi2 = float(np.sum((yw - Aw @ coef) ** 2))
    dof = len(sel) - 2
    return {"E": float(coef[1]), "E_err": float(math.sqrt(cov[1, 1])), "lnA": float(coef[0]),
            "lnA_err": float(math.sqrt(cov[0, 0])), "chi2": chi2, "dof": dof}


def plot(runs, fit, sad, A_tst, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    ax = axs[0]
    for i, r in enumerate(runs):
        ax.step(r["t"], r["s"], where="post", color="C%d" % i, label="T = %.4g (dE/T = %.1f)"
                % (r["T"], sad["dE"] / r["T"]))
    ax.set_xlabel("time")
    ax.set_ylabel("hops (slip count, both kinks)")
    ax.legend(fontsize=7)
    ax.set_title("creep of a pinned kink pair, f = %g" % sad["f"], fontsize=9)
    ax = axs[1]
    good = [r for r in runs if r["n"] > 0]
    x = np.array([sad["dE"] / r["T"] for r in good])
    ax.errorbar(x, [r["rate"] for r in good], yerr=[r["rate_err"] for r in good], fmt="o",
                label="measured rate per kink")
    for r in runs:
        if r["n"] == 0:
            ax.plot([sad["dE"] / r["T"]], [1.0 / (2 * r["tend"])], "v", color="C3",
                    label="no hop in t = %.0f (upper bound)" % r["tend"])
    xx = np.linspace(min(x.min(), 1.0), x.max() + 1, 50)
    ax.semilogy(xx, A_tst * np.exp(-xx), "k--", label="TST: $A_{TST}\\,e^{-\\Delta E/T}$ (no fit)")
    if fit:
        ax.semilogy(xx, np.exp(fit["lnA"] - fit["E"] * xx / sad["dE"]), "C1-",
                    label="fit: E = %.4f $\\pm$ %.4f ($\\Delta E$ = %.4f)" % (fit["E"], fit["E_err"],
                                                                           sad["dE"]))
    ax.set_xlabel("$\\Delta E / T$ ($\\Delta E$ from the constrained saddle)")
    ax.set_ylabel("hop rate per kink")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "creep.png", dpi=90)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=str(HERE / "out" / "creep"))
    ap.add_argument("--f", type=float, default=0.59)
    ap.add_argument("--g", type=float, default=25.0)
    ap.add_argument("--N", type=int, default=128)
    ap.add_argument("--x", type=float, nargs="+", default=[3.0, 4.0, 5.0, 6.0],
                    help="the temperatures as dE/T")
    ap.add_argument("--xcold", type=float, default=30.0, help="dE/T of the no-hop check")
    ap.add_argument("--nhop", type=int, default=60)
    ap.add_argument("--tmax", type=float, default=8000.0)
    ap.add_argument("--seed", type=int, default=4711)
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    N, n0 = args.N, args.N * 3 // 8
    n1 = args.N - n0
    fm, fp = fkme.discrete_depinning_force(args.g, KC, UC, K)
    sad = saddle(out / "saddle", f=args.f, g=args.g, N=N, n0=n0, n1=n1)
    sad["f"] = args.f
    A_tst = tst_prefactor(args.g, N)
    runs = []
    for i, x in enumerate(args.x):
        T = sad["dE"] / x
        runs.append(creep(out / ("T%d" % i), T, f=args.f, g=args.g, N=N, n0=n0, n1=n1,
                          seed=args.seed + i, tmax=args.tmax, nhop=args.nhop))
    cold = creep(out / "cold", sad["dE"] / args.xcold, f=args.f, g=args.g, N=N, n0=n0, n1=n1,
                 seed=args.seed + 99, tmax=args.tmax, nhop=args.nhop)
    fit = fit_arrhenius(runs)
    lines = ["# thermal creep of a pinned kink pair: N = %d, g = %g, kc = uc = 1, K = %g, f = %g, "
             "band %d blocks, fix langevin eta = 10, dt = 0.05" % (N, args.g, K, args.f, n1 - n0),
             "pinning range of a static kink (discrete chain)   f_- = %.4f < f = %g < f_+ = %.4f"
             % (fm, args.f, fp),
             "saddle (hopping block held at the cusp)           E_static = %.6f, E_saddle = %.6f, "
             "dE = %.5f" % (sad["E_static"], sad["E_saddle"], sad["dE"]),
             "# T        dE/T   hops  back  time     rate/kink          TST rate/kink  ratio"]
    for r in runs + [cold]:
        ktst = A_tst * math.exp(-sad["dE"] / r["T"])
        lines.append("%.6f %6.1f %5d %5d %8.1f  %.3e +- %.1e   %.3e   %s" % (
            r["T"], sad["dE"] / r["T"], r["n"], r["nback"], r["tend"], r["rate"], r["rate_err"],
            ktst, "%.2f" % (r["rate"] / ktst) if r["n"] > 0 else "-"))
    if fit:
        z = (fit["E"] - sad["dE"]) / fit["E_err"]
        lines.append("Arrhenius fit ln k = ln A - E/T                  E = %.5f +- %.5f vs dE = %.5f: "
                     "ratio %.3f, z = %+.2f; chi2 = %.1f for %d dof"
                     % (fit["E"], fit["E_err"], sad["dE"], fit["E"] / sad["dE"], z, fit["chi2"],
                        fit["dof"]))
        lines.append("prefactor                                        A = %.3f +- %.3f (x/ e^{+-}), "
                     "TST A_TST = %.3f" % (math.exp(fit["lnA"]), math.exp(fit["lnA"]) * fit["lnA_err"],
                                           A_tst))
    lines.append("cold check T = dE/%g: %d hops in t = %.0f (TST expects %.1e)"
                 % (args.xcold, cold["n"], cold["tend"],
                    2 * A_tst * math.exp(-args.xcold) * cold["tend"]))
    lines.append("# wall time %.0f s" % (time.time() - t0))
    text = "\n".join(lines)
    print(text)
    (out / "summary_creep.txt").write_text(text + "\n")
    plot(runs + [cold], fit, sad, A_tst, out)
    print("wrote", out / "creep.png")


if __name__ == "__main__":
    main()
