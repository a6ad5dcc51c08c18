"""The field of pair eq/elastic is recomputed after every change it cannot
follow by itself.

pair eq/elastic keeps h_i = sum_j k_ij (q_i - q_j) up to date
incrementally (rigid translations cost nothing, breaks update their
partners only, blocks follow their positions between list builds).  Any
change of the box, of the atoms or of the coefficients invalidates what
it keeps.  For each change below, made between two runs (fix deform:
during a run), the forces of every dumped step after the change, the
first one included, must equal a from-scratch numpy evaluation:

* contacts (fix eq/contacts, a rigid slider moved by fix move): f_x =
  -k_i s_i - h_i, s_i = per-atom column 1 of the fix, k at the atoms'
  distance; also column 7 = h_i;
* blocks (fix eq/substrate, fix brownian): f_x = (substrate force,
  column 2) + (driving spring, column 3) - h_i, q = displacement u
  (column 1), k at the distance of the sites x - u e_x; column 8 = h_i;

with k(r) = ftilde/r up to lambda_c and ftilde lambda_c^2/r^3 beyond, the
pairs over explicit periodic images (orthogonal or triclinic, along the
periodic dimensions only), on 1 and 2 MPI ranks.  Each case also shows
that it can fail: the field as it was before the change (the geometry,
the coordinates and the coefficients of before) is off by far more than
the tolerance, unless the change must leave it as it is (restart), where
it is within the tolerance.  The drift report of `pair_style eq/elastic
R check 1` stays at rounding.

Tolerance (rounding): a term k_ij (q_i - q_j) carries a few ulp of its
own, 3 eps X/r from the distance (X the size of the coordinates) and
eps (|q_i| + |q_j|) from the difference; a sum of n terms n eps times the
sum of their sizes, and each incremental update of contacts (a partner's
break since the last recompute) one more rounding: with T = max_i sum_j
|k_ij| (|q_i| + |q_j|), the error is below (2n + 32 + 2B + 8X/r_min) eps T.
The test checks n <= 60, B (breaks in the second run) <= 1000 and
X/r_min <= 300, so that this is below 4500 eps T ~ 1e-12 T: the
tolerance is 1e-12 T.
"""
import math
import re
from pathlib import Path

import numpy as np
import pytest

import eqtools

INPUTS = Path(__file__).resolve().parent / "inputs"
EPS = np.finfo(float).eps
CUT_MARGIN = 1e-8        # pair eq/elastic: within 1e-8 (relative) of rcut is inside
REL = 1e-12              # tolerance relative to T (see the module's doc string)

# ---------------------------------------------------------------- data


def write_data(path, pos, xb, yb):
    lines = ["LAMMPS data file (test_eq_field_validity)", "", f"{len(pos)} atoms", "1 atom types",
             f"{xb[0]:.17g} {xb[1]:.17g} xlo xhi", f"{yb[0]:.17g} {yb[1]:.17g} ylo yhi",
             "-0.5 0.5 zlo zhi", "", "Atoms # atomic", ""]
    lines += [f"{i + 1} 1 {p[0]:.17g} {p[1]:.17g} 0.0" for i, p in enumerate(pos)]
    Path(path).write_text("\n".join(lines) + "\n")


def contacts_data(path, nx=10, ny=8, jitter=0.15, seed=4321):
    """2d hex lattice (nearest neighbours 1 apart), random displacements:
    written here so that 1 and 2 ranks have the same atom IDs."""
    rng = np.random.default_rng(seed)
    lx, ly = float(nx), ny * math.sqrt(3.0)
    pts = [((i + 0.5 * b), (j + 0.5 * b) * math.sqrt(3.0))
           for j in range(ny) for i in range(nx) for b in (0, 1)]
    pos = (np.array(pts) + rng.uniform(-jitter, jitter, (len(pts), 2))) % [lx, ly]
    write_data(path, pos, (0.0, lx), (0.0, ly))


def blocks_data(path, n=10):
    pos = np.array([(float(i), float(j)) for j in range(n) for i in range(n)])
    write_data(path, pos, (-0.5, n - 0.5), (-0.5, n - 0.5))


# ---------------------------------------------------------------- dumps


def read_frames(path):
    """Frames of a dump custom file: dicts with step, box (lo, hi, tilt,
    periodic flags) and the columns by name, atoms sorted by id."""
    frames = []
    for part in Path(path).read_text().split("ITEM: TIMESTEP")[1:]:
        lines = part.strip().splitlines()
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
        h = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
        names = lines[h].split()[2:]
        rows = np.array([[float(v) for v in l.split()] for l in lines[h + 1:]]).reshape(-1, len(names))
        rows = rows[np.argsort(rows[:, names.index("id")], kind="stable")]
        f = {"step": int(lines[0]), "lo": lo, "hi": hi, "tilt": tilt,
             "periodic": [p.startswith("p") for p in lines[k].split()[-3:]]}
        f.update({n: rows[:, c] for c, n in enumerate(names)})
        frames.append(f)
    return frames


# ---------------------------------------------------------------- reference


def crossover(ft, lam):
    return lambda r: np.where(r <= lam, ft / r, ft * lam * lam / r ** 3)


def field(frame, box, kind, rc, ft, lam):
    """h_i from scratch over explicit periodic images of the 2d box `box`
    (a frame: lo, hi, tilt, periodic), an atom's own images left out.
    Returns h, T_i = sum_j |k_ij| (|q_i| + |q_j|), the largest number of
    partners and the smallest distance."""
    q = frame["f_c[1]"] if kind == "contacts" else frame["f_sub[1]"]
    pos = np.column_stack([frame["x"], frame["y"]])
    if kind == "blocks":       # the kernel at the sites' distance
        pos[:, 0] -= q
    lo, hi, tilt, per = box["lo"], box["hi"], box["tilt"], box["periodic"]
    Lx, Ly, xy = hi[0] - lo[0], hi[1] - lo[1], tilt[0]
    # the atoms lie in the (tilted) box up to their motion since the last
    # list build and the displacement of the sites (< 2 here): two atoms
    # are less than Lx + |xy| + 2 apart along x, Ly + 2 along y, so images
    # beyond these shifts cannot come within rc
    my = 1 + int((rc + 2.0) / Ly) if per[1] else 0
    mx = 1 + int((rc + 2.0 + abs(xy) * (1 + my)) / Lx) if per[0] else 0
    n = len(q)
    d0x = pos[:, 0][:, None] - pos[:, 0][None, :]
    d0y = pos[:, 1][:, None] - pos[:, 1][None, :]
    kern = crossover(ft, lam)
    h, T, nn = np.zeros(n), np.zeros(n), np.zeros(n, int)
    rmin = np.inf
    rc2 = (rc * (1 + CUT_MARGIN)) ** 2
    for sx in range(-mx, mx + 1):
        for sy in range(-my, my + 1):
            dx = d0x - (sx * Lx + sy * xy)
            dy = d0y - sy * Ly
            r2 = dx * dx + dy * dy
            assert not np.any(np.abs(r2 / (rc * rc) - 1.0) < 2e-9), "a pair at the cutoff: ill-posed"
            i, j = np.nonzero(r2 <= rc2)
            keep = i != j
            i, j = i[keep], j[keep]
            r = np.sqrt(r2[i, j])
            k = kern(r)
            h += np.bincount(i, k * (q[i] - q[j]), n)
            T += np.bincount(i, k * (np.abs(q[i]) + np.abs(q[j])), n)
            nn += np.bincount(i, minlength=n)
            if len(r):
                rmin = min(rmin, r.min())
    return h, T, nn.max(), rmin


KERNELS = {"contacts": (3.0, 0.05, 2.0), "blocks": (2.5, 3.0, 1.0)}


def check_frames(frames, before, kind, kernel, lag, nbreaks):
    """Every frame against the reference; returns (worst error / tolerance,
    tolerance of the first frame, h of the first frame)."""
    rc, ft, lam = kernel
    worst, first = 0.0, None
    for m, fr in enumerate(frames):
        # fix deform changes the box at the end of a step: the forces of a
        # step saw the box dumped with the step before
        box = frames[m - 1] if (lag and m > 0) else fr
        h, T, nmax, rmin = field(fr, box, kind, rc, ft, lam)
        X = max(np.abs(fr["x"]).max(), np.abs(fr["y"]).max(), (fr["hi"] - fr["lo"])[:2].max())
        # the premises of the tolerance (module doc string)
        assert nmax <= 60 and nbreaks <= 1000 and X / rmin <= 300, (nmax, nbreaks, X / rmin)
        tol = REL * T.max()
        if kind == "contacts":
            own, hcol = -fr["f_c[5]"] * fr["f_c[1]"], fr["f_c[7]"]
        else:
            own, hcol = fr["f_sub[2]"] + fr["f_sub[3]"], fr["f_sub[8]"]
        err_f = np.abs(fr["fx"] - (own - h)).max()
        err_h = np.abs(hcol - h).max()
        assert err_f <= tol + 4 * EPS * np.abs(own).max() and err_h <= tol, \
            (fr["step"], err_f, err_h, tol)
        assert np.all(fr["fy"] == 0.0)          # along dir only
        worst = max(worst, err_f / tol, err_h / tol) if tol > 0 else worst
        if first is None:
            first = (tol, h)
    return worst, first


# ---------------------------------------------------------------- changes
# One LAMMPS run per kind and rank count makes the changes one after the
# other, each followed by a run of STEPS steps with its own dump (and the
# state just before it in NAME.before.dump).  Segments: (name, kinds,
# commands, options); options: every (dump interval), lag (fix deform: the
# box of the step before), expect ("differs": the field of before the
# change is off by >> tol; "same": within tol), coeff (new kernel from
# here on), check (a function of the kind giving a check of the frames),
# flip, undo (commands after the segment's run).
STEPS = 20


def redefine(kind):
    """After clear: the system again from the data file, with the kernel
    of this point of the chain (the first one: pair_coeff comes later)."""
    common = ("units lj\ndimension 2\natom_style atomic\nboundary p p p\natom_modify map array\n"
              "read_data ${out}/state.data\n")
    if kind == "contacts":
        return common + ("pair_style eq/elastic 3.0 check ${check}\npair_coeff * * 0.05 2.0\n"
                         "neighbor 0.5 bin\nneigh_modify every 10 delay 0 check no\n"
                         "fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25 "
                         "reform uniform 0.0 0.4 start reform\ntimestep 0.01")
    return common + ("pair_style eq/elastic 2.5 check ${check}\npair_coeff * * 3.0 1.0\n"
                     "neighbor 2.5 bin\nneigh_modify every 10 delay 0 check no\n"
                     "fix sub all eq/substrate 1.0 sawtooth 1.0 drive 0.5 0.02 stage 1.0 "
                     "disorder uniform 0.6 1.4 4711\ntimestep 0.05\n"
                     # new sites: the blocks displaced from them, as at the start
                     "displace_atoms all random 0.08 0.0 0.0 977 units box")


RESTART = {
    "contacts": "neighbor 0.5 bin\nneigh_modify every 10 delay 0 check no\n"
                "fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25 reform uniform 0.0 0.4 "
                "start reform",
    "blocks": "neighbor 2.5 bin\nneigh_modify every 10 delay 0 check no\n"
              "fix sub all eq/substrate 1.0 sawtooth 1.0 drive 0.5 0.02 stage 1.0 "
              "disorder uniform 0.6 1.4 4711",
}


def new_atom_check(kind):
    def check(frames, before):
        f0 = frames[0]
        assert len(f0["id"]) == len(before["id"]) + 1
        new = np.argmax(f0["id"])
        assert f0["id"][new] > before["id"].max()
        if kind == "blocks":
            assert f0["f_sub[1]"][new] == 0.0          # a block at its site
        else:
            # a new contact, formed as the fix's start says (reform): its
            # force drawn from R = uniform [0, 0.4] (reform_as force,
            # relaxed in the field): |k s + h| <= 0.4 k, no breaks yet
            assert f0["f_c[4]"][new] == 0.0
            assert abs(f0["f_c[5]"][new] * f0["f_c[1]"][new] + f0["f_c[7]"][new]) \
                <= 0.4 * f0["f_c[5]"][new] + 1e-12
    return check


def deleted_check(kind):
    def check(frames, before):
        assert len(frames[0]["id"]) < len(before["id"]) - 5
    return check


def reformed_check(kind):
    def check(frames, before):
        if kind == "contacts":   # a new fix: fresh contacts, no breaks yet
            assert np.all(frames[0]["f_c[4]"] == 0.0) and before["f_c[4]"].sum() > 20
        else:                    # a new fix: new sites, and the blocks displaced
            # from them by at most 0.08 (their wells' origins floor(u))
            u = frames[0]["f_sub[1]"]
            assert np.all(np.abs(u) <= 0.08) and np.all(frames[0]["f_sub[6]"] == np.floor(u))
            assert np.any(frames[0]["f_sub[7]"] != before["f_sub[7]"])
    return check


def restored_check(kind):
    def check(frames, before):
        f0 = frames[0]
        assert np.array_equal(f0["id"], before["id"])
        if kind == "contacts":   # the state restored: break counts and stretches
            assert np.array_equal(f0["f_c[4]"], before["f_c[4]"])
            assert np.allclose(f0["f_c[1]"], before["f_c[1]"], rtol=0, atol=1e-13)
        else:
            assert np.allclose(f0["f_sub[1]"], before["f_sub[1]"], rtol=0, atol=1e-13)
            assert np.array_equal(f0["f_sub[6]"], before["f_sub[6]"])
    return check


LEFT = "region left block INF 4.0 INF INF INF INF units box\ngroup left region left\n"
NEWCOEFF = {"contacts": ("pair_coeff * * 0.08 1.5", (3.0, 0.08, 1.5)),
            "blocks": ("pair_coeff * * 2.0 1.5", (2.5, 2.0, 1.5))}
BOTH = ("contacts", "blocks")

SEGMENTS = [
    ("change_box-x-scale", BOTH, "change_box all x scale 1.1", {"expect": "differs"}),
    ("change_box-x-scale-remap", BOTH, "change_box all x scale 1.02 remap", {"expect": "differs"}),
    ("change_box-y-scale", BOTH, "change_box all y scale 1.07", {"expect": "differs"}),
    ("change_box-y-scale-remap", BOTH, "change_box all y scale 0.95 remap", {"expect": "differs"}),
    ("change_box-triclinic", BOTH, "change_box all triclinic\nchange_box all xy final 0.6",
     {"expect": "differs"}),
    ("change_box-tilt-remap", BOTH, "change_box all xy final -0.4 remap", {"expect": "differs"}),
    ("displace_atoms-move", BOTH, LEFT + "displace_atoms left move 0.15 0.1 0.0 units box",
     {"expect": "differs"}),
    ("displace_atoms-random", BOTH, "displace_atoms all random 0.1 0.1 0.0 4321 units box",
     {"expect": "differs"}),
    ("delete_atoms", BOTH, "region hole block 3.0 6.0 3.0 7.0 INF INF units box\n"
                           "delete_atoms region hole compress no",
     {"expect": "differs", "check": deleted_check}),
    ("create_atoms", BOTH, "create_atoms 1 single 4.5 4.5 0.0 units box",
     {"expect": "differs", "check": new_atom_check}),
    # contacts: the stretches of the left part jump by a box length (they
    # break many times); blocks: all displacements (a part would put
    # coupled blocks a box length apart)
    ("set-image", ("contacts",), "set group left image 1 NULL NULL", {"expect": "differs"}),
    ("set-image", ("blocks",), "set group all image 1 NULL NULL", {}),
    ("write_data-read_data", BOTH, "write_data ${out}/state.data\nclear\n{redefine}",
     {"expect": "differs", "check": reformed_check}),
    ("write_restart-read_restart", BOTH, "write_restart ${out}/state.restart\nclear\n"
                                         "read_restart ${out}/state.restart\n{restart}",
     {"expect": "same", "check": restored_check}),
    ("pair_coeff", BOTH, "{newcoeff}", {"expect": "differs", "coeff": True}),
    # fix deform: the box changes by at most 0.24 over the 10 steps between
    # two list builds, less than half the skin (0.5 for contacts): the
    # lists hold every pair within the cutoff (a faster deformation would
    # leave pairs out that LAMMPS' lists do not see)
    ("fix-deform-x", BOTH, "fix def all deform 1 x delta 0.0 0.47 remap none",
     {"every": 1, "lag": True, "undo": "unfix def"}),
    ("fix-deform-y", BOTH, "fix def all deform 1 y delta 0.0 0.47 remap none",
     {"every": 1, "lag": True, "undo": "unfix def"}),
    ("fix-deform-tilt", BOTH, "fix def all deform 1 xy delta 0.47 remap none",
     {"every": 1, "lag": True, "undo": "unfix def"}),
    # the tilt passes half the box length and flips at the next list build
    ("fix-deform-flip", ("contacts",), "change_box all xy final $(0.5*lx-0.2)\n"
                                       "fix def all deform 1 xy delta 0.47 remap none flip yes",
     {"every": 1, "lag": True, "flip": True, "undo": "unfix def"}),
    ("change_box-boundary", BOTH, "change_box all boundary p f p", {"expect": "differs"}),
]
KINDS = {"contacts": ("in.validity-contacts", "fix mv all move linear 1.0 0.0 0.0 units box",
                      "unfix mv", "f_c[1] f_c[4] f_c[5] f_c[7]"),
         "blocks": ("in.validity-blocks", "fix bd all brownian 1.0 5 rng none gamma_t 5.0",
                    "unfix bd", "f_sub[1] f_sub[2] f_sub[3] f_sub[6] f_sub[7] f_sub[8]")}


def chain(kind, segments):
    """The commands after the first run: every segment's change, then its
    run with a dump every `every` steps from its first step."""
    _, move, unmove, cols = KINDS[kind]
    L = []
    for name, kinds, commands, opt in segments:
        commands = (commands.replace("{redefine}", redefine(kind)).replace("{restart}", RESTART[kind])
                    .replace("{newcoeff}", NEWCOEFF[kind][0]))
        L += [f"write_dump all custom ${{out}}/{name}.before.dump id type x y fx fy {cols} "
              "modify sort id format float %.17g", unmove, commands, move,
              f"dump d all custom {opt.get('every', 5)} ${{out}}/{name}.dump id type x y fx fy {cols}",
              "dump_modify d sort id format float %.17g", f"run {STEPS}", "undump d"]
        if opt.get("undo"):
            L.append(opt["undo"])
    return "\n".join(L) + "\n"


def run_chain(tmp, kind, nprocs, segments, check=1000):
    out = tmp / f"{kind}-np{nprocs}"
    out.mkdir()
    data = out / "validity.data"
    contacts_data(data) if kind == "contacts" else blocks_data(data)
    (out / "chain.in").write_text(chain(kind, segments))
    log = eqtools.run_lammps(INPUTS / KINDS[kind][0],
                             {"data": data, "out": out, "chain": out / "chain.in", "check": check},
                             nprocs=nprocs, cwd=out)
    return log, out


def segments_of(kind):
    return [s for s in SEGMENTS if kind in s[1]]


_chains = {}


def chain_runs(kind, tmp_path_factory):
    """The chain of changes of a kind on 1 and 2 ranks, run once for all
    its tests."""
    if kind not in _chains:
        tmp = tmp_path_factory.mktemp(f"validity-{kind}")
        _chains[kind] = [run_chain(tmp, kind, nprocs, segments_of(kind))[1] for nprocs in (1, 2)]
    return _chains[kind]


PARAMS = [(name, kind) for kind in BOTH for name, kinds, _, _ in SEGMENTS if kind in kinds]


@pytest.mark.parametrize("name,kind", PARAMS)
def test_forces_after_the_change(tmp_path_factory, name, kind):
    """The forces and the field column of every dumped step after the
    change (the first, at the set-up of the run after it, included)
    against the field from scratch, on 1 and 2 ranks; the change's own
    checks (atoms added, removed, contacts re-formed, state restored); the
    field of before the change is far off (or, after a restart, within the
    tolerance); with fix deform the forces of a step follow the box of the
    step before, and a box held at its first value is far off."""
    segs = segments_of(kind)
    k = [s[0] for s in segs].index(name)
    opt = segs[k][3]
    # the kernel before and after this change
    newcoeff = [s[3].get("coeff", False) for s in segs]
    kernel_before = NEWCOEFF[kind][1] if any(newcoeff[:k]) else KERNELS[kind]
    kernel = NEWCOEFF[kind][1] if any(newcoeff[:k + 1]) else KERNELS[kind]
    for out in chain_runs(kind, tmp_path_factory):
        before = read_frames(out / f"{name}.before.dump")[0]
        frames = read_frames(out / f"{name}.dump")
        assert len(frames) == (STEPS + 1 if opt.get("every") == 1 else STEPS // 5 + 1)
        nb = frames[-1]["f_c[4]"].sum() - frames[0]["f_c[4]"].sum() if kind == "contacts" else 0
        worst, (tol0, h0) = check_frames(frames, before, kind, kernel, opt.get("lag"), nb)
        # the field is not trivial
        assert max(np.abs(f["f_c[7]" if kind == "contacts" else "f_sub[8]"]).max()
                   for f in frames) > 0.01
        if opt.get("check"):
            opt["check"](kind)(frames, before)
        # the test can fail: the field of before the change
        h_old, T_old, _, _ = field(before, before, kind, *kernel_before)
        if opt.get("expect") and len(h_old) == len(h0):
            dev = np.abs(h_old - h0).max()
            if opt["expect"] == "differs":
                assert dev > 100 * tol0, (name, kind, dev, tol0)
            else:
                assert dev <= tol0 + REL * T_old.max(), (name, kind, dev, tol0)
        elif opt.get("expect") == "differs":
            # atoms were added or removed: compare by ID
            ids0, ids1 = before["id"], frames[0]["id"]
            common = np.intersect1d(ids0, ids1)
            a = h_old[np.searchsorted(ids0, common)]
            b = h0[np.searchsorted(ids1, common)]
            assert np.abs(a - b).max() > 100 * tol0, (name, kind)
        if opt.get("lag"):
            # the box did change, and the reference must follow it: the
            # box of the first frame instead gives forces far off
            last = frames[-1]
            assert np.any(last["hi"] - last["lo"] != frames[0]["hi"] - frames[0]["lo"]) or \
                last["tilt"][0] != frames[0]["tilt"][0]
            h_fixed, T, _, _ = field(last, frames[0], kind, *kernel)
            hcol = last["f_c[7]" if kind == "contacts" else "f_sub[8]"]
            assert np.abs(hcol - h_fixed).max() > 100 * REL * T.max(), (name, kind)
        if opt.get("flip"):
            # the tilt grew past half the box length and was flipped back
            tilts = [f["tilt"][0] for f in frames]
            assert any(t2 < t1 for t1, t2 in zip(tilts, tilts[1:])), tilts


DRIFT = re.compile(r"(\d+) drift checks: max \|h_incremental - h_full\| = (\S+) "
                   r"\(scale of h: (\S+)\)")


@pytest.mark.parametrize("kind", BOTH)
def test_drift_report_with_check_1(tmp_path, kind):
    """pair_style eq/elastic R check 1: every update is compared with a
    field from scratch, the largest difference reported at the end of each
    run: X <= 1e-12 Y (Y the scale of h, as above), on 1 and 2 ranks; over
    two runs with breaks (contacts sliding rigidly) or slips (blocks
    following their positions)."""
    for nprocs in (1, 2):
        log, out = run_chain(tmp_path, kind, nprocs, [("none", BOTH, "# no change", {})], check=1)
        reports = DRIFT.findall(log)
        assert len(reports) == 2, log[-3000:]          # one per run
        for n, X, Y in reports:
            # every update that is not a recompute after a list build
            assert int(n) >= 15 and float(Y) > 0.01, (n, X, Y)
            assert float(X) <= 1e-12 * float(Y), (nprocs, n, X, Y)


def test_lattice_shell_at_the_cutoff_stays_inside(tmp_path):
    """rcut = lambda_c = 3 on a triangular lattice of spacing 1: the shell of
    6 neighbours at r = 3 lies at the cutoff.  After 2500 steps of a rigid
    slider moved by fix nve/noforce (each atom's x rounded on its own at
    every step, |x| up to 64) and 2500 more with `check 1`, every
    incremental update equals the field from scratch to rounding (a shell
    that drops out leaves k(3) |dq| ~ 1e-3 in h: with a cutoff margin of
    1e-12 it did, after about 2400 steps)."""
    log = eqtools.run_lammps(INPUTS / "in.shell-cutoff", {"steps": 2500}, cwd=tmp_path)
    reports = DRIFT.findall(log)
    assert len(reports) == 1, log[-3000:]
    n, X, Y = reports[0]
    assert int(n) >= 2000 and float(Y) > 0.01, (n, X, Y)
    assert float(X) <= 1e-12 * float(Y), (n, X, Y)
