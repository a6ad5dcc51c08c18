"""Fuzzed input for the FRICTION-EQ styles (unittest/fuzz/fuzz_inputs.py).

Every malformed case must end in a LAMMPS ERROR naming the command and the
keyword, never in a crash, a hang, NaN/inf in the output or a silently
accepted run; the valid controls must run to the end with finite output.
The cases run in shards (FEQ_FUZZ_SHARDS, default 8), each shard on all
cores (FEQ_FUZZ_JOBS); a shard fails with the table of its cases that are
not ok, with their inputs.

Known failures (bugs found by the fuzzer, to be fixed in the styles) are
taken out of the shards and run one by one as strict xfail tests: when a fix
makes one pass, its XPASS fails the run; then delete its entry below.

Environment: FEQ_LMP (the lmp binary; default FEQ_ROOT/build/lmp), FEQ_ROOT,
FEQ_FUZZ_SHARDS, FEQ_FUZZ_JOBS, FEQ_FUZZ_TIMEOUT (s per case, default 20),
FEQ_FUZZ_REPORT (a file for the JSON results of the run).
"""

import dataclasses
import os
import shutil
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import fuzz_inputs as F  # noqa: E402

ROOT = Path(os.environ.get("FEQ_ROOT", HERE.parents[1]))
LMP = os.environ.get("FEQ_LMP") or str(ROOT / "build" / "lmp")
SHARDS = int(os.environ.get("FEQ_FUZZ_SHARDS", "8"))
JOBS = int(os.environ.get("FEQ_FUZZ_JOBS", str(os.cpu_count() or 1)))
TIMEOUT = float(os.environ.get("FEQ_FUZZ_TIMEOUT", "20"))
HANG_TIMEOUT = 5.0          # a known hang need not use the full timeout

# ---------------------------------------------------------------------------
# known failures: case id -> (reason, LAMMPS release years it applies to, or
# None for all).  Reproduce one with
#   fuzz_inputs.py --lmp build/lmp --filter '^ID$'   (--show ID: its input)

KNOWN_FAILURES = {
    # LAMMPS' own, kept on purpose: fix brownian (BROWNIAN package) sets
    # v = dx/dt, which is 0/0 = NaN with timestep 0 (src/BROWNIAN/
    # fix_brownian_base.cpp; 'compute reduce ave vx' prints -nan as well,
    # without any FRICTION-EQ style).  fix eq/substrate only reports the
    # blocks' mean velocity f_sub[4] from v; timestep 0 is legal LAMMPS
    # input, so the package neither rejects it nor hides LAMMPS' NaN.
    "substrate.runtime.timestep-zero": (
        "LAMMPS: with timestep 0 fix brownian sets v = dx/dt = 0/0 (compute reduce ave vx is "
        "-nan too); fix eq/substrate passes it on as f_sub[4]", None),
}
# fixed (their cases run in the shards now): kernel tables with more points
# than 'N n' says, a NaN position with pair eq/elastic (named as such), eq/me grid-size overflow with
# thresholds ~1e300 (crash), exact renewal sums with lo -> 0 (hang), NaN
# summary with reform gaussian 0.1 1e-300, output-file errors without the
# keyword, a missing output file name taking the next keyword, 'N 2.5' /
# more points than N / 'N 4 iso' in threshold and substrate tables,
# pair_coeff type errors from utils::bounds, fix eq/substrate sawtooth uc
# and stage 1e300 (NaN/inf energies), LAMMPS 2021: '1.5.2' read as 1.5
# (EQUtil::numeric) and fix_modify on fix eq/contacts without
# modify_param()

# ---------------------------------------------------------------------------

HAVE_LMP = os.path.isfile(LMP) and os.access(LMP, os.X_OK)
VERSION, YEAR = F.lmp_version(LMP) if HAVE_LMP else ("none", 0)
CASES = F.generate(mpi=shutil.which("mpirun") is not None)
BY_ID = {c.id: c for c in CASES}
KNOWN = {cid: reason for cid, (reason, years) in KNOWN_FAILURES.items()
         if years is None or YEAR in years}
SHARDED = [c for c in CASES if c.id not in KNOWN]
RESULTS = {}


def need_lmp():
    assert HAVE_LMP, f"no lmp binary at {LMP} (set FEQ_LMP)"


def test_generator():
    """>= 300 malformed cases, every class present, unique ids, the same
    cases on every call, every known failure names a case."""
    malformed = [c for c in CASES if c.cls in F.MALFORMED_CLASSES]
    assert len(malformed) >= 300, len(malformed)
    present = {c.cls for c in CASES}
    assert set(F.MALFORMED_CLASSES) <= present, set(F.MALFORMED_CLASSES) - present
    assert {"control", "valid-edge"} <= present
    assert len(BY_ID) == len(CASES)
    again = F.generate(mpi=shutil.which("mpirun") is not None)
    assert [dataclasses.asdict(c) for c in again] == [dataclasses.asdict(c) for c in CASES]
    assert not set(KNOWN_FAILURES) - set(BY_ID), set(KNOWN_FAILURES) - set(BY_ID)
    for c in CASES:
        assert c.input.strip() and c.expect.kind in ("error", "ok", "error-or-ok", "robust")


def test_classifier():
    """The runner tells the outcomes apart (synthetic outputs, no LAMMPS)."""
    bad = F.Case("t", "zero", "fix c all eq/contacts 0 5 threshold uniform 0.75 1.25\nrun 1\n",
                 F.Expect("error", "eq/contacts", r"\bkc\b"))
    good = F.Case("g", "control", "run 1\n", F.Expect("ok"))
    last = "Last command: fix c all eq/contacts 0 5 threshold uniform 0.75 1.25\n"
    thermo = "   Step   PotEng   f_c[1]\n     0   0   0\n    10   {}   0.5\nLoop time\nTotal wall time: 0:00:00\n"
    cases = [
        (bad, 1, "ERROR: Fix eq/contacts: kc must be finite and > 0 (got 0) (src/fix.cpp:12)\n" + last,
         False, "error-ok"),
        (bad, 1, "ERROR: Illegal fix command (src/modify.cpp:7)\n" + last, False, "error-vague"),
        (bad, 1, "ERROR: Fix eq/contacts unknown keyword 'x'; allowed: kc, seed\n", False, "error-vague"),
        (bad, 1, "ERROR on proc 0: Fix eq/contacts: kc is zero\nMPI_ABORT was invoked\n", False,
         "error-ok"),
        (bad, -11, "", False, "crash"),
        (bad, 1, "Exception: vector::_M_default_append\nMPI_ABORT was invoked\n", False, "crash"),
        (bad, 1, "no error message at all\n", False, "crash"),
        (bad, 1, "ERROR: Fix eq/contacts: kc\n==7==ERROR: LeakSanitizer: detected memory leaks\n",
         False, "crash"),
        (good, 0, "fix.cpp:12:5: runtime error: signed integer overflow\nTotal wall time: 0:00:00\n",
         False, "crash"),
        (bad, 134, "mpirun noticed that process rank 1 exited on signal 11 (Segmentation fault).\n"
         "ERROR: Fix eq/contacts: kc\n", False, "crash"),
        (bad, 0, thermo.format("0.1"), False, "accepted"),
        (bad, 0, thermo.format("-nan"), False, "nan"),
        (bad, None, "", True, "hang"),
        (good, 0, thermo.format("0.1"), False, "ok"),
        (good, 0, thermo.format("inf"), False, "nan"),
        (good, 0, "  kinetic   F_k/(N k_c) = -nan (stationary)\nTotal wall time: 0:00:00\n", False, "nan"),
        (good, 0, "  ghost atom cutoff = inf\nTotal wall time: 0:00:00\n", False, "ok"),
        (good, 1, "ERROR: Fix eq/contacts: kc\n", False, "rejected"),
        (good, 0, "Step\n 0 1\n", False, "incomplete"),
    ]
    for case, rc, out, timed_out, want in cases:
        got = F.classify(case, rc, out, timed_out)[0]
        assert got == want, (want, got, out)


@pytest.mark.parametrize("index", range(SHARDS))
def test_shard(index, capsys):
    need_lmp()
    cases = F.shard(SHARDED, index, SHARDS)
    results = F.run_cases(cases, LMP, jobs=JOBS, timeout=TIMEOUT)
    RESULTS.update({r.id: r for r in results})
    bad = [r for r in results if not r.ok]
    if bad:
        import io
        buf = io.StringIO()
        F.summarize(cases, results, out=buf, label=f"shard {index}/{SHARDS}, LAMMPS {VERSION}")
        pytest.fail(f"{len(bad)} of {len(cases)} cases are not ok:\n" + buf.getvalue(),
                    pytrace=False)


@pytest.mark.parametrize("case_id", [
    pytest.param(cid, marks=pytest.mark.xfail(reason=reason, strict=True))
    for cid, reason in KNOWN.items()])
def test_known_failure(case_id):
    need_lmp()
    case = BY_ID[case_id]
    timeout = HANG_TIMEOUT if "hang" in KNOWN[case_id] or "never ends" in KNOWN[case_id] else TIMEOUT
    r = F.run_case(case, LMP, timeout=timeout, mpirun=shutil.which("mpirun") or "mpirun")
    RESULTS[r.id] = r
    assert r.ok, f"{r.outcome}: {r.message or r.detail}"


def test_summary(capsys):
    """One line of counts per class and outcome for everything this run
    executed (printed; FEQ_FUZZ_REPORT: the results as JSON)."""
    need_lmp()
    F.pytest_summary([RESULTS[c.id] for c in CASES if c.id in RESULTS], BY_ID, F.summarize,
                     f"[{LMP}, LAMMPS {VERSION}; {len(KNOWN)} known failures]", "FEQ_FUZZ_REPORT", capsys)
