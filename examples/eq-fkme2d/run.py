#!/usr/bin/python3
"""2d FK-ME interface beyond the paper (Sec. V, Discussion): rupture fronts
that nucleate at random places, and fronts arrested by quenched disorder of
the lambda_c-block thresholds.

    /usr/bin/python3 run.py [--part fronts|disorder|all] [--out out] ...

The interface: L x L blocks on a periodic square lattice, sliding along x,
nearest-neighbour coupling g (pair eq/elastic), sawtooth substrate k_c, u_c
(fix eq/substrate), driving springs K, overdamped m eta u' = force (fix
brownian); g = 25, k_c = u_c = 1, K = 0.07, m = 1, eta = 100 as the paper's
chain.  A front straight along y is the chain's kink; a slipped patch
expands as a closed front.

Part fronts (random initial state, constant driving force f0): a random
fraction p of the blocks starts one period ahead (already slipped), the
rest unslipped.  Random offsets *within* a well relax away (the linear
dynamics inside the wells obeys a maximum principle), so the random state
that nucleates must put neighbouring blocks in different wells; clusters
of pre-slipped blocks that are dense enough survive and grow as closed
fronts.  Prints the number of nuclei, the time to slip the whole interface
and the growth law of the closed fronts, dR/dt = v_inf - D_fit/R, against
the exact velocity of a straight front (fkme.vk_discrete) and the
curvature (Allen-Cahn) term D = g a^2/(m eta) of the continuum limit.
Defaults f0 = 0.75, p = 0.25, L = 128: 5 nuclei (p = 0.2 gives none, p = 0.3
or f0 = 0.8 slips the interface in one avalanche).  The fit over random,
irregular clusters is biased (it gives v_inf above the straight-front
velocity: the clusters' areas grow also by filling in their concave
parts); the clean reference is a straight front in 2d (band of 48 slipped
columns, L = 128), whose velocity from the column crossing times is
compared with fkme.vk_discrete.
Writes out/fronts_maps.png, out/fronts_growth.png, out/summary_fronts.txt.

Part disorder (quasi-static loading): a slipped band (two straight fronts
along y) in an interface with d_n gaussian (mean 1, sd w ~ 1/sqrt(N_lambda)),
the driving force raised in steps df with full relaxation after each; the
slipped fraction vs f for w = 0 and w > 0 (several disorder seeds), for the
paper's g = 25 and a narrower front (g = 5).  Prints the depinning force of
the fronts f_c (slipped fraction 1) against the discrete PN force f_+ of a
straight front (fkme.discrete_depinning_force), the forces where fronts
advance and are arrested, and the arrested avalanches.  Writes
out/disorder_frac.png, out/disorder_maps.png, out/summary_disorder.txt.
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

INPUT = HERE / "in.eq-fkme2d"
KC, UC, K, M, ETA = 1.0, 1.0, 0.07, 1.0, 100.0


# ------------------------------------------------------------------ helpers
def lammps(out, **var):
    """Run in.eq-fkme2d in folder `out` with the given variables."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    var.setdefault("out", ".")
    return eqtools.run_lammps(INPUT, var, cwd=out, log="log.lammps")


def to_grid(cols, L, name, frame=None):
    """Per-block column `name` of a dump (dict from fkme.read_dump) as an
    [L, L] array indexed [iy, ix] by the blocks' sites (column f_sub[7] =
    site x, y)."""
    sx, sy = cols["f_sub[7]"], cols["y"]
    val = cols[name]
    if frame is not None:
        sx, sy, val = sx[frame], sy[frame], val[frame]
    ix = np.mod(np.rint(sx).astype(int), L)
    iy = np.mod(np.rint(sy).astype(int), L)
    g = np.zeros((L, L))
    g[iy, ix] = val
    return g


def label_periodic(mask):
    """Connected clusters (4-neighbour) of a boolean [L, L] array on the
    torus.  Returns (labels, n) with labels 0 outside the clusters and
    1..n inside."""
    from scipy import ndimage
    lab, n = ndimage.label(mask)
    parent = list(range(n + 1))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in list(zip(lab[0, :], lab[-1, :])) + list(zip(lab[:, 0], lab[:, -1])):
        if a and b:
            ra, rb = find(a), find(b)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([find(i) for i in range(n + 1)])
    uniq = np.unique(roots[1:]) if n else np.zeros(0, int)
    remap = np.zeros(n + 1, int)
    remap[1:] = np.searchsorted(uniq, roots[1:]) + 1
    return remap[lab], len(uniq)


# ============================================================ part fronts
def run_straight(out, L=128, f0=0.8, g=25.0, band=48, dt=0.2, skip=8, gap=30):
    """A straight front in 2d: the band init (two straight fronts along y,
    `band` columns slipped) at constant force f0; the slipped fraction every
    step gives the time t_k at which each front has advanced k columns (both
    advance together), and v = 1/slope of t_k vs k (k > skip, after the
    transient of the sharp initial step).  The fronts run until they are
    `gap` columns apart across the periodic boundary: fronts closer than
    ~4 front widths attract (the kink tails overlap, r^gap with
    r = 0.813 for g = 25) and speed up (+5 % at L = 64 run to 10 columns
    apart).  Returns dict with v, the exact
    discrete-chain velocity vk_discrete and the crossing times."""
    out = Path(out)
    vref = float(fkme.vk_discrete(f0, g, KC, UC, K, M, ETA))
    tmax = (0.5 * (L - band) - 0.5 * gap) / vref
    lammps(out, L=L, g=g, f0=f0, band=band, init="band", mode="run", tmax=round(tmax, 1),
           dt=dt, every=10 ** 9, thermo=1)
    ser = fkme.read_ave_time(out / "series.dat")
    t = ser["TimeStep"] * dt
    cols = (ser["v_frac"] * L - band) / 2.0          # columns advanced per front
    kmax = int(math.floor(cols.max() + 1e-9))
    ks = np.arange(skip + 1, kmax + 1)
    tk = np.array([t[np.argmax(cols >= k - 1e-9)] for k in ks])
    v = math.nan
    if len(ks) >= 3:
        v = 1.0 / np.polyfit(ks, tk, 1)[0]
    return {"v": v, "vk_discrete": vref, "f0": f0, "g": g, "L": L, "ks": ks, "tk": tk,
            "vk_continuum": float(fkme.vk_overdamped(f0, g, KC, UC, K, M, ETA))}


def run_fronts(out, L=128, f0=0.75, p=0.25, seed=4711, tmax=2000.0, dt=0.2,
               dump_dt=25.0, g=25.0):
    """Random initial state at constant force f0: run, then analyse the
    slip maps.  Returns a dict with the time series, the maps and the
    derived numbers (see analyse_fronts)."""
    out = Path(out)
    every = max(1, round(dump_dt / dt))
    lammps(out, L=L, g=g, f0=f0, p=p, seed=seed, init="random", mode="run",
           tmax=tmax, dt=dt, every=every, thermo=every)
    ser = fkme.read_ave_time(out / "series.dat")
    steps, cols = fkme.read_dump(out / "map.dump")
    t = steps * dt
    slips = np.array([to_grid(cols, L, "f_sub[6]", k) for k in range(len(t))]) / UC
    vel = np.array([to_grid(cols, L, "vx", k) for k in range(len(t))])
    res = {"L": L, "f0": f0, "p": p, "g": g, "t_series": ser["TimeStep"] * dt,
           "frac_series": ser["v_frac"], "t": t, "slips": slips, "vel": vel}
    res.update(analyse_fronts(t, slips, L, f0, g))
    return res


def analyse_fronts(t, slips, L, f0, g, min_size=5):
    """Nuclei, full-slip time and closed-front growth from slip maps.

    nuclei: the clusters of slipped blocks (4-neighbour, periodic, at least
    min_size blocks) at the first frame after the initial relaxation
    (t >= 2 m eta/(kc+K), two relaxation times of the uniform mode) that
    grow until the next frame.  Growth: clusters followed from frame to
    frame while they do not merge (a cluster of frame k+1 that contains
    exactly one of frame k); R = sqrt(A/pi) and dR/dt by finite
    differences; fit dR/dt = v_inf - D_fit/R (least squares in 1/R)."""
    slipped = slips >= 0.5
    t_settle = 2.0 * M * ETA / (KC + K)
    k0 = int(np.searchsorted(t, t_settle))
    labs = [label_periodic(s) for s in slipped]
    sizes = [np.bincount(lab.ravel(), minlength=n + 1)[1:] for lab, n in labs]
    # nuclei: big enough clusters at k0 whose blocks are in a bigger cluster at k0+1
    nuclei = 0
    if k0 + 1 < len(t):
        lab0, n0 = labs[k0]
        lab1, _ = labs[k0 + 1]
        for c in range(1, n0 + 1):
            if sizes[k0][c - 1] < min_size:
                continue
            nxt = np.unique(lab1[lab0 == c])
            nxt = nxt[nxt > 0]
            if len(nxt) == 1 and sizes[k0 + 1][nxt[0] - 1] > sizes[k0][c - 1]:
                nuclei += 1
    frac = slipped.reshape(len(t), -1).mean(axis=1)
    full = np.nonzero(frac >= 1.0)[0]
    t_full = float(t[full[0]]) if len(full) else math.nan
    # closed-front growth of isolated clusters
    Rs, dR = [], []
    for k in range(k0, len(t) - 1):
        lab0, n0 = labs[k]
        lab1, n1 = labs[k + 1]
        for c in range(1, n0 + 1):
            a0 = sizes[k][c - 1]
            if a0 < min_size:
                continue
            nxt = np.unique(lab1[lab0 == c])
            nxt = nxt[nxt > 0]
            if len(nxt) != 1:
                continue
            # the cluster of frame k+1 must contain no other cluster of frame k
            back = np.unique(lab0[lab1 == nxt[0]])
            if len(back[back > 0]) != 1:
                continue
            a1 = sizes[k + 1][nxt[0] - 1]
            if a1 >= 0.5 * L * L:          # wraps around the torus: not a disk
                continue
            r0, r1 = math.sqrt(a0 / math.pi), math.sqrt(a1 / math.pi)
            Rs.append(0.5 * (r0 + r1))
            dR.append((r1 - r0) / (t[k + 1] - t[k]))
    Rs, dR = np.array(Rs), np.array(dR)
    v_inf = D_fit = v_err = D_err = math.nan
    # radii between the front width and a quarter of the box (bigger
    # clusters feel the fronts of their neighbours)
    sel = (Rs >= 8.0) & (Rs <= L / 4.0)
    if sel.sum() >= 4:
        A = np.column_stack([np.ones(sel.sum()), -1.0 / Rs[sel]])
        coef, res, *_ = np.linalg.lstsq(A, dR[sel], rcond=None)
        v_inf, D_fit = coef
        s2 = np.sum((dR[sel] - A @ coef) ** 2) / (sel.sum() - 2)
        v_err, D_err = np.sqrt(np.diag(s2 * np.linalg.inv(A.T @ A)))
    return {"nuclei": nuclei, "t_nuclei": float(t[min(k0, len(t) - 1)]),
            "clusters": [n for _, n in labs], "frac": frac, "t_full": t_full,
            "R": Rs, "dRdt": dR, "fit_sel": sel, "v_inf": float(v_inf), "D_fit": float(D_fit),
            "v_err": float(v_err), "D_err": float(D_err), "k0": k0,
            "vk_straight": float(fkme.vk_discrete(f0, g, KC, UC, K, M, ETA)),
            "vk_continuum": float(fkme.vk_overdamped(f0, g, KC, UC, K, M, ETA)),
            "D_theory": g / (M * ETA)}


def fronts_summary(r):
    lines = ["# part fronts: L = %d, g = %g, f0 = %g, p = %g (random pre-slipped blocks)"
             % (r["L"], r["g"], r["f0"], r["p"]),
             "nuclei (growing clusters at t = %.0f)   %d" % (r["t_nuclei"], r["nuclei"]),
             "time to slip the whole interface       %.0f" % r["t_full"],
             "closed fronts dR/dt = v_inf - D/R      v_inf = %.4f +- %.4f, D = %.3f +- %.3f "
             "(%d points, 8 <= R <= L/4)" % (r["v_inf"], r["v_err"], r["D_fit"], r["D_err"],
                                            int(r["fit_sel"].sum())),
             "straight front (discrete, exact)       v_k = %.4f   (continuum Eq. crack.eqi04: %.4f)"
             % (r["vk_straight"], r["vk_continuum"]),
             "curvature term g a^2/(m eta)           D = %.3f" % r["D_theory"]]
    return "\n".join(lines)


def straight_summary(st):
    return ("straight front in 2d (band, L = %d)      v = %.5f vs vk_discrete = %.5f: "
            "%+.2f %% (%d columns fitted); continuum %.5f"
            % (st["L"], st["v"], st["vk_discrete"], 100 * (st["v"] / st["vk_discrete"] - 1),
               len(st["ks"]), st["vk_continuum"]))


def plot_fronts(r, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t, L = r["t"], r["L"]
    want = [r["t_nuclei"] * 0.5, r["t_nuclei"], 0.35 * r["t_full"], 0.75 * r["t_full"]]
    idx = [int(np.argmin(np.abs(t - w))) for w in want]
    fig, axs = plt.subplots(2, 5, figsize=(15, 6.4))
    vmax = np.percentile(r["vel"][idx], 99.5)
    ext = (-0.5, L - 0.5, -0.5, L - 0.5)
    for j, k in enumerate(idx):
        a = axs[0, j].imshow(r["vel"][k], origin="lower", extent=ext, cmap="magma",
                             vmin=0, vmax=vmax, interpolation="nearest")
        axs[0, j].set_title(r"$\dot u$ at t = %.0f" % t[k], fontsize=9)
        b = axs[1, j].imshow(r["slips"][k], origin="lower", extent=ext, cmap="viridis",
                             vmin=0, vmax=max(1, r["slips"].max()), interpolation="nearest")
        axs[1, j].set_title("slips $a/u_c$ at t = %.0f" % t[k], fontsize=9)
    fig.colorbar(a, ax=axs[0, 3], fraction=0.046)
    fig.colorbar(b, ax=axs[1, 3], fraction=0.046)
    # arrival time of the fronts: the first frame from which a block stays
    # slipped (blocks pre-slipped at t = 0 that fell back are not counted);
    # its contour lines are the fronts at equal time intervals
    stays = np.flip(np.logical_and.accumulate(np.flip(r["slips"] >= 0.5, 0), 0), 0)
    arr = np.where(stays.any(0), t[np.argmax(stays, 0)], np.nan)
    c = axs[0, 4].imshow(arr, origin="lower", extent=ext, cmap="turbo", interpolation="nearest")
    step = 100.0 if r["t_full"] < 3000 else 500.0
    axs[0, 4].contour(np.arange(L), np.arange(L), arr, levels=np.arange(step, np.nanmax(arr), step),
                      colors="k", linewidths=0.5)
    axs[0, 4].set_title("arrival time of the fronts (contours every %g)" % step, fontsize=9)
    fig.colorbar(c, ax=axs[0, 4], fraction=0.046)
    ax = axs[1, 4]
    ax.plot(r["t_series"], r["frac_series"] * L * L, "-", color="C0")
    ax.set_xlabel("t")
    ax.set_ylabel("slipped blocks", color="C0")
    ax2 = ax.twinx()
    k0 = r["k0"]
    ax2.plot(t[k0:], r["clusters"][k0:], ".-", color="C3", ms=3, lw=0.8)
    ax2.set_ylabel("slipped clusters", color="C3")
    ax.set_title("%d nuclei, all slipped at t = %.0f" % (r["nuclei"], r["t_full"]), fontsize=9)
    for a_ in axs[:, :4].ravel():
        a_.set_xlabel("x (sliding)", fontsize=8)
        a_.set_ylabel("y", fontsize=8)
    fig.suptitle("2d FK-ME, random initial state: L = %d, g = %g, f = %g, p = %g"
                 % (L, r["g"], r["f0"], r["p"]), fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "fronts_maps.png", dpi=80)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(5.6, 4.2))
    sel = r["fit_sel"]
    ax.plot(r["R"][sel], r["dRdt"][sel], ".", ms=4, color="C0", label="isolated clusters (fitted)")
    ax.plot(r["R"][~sel], r["dRdt"][~sel], ".", ms=4, color="C7", label="not fitted")
    if np.isfinite(r["v_inf"]):
        R = np.linspace(max(4.0, r["R"].min()), r["R"].max(), 100)
        ax.plot(R, r["v_inf"] - r["D_fit"] / R, "-", color="C1",
                label="fit $v_\\infty - D/R$: %.4f, %.3f" % (r["v_inf"], r["D_fit"]))
        ax.plot(R, r["vk_straight"] - r["D_theory"] / R, "--", color="C2",
                label="$v_k$(discrete) $- g a^2/(m\\eta R)$")
    ax.axhline(r["vk_straight"], color="k", lw=0.6, ls=":", label="straight front $v_k$ (discrete)")
    ax.axhline(r["vk_continuum"], color="k", lw=0.6, ls="-.", label="continuum $v_k$, Eq. crack.eqi04")
    ax.set_xlabel("cluster radius $R = (A/\\pi)^{1/2}$")
    ax.set_ylabel("dR/dt")
    ax.set_title("growth of closed fronts, f = %g" % r["f0"], fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "fronts_growth.png", dpi=90)
    plt.close(fig)


# ========================================================== part disorder
def run_ramp(out, L=64, g=25.0, w=0.0, dseed=1234, f0=0.56, df=0.002, nlev=33,
             band=None, dt=0.2, tchunk=400.0):
    """Quasi-static loading of a slipped band (two straight fronts).
    Returns dict with f, frac per level, the seed fraction and the slip
    maps of the levels."""
    out = Path(out)
    band = L // 2 if band is None else band
    lammps(out, L=L, g=g, w=w, dseed=dseed, f0=f0, df=df, nlev=nlev, band=band,
           init="band", mode="ramp", dt=dt, tchunk=tchunk, thermo=50)
    lev = np.atleast_2d(np.loadtxt(out / "levels.dat"))
    maps, dmap = [], None
    for i in lev[:, 0].astype(int):
        _, cols = fkme.read_dump(out / ("level_%d.dump" % i))
        maps.append(to_grid(cols, L, "f_sub[6]", 0) / UC)
        if dmap is None:
            dmap = to_grid(cols, L, "f_sub[5]", 0)
    return {"L": L, "g": g, "w": w, "dseed": dseed, "f": lev[:, 1], "frac": lev[:, 2],
            "frac_seed": band / L, "maps": np.array(maps), "d": dmap, "df": df}


def analyse_ramp(r):
    """Depinning force f_c (first level with the whole interface slipped),
    first advance of the fronts f_a (slipped fraction above the seed), the
    levels where fronts stopped after advancing (arrested: seed < frac < 1)
    and the avalanches there (blocks slipped per level)."""
    f, frac, N = r["f"], r["frac"], r["L"] ** 2
    seed = r["frac_seed"]
    tol = 0.5 / N
    full = np.nonzero(frac >= 1.0 - tol)[0]
    f_c = float(f[full[0]]) if len(full) else math.nan
    adv = np.nonzero(frac > seed + tol)[0]
    f_a = float(f[adv[0]]) if len(adv) else math.nan
    arrested = (frac > seed + tol) & (frac < 1.0 - tol)
    dn = np.diff(np.concatenate([[seed], frac])) * N
    aval = dn[arrested & (dn > 0.5)]
    return {"f_c": f_c, "f_a": f_a, "n_arrested": int(arrested.sum()), "avalanches": aval}


def run_disorder(out, L=64, gs=(25.0, 5.0), ws=(0.0, 0.1, 0.2), seeds=(1234, 2345, 3456),
                 df=0.002, below=0.65, above=0.006, dt=0.2, tchunk=300.0):
    """All ramps: per g, the ordered interface and every (w > 0, seed).
    Force range: from f_+ - below (f_+ - f_min) to f_+ + above around the
    PN force f_+ of a straight front, with f_+ halfway between two levels
    (the depinning force is resolved to +- df/2)."""
    runs = []
    for g in gs:
        fm, fp = fkme.discrete_depinning_force(g, KC, UC, K)
        n_below = int(math.ceil(below * (fp - fkme.f_min(KC, UC, K)) / df))
        # a chunk must outlast the dwell time per column of a w = 0 front at
        # the first level above f_+ (f_+ + df/2), else it is taken as arrested
        tch = max(tchunk, 1.3 / fkme.vk_discrete(fp + 0.5 * df, g, KC, UC, K, M, ETA))
        f0 = fp - (n_below - 0.5) * df
        nlev = n_below + int(math.ceil(above / df))
        for w in ws:
            for s in (seeds if w > 0 else seeds[:1]):
                d = Path(out) / ("ramp_g%g_w%g_s%d" % (g, w, s))
                r = run_ramp(d, L=L, g=g, w=w, dseed=s, f0=f0, df=df, nlev=nlev, dt=dt,
                             tchunk=round(tch, 1))
                r.update(analyse_ramp(r))
                r["f_plus"], r["f_minus"] = fp, fm
                runs.append(r)
    return runs


def disorder_summary(runs):
    lines = ["# part disorder: slipped band (two straight fronts along y) loaded quasi-statically,"
             " d_n gaussian(1, w)",
             "# f_+ = PN depinning force of a straight front (fkme.discrete_depinning_force),"
             " f_min = Griffith (continuum)",
             "# levels every df = %g; an avalanche = blocks slipped at one level by fronts that"
             " then stop" % runs[0]["df"],
             "# g      w     seed   f_a(advance)  f_c(all slipped)  arrested levels  "
             "avalanches (blocks)"]
    for r in runs:
        av = r["avalanches"]
        lines.append("%5g %6.3f %6d   %10.4f   %12.4f   %10d        %s" % (
            r["g"], r["w"], r["dseed"], r["f_a"], r["f_c"], r["n_arrested"],
            ",".join("%d" % a for a in av) if len(av) else "-"))
    lines.append("# per g and w: mean f_c +- sd over seeds, shift from f_+ in units of kc w")
    for g in sorted({r["g"] for r in runs}, reverse=True):
        sub = [r for r in runs if r["g"] == g]
        fp = sub[0]["f_plus"]
        lines.append("g = %g: f_+ = %.4f, f_min = %.4f, front width sqrt(g/(kc+K)) = %.1f blocks"
                     % (g, fp, fkme.f_min(KC, UC, K), math.sqrt(g / (KC + K))))
        for w in sorted({r["w"] for r in sub}):
            fc = np.array([r["f_c"] for r in sub if r["w"] == w])
            na = sum(r["n_arrested"] for r in sub if r["w"] == w)
            sd = fc.std(ddof=1) if len(fc) > 1 else 0.0
            shift = (fc.mean() - fp) / (KC * w) if w > 0 else 0.0
            lines.append("   w = %.2f: f_c = %.4f +- %.4f (%d runs), f_c - f_+ = %+.4f%s, "
                         "arrested levels %d" % (w, fc.mean(), sd, len(fc), fc.mean() - fp,
                                                 " = %+.3f kc w" % shift if w > 0 else "", na))
    return "\n".join(lines)


def plot_disorder(runs, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    gs = sorted({r["g"] for r in runs}, reverse=True)
    fig, axs = plt.subplots(1, len(gs), figsize=(5.2 * len(gs), 4.0), squeeze=False)
    for ax, g in zip(axs[0], gs):
        sub = [r for r in runs if r["g"] == g]
        ws = sorted({r["w"] for r in sub})
        for i, w in enumerate(ws):
            for j, r in enumerate([r for r in sub if r["w"] == w]):
                ax.step(r["f"], r["frac"], where="post", color="C%d" % i, lw=1.2 if w == 0 else 0.9,
                        alpha=1.0 if w == 0 else 0.8, label=("w = %g" % w) if j == 0 else None)
        fp = sub[0]["f_plus"]
        ax.axvline(fp, color="k", ls="--", lw=0.8, label="$f_+$ (PN, straight front)")
        if fkme.f_min(KC, UC, K) > sub[0]["f"][0]:
            ax.axvline(fkme.f_min(KC, UC, K), color="gray", ls=":", lw=0.8, label="$f_{min}$ (Griffith)")
        ax.set_xlabel("driving force f")
        ax.set_ylabel("slipped fraction")
        ax.set_title("g = %g, L = %d (seed band %d columns)" % (g, sub[0]["L"], round(sub[0]["frac_seed"]
                     * sub[0]["L"])), fontsize=9)
        ax.set_xlim(sub[0]["f"][0], sub[0]["f"][-1])
        ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(out / "disorder_frac.png", dpi=90)
    plt.close(fig)

    # maps: the most advanced arrested state of each g (largest w), on the disorder map
    pick = []
    for g in gs:
        sub = [r for r in runs if r["g"] == g and r["w"] > 0]
        best = None
        for r in sub:
            arr = np.nonzero((r["frac"] > r["frac_seed"] + 0.5 / r["L"] ** 2)
                             & (r["frac"] < 1 - 0.5 / r["L"] ** 2))[0]
            if len(arr) and (best is None or r["frac"][arr[-1]] > best[0]["frac"][best[1]]):
                best = (r, arr[-1])
        if best is None and sub:
            r = max(sub, key=lambda r: r["w"])
            best = (r, int(np.nonzero(r["frac"] < 1 - 0.5 / r["L"] ** 2)[0][-1]))
        if best:
            pick.append(best)
    if not pick:
        return
    fig, axs = plt.subplots(1, len(pick), figsize=(5.0 * len(pick), 4.4), squeeze=False)
    for ax, (r, k) in zip(axs[0], pick):
        L = r["L"]
        ext = (-0.5, L - 0.5, -0.5, L - 0.5)
        im = ax.imshow(r["d"], origin="lower", extent=ext, cmap="Greys",
                       vmin=1 - 3 * r["w"], vmax=1 + 3 * r["w"], interpolation="nearest")
        slipped = np.ma.masked_less(r["maps"][k], 0.5)
        ax.imshow(slipped, origin="lower", extent=ext, cmap="autumn", alpha=0.45,
                  interpolation="nearest")
        ax.contour(np.arange(L), np.arange(L), (r["maps"][0] >= 0.5).astype(float), levels=[0.5],
                   colors="b", linewidths=0.8, linestyles="dotted")
        fig.colorbar(im, ax=ax, fraction=0.046, label="disorder factor $d_n$ (dark: strong)")
        ax.set_title("g = %g, w = %g: fronts arrested at f = %.3f\n(slipped %.2f, orange; dotted: seed band; "
                     "f_c = %.3f)" % (r["g"], r["w"], r["f"][k], r["frac"][k], r["f_c"]), fontsize=9)
        ax.set_xlabel("x (sliding)")
        ax.set_ylabel("y")
    fig.tight_layout()
    fig.savefig(out / "disorder_maps.png", dpi=90)
    plt.close(fig)


# ==================================================================== main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--part", choices=["fronts", "disorder", "all"], default="all")
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--L", type=int, default=128, help="fronts: lattice size")
    ap.add_argument("--f0", type=float, default=0.75, help="fronts: driving force")
    ap.add_argument("--p", type=float, default=0.25, help="fronts: pre-slipped fraction")
    ap.add_argument("--seed", type=int, default=4711, help="fronts: seed of the random state")
    ap.add_argument("--tmax", type=float, default=2000.0, help="fronts: duration")
    ap.add_argument("--Ld", type=int, default=64, help="disorder: lattice size")
    ap.add_argument("--gs", type=float, nargs="+", default=[25.0, 5.0])
    ap.add_argument("--ws", type=float, nargs="+", default=[0.0, 0.1, 0.2])
    ap.add_argument("--dseeds", type=int, nargs="+", default=[1234, 2345, 3456])
    ap.add_argument("--df", type=float, default=0.002, help="disorder: force step")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    if args.part in ("fronts", "all"):
        t0 = time.time()
        r = run_fronts(out / "fronts", L=args.L, f0=args.f0, p=args.p, seed=args.seed,
                       tmax=args.tmax)
        st = run_straight(out / "straight", f0=args.f0)
        text = (fronts_summary(r) + "\n" + straight_summary(st)
                + "\n# wall time %.0f s" % (time.time() - t0))
        print(text)
        (out / "summary_fronts.txt").write_text(text + "\n")
        plot_fronts(r, out)
        print("wrote", out / "fronts_maps.png", out / "fronts_growth.png")

    if args.part in ("disorder", "all"):
        t0 = time.time()
        runs = run_disorder(out, L=args.Ld, gs=args.gs, ws=args.ws, seeds=args.dseeds,
                            df=args.df)
        text = disorder_summary(runs) + "\n# wall time %.0f s" % (time.time() - t0)
        print(text)
        (out / "summary_disorder.txt").write_text(text + "\n")
        plot_disorder(runs, out)
        print("wrote", out / "disorder_frac.png", out / "disorder_maps.png")


if __name__ == "__main__":
    main()
