#!/usr/bin/python3
"""FK-ME chain and frictional cracks (paper Sec. V B) with fix eq/substrate.

    /usr/bin/python3 run.py [--part a04|a05|a03|underdamped|integrators|all]
                            [--N 3000] [--out out]

Parts (each prints a summary with the references and writes a PNG):

a04          Fig. crack.A04a: N blocks, g = 25, sawtooth k_c = u_c = 1,
             K = 0.07, stage at v = 1e-4, two central blocks k_c' = 0.5;
             when the kinks run, k_c is restored and the stage reverses to
             v_b = -2e-4.  Panels: kink centres (maximal block velocity)
             against t, driving force f(t), mean chain velocity, and the PN
             oscillation of the maximal velocity.  Checks: the nucleation
             force against the static chain (linear algebra), the arrest
             force against the discrete depinning force f_+, the PN
             frequency against v_k/a.
a05          Fig. crack.A05: v_k(f) = N(<u_dot> - v_bar)/(n_k jump) from the
             same protocol for g = 5 (v_b = -4e-5) and g = 25 (v_b = -2e-4)
             against Eq. crack.eqi04, the low-velocity law Eq. crack.v1 with
             the kink mass Eq. crack.v1a, the exact velocity of the discrete
             chain, f_min and f_max.  The paper uses N = 3e4 (--N 30000).
a03          Fig. crack.A03ab: colour map of block velocities (n, t) for the
             smooth substrate force k_c [tanh u + 1.5 e^-u sin 3u].
underdamped  m = 1 and eta = 100, 10, 3, 1 (fix nve + fix viscous): v_k at
             constant f against Eq. crack.eqi04 and its inertia-corrected
             form (g -> g (1 - v_k^2/c_0^2)), which tends to c_0 at f_max.
integrators  error of v_k (g = 25, f = 0.95) against the exact discrete
             velocity for fix brownian and fix nve + viscous (eta = 100),
             crossing exact and step, at several time steps.
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

CHAIN = HERE / "in.eq-fkme-chain"
KINK = HERE / "in.eq-fkme-kink"
KC, UC, K, M, ETA = 1.0, 1.0, 0.07, 1.0, 100.0


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
    return plt.subplots(nrows, ncols, figsize=size)


def f_nucleation(N, g, kc_weak, nweak=2):
    """Driving force at which the static chain puts the weak central blocks
    at u_c: the displacements solve (kc_n + K) u_n - g (u_n+1 + u_n-1 - 2 u_n)
    = f, linear in f."""
    kc = fkme.weak_center_kc(N, KC, kc_weak, nweak)
    A = np.diag(kc + K + 2 * g) - g * (np.eye(N, k=1) + np.eye(N, k=-1))
    A[0, -1] = A[-1, 0] = -g                      # periodic
    return UC / np.linalg.solve(A, np.ones(N)).max()


# ------------------------------------------------------------ the protocol
def protocol(out, N, g, vb, shape="sawtooth", f0=None, dump=500, tmax=None, kweak=0.5,
             every=500):
    """Run in.eq-fkme-chain; returns a dict with the series, the fine
    series, the start time and the dump (if any)."""
    if f0 is None:
        # start a little below the nucleation force (shorter loading)
        f0 = f_nucleation(min(N, 400), g, kweak) - 0.01 if shape == "sawtooth" else 0.6
    if tmax is None:
        # until f has fallen to f_min - 0.03 (all kinks stopped)
        tmax = (f0 + 0.01 - (fkme.f_min(KC, UC, K) - 0.03)) / (K * abs(vb))
    pn = min(20000, round(tmax / 0.1))          # steps sampled every 10 after the reversal
    wall = lammps(CHAIN, out, N=N, g=g, shape=shape, f0=f0, vb=vb, tmax=round(tmax),
                  dump=dump, every=every, kweak=kweak, pn=pn)
    log = (Path(out) / "log.lammps").read_text()
    line = [x for x in log.splitlines() if x.startswith("FKME kinks started")][0]
    tstart, fstart = float(line.split()[6].rstrip(",")), float(line.split()[-1])
    r = {"N": N, "g": g, "vb": vb, "tstart": tstart, "fstart": fstart, "wall": wall,
         "series": fkme.read_ave_time(Path(out) / "series.dat"),
         "load": fkme.read_ave_time(Path(out) / "load.dat"),
         "fine": fkme.read_ave_time(Path(out) / "fine.dat"), "dt": 0.1}
    if dump:
        steps, cols = fkme.read_dump(Path(out) / "chain.dump", ["id", "vx"])
        r["dump_t"] = steps * r["dt"]
        r["dump_v"] = cols["vx"]
    return r


def running(r, settle=500.0):
    """Samples of the series while the kinks run steadily: from `settle`
    time units after the start (acceleration of the new kinks) to the
    arrest (the last change of the slip count)."""
    s = r["series"]
    t = s["TimeStep"] * r["dt"]
    last = np.nonzero(s["v_slips"] < s["v_slips"][-1] - 0.5)[0]
    tend = t[last[-1]] if len(last) else t[0]
    return (t > r["tstart"] + settle) & (t <= tend)


def vk_from_mean(r, nbins=40):
    """v_k(f) = N(<u_dot> - v_bar)/(n_k jump) of the two kinks from the mean
    chain velocity (averaged over the series' interval), in nbins bins of f."""
    s = r["series"]
    vbar = fkme.background_velocity(r["vb"], KC, K)
    jump = fkme.kink_jump(KC, UC, K)
    run = running(r)
    return fkme.vk_curve_from_mean(s["v_f"][run], s["v_vmean"][run], r["N"], 2, vbar, jump,
                                   nbins)


def vk_from_slips(r, nbins=40):
    """v_k(f) from the slip count: each kink passage over a block is one
    slip, so v_k = (d slips/dt)/n_k; slope of slips(t) in each bin of f."""
    s = r["series"]
    run = running(r)
    t, f, sl = s["TimeStep"][run] * r["dt"], s["v_f"][run], s["v_slips"][run]
    edges = np.linspace(f.min(), f.max(), nbins + 1)
    fb, vk = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        sel = (f >= a) & (f <= b)
        if sel.sum() >= 3:
            fb.append(f[sel].mean())
            vk.append(np.polyfit(t[sel], sl[sel], 1)[0] / 2.0)
    return np.array(fb), np.array(vk)


def band(f, dev, fmin):
    """'min .. max' of the relative deviations dev over the bins f >= fmin."""
    d = dev[f >= fmin]
    return f"{d.min():+.4f} .. {d.max():+.4f} ({len(d)} bins)" if len(d) else "no bins"


def arrest_force(r):
    """Driving force at the last change of the slip count (to the series'
    interval)."""
    s = r["series"]
    last = np.nonzero(s["v_slips"] < s["v_slips"][-1] - 0.5)[0]
    return s["v_f"][min(last[-1] + 1, len(s["v_f"]) - 1)] if len(last) else math.nan


def pn_frequency(r):
    """Dominant frequency of the maximal block velocity in the finely
    sampled window after the reversal (the PN oscillation) and the mean
    kink velocity there from <u_dot>."""
    s = r["fine"]
    t = s["TimeStep"] * r["dt"]
    sel = t > t[0] + 0.25 * (t[-1] - t[0])           # transient of the reversal
    t, v = t[sel], s["v_vmx"][sel]
    v = v - v.mean()
    w = np.hanning(len(v))
    spec = np.abs(np.fft.rfft(v * w)) ** 2
    freq = np.fft.rfftfreq(len(v), t[1] - t[0])
    k = np.argmax(spec[1:]) + 1
    if 1 <= k < len(spec) - 1:                        # parabolic peak interpolation
        a, b, c = np.log(spec[k - 1:k + 2])
        k = k + 0.5 * (a - c) / (a - 2 * b + c)
    nu = k * (freq[1] - freq[0])
    vbar = fkme.background_velocity(r["vb"], KC, K)
    vk = fkme.kink_velocity_from_mean(s["v_vmean"][sel], r["N"], 2, vbar,
                                      fkme.kink_jump(KC, UC, K)).mean()
    return nu, vk, t, s["v_vmx"][sel], s["v_f"][sel]


# ------------------------------------------------------------------ a04
def part_a04(out, N):
    r = protocol(out / "a04", N, 25.0, -2e-4)
    fini = f_nucleation(N, 25.0, 0.5)
    fm, fp = fkme.discrete_depinning_force(25.0, KC, UC, K)
    farr = arrest_force(r)
    nu, vk_pn, tf, vf, ff = pn_frequency(r)
    # slow kinks near the arrest move by hops: between them their fastest
    # block is slower than 1e-3, but faster than the background |v_bar|
    kinks = fkme.find_kinks(r["dump_v"], threshold=1e-4, min_separation=20)
    tracks = [tr for tr in fkme.track_kinks(r["dump_t"], kinks, N, max_jump=50.0)
              if len(tr[0]) > 5]
    fb, vk = vk_from_mean(r)
    vd = np.array([fkme.vk_discrete(x, 25.0, KC, UC, K, M, ETA) for x in fb])
    fs, vs = vk_from_slips(r)
    vds = np.array([fkme.vk_discrete(x, 25.0, KC, UC, K, M, ETA) for x in fs])
    lines = [
        f"# a04: N = {N}, g = 25, sawtooth, K = 0.07, v = 1e-4 -> v_b = -2e-4, eta = 100, "
        f"fix brownian dt 0.1 (wall {r['wall']:.0f} s)",
        f"  kinks start at f = {r['fstart']:.5f} (t = {r['tstart']:.0f}); static chain with "
        f"k_c' = 0.5: f_ini = {fini:.5f}",
        f"  kinks stop at f = {farr:.4f}; discrete depinning force f_+ = {fp:.4f} "
        f"(continuum Griffith f_min = {fkme.f_min(KC, UC, K):.3f})",
        f"  PN oscillation of max velocity: frequency {nu:.5f} per time unit; "
        f"v_k/a from <u_dot> = {vk_pn:.5f} (ratio {nu / vk_pn:.4f})",
        f"  v_k from the slip count / exact discrete-chain velocity - 1 for "
        f"f >= f_+ + 0.04: {band(fs, vs / vds - 1, fp + 0.04)}",
        f"  v_k(f) against the exact discrete-chain velocity, {len(fs)} bins of f in "
        f"[{fs.min():.3f}, {fs.max():.3f}]: from the slip count rms rel. dev. "
        f"{np.sqrt(np.mean((vs / vds - 1) ** 2)):.4f} (max {np.max(np.abs(vs / vds - 1)):.4f}); "
        f"from <u_dot> (paper's formula with the jump factor) rms "
        f"{np.sqrt(np.mean((vk / vd - 1) ** 2)):.4f}",
        f"  {len(tracks)} kink tracks"]
    text = "\n".join(lines)
    print(text)
    (out / "summary_a04.txt").write_text(text + "\n")

    fig, ax = figure(4, 1, (7, 10))
    for t, x in tracks:
        ax[0].plot(t, x, ".", ms=1.5)
    ax[0].set_ylabel("kink centre n")
    s = r["series"]
    ts = s["TimeStep"] * r["dt"]
    ax[1].plot(ts, s["v_f"])
    ax[1].axhline(fp, ls=":", c="k", lw=0.8)
    ax[1].set_ylabel("f(t)")
    ax[2].plot(ts, s["v_vmean"])
    ax[2].set_ylabel(r"$\langle \dot u \rangle$")
    z = tf < tf[0] + 300.0
    ax[3].plot(tf[z], vf[z], lw=0.8)
    ax[3].set_ylabel(r"max$_n \dot u_n$")
    ax[3].set_title(f"PN oscillation: frequency {nu:.4f} = v_k/a ({vk_pn:.4f})", fontsize=9)
    ax[3].set_xlabel("t")
    ax[0].set_title("Fig. crack.A04a: two kinks from two weak blocks, stage reversed")
    fig.tight_layout()
    fig.savefig(out / "a04.png", dpi=90)
    print("  wrote", out / "a04.png")
    return r


# ------------------------------------------------------------------ a05
def part_a05(out, N, gs=(5.0, 25.0)):
    res = {}
    fig, ax = figure(1, len(gs), (5.5 * len(gs), 4.2))
    ax = np.atleast_1d(ax)
    lines = [f"# a05: v_k(f) from the slip count and from N(<u_dot> - v_bar)/(2 jump), N = {N}"]
    vbs = {5.0: -4e-5, 25.0: -2e-4}          # the paper's reversal velocities
    for k, g in enumerate(gs):
        vb = vbs.get(g, -2e-4)
        r = protocol(out / f"a05_g{g:g}", N, g, vb, dump=0)
        fb, vk = vk_from_mean(r)
        fs, vs = vk_from_slips(r)
        fp = fkme.discrete_depinning_force(g, KC, UC, K)[1]
        vd = np.array([fkme.vk_discrete(x, g, KC, UC, K, M, ETA) for x in fs])
        vc = fkme.vk_overdamped(fs, g, KC, UC, K, M, ETA)
        vdm = np.array([fkme.vk_discrete(x, g, KC, UC, K, M, ETA) for x in fb])
        lines.append(
            f"  g = {g:g}, v_b = {vb:g} (wall {r['wall']:.0f} s): kinks start at f = "
            f"{r['fstart']:.4f}, stop at f = {arrest_force(r):.4f} (f_+ = {fp:.4f})\n"
            f"    v_k from the slip count vs exact discrete chain: rms rel. dev. "
            f"{np.sqrt(np.mean((vs / vd - 1) ** 2)):.4f}, max {np.max(np.abs(vs / vd - 1)):.4f}"
            f"; from <u_dot>: rms {np.sqrt(np.mean((vk / vdm - 1) ** 2)):.4f}\n"
            f"    slip count for f >= f_+ + 0.04: {band(fs, vs / vd - 1, fp + 0.04)}\n"
            f"    vs Eq. crack.eqi04 (continuum): {np.nanmin(vs / vc - 1):+.3f} .. "
            f"{np.nanmax(vs / vc - 1):+.3f} for f in [{fs.min():.3f}, {fs.max():.3f}]")
        ff = np.linspace(fkme.f_min(KC, UC, K) + 1e-4, 1.0, 300)
        a = ax[k]
        a.plot(fb, vk, "o", ms=3, mfc="none", label="LAMMPS, N(<u_dot> - v_bar)/(n_k jump)")
        a.plot(fs, vs, "x", ms=4, label="LAMMPS, slip count / n_k")
        a.plot(ff, fkme.vk_overdamped(ff, g, KC, UC, K, M, ETA), "b-", label="Eq. crack.eqi04")
        a.plot(ff, fkme.vk_low(ff, g, KC, UC, K, M, ETA), "r--", label="Eq. crack.v1")
        fd = np.linspace(fp + 1e-3, 1.0, 60)
        a.plot(fd, [fkme.vk_discrete(x, g, KC, UC, K, M, ETA) for x in fd], "k:",
               label="discrete chain, exact")
        for x in (fkme.f_min(KC, UC, K), fkme.f_max(KC, UC, K)):
            a.axvline(x, c="grey", lw=0.8)
        a.set_xlim(0.5, 1.08)
        a.set_ylim(0, 1.2 * np.nanmax(vk))
        a.set_xlabel("f")
        a.set_ylabel("v_k")
        a.set_title(f"g = {g:g}")
        a.legend(fontsize=7)
        res[g] = (fb, vk, vd)
    text = "\n".join(lines)
    print(text)
    (out / "summary_a05.txt").write_text(text + "\n")
    fig.tight_layout()
    fig.savefig(out / "a05.png", dpi=90)
    print("  wrote", out / "a05.png")
    return res


# ------------------------------------------------------------------ a03
def part_a03(out, N):
    n = min(N, 1000)
    # the stage keeps moving forward (v = 1e-4 throughout), k_c restored once
    # the kinks run; they sweep the chain and annihilate on the far side.
    # f0 = 1.34: just below the nucleation force of the weak pair (1.362)
    r = protocol(out / "a03", n, 25.0, 1e-4, shape="smooth", f0=1.34, dump=400, tmax=12000)
    s = r["series"]
    ts = s["TimeStep"] * r["dt"]
    done = ts[np.nonzero(s["v_slips"] >= s["v_slips"][-1] - 0.5)[0][0]]
    text = (f"# a03: smooth F_s, N = {n}, g = 25, stage at v = 1e-4: kinks start at f = "
            f"{r['fstart']:.4f} (t = {r['tstart']:.0f}); every block has slipped once "
            f"{done - r['tstart']:.0f} time units later, slip count "
            f"{s['v_slips'][-1] - s['v_slips'][0]:.0f} (N = {n}); wall {r['wall']:.0f} s")
    print(text)
    (out / "summary_a03.txt").write_text(text + "\n")
    fig, ax = figure(1, 1, (7, 4.5))
    fkme.plot_spacetime(r["tstart"] + r["dump_t"] - r["dump_t"][0], r["dump_v"], ax=ax,
                        title="Fig. crack.A03ab: block velocities, smooth F_s")
    fig.tight_layout()
    fig.savefig(out / "a03.png", dpi=90)
    print("  wrote", out / "a03.png")


# ------------------------------------------------------- constant-f kinks
def crossing_times(track, first, uc=UC):
    t = track[:, 0]
    out = []
    for k in range(track.shape[1] - 1):
        u = track[:, k + 1] - (first + k - 1)
        j = np.nonzero(u >= uc)[0]
        if len(j) == 0 or j[0] == 0:
            out.append(np.nan)
            continue
        j = j[0]
        out.append(t[j - 1] + (uc - u[j - 1]) / (u[j] - u[j - 1]) * (t[j] - t[j - 1]))
    return np.array(out)


def kink_speed(out, f, g, integ="brownian", eta=ETA, dt=0.1, cross="exact", N=200,
               seed=(80, 120), track=151, v_guess=None):
    """Velocity of the right kink at constant f from the crossing times of
    blocks track .. track+4."""
    if v_guess is None:
        v_guess = fkme.vk_discrete(f, g, KC, UC, K, M, eta) if integ == "brownian" else \
            fkme.vk_inertial(f, g, KC, UC, K, M, eta)
    tmax = (track + 5 - seed[1]) / v_guess * 1.3 + 200.0
    lammps(KINK, out, f=f, g=g, integ=integ, eta=eta, dt=dt, cross=cross, N=N,
           seed0=seed[0], seed1=seed[1], track=track, tmax=round(tmax))
    tc = crossing_times(np.loadtxt(Path(out) / "track.dat"), track)
    return 4.0 / (tc[-1] - tc[0])


def part_underdamped(out):
    g, N = 25.0, 500
    fs = (0.75, 0.85, 0.95, 1.0)
    lines = [f"# underdamped: g = {g:g}, m = 1, fix nve + fix viscous, dt min(0.02, 0.5/eta), v_k at "
             "constant f (blocks 151+..155+ beyond a 40-block seed)"]
    lines.append("  eta     f     v_k LAMMPS   eqi04 (no inertia)   inertia-corrected   "
                 "LAMMPS/corrected - 1   c0")
    data = []
    for eta in (100.0, 10.0, 3.0, 1.0):
        for f in fs:
            # fix viscous is stable for dt < 2/eta; Verlet for dt < 2/sqrt(4 g + kc + K)
            v = kink_speed(out / "underdamped", f, g, integ="nve", eta=eta,
                           dt=min(0.02, 0.5 / eta), N=N, seed=(80, 120), track=300)
            vc = fkme.vk_overdamped(f, g, KC, UC, K, M, eta)
            vi = fkme.vk_inertial(f, g, KC, UC, K, M, eta)
            data.append((eta, f, v, vc, vi))
            lines.append(f"  {eta:5g}  {f:5.2f}  {v:10.5f}   {vc:10.5f}           {vi:10.5f}"
                         f"          {v / vi - 1:+.3f}                 "
                         f"{fkme.sound_speed(g, M):.3f}")
    text = "\n".join(lines)
    print(text)
    (out / "summary_underdamped.txt").write_text(text + "\n")
    d = np.array(data)
    fig, ax = figure(1, 1, (6, 4.2))
    ff = np.linspace(0.6, 1.065, 200)
    for k, eta in enumerate((100.0, 10.0, 3.0, 1.0)):
        c = f"C{k}"
        s = d[:, 0] == eta
        ax.plot(d[s, 1], d[s, 2] * eta, "o", c=c, label=f"eta = {eta:g}")
        ax.plot(ff, fkme.vk_inertial(ff, g, KC, UC, K, M, eta) * eta, "-", c=c, lw=1)
    ax.plot(ff, fkme.vk_overdamped(ff, g, KC, UC, K, M, 1.0), "k--", lw=1,
            label="eqi04 (eta v_k, no inertia)")
    ax.set_xlabel("f")
    ax.set_ylabel(r"$\eta\, v_k$")
    ax.set_title("lines: inertia-corrected eqi04")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "underdamped.png", dpi=90)
    print("  wrote", out / "underdamped.png")
    return d


def part_integrators(out):
    g, f = 25.0, 0.95
    vd = fkme.vk_discrete(f, g, KC, UC, K, M, ETA)
    # fix nve + viscous is stable for dt < 2/eta only
    dts = {"brownian": (0.2, 0.1, 0.05, 0.025), "nve": (0.01, 0.005, 0.0025, 0.00125)}
    lines = [f"# integrators: g = 25, f = 0.95, eta = 100; exact discrete v_k = {vd:.7f} "
             "(overdamped; inertia changes it by < 1e-3 at eta = 100)",
             "  integrator         crossing   dt      v_k         rel. error   wall[s]"]
    res = {}
    for integ in ("brownian", "nve"):
        for cross in ("exact", "step"):
            for dt in dts[integ]:
                t0 = time.time()
                v = kink_speed(out / "integrators", f, g, integ=integ, dt=dt, cross=cross,
                               v_guess=vd)
                res[(integ, cross, dt)] = v / vd - 1
                name = "brownian rng none" if integ == "brownian" else "nve + viscous"
                lines.append(f"  {name:18s} {cross:8s}  {dt:5.3f}  {v:.7f}  {v / vd - 1:+.2e}"
                             f"    {time.time() - t0:.1f}")
    for integ in ("brownian", "nve"):
        d = dts[integ]
        e0, e1, e2 = (res[(integ, "exact", x)] for x in d[1:])
        lines.append(f"  {integ} exact: Richardson (dt {d[2]:g}, {d[3]:g}) error "
                     f"{2 * e2 - e1:+.1e}; observed order "
                     f"{math.log2(abs(e0 - e1) / abs(e1 - e2)):.2f}")
    text = "\n".join(lines)
    print(text)
    (out / "summary_integrators.txt").write_text(text + "\n")
    fig, ax = figure(1, 1, (5.5, 4))
    for integ, mk in (("brownian", "o"), ("nve", "s")):
        for cross, ls in (("exact", "-"), ("step", ":")):
            ax.loglog(dts[integ], [abs(res[(integ, cross, dt)]) for dt in dts[integ]],
                      mk + ls, label=f"{integ} {cross}")
    x = np.array([1e-3, 0.2])
    ax.loglog(x, 7e-3 * x, "k--", lw=0.8, label="~dt")
    ax.set_xlabel("dt")
    ax.set_ylabel("|v_k / v_k,exact - 1|")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "integrators.png", dpi=90)
    print("  wrote", out / "integrators.png")
    return res


def part_hysteresis(out, N=3000, g=25.0, vb=-1e-3):
    """The paper's outlook: the driving force rises until the weak pair
    nucleates kinks (pinned on the way up), then falls while the kinks run
    (sliding on the way down) until they stop at f_+: the loop of the mean
    velocity (above the stage's creep) against f."""
    fini = f_nucleation(N, g, 0.5)
    fm, fp = fkme.discrete_depinning_force(g, KC, UC, K)
    r = protocol(out / "hysteresis", N, g, vb, f0=fini - 0.05, dump=0, every=100)
    ld, s = r["load"], r["series"]
    farr = arrest_force(r)
    vbar_up = fkme.background_velocity(1e-4, KC, K)
    vbar_dn = fkme.background_velocity(vb, KC, K)
    print(f"# hysteresis: N = {N}, g = {g}, up at v = 1e-4, down at v_b = {vb} (wall "
          f"{r['wall']:.0f} s)\n"
          f"  way up: pinned until f = {r['fstart']:.4f} (static chain with the weak pair: "
          f"{fini:.4f}; uniform chain f_max = {fkme.f_max(KC, UC, K):.3f})\n"
          f"  way down: sliding until f = {farr:.4f} (discrete depinning force f_+ = {fp:.4f}, "
          f"Griffith f_min = {fkme.f_min(KC, UC, K):.3f}); loop width {r['fstart'] - farr:.4f}")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(ld["v_f"], ld["v_vmean"] - vbar_up, "C0-", label="f rising (pinned)")
    ax.plot(s["v_f"], s["v_vmean"] - vbar_dn, "C3-", label="f falling (kinks run)")
    for x, lab, ls in ((fini, "nucleation", "--"), (fp, "$f_+$", ":"),
                       (fkme.f_min(KC, UC, K), "Griffith $f_{min}$", "-.")):
        ax.axvline(x, color="k", ls=ls, lw=0.8, label=lab)
    ax.set_xlabel("driving force f = K X_s")
    ax.set_ylabel("<du/dt> above the stage's creep")
    ax.set_title("FK-ME chain: hysteresis of depinning and arrest")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "eq-fkme-hysteresis.png", dpi=110)
    print(f"  plot: {out / 'eq-fkme-hysteresis.png'}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--part", nargs="+", default=["all"],
                    choices=["a04", "a05", "a03", "underdamped", "integrators", "hysteresis",
                             "all"])
    ap.add_argument("--N", type=int, default=3000, help="chain length (a04, a05, a03)")
    ap.add_argument("--gs", type=float, nargs="+", default=[5.0, 25.0],
                    help="a05: couplings g (v_b = -4e-5 for g = 5, else -2e-4)")
    ap.add_argument("--out", default=str(HERE / "out"))
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    parts = (["a04", "a05", "a03", "underdamped", "integrators", "hysteresis"] if "all" in a.part
             else a.part)
    for p in parts:
        t0 = time.time()
        if p == "a04":
            part_a04(out, a.N)
        elif p == "a05":
            part_a05(out, a.N, tuple(a.gs))
        elif p == "a03":
            part_a03(out, a.N)
        elif p == "underdamped":
            part_underdamped(out)
        elif p == "integrators":
            part_integrators(out)
        elif p == "hysteresis":
            part_hysteresis(out, a.N)
        print(f"  ({p}: {time.time() - t0:.0f} s)")


if __name__ == "__main__":
    main()
