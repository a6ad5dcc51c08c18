"""Decomposition independence and restart continuity of fix eq/contacts.

Random draws are keyed by (seed, atom tag, event counter), and the
per-contact state travels with the atom and is written to restart files:
the per-contact state (stretch, threshold, breaks, stiffness, anchor) must
be bit-for-bit identical on 1 and 2 MPI ranks, and a run split by
write_restart / read_restart (also onto a different number of ranks) must
continue bit-for-bit.  Compared: a dump of every contact with 17 digits
(global sums over contacts agree to rounding: their order follows the
order of the atoms on each rank).
"""
from pathlib import Path

import pytest

import eqtools

ROOT = Path(__file__).resolve().parents[2]
INPUT = ROOT / "unittest" / "python" / "inputs" / "in.contacts-state"
STEPS = 400

CASES = {
    "uniform": {},
    "smeared": {"threshold": "gaussian 1.0 0.25",
                "extra": "reform gaussian 0.2 0.05 stiffness gaussian 1.0 0.2 start reform"},
    "realistic-step": {"threshold": "realistic 1.0", "extra": "crossing step reform uniform 0 0.2"},
    # temperature, aging and an exponential delay: the budgets' run-out
    # times, formation times and delays left travel with the atoms and go
    # into restart files (with the fix's clock)
    "thermal-aging-delay": {"extra": "thermal 0.2 1.0 1.0 aging log 0.05 1.0 delay exp 0.1 rest 3",
                            "dumpextra": "f_c[8] f_c[9] f_c[10] f_c[11]"},
}


def state(tmp, mode, nprocs, **var):
    tmp.mkdir(parents=True, exist_ok=True)
    v = {"out": tmp, "mode": mode, "steps": STEPS}
    v.update(var)
    log = eqtools.run_lammps(INPUT, v, nprocs=nprocs, cwd=tmp)
    return log


def final_dump(tmp, mode):
    text = (tmp / f"state.{mode}.{STEPS}").read_text()
    rows = text.split("ITEM: ATOMS")[1]
    assert len(rows.splitlines()) > 400
    return rows


@pytest.mark.parametrize("case", sorted(CASES))
def test_one_and_two_ranks_give_identical_contacts(tmp_path, case):
    state(tmp_path / "np1", "run", 1, **CASES[case])
    state(tmp_path / "np2", "run", 2, **CASES[case])
    a, b = final_dump(tmp_path / "np1", "run"), final_dump(tmp_path / "np2", "run")
    assert a == b
    # contacts did break, several times, and atoms crossed rank boundaries
    breaks = [float(l.split()[3]) for l in a.strip().splitlines()[1:]]
    assert min(breaks) >= 1 and max(breaks) >= 3


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("ranks", [(1, 1), (2, 2), (1, 2)])
def test_restart_continues_bit_for_bit(tmp_path, case, ranks):
    nw, nr = ranks
    full = state(tmp_path, "run", 1, **CASES[case])
    state(tmp_path, "write", nw, **CASES[case])
    log = state(tmp_path, "read", nr, **CASES[case])
    assert final_dump(tmp_path, "run") == final_dump(tmp_path, "read")
    # the global friction force and count of breaks continue too (a sum
    # over contacts: equal to rounding, its order follows the atom order)
    a, b = thermo_line(full, STEPS), thermo_line(log, STEPS)
    assert a[0] == b[0] and a[2] == b[2]
    assert abs(a[1] - b[1]) <= 1e-14 * abs(a[1])
    assert "WARNING: Fix eq/contacts" not in log


def thermo_line(log, step):
    lines = [l for l in log.splitlines() if l.split()[:1] == [str(step)]]
    assert lines, log[-2000:]
    return [float(v) for v in lines[-1].split()]


def test_atom_sorting_does_not_change_the_contacts(tmp_path):
    """LAMMPS reorders atoms in memory (atom_modify sort): the state moves
    with them (copy_arrays) and the draws are keyed by atom ID."""
    state(tmp_path / "plain", "run", 1)
    state(tmp_path / "sorted", "run", 2, sort="7 1.5")
    assert final_dump(tmp_path / "plain", "run") == final_dump(tmp_path / "sorted", "run")


def test_changed_seed_on_restart_is_reported(tmp_path):
    state(tmp_path, "write", 1)
    log = state(tmp_path, "read", 1, seed=12345)
    assert "Fix eq/contacts: seed 12345 differs from the restart file's seed 99" in log
