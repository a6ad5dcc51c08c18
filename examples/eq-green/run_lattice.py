#!/usr/bin/python3
"""The paper's Sec. IV EQ lattice (4080 contacts, triangular, k_c = 1,
thresholds uniform [0.75, 1.25], quasi-static driving) with the interaction
computed from elasticity (eq-green table, gamma1 = 0.06, gamma2 = 0.3,
sigma = 0.3, cut at r = 10 a) against the analytic crossover form of
pair eq/elastic, k = ftilde / r up to lambda_c and ftilde lambda_c^2 / r^3
beyond, with
  lambda_c = the crossover length measured on the same solution
             (continuum fit on 257 x 257, r <= 40: 8.67 a; the sweep of
             run.py gives 0.51 a / gamma1 = 8.5 a), and
  ftilde   = chosen so that both kernels give the same mean field
             sum_j k_ij (the quantity that enters the mean-field ME of Sec. IV),
and against non-interacting contacts.  Prints the static peak, the kinetic
friction, avalanche statistics and the distance between the steady
distributions; writes out/lattice.png.

The kernel is computed on a square lattice and used, as a function of
distance and angle, on the triangular lattice (an approximation: the
elastic solution of the triangular lattice itself is not computed).  The
cut at 10 a drops the far tail: the script prints sum_j k_ij of the
longer table EQ_GREEN_G0.06_R30 cut at 10, 20 and 30 a.

    /usr/bin/python3 run_lattice.py [--xmax 4] [--seeds 4711 4712] [--out out]
"""
import argparse
import math
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import eqtools  # noqa: E402
import numpy as np  # noqa: E402

TABLE, KEY, GAMMA1 = "eq_green_g0.06.table", "EQ_GREEN_G0.06", 0.06
TABLE30 = "eq_green_g0.06_r30.table"    # same solution, tabulated to r = 30
RCUT = 10.0


def read_table(path):
    body = [l for l in Path(path).read_text().splitlines() if l.strip() and not l.startswith("#")]
    rows = np.array([[float(x) for x in l.split()] for l in body[2:]])
    return rows[:, 1], rows[:, 2], (rows[:, 3] if rows.shape[1] > 3 else 0 * rows[:, 2])


def table_kernel(r, phi, tr, k0, k2):
    """k(r, phi) as pair eq/elastic evaluates a table: r k interpolated
    linearly in r, k(r_1) r_1 / r below r_1, 0 beyond the last point."""
    rk0 = np.interp(r, tr, tr * k0)
    rk2 = np.interp(r, tr, tr * k2)
    k = (rk0 + rk2 * np.cos(2 * phi)) / r
    return np.where(r > tr[-1], 0.0, k)


def crossover_kernel(r, ftilde, lam):
    return np.where(r <= lam, ftilde / r, ftilde * lam ** 2 / r ** 3)


def lattice_vectors(rcut):
    """In-plane vectors to the neighbours within rcut on the triangular lattice (a = 1)."""
    n = int(rcut) + 2
    i, j = np.meshgrid(np.arange(-2 * n, 2 * n + 1), np.arange(-2 * n, 2 * n + 1))
    x = (i + 0.5 * j).ravel()
    y = (math.sqrt(3) / 2 * j).ravel()
    r = np.hypot(x, y)
    m = (r > 0) & (r <= rcut * (1 + 1e-12))
    return r[m], np.arctan2(y[m], x[m])


def matched_crossover(tr, k0, k2, lam, rcut=RCUT):
    r, phi = lattice_vectors(rcut)
    s_table = table_kernel(r, phi, tr, k0, k2).sum()
    s_unit = crossover_kernel(r, 1.0, lam).sum()
    return s_table / s_unit, s_table


def truncation_sums(cuts=(10.0, 20.0, 30.0)):
    """sum_j k_ij on the triangular lattice of the r <= 30 table cut at
    each of `cuts`: what the cut at RCUT leaves out of the far tail."""
    tr, k0, k2 = read_table(ROOT / "potentials" / TABLE30)
    out = []
    for c in cuts:
        r, phi = lattice_vectors(c)
        out.append(float(table_kernel(r, phi, tr, k0, k2).sum()))
    return out


def run(coeff, out, seed, xmax, xhist):
    d = Path(out)
    d.mkdir(parents=True, exist_ok=True)
    eqtools.run_lammps(HERE / "in.eq-green-lattice",
                       {"coeff": coeff, "rcut": RCUT, "seed": seed, "Xmax": xmax,
                        "Xhist": xhist, "out": d}, cwd=d,
                       extra=[])
    F = eqtools.load(d / "F.dat")
    av = np.atleast_2d(np.loadtxt(d / "avalanches.dat"))
    c, n, tot = eqtools.read_histo(d / "Qs.dat")
    return dict(X=F[:, 1], F=F[:, 2], av=av, qc=c, q=n / tot / (c[1] - c[0]))


def stats(r, xhist):
    X, F = r["X"], r["F"]
    early = X < 1.5
    ip = int(np.argmax(F[early]))
    late = X > xhist
    # kinetic friction: average over X (F piecewise constant between avalanches
    # is sampled at every step; weight by the advance)
    w = np.diff(X[late], append=X[late][-1])
    fk = float(np.sum(F[late] * w) / np.sum(w))
    sizes = r["av"][:, 1] if r["av"].size else np.array([0.0])
    return dict(Fs=float(F[early][ip]), Xs=float(X[early][ip]), Fk=fk,
                mean_av=float(sizes.mean()), max_av=int(sizes.max()))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(HERE / "out" / "lattice"))
    ap.add_argument("--xmax", type=float, default=4.0)
    ap.add_argument("--xhist", type=float, default=2.0)
    ap.add_argument("--seeds", type=int, nargs="+", default=[4711, 4712])
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)

    # the crossover length of the same elastic solution (eq-green summary)
    s = eqtools.run_eqgreen(["L", 257, "gamma1", GAMMA1, "rmax", 40], cwd=out)
    lam = s["crossover_lambda_continuum"]
    tr, k0, k2 = read_table(ROOT / "potentials" / TABLE)
    ftilde, ssum = matched_crossover(tr, k0, k2, lam)
    kernels = {
        "elastic table": f"table {ROOT / 'potentials' / TABLE} {KEY}",
        "crossover": f"{ftilde:.8g} {lam:.8g}",
        "none": "0 1",
    }
    print(f"kernel from eq-green (gamma1 = {GAMMA1}): {TABLE} {KEY}, cut at {RCUT} a; "
          f"sum_j k_ij = {ssum:.4f} k_c (triangular lattice)")
    print(f"analytic crossover form: lambda_c = {lam:.3f} a (measured), ftilde = {ftilde:.5f} "
          f"k_c a (same sum_j k_ij); table near zone: r k0(r) = {tr[0] * k0[0]:.5f} (r = 1), "
          f"{tr[2] * k0[2]:.5f} (r = 3)")
    tsum = truncation_sums()
    print(f"far tail cut off: sum_j k_ij of {TABLE30} cut at 10, 20, 30 a = "
          + ", ".join(f"{x:.4f}" for x in tsum) + " k_c")
    res = {}
    for name, coeff in kernels.items():
        runs = [run(coeff, out / f"{name.split()[0]}_{sd}", sd, a.xmax, a.xhist)
                for sd in a.seeds]
        st = [stats(r, a.xhist) for r in runs]
        res[name] = dict(runs=runs, st=st)
    print(f"N = 4080, X <= {a.xmax}, seeds {a.seeds} (mean +- standard error over seeds)")
    print("  kernel          F_s/(N k_c)         X_s       F_k/(N k_c) (X > %g)   mean aval.  max aval."
          % a.xhist)
    for name, r in res.items():
        v = {k: np.array([s[k] for s in r["st"]]) for k in r["st"][0]}
        se = lambda x: x.std(ddof=1) / math.sqrt(len(x)) if len(x) > 1 else float("nan")  # noqa
        print(f"  {name:<14}  {v['Fs'].mean():.5f} +- {se(v['Fs']):.5f}  {v['Xs'].mean():.3f}"
              f"     {v['Fk'].mean():.5f} +- {se(v['Fk']):.5f}          {v['mean_av'].mean():6.3f}"
              f"     {v['max_av'].max():5d}")
        r["summary"] = {k: (float(x.mean()), float(se(x))) for k, x in v.items()}
    # steady distributions: L1 distance between the kernels
    q = {n: np.mean([x["q"] for x in r["runs"]], axis=0) for n, r in res.items()}
    c = res["none"]["runs"][0]["qc"]
    w = c[1] - c[0]
    for a_, b_ in (("elastic table", "crossover"), ("elastic table", "none")):
        print(f"  int |Q_s({a_}) - Q_s({b_})| dx = {np.sum(np.abs(q[a_] - q[b_])) * w:.4f}")
    if not a.no_plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        for name, col in (("none", "gray"), ("crossover", "tab:blue"), ("elastic table", "tab:red")):
            r0 = res[name]["runs"][0]
            ax[0].plot(r0["X"], r0["F"], color=col, lw=0.8, label=name)
            ax[1].plot(c, q[name], color=col, label=name)
        ax[0].set_xlabel("X")
        ax[0].set_ylabel(r"$F/(N k_c)$")
        ax[0].legend()
        ax[1].set_xlabel("stretch x")
        ax[1].set_ylabel(r"$Q_s(x)$")
        fig.suptitle(r"Sec. IV lattice: elastic kernel ($\gamma_1=0.06$) vs crossover form", fontsize=10)
        fig.tight_layout()
        fig.savefig(out.parent / "lattice.png", dpi=120)
    return res, dict(ftilde=ftilde, lam=lam, ksum=ssum, tail_sums=tsum)


if __name__ == "__main__":
    main()
