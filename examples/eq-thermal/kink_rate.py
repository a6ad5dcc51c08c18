#!/usr/bin/python3
"""The velocity-dependent block law of FK-ME kinks (fix eq/substrate ...
rate A v0): the kink velocity against the driving force at A = 0 and
A > 0, LAMMPS against an independent integration of the same chain.

At T > 0 the block law of the master equation becomes F_k(v, T): a block
that slips at the velocity w feels, besides the substrate force of its
well, the rate force A asinh(w/(2 v0)) ~ A ln(w/v0), A = dF_k/dln v of a
block (the ME's kinetic slope per N k_c times the block's kc).  The
overdamped chain (fix brownian, gamma = m eta)

    gamma u_n' + A asinh(u_n'/(2 v0)) = g (u_n+1 + u_n-1 - 2 u_n)
                                        - kc (u_n - a_n) - K u_n + f

is integrated here independently of LAMMPS: classical RK4 with the wells
a_n frozen within a step, u' from the implicit law by Newton's method,
and the crossings of u_n = a_n + uc located on the cubic Hermite
interpolant of the step (error O(h^4)) and the step redone up to them.
The kink velocity is the number of sites between two tracked blocks over
the difference of the times at which they slip.  LAMMPS' fix brownian is
first order in dt (the rate term takes the velocity of the previous
step): its kink velocities at dt and dt/2 are Richardson-extrapolated.

python3 kink_rate.py [--quick]     (writes out/eq-thermal-kink-rate.png;
                                    lmp from FEQ_LMP or ../../build/lmp)
"""
import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
from eqtools import fkme, run_eqme, run_lammps  # noqa: E402

INPUT = HERE / "in.eq-thermal-kink-rate"
G, KC, UC, K, GAMMA, DT = 25.0, 1.0, 1.0, 0.07, 100.0, 0.1
N, SEED0, SEED1 = 200, 68, 132
TRACK = (150, 180)        # atom IDs; sites ID - 1
A_RATE, V0 = 0.01, 1e-4   # A/(2 v0) = 50 < gamma: the lagged rate term is stable (the test's)
# the worked example: the block's contacts as those of examples/eq-thermal
# (thresholds uniform [0.75, 1.25], theta = 0.02, eps_a = omega = 1); the
# kink's blocks slip at up to ~1e-2, so the ME's slope is taken as the
# secant over [1e-4, 1e-2] and v0 = 1e-4
EQME = ["threshold", "uniform", "0.75", "1.25", "thermal", "0.02", "1.0", "1.0",
        "velocity", "1e-3"]
V_LO, V_HI = 1e-4, 1e-2


def rate_from_me(workdir, kc=KC):
    """A = kc * (F_k(v_hi) - F_k(v_lo)) / (N k_c ln(v_hi/v_lo)) from eq-me's
    kinetic table (F_k in units of N k_c; the block's kc is N_c k_c, as
    for the table shape: phi = F/(N k_c), F_s = kc phi), v0 = v_lo."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    run_eqme(EQME + ["kinetic", "fk.dat", V_LO, V_HI, 5], cwd=workdir)
    d = np.loadtxt(workdir / "fk.dat")
    secant = (d[-1, 1] - d[0, 1]) / math.log(d[-1, 0] / d[0, 0])
    return kc * secant, V_LO, d


def initial_positions(f, n=N, seed=(SEED0, SEED1), kc=KC, uc=UC, K=K):
    """The input's start: u_R = f/(kc+K), blocks seed0+1..seed1 (IDs) at
    u_L = (f + kc uc)/(kc+K)."""
    ids = np.arange(1, n + 1)
    uR, uL = f / (kc + K), (f + kc * uc) / (kc + K)
    return np.where((ids > seed[0]) & (ids <= seed[1]), uL, uR)


# --------------------------------------------------- the independent chain
def rate_velocity(F, gamma, A, v0, w=None):
    """w solving gamma w + A asinh(w/(2 v0)) = F (vectorised Newton from w =
    F/gamma or the guess w; G is increasing and concave for w > 0, convex
    for w < 0, so after the first step the iterates approach the root
    monotonically).  Stops when the Newton step is below 1e-13 |w|: the
    error left is of the order of the square of that step, i.e. the
    rounding of G (a few ulp of |w| ln(w/v0))."""
    F = np.asarray(F, float)
    if A == 0.0:
        return F / gamma
    w = F / gamma if w is None else np.array(w, float)
    for _ in range(100):
        G = gamma * w + A * np.arcsinh(w / (2 * v0)) - F
        dG = gamma + A / np.hypot(w, 2 * v0)
        step = G / dG
        w = w - step
        if np.all(np.abs(step) <= 1e-13 * np.abs(w) + 1e-300):
            return w
    raise RuntimeError("Newton did not converge")


class Chain:
    def __init__(self, f, A, v0, n=N, g=G, kc=KC, uc=UC, K=K, gamma=GAMMA):
        self.f, self.A, self.v0, self.n = f, A, v0, n
        self.g, self.kc, self.uc, self.K, self.gamma = g, kc, uc, K, gamma

    def force(self, u, a):
        return (self.g * (np.roll(u, 1) + np.roll(u, -1) - 2 * u) - self.kc * (u - a)
                - self.K * u + self.f)

    def deriv(self, u, a):
        return rate_velocity(self.force(u, a), self.gamma, self.A, self.v0)

    def rk4(self, u, a, h, k1):
        k2 = self.deriv(u + 0.5 * h * k1, a)
        k3 = self.deriv(u + 0.5 * h * k2, a)
        k4 = self.deriv(u + h * k3, a)
        return u + (h / 6.0) * (k1 + 2 * (k2 + k3) + k4)


def reference_crossings(f, A, v0, h, t_end, track=TRACK, **chain):
    """Times at which the tracked blocks (atom IDs) first reach u = a + uc,
    and the largest and smallest block velocity seen (a kink's range of
    u')."""
    ch = Chain(f, A, v0, **chain)
    u = initial_positions(f, ch.n, uc=ch.uc, kc=ch.kc, K=ch.K)
    a = np.floor(u / ch.uc) * ch.uc
    want = {i - 1: None for i in track}
    t = 0.0
    k1 = ch.deriv(u, a)
    wmax, wmin = -np.inf, np.inf    # while the kink runs between the tracked blocks
    while t < t_end and any(v is None for v in want.values()):
        unew = ch.rk4(u, a, h, k1)
        up = np.nonzero(unew - a >= ch.uc)[0]
        if np.any(unew - a < 0.0):
            raise RuntimeError("a block moved backward out of its well")
        if len(up) == 0:
            u, t = unew, t + h
            k1 = ch.deriv(u, a)
        else:
            knew = ch.deriv(unew, a)
            th = fkme._hermite_root(u[up], k1[up], unew[up], knew[up], h, a[up] + ch.uc)
            thmin = th.min()
            sel = up[th <= thmin + 1e-12]
            he = thmin * h
            if he > 0.0:
                u = ch.rk4(u, a, he, k1)
                t += he
            u[sel] = a[sel] + ch.uc
            a[sel] += ch.uc
            for j in sel:
                if j in want and want[j] is None:
                    want[j] = t
            k1 = ch.deriv(u, a)
        if want[track[0] - 1] is not None:
            wmax, wmin = max(wmax, k1.max()), min(wmin, k1.min())
    return np.array([want[i - 1] for i in track]), wmax, wmin


def reference_velocity(f, A, v0, h=0.1, track=TRACK, **chain):
    """Kink velocity of the reference at step h, its error estimated from h
    and 2h (RK4: the error at h is |v(h) - v(2h)|/15 for a fourth-order
    series), and the range of block velocities."""
    t_end = 4.0 * (track[1] - SEED1) / max(fkme.vk_discrete(f, G, KC, UC, K, 1.0, GAMMA), 1e-3)
    vs = []
    for hh in (2 * h, h):
        tc, wmax, wmin = reference_crossings(f, A, v0, hh, t_end, track, **chain)
        vs.append((track[1] - track[0]) / (tc[1] - tc[0]))
    return vs[1], abs(vs[1] - vs[0]) / 15.0, wmax, wmin


# -------------------------------------------------------------- LAMMPS
def crossing_times(path, track=TRACK, uc=UC):
    """Times at which the tracked blocks reach u = uc: linear between the
    steps, which is fix brownian's path (its step is a straight move)."""
    d = np.loadtxt(path)
    t = d[:, 0]
    out = []
    for k, ident in enumerate(track):
        u = d[:, k + 1] - (ident - 1)
        hit = np.nonzero(u >= uc)[0]
        if len(hit) == 0:
            raise RuntimeError(f"block {ident} has not slipped by t = {t[-1]:g}: run longer")
        j = hit[0]
        out.append(t[j - 1] + (uc - u[j - 1]) / (u[j] - u[j - 1]) * (t[j] - t[j - 1]))
    return np.array(out)


def lammps_velocity(f, A, v0, dt, workdir, nprocs=1, margin=1.3, **extra):
    """Kink velocity of one LAMMPS run (A < 0: no rate keyword), run for
    `margin` times the time the A = 0 kink needs to pass the tracked blocks."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    t_end = margin * (TRACK[1] - SEED1 + 10) / fkme.vk_discrete(f, G, KC, UC, K, 1.0, GAMMA)
    var = dict(N=N, g=G, K=K, f=f, A=A, v0=v0, eta=GAMMA, dt=dt, steps=int(math.ceil(t_end / dt)),
               seed0=SEED0, seed1=SEED1, track1=TRACK[0], track2=TRACK[1], out=".")
    var.update(extra)
    run_lammps(INPUT, variables=var, nprocs=nprocs, cwd=workdir)
    tc = crossing_times(workdir / "track.dat")
    return (TRACK[1] - TRACK[0]) / (tc[1] - tc[0])


def lammps_extrapolated(f, A, v0, workdir, dt=DT, levels=2, margin=1.3):
    """Richardson: 2 v(dt/2) - v(dt) (and the same one level finer with
    levels = 3, whose difference from the first estimates its error)."""
    v = [lammps_velocity(f, A, v0, dt / 2 ** k, Path(workdir) / f"dt{k}", margin=margin)
         for k in range(levels)]
    ext = [2 * v[k + 1] - v[k] for k in range(levels - 1)]
    return v, ext


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="three forces")
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--doc-img", action="store_true", help="also write doc/src/img/eq_thermal_kink_rate.png")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    forces = (0.8, 1.0) if args.quick else (0.7, 0.8, 0.9, 1.0)
    A_me, v0, table = rate_from_me(out / "kink-rate")
    print(f"FRICTION-EQ eq-thermal kink rate: overdamped chain N = {N}, g = {G}, kc = uc = {KC}, "
          f"K = {K}, gamma = {GAMMA}, dt = {DT}")
    print(f"  eq-me {' '.join(EQME)} kinetic fk.dat {V_LO:g} {V_HI:g} 5:")
    print("    v: " + "  ".join(f"{r[0]:.3g}" for r in table) + "\n    F_k/(N k_c): "
          + "  ".join(f"{r[1]:.5f}" for r in table) + "\n    dF_k/dln v: "
          + "  ".join(f"{r[2]:.5f}" for r in table))
    print(f"  rate A = kc * secant slope = {A_me:.5f}, v0 = {v0:g} (A/(2 v0) = {A_me / (2 * v0):.4g} "
          f"< gamma = {GAMMA:g})")
    print("  v_k: LAMMPS (dt, dt/2 -> Richardson) / reference (RK4, implicit law) / rel. diff;"
          " A = 0 also against the exact travelling wave; slowdown 1 - v/v(A=0)")
    rows = []
    t0 = time.time()
    for f in forces:
        row = dict(f=f)
        for tag, A in (("0", 0.0), ("A", A_me)):
            v, ext = lammps_extrapolated(f, A, v0, out / "kink-rate" / f"f{f}-{tag}", margin=1.8)
            ref, err, wmax, wmin = reference_velocity(f, A, v0, h=0.2)
            row[tag] = dict(v=v, ext=ext[0], ref=ref, ref_err=err, wmax=wmax, wmin=wmin)
        row["exact"] = fkme.vk_discrete(f, G, KC, UC, K, 1.0, GAMMA)
        r0, rA = row["0"], row["A"]
        slow = 1 - rA["ref"] / r0["ref"]
        # the rate force lies between the viscous drags gamma_lo w and
        # gamma_hi w for 0 <= w <= wmax (concave): bounds of the slowdown
        g_hi = A_me / (2 * v0)
        g_lo = A_me * math.asinh(rA["wmax"] / (2 * v0)) / rA["wmax"]
        row["bounds"] = (1 - GAMMA / (GAMMA + g_lo), 1 - GAMMA / (GAMMA + g_hi))
        row["eta_T"] = A_me / rA["wmax"]
        row["slow"] = slow
        rows.append(row)
        print(f"  f = {f:5.3f}  A = 0:  {r0['v'][0]:.6f} {r0['v'][1]:.6f} -> {r0['ext']:.6f} / "
              f"{r0['ref']:.6f} / {r0['ext'] / r0['ref'] - 1:+.1e}   exact {row['exact']:.6f} "
              f"({r0['ref'] / row['exact'] - 1:+.1e})")
        print(f"             A > 0:  {rA['v'][0]:.6f} {rA['v'][1]:.6f} -> {rA['ext']:.6f} / "
              f"{rA['ref']:.6f} / {rA['ext'] / rA['ref'] - 1:+.1e}   slowdown {slow:.4f} "
              f"(viscous bounds [{row['bounds'][0]:.4f}, {row['bounds'][1]:.4f}]; "
              f"eta_T/eta = A/(u'_max gamma) = {row['eta_T'] / GAMMA:.4f}, u'_max = {rA['wmax']:.4g})")
    print(f"  time {time.time() - t0:.0f} s")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    fs = np.array([r["f"] for r in rows])
    ff = np.linspace(0.63, max(fs) + 0.02, 80)
    ax.plot(ff, [fkme.vk_discrete(x, G, KC, UC, K, 1.0, GAMMA) for x in ff], "k-", lw=0.8,
            label="exact travelling wave, A = 0")
    for tag, mk, lab in (("0", "o", "A = 0"), ("A", "s", f"A = {A_me:.4f}, v0 = {v0:g}")):
        ax.plot(fs, [r[tag]["ext"] for r in rows], mk, mfc="none", label=f"LAMMPS, {lab}")
        ax.plot(fs, [r[tag]["ref"] for r in rows], "+", ms=10, color="C3" if tag == "A" else "C2",
                label=f"reference, {lab}")
    ax.axvline(fkme.discrete_depinning_force(G, KC, UC, K)[1], color="0.6", ls=":", lw=0.8)
    ax.set_xlabel("driving force f")
    ax.set_ylabel("kink velocity v_k (sites per time)")
    ax.legend(fontsize=7)
    bx.plot(fs, [r["slow"] for r in rows], "s-", label="slowdown 1 - v_k(A)/v_k(0)")
    bx.plot(fs, [r["bounds"][0] for r in rows], "v--", label="viscous bound, secant A asinh/u'_max")
    bx.plot(fs, [r["eta_T"] / GAMMA for r in rows], "x:", label="eta_T/eta, eta_T = A/u'_max")
    bx.set_xlabel("driving force f")
    bx.set_ylabel("relative slowdown")
    bx.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "eq-thermal-kink-rate.png", dpi=110)
    if args.doc_img:
        fig.savefig(HERE.parents[1] / "doc" / "src" / "img" / "eq_thermal_kink_rate.png", dpi=80)
    print(f"  plot: {out / 'eq-thermal-kink-rate.png'}")


if __name__ == "__main__":
    main()
