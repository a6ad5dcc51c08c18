"""pair eq/elastic against an independent numpy evaluation of the model
(paper Sec. IV): h_i = sum_j k_ij (x_i - x_j) with the crossover kernel
(or a table), energy (1/2) sum_pairs k_ij (x_i - x_j)^2, force on contact
i along the sliding direction -(k_i x_i + h_i), per-atom energies,
single() (compute pair/local), the virial, and sum_i h_i = 0 (the
interaction redistributes force, it does not change the friction force).
"""
import math
from pathlib import Path

import numpy as np
import pytest

import eqtools

ROOT = Path(__file__).resolve().parents[2]
INPUT = ROOT / "unittest" / "python" / "inputs" / "in.interact-forces"
TABLE = ROOT / "potentials" / "eq_crossover.table"


def kernel_crossover(ft, lam):
    return lambda r, c2: np.where(r <= lam, ft / r, ft * lam * lam / r ** 3)


def kernel_aniso(r, c2):
    # ANISO_TEST of eq_crossover.table: k0 = 1/r, k2 = 0.3/r up to r = 8
    return np.where(r <= 8.0, (1.0 + 0.3 * c2) / r, 0.0)


CASES = {
    "crossover": ({"coeff": "0.3 2.0", "rcut": 3.5}, kernel_crossover(0.3, 2.0), 3.5, 0),
    "near-zone-y": ({"coeff": "0.2 3.0", "rcut": 3.0, "dir": "y"}, kernel_crossover(0.2, 3.0), 3.0, 1),
    "aniso-table": ({"coeff": f"table {TABLE} ANISO_TEST", "rcut": 4.0}, kernel_aniso, 4.0, 0),
}


def read_dump(path):
    text = Path(path).read_text()
    box = text.split("ITEM: BOX BOUNDS")[1].splitlines()[1:3]
    L = np.array([float(b.split()[1]) - float(b.split()[0]) for b in box])
    rows = text.split("ITEM: ATOMS")[1].strip().splitlines()[1:]
    return L, np.array([[float(v) for v in l.split()] for l in rows])


@pytest.mark.parametrize("case", sorted(CASES))
def test_pair_against_numpy(tmp_path, case):
    var, kern, rcut, d = CASES[case]
    log = eqtools.run_lammps(INPUT, dict(var, out=tmp_path), cwd=tmp_path)
    L, a = read_dump(tmp_path / "atoms.dump")
    ids, x, y, s, k, h, fx, fy, pe = a.T
    n = len(ids)
    # all pairs, minimum image in the periodic box
    dx = x[:, None] - x[None, :]
    dy = y[:, None] - y[None, :]
    dx -= L[0] * np.round(dx / L[0])
    dy -= L[1] * np.round(dy / L[1])
    r = np.hypot(dx, dy)
    np.fill_diagonal(r, np.inf)
    inside = r <= rcut
    c2 = 2.0 * (dx if d == 0 else dy) ** 2 / np.where(inside, r * r, 1.0) - 1.0
    kij = np.where(inside, kern(np.where(inside, r, 1.0), c2), 0.0)
    ds = s[:, None] - s[None, :]
    h_ref = np.sum(kij * ds, axis=1)
    e_ref = 0.25 * np.sum(kij * ds * ds)
    scale = np.max(np.abs(h_ref))
    assert scale > 0.05                      # the test exercises the interaction
    assert np.max(np.abs(h - h_ref)) < 1e-12 * max(1.0, scale)
    assert abs(np.sum(h)) < 1e-12 * n * scale
    # forces: spring + interaction along the sliding direction only
    f_along, f_across = (fx, fy) if d == 0 else (fy, fx)
    assert np.max(np.abs(f_along + k * s + h)) < 1e-12
    assert np.max(np.abs(f_across)) == 0.0
    # energies: per atom and total
    assert np.max(np.abs(pe - 0.25 * np.sum(kij * ds * ds, axis=1))) < 1e-12
    thermo = [l for l in log.splitlines() if l.split()[:1] == ["0"]][-1].split()
    # lj units: thermo normalizes extensive values by the number of atoms
    assert abs(float(thermo[1]) * n - e_ref) < 1e-10 * max(1.0, e_ref)
    # virial: W_ab = sum_pairs del_a f_b with f = -k_ij (x_i - x_j) along dir
    # (pressure = W / area; the atoms are at rest)
    fpair = -kij * ds
    w = {"xx": 0.5 * np.sum(dx * fpair) if d == 0 else 0.0,
         "yy": 0.5 * np.sum(dy * fpair) if d == 1 else 0.0}
    area = L[0] * L[1]
    pxx, pyy, pxy = (float(v) for v in thermo[3:6])
    # (LAMMPS' xy entry is sum del_x f_y; for dir x it is sum del_x f_y = 0)
    assert abs(pxx - w["xx"] / area) < 1e-10 and abs(pyy - w["yy"] / area) < 1e-10
    assert abs(pxy - (0.5 * np.sum(dx * fpair) / area if d == 1 else 0.0)) < 1e-10
    # single(): compute pair/local; columns index dist eng force p1 p2 p3
    # p7: p1..p3 the force on i (along dir only), p7 = k_ij, force = the
    # force on i projected on the pair vector (|force| <= |f|)
    pl = np.array([[float(v) for v in l.split()] for l in
                   (tmp_path / "pairs.dump").read_text().split("ITEM: ENTRIES")[1].strip().splitlines()[1:]])
    assert len(pl) > n
    e_pairs = pl[:, 2]
    assert abs(np.sum(e_pairs) - e_ref) < 1e-10 * max(1.0, e_ref)
    assert np.all(pl[:, 1] <= rcut * (1 + 1e-9))
    f_dir, f_other, kp = pl[:, 4 + d], pl[:, 5 - d], pl[:, 7]
    assert np.all(f_other == 0.0) and np.all(pl[:, 6] == 0.0)
    assert np.allclose(e_pairs, 0.5 * kp * (f_dir / np.where(kp > 0, kp, 1)) ** 2,
                       rtol=1e-9, atol=1e-14)
    assert np.all(np.abs(pl[:, 3]) <= np.abs(f_dir) * (1 + 1e-12))

def frames(path, tag):
    """{step: (box lengths, rows)} of a LAMMPS dump (atoms or local)."""
    out = {}
    for part in Path(path).read_text().split("ITEM: TIMESTEP")[1:]:
        step = int(part.strip().splitlines()[0])
        box = part.split("ITEM: BOX BOUNDS")[1].splitlines()[1:3]
        L = np.array([float(b.split()[1]) - float(b.split()[0]) for b in box])
        rows = part.split(tag)[1].strip().splitlines()[1:]
        out[step] = (L, np.array([[float(v) for v in l.split()] for l in rows]))
    return out


def test_single_after_avalanches(tmp_path):
    """A moving slider breaks contacts: on dump steps without an energy
    tally (no pe compute, no thermo output) single() -- compute pair/local --
    must still see the stretches after the step's avalanche, not those
    before it (a bug found in review: it read stale ghost stretches)."""
    eqtools.run_lammps(INPUT, {"out": tmp_path, "steps": 120, "every": 10, "pe": "no"}, cwd=tmp_path)
    A = frames(tmp_path / "atoms.dump", "ITEM: ATOMS")
    P = frames(tmp_path / "pairs.dump", "ITEM: ENTRIES")
    kern = kernel_crossover(0.3, 2.0)
    moved = 0
    for step, (L, a) in A.items():
        ids, x, y, s, k, h, fx, fy = a.T
        dx = x[:, None] - x[None, :]
        dy = y[:, None] - y[None, :]
        dx -= L[0] * np.round(dx / L[0])
        dy -= L[1] * np.round(dy / L[1])
        r = np.hypot(dx, dy)
        np.fill_diagonal(r, np.inf)
        kij = np.where(r <= 3.5, kern(np.where(r <= 3.5, r, 1.0), None), 0.0)
        ds = s[:, None] - s[None, :]
        e_ref = 0.25 * np.sum(kij * ds * ds)
        assert abs(P[step][1][:, 2].sum() - e_ref) < 1e-10 * max(1.0, e_ref), step
        moved += step > 0
    assert moved >= 10


def test_field_cleared_without_pair_style(tmp_path):
    """A run without pair eq/elastic after one with it: the interaction
    column (f_c[7]) must not keep the old field h_i, which would also
    mislead fix eq/quasistatic; the contacts keep their stretches."""
    text = INPUT.read_text() + (
        "uncompute pe\nuncompute pl\nundump d\nundump p\npair_style none\n"
        "dump d2 all custom 1 ${out}/after.dump id x y f_c[1] f_c[5] f_c[7]\n"
        "dump_modify d2 sort id format float %20.16g\nrun 0\n")
    infile = tmp_path / "in.cleared"
    infile.write_text(text)
    eqtools.run_lammps(infile, {"out": tmp_path}, cwd=tmp_path)
    _, before = read_dump(tmp_path / "atoms.dump")
    _, after = read_dump(tmp_path / "after.dump")
    assert np.abs(before[:, 5]).max() > 0.01          # there was a field
    assert np.all(after[:, 5] == 0.0)
    assert np.allclose(after[:, 3], before[:, 3], rtol=0, atol=1e-12)  # same stretches


RESTART_CASES = {
    # two types: 1-1 and 2-2 set, 1-2 mixed (geometric) by init_one
    "mixed-crossover": ["pair_coeff 1 1 0.3 2.0", "pair_coeff 2 2 0.1 3.0 3.2"],
    "aniso-table": [f"pair_coeff * * table {TABLE} ANISO_TEST 4.0"],
    "table-and-crossover": [f"pair_coeff 1 1 table {TABLE} CROSSOVER_L3",
                            "pair_coeff 1 2 0.2 1.5", "pair_coeff 2 2 0.05 2.5"],
}


@pytest.mark.parametrize("case", sorted(RESTART_CASES))
def test_coefficients_from_restart(tmp_path, case):
    """read_restart restores every coefficient (crossover, mixed, table
    and anisotropic kernels, per-pair cutoffs) without pair_coeff: the
    same fields h_i and forces as before the restart.  (LAMMPS' harness
    re-issues pair_coeff after read_restart for a style without data-file
    output, so it does not check this.)"""
    setup = "\n".join([
        "units lj", "dimension 2", "atom_style atomic", "boundary p p p",
        "lattice hex 1.1547005383792515", "region box block 0 12 0 7 -0.5 0.5",
        "create_box 2 box", "create_atoms 1 box", "set type 1 type/fraction 2 0.4 99",
        "mass * 1.0", "displace_atoms all random 0.2 0.2 0.0 4321 units box",
        "pair_style eq/elastic 3.5"] + RESTART_CASES[case] + [
        "neighbor 0.5 bin",
        "fix c all eq/contacts 1.0 77 threshold uniform 0.75 1.25 reform gaussian 0.1 0.15 "
        "start reform"])
    dump = ("dump d all custom 1 {f} id type f_c[1] f_c[7] fx\n"
            "dump_modify d sort id format float %20.16g\nrun 0\n")
    (tmp_path / "in.write").write_text(
        setup + "\n" + dump.format(f="before.dump") + "write_restart state.restart\n")
    (tmp_path / "in.read").write_text(
        "read_restart state.restart\nneighbor 0.5 bin\n"
        "fix c all eq/contacts 1.0 77 threshold uniform 0.75 1.25 reform gaussian 0.1 0.15 "
        "start reform\n" + dump.format(f="after.dump"))
    eqtools.run_lammps(tmp_path / "in.write", cwd=tmp_path)
    log = eqtools.run_lammps(tmp_path / "in.read", cwd=tmp_path)
    assert "pair_coeff" not in (tmp_path / "in.read").read_text()
    _, a = read_dump(tmp_path / "before.dump")
    _, b = read_dump(tmp_path / "after.dump")
    assert np.unique(a[:, 1]).size == 2
    assert np.abs(a[:, 3]).max() > 0.01, log          # a field to compare
    assert np.array_equal(a[:, :2], b[:, :2])
    # stretches are recomputed from the restored positions and anchors
    assert np.allclose(b[:, 2:], a[:, 2:], rtol=0, atol=1e-13)
