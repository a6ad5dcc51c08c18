#!/usr/bin/python3
"""Benchmark of the surface Green tensor solver (eq-green, paper Sec. III).

Prints, for the FFT path (open array, zero-padded FFTs, preconditioned CG)
on L x L lattices, the time and CG iterations of one solve of the stressed
state (F = B K U0), the total for the five solves of a removal experiment
(state, without the contact, Eq. int.eq09, slip kernels along x and y for
the kernel and the reciprocity check), the memory held by
the operator and the peak resident memory of the process; the iterations
without preconditioner; and the dense Cholesky path where it fits, with
its memory and a cubic extrapolation to L = 89.

    /usr/bin/python3 examples/bench/bench_green.py [--sizes 89 256 512 1024]
                                                   [--gamma1 0.06] [--dense 15 25 35 45]
"""
import argparse
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402
import numpy as np  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[89, 256, 512, 1024])
    ap.add_argument("--dense", type=int, nargs="+", default=[15, 25, 35, 45])
    ap.add_argument("--gamma1", type=float, default=0.06)
    ap.add_argument("--noprecond", type=int, nargs="+", default=[89, 256],
                    help="sizes also run without preconditioner")
    a = ap.parse_args(argv)
    g = a.gamma1
    with tempfile.TemporaryDirectory() as d:
        print(f"eq-green benchmark, gamma1 = {g}, gamma2 = 0.3, sigma = 0.3, open array, "
              f"tol 1e-12 (relative residual)")
        print("  L      N        unknowns  precond    iters  t_state[s]  t_removal(5 solves)[s]"
              "  operator[MB]  peak RSS[MB]")
        for L in a.sizes:
            for pc in ["circulant"] + (["none"] if L in a.noprecond else []):
                t0 = time.time()
                s = eqtools.run_eqgreen(["L", L, "gamma1", g, "precond", pc, "rmax", 4], cwd=d)
                wall = time.time() - t0
                print(f"  {L:<5d} {L * L:<8d} {int(s['unknowns']):<9d} {pc:<10} "
                      f"{int(s['iterations_state']):5d}  {s['seconds_state']:10.3f}  "
                      f"{s['seconds_total']:10.3f} (wall {wall:.1f})      "
                      f"{s['operator_MB']:10.1f}  {s['peak_rss_MB']:10.1f}")
        print("dense Cholesky (Eigen LLT on the 2N x 2N in-plane matrix; each of the 3 removal")
        print("solves refactorises):")
        print("  L      unknowns  matrix[MB]  t_state[s]  max |f_fft - f_dense| (r = 1 profile)")
        ts = []
        for L in a.dense:
            s = eqtools.run_eqgreen(["L", L, "gamma1", g, "method", "dense", "rmax", 1,
                                     "profile", "pd.dat"], cwd=d)
            f = eqtools.run_eqgreen(["L", L, "gamma1", g, "rmax", 1, "profile", "pf.dat"], cwd=d)
            dd = eqtools.read_green_profile(Path(d) / "pd.dat")["x"][:, 1:]
            ff = eqtools.read_green_profile(Path(d) / "pf.dat")["x"][:, 1:]
            n = int(s["unknowns"])
            ts.append((n, s["seconds_state"]))
            print(f"  {L:<5d}  {n:<8d}  {8.0 * n * n / 2**20:9.1f}  {s['seconds_state']:10.3f}"
                  f"  {np.abs(dd - ff).max():.2e}")
        n89 = 2 * 89 * 89
        nn, tt = np.array(ts).T
        print(f"  L = 89: 2N = {n89} unknowns, dense matrix {8.0 * n89 ** 2 / 2**30:.2f} GiB "
              f"(3N x 3N with the normal components: {8.0 * (1.5 * n89) ** 2 / 2**30:.2f} GiB); "
              f"Cholesky extrapolated (t ~ n^3 from the largest above) "
              f"{tt[-1] * (n89 / nn[-1]) ** 3:.0f} s per solve")


if __name__ == "__main__":
    main()
