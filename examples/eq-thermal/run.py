#!/usr/bin/python3
"""FRICTION-EQ: temperature, velocity and aging of EQ contacts (fix
eq/contacts keywords thermal, aging, delay, rest) against the master
equation with the same terms (eq-me: renewal quadrature and transient).

N = 10^4 independent contacts on a rigid slider, thresholds uniform on
[0.75, 1.25], k_c = 1, omega = 1, eps_a = 1 (units lj, k_B = 1).  Prints a
summary and writes out/eq-thermal.png:
  left:  kinetic friction F_k(v) over six decades of the slider velocity,
         thermal (theta = 0.01, 0.02, 0.05), threshold aging (beta = 0.05,
         tau_a = 1) and both with an exponential delay (tau = 10): EQ
         runs (per-contact time averages over X in [3, 6], +-2 standard
         errors) against eq-me's steady F_k (lines) and its F(X) averaged over
         the same window (crosses: at small v aging is not steady by X = 3);
  right: F(X) after a rest t_w = 0, 1e2, 1e4, 1e6 (T = 0, aging, v = 1e-2):
         the static peak grows with ln t_w.

  ./run.py            (about 2 minutes on one core)
  ./run.py --np 2     two MPI ranks
"""
import argparse
import math
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402
import numpy as np  # noqa: E402

THRESHOLD = ["threshold", "uniform", "0.75", "1.25"]
CURVES = {    # label: fix eq/contacts / eq-me keywords
    r"$\theta = 0.01$": ["thermal", "0.01", "1.0", "1.0"],
    r"$\theta = 0.02$": ["thermal", "0.02", "1.0", "1.0"],
    r"$\theta = 0.05$": ["thermal", "0.05", "1.0", "1.0"],
    r"aging $\beta = 0.05$": ["aging", "log", "0.05", "1.0"],
    r"$\theta = 0.02$ + aging + delay 10": ["thermal", "0.02", "1.0", "1.0", "aging", "log",
                                            "0.05", "1.0", "delay", "exp", "10.0"],
}
VELOCITIES = [1e-7, 1e-5, 1e-3, 1e-1]
RESTS = [0.0, 1e2, 1e4, 1e6]
AGING = ["aging", "log", "0.05", "1.0"]
N_SIDE, DX, XHALF = 100, 2e-3, 3.0


def eq_kinetic(out, kw, v, nprocs):
    """F_k per contact and its standard error from one EQ run."""
    out.mkdir(parents=True, exist_ok=True)
    log = eqtools.run_lammps(HERE / "in.eq-thermal",
                             {"n": N_SIDE, "v": v, "dX": DX, "Xhalf": XHALF, "out": out,
                              "contacts": " ".join(THRESHOLD + kw)}, nprocs=nprocs, cwd=out)
    rows = (out / "avg.dump").read_text().split("ITEM: ATOMS")[-1].strip().splitlines()[1:]
    m = np.array([float(r.split()[1]) for r in rows])
    loop = sum(float(l.split()[3]) for l in log.splitlines() if l.startswith("Loop time of"))
    return m.mean(), m.std(ddof=1) / math.sqrt(len(m)), loop


def me_window(out, kw, v):
    """eq-me's F(X) from fresh contacts, averaged over the runs' window"""
    eqtools.run_eqme(THRESHOLD + kw + ["velocity", v, "xmax", 2 * XHALF, "dx", DX, "force",
                                       "me_F.dat"], cwd=out)
    me = eqtools.load(out / "me_F.dat")
    w = (me[:, 0] > XHALF + 0.5 * DX) & (me[:, 0] < 2 * XHALF + 0.5 * DX)
    return me[w, 1].mean()


def run(nprocs=1, out=None, plot=True, quiet=False):
    out = Path(out or HERE / "out")
    out.mkdir(parents=True, exist_ok=True)
    N = N_SIDE * N_SIDE
    res = {"curves": {}, "rests": {}}
    t0 = time.time()
    for label, kw in CURVES.items():
        tag = "_".join(kw[:2]) + (f"_{len(kw)}" if len(kw) > 4 else "")
        me = eqtools.run_eqme(THRESHOLD + kw + ["velocity", VELOCITIES[0], "kinetic",
                                                 f"Fk_{tag}.dat", 1e-8, 1.0, 33], cwd=out)
        curve = eqtools.load(out / f"Fk_{tag}.dat")    # v F_k slope n_a Gamma_s
        pts = [eq_kinetic(out / f"{tag}_v{v:g}", kw, v, nprocs) for v in VELOCITIES]
        Fme = np.interp(np.log(VELOCITIES), np.log(curve[:, 0]), curve[:, 1])
        # what the runs average: F(X) of eq-me over the same window (the
        # run starts from fresh contacts; at small v aging is still slow there)
        Fwin = np.array([me_window(out / f"{tag}_v{v:g}", kw, v) for v in VELOCITIES])
        F, se, loops = (np.array(c) for c in zip(*pts))
        res["curves"][label] = dict(me=curve, F=F, se=se, Fme=Fme, Fwin=Fwin,
                                    z=(F - Fwin) / se, loop=loops.sum())
    for tw in RESTS:
        d = out / f"rest{tw:g}"
        d.mkdir(parents=True, exist_ok=True)
        eqtools.run_lammps(HERE / "in.eq-thermal",
                           {"n": N_SIDE, "v": 1e-2, "dX": DX, "Xhalf": 1.0, "out": d,
                            "contacts": " ".join(THRESHOLD + AGING + ["rest", str(tw)])},
                           nprocs=nprocs, cwd=d)
        eq = eqtools.load(d / "F.dat")
        me = eqtools.run_eqme(THRESHOLD + AGING + ["rest", tw, "velocity", 1e-2, "xmax", 2.0,
                                                   "dx", DX, "force", "me_F.dat"], cwd=d)
        mef = eqtools.load(d / "me_F.dat")
        res["rests"][tw] = dict(X=eq[:, 1], F=eq[:, 2], me=mef, peak=eq[:, 2].max(),
                                peak_me=me["static_peak"])
    res["seconds"] = time.time() - t0
    # cost per contact-step at T > 0 against T = 0, same scene
    res["cost"] = cost(out, nprocs)
    if not quiet:
        summary(res, N, nprocs)
    if plot:
        res["plot"] = str(make_plot(out, res, N))
        if not quiet:
            print(f"  plot: {Path(res['plot']).resolve().relative_to(Path.cwd().resolve()) if Path(res['plot']).resolve().is_relative_to(Path.cwd().resolve()) else res['plot']}")
    return res


def cost(out, nprocs):
    per = {}
    for name, kw in (("T = 0", []), ("theta = 0.02", CURVES[r"$\theta = 0.02$"]),
                     ("theta = 0.02 + aging + delay", CURVES[r"$\theta = 0.02$ + aging + delay 10"])):
        _, _, loop = eq_kinetic(out / f"cost_{len(kw)}", kw, 1e-4, nprocs)
        per[name] = 1e9 * loop / (N_SIDE * N_SIDE * 2 * round(XHALF / DX))
    return per


def summary(res, N, nprocs):
    print(f"FRICTION-EQ eq-thermal: N = {N} contacts, thresholds uniform [0.75, 1.25], "
          f"dX = {DX:g}, {nprocs} MPI rank(s)")
    print("  kinetic friction F_k/(N k_c): EQ (per-contact time averages on X in "
          f"[{XHALF:g}, {2 * XHALF:g}]) / eq-me over the same window; z: their difference in "
          "standard errors; eq-me steady F_k in the plot")
    vs = "  ".join(f"v = {v:<8g}" for v in VELOCITIES)
    print(f"    {'':34s} {vs}   max|z|  slope EQ / ME")
    for label, c in res["curves"].items():
        vals = "  ".join(f"{F:.4f}/{Fm:.4f}" for F, Fm in zip(c["F"], c["Fme"]))
        sl_eq = np.polyfit(np.log(VELOCITIES), c["F"], 1)[0]
        sl_me = np.polyfit(np.log(VELOCITIES), c["Fme"], 1)[0]
        name = label.replace("$", "").replace("\\theta", "theta").replace("\\beta", "beta")
        print(f"    {name:34s} {vals}   {np.max(np.abs(c['z'])):.2f}   {sl_eq:+.4f} / {sl_me:+.4f}")
    print("  static friction after a rest t_w (T = 0, log aging beta = 0.05, v = 1e-2): EQ / eq-me")
    print("    " + "   ".join(f"t_w = {tw:g}: {r['peak']:.4f} / {r['peak_me']:.4f}"
                              for tw, r in res["rests"].items()))
    c = res["cost"]
    base = c["T = 0"]
    print("  cost (LAMMPS loop, v = 1e-4): " + ", ".join(
        f"{k} {v:.1f} ns per contact-step ({v / base:.2f}x)" for k, v in c.items()))
    print(f"  total {res['seconds']:.0f} s")


def make_plot(out, res, N):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, ar) = plt.subplots(1, 2, figsize=(11, 4.4), gridspec_kw={"width_ratios": [1.4, 1]})
    for k, (label, c) in enumerate(res["curves"].items()):
        col = f"C{k}"
        ax.semilogx(c["me"][:, 0], c["me"][:, 1], "-", color=col, lw=1.1, label=label)
        ax.errorbar(VELOCITIES, c["F"], yerr=2 * c["se"], fmt="o", color=col, ms=4)
        ax.plot(VELOCITIES, c["Fwin"], "x", color="k", ms=5, mew=0.8,
                label="eq-me over the runs' window" if k == 0 else None)
    ax.set_xlabel(r"slider velocity $v$ ($x_c\,\omega$)")
    ax.set_ylabel(r"$F_k/(N k_c)$")
    ax.set_title(f"lines: eq-me, steady; points: EQ, N = {N}, X in [{XHALF:g}, {2 * XHALF:g}]",
                 fontsize=9)
    ax.legend(fontsize=7, loc="lower left")
    for k, (tw, r) in enumerate(res["rests"].items()):
        col = f"C{k}"
        ar.plot(r["me"][:, 0], r["me"][:, 1], "-", color=col, lw=1.1, label=f"$t_w$ = {tw:g}")
        ar.plot(r["X"][::10], r["F"][::10], ".", color=col, ms=2)
    ar.set_xlabel(r"slider displacement $X$")
    ar.set_ylabel(r"$F(X)/(N k_c)$")
    ar.set_title(r"after a rest $t_w$: $T = 0$, aging, $v = 10^{-2}$", fontsize=9)
    ar.legend(fontsize=7)
    fig.suptitle("EQ contacts with temperature, aging and delays", fontsize=10)
    path = out / "eq-thermal.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--np", type=int, default=1, help="MPI ranks")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    res = run(nprocs=a.np, out=a.out)
    ok = all(np.max(np.abs(c["z"])) < 5.0 for c in res["curves"].values())
    if not ok:
        print("  WARNING: EQ and eq-me disagree beyond their statistical error")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
