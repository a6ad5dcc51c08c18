"""Stateful misuse of the FRICTION-EQ styles (unittest/fuzz/misuse_inputs.py).

Partners removed or replaced during and between runs, restart files re-read
with other arguments or garbled, box and atom changes between runs,
overflowing products of finite arguments, outputs read before the first run
and forbidden combinations; every input on 1 and on 2 MPI ranks.  Every case
must end in a LAMMPS ERROR matching its expectation (a partner problem names
both styles) or in a run to the end with finite output, no "CHECK FAILED"
line of its in-script oracles and no drift of pair eq/elastic's incremental
field; never in a crash or a hang.  The cases run in shards
(FEQ_MISUSE_SHARDS, default 6); a shard fails with the table of its cases
that are not ok.

Known failures are taken out of the shards and run one by one as strict
xfail tests: when a fix makes one pass, its XPASS fails the run; then
delete its entry below.

Environment: FEQ_LMP (the lmp binary; default FEQ_ROOT/build/lmp), FEQ_ROOT,
FEQ_MISUSE_SHARDS, FEQ_MISUSE_JOBS (lmp processes at a time, default 1),
FEQ_MISUSE_TIMEOUT (s per case, default 20), FEQ_MISUSE_REPORT (a file for
the JSON results of the run).
"""

import dataclasses
import io
import os
import shutil
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import fuzz_inputs as F  # noqa: E402
import misuse_inputs as M  # noqa: E402

ROOT = Path(os.environ.get("FEQ_ROOT", HERE.parents[1]))
LMP = os.environ.get("FEQ_LMP") or str(ROOT / "build" / "lmp")
SHARDS = int(os.environ.get("FEQ_MISUSE_SHARDS", "6"))
JOBS = int(os.environ.get("FEQ_MISUSE_JOBS", "1"))
TIMEOUT = float(os.environ.get("FEQ_MISUSE_TIMEOUT", "20"))
HANG_TIMEOUT = 5.0          # a known hang need not use the full timeout
MPI = shutil.which("mpirun") is not None

# ---------------------------------------------------------------------------
# known failures: case id -> (reason, LAMMPS release years it applies to, or
# None for all).  Reproduce one with
#   misuse_inputs.py --lmp build/lmp --filter '^ID$'   (--show ID: its input)

KNOWN_FAILURES = {
}

# ---------------------------------------------------------------------------

HAVE_LMP = os.path.isfile(LMP) and os.access(LMP, os.X_OK)
VERSION, YEAR = F.lmp_version(LMP) if HAVE_LMP else ("none", 0)
CASES = M.generate(mpi=MPI)
BY_ID = {c.id: c for c in CASES}
KNOWN = {cid: reason for cid, (reason, years) in KNOWN_FAILURES.items()
         if years is None or YEAR in years}
SHARDED = [c for c in CASES if c.id not in KNOWN]
RESULTS = {}


def need_lmp():
    assert HAVE_LMP, f"no lmp binary at {LMP} (set FEQ_LMP)"


def test_generator():
    """>= 300 cases, every class with >= 40 inputs, each input on 1 and on 2
    ranks, unique ids, the same cases on every call, every known failure
    names a case."""
    assert len(CASES) >= 300, len(CASES)
    assert len(BY_ID) == len(CASES)
    inputs = {}
    for c in CASES:
        assert c.cls in M.CLASSES, c.cls
        assert c.id.endswith(f".np{c.np}"), c.id
        inputs.setdefault(c.id.rsplit(".", 1)[0], set()).add(c.np)
    want = {1, 2} if MPI else {1}
    assert all(nps == want for nps in inputs.values()), [k for k, v in inputs.items() if v != want][:5]
    per_class = {cls: sum(1 for k in inputs if k.startswith(cls + ".")) for cls in M.CLASSES}
    assert all(n >= 40 for n in per_class.values()), per_class
    again = M.generate(mpi=MPI)
    assert [dataclasses.asdict(c) for c in again] == [dataclasses.asdict(c) for c in CASES]
    assert not set(KNOWN_FAILURES) - set(BY_ID), set(KNOWN_FAILURES) - set(BY_ID)
    for c in CASES:
        assert c.input.strip() and c.expect.kind in ("error", "ok", "error-or-ok", "robust")
        assert isinstance(c.expect, M.Expect)


def test_classifier():
    """The outcomes are told apart (synthetic outputs, no LAMMPS)."""
    partner = M.Case("p", "unfix-within", "run 10\n", M.err(M.QS_GONE, r"\bc\b"))
    good = M.Case("g", "box-atoms", "run 10\n", M.ok())
    warn = M.Case("w", "restart-args", "run 10\n", M.ok(warn=r"\bseed\b"))
    garbled = M.Case("r", "restart-garbled", "run 10\n", M.err(M.RESTART_ERR))
    either = M.Case("e", "before-run", "run 10\n", M.err_or_ok(M.NOT_YET))
    end = "Loop time of 0.1\nTotal wall time: 0:00:00\n"
    drift = ("pair eq/elastic: 41 field updates on rank 0: ...; 40 drift checks: max |h_incremental - "
             "h_full| = {} (scale of h: {})\n")
    qs_msg = ("ERROR: Fix q eq/quasistatic: fix c eq/contacts, the contacts it drives, was removed or "
              "replaced during the run (e.g. unfix in run N pre no every M) (src/fix.cpp:1)\n")
    cases = [
        (partner, 1, qs_msg, "error-ok"),
        # one style named only
        (partner, 1, "ERROR: Fix q eq/quasistatic: , the contacts it drives, was removed or replaced "
         "during the run\n", "error-vague"),
        (partner, 0, end, "accepted"),
        (partner, -11, qs_msg, "crash"),
        (good, 0, end, "ok"),
        (good, 0, "CHECK FAILED count 79 80\n" + end, "wrong"),
        (good, 1, "CHECK FAILED count 79 80\nERROR: Fix c eq/contacts: x\n", "wrong"),
        (good, 0, drift.format("1.66e-15", "0.684") + end, "ok"),
        (good, 0, drift.format("0", "0") + end, "ok"),
        (good, 0, drift.format("8.93e-05", "1.99") + end, "drift"),
        (good, 0, drift.format("-nan", "1.99") + end, "nan"),
        (good, 0, "   Step  PotEng\n  10  -nan\n" + end, "nan"),
        (good, 1, "ERROR: Lost atoms: original 80 current 79\n", "rejected"),
        (good, None, "", "hang"),
        (warn, 0, "WARNING: Fix eq/contacts: seed 7 differs from the restart file's seed 99\n" + end, "ok"),
        (warn, 0, end, "no-warning"),
        # a crash pattern inside LAMMPS' own ERROR message is no crash
        (garbled, 1, "ERROR: Incomplete or corrupted LAMMPS restart file (src/read_restart.cpp:9)\n",
         "error-ok"),
        (garbled, 1, "corrupted size vs. prev_size\n", "crash"),
        (garbled, 1, "ERROR: Fix c eq/contacts: x\n[vm:1] *** Process received signal ***\n", "crash"),
        (either, 1, "ERROR: Variable v: Compute used in variable between runs is not current\n", "error-ok"),
        (either, 0, end, "ok"),
    ]
    for case, rc, out, want in cases:
        got = M.classify(case, rc, out, rc is None)[0]
        assert got == want, (want, got, out)
    # fuzz_inputs' cases keep their own classification
    fuzz = F.Case("f", "control", "run 1\n", F.Expect("ok"))
    assert M.classify(fuzz, 0, "CHECK FAILED x 1 2\n" + end, False)[0] == "ok"


@pytest.mark.parametrize("index", range(SHARDS))
def test_shard(index):
    need_lmp()
    cases = M.shard(SHARDED, index, SHARDS)
    results = M.run_cases(cases, LMP, jobs=JOBS, timeout=TIMEOUT)
    RESULTS.update({r.id: r for r in results})
    bad = [r for r in results if not r.ok]
    if bad:
        buf = io.StringIO()
        M.summarize(cases, results, out=buf, label=f"shard {index}/{SHARDS}, LAMMPS {VERSION}")
        pytest.fail(f"{len(bad)} of {len(cases)} cases are not ok:\n" + buf.getvalue(), pytrace=False)


@pytest.mark.parametrize("case_id", [
    pytest.param(cid, marks=pytest.mark.xfail(reason=reason, strict=True))
    for cid, reason in KNOWN.items()] or ["none"])
def test_known_failure(case_id):
    """Each known failure still fails ("none": the list is empty; an empty
    parameter set would be a skip, which ctest counts as a failure)."""
    if case_id == "none":
        return
    need_lmp()
    case = BY_ID[case_id]
    timeout = HANG_TIMEOUT if "hang" in KNOWN[case_id] else TIMEOUT
    r = M.run_case(case, LMP, timeout=timeout, mpirun=shutil.which("mpirun") or "mpirun")
    RESULTS[r.id] = r
    assert r.ok, f"{r.outcome}: {r.message or r.detail}"


def test_summary(capsys):
    """One line of counts per class and outcome for everything this run
    executed (printed; FEQ_MISUSE_REPORT: the results as JSON)."""
    need_lmp()
    F.pytest_summary([RESULTS[c.id] for c in CASES if c.id in RESULTS], BY_ID, M.summarize,
                     f"[{LMP}, LAMMPS {VERSION}; {len(KNOWN)} known failures]", "FEQ_MISUSE_REPORT", capsys)
