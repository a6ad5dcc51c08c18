#!/usr/bin/python3
"""Accuracy per cost: run time against error, for the master-equation
solver and for the EQ simulation (fix eq/contacts).

1. ME solver (eq-me): max |F - F_ref|/(N k_c) over X in [0, 8] against the
   grid step dx, plain second-order scheme and Richardson (dx, dx/2):
   - uniform thresholds [0.75,1.25]: reference = exact renewal solution;
   - realistic thresholds, reform gaussian 0.3 0.1: reference = Richardson
     at dx = 2.5e-4 (third order there: error ~1e-13).
2. EQ model, rigid slider, N contacts: the discretization error of
   F(X) at the sample points, measured with common random numbers (the
   same seed: with crossing exact the break sequence does not depend on
   dX, so F_exact is the step-free result of that realization; with
   crossing step a contact re-forms at the end of the step), against the
   run time; the statistical error sd/sqrt(N) is the floor any method
   reaches at that N.

Prints both tables and writes out/accuracy.png.
"""
import argparse
import math
import re
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402
import numpy as np  # noqa: E402

RIGID = HERE.parents[0] / "eq-rigid" / "in.eq-rigid"


def me_table(out):
    rows = []
    unif = ["threshold", "uniform", 0.75, 1.25, "xmax", 8]
    real = ["threshold", "realistic", 1.0, "reform", "gaussian", 0.3, 0.1, "xmax", 8]
    eqtools.run_eqme(real + ["dx", 2.5e-4, "force", "ref.dat"], cwd=out)
    ref = eqtools.load(out / "ref.dat")
    for name, args in (("uniform", unif), ("realistic", real)):
        for rich in ("no", "yes"):
            for dx in (0.016, 0.008, 0.004, 0.002, 0.001, 0.0005):
                extra = ["dx", dx, "richardson", rich, "force", "f.dat"]
                if name == "uniform":
                    extra += ["exact", "e.dat"]
                s = eqtools.run_eqme(args + extra, cwd=out)
                if name == "uniform":
                    err = s["exact_max_error"]
                else:
                    f = eqtools.load(out / "f.dat")
                    k = np.rint(f[:, 0] / 2.5e-4).astype(int)
                    err = float(np.max(np.abs(f[:, 1] - ref[k, 1])))
                rows.append((name, rich, dx, s["seconds"], err))
    return rows


def eq_table(out, nx, ny, seed):
    rows = []
    me = eqtools.run_eqme(["threshold", "uniform", 0.75, 1.25, "xmax", 8, "dx", 1e-3,
                           "force", "me.dat"], cwd=out)
    mef = eqtools.load(out / "me.dat")
    N = 2 * nx * ny
    runs = {}
    for crossing in ("exact", "step"):
        for dX in (0.08, 0.04, 0.02, 0.01, 0.005):
            sub = out / f"{crossing}{dX}"
            sub.mkdir(exist_ok=True)
            log = eqtools.run_lammps(RIGID, {"nx": nx, "ny": ny, "seed": seed, "dX": dX, "Xmax": 8,
                                             "Xsteady": 8, "out": sub,
                                             "contacts": "threshold uniform 0.75 1.25 crossing "
                                             + crossing}, cwd=sub)
            loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", log).group(1))
            d = eqtools.load(sub / "F.dat")
            runs[(crossing, dX)] = (d[:, 1], d[:, 2], loop)
    Xc, Fc, _ = runs[("exact", 0.08)]    # common sample points X = 0.08 k
    stat = float(np.sqrt(np.mean(mef[np.rint(Xc / 1e-3).astype(int), 2] ** 2) / N))
    for (crossing, dX), (X, F, loop) in runs.items():
        k = np.rint(Xc / dX).astype(int)
        disc = float(np.sqrt(np.mean((F[k] - Fc) ** 2)))
        rows.append((crossing, dX, loop, disc))
    return rows, stat, N


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--nx", type=int, default=120)
    ap.add_argument("--ny", type=int, default=68)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--out", default=str(HERE / "out"), help="folder for the runs' files")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)

    me = me_table(out)
    print("1. master-equation solver: max |F - F_ref|/(N k_c) on X in [0, 8]")
    print(f"{'thresholds':>10} {'Richardson':>10} {'dx':>8} {'time s':>9} {'error':>10}")
    for name, rich, dx, t, e in me:
        print(f"{name:>10} {rich:>10} {dx:>8.4f} {t:>9.4f} {e:>10.2e}")

    eq, stat, N = eq_table(out, a.nx, a.ny, a.seed)
    print(f"\n2. EQ model, N = {N}: RMS discretization error of F(X)/(N k_c) at X = 0.08 k "
          f"(common random numbers), statistical error sd/sqrt(N) = {stat:.1e}")
    print(f"{'crossing':>9} {'dX':>7} {'loop s':>8} {'error':>10}")
    for crossing, dX, t, e in eq:
        print(f"{crossing:>9} {dX:>7.3f} {t:>8.3f} {e:>10.2e}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (p, q) = plt.subplots(1, 2, figsize=(10, 4))
    for name, mk in (("uniform", "o"), ("realistic", "s")):
        for rich, ls in (("no", "-"), ("yes", "--")):
            r = [(t, e) for n, rr, dx, t, e in me if n == name and rr == rich]
            p.loglog([max(t, 1e-4) for t, e in r], [max(e, 1e-16) for t, e in r], mk + ls,
                     label=f"{name}, Richardson {rich}")
    p.set_xlabel("eq-me run time (s)")
    p.set_ylabel(r"max error of $F/(N k_c)$")
    p.set_title("master-equation solver", fontsize=10)
    p.legend(fontsize=7)
    for crossing, mk in (("step", "o-"), ("exact", "s-")):
        r = [(t, e) for c, dX, t, e in eq if c == crossing]
        q.loglog([t for t, e in r], [max(e, 1e-16) for t, e in r], mk, label=f"crossing {crossing}")
    q.axhline(stat, color="k", ls=":", lw=0.8, label=r"statistical error $sd/\sqrt{N}$")
    q.set_xlabel("LAMMPS loop time (s)")
    q.set_ylabel(r"discretization error of $F/(N k_c)$")
    q.set_title(f"EQ simulation, N = {N}", fontsize=10)
    q.legend(fontsize=7)
    fig.savefig(out / "accuracy.png", dpi=90, bbox_inches="tight")
    print(f"\nplot: {out / 'accuracy.png'}")


if __name__ == "__main__":
    main()
