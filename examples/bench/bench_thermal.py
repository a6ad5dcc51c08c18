#!/usr/bin/python3
"""Benchmark of fix eq/contacts with temperature, aging and delays: the
fix's own cost per contact-step (the run with the fix minus the same run
without it, as bench_contacts.py) at T = 0 and with the keywords thermal
(theta = 0.02), aging and delay on, in the same scene (in.bench: hex
lattice, slider at v = 1, dX = 0.01, a break per contact every ~100
steps), and the ratio to T = 0 (issue 23's goal: at most 1.5).

  ./bench_thermal.py                 N = 1e4 and 1e6, 1 rank, minimum of 3
  ./bench_thermal.py --sizes 1e4     a quick check
"""
import argparse
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from bench_contacts import lattice, one  # noqa: E402

CASES = [("T = 0", ""),
         ("thermal", "thermal 0.02 1.0 1.0"),
         ("thermal, barrier 2 0.25", "thermal 0.02 1.0 1.0 barrier 2 0.25"),
         ("aging (T = 0)", "aging log 0.05 1.0"),
         ("thermal + aging + delay", "thermal 0.02 1.0 1.0 aging log 0.05 1.0 delay exp 0.1")]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--sizes", default="1e4,1e6")
    ap.add_argument("--ranks", default="1")
    ap.add_argument("--work", type=float, default=1e8, help="contact-steps per run (sets steps)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per configuration (minimum taken)")
    ap.add_argument("--out", default=str(HERE / "out"))
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    print("fix eq/contacts with temperature, aging and delays: ns per contact-step of the fix "
          "(run with the fix minus the run without), minimum of %d" % a.repeat)
    print(f"{'N':>9} {'ranks':>5} {'steps':>6}  " + "  ".join(f"{c[0]:>24}" for c in CASES))
    for n in [int(float(v)) for v in a.sizes.split(",")]:
        steps = max(100, int(a.work / n))
        for r in [int(v) for v in a.ranks.split(",")]:
            base = min(one(n, r, "no", "noforce", steps, out)[1] for _ in range(a.repeat))
            costs = []
            for _, extra in CASES:
                best = None
                for _ in range(a.repeat):
                    natoms, t, _ = one(n, r, "yes", "noforce", steps, out, extra=extra)
                    best = t if best is None else min(best, t)
                costs.append(1e9 * (best - base) / (natoms * steps))
            cells = "  ".join(f"{c:>12.2f} ({c / costs[0]:4.2f}x)  " for c in costs)
            print(f"{natoms:>9} {r:>5} {steps:>6}  {cells}", flush=True)
    print("(x): the ratio to the fix at T = 0 in the same scene.")


if __name__ == "__main__":
    main()
