"""Outputs and hooks of fix eq/contacts: fix_modify energy, the global
vector against sums computed here from the dumped positions and the model
(and, for consistency, against compute reduce over the per-atom array),
minimization (the contacts hold and the slider relaxes onto the anchors),
and atoms created after the fix."""
from pathlib import Path

import numpy as np

import eqtools
from eqtools import fkme

INPUT = Path(__file__).resolve().parent / "inputs" / "in.outputs"


def thermo_rows(log):
    rows = []
    for line in log.splitlines():
        w = line.split()
        if len(w) == 10 and w[0].isdigit():
            rows.append([float(v) for v in w])
    return rows


EPS = np.finfo(float).eps
# 400 atoms on a hex lattice in a periodic 2d box, one per contact
LATTICE_400 = """
units lj
dimension 2
atom_style atomic
lattice hex 1.1547005383792515
region box block 0 20 0 10 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
comm_modify cutoff 0.5
"""


def check_against_the_model(rows, dump_path):
    """The global outputs against the model evaluated here from the dump
    (every 50 steps of the sliding run): the stretch s_i = xu_i - a_i from
    the atom's unwrapped position and its anchor, F = sum k_i s_i, E = 1/2
    sum k_i s_i^2; the force in LAMMPS' force array f_x,i = -k_i s_i and
    its sum -F (the slider's force balance); and the break counts from the
    anchors: re-forming at 0 (reform delta 0.0) moves the anchor by the
    breaking stretch x_s in [0.75, 1.25] (crossing exact), so a contact
    with n breaks has 0.75 n <= a_i - a_i(0) <= 1.25 n, a_i(0) = xu_i(0)
    (start relaxed).

    Tolerances, all rounding: the test's s_i and the fix's differ by a few
    ulp of the coordinates, ds <= 4 eps max|xu, a|; a sum of n terms
    carries n eps sum|term|; thermo prints 15 digits (%20.15g: 5e-15
    relative)."""
    steps, d = fkme.read_dump(dump_path)
    assert list(steps) == [0, 50, 100, 150, 200, 250]
    thermo = {int(r[0]): r for r in rows if r[0] <= 250}
    a0 = d["f_c[6]"][0]
    assert np.array_equal(a0, d["xu"][0])               # relaxed start
    for k, step in enumerate(steps):
        xu, fx, nb, kk, a = (d[c][k] for c in ("xu", "fx", "f_c[4]", "f_c[5]", "f_c[6]"))
        n = len(xu)
        _, pe, _, _, F, _, total, _, _, _ = thermo[step]
        s = xu - a
        ds = 4 * EPS * max(np.abs(xu).max(), np.abs(a).max())
        F_ref, E_ref = np.sum(kk * s), 0.5 * np.sum(kk * s * s)
        tol_F = 5e-15 * abs(F) + np.sum(kk) * ds + 2 * n * EPS * np.sum(np.abs(kk * s))
        tol_E = 5e-15 * abs(pe) + np.sum(kk * np.abs(s)) * ds + 2 * n * EPS * E_ref
        assert abs(F - F_ref) <= tol_F, (step, F, F_ref, tol_F)
        assert abs(pe - E_ref) <= tol_E, (step, pe, E_ref, tol_E)
        assert np.all(np.abs(fx + kk * s) <= kk * ds + EPS * np.abs(kk * s)), step
        assert abs(F + np.sum(fx)) <= 5e-15 * abs(F) + 2 * n * EPS * np.sum(np.abs(fx)), step
        da = a - a0
        assert np.all(0.75 * nb - ds <= da) and np.all(da <= 1.25 * nb + ds), step
        assert total == np.sum(nb), step
    assert d["f_c[4]"][-1].min() >= 1 and d["f_c[4]"][-1].max() >= 3   # the test has breaks


def test_outputs_energy_minimize_and_new_atoms(tmp_path):
    log = eqtools.run_lammps(INPUT, {"out": tmp_path}, cwd=tmp_path)
    rows = thermo_rows(log)
    check_against_the_model(rows, tmp_path / "contacts.dump")
    # consistency of the outputs with each other; columns:
    # step pe f_c f_c[5] f_c[1] c_F f_c[3] c_B f_c[4] f_c[7]
    for step, pe, scalar, energy, F, sumF, total, sumB, att, n in rows:
        assert pe == scalar == energy                     # fix_modify energy yes
        assert abs(F - sumF) <= 1e-12 * max(1.0, abs(F))  # global F = compute reduce of f_c[3]
        assert total == sumB                              # total breaks = compute reduce of f_c[4]
        assert att == n
    run = [r for r in rows if r[0] <= 250]
    assert run[-1][6] > 500                               # contacts broke while sliding
    # minimization: nothing breaks, the slider relaxes onto the anchors
    after = [r for r in rows if r[0] > 250 and r[9] == 400]
    assert after and after[-1][6] == run[-1][6]
    assert after[-1][1] < 1e-20 and abs(after[-1][4]) < 1e-12
    # an atom created after the fix is a contact (relaxed where it appears)
    last = rows[-1]
    assert last[9] == 401 and last[8] == 401 and last[6] > run[-1][6]


def test_atoms_leaving_and_rejoining_the_group(tmp_path):
    """An atom that leaves the fix group stops being a contact; when it
    comes back it forms a fresh, relaxed contact (its break count kept)."""
    inp = tmp_path / "in.group"
    inp.write_text(LATTICE_400 + """
atom_modify sort 0 0.0
group g id 1:400
group back id 201:400
fix c g eq/contacts 1.0 5 threshold uniform 0.75 1.25
fix m all move linear 1.0 0.0 0.0 units box
timestep 0.01
compute sb back reduce sum f_c[1]
compute nb back reduce sum f_c[4]
thermo_style custom step f_c[7] c_sb c_nb
thermo_modify norm no
thermo 10
run 150
group g clear
group g id 1:200
run 50
group g id 201:400
run 0
""")
    log = eqtools.run_lammps(inp, cwd=tmp_path)
    rows = [[float(v) for v in l.split()] for l in log.splitlines()
            if len(l.split()) == 4 and l.split()[0].isdigit()]
    before = [r for r in rows if r[0] == 150][0]
    assert before[1] == 400 and before[2] > 50 and before[3] > 0     # stretched, broken
    away = [r for r in rows if r[0] == 200 and r[1] == 200][-1]
    assert away[2] == 0.0                                            # not contacts now
    back = rows[-1]
    assert back[1] == 400 and back[2] == 0.0 and back[3] == before[3]


def test_table_file_read_by_rank_0_only(tmp_path):
    """The table file is read by rank 0 and broadcast: a rank that cannot
    see the file neither fails nor waits for the others."""
    import os
    import shutil
    import subprocess
    table = tmp_path / "pc.table"
    table.write_text("KEY\nN 2\n\n1 0.75 1.0\n2 1.25 1.0\n")
    inp = tmp_path / "in.table"
    inp.write_text("""
units lj
atom_style atomic
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 random 20 1 NULL
mass 1 1.0
fix c all eq/contacts 1.0 5 threshold table pc.table KEY
run 0
""")
    a, b = tmp_path / "A", tmp_path / "B"
    a.mkdir()
    b.mkdir()
    mpirun = os.environ.get("MPIEXEC") or shutil.which("mpirun")

    def mpmd(with_file):
        for d in (a, b):
            f = d / "pc.table"
            if f.exists():
                f.unlink()
        shutil.copy(table, with_file / "pc.table")
        cmd = [mpirun, "-np", "1", "-wdir", str(a), eqtools.lmp_exe(), "-in", str(inp), "-log",
               "none", ":", "-np", "1", "-wdir", str(b), eqtools.lmp_exe(), "-in", str(inp),
               "-log", "none"]
        return subprocess.run(cmd, env=eqtools.mpi_env(), stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, timeout=120)
    ok = mpmd(a)          # rank 0 runs in A
    assert ok.returncode == 0 and "ERROR" not in ok.stdout, ok.stdout[-2000:]
    bad = mpmd(b)         # rank 0 cannot see it: a clean error on all ranks
    assert "ERROR: Fix eq/contacts threshold table: cannot open table file 'pc.table'" in bad.stdout


GROUP_INPUT = LATTICE_400 + """
group same type 1
group keep type 1
region slab block 5 9.6 INF INF INF INF
group sub region slab
if "${cut} == before" then "group ${grp} subtract ${grp} sub"
fix c ${grp} eq/contacts 1.0 7 threshold uniform 0.75 1.25 ${extra}
velocity keep set 1.0 0.0 0.0 units box
fix slide keep nve/noforce
timestep 0.01
thermo_style custom step f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8]
thermo_modify norm no format float %.17g
thermo 100
dump d keep custom 250 ${grp}.dump id f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6]
dump_modify d sort id format float %.17g
run 500
if "${cut} == between" then "group ${grp} subtract ${grp} sub"
run 500 pre ${pre}
"""


def test_group_all_and_the_same_atoms_in_another_group(tmp_path):
    """fix eq/contacts on group all skips the atoms' masks while every
    local atom has group all's bit: the same atoms in another group (its
    own bit, masks read) give the same numbers to the bit, every global
    and per-atom output, athermal and thermal, on 1 and 2 ranks.  LAMMPS
    can take atoms out of group all (group all subtract all G): before
    the fix is defined, or between runs (also with pre no, where the
    run has no set-up), the same subtraction applied to the other group
    gives the same numbers too.  The subtracted slab, x in [5, 9.5], lies
    on rank 0 of 2 and slides onto rank 1 during the run: rank 1 starts
    with every mask set and must find the arrivals at a neighbor build."""
    inp = tmp_path / "in.groups"
    inp.write_text(GROUP_INPUT)
    cases = [("", "no", "yes", 1), ("", "no", "yes", 2),
             ("reform uniform -0.2 0.2 crossing exact", "no", "yes", 1),
             ("thermal 0.02 1 1 barrier 2 0.25", "no", "yes", 2),
             ("aging log 0.05 1 delay exp 10", "no", "yes", 1),
             ("", "before", "yes", 1), ("", "before", "yes", 2),
             ("thermal 0.02 1 1", "before", "yes", 2), ("", "between", "yes", 2),
             ("", "between", "no", 1), ("thermal 0.02 1 1", "between", "no", 2)]
    for extra, cut, pre, ranks in cases:
        out = {}
        for grp in ("all", "same"):
            log = eqtools.run_lammps(inp, {"grp": grp, "extra": extra, "cut": cut, "pre": pre},
                                     nprocs=ranks, cwd=tmp_path)
            rows = [l for l in log.splitlines() if len(l.split()) == 9 and l.split()[0].isdigit()]
            dump = (tmp_path / f"{grp}.dump").read_text()
            out[grp] = (rows, dump)
        rows = out["all"][0]
        counts = [float(r.split()[7]) for r in rows]    # f_c[7]: contacts of the group
        assert len(rows) == 12 and float(rows[-1].split()[3]) > 300, extra   # broke while sliding
        assert counts[-1] == (300 if cut != "no" else 400), (extra, cut)   # 100 in the slab
        assert out["same"] == out["all"], (extra, cut, pre, ranks)
