"""Every global and per-atom output of fix eq/contacts, eq/substrate,
eq/meso and eq/quasistatic gives the same values through every access
path, and the values before the first run are those of the model at the
fix's definition.

Paths (written by `output_commands`):

* thermo: f_ID, f_ID[i] (thermo_modify norm no, format float %20.16g);
* equal-style variables of f_ID and f_ID[i], in thermo;
* fix ave/time 1 1 N f_ID f_ID[i] (file, format %20.16g), every N = 5
  steps, also between the thermo steps (every 10): the sums over the
  ranks are made whenever an output asks;
* per-atom columns: dump custom f_ID[i] (every step, %.17g), fix ave/atom
  1 1 N f_ID[i] (dumped every N beside them), compute reduce sum f_ID[i],
  and atom-style variables of the columns with compute reduce sum: of
  fix ave/atom's array (any LAMMPS), and of f_ID[i] itself, which means
  the per-atom column in LAMMPS 4 Feb 2025 and 4 Jul 2026 (its reduce sum
  is compute reduce's) and the global vector entry in 29 Sep 2021 (its
  reduce sum is N f_ID[i]; see atom_variable_rule);
* before the first run: print of $(f_ID[i]) and $(v_...) (LAMMPS passes
  an equal-style variable named in a formula through its %.15g string)
  and write_dump of the per-atom columns; the same values, to the bit,
  after run 0 (nothing changes at a run's set-up here), and the model's
  values at definition (counts, the driving springs' K X0, the contacts'
  sums, the blocks' screening sums Pi_0).

The sums the docs define (friction force, break counts, energies, means)
are checked against the dumped per-atom columns of the same step (fix
eq/meso: the mean screening against the mean of column 4); thermo_modify
norm yes divides exactly the entries the docs call extensive by the
number of atoms.  Entries tied to the motion: the stage X0 + v t, the
slider of fix eq/quasistatic (the displacement of every atom, the advance
of the step), one avalanche per quasi-static step.

Tolerances: the same double printed by two paths with the same format
must be the same text; a sum of n values computed in another order
differs by at most n eps sum |x|; a value printed with %20.16g carries a
relative rounding of 5e-16.
"""
import re
from pathlib import Path

import numpy as np
import pytest

import eqtools

INPUTS = Path(__file__).resolve().parent / "inputs"
EPS = np.finfo(float).eps
PRINT16 = 1e-15          # relative rounding of %20.16g, with a factor 2
EVERY = 5                # ave/time, ave/atom, their dump
THERMO = 10

# fix ID, length of the global vector, per-atom columns, extensive entries
FIXES = {
    "contacts": [("c", 8, 7, {1, 2, 3, 4, 5, 7})],
    "quasistatic": [("c", 8, 7, {1, 2, 3, 4, 5, 7}), ("q", 2, 0, set())],
    "substrate": [("sub", 10, 8, {6, 7, 8, 9, 10})],
    "meso": [("m", 9, 7, {1, 5, 6})],
}
# entries that have no value before the first run: an error says so
# (eq/meso's largest Pi0 needs the neighbor list of a run)
NOT_BEFORE_RUN = {"m": {9}}
SETUPS = {   # input, variables
    "contacts": ("in.paths-contacts", {"pair": "no"}),
    "quasistatic": ("in.paths-contacts", {"pair": "yes"}),
    "substrate": ("in.paths-substrate", {}),
    "meso": ("in.paths-meso", {}),
}


def output_commands(fixes, out):
    """The output paths of every fix, and the prints before the first run
    and after run 0."""
    L, th, pr = [], ["step"], []
    for fid, nv, nc, _ in fixes:
        vec = [f"f_{fid}[{i}]" for i in range(1, nv + 1)]
        L.append(f"variable {fid}_s equal f_{fid}")
        L += [f"variable {fid}_v{i} equal f_{fid}[{i}]" for i in range(1, nv + 1)]
        th += [f"f_{fid}"] + vec + [f"v_{fid}_s"] + [f"v_{fid}_v{i}" for i in range(1, nv + 1)]
        if nc:
            # an atom-style variable of f_ID[i] itself: the global vector
            # entry in LAMMPS up to 2022, the per-atom column in 2025 and
            # later (see atom_variable_rule)
            ng = min(nv, nc)
            L += [f"variable {fid}_g{i} atom f_{fid}[{i}]" for i in range(1, ng + 1)]
            L.append(f"compute {fid}_rg all reduce sum " +
                     " ".join(f"v_{fid}_g{i}" for i in range(1, ng + 1)))
            th += [f"c_{fid}_rg[{i}]" for i in range(1, ng + 1)]
        L.append(f"fix {fid}_at all ave/time 1 1 {EVERY} f_{fid} " + " ".join(vec) +
                 f" file {out}/{fid}.avetime format ' %20.16g'")
        have = [i for i in range(1, nv + 1) if i not in NOT_BEFORE_RUN.get(fid, set())]
        pr.append(f"{fid} $(f_{fid}:%.17g) " + " ".join(f"$(f_{fid}[{i}]:%.17g)" for i in have) +
                  f" $(v_{fid}_s:%.17g) " + " ".join(f"$(v_{fid}_v{i}:%.17g)" for i in have))
        if nc:
            col = [f"f_{fid}[{i}]" for i in range(1, nc + 1)]
            L.append(f"fix {fid}_aa all ave/atom 1 1 {EVERY} " + " ".join(col))
            L += [f"variable {fid}_a{i} atom f_{fid}_aa[{i}]" for i in range(1, nc + 1)]
            L.append(f"compute {fid}_r all reduce sum " + " ".join(col))
            L.append(f"compute {fid}_ra all reduce sum " +
                     " ".join(f"v_{fid}_a{i}" for i in range(1, nc + 1)))
            th += [f"c_{fid}_r[{i}]" for i in range(1, nc + 1)] + \
                  [f"c_{fid}_ra[{i}]" for i in range(1, nc + 1)]
            L.append(f"write_dump all custom {out}/{fid}.before.dump id xu " + " ".join(col) +
                     " modify sort id format float %.17g")
            L.append(f"dump {fid}_d all custom 1 {out}/{fid}.dump id xu vx " + " ".join(col))
            L.append(f"dump_modify {fid}_d sort id format float %.17g")
            L.append(f"dump {fid}_e all custom {EVERY} {out}/{fid}.ave.dump id " + " ".join(col) + " " +
                     " ".join(f"f_{fid}_aa[{i}]" for i in range(1, nc + 1)))
            L.append(f"dump_modify {fid}_e sort id format float %.17g")
        else:
            L.append(f"dump {fid}_d all custom 1 {out}/{fid}.dump id xu")
            L.append(f"dump_modify {fid}_d sort id format float %.17g")
    L.append("thermo_style custom " + " ".join(th))
    L.append("thermo_modify norm no format float %20.16g")
    L.append(f"thermo {THERMO}")
    before = "\n".join(L + [f'print "BEFORE {p}"' for p in pr]) + "\n"
    after = "\n".join(f'print "AFTER0 {p}"' for p in pr) + "\n"
    return before, after


def run(tmp, setup, nprocs):
    out = tmp / f"np{nprocs}"
    out.mkdir()
    inp, var = SETUPS[setup]
    before, after = output_commands(FIXES[setup], out)
    (out / "outputs.in").write_text(before)
    (out / "after0.in").write_text(after)
    log = eqtools.run_lammps(INPUTS / inp, dict(var, out=out, outputs=out / "outputs.in",
                                                after0=out / "after0.in", every=EVERY),
                             nprocs=nprocs, cwd=out)
    return log, out


# ---------------------------------------------------------------- readers

def thermo_runs(log):
    """[[{column: text}] per run]."""
    runs, head = [], None
    for l in log.splitlines():
        w = l.split()
        if w[:1] == ["Step"]:
            head = w
            runs.append([])
        elif l.startswith("Loop time"):
            head = None
        elif head and len(w) == len(head) and w[0].isdigit():
            runs[-1].append(dict(zip(head, w)))
    return runs


def prints(log, tag):
    out = {}
    for l in log.splitlines():
        w = l.split()
        if w[:1] == [tag]:
            out[w[1]] = w[2:]
    return out


def avetime(path):
    rows = {}
    for l in Path(path).read_text().splitlines():
        if l.startswith("#") or not l.strip():
            continue
        w = l.split()
        rows[int(w[0])] = w[1:]
    return rows


def dump_frames(path):
    """{step: {column: array}} of a dump custom file (sorted by id)."""
    frames = {}
    for part in Path(path).read_text().split("ITEM: TIMESTEP")[1:]:
        lines = part.strip().splitlines()
        h = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
        names = lines[h].split()[2:]
        rows = np.array([[float(v) for v in l.split()] for l in lines[h + 1:]]).reshape(-1, len(names))
        frames[int(lines[0])] = {n: rows[:, c] for c, n in enumerate(names)}
    return frames


def close(value, ref, n_terms=1, size=None):
    """|value - ref| within the rounding of a printed value and of a sum of
    n_terms terms of total size `size` (default |ref|)."""
    size = abs(ref) if size is None else size
    return abs(value - ref) <= PRINT16 * max(abs(value), abs(ref)) + (n_terms + 2) * EPS * size


# ---------------------------------------------------------------- model sums

def doc_sums(fid, d, prev, natoms):
    """The global entries that the docs define from the per-atom columns
    (d: the dump of this step, prev: of the step before), as (entry,
    reference, size of the sum's terms, number of terms); entries not
    derivable from the columns are left out."""
    c = lambda i: d[f"f_{fid}[{i}]"]
    n = natoms
    out = []
    if fid == "c":
        att = c(2) > 0   # attached contacts have a threshold (none detach here)
        out += [(1, c(3).sum(), np.abs(c(3)).sum(), n), (3, c(4).sum(), c(4).sum(), 1),
                (4, float(att.sum()), 0, 1), (5, 0.5 * np.sum(c(3) * c(1)), np.sum(np.abs(c(3) * c(1))), n + 2),
                (6, c(1).sum() / att.sum(), np.abs(c(1)).sum() / att.sum(), n + 2), (7, float(n), 0, 1)]
        if prev is not None:
            out.append((2, c(4).sum() - prev[f"f_{fid}[4]"].sum(), 0, 1))
    elif fid == "sub":
        u, fs, fd, kc, dd, a = c(1), c(2), c(3), c(4), c(5), c(6)
        K = 0.5
        r = u - a
        esub = kc * dd * (0.5 * r * r + 0.5 * a)          # sawtooth: V = r^2/2, W = V(1) = 1/2
        out += [(4, d["vx"].sum() / n, np.abs(d["vx"]).sum() / n, n), (5, u.sum() / n, np.abs(u).sum() / n, n),
                (6, -fs.sum(), np.abs(fs).sum(), n), (7, fd.sum(), np.abs(fd).sum(), n),
                (8, esub.sum(), np.abs(esub).sum(), n + 8),
                (9, np.sum(fd * fd) / (2 * K), np.sum(fd * fd) / (2 * K), n + 8), (10, float(n), 0, 1)]
    elif fid == "m":
        out += [(1, c(2).sum(), np.abs(c(2)).sum(), n), (2, c(3).sum() / n, np.abs(c(3)).sum() / n, n),
                (3, c(4).sum() / n, np.abs(c(4)).sum() / n, n), (4, c(1).sum() / n, np.abs(c(1)).sum() / n, n),
                (5, c(5).sum(), np.abs(c(5)).sum(), n), (6, float(n), 0, 1)]
    return out


def check_definition(setup, fid, vals, before, natoms):
    """The values before the first run against the model at definition;
    vals = [scalar, vector...] from print, before = write_dump's columns."""
    s, v = vals[0], vals[1:]
    c = (lambda i: before[f"f_{fid}[{i}]"]) if before is not None else None
    n = natoms
    if fid == "c":
        assert v[3] == n and v[6] == n and v[1] == 0 and v[2] == 0 and v[7] == 0, v
        assert np.all(c(4) == 0) and np.all((c(2) >= 0.75) & (c(2) <= 1.25)) and np.all(c(7) == 0)
        # anchors: s = xu - anchor, rounded
        assert np.all(np.abs(c(6) - (before["xu"] - c(1))) <= 2 * EPS * np.abs(before["xu"]))
        if setup == "quasistatic":                                  # start relaxed
            assert np.all(c(1) == 0) and np.all(c(3) == 0) and v[0] == 0 and v[4] == 0 and s == 0
            assert np.all(c(5) == 1.0)
        else:                                                       # start reform, stiffness
            assert np.all((c(1) >= 0) & (c(1) <= 0.4)) and np.all((c(5) >= 1.0) & (c(5) <= 3.0))
            assert np.all(c(3) == c(5) * c(1))
            assert close(v[0], c(3).sum(), n, np.abs(c(3)).sum()) and v[0] > 0
            assert close(v[4], 0.5 * np.sum(c(3) * c(1)), n + 2, np.sum(c(3) * c(1)))
            assert close(v[5], c(1).sum() / n, n + 2, c(1).sum() / n) and s == v[4]
    elif fid == "q":
        assert s == 0 and v == [0, 0]
    elif fid == "sub":
        K, X0, vs = 0.5, 4.0, 0.2
        assert v[0] == K * X0 and v[1] == X0 and v[2] == vs and v[3] == 0 and v[4] == 0, v
        assert v[5] == 0 and v[6] == n * K * X0 and v[7] == 0 and v[9] == n, v
        assert close(v[8], n * 0.5 * K * X0 ** 2, n) and s == v[7] + v[8]
        assert np.all(c(1) == 0) and np.all(c(2) == 0) and np.all(c(3) == K * X0)
        assert np.all(c(4) == 1.0) and np.all((c(5) >= 0.6) & (c(5) <= 1.4)) and np.all(c(6) == 0)
        assert np.all(c(7) == before["xu"]) and np.all(c(8) == 0)
    elif fid == "m":
        K, X0 = 50.0, 0.3
        # F_n = N_lambda k_c <u>, <u> = 0.1 for R uniform on [0, 0.2] (to the grid)
        assert np.all(np.abs(c(2) - 10.0) < 0.05) and np.all(c(1) == 0) and np.all(c(3) == 0)
        assert np.all(c(4) == 0) and np.all(c(5) == K * X0) and np.all(c(6) == 1.0)
        assert np.all(c(7) == before["xu"])
        assert close(v[0], c(2).sum(), n, np.abs(c(2)).sum()) and s == v[0]
        assert v[1] == 0 and v[2] == 0 and v[3] == 0 and v[4] == n * K * X0 and v[5] == n
        assert v[6] == X0 and v[7] <= 1e-9
        # Pi_0 (entry 9) is not available before the first run
        assert np.isnan(v[8])


_runs = {}


def runs_of(setup, tmp_path_factory):
    """The runs of a set-up on 1 and 2 ranks, made once for both tests."""
    if setup not in _runs:
        tmp = tmp_path_factory.mktemp(f"paths-{setup}")
        _runs[setup] = [(nprocs,) + run(tmp, setup, nprocs) for nprocs in (1, 2)]
    return _runs[setup]


@pytest.mark.parametrize("setup", sorted(SETUPS))
def test_values_before_the_first_run(tmp_path_factory, setup):
    """Read before the first run (print of $(f_ID), $(f_ID[i]) and of
    equal-style variables of them; write_dump of the per-atom columns):
    the same through both paths, the same as after run 0, and the model's
    values at the fix's definition."""
    for nprocs, log, out in runs_of(setup, tmp_path_factory):
        check_before(setup, log, out, nprocs)


@pytest.mark.parametrize("setup", sorted(SETUPS))
def test_output_paths_during_runs(tmp_path_factory, setup):
    """Thermo, equal-style variables, fix ave/time, dump custom, fix
    ave/atom, compute reduce of the columns and of atom-style variables:
    the same values at every step they share, the docs' sums of the
    per-atom columns, and thermo_modify norm yes on the extensive entries."""
    for nprocs, log, out in runs_of(setup, tmp_path_factory):
        check_run(setup, log, out, nprocs)


def check_before(setup, log, out, nprocs):
    natoms = int(re.search(r"Created (\d+) atoms", log).group(1))
    B, A = prints(log, "BEFORE"), prints(log, "AFTER0")
    for fid, nv, nc, ext in FIXES[setup]:
        b, a = B[fid], A[fid]
        missing = NOT_BEFORE_RUN.get(fid, set())
        nh = nv - len(missing)
        assert len(b) == 2 * (nh + 1), (fid, b)
        # an equal-style variable referenced as v_name in a formula ($(v_..))
        # passes through LAMMPS' string of it, %.15g
        assert [float(f"{float(x):.15g}") for x in b[:nh + 1]] == [float(x) for x in b[nh + 1:]], \
            (fid, "f_ID", b[:nh + 1], "equal-style variables", b[nh + 1:])
        assert a == b, (fid, "after run 0", a, "before", b)
        before = None
        if nc:
            before = dump_frames(out / f"{fid}.before.dump")[0]
            after0 = dump_frames(out / f"{fid}.dump")[0]
            for i in range(1, nc + 1):
                col = f"f_{fid}[{i}]"
                assert np.array_equal(before[col], after0[col]), (fid, col, "before vs run 0")
        vals = [float(x) for x in b[:nh + 1]]
        for i in sorted(missing):           # entry i (1-based) is not printed: a placeholder
            vals.insert(i, float("nan"))
        check_definition(setup, fid, vals, before, natoms)


def atom_variable_rule(log):
    """What f_ID[i] means in an atom-style variable for a fix with a global
    vector and a per-atom array: LAMMPS 29 Sep 2021 takes the global vector
    entry, 4 Feb 2025 and 4 Jul 2026 the per-atom column (variable.cpp
    decides by the variable's style there).  None for versions between,
    where the test accepts either."""
    m = re.search(r"LAMMPS \((\d+) (\w{3})\w* (\d{4})", log)
    months = "Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec".split()
    date = (int(m.group(3)), months.index(m.group(2)) + 1, int(m.group(1)))
    if date >= (2025, 2, 4):
        return "per-atom"
    if date <= (2022, 1, 6):
        return "global"
    return None


def check_run(setup, log, out, nprocs):
    rule = atom_variable_rule(log)
    runs = thermo_runs(log)
    assert len(runs) == 3, log[-3000:]
    natoms = int(re.search(r"Loop time of \S+ on \d+ procs for \d+ steps with (\d+) atoms", log).group(1))
    for fid, nv, nc, ext in FIXES[setup]:
        D = dump_frames(out / f"{fid}.dump")
        E = dump_frames(out / f"{fid}.ave.dump") if nc else {}
        T = avetime(out / f"{fid}.avetime")
        # thermo norm no: runs 0 and 1
        thermo = {}
        for row in runs[0] + runs[1]:
            step = int(row["Step"])
            vals = [row[f"f_{fid}"]] + [row[f"f_{fid}[{i}]"] for i in range(1, nv + 1)]
            assert row[f"v_{fid}_s"] == vals[0], (fid, step)
            for i in range(1, nv + 1):
                assert row[f"v_{fid}_v{i}"] == vals[i], (fid, step, i)
            if nc:
                d = D[step]
                for i in range(1, nc + 1):
                    r, ra = row[f"c_{fid}_r[{i}]"], row[f"c_{fid}_ra[{i}]"]
                    assert r == ra, (fid, step, i, r, ra)
                    x = d[f"f_{fid}[{i}]"]
                    assert close(float(r), x.sum(), len(x), np.abs(x).sum()), (fid, step, i, r, x.sum())
                for i in range(1, min(nv, nc) + 1):
                    g = row[f"c_{fid}_rg[{i}]"]
                    col = g == row[f"c_{fid}_r[{i}]"]        # the column: compute reduce's sum
                    glob = close(float(g), natoms * float(vals[i]), natoms,
                                 natoms * abs(float(vals[i])))  # the global entry on every atom
                    assert (col if rule == "per-atom" else glob if rule == "global" else col or glob), \
                        (fid, step, i, rule, g)
            thermo[step] = vals
        assert len(thermo) >= 7
        # fix ave/time: the same text as thermo where both write, and
        # between the thermo steps the sums of the dump
        assert sorted(T) == list(range(0, 61, EVERY)) + [65], sorted(T)
        for step, vals in T.items():
            if step in thermo and step <= 60:
                assert vals == thermo[step], (fid, step, vals, thermo[step])
            if nc and step in E:
                e = E[step]
                for i in range(1, nc + 1):
                    assert np.array_equal(e[f"f_{fid}[{i}]"], e[f"f_{fid}_aa[{i}]"]), (fid, step, i)
                    assert np.array_equal(e[f"f_{fid}[{i}]"], D[step][f"f_{fid}[{i}]"]), (fid, step, i)
            v = [float(x) for x in vals]
            # the scalar: an entry of the vector (or two of them, summed)
            if fid == "c":
                assert vals[0] == vals[5], (step, vals)
            elif fid in ("q", "m"):
                assert vals[0] == vals[1], (step, vals)
            prev = D.get(step - 1)
            for entry, ref, size, nt in doc_sums(fid, D[step], prev, natoms):
                assert close(v[entry], ref, nt, size), (setup, fid, step, entry, v[entry], ref)
            check_step_model(setup, fid, v, D, step, out)
        # thermo_modify norm yes (run 2): extensive entries / N, the
        # variables are never normalized
        for row in runs[2]:
            for i in range(1, nv + 1):
                f, var = float(row[f"f_{fid}[{i}]"]), float(row[f"v_{fid}_v{i}"])
                want = var / natoms if i in ext else var
                assert close(f, want), (fid, i, f, var, i in ext)
    # the run did something
    if setup in ("contacts", "quasistatic"):
        last = avetime(out / "c.avetime")[60]
        assert float(last[3]) > 20
    if setup == "substrate":        # blocks slipped to the next well
        assert dump_frames(out / "sub.dump")[60]["f_sub[6]"].max() >= 1.0
    if setup == "meso":             # contacts broke
        assert dump_frames(out / "m.dump")[60]["f_m[3]"].min() > 0.0


def check_step_model(setup, fid, v, D, step, out):
    """Entries tied to each other or to the motion: the contacts' avalanche
    rounds, the stage of the blocks, the slider of eq/quasistatic."""
    if fid == "c":
        breaks, rounds = v[2], v[8]
        assert (rounds == 0) == (breaks == 0), (step, breaks, rounds)
        if setup == "contacts":
            assert rounds == (1 if breaks > 0 else 0)
        elif step > 0:        # quasi-static: every step one avalanche
            assert breaks >= 1 and rounds >= 1, (step, breaks, rounds)
    if fid == "sub":
        K, X0, vs, dt = 0.5, 4.0, 0.2, 0.05
        assert close(v[1], K * v[2]) and v[3] == vs
        assert close(v[2], X0 + vs * dt * step, step + 2, X0 + vs * dt * step)
        assert close(v[0], v[8] + v[9], 2, abs(v[8]) + abs(v[9]))
    if fid == "m":
        K, X0, vs, dt = 50.0, 0.3, 0.1, 0.5
        assert close(v[7], X0 + vs * dt * step, step + 2, X0 + vs * dt * step)
        d = D[step]
        Xs = d["f_m[5]"] / K + d["f_m[1]"]
        assert np.all(np.abs(Xs - v[7]) <= 8 * EPS * (np.abs(d["f_m[5]"]) / K + abs(v[7])) + PRINT16 * abs(v[7]))
        assert v[8] <= 1e-9 and abs(v[9] - 0.4) <= 1e-12
    if fid == "q":
        # X: the displacement of every atom since the fix was defined, and
        # the advance of the step: the change of the positions in it
        xu, xu0 = D[step]["xu"], D[0]["xu"]
        tol = (step + 2) * 2 * EPS * np.abs(xu).max()
        assert np.all(np.abs(xu - xu0 - v[1]) <= tol + PRINT16 * v[1]), step
        if step > 0:
            adv = xu - D[step - 1]["xu"]
            assert np.all(np.abs(adv - v[2]) <= 4 * EPS * np.abs(xu).max() + PRINT16 * v[2]), step
            assert v[2] > 0


def test_meso_pi0_only_after_a_run(tmp_path):
    """eq/meso's largest Pi0 (entry 9) needs the neighbor list of a run:
    read before the first run it is an error that says so, never 0; after
    run 0 it is N_lambda kappa sum_m (lambda_c/r)^3 over the 4 neighbours at
    r = 1 (the square lattice of in.paths-meso)."""
    inp = INPUTS / "in.paths-meso"
    (tmp_path / "outputs.in").write_text('print "PI0 $(f_m[9]:%.17g)"\n')
    (tmp_path / "after0.in").write_text('print "PI0 $(f_m[9]:%.17g)"\n')
    log = eqtools.run_lammps(inp, dict(out=tmp_path, outputs=tmp_path / "outputs.in",
                                       after0=tmp_path / "after0.in", every=EVERY),
                             cwd=tmp_path, check=False)
    assert re.search(r"ERROR: Fix m eq/meso: the largest Pi0 \(global vector entry 9\) is not "
                     r"available before the first run", log), log[-2000:]
    (tmp_path / "outputs.in").write_text("")
    log = eqtools.run_lammps(inp, dict(out=tmp_path, outputs=tmp_path / "outputs.in",
                                       after0=tmp_path / "after0.in", every=EVERY), cwd=tmp_path)
    pi0 = [float(l.split()[1]) for l in log.splitlines() if l.startswith("PI0")]
    assert pi0 and abs(pi0[0] - 100 * 0.001 * 4) <= 1e-12, pi0
