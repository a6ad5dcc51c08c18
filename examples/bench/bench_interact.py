#!/usr/bin/python3
"""Benchmarks of interacting contacts (pair eq/elastic, issue 3).

1. Pair cost per contact-step against pair lj/cut at the same cutoff
   (same neighbours), measured in one LAMMPS run (in.bench-pair), for
   N = 4096 ... 1e6 on 1 and 2 ranks, in the steady state of a rigidly
   moving slider.  The eq/elastic cost includes what the fix does for the
   interaction (the field update and the avalanches in pre_force) and the
   forces.  The neighbour list builds are shown apart (lj/cut: a half
   list; eq/elastic: a full list).
   The cost per break: a run at ten times the velocity (ten times the
   breaks per step) minus a run of the same motion whose contacts cannot
   break (same list builds and field updates), in LAMMPS' timer sections
   Modify and Pair (averages over the ranks: the field updates, the
   avalanches and, after a step with breaks, the pair's update of the
   ghosts' fields; each run's minimum over the repeats), divided by its
   breaks, and
   by its avalanche rounds (cost per round, the breaks of a round
   included).  Beside it, the update of the partners' fields alone as a
   plain loop (hand_scatter.cpp, the same lattice and pair layout, breaks
   at random contacts, in cache): its cost per break, and the ratio.
2. Run time against error: F(X) of a rigid slider (N = 4080, kappa = 0.03,
   lambda_c = 3) driven by fixed steps dX, against the quasi-static run
   (fix eq/quasistatic) of the same contacts, which has no step error.

3. Instructions per break (--part instructions; valgrind's callgrind,
   N = 16384, 300 steps at dX = 0.01, in.bench-break): the run whose
   contacts break minus the same motion with unbreakable contacts, per
   break, beside the hand loop's (hand_scatter.cpp's scatter_round
   alone, the breaks per round of the run): a ratio without the timing
   noise of a shared machine (instructions, not time: the partner update
   waits on memory more than the rest of a break does).

  ./bench_interact.py                       the first two tables
  ./bench_interact.py --part pair           only the first
  ./bench_interact.py --part instructions   the third
"""
import argparse
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import numpy as np  # noqa: E402

import eqtools  # noqa: E402

SECTIONS = ("Pair", "Neigh", "Comm", "Modify")


def hand_scatter(out):
    """compile hand_scatter.cpp (-O2, as the LAMMPS build) into out/"""
    exe = Path(out) / "hand_scatter"
    src = HERE / "hand_scatter.cpp"
    if not exe.exists() or exe.stat().st_mtime < src.stat().st_mtime:
        Path(out).mkdir(parents=True, exist_ok=True)
        cxx = shutil.which("g++") or "c++"
        subprocess.run([cxx, "-O2", "-g", "-DNDEBUG", "-std=c++17", str(src), "-o", str(exe)], check=True)
    return exe


def partner_update(exe, n, per_round):
    """ns per break of the plain partner update, n contacts, rounds of per_round breaks"""
    o = subprocess.run([str(exe), str(n), str(max(1, int(round(per_round))))], check=True,
                       capture_output=True, text=True).stdout
    return float(re.search(r"ns_per_break ([0-9.]+)", o).group(1))


def parse_runs(log):
    out = {}
    parts = log.split("BENCH ")[1:]
    breaks = [float(v) for v in re.findall(r"^BREAKS ([0-9.eE+-]+)", log, re.M)]

    for k, p in enumerate(parts):
        name = p.split()[0]
        loop = float(re.search(r"Loop time of ([0-9.eE+-]+)", p).group(1))
        steps = int(re.search(r"for (\d+) steps with (\d+) atoms", p).group(1))
        natoms = int(re.search(r"for \d+ steps with (\d+) atoms", p).group(1))
        t = {}
        for sec in SECTIONS:
            m = re.search(r"^%s\s*\|([^|]*)\|\s*([0-9.eE+-]+)" % sec, p, re.M)
            t[sec] = float(m.group(2)) if m else 0.0
        nb = re.search(r"Ave neighs/atom = ([0-9.]+)", p)
        rd = re.search(r"^ROUNDS ([0-9.eE+-]+)", p, re.M)
        out[name] = {"loop": loop, "steps": steps, "natoms": natoms, "t": t,
                     "neigh": float(nb.group(1)) if nb else 0.0,
                     "rounds": float(rd.group(1)) if rd else 0.0,    # per step
                     # the held run's fix is a new one: its count starts at 0
                     "breaks": (breaks[k] - (breaks[k - 1] if k > 0 and name != "eq/elastic-held" else 0.0)
                                if k < len(breaks) else 0.0)}
    return out


def break_cost(runs):
    """ns per break and us per round: the Modify and Pair sections (the fixes' pre_force with
    the field updates and the avalanches; the forces, and the pair's update of the ghosts'
    fields after a step with breaks) of the breaks run less those of the held run, each the
    minimum over the runs (Neigh, Comm and Output do the same work in both runs and would
    only add their noise).  The breaks and rounds are the same in every run (same seeds)."""
    def best(name):
        return min(res[name]["t"]["Modify"] + res[name]["t"]["Pair"] for res in runs)
    hi = runs[0]["eq/elastic-breaks"]
    extra = best("eq/elastic-breaks") - best("eq/elastic-held")
    nround = hi["rounds"] * hi["steps"]
    return 1e9 * extra / max(hi["breaks"], 1.0), 1e6 * extra / max(nround, 1.0)


def pair_table(sizes, ranks, work, out, repeat):
    print("pair eq/elastic vs lj/cut, rcut = 3 (36 lattice neighbours), steady sliding of a rigid "
          "slider, dX = 0.001 per step; ns per contact-step (run minus the run without pair style); "
          f"minimum of {repeat} runs.\nPer break and per round: the run at dX = 0.01 minus the same "
          "motion with unbreakable contacts, in LAMMPS' Modify and Pair sections (each the minimum "
          "of the runs); hand: the partner update alone (hand_scatter.cpp, one rank's share, "
          "divided by the ranks: wall time per break)")
    print(f"{'N':>8} {'ranks':>5} {'steps':>5} {'no pair':>8} {'lj/cut':>7} {'eq/elastic':>10} "
          f"{'ratio':>6} {'breaks/step':>11} {'x10: breaks/step':>16} {'rounds/step':>11} "
          f"{'ns/break':>8} {'us/round':>8} {'hand ns/break':>13} {'break/hand':>10} "
          f"{'Neigh lj':>8} {'Neigh eq':>8}  neighbours/atom (lj half, eq full)")
    exe = hand_scatter(out)
    for n in sizes:
        ny = max(1, int(round((n / 4.0) ** 0.5)))
        nx = 2 * ny
        steps = max(50, int(work / (2 * nx * ny)))
        for r in ranks:
            runs = []
            for _ in range(repeat):
                log = eqtools.run_lammps(HERE / "in.bench-pair",
                                         {"nx": nx, "ny": ny, "steps": steps}, nprocs=r, cwd=out)
                runs.append(parse_runs(log))
            best = min(runs, key=lambda res: res["eq/elastic"]["loop"])
            per_break, per_round = break_cost(runs)
            N = best["none"]["natoms"]
            ns = {k: 1e9 * v["loop"] / (v["steps"] * N) for k, v in best.items()}
            lj = ns["lj/cut"] - ns["none"]
            eq = ns["eq/elastic"] - ns["none"]
            hi = best["eq/elastic-breaks"]
            per_step = hi["breaks"] / hi["steps"]
            # the partner update of one rank's share (its rounds' breaks),
            # as wall time per break of r ranks working at once
            hand = partner_update(exe, N // r, per_step / max(hi["rounds"], 1e-9) / r) / r
            neigh = {k: 1e9 * best[k]["t"]["Neigh"] / (best[k]["steps"] * N)
                     for k in ("lj/cut", "eq/elastic")}
            print(f"{N:>8} {r:>5} {steps:>5} {ns['none']:>8.1f} {lj:>7.1f} {eq:>10.1f} "
                  f"{eq / lj:>6.2f} {best['eq/elastic']['breaks'] / steps:>11.1f} {per_step:>16.1f} "
                  f"{hi['rounds']:>11.2f} {per_break:>8.0f} {per_round:>8.1f} {hand:>13.0f} "
                  f"{per_break / hand:>10.2f} {neigh['lj/cut']:>8.1f} {neigh['eq/elastic']:>8.1f}  "
                  f"{best['lj/cut']['neigh']:.0f}, {best['eq/elastic']['neigh']:.0f}", flush=True)


def callgrind(cmd, out, marker, collect):
    """instructions within the functions `collect` of the process that ran `marker` under
    callgrind, and its output"""
    valgrind = shutil.which("valgrind")
    if not valgrind:
        sys.exit("bench_interact.py --part instructions: needs valgrind (apt-get install valgrind)")
    p = subprocess.run([valgrind, "--tool=callgrind", f"--callgrind-out-file={out}/callgrind.out",
                        f"--toggle-collect={collect}"]
                       + [str(c) for c in cmd], cwd=out, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, env=eqtools.mpi_env())
    pid = re.search(r"^==(\d+)== Command: .*%s" % re.escape(marker), p.stdout, re.M)
    m = pid and re.findall(r"^==%s== Collected : (\d+)" % pid.group(1), p.stdout, re.M)
    if p.returncode != 0 or not m:
        raise eqtools.RunError("callgrind run failed:\n" + p.stdout[-3000:])
    return int(m[-1]), p.stdout


def instructions_table(n, steps, out):
    ny = max(1, int(round((n / 4.0) ** 0.5)))
    nx = 2 * ny
    runs = {}
    for held in ("no", "yes"):
        cmd = [eqtools.lmp_exe(), "-in", HERE / "in.bench-break", "-log", "none", "-nocite"]
        for k, v in {"nx": nx, "ny": ny, "steps": steps, "held": held}.items():
            cmd += ["-var", k, v]
        # the run loops only (LAMMPS' Verlet::run): not the set-up, where
        # the held run's fix forms its contacts anew
        ir, text = callgrind(cmd, out, "in.bench-break", "LAMMPS_NS::Verlet::run*")
        found = [re.search(r"^%s ([0-9.eE+-]+)" % k, text, re.M) for k in ("BEFORE", "AFTER", "ROUNDS")]
        if not all(found):
            raise eqtools.RunError("in.bench-break printed no BEFORE/AFTER/ROUNDS:\n" + text[-3000:])
        before, after, rounds = (float(m.group(1)) for m in found)
        runs[held] = (ir, after - before, rounds)
    (ib, nbreaks, rounds), (ih, _, _) = runs["no"], runs["yes"]
    per_break = (ib - ih) / max(nbreaks, 1.0)
    per_round = max(1, int(round(nbreaks / steps / max(rounds, 1e-9))))
    exe = hand_scatter(out)
    total = 20000
    ir, _ = callgrind([exe, 2 * nx * ny, per_round, total], out, "hand_scatter", "*scatter_round*")
    hand = ir / (3 * max(1, total // per_round) * per_round)
    print(f"instructions per break (callgrind): N = {2 * nx * ny}, {steps} steps at dX = 0.01, "
          f"{nbreaks / steps:.1f} breaks and {rounds:.2f} rounds per step; the breaking run minus "
          f"the held one, and the partner update alone (hand_scatter.cpp, {per_round} breaks "
          f"per round)")
    print(f"{'N':>8} {'breaks':>8} {'instr/break':>11} {'hand instr/break':>16} {'break/hand':>10}")
    print(f"{2 * nx * ny:>8} {nbreaks:>8.0f} {per_break:>11.0f} {hand:>16.0f} "
          f"{per_break / hand:>10.2f}", flush=True)


def f_on_grid(d, grid, qs):
    X, F, att = d[:, 1], d[:, 2], d[:, 3]
    if not qs:
        return np.interp(grid, X, F)
    i = np.searchsorted(X, grid, side="right") - 1
    return F[i] + (grid - X[i]) * att[i] / 4080.0


def accuracy_table(kappa, xmax, out):
    inp = ROOT / "unittest" / "python" / "inputs" / "in.quasistatic"
    fine = np.arange(0.001, xmax - 0.04, 0.001)

    def run(tag, **v):
        d = Path(out) / tag
        d.mkdir(parents=True, exist_ok=True)
        t0 = time.perf_counter()
        eqtools.run_lammps(inp, dict(v, nx=60, ny=34, kappa=kappa, Xmax=xmax, out=d), cwd=d)
        return time.perf_counter() - t0, eqtools.load(d / "F.dat")

    print(f"\nrun time vs error, N = 4080, kappa = {kappa}, lambda_c = 3, X in [0, {xmax}]; "
          f"errors of F/(N k_c) against the quasi-static run: at the step ends, and of F(X) "
          f"on a 0.001 grid (linear between step ends)")
    print(f"{'reform_as':>9} {'crossing':>8} {'drive':>12} {'steps':>6} {'time s':>7} "
          f"{'step ends':>10} {'grid rms':>9} {'grid max':>9} {'breaks/step':>11}")
    # reform_as force with crossing exact (default: Abelian cascade) and
    # with crossing step (the reset of induced breaks), reform_as stretch
    for rmode, crossing in (("force", "exact"), ("force", "step"), ("stretch", "exact")):
        tag = f"{rmode}_{crossing}"
        tq, dq = run(f"qs_{tag}", drive="qs", dX=0.05, rmode=rmode, crossing=crossing)
        ref = f_on_grid(dq, fine, True)
        b = dq[:, 4]
        print(f"{rmode:>9} {crossing:>8} {'quasistatic':>12} {len(dq):>6} {tq:>7.2f} "
              f"{0.0:>10.1e} {0.0:>9.1e} {0.0:>9.1e} {b[b > 0].mean():>11.2f}")
        for dX in (0.04, 0.01, 0.004, 0.001):
            t, d = run(f"step{dX}_{tag}", drive="step", dX=dX, rmode=rmode, crossing=crossing)
            m = d[:, 1] > 0
            ends = np.max(np.abs(f_on_grid(dq, d[m, 1], True) - d[m, 2]))
            e = np.interp(fine, d[:, 1], d[:, 2]) - ref
            b = d[:, 4]
            print(f"{rmode:>9} {crossing:>8} {'step %g' % dX:>12} {len(d):>6} {t:>7.2f} "
                  f"{ends:>10.1e} {np.sqrt(np.mean(e * e)):>9.1e} {np.max(np.abs(e)):>9.1e} "
                  f"{b[b > 0].mean():>11.2f}")


ROOT = HERE.parents[1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--part", choices=["pair", "accuracy", "instructions", "all"], default="all")
    ap.add_argument("--sizes", default="4096,65536,1e6")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--work", type=float, default=2e7, help="contact-steps per timed run")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each size (minimum taken)")
    ap.add_argument("--kappa", type=float, default=0.03)
    ap.add_argument("--xmax", type=float, default=2.5)
    ap.add_argument("--out", default=str(HERE / "out"))
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.part in ("pair", "all"):
        pair_table([int(float(v)) for v in a.sizes.split(",")],
                   [int(v) for v in a.ranks.split(",")], a.work, out, a.repeat)
    if a.part in ("accuracy", "all"):
        accuracy_table(a.kappa, a.xmax, out)
    if a.part == "instructions":
        instructions_table(16384, 300, out)


if __name__ == "__main__":
    main()
