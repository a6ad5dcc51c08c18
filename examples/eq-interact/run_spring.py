#!/usr/bin/python3
"""A slip induced by the interaction between contacts (paper Sec. IV,
"Stick-slip versus smooth sliding"): a slider on realistic thresholds
(x_s = 1) pulled through a spring K = 2 K* (K*/K_s = 0.17425, the
non-interacting master equation) slides smoothly without interaction,
because K > K*; the interaction raises the critical stiffness to
K*_eff(kappa) (run_kstar.py: K*_eff/K* = 2.3 at kappa = 0.05, 3.1 at 0.1,
4.5 at 0.2), and once K*_eff > K the slider slips once, at the onset peak
(where -dF/dX exceeds K); afterwards it slides on the kinetic plateau.

Runs in.eq-interact-spring for each kappa and measures, after the spring
has loaded the interface to its static peak (stage displacement > LOAD):

* slips: stretches of time with slider velocity > 3 v in which the slider
  advances more than 5 stage windows (0.02 each).  Quasi-static sliding
  with K > K*_eff advances at most K/(K - K*_eff) windows per window;
* the largest slider advance within one stage window (the quasi-static
  bound for K = 2 K* is 2 windows);
* the velocity spread sd(V)/v and the largest drop of the spring force
  within one slip, per N k_c.

    /usr/bin/python3 run_spring.py [--kappas 0 0.05 0.2] [--Kratio 2] [--out out]

Prints a table and writes out/spring.png.

Measured (N = 4080, seed 2024, K = 2 K*): kappa = 0 and 0.02 (K*_eff =
1.5 K* < K) slide smoothly; kappa = 0.05, 0.1, 0.2 slip once at the static
peak (spring-force drop 0.05 N k_c, velocity peak 4-6 v) and then slide
with larger velocity fluctuations (sd(V)/v 0.54-0.59 against 0.37), but
without periodic stick-slip at this K and N: K*_eff is the stiffness of
the onset (relaxed start), not of the steady state.
"""
import argparse
import math
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import numpy as np  # noqa: E402

import eqtools  # noqa: E402

CONTACTS = "threshold realistic 1.0 reform delta 0.0"
XC = 0.75 * math.sqrt(math.pi)     # mean threshold of realistic x_s = 1
V_STAGE = 0.004
WINDOW = 0.02      # stage displacement over which an advance is measured
LOAD = 3.0         # analysis starts at this stage displacement (near the peak)
KAPPAS = (0.0, 0.02, 0.05, 0.1, 0.2)


def run_one(kappa, out, Kratio=2.0, seed=2024, xend=6.0, nx=60, ny=34, gamma=2.0, dt=0.1,
            nprocs=1):
    d = Path(out) / ("spring_k%g_K%g_s%d_dt%g" % (kappa, Kratio, seed, dt))
    d.mkdir(parents=True, exist_ok=True)
    eqtools.run_lammps(HERE / "in.eq-interact-spring",
                       {"kappa": kappa, "xc": XC, "Kratio": Kratio, "seed": seed, "Xend": xend,
                        "nx": nx, "ny": ny, "gamma": gamma, "dt": dt, "v": V_STAGE,
                        "contacts": CONTACTS,
                        "out": d}, nprocs=nprocs, cwd=d)
    return eqtools.load(d / "slider.dat")[:, 1:]      # Xs X V F_friction F_spring


def slips(d, v=V_STAGE, window=WINDOW, load=LOAD):
    """Slip events after the stage passed `load`: (stage at onset, slider
    position, advance, spring-force drop); largest advance in one stage
    window; velocity spread sd(V)/v; largest spring-force drop in a slip."""
    d = d[d[:, 0] >= load]
    Xs, X, V, Fk = d[:, 0], d[:, 1], d[:, 2], d[:, 4]
    n = max(1, int(round(window / (Xs[1] - Xs[0]))))
    fast = V > 3 * v
    events = []
    i = 0
    while i < len(V):
        if fast[i]:
            j = i
            while j + 1 < len(V) and fast[j + 1]:
                j += 1
            if X[j] - X[i] > 5 * window:
                events.append({"stage": float(Xs[i]), "X": float(X[i]),
                               "jump": float(X[j] - X[i]),
                               "drop": float(Fk[max(i - 1, 0)]
                                             - Fk[j:min(j + 2 * n, len(Fk))].min())})
            i = j + 1
        else:
            i += 1
    adv = float(np.max(X[n:] - X[:-n])) / window
    return {"events": events, "max_advance": adv, "v_spread": float(V.std() / v),
            "v_max": float(V.max() / v),
            "max_drop": max([e["drop"] for e in events], default=0.0)}


def run(out=None, kappas=KAPPAS, Kratio=2.0, seed=2024, xend=6.0, nx=60, ny=34, gamma=2.0,
        plot=True, quiet=False):
    out = Path(out or HERE / "out")
    out.mkdir(parents=True, exist_ok=True)
    res = {"Kratio": Kratio, "N": 2 * nx * ny, "rows": []}
    for k in kappas:
        d = run_one(k, out, Kratio, seed, xend, nx, ny, gamma)
        s = slips(d)
        s.update({"kappa": k, "data": d, "stick_slip": len(s["events"]) > 1,
                  "regime": regime(s["events"])})
        res["rows"].append(s)
    text = summary(res)
    (out / "spring_summary.txt").write_text(text + "\n")
    if not quiet:
        print(text)
    if plot:
        res["plot"] = str(make_plot(out, res))
        if not quiet:
            print("  plot:", res["plot"])
    return res


def regime(events):
    """smooth (no slip), one slip (the onset peak), or stick-slip (repeated
    slips)."""
    if not events:
        return "smooth"
    return "one slip" if len(events) == 1 else "stick-slip (%d slips)" % len(events)


def summary(res):
    lines = ["# FRICTION-EQ spring-driven slider on interacting contacts: realistic thresholds "
             "x_s = 1, N = %d, K = %g K* (K*/K_s = 0.17425), v = %g, stage > %g analysed"
             % (res["N"], res["Kratio"], V_STAGE, LOAD),
             "# kappa  slips  largest advance/window  sd(V)/v  max V/v  largest force drop/(N k_c)"
             "  regime"]
    for r in res["rows"]:
        lines.append("%6.3f  %5d  %12.2f            %7.2f  %7.1f  %10.4f              %s"
                     % (r["kappa"], len(r["events"]), r["max_advance"], r["v_spread"], r["v_max"],
                        r["max_drop"], r["regime"]))
    return "\n".join(lines)


def make_plot(out, res):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = res["rows"]
    fig, axes = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for i, r in enumerate(rows):
        d = r["data"]
        lab = "$\\kappa$ = %g (%s)" % (r["kappa"], r["regime"])
        axes[0].plot(d[:, 0], d[:, 4], "-", lw=0.7, color="C%d" % i, label=lab)
        axes[1].plot(d[:, 0], d[:, 2] / V_STAGE, "-", lw=0.5, color="C%d" % i)
    axes[0].set_ylabel("spring force $K(X_{stage} - X)/(N k_c)$")
    axes[0].legend(fontsize=7)
    axes[0].set_title("slider on realistic thresholds, K = %g K*, N = %d"
                      % (res["Kratio"], res["N"]), fontsize=9)
    axes[1].set_ylabel("slider velocity / v")
    axes[1].set_xlabel("stage displacement")
    axes[1].axhline(1.0, color="k", lw=0.5, ls=":")
    fig.tight_layout()
    path = Path(out) / "spring.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kappas", type=float, nargs="+", default=list(KAPPAS))
    ap.add_argument("--Kratio", type=float, default=2.0)
    ap.add_argument("--seed", type=int, default=2024)
    ap.add_argument("--xend", type=float, default=6.0)
    ap.add_argument("--out", default=str(HERE / "out"))
    a = ap.parse_args()
    run(out=a.out, kappas=a.kappas, Kratio=a.Kratio, seed=a.seed, xend=a.xend)
