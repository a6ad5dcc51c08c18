#!/usr/bin/python3
"""Velocity-dependent stick-slip at T > 0: a spring-driven EQ slider
(in.eq-thermal-stickslip) against the master equation (ME).

N = 1020 contacts, thresholds uniform [0.75, 1.25] re-forming unstretched,
theta = k_B T/eps_a, omega = 1 (units lj); spring K = Kn N k_c, stage
velocity v; the slider's inertia and damping scale with v so that the
stage moves v sqrt(m/k_c) = 1e-3 per slider time (a slip is fast against
the loading) and every run takes the same number of steps.

Two ME predictions:
  quasi-static  F(X) from rest at constant v (eq-me ... velocity v): a
          slider that follows the stage at v loses its stable branch
          where -F'(X) = K, so that it slips for K < K*(v) = max(-F'(X));
          the same construction gives its trajectory (quasi_static()).
  in time the ME of the contacts in time coupled to the slider's equation
          of motion (tools/eqtools/slider.py, written apart from the C++):
          during a slip the contacts are loaded faster, break less by
          thermal activation, and the friction rises (the direct effect of
          rate-and-state friction), which K*(v) leaves out.
A run "slips" if the slider advances by more than SLIP = 0.1 x_c beyond
the stage within one stretch of time in which it moves faster than 3 v
(averaged over 0.01 x_c of stage travel).

Prints, per theta and v: K*(v), the largest jumps of the EQ runs, the ME
in time and the quasi-static ME on a grid of K and the K below which each
slips; writes
out/eq-thermal-stickslip.png (the K-v phase diagram and trajectories).

  ./stickslip.py               (about 16 minutes on one core)
  ./stickslip.py --quick       fewer points (3 minutes)
  ./stickslip.py --reuse       re-plot from out/stickslip/stickslip.json
  ./stickslip.py --meso        also one fix eq/meso block at T > 0 at every
                               point (in.eq-thermal-meso-stickslip), against
                               the ME in time on the same grid
"""
import argparse
import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402
from eqtools import slider  # noqa: E402
import numpy as np  # noqa: E402

LO, HI = 0.75, 1.25
SLOW, DX = 1e-3, 2e-4      # v sqrt(m/k_c); stage travel per step
ME_GRID = dict(n_labels=16, dA=4e-3)   # ME in time: threshold panels, anchor cells
SLIP = 0.1                 # a jump beyond the stage larger than this is a slip
WINDOW = 0.01              # stage travel over which the slider velocity is averaged
NX, NY, SEED = 30, 17, 2024


def contacts(theta):
    return f"threshold uniform {LO} {HI} reform delta 0.0 thermal {theta} 1.0 1.0"


def xend(Kn):
    """stage travel that takes the slider past its first peak (F_s <= 0.75)"""
    return 1.5 + 0.8 / Kn


def eq_run(out, theta, v, Kn, seed=SEED, nx=NX, ny=NY, nprocs=1):
    """One LAMMPS run; returns dict(stage, X, V_over_v, F) every 10 steps."""
    out.mkdir(parents=True, exist_ok=True)
    eqtools.run_lammps(HERE / "in.eq-thermal-stickslip",
                       {"nx": nx, "ny": ny, "seed": seed, "contacts": contacts(theta),
                        "Kn": Kn, "v": v, "slow": SLOW, "dX": DX, "Xend": xend(Kn),
                        "out": out}, nprocs=nprocs, cwd=out)
    d = eqtools.load(out / "slider.dat")    # step Xs X V/v F
    return {"stage": d[:, 1], "X": d[:, 2], "V_over_v": d[:, 3], "F": d[:, 4]}


def meso_run(out, theta, v, Kn):
    """The same slider as one fix eq/meso block at T > 0 (its contacts are
    their master equation, on the grid of the ME in time):
    in.eq-thermal-meso-stickslip; returns dict(stage, X, V_over_v, F)."""
    out.mkdir(parents=True, exist_ok=True)
    eqtools.run_lammps(HERE / "in.eq-thermal-meso-stickslip",
                       {"T": theta, "Kn": Kn, "v": v, "slow": SLOW, "dX": DX, "Xend": xend(Kn),
                        "grid": ME_GRID["dA"], "labels": ME_GRID["n_labels"], "out": out}, cwd=out)
    d = eqtools.load(out / "meso-slider.dat")    # step Xs X V/v F
    return {"stage": d[:, 1], "X": d[:, 2], "V_over_v": d[:, 3], "F": d[:, 4]}


def me_run(theta, v, Kn):
    return slider.slider_me(Kn, v, theta, lo=LO, hi=HI, slow=SLOW, dX=DX, Xend=xend(Kn), **ME_GRID)


def fast_stretches(res, w=WINDOW):
    """Stretches of stage travel in which the slider, its velocity averaged
    over windows of stage travel w, moves faster than 3 v: (stage position
    at the start, advance of the slider beyond the stage) for each.  EQ
    runs and the ME in time are sampled alike (every 10 steps), and the
    average over a window keeps the EQ's noise (a break moves the slider by
    ~1/N) from cutting a slip into pieces."""
    grid = np.arange(0.0, res["stage"][-1], w)
    X = np.interp(grid, res["stage"], res["X"])
    fast = np.diff(X) > 3 * w
    out, i = [], 0
    while i < len(fast):
        j = i
        while j < len(fast) and fast[j]:
            j += 1
        if j > i:
            out.append((grid[i], X[j] - X[i] - (grid[j] - grid[i])))
        i = j + 1
    return out


def largest_jump(res, w=WINDOW):
    """the largest advance beyond the stage of fast_stretches (0 if none)"""
    return max((j for _, j in fast_stretches(res, w)), default=0.0)


def me_constant_velocity(theta, v, cwd):
    """eq-me at constant v: K*(v) and F(X) from rest (columns X, F, ...)"""
    cwd.mkdir(parents=True, exist_ok=True)
    s = eqtools.run_eqme(contacts(theta).split() + ["velocity", v, "xmax", 6.0, "dx", 0.002,
                                                    "force", "me_F.dat"], cwd=cwd)
    return s["kstar"], eqtools.load(cwd / "me_F.dat")


def kstar(theta, v, cwd):
    return me_constant_velocity(theta, v, cwd)[0]


def quasi_static(me, K, stage_end, w=WINDOW):
    """The slider of the quasi-static ME at constant v: on the stable branch
    K (stage - X) = F(X), F(X) of the ME at v (me: columns X, F); where the
    branch folds back (-F' > K) it jumps forward to the next stable point
    (overdamped landing): X(stage) = the largest X whose running maximum of
    X + F(X)/K does not exceed the stage.  Sampled at stage steps w/10."""
    X, F = me[:, 0], me[:, 1]
    reach = np.maximum.accumulate(X + F / K)
    stage = np.arange(0.0, stage_end, 0.1 * w)
    i = np.clip(np.searchsorted(reach, stage, side="right") - 1, 0, len(X) - 1)
    return {"stage": stage, "X": X[i]}


def boundary(kgrid, jumps):
    """K where the largest jump crosses SLIP (linear interpolation between
    the grid points around the last crossing; the jump falls with K); the
    grid's ends if it slips everywhere / nowhere (None)"""
    k, j = np.asarray(kgrid), np.asarray(jumps)
    if j[0] <= SLIP:
        return None
    above = np.nonzero(j > SLIP)[0][-1]
    if above == len(k) - 1:
        return k[-1]
    i = above
    return k[i] + (j[i] - SLIP) * (k[i + 1] - k[i]) / (j[i] - j[i + 1])


def _k(k):
    return "none" if k is None else f"{k:.3f}"


QS_GRID = np.arange(0.05, 3.0, 0.01)    # K of the quasi-static boundary (cheap)


def meso_point(out, th, v, Kn):
    """the fix eq/meso block against the ME in time at one point: its
    largest jump and the largest distance between the two trajectories"""
    m, me = meso_run(out, th, v, Kn), me_run(th, v, Kn)
    n = min(len(m["X"]), len(me["X"]))
    return {"meso": largest_jump(m), "meso_dev": float(np.max(np.abs(m["X"][:n] - me["X"][:n])))}


def scan(th, v, kgrid, out, cache, nprocs=1, meso=False):
    """One (theta, v): K*(v) and the largest jumps at each K of the EQ runs
    and the ME in time (points already in cache are taken from it), the
    quasi-static ME at v on the fine QS_GRID, and the K below which each
    slips; with meso also those of one fix eq/meso block."""
    tag = f"th{th:g}_v{v:g}"
    ks, Fme = me_constant_velocity(th, v, out / tag)
    r = {"kstar": ks, "eq": [], "me": [], "meso": [], "meso_dev": []}
    for Kn in kgrid:
        key = f"{th:g} {v:g} {Kn:g}"
        if key not in cache:
            cache[key] = {"eq": largest_jump(eq_run(out / tag / f"K{Kn:g}", th, v, Kn,
                                                    nprocs=nprocs)),
                          "me": largest_jump(me_run(th, v, Kn))}
        if meso and "meso" not in cache[key]:
            cache[key].update(meso_point(out / tag / f"meso{Kn:g}", th, v, Kn))
        r["eq"].append(cache[key]["eq"])
        r["me"].append(cache[key]["me"])
        if meso:
            r["meso"].append(cache[key]["meso"])
            r["meso_dev"].append(cache[key]["meso_dev"])
    r["qs"] = [largest_jump(quasi_static(Fme, Kn, xend(Kn))) for Kn in kgrid]
    r["eq_boundary"], r["me_boundary"] = boundary(kgrid, r["eq"]), boundary(kgrid, r["me"])
    r["qs_boundary"] = boundary(QS_GRID, [largest_jump(quasi_static(Fme, K, xend(K)))
                                          for K in QS_GRID])
    print(f"  theta {th:<5g} v {v:<7g} K*(v) {ks:.3f}; slips below K = "
          f"{_k(r['eq_boundary'])} (EQ), {_k(r['me_boundary'])} (ME in time), "
          f"{_k(r['qs_boundary'])} (quasi-static ME at v); largest jump EQ/ME in time/"
          "quasi-static at K = " + "  ".join(f"{K:g}: {j:.3f}/{m:.3f}/{q:.3f}" for K, j, m, q
                                            in zip(kgrid, r["eq"], r["me"], r["qs"])),
          flush=True)
    if meso:
        print(f"    fix eq/meso block: slips below K = {_k(boundary(kgrid, r['meso']))}; largest "
              f"jump/largest distance to the ME in time at K = "
              + "  ".join(f"{K:g}: {j:.4f}/{d:.1e}" for K, j, d in zip(kgrid, r["meso"], r["meso_dev"])),
              flush=True)
    return r


def run(thetas, velocities, kgrid, out, nprocs=1, plot=True, reuse=False, meso=False):
    """All (theta, v).  The largest jumps of each point are kept in
    out/stickslip.json and, with reuse, read back from it instead of being
    run again."""
    out.mkdir(parents=True, exist_ok=True)
    path = out / "stickslip.json"
    cache = json.loads(path.read_text()) if reuse and path.exists() else {}
    t0 = time.time()
    res = {}
    for th in thetas:
        for v in velocities:
            res[(th, v)] = scan(th, v, kgrid, out, cache, nprocs, meso)
            path.write_text(json.dumps(cache, indent=1))
    print(f"  total {time.time() - t0:.0f} s")
    if plot:
        print(f"  plot: {make_plot(out, res, thetas, velocities, kgrid)}")
    return res


def agreement(res, kgrid):
    """EQ runs whose slip/no-slip differs from the ME in time, away from
    its boundary by more than 10 %"""
    bad = []
    for (th, v), r in res.items():
        kb = r["me_boundary"] or 0.0
        for K, j in zip(kgrid, r["eq"]):
            if abs(K - kb) > 0.1 * max(kb, K) and (j > SLIP) != (K < kb):
                bad.append((th, v, K, j))
    return bad


def make_plot(out, res, thetas, velocities, kgrid):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(thetas) + 1, figsize=(4.6 * (len(thetas) + 1), 4.6),
                             layout="constrained")
    for ax, th in zip(axes, thetas):
        vv = np.array(velocities)
        def line(key):
            return np.array([res[(th, v)][key] or np.nan for v in velocities])
        ax.semilogx(vv, line("kstar"), "k--", lw=1, label=r"$K^*(v)$ (ME at constant $v$)")
        ax.semilogx(vv, line("qs_boundary"), "k-.", lw=1, label="slips below: quasi-static ME")
        ax.semilogx(vv, line("me_boundary"), "C3-", label="slips below: ME in time")
        ax.semilogx(vv, line("eq_boundary"), "C0:", label="slips below: EQ runs")
        vk = [(v, K, j) for v in velocities for K, j in zip(kgrid, res[(th, v)]["eq"])]
        v_, K_, j_ = (np.array(c) for c in zip(*vk))
        sc = ax.scatter(v_, K_, c=j_, cmap="viridis", vmin=0.0, vmax=0.7, s=36,
                        edgecolors=np.where(j_ > SLIP, "k", "none"))
        ax.plot([], [], "o", mfc="none", mec="k", label=f"EQ run, largest jump > {SLIP:g} "
                "(colour: the jump)")
        ax.set_xlabel(r"stage velocity $v$ ($x_c\omega$)")
        ax.set_ylabel(r"spring $K/(N k_c)$")
        ax.set_title(rf"$\theta$ = {th:g}", fontsize=9)
        if th == thetas[0]:
            fig.legend(loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=3, fontsize=8)
    fig.colorbar(sc, ax=axes[:-1], label=r"EQ: largest jump beyond the stage ($x_c$)",
                 shrink=0.8)
    ax = axes[-1]
    th, v = thetas[-1], velocities[len(velocities) // 2]
    for k, Kn in enumerate((0.3, 0.9)):
        d = eq_run(out / "traj" / f"K{Kn:g}", th, v, Kn)
        m = me_run(th, v, Kn)
        ax.plot(d["stage"][::5], d["X"][::5], "o", color=f"C{k}", ms=2.5, mew=0,
                label=f"K = {Kn:g} N k_c")
        ax.plot(m["stage"], m["X"], "-", color="k", lw=0.8)
    ax.set_xlabel("stage position $vt$")
    ax.set_ylabel("slider position $X$")
    ax.set_title(rf"$\theta$ = {th:g}, v = {v:g}: EQ (dots), ME in time (black)", fontsize=9)
    ax.legend(fontsize=7)
    fig.suptitle("Stick-slip of a spring-driven slider at T > 0", fontsize=10)
    path = out / "eq-thermal-stickslip.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--np", type=int, default=1, help="MPI ranks")
    ap.add_argument("--out", default=str(HERE / "out" / "stickslip"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--reuse", action="store_true",
                    help="take the points already in OUT/stickslip.json")
    ap.add_argument("--meso", action="store_true",
                    help="also one fix eq/meso block (in.eq-thermal-meso-stickslip) at every point")
    a = ap.parse_args()
    if a.quick:
        thetas, vels, kgrid = [0.05], [1e-1, 1e-3, 1e-5], [0.2, 0.5, 0.8, 1.2]
    else:
        thetas, vels = [0.02, 0.05], [1e-1, 1e-2, 1e-3, 1e-4, 1e-5]
        kgrid = [0.15, 0.3, 0.45, 0.6, 0.8, 1.0, 1.25, 1.5, 1.8]
    res = run(thetas, vels, kgrid, Path(a.out), nprocs=a.np, reuse=a.reuse, meso=a.meso)
    bad = agreement(res, kgrid)
    for b in bad:
        print("  WARNING: EQ and the ME in time disagree at theta %g v %g K %g (jump %.3f)" % b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
