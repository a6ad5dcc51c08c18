#!/usr/bin/python3
"""Benchmark of fix eq/contacts: nanoseconds per contact-step for
N = 1e4, 1e5, 1e6 contacts on 1 and 2 MPI ranks, with LAMMPS' timer
breakdown.  Each configuration is run with and without the fix (same
driver), so the fix's own cost is separated from LAMMPS' time stepping.
Beside it, the same work as a plain loop (hand_contacts.cpp, compiled
-O2 like the LAMMPS build; on r ranks, r copies of N/r contacts at once)
and the memory-bandwidth bound of the fix: the bytes its loop moves per
contact-step over the bandwidth of the STREAM triad measured by the same
program (times 4/3: the triad's stores also read their line).

  ./bench_contacts.py                  the table for the README
  ./bench_contacts.py --driver move    with fix move linear as the driver
  ./bench_contacts.py --sizes 1e4      a quick check
"""
import argparse
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import eqtools  # noqa: E402

SECTIONS = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")
# bytes the fix's loop moves per contact-step: its state row (7 doubles)
# read and written back, image flags read, x read (its line of 3
# doubles), f read and written (the masks are not read: in.bench's fix is
# on group all)
FIX_BYTES = 56 + 56 + 4 + 24 + 48


def hand_loop(out):
    """compile hand_contacts.cpp (-O2, as the LAMMPS build) into out/"""
    exe = Path(out) / "hand_contacts"
    src = HERE / "hand_contacts.cpp"
    if not exe.exists() or exe.stat().st_mtime < src.stat().st_mtime:
        cxx = shutil.which("g++") or "c++"
        subprocess.run([cxx, "-O2", "-g", "-DNDEBUG", "-std=c++17",
                        f"-I{HERE.parents[1] / 'src' / 'FRICTION-EQ' / 'lib'}", str(src), "-o", str(exe)],
                       check=True)
    return exe


def run_hand(exe, n, ranks, steps):
    """ranks copies of n/ranks contacts at once: (wall ns per contact-step
    of the n contacts, triad GB/s of the first copy)"""
    procs = [subprocess.Popen([str(exe), str(n // ranks), str(steps)], stdout=subprocess.PIPE, text=True)
             for _ in range(ranks)]
    outs = [p.communicate()[0] for p in procs]
    ns = max(float(re.search(r"ns_per_contact_step ([0-9.]+)", o).group(1)) for o in outs) / ranks
    bw = float(re.search(r"triad_GB_per_s ([0-9.]+)", outs[0]).group(1))
    return ns, bw


def lattice(n):
    """hex cells nx x ny (2 contacts each) with 2 nx ny ~ n, nx = 2 ny"""
    ny = max(1, int(round(math.sqrt(n / 4.0))))
    return 2 * ny, ny


def one(n, ranks, fix, driver, steps, out, extra="", v=1.0):
    nx, ny = lattice(n)
    log = eqtools.run_lammps(HERE / "in.bench", {"nx": nx, "ny": ny, "steps": steps, "fix": fix,
                                                 "driver": driver, "extra": extra, "v": v},
                             nprocs=ranks, cwd=out)
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", log).group(1))
    natoms = int(re.search(r"for \d+ steps with (\d+) atoms", log).group(1))
    timers = {}
    for sec in SECTIONS:
        # "Section | min | avg | max | %varavg | %total": take the average
        m = re.search(r"^%s\s*\|([^|]*)\|\s*([0-9.eE+-]+)" % sec, log, re.M)
        timers[sec] = float(m.group(2)) if m else 0.0
    return natoms, loop, timers


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--sizes", default="1e4,1e5,1e6")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--driver", default="noforce", choices=["noforce", "move"])
    ap.add_argument("--work", type=float, default=2e8, help="contact-steps per run (sets steps)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per configuration (minimum taken)")
    ap.add_argument("--out", default=str(HERE / "out"), help="folder for the runs' files")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    print(f"fix eq/contacts benchmark: thresholds uniform [0.75,1.25], dX = 0.01 (a break per "
          f"contact every ~100 steps), driver {a.driver}")
    exe = hand_loop(out)
    print(f"{'N':>9} {'ranks':>5} {'steps':>6} {'total':>9} {'baseline':>9} {'eq/contacts':>11} "
          f"{'hand loop':>9} {'ratio':>5} {'bw bound':>8} {'ratio':>5}   "
          f"LAMMPS timers with the fix, % of loop ({', '.join(SECTIONS)})")
    print(f"{'':>9} {'':>5} {'':>6} {'ns/c-step':>9} {'ns/a-step':>9} {'ns/c-step':>11} "
          f"{'ns/c-step':>9} {'':>5} {'ns/c-step':>8}")
    for n in [int(float(v)) for v in a.sizes.split(",")]:
        steps = max(100, int(a.work / n))
        for r in [int(v) for v in a.ranks.split(",")]:
            best = None
            for _ in range(a.repeat):
                res = one(n, r, "yes", a.driver, steps, out)
                if best is None or res[1] < best[1]:
                    best = res
            natoms, t_fix, timers = best
            t_base = min(one(n, r, "no", a.driver, steps, out)[1] for _ in range(a.repeat))
            hand, bw = min(run_hand(exe, natoms, r, steps) for _ in range(a.repeat))
            bound = FIX_BYTES / (bw * 4.0 / 3.0) / r    # ns: bytes / (GB/s), r ranks at once
            cs = natoms * steps
            fix = 1e9 * (t_fix - t_base) / cs
            pct = " ".join(f"{100 * timers[s] / t_fix:5.1f}" for s in SECTIONS)
            print(f"{natoms:>9} {r:>5} {steps:>6} {1e9 * t_fix / cs:>9.2f} {1e9 * t_base / cs:>9.2f} "
                  f"{fix:>11.2f} {hand:>9.2f} {fix / hand:>5.2f} {bound:>8.2f} {fix / bound:>5.2f}   {pct}",
                  flush=True)
    print("ns/c-step: wall time of the run loop per contact and step; baseline: the same run "
          "without the fix;\neq/contacts: the difference; hand loop: hand_contacts.cpp, the same work "
          "(ratio: fix / hand loop);\nbw bound: %d bytes per contact-step at the triad bandwidth x 4/3, "
          "over the ranks (ratio: fix / bound).\n2 ranks on this 2-core machine share memory bandwidth "
          "(the bound assumes the bandwidth of one core per rank)." % FIX_BYTES)


if __name__ == "__main__":
    main()
