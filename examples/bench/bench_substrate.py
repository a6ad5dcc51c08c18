#!/usr/bin/python3
"""Benchmark of the FK-ME chain (fix eq/substrate, paper Sec. V B): block-steps
per second and nanoseconds per block-step for N = 3e4 and 3e6 blocks on 1
and 2 MPI ranks, with LAMMPS' timer breakdown.  Each configuration is also
run without fix eq/substrate (same coupling and integrator), so the fix's
own cost is separated (with bond_style harmonic as the coupling: pair
eq/elastic needs the fix), and the coupling by pair eq/elastic is compared
with bond_style harmonic.

  ./bench_substrate.py                 the table for the README
  ./bench_substrate.py --sizes 3e4     a quick check
"""
import argparse
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402

SECTIONS = ("Pair", "Bond", "Neigh", "Comm", "Modify", "Other")


def one(n, ranks, fix, coupling, steps, out):
    log = eqtools.run_lammps(HERE / "in.bench-substrate", {"N": n, "steps": steps, "fix": fix,
                                                           "coupling": coupling},
                             nprocs=ranks, cwd=out)
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", log).group(1))
    natoms = int(re.search(r"for \d+ steps with (\d+) atoms", log).group(1))
    timers = {}
    for sec in SECTIONS:
        m = re.search(r"^%s\s*\|([^|]*)\|\s*([0-9.eE+-]+)" % sec, log, re.M)
        timers[sec] = float(m.group(2)) if m else 0.0
    return natoms, loop, timers


def best(n, r, fix, coupling, steps, out, repeat):
    runs = [one(n, r, fix, coupling, steps, out) for _ in range(repeat)]
    return min(runs, key=lambda x: x[1])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--sizes", default="3e4,3e6")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--couplings", default="pair,bond")
    ap.add_argument("--work", type=float, default=3e8, help="block-steps per run (sets steps)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per configuration (minimum taken)")
    ap.add_argument("--out", default=str(HERE / "out"), help="folder for the runs' files")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    print("FK-ME chain benchmark: g = 25, sawtooth, f = 0.95, kink pairs every 200 blocks, "
          "fix brownian dt = 0.1")
    print(f"{'N':>9} {'ranks':>5} {'coupling':>8} {'fix':>4} {'steps':>6} {'ns/b-step':>9} "
          f"{'Mb-steps/s':>10}   LAMMPS timers, % of loop ({', '.join(SECTIONS)})")
    configs = [(c, "yes") for c in a.couplings.split(",")] + [("bond", "no")]
    for n in [int(float(v)) for v in a.sizes.split(",")]:
        steps = max(100, int(a.work / n))
        for r in [int(v) for v in a.ranks.split(",")]:
            res = {}
            for coupling, fix in configs:
                natoms, t, timers = best(n, r, fix, coupling, steps, out, a.repeat)
                if natoms != n:
                    sys.exit(f"bench_substrate: {natoms} atoms created for N = {n}")
                res[coupling, fix] = t
                bs = natoms * steps
                pct = " ".join(f"{100 * timers[s] / t:5.1f}" for s in SECTIONS)
                print(f"{natoms:>9} {r:>5} {coupling:>8} {fix:>4} {steps:>6} {1e9 * t / bs:>9.2f} "
                      f"{bs / t / 1e6:>10.1f}   {pct}", flush=True)
            if ("bond", "yes") in res:
                print(f"{'':>9} {'':>5} fix eq/substrate alone: "
                      f"{1e9 * (res['bond', 'yes'] - res['bond', 'no']) / bs:.2f} ns/b-step", flush=True)
    print("ns/b-step: wall time of the run loop per block and step (minimum of the repeats); "
          "fix no: without fix eq/substrate.\n2 ranks on this 2-core machine share memory bandwidth.")


if __name__ == "__main__":
    main()
