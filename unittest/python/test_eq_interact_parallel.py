"""Interacting contacts (pair eq/elastic): decomposition independence and
restart continuity.

The avalanche rounds are synchronous (all contacts over their thresholds
break at once, then the field is updated), so the sequence of breaks does
not depend on how the contacts are split over ranks.  The field h_i is a
sum over neighbours whose order follows the neighbour lists: values agree
to rounding, breaks and avalanches exactly.  Compared: the avalanche
records (step, size, trigger, rounds), every contact's break count, and
stretches / thresholds / anchors to 1e-9.

Identical results need the same atom IDs at the same sites: the random
draws are keyed by atom ID, and create_atoms numbers atoms processor by
processor.  The create_atoms tests below run on the grid LAMMPS picks for
2 ranks (1 x 2 here: a split along y keeps the IDs of 1 rank);
test_split_along_x_needs_the_same_atom_ids reads the contacts from a data
file (write_data once) on a 2 x 1 grid, and shows that create_atoms on that
grid gives other contacts.
"""
from pathlib import Path

import numpy as np
import pytest

import eqtools

ROOT = Path(__file__).resolve().parents[2]
INPUT = ROOT / "unittest" / "python" / "inputs" / "in.interact-state"
STEPS = 600
CASES = {"qs": {"drive": "qs", "kappa": 0.06},
         "step-avalanche": {"drive": "step", "kappa": 0.1, "dX": 0.004}}


def run(tmp, mode, nprocs, **var):
    tmp.mkdir(parents=True, exist_ok=True)
    v = {"out": tmp, "mode": mode, "steps": STEPS}
    v.update(var)
    return eqtools.run_lammps(INPUT, v, nprocs=nprocs, cwd=tmp)


def final_state(tmp, mode):
    text = (tmp / f"state.{mode}.{STEPS}").read_text()
    rows = np.array([[float(v) for v in l.split()]
                     for l in text.split("ITEM: ATOMS")[1].strip().splitlines()[1:]])
    return rows  # id stretch threshold nbreak stiffness anchor interact


def avalanches(tmp, mode):
    return [l for l in (tmp / f"aval.{mode}").read_text().splitlines() if not l.startswith("#")]


def same(a, b):
    assert a.shape == b.shape
    assert np.array_equal(a[:, 0], b[:, 0]) and np.array_equal(a[:, 3], b[:, 3])
    assert np.max(np.abs(a[:, [1, 2, 5, 6]] - b[:, [1, 2, 5, 6]])) < 1e-9


@pytest.mark.parametrize("case", sorted(CASES))
def test_split_along_x_needs_the_same_atom_ids(tmp_path, case):
    """The draws are keyed by atom ID.  create_atoms numbers the atoms
    processor by processor, so with the box split along x (processors
    2 1 1) the same lattice site gets another ID than on 1 rank, and the
    contacts get other thresholds: the runs differ.  With the contacts
    read from a data file (write_data once; same IDs at the same sites) the
    split along x gives the breaks, avalanches, stretches and interaction
    forces of 1 rank."""
    var = dict(CASES[case])
    run(tmp_path / "data", "data", 1, **var)
    data = tmp_path / "data" / "contacts.data"
    run(tmp_path / "np1", "run", 1, datafile=data, fromdata=1, **var)
    run(tmp_path / "np2x", "run", 2, datafile=data, fromdata=1, grid="2 1 1", **var)
    a, b = final_state(tmp_path / "np1", "run"), final_state(tmp_path / "np2x", "run")
    same(a, b)
    assert avalanches(tmp_path / "np1", "run") == avalanches(tmp_path / "np2x", "run")
    assert a[:, 3].min() >= 1 and np.abs(a[:, 6]).max() > 0   # breaks, and a field
    if case != "qs":
        return
    # create_atoms on a 2 x 1 grid: other IDs, other contacts
    run(tmp_path / "np2c", "run", 2, grid="2 1 1", **var)
    c = final_state(tmp_path / "np2c", "run")
    assert not np.array_equal(a[:, 3], c[:, 3]) or np.abs(a[:, 2] - c[:, 2]).max() > 1e-6


@pytest.mark.parametrize("case", sorted(CASES))
def test_one_and_two_ranks_same_breaks_and_avalanches(tmp_path, case):
    run(tmp_path / "np1", "run", 1, **CASES[case])
    run(tmp_path / "np2", "run", 2, **CASES[case])
    a, b = final_state(tmp_path / "np1", "run"), final_state(tmp_path / "np2", "run")
    same(a, b)
    av1, av2 = avalanches(tmp_path / "np1", "run"), avalanches(tmp_path / "np2", "run")
    assert av1 == av2
    sizes = [int(l.split()[1]) for l in av1]
    # the runs did what they test: many breaks, multi-contact avalanches
    assert a[:, 3].min() >= 1 and max(sizes) >= 5


@pytest.mark.parametrize("case", sorted(CASES))
def test_newton_off_on_two_ranks(tmp_path, case):
    """newton off on 2 ranks: the breaks and avalanches of 1 rank with
    newton on (the style returns the ghost shares of a break's field by
    its own reverse communication, whatever the newton setting)."""
    run(tmp_path / "np1", "run", 1, **CASES[case])
    run(tmp_path / "np2off", "run", 2, newton="off", **CASES[case])
    same(final_state(tmp_path / "np1", "run"), final_state(tmp_path / "np2off", "run"))
    assert avalanches(tmp_path / "np1", "run") == avalanches(tmp_path / "np2off", "run")


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("ranks", [(1, 1), (1, 2)])
def test_restart_continues(tmp_path, case, ranks):
    nw, nr = ranks
    run(tmp_path, "run", 1, **CASES[case])
    run(tmp_path, "write", nw, **CASES[case])
    log = run(tmp_path, "read", nr, **CASES[case])
    same(final_state(tmp_path, "run"), final_state(tmp_path, "read"))
    full = avalanches(tmp_path, "run")
    assert avalanches(tmp_path, "write") + avalanches(tmp_path, "read") == full
    assert "WARNING: Fix eq" not in log and "WARNING: Pair eq" not in log


def test_a_change_too_large_to_follow_on_one_rank(tmp_path):
    """A break that changes a stretch by 1.25e6 (contact 7, moved by 500
    periodic images of a box 2500 long between runs) on the one rank that
    holds it: the
    field is recomputed on every rank (an incremental update would keep
    2e6 x 1e-16 of rounding in the partners' fields), and 2 ranks give
    the breaks, avalanches and field of 1 rank."""
    inp = ROOT / "unittest" / "python" / "inputs" / "in.huge-change"
    out = {}
    for n in (1, 2):
        d = tmp_path / f"np{n}"
        d.mkdir()
        eqtools.run_lammps(inp, {"out": d}, nprocs=n, cwd=d)
        text = (d / "state").read_text()
        out[n] = np.array([[float(v) for v in l.split()]
                           for l in text.split("ITEM: ATOMS")[1].strip().splitlines()[1:]])
        out[n, "aval"] = [l for l in (d / "aval").read_text().splitlines() if not l.startswith("#")]
    same(out[1], out[2])
    assert out[1, "aval"] == out[2, "aval"]
    # contact 7 broke at the step after the move (its anchor followed it)
    # and re-formed near 0
    assert out[1][6, 3] >= 1 and abs(out[1][6, 1]) < 10.0 and out[1][6, 5] > 1e6
