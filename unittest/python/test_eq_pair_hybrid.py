"""pair eq/elastic as a sub-style of pair hybrid and hybrid/overlay.

* With partners that contribute nothing (zero, lj/cut with epsilon 0,
  soft with A 0, and pair hybrid with eq/elastic on type pair 1 1 and
  zero on the others against eq/elastic alone with ftilde 0 there), the
  runs are those of eq/elastic alone, bit for bit: the dumps (positions,
  forces, the per-atom columns of the fix, written with %.17g) and the
  thermo output (energy, break counts, %20.16g) are identical text, for
  contacts (fix eq/contacts, driven by fix move and by fix eq/quasistatic)
  and blocks (fix eq/substrate: a chain with fix brownian, a square
  lattice with fix nve + fix viscous), on 1 and 2 MPI ranks.
* With partners that contribute (lj/cut, soft, table; pair hybrid with
  lj/cut on the type pairs with type 2), the force on every atom is the
  sum of both, against numpy: the fix's force (-k_i s_i, or the dumped
  substrate and driving-spring forces of the blocks), the field
  -sum_j k_ij (q_i - q_j) along dir only (k of the crossover kernel at the
  atoms' distance for contacts, at the sites' distance for blocks; only
  the type pairs given to eq/elastic couple) and the partner's forces from
  its closed form, on 1 and 2 ranks, which also break the same contacts.
* Two eq/elastic sub-styles in one hybrid are an error.
* single(): compute pair/local dist eng force p1..p7 against numpy, and
  the sum of the pair energies against pe (alone, under hybrid/overlay
  with eq/elastic's pair_coeff last, and under hybrid by type pairs; see
  SINGLE_CASES for what LAMMPS' pair hybrid passes on).

Tolerances are rounding bounds, stated where they are used (see
`field_tolerance`): the tests compare exact doubles (%.17g) and allow only
for the order and the rounding of the operations.
"""
import math
import os
import re
from pathlib import Path

import numpy as np
import pytest

import eqtools

INPUTS = Path(__file__).resolve().parent / "inputs"
EPS = np.finfo(float).eps
# the cutoff margin of pair eq/elastic: distances within 1e-8 (relative)
# of rcut count as inside
CUT_MARGIN = 1e-8

# ---------------------------------------------------------------- geometry


def hex_data(path, nx=10, ny=8, jitter=0.2, frac2=0.4, seed=20261125):
    """A 2d hex lattice (nearest neighbours 1 apart, nx x ny cells, 2 atoms
    per cell) with random displacements up to `jitter` and a random 40 % of
    type 2, as a data file (positions exact in %.17g).  Written here, read
    by every run, so that 1 and 2 ranks see the same atom IDs."""
    rng = np.random.default_rng(seed)
    lx, ly = float(nx), ny * math.sqrt(3.0)
    pts = [((i + 0.5 * b), (j + 0.5 * b) * math.sqrt(3.0))
           for j in range(ny) for i in range(nx) for b in (0, 1)]
    pos = np.array(pts) + rng.uniform(-jitter, jitter, (len(pts), 2))
    pos %= [lx, ly]
    types = 1 + (rng.random(len(pts)) < frac2)
    # no two contacts closer than the inner end of the test's table (0.5)
    d = pos[:, None, :] - pos[None, :, :]
    d -= np.round(d / [lx, ly]) * [lx, ly]
    r = np.hypot(d[..., 0], d[..., 1]) + np.eye(len(pos)) * 1e9
    assert r.min() > TAB_RIN
    write_data(path, pos, types, (0.0, lx), (0.0, ly))
    return len(pts)


def lattice_data(path, nx, ny, frac2=0.4, seed=77):
    """Blocks on a square lattice of spacing 1 (ny = 1: a chain along x in a
    box 4 wide across it), a random 40 % of type 2."""
    rng = np.random.default_rng(seed)
    pos = np.array([(float(i), float(j)) for j in range(ny) for i in range(nx)])
    types = 1 + (rng.random(len(pos)) < frac2)
    ylo, yhi = (-0.5, ny - 0.5) if ny > 1 else (-2.0, 2.0)
    write_data(path, pos, types, (-0.5, nx - 0.5), (ylo, yhi))
    return len(pos)


def write_data(path, pos, types, xb, yb):
    lines = ["LAMMPS data file (test_eq_pair_hybrid)", "", f"{len(pos)} atoms", "2 atom types",
             f"{xb[0]:.17g} {xb[1]:.17g} xlo xhi", f"{yb[0]:.17g} {yb[1]:.17g} ylo yhi",
             "-0.5 0.5 zlo zhi", "", "Atoms # atomic", ""]
    lines += [f"{i + 1} {t} {p[0]:.17g} {p[1]:.17g} 0.0" for i, (p, t) in enumerate(zip(pos, types))]
    Path(path).write_text("\n".join(lines) + "\n")


def read_frames(path):
    """Frames of a dump custom (or local) file: list of dicts with step,
    box (lo[3], hi[3], tilt[3]) and the columns by name; atoms sorted by id."""
    frames = []
    text = Path(path).read_text()
    for part in text.split("ITEM: TIMESTEP")[1:]:
        lines = part.strip().splitlines()
        step = int(lines[0])
        k = next(i for i, l in enumerate(lines) if l.startswith("ITEM: BOX BOUNDS"))
        tri = "xy" in lines[k]
        b = np.array([[float(v) for v in lines[k + 1 + d].split()] for d in range(3)])
        tilt = b[:, 2] if tri else np.zeros(3)
        lo, hi = b[:, 0].copy(), b[:, 1].copy()
        if tri:   # bounding box -> box (LAMMPS' dump convention)
            xy, xz, yz = tilt
            lo[0] -= min(0.0, xy, xz, xy + xz)
            hi[0] -= max(0.0, xy, xz, xy + xz)
            lo[1] -= min(0.0, yz)
            hi[1] -= max(0.0, yz)
        h = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS") or
                 l.startswith("ITEM: ENTRIES"))
        names = lines[h].split()[2:]
        rows = np.array([[float(v) for v in l.split()] for l in lines[h + 1:]]).reshape(-1, len(names))
        if "id" in names:
            rows = rows[np.argsort(rows[:, names.index("id")], kind="stable")]
        f = {"step": step, "lo": lo, "hi": hi, "tilt": tilt,
             "periodic": lines[k].split()[-3:]}
        f.update({n: rows[:, c] for c, n in enumerate(names)})
        frames.append(f)
    return frames


def image_pairs(pos, frame, rcut):
    """All pairs (i, j, image) of the 2d positions within rcut (relative
    margin CUT_MARGIN), periodic images included explicitly (triclinic
    shifts too), an atom's own images left out: (i, j, dvec = p_i - p_j')
    with r = |dvec|."""
    lo, hi, tilt = frame["lo"], frame["hi"], frame["tilt"]
    per = [p.startswith("p") for p in frame["periodic"]]
    a = np.array([hi[0] - lo[0], 0.0])
    b = np.array([tilt[0], hi[1] - lo[1]])
    # the atoms lie in the (tilted) box up to their motion since the last
    # list build and the displacements of the sites (< 2 here): images
    # beyond these shifts cannot come within rcut
    my = 1 + int((rcut + 2.0) / b[1]) if per[1] else 0
    mx = 1 + int((rcut + 2.0 + abs(b[0]) * (1 + my)) / a[0]) if per[0] else 0
    I, J, D = [], [], []
    for sx in range(-mx, mx + 1):
        for sy in range(-my, my + 1):
            shift = sx * a + sy * b
            d = pos[:, None, :] - (pos[None, :, :] + shift)
            r2 = np.einsum("ijk,ijk->ij", d, d)
            near = r2 <= (rcut * (1 + CUT_MARGIN)) ** 2
            np.fill_diagonal(near, False)
            ii, jj = np.nonzero(near)
            I.append(ii)
            J.append(jj)
            D.append(d[ii, jj])
    I, J, D = np.concatenate(I), np.concatenate(J), np.concatenate(D)
    r = np.hypot(D[:, 0], D[:, 1])
    # a pair within rounding of the cutoff would be ill-posed
    assert not np.any(np.abs(r / rcut - 1.0) < 1e-9), "a pair at the cutoff"
    return I, J, D, r


def crossover(ft, lam):
    return lambda r: np.where(r <= lam, ft / r, ft * lam * lam / r ** 3)


# ---------------------------------------------------------------- partners
# LAMMPS' styles in closed form: the force on i from j is fpair * (p_i - p_j);
# each returns fpair, the magnitude of fpair's terms (for the rounding
# bound), the power p of its fall-off (the rounding of the distance, of
# 2 eps X, changes it by p 2 eps X / r relative), an absolute error of
# fpair beyond that (table set-up) and the pair energy.


def lj(eps_, sig, rc):
    def f(r):
        on = r * r < rc * rc
        rep, att = 48 * eps_ * sig ** 12 / r ** 14, 24 * eps_ * sig ** 6 / r ** 8
        e = 4 * eps_ * ((sig / r) ** 12 - (sig / r) ** 6)
        z = np.zeros_like(r)
        return (np.where(on, rep - att, 0.0), np.where(on, rep + att, 0.0), 14, z,
                np.where(on, e, 0.0))
    return f


def soft(A, rc):
    def f(r):
        on = r < rc
        v = A * np.sin(np.pi * r / rc) * np.pi / rc / r
        e = A * (1 + np.cos(np.pi * r / rc))
        return np.where(on, v, 0.0), np.where(on, np.abs(v), 0.0), 2, np.zeros_like(r), \
            np.where(on, e, 0.0)
    return f


TAB_A, TAB_RC, TAB_RIN, TAB_N = 0.6, 2.0, 0.5, 151


def table_file(path):
    """Force F(r) = A r (1 - r^2/rc^2), a cubic: the clamped cubic spline
    that pair table fits through the file's points (FPRIME given) is F
    itself, and F/r is linear in r^2, which the table interpolates
    linearly: the table gives the closed form up to the rounding of its
    set-up (the spline's second derivatives from differences over
    h = 0.01 carry eps |F|/h^2, which the interpolation multiplies by
    h^2: a few ulp of max |F| <= A rc; F/a at a >= rinner = 0.5)."""
    r = np.linspace(TAB_RIN, TAB_RC, TAB_N)
    F = TAB_A * r * (1 - r * r / TAB_RC ** 2)
    E = -TAB_A * (r * r / 2 - r ** 4 / (4 * TAB_RC ** 2)) + TAB_A * TAB_RC ** 2 / 4
    fp = lambda x: TAB_A * (1 - 3 * x * x / TAB_RC ** 2)
    lines = ["# test_eq_pair_hybrid: F = A r (1 - r^2/rc^2)", "", "CUBIC",
             f"N {TAB_N} R {TAB_RIN:.17g} {TAB_RC:.17g} FPRIME {fp(TAB_RIN):.17g} {fp(TAB_RC):.17g}", ""]
    lines += [f"{k + 1} {r[k]:.17g} {E[k]:.17g} {F[k]:.17g}" for k in range(TAB_N)]
    Path(path).write_text("\n".join(lines) + "\n")


def table(r):
    on = (r * r < TAB_RC ** 2) & (r >= TAB_RIN)
    v = TAB_A * (1 - r * r / TAB_RC ** 2)
    # the set-up (see table_file): 32 ulp of max|F|/rinner <= 4 A per term
    return np.where(on, v, 0.0), np.where(on, np.abs(v), 0.0), 2, np.where(on, 128 * EPS * TAB_A, 0.0), None


# ---------------------------------------------------------------- set-ups
FT, LAM = 0.05, 2.0          # contacts: kernel ftilde/r up to 2, r^-3 to 3
RC_C = 3.0
G, RC_CHAIN, RC_SQ = 3.0, 1.5, 1.2   # blocks: g at r = 1 (lambda_c = 1)

SYSTEMS = {
    # name: (kind, input variables, eq/elastic cutoff, ftilde, lambda_c)
    "contacts-move": ("contacts", {"drive": "move"}, RC_C, FT, LAM),
    "contacts-quasistatic": ("contacts", {"drive": "quasistatic"}, RC_C, FT, LAM),
    "chain-brownian": ("chain", {"integ": "brownian"}, RC_CHAIN, G, 1.0),
    "square-viscous": ("square", {"integ": "viscous"}, RC_SQ, G, 1.0),
    "square-brownian": ("square", {"integ": "brownian", "yfix": "yes"}, RC_SQ, G, 1.0),
}


def setup_system(tmp, name):
    kind, var, rc, ft, lam = SYSTEMS[name]
    data = tmp / f"{kind}.data"
    if kind == "contacts":
        hex_data(data)
        inp = INPUTS / "in.hybrid-contacts"
    else:
        lattice_data(data, 48, 1) if kind == "chain" else lattice_data(data, 10, 10)
        inp = INPUTS / "in.hybrid-blocks"
    return inp, dict(var, data=data), rc, ft, lam, kind


def run(tmp, name, pairs, tag, nprocs=1, **extra):
    """Run system `name` with the pair lines `pairs` in tmp/tag; returns
    (log, that folder)."""
    out = tmp / tag
    out.mkdir()
    inp, var, *_ = setup_system(out, name)
    (out / "pairs.in").write_text(pairs + "\n")
    table_file(out / "cubic.table")
    var.update(pairs=out / "pairs.in", out=out)
    var.update(extra)
    log = eqtools.run_lammps(inp, var, nprocs=nprocs, cwd=out)
    return log, out


def thermo_lines(log):
    """The thermo rows of the log as text (bit-for-bit comparison): the
    lines between a header 'Step ...' and 'Loop time'."""
    rows, on = [], False
    for l in log.splitlines():
        if l.split()[:1] == ["Step"]:
            on = True
        elif l.startswith("Loop time"):
            on = False
        elif on and l.split() and l.split()[0].isdigit():
            rows.append(l)
    return rows


def alone(kind, two_type_zero=False):
    rc, ft, lam = {"contacts": (RC_C, FT, LAM), "chain": (RC_CHAIN, G, 1.0),
                   "square": (RC_SQ, G, 1.0)}[kind]
    if two_type_zero:
        return (f"pair_style eq/elastic {rc}\npair_coeff 1 1 {ft} {lam}\n"
                f"pair_coeff 1 2 0.0 {lam}\npair_coeff 2 2 0.0 {lam}")
    return f"pair_style eq/elastic {rc}\npair_coeff * * {ft} {lam}"


def zero_partner(kind, which):
    rc, ft, lam = {"contacts": (RC_C, FT, LAM), "chain": (RC_CHAIN, G, 1.0),
                   "square": (RC_SQ, G, 1.0)}[kind]
    # partner cutoffs no larger than eq/elastic's: the neighbor lists (their
    # bins, hence the order of the neighbours and of the sums) are those of
    # eq/elastic alone
    rp = min(rc, 1.2)
    if which == "overlay-zero":
        return f"pair_style hybrid/overlay eq/elastic {rc} zero {rc}\n" \
               f"pair_coeff * * eq/elastic {ft} {lam}\npair_coeff * * zero"
    if which == "overlay-lj-eps0":
        return f"pair_style hybrid/overlay eq/elastic {rc} lj/cut {rp}\n" \
               f"pair_coeff * * eq/elastic {ft} {lam}\npair_coeff * * lj/cut 0.0 0.8"
    if which == "overlay-soft-A0":
        return f"pair_style hybrid/overlay soft {rp} eq/elastic {rc}\n" \
               f"pair_coeff * * soft 0.0\npair_coeff * * eq/elastic {ft} {lam}"
    if which == "hybrid-zero-2types":
        return f"pair_style hybrid eq/elastic {rc} zero {rc}\n" \
               f"pair_coeff 1 1 eq/elastic {ft} {lam}\npair_coeff 1 2 zero\npair_coeff 2 2 zero"
    raise KeyError(which)


ZERO = ["overlay-zero", "overlay-lj-eps0", "overlay-soft-A0", "hybrid-zero-2types"]
ZERO_SYSTEMS = ["contacts-move", "contacts-quasistatic", "chain-brownian", "square-viscous"]


def activity(out, kind):
    """The run did something: contacts broke / blocks slipped, and the
    field is not zero."""
    fr = read_frames(out / "atoms.dump")
    if kind == "contacts":
        assert fr[-1]["f_c[4]"].sum() > 50
        assert max(np.abs(f["f_c[7]"]).max() for f in fr) > 0.01
    else:
        assert np.abs(fr[-1]["f_sub[6]"]).max() >= 1.0      # slipped at least one well
        assert max(np.abs(f["f_sub[8]"]).max() for f in fr) > 0.01


_alone = {}


def reference(factory, system, two=False, nprocs=1):
    """eq/elastic alone (ftilde 0 on the type pairs with type 2 if `two`),
    run once per module."""
    key = (system, two, nprocs)
    if key not in _alone:
        kind = SYSTEMS[system][0]
        tmp = factory.mktemp(f"alone-{system}-{int(two)}-np{nprocs}")
        _alone[key] = run(tmp, system, alone(kind, two), "alone", nprocs=nprocs)
    return _alone[key]


@pytest.mark.parametrize("system", ZERO_SYSTEMS)
@pytest.mark.parametrize("partner", ZERO)
def test_partners_contributing_nothing_bit_for_bit(tmp_path, tmp_path_factory, system, partner):
    """Partners that contribute nothing leave the run of eq/elastic alone
    unchanged to the last bit: same dump text (forces, positions, every
    per-atom column of the fix, %.17g), same thermo text (pe, break counts
    or block outputs, %20.16g).  The hybrid with eq/elastic on type pair
    1 1 and zero on 1 2 and 2 2 is compared with eq/elastic alone whose
    1 2 and 2 2 kernels are zero (ftilde 0): a term 0 * (q_i - q_j) leaves
    every sum as it is."""
    kind = SYSTEMS[system][0]
    two = partner == "hybrid-zero-2types"
    log_ref, out_ref = reference(tmp_path_factory, system, two)
    activity(out_ref, kind)
    log, out = run(tmp_path, system, zero_partner(kind, partner), "hybrid")
    ref_rows, rows = thermo_lines(log_ref), thermo_lines(log)
    assert len(ref_rows) == 11 and rows == ref_rows
    assert (out / "atoms.dump").read_text() == (out_ref / "atoms.dump").read_text()


def test_bit_for_bit_comparison_can_fail(tmp_path, tmp_path_factory):
    """The control: a partner that contributes a little (soft, A = 1e-9)
    changes the dump text, so the comparison above can tell."""
    log_ref, out_ref = reference(tmp_path_factory, "contacts-move")
    pairs = (f"pair_style hybrid/overlay eq/elastic {RC_C} soft 1.2\n"
             f"pair_coeff * * eq/elastic {FT} {LAM}\npair_coeff * * soft 1e-9")
    log, out = run(tmp_path, "contacts-move", pairs, "hybrid")
    assert (out / "atoms.dump").read_text() != (out_ref / "atoms.dump").read_text()


def test_partners_contributing_nothing_two_ranks(tmp_path, tmp_path_factory):
    """The same on 2 MPI ranks (the field's sums follow each rank's lists:
    hybrid and alone are compared on the same decomposition), and the
    breaks of 2 ranks are those of 1 rank."""
    for system, partner in (("contacts-quasistatic", "overlay-zero"),
                            ("contacts-move", "overlay-lj-eps0"),
                            ("chain-brownian", "overlay-soft-A0")):
        kind = SYSTEMS[system][0]
        log_ref, out_ref = reference(tmp_path_factory, system, nprocs=2)
        log, out = run(tmp_path, system, zero_partner(kind, partner), f"{system}-hybrid", nprocs=2)
        assert thermo_lines(log) == thermo_lines(log_ref)
        assert (out / "atoms.dump").read_text() == (out_ref / "atoms.dump").read_text()
        log1, out1 = reference(tmp_path_factory, system)
        a, b = read_frames(out1 / "atoms.dump"), read_frames(out / "atoms.dump")
        col = "f_c[4]" if kind == "contacts" else "f_sub[6]"
        for fa, fb in zip(a, b):
            assert np.array_equal(fa[col], fb[col]), (system, fa["step"])


# ---------------------------------------------------------------- sums

def field_reference(frame, kind, rc, ft, lam, coupled_types=None):
    """-h along x from scratch, with its rounding bound.

    Contacts: q = stretch (column 1), k at the atoms' distance; blocks:
    q = displacement (column 1), k at the distance of the sites x - q e_x.
    coupled_types: only pairs of these types couple (pair hybrid)."""
    qcol = "f_c[1]" if kind == "contacts" else "f_sub[1]"
    q = frame[qcol]
    pos = np.column_stack([frame["x"], frame["y"]])
    if kind != "contacts":
        pos = pos - np.column_stack([q, np.zeros_like(q)])
    I, J, D, r = image_pairs(pos, frame, rc)
    if coupled_types is not None:
        t = frame["type"]
        keep = np.isin(t[I], coupled_types) & np.isin(t[J], coupled_types)
        I, J, D, r = I[keep], J[keep], D[keep], r[keep]
    k = crossover(ft, lam)(r)
    n = len(q)
    h = np.bincount(I, k * (q[I] - q[J]), n)
    return h, (I, J, r, k, q)


def field_tolerance(parts, frame, nbreaks):
    """Rounding bound of h_i, per atom.  Each term k_ij (q_i - q_j), of size
    T_ij = |k_ij| (|q_i| + |q_j|): the kernel carries a few ulp of its own
    and 3 eps X / r_ij from the rounding of the distance (X: the size of
    the coordinates, up to the box length; ghosts are shifted copies; k
    falls as r^-3 at most), the difference carries eps (|q_i| + |q_j|)
    (blocks: q = x - w, 2 eps X each); a sum of n_i terms in any order
    n_i eps sum T.  Contacts: between two list builds the field is updated
    incrementally, each break of a partner adding one rounding of the
    updated value: at most `nbreaks` updates.  Together
    eps sum_j T_ij (2 n_i + 32 + 2 nbreaks + 8 X / r_ij) + eps 8 X K_i."""
    I, J, r, k, q = parts
    n = len(q)
    X = max(np.abs(frame["x"]).max(), np.abs(frame["y"]).max(),
            (frame["hi"] - frame["lo"])[:2].max(), np.abs(q).max())
    T = np.abs(k) * (np.abs(q[I]) + np.abs(q[J]))
    nn = np.bincount(I, minlength=n)
    tol = EPS * (np.bincount(I, T * (2 * nn[I] + 32 + 2 * nbreaks + 8 * X / r), n)
                 + 8 * X * np.bincount(I, np.abs(k), n))
    return tol


def partner_reference(frame, pf, rc, types=None):
    """The partner's forces (x, y) on every atom at the atoms' positions,
    with a rounding bound per atom: each term carries a few ulp and, from
    the rounding of the distance, p eps X / r (p the power of its fall-off);
    a sum of n terms n eps sum of the terms' magnitudes."""
    pos = np.column_stack([frame["x"], frame["y"]])
    I, J, D, r = image_pairs(pos, frame, rc)
    if types is not None:
        t = frame["type"]
        keep = (t[I] == 2) | (t[J] == 2)
        I, J, D, r = I[keep], J[keep], D[keep], r[keep]
    fp, mag, p, add, _ = pf(r)
    n = len(pos)
    fx = np.bincount(I, fp * D[:, 0], n)
    fy = np.bincount(I, fp * D[:, 1], n)
    X = max(np.abs(pos).max(), (frame["hi"] - frame["lo"])[:2].max())
    nn = np.bincount(I, minlength=n)
    tol = EPS * np.bincount(I, mag * r * (2 * nn[I] + 32 + 4 * p * X / r), n) \
        + np.bincount(I, add * r, n)
    return fx, fy, tol


SUM_CASES = {
    # name: (system, pair lines, partner closed form, its cutoff, hybrid types)
    "contacts-lj": ("contacts-move",
                    f"pair_style hybrid/overlay eq/elastic {RC_C} lj/cut 2.5\n"
                    f"pair_coeff * * eq/elastic {FT} {LAM}\npair_coeff * * lj/cut 0.02 0.8",
                    lj(0.02, 0.8, 2.5), 2.5, None),
    "contacts-soft-quasistatic": ("contacts-quasistatic",
                                  f"pair_style hybrid/overlay soft 1.5 eq/elastic {RC_C}\n"
                                  f"pair_coeff * * soft 0.3\npair_coeff * * eq/elastic {FT} {LAM}",
                                  soft(0.3, 1.5), 1.5, None),
    "contacts-table": ("contacts-move",
                       f"pair_style hybrid/overlay eq/elastic {RC_C} table linear 2000\n"
                       f"pair_coeff * * eq/elastic {FT} {LAM}\n"
                       f"pair_coeff * * table cubic.table CUBIC {TAB_RC}",
                       table, TAB_RC, None),
    "contacts-hybrid-types": ("contacts-move",
                              f"pair_style hybrid eq/elastic {RC_C} lj/cut 2.5\n"
                              f"pair_coeff 1 1 eq/elastic {FT} {LAM}\n"
                              f"pair_coeff 1 2 lj/cut 0.02 0.8\npair_coeff 2 2 lj/cut 0.02 0.8",
                              lj(0.02, 0.8, 2.5), 2.5, [1]),
    "chain-lj": ("chain-brownian",
                 f"pair_style hybrid/overlay eq/elastic {RC_CHAIN} lj/cut 1.5\n"
                 f"pair_coeff * * eq/elastic {G} 1.0\npair_coeff * * lj/cut 0.05 0.8",
                 lj(0.05, 0.8, 1.5), 1.5, None),
    "chain-table": ("chain-brownian",
                    f"pair_style hybrid/overlay table linear 2000 eq/elastic {RC_CHAIN}\n"
                    f"pair_coeff * * table cubic.table CUBIC {TAB_RC}\n"
                    f"pair_coeff * * eq/elastic {G} 1.0",
                    table, TAB_RC, None),
    "square-soft": ("square-brownian",
                    f"pair_style hybrid/overlay eq/elastic {RC_SQ} soft 1.5\n"
                    f"pair_coeff * * eq/elastic {G} 1.0\npair_coeff * * soft 0.2",
                    soft(0.2, 1.5), 1.5, None),
    "square-hybrid-types": ("square-brownian",
                            f"pair_style hybrid eq/elastic {RC_SQ} lj/cut 1.5\n"
                            f"pair_coeff 1 1 eq/elastic {G} 1.0\n"
                            f"pair_coeff 1 2 lj/cut 0.05 0.8\npair_coeff 2 2 lj/cut 0.05 0.8",
                            lj(0.05, 0.8, 1.5), 1.5, [1]),
}


def check_sums(out, case, nprocs):
    system, pairs, pf, rcp, types = SUM_CASES[case]
    kind, _, rc, ft, lam = SYSTEMS[system]
    kind = "contacts" if kind == "contacts" else "blocks"
    frames = read_frames(out / "atoms.dump")
    assert len(frames) == 11
    worst, scale_f, scale_p = 0.0, 0.0, 0.0
    nb_total = frames[-1]["f_c[4]"].sum() if kind == "contacts" else 0
    for fr in frames:
        h, parts = field_reference(fr, kind, rc, ft, lam, types)
        tol_h = field_tolerance(parts, fr, nb_total)
        px, py, tol_p = partner_reference(fr, pf, rcp, types)
        if kind == "contacts":
            own = -fr["f_c[5]"] * fr["f_c[1]"]
            tol_own = 2 * EPS * np.abs(own)
            hcol = fr["f_c[7]"]
        else:
            own = fr["f_sub[2]"] + fr["f_sub[3]"]
            tol_own = 4 * EPS * (np.abs(fr["f_sub[2]"]) + np.abs(fr["f_sub[3]"]))
            hcol = fr["f_sub[8]"]
        fx_ref = own - h + px
        tol = tol_h + tol_p + tol_own + 4 * EPS * (np.abs(own) + np.abs(h) + np.abs(px))
        err = np.abs(fr["fx"] - fx_ref)
        assert np.all(err <= tol), (case, nprocs, fr["step"], np.max(err / tol))
        # the field itself (the fix's column): the pair's h
        assert np.all(np.abs(hcol - h) <= tol_h), (case, fr["step"])
        if types is not None:      # atoms of type 2 are not coupled
            assert np.all(hcol[fr["type"] == 2] == 0.0)
        # across dir: the partner only (the blocks' fy is zeroed by setforce)
        if kind == "contacts":
            assert np.all(np.abs(fr["fy"] - py) <= tol_p + 4 * EPS * np.abs(py)), (case, fr["step"])
        else:
            assert np.all(fr["fy"] == 0.0) or np.all(np.abs(fr["fy"] - py) <= tol_p)
        worst = max(worst, float(np.max(err / tol)))
        scale_f = max(scale_f, np.abs(h).max())
        scale_p = max(scale_p, np.abs(px).max() + np.abs(py).max())
    # both contribute
    assert scale_f > 0.01 and scale_p > 0.01, (case, scale_f, scale_p)
    return frames, worst


@pytest.mark.parametrize("case", sorted(SUM_CASES))
def test_forces_are_the_sum_of_both(tmp_path, case):
    """Forces of hybrid/overlay (and hybrid by type pairs) = fix + field +
    partner, against numpy, on 1 and 2 MPI ranks; both rank counts give
    the same breaks (contacts: per-atom break counts and the global count;
    blocks: the wells every block is in).  A reference that leaves out the
    partner, or lets the type-2 atoms couple, must fail (checked)."""
    system, pairs, pf, rcp, types = SUM_CASES[case]
    kind = SYSTEMS[system][0]
    per_rank = {}
    for nprocs in (1, 2):
        log, out = run(tmp_path, system, pairs, f"np{nprocs}", nprocs=nprocs)
        per_rank[nprocs] = (thermo_lines(log), check_sums(out, case, nprocs)[0])
    col = "f_c[4]" if kind == "contacts" else "f_sub[6]"
    for a, b in zip(per_rank[1][1], per_rank[2][1]):
        assert np.array_equal(a[col], b[col]), a["step"]
    if kind == "contacts":
        # f_c[2], f_c[3], f_c[4] of thermo (columns 4-6): exact counts
        c1 = [r.split()[3:6] for r in per_rank[1][0]]
        c2 = [r.split()[3:6] for r in per_rank[2][0]]
        assert c1 == c2
        assert float(c1[-1][1]) > 50
    # the check can fail: without the partner, or with every type coupled
    fr = per_rank[1][1][-1]
    rc, ft, lam = SYSTEMS[system][2:]
    k_ = "contacts" if kind == "contacts" else "blocks"
    h, parts = field_reference(fr, k_, rc, ft, lam, types)
    h_all, _ = field_reference(fr, k_, rc, ft, lam, None)
    px, _, _ = partner_reference(fr, pf, rcp, types)
    own = (-fr["f_c[5]"] * fr["f_c[1]"]) if kind == "contacts" else fr["f_sub[2]"] + fr["f_sub[3]"]
    tol = field_tolerance(parts, fr, 1000)
    assert np.max(np.abs(fr["fx"] - (own - h))) > 1e3 * tol.max()
    if types is not None:
        assert np.max(np.abs(fr["fx"] - (own - h_all + px))) > 1e3 * tol.max()


# ---------------------------------------------------------------- errors

@pytest.mark.parametrize("style", ["hybrid/overlay", "hybrid"])
def test_two_eq_elastic_sub_styles_are_an_error(tmp_path, style):
    if style == "hybrid":
        pairs = (f"pair_style hybrid eq/elastic {RC_C} eq/elastic 2.0\n"
                 f"pair_coeff 1 1 eq/elastic 1 {FT} {LAM}\npair_coeff 1 2 eq/elastic 1 {FT} {LAM}\n"
                 f"pair_coeff 2 2 eq/elastic 2 0.01 1.0")
    else:
        pairs = (f"pair_style hybrid/overlay eq/elastic {RC_C} eq/elastic 2.0\n"
                 f"pair_coeff * * eq/elastic 1 {FT} {LAM}\npair_coeff * * eq/elastic 2 0.01 1.0")
    out = tmp_path / "run"
    out.mkdir()
    hex_data(out / "contacts.data")
    (out / "pairs.in").write_text(pairs + "\n")
    log = eqtools.run_lammps(INPUTS / "in.hybrid-contacts",
                             {"data": out / "contacts.data", "pairs": out / "pairs.in", "out": out,
                              "steps": 10, "every": 10}, cwd=out, check=False)
    err = [l for l in log.splitlines() if "ERROR" in l]
    assert err and "sub-styles eq/elastic" in err[0], log[-2000:]
    assert "Loop time" not in log


# ---------------------------------------------------------------- single()

# Under hybrid/overlay LAMMPS' PairHybridOverlay::copy_svector (29 Sep
# 2021 to 4 Jul 2026 alike) passes on the extra values of a sub-style only
# when it is the last one mapped to the type pair, i.e. the last pair_coeff
# for it (its loop over the map does not stop at the match): eq/elastic's
# pair_coeff comes last here.  And a sub-style is not called for a pair
# beyond its own cutoff, while pair hybrid still copies the extra values
# it kept from the pair before: the partners' cutoffs here do not exceed
# eq/elastic's.
SINGLE_CASES = {
    "contacts-alone": ("contacts-move", alone("contacts"), None, None),
    "contacts-overlay-lj": ("contacts-move",
                            f"pair_style hybrid/overlay eq/elastic {RC_C} lj/cut 2.5\n"
                            f"pair_coeff * * lj/cut 0.02 0.8\npair_coeff * * eq/elastic {FT} {LAM}",
                            lj(0.02, 0.8, 2.5), None),
    "contacts-hybrid-types": ("contacts-move", SUM_CASES["contacts-hybrid-types"][1],
                              lj(0.02, 0.8, 2.5), [1]),
    "blocks-alone": ("square-brownian", alone("square"), None, None),
    "blocks-overlay-soft": ("square-brownian",
                            f"pair_style hybrid/overlay eq/elastic {RC_SQ} soft 1.15\n"
                            f"pair_coeff * * soft 0.2\npair_coeff * * eq/elastic {G} 1.0",
                            soft(0.2, 1.15), None),
}


@pytest.mark.parametrize("case", sorted(SINGLE_CASES))
def test_single_against_numpy(tmp_path, case):
    """compute pair/local dist eng force p1..p7 (patom1 patom2 from compute
    property/local over the same pairs): eq/elastic's single() returns
    (1/2) k_ij (q_i - q_j)^2 and fforce = (F_i . del)/r^2, F_i the force on
    i, -k_ij (q_i - q_j) along dir (pair/local's force = r fforce = the
    component of F_i along del/r), p1..p3 = F_i, p4..p6 = 0 (no torque),
    p7 = k_ij.  Under hybrid/overlay the energy and the force are summed
    with the partner's (its closed form), p1..p7 are eq/elastic's; with
    pair hybrid the type pairs of lj/cut have p1..p7 = 0 and eq/elastic's
    only k for type pair 1 1.  The sum of the pair energies is pe (thermo,
    norm no).  Rounding: each entry is a few operations on exact inputs,
    k carries 3 eps X/r from the distance: 1e-12 relative to the entries'
    scale leaves a factor > 10 over 8 X/r eps (X ~ 14, r >= 0.5)."""
    system, pairs, pf, types = SINGLE_CASES[case]
    kind, _, rc, ft, lam = SYSTEMS[system]
    plain_hybrid = re.search(r"pair_style hybrid\s", pairs) is not None
    if plain_hybrid and int(os.environ.get("FEQ_LAMMPS_VERSION", "0") or 0) < 20260704:
        # LAMMPS' pair hybrid before 4 Jul 2026 would crash on the extra
        # values (PairHybrid::copy_svector): the sub-style offers none, and
        # compute pair/local says so
        with pytest.raises(eqtools.RunError, match="does not have extra field requested by "
                                                   "compute pair/local"):
            run(tmp_path, system, pairs, "run", pairlocal="yes", steps=60)
        return
    log, out = run(tmp_path, system, pairs, "run", pairlocal="yes", steps=60)
    A = {f["step"]: f for f in read_frames(out / "atoms.dump")}
    P = {f["step"]: f for f in read_frames(out / "pairs.dump")}
    pe = {int(r.split()[0]): float(r.split()[1]) for r in thermo_lines(log)}
    assert sorted(A) == sorted(P) == [0, 20, 40, 60]
    qcol = "f_c[1]" if kind == "contacts" else "f_sub[1]"
    seen_k = 0
    for step in sorted(A):
        a, p = A[step], P[step]
        idx = {int(t): n for n, t in enumerate(a["id"])}
        i = np.array([idx[int(t)] for t in p["c_pp[1]"]])
        j = np.array([idx[int(t)] for t in p["c_pp[2]"]])
        x, y, q, t = a["x"], a["y"], a[qcol], a["type"]
        L = (a["hi"] - a["lo"])[:2]
        dx = x[i] - x[j]
        dy = y[i] - y[j]
        dx -= L[0] * np.round(dx / L[0])
        dy -= L[1] * np.round(dy / L[1])
        r = np.hypot(dx, dy)
        # the pairs of the dump are aligned with patom1, patom2
        assert np.allclose(p["c_pl[1]"], r, rtol=1e-13, atol=0), step
        sx = dx - (q[i] - q[j]) if kind != "contacts" else dx
        rk = np.hypot(sx, dy)
        cpl = np.ones(len(i), bool) if types is None else (t[i] == 1) & (t[j] == 1)
        k = np.where(cpl & (rk <= rc * (1 + CUT_MARGIN)), crossover(ft, lam)(rk), 0.0)
        dq = q[i] - q[j]
        Fi = -k * dq
        eng = 0.5 * k * dq * dq
        force = Fi * dx / r
        if pf is not None:
            part = np.ones(len(i), bool) if types is None else (t[i] == 2) | (t[j] == 2)
            fp, _, _, _, ep = pf(r)
            force = force + np.where(part, fp, 0.0) * r
            eng = eng + np.where(part, ep, 0.0)
        # p1..p7, each column on its own scale (p2..p6 exactly 0)
        for c, w in enumerate([Fi] + [np.zeros_like(Fi)] * 5 + [k]):
            g = p[f"c_pl[{c + 4}]"]
            sc = np.abs(w).max()
            assert np.all(np.abs(g - w) <= 1e-12 * sc), (case, step, f"p{c + 1}", np.abs(g - w).max())
        sf = np.abs(force).max()
        assert np.all(np.abs(p["c_pl[3]"] - force) <= 1e-12 * sf), \
            (case, step, np.abs(p["c_pl[3]"] - force).max())
        se = np.abs(eng).max()
        assert np.all(np.abs(p["c_pl[2]"] - eng) <= 1e-12 * se), \
            (case, step, np.abs(p["c_pl[2]"] - eng).max())
        # the sum of the pair energies is the pair energy of thermo (norm no)
        e_sum = p["c_pl[2]"].sum()
        assert abs(e_sum - pe[step]) <= 1e-12 * len(eng) * se, (case, step, e_sum, pe[step])
        seen_k += int(np.count_nonzero(k * dq))
    assert seen_k > 100
