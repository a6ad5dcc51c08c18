#!/usr/bin/python3
"""lambda_c blocks with their own master equation (fix eq/meso, paper Sec.
"Far zone" and "Elastic screening length").

    /usr/bin/python3 run.py [--part screen|driven|lattice|all] [--out out] [--img]

Parts (each prints a summary with the references and writes a PNG):

screen   in.eq-meso-screen: a lattice of blocks slides rigidly past a pinned
         stripe at x = 0; the screening eps_n = x_c sum_m Gamma_m Pi_mn of
         every block against the linear system of the self-consistent
         Eq. scr.eq08 on the lattice (tools/eqtools/meso.screening_lattice),
         the decay length of Delta eps = eps - eps0 (cosh fit between the
         periodic images of the stripe) against the exact lattice decay
         (root of sum_m Pi_m cosh(x_m/l) = 1) and the continuum length
         of the Taylor expansion (scr.eq09): (eps0/2)^1/2 for a chain (the
         paper's Eq. eq10), (eps0/4)^1/2 for a stripe on a square lattice,
         (eps0 <x^2>_Pi / 2)^1/2 for any kernel.  Three lattices: square
         24 x 4 and chain 30 x 1 with nearest neighbours, square 16 x 8
         with Pi = N_lambda kappa r^-3 up to r = 3.  -> out/eq-meso-screen.png
driven   in.eq-meso-driven: one block of N_lambda = 1000 contacts
         (realistic thresholds) pulled through a spring K = 0.5, 1.5, 3 K*
         (K* = max(-dF/dX) of the master equation, from eq-me): stage
         force K (X_s - X) against the stage position and block velocity
         against time; vmax/v_stage against the quasi-static bound
         K/(K - K*).  -> out/eq-meso-driven.png
lattice  in.eq-meso-driven with 8 blocks and screening (Pi0 = 0.5): the
         smallest K that slides smoothly, with and without screening,
         and with a shorter rate window; K*_eff = max(-dF/dX) of the
         quasi-static F(X) of the blocks.  -> out/eq-meso-lattice.png
"""
import argparse
import math
import shutil
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import numpy as np  # noqa: E402

import eqtools  # noqa: E402
from eqtools import meso  # noqa: E402

SCREEN = HERE / "in.eq-meso-screen"
DRIVEN = HERE / "in.eq-meso-driven"
IMG = HERE.parents[1] / "doc" / "src" / "img"
NLAM = 1000          # contacts per block of the driven inputs
ETA = 2000.0         # their damping (fix brownian gamma_t, the input's default)


def lammps(infile, out, **var):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    var.setdefault("out", ".")
    t0 = time.time()
    eqtools.run_lammps(infile, var, cwd=out, log="log.lammps")
    return time.time() - t0


def figure(nrows, ncols, size):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt.subplots(nrows, ncols, figsize=size, squeeze=False)


COPY_IMG = False     # --img: copy the PNGs to doc/src/img/eq_meso_*.png


def save(fig, out, name):
    fig.tight_layout()
    path = out / name
    fig.savefig(path, dpi=80)
    print("  wrote", path)
    if COPY_IMG:
        dest = IMG / name.replace("eq-meso-", "eq_meso_")
        shutil.copyfile(path, dest)
        print("  copied to", dest)


# ---------------------------------------------------------------- screen
def dump_rows(path):
    """Last frame of a LAMMPS dump (sorted by id) as a 2-d array."""
    block = Path(path).read_text().split("ITEM: ATOMS")[-1].splitlines()
    return np.array([[float(v) for v in line.split()] for line in block[1:] if line.strip()])


def kernel_moments(rcut, kernel, chain):
    """Pi_m of the infinite lattice within rcut (square lattice, or a chain):
    lists of x_m and Pi_m over the partners m of one block."""
    reach = int(math.ceil(rcut))
    xs, ps = [], []
    for i in range(-reach, reach + 1):
        for j in ([0] if chain else range(-reach, reach + 1)):
            r2 = i * i + j * j
            if 0 < r2 <= rcut * rcut * (1 + 2e-12):
                xs.append(float(i))
                ps.append(kernel(math.sqrt(r2)))
    return np.array(xs), np.array(ps)


def exact_decay(xs, ps):
    """Slowest decay length of Delta eps away from a stripe on the infinite
    lattice: Delta eps(x) = sum_m Pi_m Delta eps(x + x_m) with Delta eps ~
    exp(-x/l) gives sum_m Pi_m cosh(x_m/l) = 1 (bisection in 1/l)."""
    f = lambda q: np.sum(ps * np.cosh(xs * q)) - 1.0
    lo, hi = 0.0, 1.0
    while f(hi) < 0:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 1.0 / (0.5 * (lo + hi))


def cosh_fit(x, deps, L):
    """Delta eps(x) = A cosh((x - L/2)/l) between the stripe and its periodic
    image L away (the exact form of the nearest-neighbour lattice solution
    for x >= 1): l and its standard error (as in the test)."""
    from scipy.optimize import curve_fit
    f = lambda x, A, ell: A * np.cosh((x - 0.5 * L) / ell)
    p, cov = curve_fit(f, x, deps, p0=(deps.min(), 2.0))
    return p[0], p[1], math.sqrt(cov[1, 1])


def screen_case(out, name, nx, ny, nlam, kappa, rcut, grid, window, dX, Xmax, chain=False,
                fit_from=1):
    var = dict(nx=nx, ny=ny, nlam=nlam, kappa=f"{kappa:.17g}", rcut=rcut, grid=grid,
               window=window, dX=dX, Xmax=Xmax)
    if chain:
        var["yboundary"] = "f"
    wall = lammps(SCREEN, out / f"screen-{name}", **var)
    a = dump_rows(out / f"screen-{name}" / "eps.dump")     # id x y eps Gamma F X
    sites = np.mod(np.c_[np.rint(a[:, 1] - a[:, 6]), np.rint(a[:, 2])], [nx, ny])
    sliding = sites[:, 0] != 0
    kern = meso.pi_kernel(nlam, kappa)
    ref, pi0 = meso.screening_lattice(sites, [nx, 0.0 if chain else ny], sliding, rcut, kern)
    eps = a[:, 3]
    dev = np.max(np.abs(eps - ref)) / ref.max()
    xs, ps = kernel_moments(rcut, kern, chain)
    Pi0 = ps.sum()
    eps0 = Pi0 / (1.0 - Pi0)
    ell_exact = exact_decay(xs, ps)
    lam_s = math.sqrt(np.sum(ps * xs * xs) / (2.0 * (1.0 - Pi0)))   # scr.eq09 for this kernel
    cols = np.arange(fit_from, nx - fit_from + 1 if fit_from > 1 else nx)
    prof = np.array([eps[sites[:, 0] == c].mean() for c in cols])
    rprof = np.array([ref[sites[:, 0] == c].mean() for c in cols])
    A, ell, dell = cosh_fit(cols, prof - eps0, nx)
    _, ell_ref, _ = cosh_fit(cols, rprof - eps0, nx)
    r = dict(name=name, nx=nx, ny=ny, sites=sites, eps=eps, ref=ref, dev=dev, Pi0=Pi0,
             pi0_fix=pi0.max(), eps0=eps0, ell=ell, dell=dell, ell_ref=ell_ref,
             ell_exact=ell_exact, lam_s=lam_s, wall=wall, fit_from=fit_from)
    return r


def part_screen(out):
    rows = []
    nlam = 100
    # the stripe and the chain of the tests (nearest neighbours, Pi0 = 0.972)
    rows.append(screen_case(out, "stripe", 24, 4, nlam, 0.00243, 1.01, 5e-8, 2e-5, 1e-5, 0.012))
    rows.append(screen_case(out, "chain", 30, 1, nlam, 0.00486, 1.01, 5e-8, 2e-5, 1e-5, 0.012,
                            chain=True))
    # Pi = N kappa r^-3 up to r = 3 on the square lattice, scaled to Pi0 = 0.9
    xs, ps = kernel_moments(3.01, meso.pi_kernel(1.0, 1.0), False)
    kappa = 0.9 / (nlam * ps.sum())
    rows.append(screen_case(out, "r3", 16, 8, nlam, kappa, 3.01, 2e-7, 2e-5, 1e-5, 0.006,
                            fit_from=3))
    formula = {"stripe": "(eps0/4)^1/2", "chain": "(eps0/2)^1/2 (Eq. eq10)",
               "r3": "(eps0 <x^2>_Pi/2)^1/2"}
    title = {"stripe": "square 24 x 4, nearest neighbours",
             "chain": "chain of 30, nearest neighbours",
             "r3": "square 16 x 8, $r^{-3}$ up to 3"}
    print("# screen: blocks sliding past a pinned stripe (N_lambda = 100, x_c = 1e-4, "
          "thresholds uniform [0.75,1.25] x_c, reform delta 0)")
    for r in rows:
        print(f"  {r['name']:6s} Pi0 = {r['Pi0']:.4f} (fix: {r['pi0_fix']:.4f}), eps0 = "
              f"{r['eps0']:.4f}; max |eps - lattice|/max eps = {r['dev']:.2e} ({r['wall']:.0f} s)")
        lim = f", columns {r['fit_from']}..{r['nx'] - r['fit_from']}" if r["fit_from"] > 1 else ""
        print(f"         decay length: fit {r['ell']:.5f} +- {r['dell']:.1e}{lim} "
              f"(same fit to the lattice solution {r['ell_ref']:.5f}); exact lattice "
              f"{r['ell_exact']:.5f}; continuum {formula[r['name']]} = {r['lam_s']:.5f} "
              f"({100 * (r['lam_s'] / r['ell_exact'] - 1):+.2f} %)")
    fig, ax = figure(2, 3, (12, 6.4))
    for k, r in enumerate(rows):
        x = r["sites"][:, 0]
        L = r["nx"]
        cols = np.arange(L + 1)
        lat = np.array([r["ref"][x == (c % L)].mean() for c in cols])
        # continuum profile, matched to the lattice solution in the middle
        xx = np.linspace(0, L, 400)
        mid = r["ref"][x == L // 2].mean() - r["eps0"]
        cont = r["eps0"] + mid * np.cosh((xx - 0.5 * L) / r["lam_s"]) / np.cosh(
            (L // 2 - 0.5 * L) / r["lam_s"])
        xp = np.where(x == 0, 0, x)
        a0, a1 = ax[0][k], ax[1][k]
        a0.plot(cols, lat, "-", color="0.6", lw=2, label="lattice solution (scr.eq08)")
        a0.plot(xp, r["eps"], "o", ms=3.5, color="C0", label="fix eq/meso, every block")
        a0.plot(xx, cont, "--", color="C3", lw=1, label=r"continuum, $\lambda_s$ = %.3f" % r["lam_s"])
        a0.axhline(r["eps0"], color="k", lw=0.5, ls=":")
        a0.set_title(title[r["name"]], fontsize=10)
        a0.set_xlabel(r"x / $\lambda_c$ (pinned stripe at 0 and %d)" % L)
        a0.set_ylabel(r"$\varepsilon$")
        sel = (cols > 0) & (cols < L)
        a1.semilogy(cols[sel], r["eps0"] - lat[sel], "-", color="0.6", lw=2, label="lattice")
        a1.semilogy(xp[xp > 0], r["eps0"] - r["eps"][xp > 0], "o", ms=3.5, color="C0",
                    label="fix eq/meso")
        a1.semilogy(xx[(xx > 0.5) & (xx < L - 0.5)],
                    (r["eps0"] - cont)[(xx > 0.5) & (xx < L - 0.5)], "--", color="C3", lw=1,
                    label="continuum")
        a1.set_xlabel(r"x / $\lambda_c$")
        a1.set_ylabel(r"$\varepsilon_0 - \varepsilon$")
        a1.text(0.5, 0.92, r"fit %.3f, lattice %.3f, formula %.3f" % (r["ell"], r["ell_exact"],
                                                                      r["lam_s"]),
                transform=a1.transAxes, ha="center", fontsize=8)
    ax[0][0].legend(fontsize=7, loc="lower center")
    save(fig, out, "eq-meso-screen.png")
    return rows


# ---------------------------------------------------------------- driven
def kstar_me(out):
    """K* = max(-dF/dX) of one block (realistic thresholds x_s = 1, relaxed
    start), from eq-me: K*/(N k_c) and the ME force curve."""
    d = Path(out)
    d.mkdir(parents=True, exist_ok=True)
    me = eqtools.run_eqme(["threshold", "realistic", "1.0", "xmax", 6.0, "force", "me.dat"], cwd=d)
    return me, eqtools.load(d / "me.dat")


def driven(out, K, v=0.002, Xend=40.0, nblocks=1, extra=""):
    """One run of in.eq-meso-driven: time, stage X_s, mean block X, the
    interface force per block F = K (X_s - X) - eta dX/dt (exact for fix
    brownian: the printed X_s, X are those the forces of the step saw) and
    vmax / v_stage after X_s = 0.5."""
    wall = lammps(DRIVEN, out, K=f"{K:.17g}", nlam=NLAM, v=v, Xend=Xend, nblocks=nblocks,
                  extra=extra)
    t = eqtools.load(Path(out) / "driven.dat")
    time_, Xs, X = t[:, 0], t[:, 1], t[:, 2]
    vel = np.diff(X) / np.diff(time_)
    F = K * (Xs[:-1] - X[:-1]) - ETA * vel
    vmax = np.max(vel[Xs[1:] > 0.5]) / v
    return dict(t=time_, Xs=Xs, X=X, vel=vel / v, F=F, vmax=vmax, wall=wall, K=K)


def part_driven(out):
    me, curve = kstar_me(out / "driven")
    kstar = me["kstar"] * NLAM
    print(f"# driven: one block, N_lambda = {NLAM}, realistic thresholds x_s = 1, v = 0.002, "
          f"eta = {ETA:g} (fix brownian)")
    print(f"  K* = {me['kstar']:.6f} N k_c = {kstar:.2f} (eq-me, at X = {me['kstar_X']:.4f}); "
          f"static peak {me['static_peak']:.4f} N k_c")
    runs = []
    for f in (0.5, 1.5, 3.0):
        r = driven(out / f"driven-K{f:g}", f * kstar)
        r["f"] = f
        runs.append(r)
        bound = f"quasi-static bound K/(K - K*) = {f / (f - 1):.3f}" if f > 1 else \
            "K < K*: no quasi-static path (slip)"
        print(f"  K = {f:g} K*: vmax/v_stage = {r['vmax']:.3f}; {bound} ({r['wall']:.1f} s)")
    fig, ax = figure(1, 2, (11, 4))
    for r in runs:
        lab = r"K = %g K$^*$" % r["f"]
        ax[0][0].plot(r["Xs"], r["K"] * (r["Xs"] - r["X"]) / NLAM, lw=1, label=lab)
        ax[0][1].plot(r["t"][1:], r["vel"], lw=1, label=lab + ", max %.2f" % r["vmax"])
    ax[0][0].set_xlabel(r"stage position $X_s$")
    ax[0][0].set_xlim(0, 20)
    ax[0][0].set_ylabel(r"stage force $K(X_s - X) / N_\lambda k_c$")
    ax[0][0].legend(fontsize=8)
    ax[0][1].set_xlabel("time")
    ax[0][1].set_ylabel(r"block velocity / $v_{stage}$")
    ax[0][1].set_xlim(0, 12000)
    ax[0][1].legend(fontsize=8)
    save(fig, out, "eq-meso-driven.png")
    return runs


# --------------------------------------------------------------- lattice
def classify(out, K, extra, v=1e-3):
    """Stick-slip or smooth: run at the stage velocity v and v/4 (stage
    travel 10).  Sliding smoothly, the block follows the stage
    quasi-statically, vmax/v_stage ~ K/(K - K*_eff) for either velocity;
    slipping, its velocity is set by the damping, so vmax/v_stage grows by
    up to 4.  Smooth: the ratio of vmax/v_stage changes by less than 1.5."""
    fast = driven(out / "fast", K, v=v, Xend=10.0, nblocks=8, extra=extra)
    slow = driven(out / "slow", K, v=v / 4, Xend=10.0, nblocks=8, extra=extra)
    ratio = slow["vmax"] / fast["vmax"]
    return dict(K=K, fast=fast["vmax"], slow=slow["vmax"], ratio=ratio, smooth=ratio < 1.5,
                run=slow)


def kstar_eff(run, dx=0.02):
    """max(-dF/dX) of the quasi-static F(X) per block of a smooth run, F
    resampled on a grid of dx (X monotone: the master equation and the
    windowed rate depend on the path X only)."""
    X, F = run["X"][:-1], run["F"]
    keep = np.r_[True, np.diff(X) > 0]
    X, F = X[keep], F[keep]
    grid = np.arange(X[0], X[-1], dx)
    Fg = np.interp(grid, X, F)
    return np.max(-np.gradient(Fg, dx)), grid, Fg


def part_lattice(out):
    me, curve = kstar_me(out / "lattice")
    kstar = me["kstar"] * NLAM
    a = 10.0 ** -0.5                 # lattice sq 10.0 in lj units: spacing rho^-1/2
    Pi0 = 0.5                        # 2 neighbours along the row + 2 periodic images across
    kappa = Pi0 / (4 * NLAM)
    scr = f"screen {kappa:.6g} {a:.9f} {1.01 * a:.9f}"
    cases = [("no screening", ""), ("screening, window x_c", scr),
             ("screening, window 0.3", scr + " window 0.3")]
    grid = [0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0]
    eps0 = Pi0 / (1 - Pi0)
    print(f"# lattice: 8 blocks in a periodic row (spacing a = {a:.5f}, box one block high), "
          f"N_lambda = {NLAM}, realistic x_s = 1, K* = {kstar:.2f}")
    print(f"  screening Pi1 = N kappa = {NLAM * kappa:.4g}, nu = 4, Pi0 = {Pi0}, eps0 = {eps0:g}; "
          f"smooth = vmax/v_stage changes by < 1.5 between v = 1e-3 and 2.5e-4")
    res = []
    for name, extra in cases:
        t0 = time.time()
        d = out / ("lattice-" + name.replace(",", "").replace(" ", "_"))
        scan = []
        for f in grid:
            c = classify(d, f * kstar, extra)
            c["f"] = f
            scan.append(c)
            if c["smooth"] and len([s for s in scan if s["smooth"]]) >= 2:
                break
        # refine between the last stick-slip and the first smooth K (bisection)
        lo = max([s["f"] for s in scan if not s["smooth"]], default=None)
        hi = min(s["f"] for s in scan if s["smooth"])
        if lo is not None and lo < hi:
            for _ in range(4):
                mid = 0.5 * (lo + hi)
                c = classify(d, mid * kstar, extra)
                c["f"] = mid
                scan.append(c)
                lo, hi = (lo, mid) if c["smooth"] else (mid, hi)
        scan.sort(key=lambda s: s["f"])
        stiff = max(scan, key=lambda s: s["f"])
        ke, Xg, Fg = kstar_eff(stiff["run"])
        Xr = stiff["run"]["X"][:-1]
        steady = stiff["run"]["F"][Xr > Xr.max() - 1.0].mean() / NLAM     # the last unit of X
        r = dict(name=name, scan=scan, lo=lo, hi=hi, kse=ke / kstar, X=Xg, F=Fg / NLAM,
                 steady=steady, wall=time.time() - t0)
        res.append(r)
        print(f"  {name}: K/K* " + ", ".join(
            f"{s['f']:.3g}:{s['fast']:.1f}/{s['slow']:.1f}{'' if s['smooth'] else '*'}"
            for s in scan) + "   (vmax/v_stage at v/(v/4), * = stick-slip)")
        print(f"    smallest smooth K = {hi:.3f} K* (largest stick-slip {lo:.3f} K*); K*_eff = "
              f"max(-dF/dX) at K = {stiff['f']:g} K*: {r['kse']:.3f} K*; F at the end "
              f"(X = {Xr.max() - 1:.1f}..{Xr.max():.1f}) {steady:.4f} N k_c ({r['wall']:.0f} s)")
    base = res[0]
    for r in res[1:]:
        print(f"  {r['name']}: K_min ratio {r['hi'] / base['hi']:.3f}, K*_eff ratio "
              f"{r['kse'] / base['kse']:.3f} (K*_eff/K*: the paper's beta0)")
    print(f"  steady F: kinetic F_k/(1 + eps0) = {me['kinetic_force'] / (1 + eps0):.4f} N k_c "
          f"with screening, {me['kinetic_force']:.4f} without")
    fig, ax = figure(1, 2, (11, 4))
    for k, r in enumerate(res):
        f = np.array([s["f"] for s in r["scan"]])
        ax[0][0].semilogy(f, [s["slow"] for s in r["scan"]], "o-", color=f"C{k}", ms=4,
                          label=r["name"] + r", v = 2.5e-4")
        ax[0][0].semilogy(f, [s["fast"] for s in r["scan"]], "s:", color=f"C{k}", ms=3,
                          mfc="none", label=r["name"] + r", v = 1e-3")
        ax[0][0].axvline(r["kse"], color=f"C{k}", lw=0.8, ls="--")
        ax[0][1].plot(r["X"], r["F"], color=f"C{k}", lw=1,
                      label=r["name"] + r", $K^*_{eff}$ = %.2f $K^*$" % r["kse"])
    ax[0][1].plot(curve[:, 0], curve[:, 1], color="k", lw=0.7, ls=":", label="master equation (eq-me)")
    ax[0][0].set_xlabel(r"K / K$^*$ (dashed: $K^*_{eff}$ from F(X))")
    ax[0][0].set_ylabel(r"$v_{max} / v_{stage}$")
    ax[0][0].legend(fontsize=7)
    ax[0][1].set_xlabel("block displacement X")
    ax[0][1].set_ylabel(r"F / $N_\lambda k_c$ (quasi-static, stiffest K)")
    ax[0][1].set_xlim(0, 6)
    ax[0][1].legend(fontsize=7)
    save(fig, out, "eq-meso-lattice.png")
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--part", nargs="+", default=["all"],
                    choices=["screen", "driven", "lattice", "all"])
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--img", action="store_true",
                    help="copy the PNGs to doc/src/img/eq_meso_*.png (the README's images)")
    a = ap.parse_args()
    global COPY_IMG
    COPY_IMG = a.img
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    parts = ["screen", "driven", "lattice"] if "all" in a.part else a.part
    t00 = time.time()
    for p in parts:
        t0 = time.time()
        {"screen": part_screen, "driven": part_driven, "lattice": part_lattice}[p](out)
        print(f"  ({p}: {time.time() - t0:.0f} s)")
    print(f"  (total: {time.time() - t00:.0f} s)")


if __name__ == "__main__":
    main()
