"""Reliability of every stateful style of the package against the domain
decomposition, split runs, run 0, restart files and data files.

Cases (inputs/in.reliability-*; the atoms are read from data files written
here, IDs in a fixed order, so that the same site has the same ID on any
number of ranks; create_atoms box would number them processor by
processor):

* contacts          fix eq/contacts, 192 contacts (16 x 12 square lattice),
                    slider driven by fix move;
* contacts-pair     the same with pair eq/elastic (kappa 0.1, lambda_c 3,
                    about 36 partners per contact): avalanches;
* quasistatic-pair  fix eq/quasistatic driving the contacts with pair
                    eq/elastic (kappa 0.06);
* substrate-pair    fix eq/substrate, 12 x 4 blocks coupled by pair
                    eq/elastic, driven, overdamped; weak blocks (fix_modify
                    kc) and quenched disorder; kinks slip the blocks by
                    whole periods (reverse break: the well origins are
                    state);
* substrate-bond    the same physics on a chain of 40 blocks coupled by
                    bond_style harmonic;
* meso-screen       fix eq/meso with screening, 12 x 4 blocks sliding past a
                    pinned stripe;
* meso-pair         fix eq/meso blocks coupled by pair eq/elastic, driven,
                    overdamped, past the static peak into kinetic sliding.

Compared (dumps sorted by id, %.17g, every 50 steps of 400): the unwrapped
position xu (not x and ix: LAMMPS re-wraps an atom that sits exactly on a
periodic boundary at different moments, e.g. when a restart file is
written, which moves x by a box length and ix by one), the velocity, the
force on the atom and every per-atom column of the fix; and the avalanche
records of fix eq/contacts.

What must agree to the last bit (the package's promises): everything of
fix eq/contacts without a pair style (draws keyed by (seed, ID, breaks));
the thresholds, break counts, stiffnesses and avalanche records with pair
eq/elastic (synchronous avalanche rounds); every block of fix eq/meso with
screening (partners summed in the order of their IDs); the discrete state
of fix eq/substrate (k_c, disorder factor, well origin, site) and of fix
eq/meso (site).

What agrees to rounding: all that depends on the field of pair
eq/elastic, h_i = sum_j k_ij (s_i - s_j), a sum over up to 36 partners
in the order of the neighbor lists (which follows the decomposition) and
updated incrementally between list builds; and whatever an integrator
then makes of it (the blocks' positions, velocities, forces).  Also
bond_style harmonic with newton off (the two halves of a bond force are
added on different ranks).  Tolerance: RTOL = 1e-12 of the largest
magnitude of the column in the reference run.  Rounding of an n-term sum
is at most n eps sum|terms| (36 x 2.2e-16 = 8e-15 relative per
evaluation); measured over 400 steps: at most 2e-14 relative, so the
tolerance has a margin of 50.  A physical difference is far larger: one
break changes a stretch by at least 0.55, one slip a displacement by a
period, and the discrete state is compared exactly.
"""
import os
import re
from pathlib import Path

import numpy as np
import pytest

import eqtools
from eqtools import fkme

# up to 4 ranks share 2 cores: a rank that waits must give the core back
# (Open MPI's busy polling makes such runs up to 100 times slower on a
# loaded machine); inherited by the runs of this file only
os.environ.setdefault("OMPI_MCA_mpi_yield_when_idle", "1")

INPUTS = Path(__file__).resolve().parent / "inputs"
CONTACTS = INPUTS / "in.reliability-contacts"
SUBSTRATE = INPUTS / "in.reliability-substrate"
MESO = INPUTS / "in.reliability-meso"

STEPS, HALF, EVERY = 400, 250, 50
RTOL = 1e-12

C_STATE = ["f_c[2]", "f_c[4]", "f_c[5]"]               # threshold, breaks, stiffness
C_ALL = ["xu", "vx", "fx", "f_c[1]", "f_c[2]", "f_c[4]", "f_c[5]", "f_c[6]", "f_c[7]"]
S_ALL = ["xu", "vx", "fx"] + [f"f_sub[{k}]" for k in range(1, 9)]
S_STATE = ["f_sub[4]", "f_sub[5]", "f_sub[6]", "f_sub[7]"]   # kc, disorder, well origin, site
M_ALL = ["xu", "vx", "fx"] + [f"f_m[{k}]" for k in range(1, 8)]

# input, data file, variables, columns compared exactly, columns to
# rounding, avalanche records, newton matters
CASES = {
    "contacts": (CONTACTS, "contacts", dict(kappa=0.0, drive="move", dX=0.01),
                 C_ALL, [], True, False),
    "contacts-pair": (CONTACTS, "contacts", dict(kappa=0.1, drive="move", dX=0.004),
                      ["xu", "vx"] + C_STATE, ["fx", "f_c[1]", "f_c[6]", "f_c[7]"], True, True),
    "quasistatic-pair": (CONTACTS, "contacts", dict(kappa=0.06, drive="qs", dX=0.05),
                         ["vx"] + C_STATE, ["xu", "fx", "f_c[1]", "f_c[6]", "f_c[7]"], True, True),
    "substrate-pair": (SUBSTRATE, "blocks", dict(coupling="pair"),
                       S_STATE, [c for c in S_ALL if c not in S_STATE], False, True),
    "substrate-bond": (SUBSTRATE, "chain", dict(coupling="bond"),
                       S_STATE, [c for c in S_ALL if c not in S_STATE], False, True),
    "meso-screen": (MESO, "blocks", dict(coupling="screen"), M_ALL, [], False, False),
    "meso-pair": (MESO, "blocks", dict(coupling="pair"),
                  ["f_m[7]"], [c for c in M_ALL if c != "f_m[7]"], False, True),
}
# processor grids that split the interacting region; the chain (along x,
# at y = 0) is split along x, and by 2 2 1 with its atoms on the boundary
# between two subdomains in y
GRIDS_2D = [(2, "2 1 1"), (3, "3 1 1"), (4, "4 1 1"), (4, "1 4 1"), (4, "2 2 1")]
GRIDS_CHAIN = [(2, "2 1 1"), (3, "3 1 1"), (4, "4 1 1"), (4, "2 2 1")]


# ------------------------------------------------------------ data files
def write_data(path, pts, box, bonds=None):
    """A LAMMPS data file with the atoms in the given order (IDs 1..n)."""
    style = "bond" if bonds is not None else "atomic"
    lines = ["# FRICTION-EQ reliability test", "", f"{len(pts)} atoms", "1 atom types"]
    if bonds is not None:
        lines += [f"{len(bonds)} bonds", "1 bond types"]
    lines += ["", f"{box[0][0]!r} {box[0][1]!r} xlo xhi", f"{box[1][0]!r} {box[1][1]!r} ylo yhi",
              "-0.5 0.5 zlo zhi", "", "Masses", "", "1 1.0", "", f"Atoms # {style}", ""]
    for i, (x, y) in enumerate(pts, 1):
        lines.append(f"{i} 1 1 {x!r} {y!r} 0.0" if bonds is not None else f"{i} 1 {x!r} {y!r} 0.0")
    if bonds is not None:
        lines += ["", "Bonds", ""] + [f"{k} 1 {a} {b}" for k, (a, b) in enumerate(bonds, 1)]
    Path(path).write_text("\n".join(lines) + "\n")


def data_file(name, folder):
    path = Path(folder) / f"{name}.data"
    if path.exists():
        return path
    if name == "contacts":          # 16 x 12 contacts, spacing 1
        write_data(path, [(i + 0.5, j + 0.5) for j in range(12) for i in range(16)],
                   [(0.0, 16.0), (0.0, 12.0)])
    elif name == "blocks":          # 12 x 4 blocks at integer sites
        write_data(path, [(float(i), float(j)) for j in range(4) for i in range(12)],
                   [(-0.5, 11.5), (-0.5, 3.5)])
    elif name == "chain":           # 40 blocks along x, a ring of bonds
        write_data(path, [(float(i), 0.0) for i in range(40)], [(-0.5, 39.5), (-2.0, 2.0)],
                   bonds=[(i, i % 40 + 1) for i in range(1, 41)])
    elif name == "contacts3":       # 3 contacts on 4 ranks
        write_data(path, [(0.5, 0.5), (1.5, 2.5), (2.5, 0.7)], [(0.0, 4.0), (0.0, 4.0)])
    elif name == "blocks3":         # 3 blocks on 4 ranks (subdomains wider than the skin)
        write_data(path, [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)], [(-0.5, 11.5), (-0.5, 0.5)])
    return path


# --------------------------------------------------------------- running
_CACHE = {}


def run(case, folder, tag, nprocs=1, **var):
    inp, data, base, *_ = CASES[case]
    folder.mkdir(parents=True, exist_ok=True)
    v = dict(base, data=data_file(data, folder), out=folder, tag=tag, steps=STEPS, half=HALF,
             every=EVERY)
    v.update(var)
    return eqtools.run_lammps(inp, v, nprocs=nprocs, cwd=folder)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The uninterrupted 1-rank run of a case (restart file at HALF),
    once per case."""
    def get(case):
        if case not in _CACHE:
            d = tmp_path_factory.mktemp(case)
            log = run(case, d, "ref", wrestart=1)
            _CACHE[case] = (d, log)
        return _CACHE[case]
    return get


def dump(path):
    steps, d = fkme.read_dump(path)
    return list(steps), d


def compare(ref, other, exact, close, frames=None, what=""):
    """Columns `exact` bitwise and `close` to RTOL of the reference's
    largest magnitude, in the frames (timesteps) of `other` (or `frames`)."""
    sr, dr = ref
    so, do = other
    frames = so if frames is None else frames
    for step in frames:
        i, j = sr.index(step), so.index(step)
        assert np.array_equal(dr["id"][i], do["id"][j]), (what, step)
        for c in exact:
            bad = np.nonzero(dr[c][i] != do[c][j])[0]
            assert len(bad) == 0, (what, step, c, dr["id"][i][bad[:5]], dr[c][i][bad[:5]],
                                   do[c][j][bad[:5]])
        for c in close:
            scale = max(np.abs(dr[c]).max(), 1e-300)
            err = np.abs(dr[c][i] - do[c][j]).max()
            assert err <= RTOL * scale, (what, step, c, err, scale)


def package_warnings(log):
    """Warnings of the package's styles (LAMMPS' own, e.g. a restart file
    read on another processor grid, are expected)."""
    return [l for l in log.splitlines() if re.search(r"WARNING.*\b(Fix|Pair|fix|pair) eq/", l)]


def records(folder, tag):
    return [l for l in (folder / f"aval.{tag}").read_text().splitlines() if not l.startswith("#")]


def activity(case, d):
    """The run did what it tests: contacts broke several times / blocks
    slipped / meso blocks broke their contacts and slid."""
    if case.startswith(("contacts", "quasistatic")):
        assert d["f_c[4]"][-1].min() >= 1 and d["f_c[4]"][-1].max() >= 3
    elif case.startswith("substrate"):
        assert d["f_sub[6]"][-1].sum() >= 30
    elif case == "meso-screen":
        assert d["f_m[3]"][-1].max() > 0 and d["f_m[4]"][-1].max() > 1.0   # rates, eps > 1
    else:
        assert d["f_m[1]"][-1].min() > 3.0 and np.ptp(d["f_m[1]"][-1]) > 0.1


# ------------------------------------------------------------------ tests
@pytest.mark.parametrize("case", sorted(CASES))
def test_any_processor_grid_gives_the_same_run(reference, case):
    """1, 2, 3 and 4 ranks (oversubscribed) on grids that split the
    interacting region (4 1 1, 1 4 1, 2 2 1, ...), and newton off where a
    pair or bond style is involved: every frame of the run as the 1-rank
    reference (bitwise / to rounding, see the module doc).  The atoms
    migrate: the slider travels 1.6 to 4 lattice spacings, the blocks
    slip by whole periods or slide 6 spacings; subdomains are 1 to 20
    spacings wide."""
    d, _ = reference(case)
    _, data, _, exact, close, aval, newton = CASES[case]
    ref = dump(d / "dump.ref")
    activity(case, ref[1])
    grids = list(GRIDS_CHAIN if data == "chain" else GRIDS_2D)
    if newton:
        grids.append((2, "2 1 1", "off"))
    for n, grid, *nw in grids:
        tag = f"np{n}_{grid.replace(' ', '')}" + ("_off" if nw else "")
        run(case, d, tag, n, grid=grid, newton=nw[0] if nw else "on")
        other = dump(d / f"dump.{tag}")
        assert other[0] == ref[0]
        compare(ref, other, exact, close, what=tag)
        if aval:
            assert records(d, tag) == records(d, "ref"), tag


def split_run(case, d):
    """run HALF, write_dump, run 0, write_dump, write_data, run the rest,
    on 4 ranks (2 2 1) with a restart file written at HALF."""
    if not (d / "split" / "dump.split").exists():
        run(case, d / "split", "split", 4, grid="2 2 1", mode="split", wrestart=1)
    return d / "split"


def contact_stretch_split(case, exact, close):
    """fix eq/contacts stores the stretch of a contact that broke in a step
    as r + overshoot, and recomputes it as xu - anchor at the start of the
    next run: both are the same number to rounding (an ulp of xu), so the
    stretch and the force of such contacts at the first step of a run are
    compared to rounding (test_run0_keeps_contact_stretches_bitwise shows
    the difference)."""
    if case.startswith(("contacts", "quasistatic")):
        moved = [c for c in ("fx", "f_c[1]") if c in exact]
        return [c for c in exact if c not in moved], close + moved
    return exact, close


@pytest.mark.parametrize("case", sorted(CASES))
def test_split_run_and_run0(reference, case):
    """run N/2 + run 0 + run N/2 on 4 ranks equals run N on 1 rank (all
    frames after the split as in the decomposition test; the frame of the
    split itself with the stretches of contacts that broke in that step to
    rounding), and run 0 changes nothing: the state before and after it is
    identical (pair fields, recomputed from scratch at the start of a run,
    to rounding)."""
    d, _ = reference(case)
    _, _, _, exact, close, aval, _ = CASES[case]
    s = split_run(case, d)
    ref, other = dump(d / "dump.ref"), dump(s / "dump.split")
    assert other[0] == ref[0]
    later = [t for t in ref[0] if t > HALF]
    compare(ref, other, exact, close, frames=later, what="split")
    ex0, cl0 = contact_stretch_split(case, exact, close)
    compare(ref, other, ex0, cl0, frames=[HALF], what="split step")
    if aval:
        assert records(s, "split") == records(d, "ref")
    before, after = dump(s / "before0.split"), dump(s / "after0.split")
    assert before[0] == after[0] == [HALF]
    compare(before, after, ex0, cl0, what="run 0")
    compare(ref, before, ex0, cl0, what="before run 0")


@pytest.mark.parametrize("case", sorted(CASES))
def test_restart_mid_run_continues(reference, case):
    """write_restart in the middle of a run (the restart command, at step
    HALF) and read_restart: the continuation equals the uninterrupted run,
    on the same number of ranks (1 -> 1) and on another (4 -> 3): the
    frames after HALF as in the decomposition test, the frame at HALF with
    the stretches of contacts that broke in that step to rounding; the
    avalanche records of the two parts add up to the whole; no warning."""
    d, _ = reference(case)
    _, _, _, exact, close, aval, _ = CASES[case]
    s = split_run(case, d)
    ref = dump(d / "dump.ref")
    later = [t for t in ref[0] if t > HALF]
    ex0, cl0 = contact_stretch_split(case, exact, close)
    for folder, n, grid in ((d, 1, "* * *"), (s, 3, "3 1 1")):
        log = run(case, folder, f"read{n}", n, grid=grid, mode="read")
        other = dump(folder / f"dump.read{n}")
        assert other[0] == [HALF] + later
        compare(ref, other, exact, close, frames=later, what=f"read{n}")
        compare(ref, other, ex0, cl0, frames=[HALF], what=f"read{n} step")
        assert not package_warnings(log), log[-3000:]
        if aval:
            first = [l for l in records(d, "ref") if int(l.split()[0]) <= HALF]
            assert first + records(folder, f"read{n}") == records(d, "ref")


def test_run0_keeps_contact_stretches_bitwise(reference):
    """run 0 must change nothing, bit for bit, without a pair style."""
    d, _ = reference("contacts")
    s = split_run("contacts", d)
    before, after = dump(s / "before0.split"), dump(s / "after0.split")
    compare(before, after, C_ALL, [], what="run 0")


@pytest.mark.parametrize("case", sorted(CASES))
def test_data_file_round_trip(reference, case):
    """write_data in the middle of a run, read_data on 2 ranks and the fix
    defined anew.  Data files hold no per-atom state of the package's
    fixes (nor the pair coefficients): what a user gets is a fresh start at
    the saved positions.  Tested: positions, image flags and velocities
    round-trip bit for bit; then

    * eq/contacts: every contact starts relaxed (stretch 0, anchor = xu,
      no breaks) with the thresholds and stiffnesses of step 0 of the
      original run (the draws are keyed by (seed, ID, breaks), and the
      break counts start again at 0);
    * eq/substrate: displacement 0 (the sites are the saved positions), no
      slip, the stage back at X0, the disorder factors of the original
      run (keyed by (seed, ID)) and the k_c the input sets;
    * eq/meso: displacement 0, relaxed contacts (F = 0, attached fraction
      1), no rate;

    and the run continues without error or warning, with breaks / slips."""
    d, _ = reference(case)
    s = split_run(case, d)
    folder = s / "fromdata"
    log = run(case, folder, "data", 2, data=s / "mid.data", mode="data")
    assert not package_warnings(log), log[-3000:]
    saved, new = dump(s / "after0.split"), dump(folder / "dump.data")
    ref = dump(d / "dump.ref")
    i = new[0].index(0)
    for c in ("x", "y", "ix", "vx"):
        assert np.array_equal(saved[1][c][0], new[1][c][i]), c
    n = new[1]
    zero = np.zeros_like(n["xu"][i])
    if case.startswith(("contacts", "quasistatic")):
        assert np.array_equal(n["f_c[1]"][i], zero) and np.array_equal(n["f_c[4]"][i], zero)
        assert np.array_equal(n["f_c[6]"][i], n["xu"][i])
        assert np.array_equal(n["f_c[2]"][i], ref[1]["f_c[2]"][0])
        assert np.array_equal(n["f_c[5]"][i], ref[1]["f_c[5]"][0])
        assert n["f_c[4]"][-1].max() >= 1
    elif case.startswith("substrate"):
        for c in ("f_sub[1]", "f_sub[6]"):
            assert np.array_equal(n[c][i], zero), c
        assert np.array_equal(n["f_sub[7]"][i], n["xu"][i])
        assert np.allclose(n["f_sub[3]"][i], 0.9, rtol=1e-14)          # K X0 = f0
        for c in ("f_sub[4]", "f_sub[5]"):
            assert np.array_equal(n[c][i], ref[1][c][0]), c
        assert n["f_sub[6]"][-1].sum() > 0
    else:
        for c in ("f_m[1]", "f_m[2]", "f_m[3]"):
            assert np.array_equal(n[c][i], zero), c
        assert np.array_equal(n["f_m[6]"][i], zero + 1.0)
        assert np.array_equal(n["f_m[7]"][i], n["xu"][i])
        assert n["f_m[3]"][-1].max() > 0


THREE = {"contacts-pair": ("contacts3", "2 2 1", {}),
         "substrate-pair": ("blocks3", "4 1 1", {"weak1": 2, "weak2": 2}),
         "meso-pair": ("blocks3", "4 1 1", {"stripe": 1})}


@pytest.mark.parametrize("case", sorted(THREE))
def test_more_ranks_than_atoms(tmp_path, case):
    """3 atoms on 4 ranks: ranks without atoms take part in every
    reduction and communication; the run equals the 1-rank run."""
    data, grid, var = THREE[case]
    _, _, _, exact, close, aval, _ = CASES[case]
    path = data_file(data, tmp_path)
    run(case, tmp_path, "np1", 1, data=path, **var)
    log = run(case, tmp_path, "np4", 4, data=path, grid=grid, **var)
    assert not package_warnings(log), log[-3000:]
    a, b = dump(tmp_path / "dump.np1"), dump(tmp_path / "dump.np4")
    assert a[0] == b[0] and len(a[1]["id"][0]) == 3
    compare(a, b, exact, close, what="3 atoms on 4 ranks")
    if aval:
        assert records(tmp_path, "np1") == records(tmp_path, "np4")
        assert a[1]["f_c[4]"][-1].min() >= 1


def crossing_steps(d):
    """Steps in which a block of the substrate-pair case passed the end of
    its well (its well origin changed)."""
    steps, a = dump(d)
    o = a["f_sub[6]"]
    return [steps[k] for k in range(1, len(steps)) if np.any(o[k] != o[k - 1])]


def test_substrate_split_at_a_crossing_step(tmp_path):
    """The substrate-pair case split (run + run, and write_restart /
    read_restart) exactly at a step in which a block crossed into the next
    well continues as the uninterrupted run, to rounding."""
    run("substrate-pair", tmp_path, "every", 1, every=1)
    steps = [t for t in crossing_steps(tmp_path / "dump.every") if 100 < t < STEPS - 50]
    assert steps
    h = steps[0]
    ref = dump(tmp_path / "dump.every")
    var = dict(every=1, half=h)
    run("substrate-pair", tmp_path, "split", 1, mode="split", **var)
    run("substrate-pair", tmp_path, "w", 1, wrestart=1, steps=h, **var)
    run("substrate-pair", tmp_path, "read", 1, mode="read", **var)
    _, _, _, exact, close, *_ = CASES["substrate-pair"]
    for tag in ("split", "read"):
        other = dump(tmp_path / f"dump.{tag}")
        compare(ref, other, exact, close, frames=[t for t in other[0] if t > h], what=tag)


def test_substrate_split_between_crossings(tmp_path):
    """The control of the test above: split at a step without a crossing,
    the continuation equals the uninterrupted run to rounding."""
    run("substrate-pair", tmp_path, "every", 1, every=1)
    cross = set(crossing_steps(tmp_path / "dump.every"))
    h = next(t for t in range(200, STEPS) if t not in cross and t - 1 in cross)
    ref = dump(tmp_path / "dump.every")
    run("substrate-pair", tmp_path, "split", 1, mode="split", every=1, half=h)
    other = dump(tmp_path / "dump.split")
    _, _, _, exact, close, *_ = CASES["substrate-pair"]
    compare(ref, other, exact, close, frames=[t for t in other[0] if t > h], what="split")
