#!/usr/bin/python3
"""Thermal creep of arrested kinks of the FK-ME chain (fix eq/substrate
thermal): v_creep against 1/T at two driving forces below the discrete
depinning force f_+, against the rate prediction.

Below f_+ a kink of the overdamped sawtooth chain is pinned (Peierls-
Nabarro); at T > 0 its front block, at the stretch u_1 = u_R + D r/(1+r) of
the static kink, hops to the next well at the rate nu(u_1) = omega exp(-
eps_a (1 - u_1/u_c)^(3/2) / k_B T) and the kink advances by one site.  The
prediction of the mean time per hop and front, W, is the renewal integral
W = int_0^inf exp(-H(t)) dt, H(t) = int_0^t sum_n nu(s_n(t')) dt', along the
relaxation s_n(t) of the chain after a hop of its front block, solved
exactly (the chain is linear between hops: eigen-decomposition), i.e.
1/nu(u_1) plus the dead time of the relaxation.  The creep velocity is
1/W sites per unit time and front; ln v is linear in 1/T with the
Arrhenius slope -eps_a (1 - u_1/u_c)^(3/2).

python3 creep.py [--quick]        (writes out/eq-thermal-creep.png; lmp from
                                   FEQ_LMP or ../../build/lmp)
"""
import argparse
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
from eqtools import run_lammps  # noqa: E402

INPUT = HERE / "in.eq-thermal-creep"
G, KC, UC, K, GAMMA, DT = 25.0, 1.0, 1.0, 0.07, 100.0, 0.1
# blocks SEED0+1 .. SEED1 slipped (64): the two kinks 64 sites apart through
# the slipped domain, and at least 48 through the unslipped part while the
# hops counted happen (their interaction shifts u_1 by ~ D r^48, a rate
# change below 1 %)
N, SEED0, SEED1 = 200, 68, 132
MAX_HOPS = N - (SEED1 - SEED0) - 48


def chain_matrix(n, g=G, kc=KC, K=K):
    L = np.zeros((n, n))
    for i in range(n):
        L[i, i] = -2 * g - kc - K
        L[i, (i + 1) % n] += g
        L[i, (i - 1) % n] += g
    return L


def static_kink(f, n=N, slipped=(SEED0, SEED1), g=G, kc=KC, uc=UC, K=K):
    """Stretches s_n of the static periodic chain with blocks slipped[0] ..
    slipped[1]-1 (0-based sites) in the next well, and the well origins."""
    a = np.where((np.arange(n) >= slipped[0]) & (np.arange(n) < slipped[1]), uc, 0.0)
    u = np.linalg.solve(-chain_matrix(n, g, kc, K), kc * a + f)
    return u - a, a


def front_stretch(f, g=G, kc=KC, uc=UC, K=K):
    """u_1 = u_R + D r/(1+r) of the static kink (fkme.discrete_depinning_force)."""
    kap = kc + K
    q = 1.0 + kap / (2.0 * g)
    r = q - math.sqrt(q * q - 1.0)
    return f / kap + kc * uc / kap * r / (1.0 + r)


def rate(s, theta, omega, uc=UC):
    u = np.clip(1.0 - np.abs(s) / uc, 0.0, None)
    return omega * np.exp(-u ** 1.5 / theta)


def predicted_wait(f, theta, omega, n=N, slipped=(SEED0, SEED1), g=G, kc=KC, uc=UC, K=K,
                   gamma=GAMMA):
    """(W, 1/nu_static): mean time per hop of the right front, the renewal
    integral along the exact relaxation after the hop of its front block
    (the blocks closer to it than to the other front), and the inverse of the static rate."""
    L = chain_matrix(n, g, kc, K)
    s, a = static_kink(f, n, slipped, g, kc, uc, K)
    m = slipped[1]
    a2 = a.copy()
    a2[m] += uc
    u0 = s + a
    u2 = np.linalg.solve(-L, kc * a2 + f)
    w, V = np.linalg.eigh(L / gamma)
    c0 = V.T @ (u0 - u2)
    idx = np.arange(m - (m - slipped[0]) // 2, m + (n - m + slipped[0]) // 2) % n
    nu_static = rate((u2 - a2)[idx], theta, omega, uc).sum()
    t = np.linspace(0.0, 60.0 / nu_static, 300001)
    S = u2[idx, None] + V[idx] @ (c0[:, None] * np.exp(np.outer(w, t))) - a2[idx, None]
    r = rate(S, theta, omega, uc).sum(axis=0)
    H = np.concatenate([[0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * np.diff(t))])
    surv = np.exp(-H)
    W = float(np.sum(0.5 * (surv[1:] + surv[:-1]) * np.diff(t)))
    return W, 1.0 / nu_static


def run_creep(f, T, steps, workdir, eps=1.0, omega=1.0, nprocs=1, every=10, tseed=4711, **extra):
    """One LAMMPS run; returns the times of the thermal hops (at `every`-step
    resolution: the time of the first print at which the count rose)."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    var = dict(N=N, seed0=SEED0, seed1=SEED1, f=f, T=T, eps=eps, omega=omega, tseed=tseed,
               steps=steps, every=every, out=".", g=G, K=K, eta=GAMMA, dt=DT)
    var.update(extra)
    run_lammps(INPUT, variables=var, nprocs=nprocs, cwd=workdir)
    d = np.loadtxt(workdir / "hops.dat")
    t, nh = d[:, 0], d[:, 1].astype(int)
    times = []
    prev = 0
    for k in range(len(t)):
        for _ in range(nh[k] - prev):
            times.append(t[k] - 0.5 * every * DT)    # mid-interval
        prev = nh[k]
    return np.array(times), t[-1]


def wait_estimate(times, t_end, max_hops=MAX_HOPS):
    """Mean time per hop and front (two fronts) from the first max_hops hops
    (or all of them, censored at t_end), and the number used."""
    if len(times) >= max_hops:
        return 2.0 * times[max_hops - 1] / max_hops, max_hops
    return (2.0 * t_end / len(times) if len(times) else math.inf), len(times)


def measure(f, x, workdir, omega=1.0, hops=MAX_HOPS, nprocs=1, tseed=None):
    """Creep at theta = b_1 / x (b_1 = (1 - u_1/u_c)^(3/2), eps_a = 1):
    measured and predicted W, and the count.  The seed of the budgets
    differs between (f, x) unless given: with one seed the blocks that hop
    draw the same budgets at every temperature, and the runs share their
    fluctuation (the mean of the 88 budgets of seed 4711 is 1.28)."""
    if tseed is None:
        tseed = 1000 + int(round(100 * f)) * 10 + int(round(x))
    b1 = (1.0 - front_stretch(f)) ** 1.5
    theta = b1 / x
    W, inv_nu = predicted_wait(f, theta, omega)
    steps = int(math.ceil(1.3 * hops * W / 2.0 / DT))
    times, t_end = run_creep(f, theta, steps, workdir, omega=omega, nprocs=nprocs, tseed=tseed)
    W_meas, n = wait_estimate(times, t_end, hops)
    return dict(f=f, theta=theta, b1=b1, W=W, inv_nu=inv_nu, W_meas=W_meas, n=n, steps=steps)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="two temperatures per force")
    ap.add_argument("--out", default=str(HERE / "out"))
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    xs = (6.0, 8.0) if args.quick else (6.0, 7.0, 8.0)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for f in (0.57, 0.60):
            for x in xs:
                r = measure(f, x, Path(tmp) / f"f{f}_x{x}")
                rows.append(r)
                print(f"f = {f:.2f}  theta = {r['theta']:.6g}  b1/theta = {x:.1f}  hops = {r['n']:3d}"
                      f"  W_meas = {r['W_meas']:9.1f}  W_pred = {r['W']:9.1f} (1/nu = {r['inv_nu']:.1f})"
                      f"  ratio = {r['W_meas'] / r['W']:.3f} +- {1 / math.sqrt(max(r['n'], 1)):.3f}",
                      flush=True)
    print("\nArrhenius slope of ln(1/(W - dead time)) against 1/theta (eps_a = 1):")
    for f in (0.57, 0.60):
        rr = [r for r in rows if r["f"] == f]
        xinv = np.array([1.0 / r["theta"] for r in rr])
        # the measured rate of the static front: 1/(W_meas - (W - 1/nu))
        y = np.array([-math.log(r["W_meas"] - (r["W"] - r["inv_nu"])) for r in rr])
        slope = np.polyfit(xinv, y, 1)[0]
        print(f"  f = {f:.2f}: slope = {slope:.5f}, -(1 - u_1)^(3/2) = {-rr[0]['b1']:.5f} "
              f"(u_1 = {front_stretch(f):.5f})")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4.2))
        for f, c in ((0.57, "C0"), (0.60, "C1")):
            rr = [r for r in rows if r["f"] == f]
            ax.errorbar([r["b1"] / r["theta"] for r in rr], [1 / r["W_meas"] for r in rr],
                        yerr=[1 / r["W_meas"] / math.sqrt(max(r["n"], 1)) for r in rr], fmt="o",
                        color=c, label=f"LAMMPS, f = {f}")
            xx = np.linspace(5.5, 8.5, 30)
            ax.plot([r["b1"] / r["theta"] for r in rr], [1 / r["W"] for r in rr], "-", color=c,
                    label=f"renewal prediction, f = {f}")
            ax.plot(xx, [math.exp(-x) for x in xx], ":", color="gray")
        ax.set_yscale("log")
        ax.set_xlabel(r"$\epsilon_a (1-u_1/u_c)^{3/2} / k_B T$")
        ax.set_ylabel("creep velocity per front (sites / time)")
        ax.set_title(r"FK-ME kink creep, g = 25, $\omega$ = 1 (dotted: $\omega e^{-x}$)")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(out / "eq-thermal-creep.png", dpi=120)
        print(f"wrote {out / 'eq-thermal-creep.png'}")
    except ImportError:
        print("(matplotlib not available: no plot)")


if __name__ == "__main__":
    main()
