#!/usr/bin/python3
"""Paper Fig. mf.B03: onset of sliding F(X) from relaxed contacts for
kappa = 0.005, 0.01, 0.03, 0.05, 0.07 (EQ, N = 4080, quasi-static driving)
against the mean-field ME with the initial thresholds P_ci (Eq. mf.eq15),
with the paper's c1 = 33.9, c2 = 3.0, kappa_c = 0.074 and with beta0, eps0
fitted per kappa (and c1, c2, kappa_c fitted to those); and the avalanche
regime above kappa_c (abrupt drop of F, system-size avalanches).

    /usr/bin/python3 run_onset.py [--kappas ...] [--crossing step] [--out out]

The comparison covers the initial part of F(X) that Eq. mf.eq15 describes:
X from 0.7 to the first minimum after the static peak.
"""
import argparse
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import numpy as np  # noqa: E402

import eqtools  # noqa: E402
from eqtools import meanfield as mf  # noqa: E402

N = 4080


def run_eq(kappa, out, seed=4711, xmax=2.0, dxmax=0.005, nprocs=1, crossing="exact"):
    d = Path(out) / ("onset_k%g_s%d%s" % (kappa, seed, "" if crossing == "exact" else "_" + crossing))
    d.mkdir(parents=True, exist_ok=True)
    eqtools.run_lammps(HERE / "in.eq-interact",
                       {"kappa": kappa, "seed": seed, "Xmax": xmax, "dX": dxmax, "out": d,
                        "crossing": crossing},
                       nprocs=nprocs, cwd=d)
    F = eqtools.load(d / "F.dat")
    av = np.atleast_2d(np.loadtxt(d / "avalanches.dat"))
    return F[:, 1], F[:, 2], av


def first_minimum(X, F, x0=0.7):
    """X of the first minimum of F after its static peak (F sampled densely)."""
    m = X >= x0
    Xs, Fs = X[m], F[m]
    ip = int(np.argmax(Fs[Xs < 1.3])) if np.any(Xs < 1.3) else 0
    grid = np.arange(Xs[ip], Xs[-1], 0.005)
    g = np.interp(grid, Xs, Fs)
    # smooth over 0.02 against the noise, then the first rise
    k = 5
    gs = np.convolve(g, np.ones(k) / k, mode="same")
    rise = np.nonzero(np.diff(gs[k:-k]) > 0)[0]
    return grid[k + rise[0]] if len(rise) else grid[-1]


def onset_rms(X, F, Xm, Fm, xmin):
    m = (X >= 0.7) & (X <= xmin)
    d = F[m] - np.interp(X[m], Xm, Fm)
    return float(np.sqrt(np.mean(d * d))), float(np.max(np.abs(d)))


def fit_beta_eps(kappa, X, F, xmin, work, start):
    from scipy.optimize import minimize

    def cost(p):
        b0, e0 = p
        if b0 < 1.0 or e0 < 0:
            return 1e9
        Xm, Fm, _ = mf.solve_onset(kappa, work, dx=0.005, xmax=xmin + 0.1, beta_eps=(b0, e0))
        return onset_rms(X, F, Xm, Fm, xmin)[0]

    res = minimize(cost, start, method="Nelder-Mead",
                   options={"xatol": 1e-3, "fatol": 1e-6, "maxiter": 120})
    return res.x, res.fun


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kappas", type=float, nargs="+", default=[0.005, 0.01, 0.03, 0.05, 0.07])
    ap.add_argument("--avalanche-kappas", type=float, nargs="+", default=[0.1, 0.2])
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--nofit", action="store_true", help="skip the beta0, eps0 fits")
    ap.add_argument("--crossing", choices=["exact", "step"], default="exact",
                    help="fix eq/contacts crossing (step: a break carries no overshoot, also "
                         "not that of the field jump of an avalanche round)")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    work = out / "me_onset"

    rows = []
    for k in args.kappas + args.avalanche_kappas:
        X, F, av = run_eq(k, out, crossing=args.crossing)
        r = {"kappa": k, "X": X, "F": F, "largest": int(av[:, 1].max()) if av.size else 0,
             "drop": float(np.max(-np.diff(F)))}
        if mf.onset_defined(k) and k in args.kappas:
            xmin = first_minimum(X, F)
            Xm, Fm, _ = mf.solve_onset(k, work, xmax=2.0)
            r.update(xmin=xmin, Xm=Xm, Fm=Fm, rms=onset_rms(X, F, Xm, Fm, xmin))
            if not args.nofit:
                _, b0, e0 = mf.onset_params(k)
                (fb, fe), frms = fit_beta_eps(k, X, F, xmin, work, [b0, e0])
                r.update(fit=(fb, fe), fit_rms=frms)
                Xf, Ff, _ = mf.solve_onset(k, work, xmax=2.0, beta_eps=(fb, fe))
                r.update(Xf=Xf, Ff=Ff)
        rows.append(r)

    lines = ["# Fig. mf.B03: N = %d, onset from relaxed contacts, crossing %s; paper c1, c2, "
             "kappa_c = %s" % (N, args.crossing, mf.PAPER_C),
             "# kappa  X_min  rms(paper c)  max(paper c) | fit: beta0 eps0 rms | largest avalanche, "
             "largest one-step drop of F/(N k_c)"]
    fits = [r for r in rows if "fit" in r]
    for r in rows:
        if "rms" in r:
            fb, fe = r.get("fit", (np.nan, np.nan))
            lines.append("%6.3f  %.3f  %.4f  %.4f | %.3f %.3f %.4f | %d %.4f" %
                         (r["kappa"], r["xmin"], r["rms"][0], r["rms"][1], fb, fe,
                          r.get("fit_rms", np.nan), r["largest"], r["drop"]))
        else:
            lines.append("%6.3f  (above kappa_c: no P_ci)                     | %d %.4f" %
                         (r["kappa"], r["largest"], r["drop"]))
    if len(fits) >= 2:
        # 1/(beta0 - 1) = 1/(c1 kappa) - 1/(c1 kappa_c): linear in 1/kappa
        k = np.array([r["kappa"] for r in fits])
        b0 = np.array([r["fit"][0] for r in fits])
        e0 = np.array([r["fit"][1] for r in fits])
        slope, icpt = np.polyfit(1.0 / k, 1.0 / (b0 - 1.0), 1)
        c1 = 1.0 / slope
        kc = -slope / icpt if icpt < 0 else np.inf
        c2 = float(np.sum(e0 * (b0 - 1)) / np.sum((b0 - 1) ** 2))
        lines.append("# fitted c1 = %.2f  c2 = %.3f  kappa_c = %.4f" % (c1, c2, kc))
    text = "\n".join(lines)
    print(text)
    tag = "" if args.crossing == "exact" else "_" + args.crossing
    (out / ("onset_summary%s.txt" % tag)).write_text(text + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for i, r in enumerate(rows):
        col = "C%d" % i
        ax.plot(r["X"], r["F"], ":", lw=1, color=col, label="EQ $\\kappa$=%g" % r["kappa"])
        if "Fm" in r:
            ax.plot(r["Xm"], r["Fm"], "-", lw=1, color=col)
        if "Ff" in r:
            ax.plot(r["Xf"], r["Ff"], "--", lw=0.8, color=col)
    ax.set_xlim(0.5, 1.6)
    ax.set_xlabel("X / x_c")
    ax.set_ylabel("F / (N k_c x_c)")
    ax.set_title("EQ (dotted), ME paper c (solid), ME fitted $\\beta_0,\\epsilon_0$ (dashed)",
                 fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / ("onset%s.png" % tag), dpi=110)
    print("wrote", out / ("onset%s.png" % tag))


if __name__ == "__main__":
    main()
