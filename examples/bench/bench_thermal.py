#!/usr/bin/python3
"""Benchmark of fix eq/contacts with temperature, aging and delays: the
fix's own cost per contact-step (the run with the fix minus the same run
without it, as bench_contacts.py) at T = 0 and with the keywords thermal
(theta = 0.02), aging and delay on, in the same scene (in.bench: hex
lattice, slider at v = 1, dX = 0.01, a break per contact every ~100
steps), and the ratio to T = 0 (issue 23's goal: at most 1.5).  Each
case's minimum over --repeat runs, the cases run round robin (every
repeat runs each once), so that a slow spell of a shared machine does
not fall on one case alone.

Part accuracy: run time against error at T > 0 (theta = 0.02, v = 1e-4,
N = 10^4, ../eq-thermal/in.eq-thermal): F(X) at the common sample points
X = 0.1 k on [0, 4] for slider steps dX = 0.05 ... 0.002 with crossing
exact and step, the same seed (common random numbers); the reference is
crossing exact at dX = 0.001.

The last two cases add the keyword peratom 100 (the per-atom array
valid every 100 steps, the common step on compact rows of 6 doubles):
the same numbers, fewer bytes per contact-step where the state does not
fit in the caches.

Option --speeds: the slider velocity v (default 1); a contact lives
about 100/v steps, and the work per life (a new threshold, the budget of
its thermal hazard, two or three bounds of its rate) weighs 1/(steps per
life) against the work per step.

Part instructions: the same ratio in instructions (valgrind's callgrind,
N = 2000, 2000 steps, the run without the fix subtracted): a figure
without the timing noise of a shared machine.

  ./bench_thermal.py                 N = 1e4 and 1e6, 1 rank, minimum of 3
  ./bench_thermal.py --sizes 1e4     a quick check
  ./bench_thermal.py --sizes 1e4 --speeds 1,0.3,0.1,0.03
  ./bench_thermal.py --part instructions --speeds 1,0.1
  ./bench_thermal.py --part accuracy
"""
import argparse
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from bench_contacts import lattice, one  # noqa: E402
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402

CASES = [("T = 0", ""),
         ("thermal", "thermal 0.02 1.0 1.0"),
         ("thermal, barrier 2 0.25", "thermal 0.02 1.0 1.0 barrier 2 0.25"),
         ("aging (T = 0)", "aging log 0.05 1.0"),
         ("thermal + aging + delay", "thermal 0.02 1.0 1.0 aging log 0.05 1.0 delay exp 0.1"),
         ("thermal, peratom 100", "thermal 0.02 1.0 1.0 peratom 100"),
         ("all three, peratom 100",
          "thermal 0.02 1.0 1.0 aging log 0.05 1.0 delay exp 0.1 peratom 100")]


def accuracy(out):
    """RMS error of F(X) against the finest exact run, and loop time."""
    contacts = "threshold uniform 0.75 1.25 thermal 0.02 1.0 1.0"
    X_SAMPLE = np.round(np.arange(1, 41) * 0.1, 10)

    def runF(dX, crossing):
        d = out / f"acc_{crossing}_{dX:g}"
        d.mkdir(parents=True, exist_ok=True)
        log = eqtools.run_lammps(HERE.parent / "eq-thermal" / "in.eq-thermal",
                                 {"n": 100, "v": 1e-4, "dX": dX, "Xhalf": 2.0, "out": d,
                                  "contacts": f"{contacts} crossing {crossing}"}, cwd=d)
        loop = sum(float(l.split()[3]) for l in log.splitlines() if l.startswith("Loop time of"))
        f = eqtools.load(d / "F.dat")
        idx = {round(x, 10): k for k, x in enumerate(np.round(f[:, 1], 10))}
        return np.array([f[idx[x], 2] for x in X_SAMPLE]), loop

    ref, _ = runF(0.001, "exact")
    print("run time against error at T > 0: theta = 0.02, v = 1e-4, N = 10^4, F(X) at X = 0.1 k "
          "on [0, 4],\nthe same seed; reference: crossing exact at dX = 0.001.  Statistical error "
          "of F/(N k_c) at this N: about %.1e" % (0.25 / math.sqrt(1e4)))
    print(f"{'dX':>7}  {'exact: loop s':>13} {'RMS error':>10}   {'step: loop s':>12} {'RMS error':>10}")
    for dX in (0.05, 0.02, 0.01, 0.005, 0.002):
        row = []
        for crossing in ("exact", "step"):
            F, loop = runF(dX, crossing)
            row += [loop, math.sqrt(np.mean((F - ref) ** 2))]
        print(f"{dX:>7g}  {row[0]:>13.2f} {row[1]:>10.2e}   {row[2]:>12.2f} {row[3]:>10.2e}", flush=True)


def instructions(out, speeds):
    """Instructions per contact-step of the fix (callgrind), and the ratio to T = 0."""
    valgrind = shutil.which("valgrind")
    if not valgrind:
        sys.exit("bench_thermal.py --part instructions: needs valgrind (apt-get install valgrind)")
    nx, ny, steps = 50, 20, 2000
    natoms = 2 * nx * ny

    def count(fix, extra, v):
        f = out / "callgrind.out"
        cmd = [valgrind, "--tool=callgrind", "--trace-children=yes", f"--callgrind-out-file={f}",
               eqtools.lmp_exe(), "-in", str(HERE / "in.bench"), "-log", "none", "-nocite",
               "-screen", "none"]
        for k, val in {"nx": nx, "ny": ny, "steps": steps, "fix": fix, "extra": extra, "v": v}.items():
            cmd += ["-var", k, str(val)]
        p = subprocess.run(cmd, cwd=out, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           env=eqtools.mpi_env())
        # the process that ran the input (FEQ_LMP may be a wrapper that
        # execs lmp; MPI may start helper processes): its own total
        pid = re.search(r"^==(\d+)== Command: .*in\.bench", p.stdout, re.M)
        m = pid and re.findall(r"^==%s== Collected : (\d+)" % pid.group(1), p.stdout, re.M)
        if p.returncode != 0 or not m:
            raise eqtools.RunError("callgrind run failed:\n" + p.stdout[-3000:])
        return int(m[-1])

    print(f"fix eq/contacts: instructions per contact-step (callgrind; N = {natoms}, {steps} steps, "
          "the run without the fix subtracted)")
    print(f"{'v':>6} {'steps/life':>10}  " + "  ".join(f"{c[0]:>24}" for c in CASES))
    for v in speeds:
        base = count("no", "", v)
        per = [(count("yes", extra, v) - base) / (natoms * steps) for _, extra in CASES]
        cells = "  ".join(f"{c:>12.1f} ({c / per[0]:4.2f}x)  " for c in per)
        print(f"{v:>6g} {100.0 / v:>10.0f}  {cells}", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--sizes", default="1e4,1e6")
    ap.add_argument("--ranks", default="1")
    ap.add_argument("--speeds", default="1", help="slider velocities (a life: ~100/v steps)")
    ap.add_argument("--work", type=float, default=1e8, help="contact-steps per run (sets steps)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per configuration (minimum taken)")
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--part", default="cost", choices=["cost", "accuracy", "instructions"])
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    speeds = [float(v) for v in a.speeds.split(",")]
    if a.part == "accuracy":
        accuracy(out)
        return
    if a.part == "instructions":
        instructions(out, speeds)
        return
    print("fix eq/contacts with temperature, aging and delays: ns per contact-step of the fix "
          "(run with the fix minus the run without), minimum of %d" % a.repeat)
    print(f"{'N':>9} {'ranks':>5} {'steps':>6} {'v':>5}  " + "  ".join(f"{c[0]:>24}" for c in CASES))
    for n in [int(float(v)) for v in a.sizes.split(",")]:
        steps = max(100, int(a.work / n))
        for r in [int(v) for v in a.ranks.split(",")]:
            for v in speeds:
                # round robin: each repeat runs every case once, so that a
                # slow spell of a shared machine does not fall on one case
                base = math.inf
                best = [math.inf] * len(CASES)
                for _ in range(a.repeat):
                    base = min(base, one(n, r, "no", "noforce", steps, out, v=v)[1])
                    for k, (_, extra) in enumerate(CASES):
                        natoms, t, _ = one(n, r, "yes", "noforce", steps, out, extra=extra, v=v)
                        best[k] = min(best[k], t)
                costs = [1e9 * (b - base) / (natoms * steps) for b in best]
                cells = "  ".join(f"{c:>12.2f} ({c / costs[0]:4.2f}x)  " for c in costs)
                print(f"{natoms:>9} {r:>5} {steps:>6} {v:>5g}  {cells}", flush=True)
    print("(x): the ratio to the fix at T = 0 in the same scene.")


if __name__ == "__main__":
    main()
