#!/usr/bin/python3
"""Stick-slip versus smooth sliding of a spring-driven EQ slider (paper
Sec. II C): the master equation (ME) gives K* = max(-dF/dX); a slider
pulled through a spring K < K* becomes unstable where -F'(X) = K and slips,
for K > K* it follows the quasi-static branch K (X_stage - X) = F(X).

Runs eq-me (F(X), K*) and two LAMMPS runs (K = 0.5 K* and K = 2 K*),
and predicts the slips from the ME: the quasi-static construction (onset
where -F'(X) = K) and the slider's equation of motion with the ME force
(the EQ model is rate independent, so F depends on X only).  Prints the
slips found and predicted and writes out/eq-stickslip.png.

Without interactions between contacts the distribution of stretches
dephases after the first slips, so the stick-slip is transient (a few
decaying slips); with interactions it persists (paper Sec. IV).
"""
import argparse
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402
import numpy as np  # noqa: E402

THRESHOLD = ["threshold", "uniform", "0.75", "1.25", "reform", "delta", "0.0"]
WINDOW = 0.02   # stage displacement over which a slip is measured


def predict_first_slip(me, K):
    """Quasi-static ME construction for spring stiffness K (per N k_c):
    onset X_c where -F'(X) first exceeds K, stage position there, and the
    next stable point of K (Xs_c - X) = F(X) (overdamped landing)."""
    X, F = me[:, 0], me[:, 1]
    slope = -np.diff(F) / np.diff(X)
    i = np.argmax(slope > K)
    if slope[i] <= K:
        return None
    Xc, Fc = X[i], F[i]
    Xs = Xc + Fc / K
    rest = K * (Xs - X[i + 1:]) - F[i + 1:]
    j = i + 1 + np.argmax(rest <= 0)
    return {"X": Xc, "stage": Xs, "jump": X[j] - Xc, "F_before": Fc, "F_after": F[j]}


def simulate_me(me, K, v=0.004, gamma=2.0, dt=0.01, Xend=5.0):
    """Slider of mass N m (m = 1) with damping gamma per unit mass, pulled
    through the spring K (per N k_c) by a stage moving at v, against the
    master-equation force F(X) (per N k_c).  The EQ model is rate
    independent, so F depends on X only; when the slider backs up from its
    furthest position X_max the contacts unload elastically, F = F(X_max) -
    (X_max - X) k_c, until it is back at X_max.  Velocity Verlet; returns
    rows (stage, X, V) every 50 steps."""
    Xg, Fg = me[:, 0], me[:, 1]
    X = V = Xmax = t = 0.0

    def force(x):
        if x >= Xmax:
            return np.interp(x, Xg, Fg)
        return np.interp(Xmax, Xg, Fg) - (Xmax - x)
    out = []
    for i in range(int(round(Xend / (v * dt)))):
        a = K * (v * t - X) - force(X) - gamma * V
        V += 0.5 * dt * a
        X += dt * V
        Xmax = max(Xmax, X)
        t += dt
        V += 0.5 * dt * (K * (v * t - X) - force(X) - gamma * V)
        if i % 50 == 0:
            out.append((v * t, X, V))
    return np.array(out)


def slips(d, v, window=WINDOW):
    """Slip events: stretches of time with slider velocity > 3 v in which
    the slider advances more than 5 stage windows (quasi-static sliding
    with K > K* advances at most K/(K - K*) = 2 windows per window).
    Returns the events (stage position at the onset, slider position,
    advance) and the largest advance within one stage window."""
    Xs, X, V = d[:, 0], d[:, 1], d[:, 2]
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
                events.append({"stage": Xs[i], "X": X[i], "jump": X[j] - X[i]})
            i = j + 1
        else:
            i += 1
    return events, float(np.max(X[n:] - X[:-n]))


def run(out=None, nx=30, ny=17, seed=2024, ratios=(0.5, 2.0), xend=5.0, plot=True, quiet=False):
    out = Path(out or HERE / "out")
    out.mkdir(parents=True, exist_ok=True)
    s = eqtools.run_eqme(THRESHOLD + ["xmax", 6, "dx", 1e-3, "force", "me_F.dat"], cwd=out)
    me = eqtools.load(out / "me_F.dat")
    kstar = s["kstar"]
    results = {"kstar": kstar, "runs": {}}
    for r in ratios:
        sub = out / f"K{r:g}s{seed}"
        sub.mkdir(exist_ok=True)
        eqtools.run_lammps(HERE / "in.eq-stickslip", {"nx": nx, "ny": ny, "seed": seed,
                                                      "Kratio": r, "out": sub, "Xend": xend,
                                                      "contacts": " ".join(THRESHOLD)}, cwd=sub)
        d = eqtools.load(sub / "slider.dat")[:, 1:]    # Xs X V F_friction F_spring
        ev, dmax = slips(d, 0.004)
        dyn = simulate_me(me, r * kstar, Xend=xend)
        results["runs"][r] = {"data": d, "slips": ev, "max_advance": dmax,
                              "predicted": predict_first_slip(me, r * kstar),
                              "predicted_slips": slips(dyn, 0.004)[0], "me_dynamics": dyn}
    if not quiet:
        N = 2 * nx * ny
        print(f"FRICTION-EQ stick-slip: N = {N} contacts, thresholds uniform [0.75, 1.25]; "
              f"ME K*/K_s = {kstar:.4f}")
        for r, res in results["runs"].items():
            p = res["predicted"]
            print(f"  K = {r:g} K*: {len(res['slips'])} slip(s); largest slider advance within a "
                  f"stage advance of {WINDOW}: {res['max_advance']:.3f}")
            if p:
                print(f"    ME, quasi-static: instability at stage {p['stage']:.3f} (X = {p['X']:.3f}), "
                      f"overdamped jump {p['jump']:.3f}")
            else:
                print("    ME predicts no instability (smooth sliding)")
            for e in res["predicted_slips"][:4]:
                print(f"    ME + slider inertia: slip at stage {e['stage']:.3f} (X = {e['X']:.3f}), "
                      f"advance {e['jump']:.3f}")
            for e in res["slips"][:4]:
                print(f"    slip at stage {e['stage']:.3f} (X = {e['X']:.3f}): slider advanced "
                      f"{e['jump']:.3f}")
    if plot:
        results["plot"] = str(make_plot(out, me, results))
        if not quiet:
            print(f"  plot: {results['plot']}")
    return results


def make_plot(out, me, results):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = results["runs"]
    fig, axes = plt.subplots(2, len(runs), figsize=(5.5 * len(runs), 6), sharex=True)
    for j, (r, res) in enumerate(runs.items()):
        d = res["data"]
        ax = axes[0, j]
        ax.plot(d[:, 0], d[:, 4], "b-", lw=0.8, label="spring force K(X_stage - X)")
        ax.plot(d[:, 1], d[:, 3], "r-", lw=0.5, alpha=0.6, label="friction F(X) (vs X)")
        ax.plot(me[:, 0], me[:, 1], "k--", lw=0.8, label="ME F(X)")
        dyn = res["me_dynamics"]
        ax.plot(dyn[:, 0], r * results["kstar"] * (dyn[:, 0] - dyn[:, 1]), "g:", lw=1.0,
                label="spring force, ME + inertia")
        ax.set_title(f"K = {r:g} K*  ({'stick-slip' if res['slips'] else 'smooth sliding'})",
                     fontsize=10)
        ax.set_ylabel(r"force / $N k_c$")
        ax.legend(fontsize=7)
        axes[1, j].plot(d[:, 0], d[:, 2] / 0.004, "b-", lw=0.5)
        axes[1, j].set_ylabel(r"slider velocity / $v$")
        axes[1, j].set_xlabel("stage (or slider) displacement")
    path = out / "eq-stickslip.png"
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return path


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--out", default=None)
    ap.add_argument("--seed", type=int, default=2024)
    a = ap.parse_args()
    run(out=a.out, seed=a.seed)
