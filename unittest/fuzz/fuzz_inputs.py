#!/usr/bin/python3
"""Fuzzed input for the FRICTION-EQ styles: generator and runner.

Derives malformed LAMMPS inputs from a few small valid base inputs (the
set-ups of examples/ and unittest/python/inputs/, shrunk to ~100 atoms and
a few dozen steps), one mutation per case, and runs each under a timeout.
Every malformed case must end in a LAMMPS ERROR whose message names the
command and the keyword (regular expressions, case-insensitive; the
"Last command:" echo that LAMMPS adds does not count), never in a crash,
a hang, NaN/inf in the output, or a run that silently accepts the input.
Valid controls must run to the end with finite output.

    /usr/bin/python3 unittest/fuzz/fuzz_inputs.py --lmp build/lmp
    /usr/bin/python3 unittest/fuzz/fuzz_inputs.py --lmp build-2021/lmp --jobs 2 --filter 'table'
    /usr/bin/python3 unittest/fuzz/fuzz_inputs.py --list            # ids, classes, expectations
    /usr/bin/python3 unittest/fuzz/fuzz_inputs.py --show ID         # one case's input and files

Outcomes: error-ok (ERROR naming command and keyword), error-vague (ERROR
not naming them), crash (signal, uncaught exception, MPI abort or non-zero
exit without ERROR), hang (timeout), nan (nan/inf in a thermo row, nan in
anything else LAMMPS or the styles print), accepted (a malformed input ran
without error); for the controls ok, rejected (a valid input stopped with
an error) or incomplete.  Class "extreme" holds finite values that the
documentation allows (1e300, 1e-300, timestep 0, ...): they must not crash,
hang or print NaN, and any ERROR is fine for them (error-other when it does
not name command and keyword).

A keyword counts as named only outside the message's "allowed: ..." list;
LAMMPS' "Last command:" echo never counts.

Python 3 standard library only.  The generator is deterministic.
"""

import argparse
import collections
import dataclasses
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(os.environ.get("FEQ_ROOT", Path(__file__).resolve().parents[2]))

MALFORMED_CLASSES = (
    "missing", "zero", "negative", "nan", "inf", "huge", "wrong-type", "unknown-keyword",
    "unknown-value", "wrong-group", "wrong-id", "before-box", "atom-style", "dimension",
    "pair-coeff", "conflict", "out-of-range", "runtime", "file-missing", "file-empty",
    "file-garbled", "file-nonmonotonic", "file-nan", "file-range", "file-unwritable")
# extreme: finite but extreme values (1e300, 1e-300, timestep 0, ...) that the
#          documentation does not forbid: an error naming command and keyword,
#          or a run to the end with finite output; never crash, hang or NaN.
OTHER_CLASSES = ("extreme", "control", "valid-edge")

# ----------------------------------------------------------------------------
# expectations


@dataclasses.dataclass
class Expect:
    kind: str                 # "error", "ok", "error-or-ok" or "robust"
    cmd: str = ""             # regex the ERROR message must match (command)
    kw: str = ""              # regex the ERROR message must match (keyword)

    def text(self):
        if self.kind == "ok":
            return "runs to the end, finite output"
        if self.kind == "robust":
            return ("an ERROR (best naming /" + self.cmd + "/ and /" + self.kw + "/) or a run to "
                    "the end with finite output; no crash, hang or NaN")
        s = f"ERROR /{self.cmd}/ and /{self.kw}/"
        return s if self.kind == "error" else s + " (or runs to the end, finite output)"


@dataclasses.dataclass
class Case:
    id: str
    cls: str
    input: str
    expect: Expect
    files: dict = dataclasses.field(default_factory=dict)   # name -> str or bytes
    np: int = 1
    note: str = ""
    # the runner's time limit (a hang) is this many times its default: a
    # case whose expected end is a long computation (an avalanche of
    # 100000 rounds on 2 oversubscribed ranks)
    budget: float = 1.0

    def write(self, folder):
        folder = Path(folder)
        (folder / "in.case").write_text(self.input)
        for name, content in self.files.items():
            p = folder / name
            p.parent.mkdir(parents=True, exist_ok=True)
            if isinstance(content, bytes):
                p.write_bytes(content)
            else:
                p.write_text(content)


# ----------------------------------------------------------------------------
# command model: head tokens, positional parameters, keyword groups


@dataclasses.dataclass
class P:
    """One value of a command.  kind: real, int, word, outfile, infile, key,
    fixid, group.  valid: mutation classes that are valid for this value
    (they become valid-edge controls).  extreme: (value, expect-kind) pairs
    of finite extremes.  nomissing: dropping it is not an error (optional
    trailing value) or not well defined."""
    name: str
    value: str
    kind: str = "real"
    valid: tuple = ()
    choices: tuple = ()
    extreme: tuple = (("1e300", "robust"), ("1e-300", "robust"))
    nomissing: bool = False


@dataclasses.dataclass
class Cmd:
    name: str                 # short name for ids, e.g. "contacts"
    cmd_re: str               # the command, as its messages name it
    head: list                # leading literal tokens
    pos: list                 # positional P's
    groups: list              # [(keyword, [P or literal str, ...]), ...]
    pinned: int = 0           # the first `pinned` groups are positional (a shape): never moved

    def tokens(self):
        out = list(self.head) + [p.value for p in self.pos]
        for kw, items in self.groups:
            out.append(kw)
            out += [it.value if isinstance(it, P) else it for it in items]
        return out

    def line(self):
        return " ".join(self.tokens())


def tok_render(head, pos, groups):
    out = list(head) + [v for v in pos if v is not None]
    for kw, vals in groups:
        if kw is not None:
            out.append(kw)
        out += [v for v in vals if v is not None]
    return " ".join(out)


REAL_VARIANTS = [
    ("missing", None), ("zero", "0"), ("negative", "-0.5"), ("nan", "nan"), ("nan", "NaN"),
    ("inf", "inf"), ("inf", "-inf"), ("huge", "1e400"), ("huge", "-1e400"),
    ("wrong-type", "abc"), ("wrong-type", "1.5.2"),
]
INT_VARIANTS = [
    ("missing", None), ("zero", "0"), ("negative", "-3"), ("nan", "nan"), ("inf", "inf"),
    ("huge", "99999999999999999999"), ("huge", "1e400"), ("wrong-type", "1.5"),
    ("wrong-type", "abc"), ("wrong-type", "7x"),
]
WORD_VARIANTS = [("missing", None), ("unknown-value", "bogus"), ("wrong-type", "1")]
OUTFILE_VARIANTS = [("missing", None), ("file-unwritable", "/nonexistent/dir/out.dat"),
                    ("file-unwritable", ".")]
INFILE_VARIANTS = [("missing", None), ("file-missing", "no_such_file.table"),
                   ("file-missing", ".")]
KEY_VARIANTS = [("missing", None), ("file-missing", "NOPE")]


def slug(v):
    if v is None:
        return "none"
    s = re.sub(r"[^A-Za-z0-9.+-]+", "_", v).strip("_")
    return s or "x"


def mutate_cmd(cmd, skip=()):
    """Yield (id_suffix, cls, line, kw_re) for one mutation of every value
    of cmd (each value once; `skip` holds (group, name) pairs done in another
    configuration of the same command)."""
    # positional values
    pos_names = "|".join(re.escape(p.name) for p in cmd.pos)
    for i, p in enumerate(cmd.pos):
        if ("", p.name) in skip:
            continue
        for cls, val in variants_of(p):
            pos = [q.value for q in cmd.pos]
            pos[i] = val
            line = tok_render(cmd.head, pos, [(k, [it.value if isinstance(it, P) else it
                                                   for it in items]) for k, items in cmd.groups])
            kw = (rf"\b({pos_names})\b" if cls == "missing" else rf"\b{re.escape(p.name)}\b")
            yield f"{p.name}.{cls}.{slug(val)}", cls, line, kw, p, val
    # keyword values
    for gi, (gkw, items) in enumerate(cmd.groups):
        for ii, it in enumerate(items):
            if not isinstance(it, P) or (gkw, it.name) in skip:
                continue
            for cls, val in variants_of(it):
                movable = gi >= cmd.pinned
                for last in ((False, True) if cls == "missing" and movable else (False,)):
                    groups = []
                    for gj, (k, its) in enumerate(cmd.groups):
                        vals = [x.value if isinstance(x, P) else x for x in its]
                        if gj == gi:
                            vals[ii] = val
                        groups.append((k, vals))
                    if last:
                        if gi == len(groups) - 1:
                            continue
                        groups.append(groups.pop(gi))
                    pos = [q.value for q in cmd.pos]
                    line = tok_render(cmd.head, pos, groups)
                    suffix = ".last" if last else ""
                    yield (f"{gkw}.{it.name}.{cls}.{slug(val)}{suffix}", cls, line,
                           rf"\b{re.escape(gkw)}\b", it, val)


def variants_of(p):
    table = {"real": REAL_VARIANTS, "int": INT_VARIANTS, "word": WORD_VARIANTS,
             "outfile": OUTFILE_VARIANTS, "infile": INFILE_VARIANTS, "key": KEY_VARIANTS}
    out = []
    for cls, val in table.get(p.kind, [("missing", None)]):
        if cls == "missing" and p.nomissing:
            continue
        if p.kind == "real" and cls == "negative" and p.value.startswith("-"):
            val = "-" + str(abs(float(p.value)) * 10)
        out.append((cls, val))
    if p.kind == "real":
        for val, _ in p.extreme:
            out.append(("extreme", val))
    if p.kind == "word" and p.name == "dir":
        out.append(("unknown-value", "X"))
    return out


def mutation_expect(cmd, cls, kw_re, p, val):
    """Expectation and class for one mutation (valid mutations become
    valid-edge controls)."""
    if cls in p.valid:
        return "valid-edge", Expect("ok")
    if cls == "extreme":
        kind = dict(p.extreme).get(val, "robust")
        return "extreme", Expect(kind, cmd.cmd_re, kw_re)
    return cls, Expect("error", cmd.cmd_re, kw_re)


# ----------------------------------------------------------------------------
# base inputs.  {NAME} slots are filled with the commands' lines.

LAT2D = """units           lj
dimension       2
atom_style      atomic
boundary        p p p
lattice         sq 1.0
region          box block 0 10 0 10 -0.5 0.5
create_box      1 box
create_atoms    1 box
mass            1 1.0
"""

BASE_CONTACTS = LAT2D + """comm_modify     cutoff 0.5
neighbor        0.5 bin
neigh_modify    every 5 delay 0 check yes
{contacts}
fix_modify      c energy yes
fix             m all move linear 1.0 0.5 0.0 units box
timestep        0.05
thermo_style    custom step pe f_c f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8]
thermo_modify   norm no
thermo          5
run             30
"""

HEX2D = """units           lj
dimension       2
atom_style      atomic
boundary        p p p
lattice         hex 1.1547005383792515
region          box block 0 8 0 5 -0.5 0.5
create_box      2 box
create_atoms    1 box
mass            * 1.0
"""

BASE_INTERACT = HEX2D + """{pairstyle}
{paircoeff}
neighbor        0.5 bin
neigh_modify    every 1 delay 0 check yes
fix             c all eq/contacts 1.0 99 threshold uniform 0.75 1.25 avalanches aval.dat
{quasistatic}
thermo_style    custom step pe f_c[1] f_c[2] f_c[3] f_c[4] f_c[6] f_c[8] f_q f_q[2]
thermo_modify   norm no
thermo          5
run             30
"""

CHAIN = """units           lj
dimension       2
atom_style      atomic
atom_modify     map array
boundary        p p p
lattice         sq 1.0
region          box block 0 40 -2 2 -0.5 0.5
create_box      1 box
region          line block 0 40 -0.1 0.1 -0.5 0.5 units box
create_atoms    1 region line
mass            1 1.0
"""

BASE_SUBSTRATE = CHAIN + """pair_style      eq/elastic 1.5
pair_coeff      1 1 25.0 1.0
neighbor        1.0 bin
neigh_modify    every 1 delay 0 check yes
group           center id 20 21
{substrate}
{modkc}
{modvel}
fix_modify      sub energy yes
fix             bd all brownian 1.0 1 rng none gamma_t 100.0
timestep        0.1
thermo_style    custom step pe f_sub f_sub[1] f_sub[2] f_sub[3] f_sub[4] f_sub[5] f_sub[6] f_sub[7] f_sub[8] f_sub[9] f_sub[10]
thermo_modify   norm no
thermo          5
run             30
"""

BASE_EQME = """{eqme}
print           "FXMAX ${{eq_me_force_at_xmax}}"
"""

GOOD_THRESHOLD = "# thresholds\nGOOD\nN 4\n\n1 0.5 0.0\n2 0.8 2.0\n3 1.0 1.0\n4 1.3 0.0\n"
GOOD_KERNEL = ("# kernel\nKERN\nN 4\n\n1 1.0 0.06\n2 2.0 0.03\n3 3.0 0.02\n4 4.0 0.005\n\n"
               "ANISO\nN 3 aniso\n\n1 1.0 0.06 0.01\n2 2.0 0.03 0.004\n3 3.0 0.02 0.002\n")
GOOD_SUBSTRATE = "# substrate\nBLOCK\nN 3\n\n1 0.0 0.0\n2 0.5 1.0\n3 1.0 0.8\n"
GOOD_FILES = {"th.table": GOOD_THRESHOLD, "k.table": GOOD_KERNEL, "sub.table": GOOD_SUBSTRATE}

POS = ("zero", "negative")            # the valid set of a value that may be any finite number
ANY = ("zero", "negative")


def P_pos(name, value, **kw):
    return P(name, value, "real", **kw)


def contacts_cmd(threshold, reform, stiffness, extra, fid="c", group="all"):
    return Cmd("contacts", r"eq/contacts", ["fix", fid, group, "eq/contacts"],
               [P("kc", "1.0"), P("seed", "4711", "int")],
               [threshold, reform, stiffness] + extra)


def dist_groups(prefix=""):
    """The threshold/reform/stiffness configurations shared by fix
    eq/contacts and eq/me: four configurations that together hold every
    style and every value."""
    thr = [
        ("threshold", ["uniform", P("lo", "0.75", valid=("zero",)), P("hi", "1.25")]),
        ("threshold", ["gaussian", P("mean", "1.0"), P("sd", "0.2")]),
        ("threshold", ["realistic", P("xs", "1.0")]),
        ("threshold", ["table", P("file", "th.table", "infile"), P("key", "GOOD", "key")]),
    ]
    # |r| must stay below the largest threshold (1.25 / 1.3 / unbounded)
    big = (("1e300", "error"), ("1e-300", "robust"))
    ref = [
        ("reform", ["delta", P("x0", "0.0", valid=ANY, extreme=big)]),
        ("reform", ["uniform", P("lo", "0.02", valid=ANY, extreme=big), P("hi", "0.1", extreme=big)]),
        ("reform", ["gaussian", P("mean", "0.1", valid=ANY, extreme=big), P("sd", "0.05", extreme=big)]),
        ("reform", ["none"]),
    ]
    stf = [
        ("stiffness", ["uniform", P("lo", "0.5"), P("hi", "1.5")]),
        ("stiffness", ["gaussian", P("mean", "1.0"), P("sd", "0.1")]),
        ("stiffness", ["constant"]),
        ("stiffness", ["constant"]),
    ]
    return list(zip(thr, ref, stf))


def style_word(name, value, choices):
    return P(name, value, "word", choices=choices)


# ----------------------------------------------------------------------------
# the cases


class Builder:
    def __init__(self):
        self.cases = []
        self.ids = set()

    def add(self, cid, cls, text, expect, files=None, np=1, note=""):
        base = cid
        n = 2
        while cid in self.ids:
            cid = f"{base}~{n}"
            n += 1
        self.ids.add(cid)
        assert cls in MALFORMED_CLASSES + OTHER_CLASSES, cls
        self.cases.append(Case(cid, cls, text, expect, dict(files or {}), np, note))
        return cid


def fill(base, **cmds):
    return base.format(**cmds)


def gen_contacts(b):
    """fix eq/contacts: every value of every keyword (4 configurations)."""
    done = set()
    extras0 = [("dir", [style_word("dir", "x", ("x", "y", "z"))]),
               ("crossing", [style_word("crossing", "exact", ("exact", "step"))]),
               ("start", [style_word("start", "relaxed", ("relaxed", "reform"))]),
               ("reform_as", [style_word("reform_as", "force", ("force", "stretch"))]),
               ("avalanches", [P("file", "aval.dat", "outfile")])]
    extras1 = [("dir", ["y"]), ("crossing", ["step"]), ("start", ["reform"]),
               ("reform_as", ["stretch"])]
    # temperature, aging and delays: every value (configuration 2)
    extras2 = [("thermal", [P("T", "0.05", valid=("zero",)), P("eps_a", "1.0"),
                            P("omega", "1.0")]),
               ("barrier", [P("p", "2.0", valid=("zero",)), P("q", "0.25", valid=("zero",))]),
               ("aging", [style_word("aging", "log", ("none", "log", "exp")),
                          P("beta", "0.05", valid=("zero",)), P("tau_a", "1.0")]),
               ("delay", [style_word("delay", "exp", ("none", "fixed", "exp")),
                          P("tau", "0.1", valid=("zero",))]),
               ("rest", [P("t_w", "10.0", valid=("zero",))])]
    for k, (thr, ref, stf) in enumerate(dist_groups()):
        thr = (thr[0], [style_word("style", thr[1][0], ("uniform", "gaussian", "realistic", "table"))]
               + thr[1][1:]) if k == 0 else thr
        ref = (ref[0], [style_word("style", ref[1][0], ("delta", "uniform", "gaussian", "none"))]
               + ref[1][1:]) if k == 0 else ref
        stf = (stf[0], [style_word("style", stf[1][0], ("constant", "uniform", "gaussian"))]
               + stf[1][1:]) if k == 0 else stf
        extra = extras0 if k == 0 else (extras1 if k == 1 else (extras2 if k == 2 else []))
        cmd = contacts_cmd(thr, ref, stf, extra)
        files = dict(GOOD_FILES)
        b.add(f"contacts.control{k}", "control", fill(BASE_CONTACTS, contacts=cmd.line()),
              Expect("ok"), files)
        for suffix, cls, line, kw, p, val in mutate_cmd(cmd, done):
            ocls, exp = mutation_expect(cmd, cls, kw, p, val)
            sub = thr[1][0] if suffix.startswith("threshold") else (
                ref[1][0] if suffix.startswith("reform.") else (
                    stf[1][0] if suffix.startswith("stiffness") else ""))
            if isinstance(sub, P):
                sub = sub.value
            cid = f"contacts.{suffix}" if not sub else f"contacts.{suffix.split('.')[0]}-{sub}.{'.'.join(suffix.split('.')[1:])}"
            b.add(cid, ocls, fill(BASE_CONTACTS, contacts=line), exp, files)
        done |= {("", "kc"), ("", "seed")}
        # the style words were mutated in configuration 0; extras too
        done |= {(g, "style") for g in ("threshold", "reform", "stiffness")}
        done |= {(g, n) for g, n in [("dir", "dir"), ("crossing", "crossing"), ("start", "start"),
                                     ("reform_as", "reform_as"), ("avalanches", "file")]}
    # the compact rows (keyword peratom; per-atom output every 5 steps, the
    # thermo reads globals only): configuration 2 with peratom 5, and the
    # mutations of N (configuration 2 itself keeps the default rows)
    thr, ref, stf = list(dist_groups())[2]
    cmd = contacts_cmd(thr, ref, stf, extras2 + [("peratom", [P("N", "5", "int")])])
    b.add("contacts.control-peratom", "control", fill(BASE_CONTACTS, contacts=cmd.line()),
          Expect("ok"), dict(GOOD_FILES))
    for suffix, cls, line, kw, p, val in mutate_cmd(cmd, set()):
        if suffix.startswith("peratom."):
            ocls, exp = mutation_expect(cmd, cls, kw, p, val)
            b.add(f"contacts.{suffix}", ocls, fill(BASE_CONTACTS, contacts=line), exp, GOOD_FILES)
    # keywords: misspelled, unknown, threshold missing, a value left over
    good = "fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25"
    for bad in ("thresholds", "Threshold", "reforms", "stifness", "direction", "cross", "startup",
                "reform-as", "avalanche"):
        line = {"thresholds": "fix c all eq/contacts 1.0 4711 thresholds uniform 0.75 1.25",
                "Threshold": "fix c all eq/contacts 1.0 4711 Threshold uniform 0.75 1.25"}.get(
                    bad, f"{good} {bad} 1")
        b.add(f"contacts.unknown.{bad}", "unknown-keyword", fill(BASE_CONTACTS, contacts=line),
              Expect("error", "eq/contacts", rf"\b{re.escape(bad)}\b"), GOOD_FILES)
    b.add("contacts.unknown.trailing-value", "unknown-keyword",
          fill(BASE_CONTACTS, contacts=f"{good} dir x y"),
          Expect("error", "eq/contacts", r"\by\b|dir"))
    b.add("contacts.unknown.bare-style", "unknown-keyword",
          fill(BASE_CONTACTS, contacts="fix c all eq/contacts 1.0 4711 uniform 0.75 1.25"),
          Expect("error", "eq/contacts", r"uniform|threshold"))
    b.add("contacts.threshold.absent", "missing",
          fill(BASE_CONTACTS, contacts="fix c all eq/contacts 1.0 4711 reform delta 0.0"),
          Expect("error", "eq/contacts", r"\bthreshold\b"))
    b.add("contacts.args.none", "missing", fill(BASE_CONTACTS, contacts="fix c all eq/contacts"),
          Expect("error", "eq/contacts", r"\bkc\b"))
    b.add("contacts.args.kc-only", "missing", fill(BASE_CONTACTS, contacts="fix c all eq/contacts 1.0"),
          Expect("error", "eq/contacts", r"\bseed\b"))
    b.add("contacts.kc.nan.variable", "nan",
          "variable k string -nan\n" + fill(BASE_CONTACTS, contacts=(
              "fix c all eq/contacts ${k} 4711 threshold uniform 0.75 1.25")),
          Expect("error", "eq/contacts", r"\bkc\b"))
    b.add("contacts.kc.wrong-type.v_ref", "wrong-type",
          "variable k equal 1.0\n" + fill(BASE_CONTACTS, contacts=(
              "fix c all eq/contacts v_k 4711 threshold uniform 0.75 1.25")),
          Expect("error", "eq/contacts", r"\bkc\b"))
    # conflicts between keywords, and values beyond another value's range
    for cid, line, kw, cls in [
        ("start-reform-none", f"{good} reform none start reform", r"\bstart\b|\breform\b", "conflict"),
        ("reform-delta-at-threshold", f"{good} reform delta 1.25", r"\breform\b", "out-of-range"),
        ("reform-delta-beyond-negative", f"{good} reform delta -1.3", r"\breform\b", "out-of-range"),
        ("reform-uniform-beyond", f"{good} reform uniform 0.5 1.3", r"\breform\b", "out-of-range"),
        ("reform-gaussian-wide", f"{good} reform gaussian 0.2 0.3", r"\breform\b", "out-of-range"),
        ("reform-delta-table", "fix c all eq/contacts 1.0 4711 threshold table th.table GOOD reform delta 1.3",
         r"\breform\b", "out-of-range"),
        ("threshold-uniform-equal", "fix c all eq/contacts 1.0 4711 threshold uniform 1.0 1.0",
         r"\bthreshold\b", "out-of-range"),
        ("stiffness-uniform-equal", f"{good} stiffness uniform 1.0 1.0", r"\bstiffness\b", "out-of-range"),
        ("reform-uniform-equal", f"{good} reform uniform 0.1 0.1", r"\breform\b", "out-of-range"),
    ]:
        b.add(f"contacts.{cid}", cls, fill(BASE_CONTACTS, contacts=line),
              Expect("error", "eq/contacts", kw), GOOD_FILES)


def gen_eqme(b):
    """eq/me: every value of every keyword (4 configurations)."""
    done = set()
    for k, (thr, ref, stf) in enumerate(dist_groups()):
        if k == 0:
            thr = (thr[0], [style_word("style", "uniform", ())] + thr[1][1:])
            ref = (ref[0], [style_word("style", "delta", ())] + ref[1][1:])
            stf = (stf[0], [style_word("style", "uniform", ())] + stf[1][1:])
            extra = [("dir", [style_word("dir", "x", ())]),
                     ("xmax", [P("X", "2.0", extreme=(("1e300", "robust"),
                                                      ("1e-300", "robust")))]),
                     ("dx", [P("h", "0.01", extreme=(("1e300", "robust"),
                                                     ("1e-300", "robust")))]),
                     ("start", [style_word("start", "relaxed", ())]),
                     ("crossing", [style_word("crossing", "exact", ())]),
                     ("richardson", [style_word("richardson", "yes", ())]),
                     ("force", [P("file", "f.dat", "outfile")]),
                     ("steady", [P("file", "qs.dat", "outfile")]),
                     ("snapshot", [P("X", "1.0", valid=("zero",)), P("file", "q1.dat", "outfile")]),
                     ("summary", [P("file", "s.dat", "outfile")]),
                     ("substrate", [P("file", "me.table", "outfile"), "BLOCK",
                                    P("uc", "1.25")])]
        elif k == 1:
            extra = [("xmax", ["2.0"]), ("dx", ["0.01"]), ("crossing", ["step"]),
                     ("richardson", ["no"]), ("start", ["reform"])]
        else:
            extra = [("xmax", ["2.0"]), ("dx", ["0.01"])]
        cmd = Cmd("eqme", r"eq/me", ["eq/me"], [], [thr, ref, stf] + extra)
        b.add(f"eqme.control{k}", "control", fill(BASE_EQME, eqme=cmd.line()), Expect("ok"),
              GOOD_FILES)
        for suffix, cls, line, kw, p, val in mutate_cmd(cmd, done):
            ocls, exp = mutation_expect(cmd, cls, kw, p, val)
            g = suffix.split(".")[0]
            sub = {"threshold": thr, "reform": ref, "stiffness": stf}.get(g)
            if sub is not None:
                s0 = sub[1][0].value if isinstance(sub[1][0], P) else sub[1][0]
                cid = f"eqme.{g}-{s0}.{'.'.join(suffix.split('.')[1:])}"
            else:
                cid = f"eqme.{suffix}"
            b.add(cid, ocls, fill(BASE_EQME, eqme=line), exp, GOOD_FILES)
        for gkw, items in cmd.groups:
            for it in items:
                if isinstance(it, P) and gkw not in ("threshold", "reform", "stiffness"):
                    done.add((gkw, it.name))
        # the distribution values are mutated in every configuration (one style each)
        done |= {(g, "style") for g in ("threshold", "reform", "stiffness")}
    # the exact renewal solution (uniform thresholds with lo > 0, re-forming at 0)
    ex = Cmd("eqme", r"eq/me", ["eq/me"], [], [
        ("threshold", ["uniform", P("lo", "0.75"), P("hi", "1.25")]),
        ("xmax", ["2.0"]), ("dx", ["0.01"]), ("exact", [P("file", "ex.dat", "outfile")])])
    b.add("eqme.control-exact", "control", fill(BASE_EQME, eqme=ex.line()), Expect("ok"))
    for suffix, cls, line, kw, p, val in mutate_cmd(ex):
        if not suffix.startswith("exact"):
            continue
        ocls, exp = mutation_expect(ex, cls, kw, p, val)
        b.add(f"eqme.{suffix}", ocls, fill(BASE_EQME, eqme=line), exp)
    for cid, line in [("lo-tiny", "eq/me threshold uniform 1e-300 1.25 xmax 2 dx 0.01 exact ex.dat"),
                      ("hi-huge", "eq/me threshold uniform 0.75 1e300 xmax 2 dx 0.01 exact ex.dat"),
                      ("xmax-huge", "eq/me threshold uniform 0.75 1.25 xmax 1e300 dx 0.01 exact ex.dat")]:
        b.add(f"eqme.exact.{cid}", "extreme", fill(BASE_EQME, eqme=line),
              Expect("robust", "eq/me", r"\bexact\b|\bthreshold\b|\bxmax\b"))
    good = "eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01"
    for bad in ("thresholds", "dX", "Xmax", "steps", "snap", "richardsn", "substrates", "output"):
        b.add(f"eqme.unknown.{bad}", "unknown-keyword", fill(BASE_EQME, eqme=f"{good} {bad} 1"),
              Expect("error", "eq/me", rf"\b{re.escape(bad)}\b"))
    for cid, line, kw, cls in [
        ("threshold.absent", "eq/me xmax 2 dx 0.01", r"\bthreshold\b", "missing"),
        ("args.none", "eq/me", r"\bthreshold\b", "missing"),
        ("exact-gaussian", "eq/me threshold gaussian 1.0 0.2 xmax 2 dx 0.01 exact ex.dat", r"\bexact\b", "conflict"),
        ("exact-reform", f"{good} reform delta 0.1 exact ex.dat", r"\bexact\b", "conflict"),
        ("exact-start-reform", f"{good} reform uniform 0 0.1 start reform exact ex.dat", r"\bexact\b", "conflict"),
        ("exact-crossing-step", f"{good} crossing step exact ex.dat", r"\bexact\b", "conflict"),
        ("exact-lo-zero", "eq/me threshold uniform 0 1.25 xmax 2 dx 0.01 exact ex.dat", r"\bexact\b", "conflict"),
        ("richardson-step", f"{good} crossing step richardson yes", r"\brichardson\b", "conflict"),
        ("steady-reform-none", f"{good} reform none steady qs.dat", r"\bsteady\b", "conflict"),
        ("start-reform-none", f"{good} reform none start reform", r"\bstart\b|\breform\b", "conflict"),
        ("substrate-uc-beyond-xmax", f"{good} substrate me.table BLOCK 3.0", r"\bsubstrate\b", "out-of-range"),
        ("snapshot-beyond-xmax", f"{good} snapshot 5.0 q5.dat", r"\bsnapshot\b", "out-of-range"),
        ("snapshot-negative", f"{good} snapshot -1.0 q5.dat", r"\bsnapshot\b", "negative"),
        ("reform-delta-at-threshold", f"{good} reform delta 1.25", r"\breform\b", "out-of-range"),
        ("substrate-key-missing", f"{good} substrate me.table", r"\bsubstrate\b", "missing"),
        ("substrate-uc-missing-last", f"{good} substrate me.table BLOCK", r"\bsubstrate\b", "missing"),
        ("snapshot-file-missing-last", f"{good} snapshot 1.0", r"\bsnapshot\b", "missing"),
        ("threshold-table-reform-beyond", "eq/me threshold table th.table GOOD reform delta 1.3 xmax 2 dx 0.01",
         r"\breform\b", "out-of-range"),
    ]:
        b.add(f"eqme.{cid}", cls, fill(BASE_EQME, eqme=line), Expect("error", "eq/me", kw), GOOD_FILES)
    # "xmax, rounded to a multiple of dx": xmax 0.5 with dx 1 runs to X = 1
    b.add("eqme.dx-beyond-xmax", "valid-edge",
          fill(BASE_EQME, eqme="eq/me threshold uniform 0.75 1.25 xmax 0.5 dx 1.0"), Expect("ok"))
    b.add("eqme.kstar.nan.variable", "nan",
          "variable x string -nan\n" + fill(BASE_EQME, eqme=(
              "eq/me threshold uniform 0.75 1.25 xmax ${x} dx 0.01")),
          Expect("error", "eq/me", r"\bxmax\b"))
    b.add("eqme.variable-not-internal", "conflict",
          "variable eq_me_kstar equal 1.0\n" + fill(BASE_EQME, eqme=good),
          Expect("error", "eq/me", r"eq_me_kstar"))
    # eq/me needs no box: a valid control before any box exists
    b.add("eqme.before-box", "control", "units lj\n" + fill(BASE_EQME, eqme=good), Expect("ok"))


def gen_interact(b):
    """pair_style eq/elastic, pair_coeff, fix eq/quasistatic."""
    ps = Cmd("pairstyle", r"eq/elastic", ["pair_style", "eq/elastic"],
             [P("rcut", "3.0", extreme=(("1e300", "robust"), ("1e-300", "robust")))], [])
    pc = Cmd("paircoeff", r"eq/elastic|pair_coeff|pair coeff", ["pair_coeff", "*", "*"],
             [P("ftilde", "0.06", valid=("zero",), nomissing=True),
              P("lambda_c", "3.0", nomissing=True),
              P("rcut", "3.0", nomissing=True)], [])
    pct = Cmd("paircoeff", r"eq/elastic|pair_coeff|pair coeff", ["pair_coeff", "*", "*"], [],
              [("table", [P("file", "k.table", "infile", nomissing=True),
                          P("key", "KERN", "key", nomissing=True),
                          P("rcut", "3.0", nomissing=True)])])
    qs = Cmd("quasistatic", r"eq/quasistatic", ["fix", "q", "all", "eq/quasistatic"],
             [P("contacts-ID", "c", "fixid", nomissing=True)],
             [("max", [P("dX", "0.02")])])
    base = dict(pairstyle=ps.line(), paircoeff=pc.line(), quasistatic=qs.line())
    b.add("interact.control", "control", fill(BASE_INTERACT, **base), Expect("ok"), GOOD_FILES)
    b.add("interact.control-table", "control",
          fill(BASE_INTERACT, **dict(base, paircoeff=pct.line())), Expect("ok"), GOOD_FILES)
    b.add("interact.control-aniso", "control",
          fill(BASE_INTERACT, **dict(base, paircoeff="pair_coeff * * table k.table ANISO")),
          Expect("ok"), GOOD_FILES)
    b.add("interact.control-np2", "control", fill(BASE_INTERACT, **base), Expect("ok"), GOOD_FILES, np=2)
    for name, cmd in (("pairstyle", ps), ("paircoeff", pc), ("paircoeff-table", pct), ("quasistatic", qs)):
        for suffix, cls, line, kw, p, val in mutate_cmd(cmd):
            ocls, exp = mutation_expect(cmd, cls, kw, p, val)
            if name == "paircoeff-table" and p.name == "rcut":
                kw = r"\brcut\b"
                exp = dataclasses.replace(exp, kw=kw) if exp.kind != "ok" else exp
            slot = name.split("-")[0]
            b.add(f"{name}.{suffix}", ocls, fill(BASE_INTERACT, **dict(base, **{slot: line})), exp,
                  GOOD_FILES)
    # positional values that may not be dropped one by one (rcut is optional)
    for cid, line, kw in [
        ("paircoeff.lambda_c.missing", "pair_coeff * * 0.06", r"lambda_c"),
        ("paircoeff.ftilde.missing", "pair_coeff * *", r"ftilde"),
        ("paircoeff.table.key.missing", "pair_coeff * * table k.table", r"\btable\b|keyword|key"),
        ("paircoeff.table.file.missing", "pair_coeff * * table", r"\btable\b|file"),
        ("paircoeff.too-many", "pair_coeff * * 0.06 3.0 3.0 4.0", r"values|args|rcut"),
        ("paircoeff.table-too-many", "pair_coeff * * table k.table KERN 3.0 4.0", r"values|args|rcut"),
    ]:
        b.add(cid, "missing" if "missing" in cid else "unknown-keyword",
              fill(BASE_INTERACT, **dict(base, paircoeff=line)),
              Expect("error", r"eq/elastic|pair_coeff|pair coeff", kw), GOOD_FILES)
    b.add("paircoeff.table.rcut.valid-omitted", "valid-edge",
          fill(BASE_INTERACT, **dict(base, paircoeff="pair_coeff * * table k.table KERN")),
          Expect("ok"), GOOD_FILES)
    b.add("paircoeff.rcut.valid-omitted", "valid-edge",
          fill(BASE_INTERACT, **dict(base, paircoeff="pair_coeff * * 0.06 3.0")), Expect("ok"))
    for cid, line, kw in [
        ("pairstyle.args.none", "pair_style eq/elastic", r"rcut"),
        ("pairstyle.too-many", "pair_style eq/elastic 3.0 4.0", r"rcut|4\.0"),
    ]:
        b.add(cid, "missing" if "none" in cid else "unknown-keyword",
              fill(BASE_INTERACT, **dict(base, pairstyle=line)), Expect("error", "eq/elastic", kw))
    for bad in ("min", "Max", "maximum", "step"):
        b.add(f"quasistatic.unknown.{bad}", "unknown-keyword",
              fill(BASE_INTERACT, **dict(base, quasistatic=f"fix q all eq/quasistatic c {bad} 0.02")),
              Expect("error", "eq/quasistatic", rf"\b{bad}\b"))
    b.add("quasistatic.unknown.trailing", "unknown-keyword",
          fill(BASE_INTERACT, **dict(base, quasistatic="fix q all eq/quasistatic c max 0.02 0.03")),
          Expect("error", "eq/quasistatic", r"0\.03|\bmax\b"))
    b.add("quasistatic.args.none", "missing",
          fill(BASE_INTERACT, **dict(base, quasistatic="fix q all eq/quasistatic")),
          Expect("error", "eq/quasistatic", r"contacts-ID|contacts"))
    b.add("quasistatic.max.valid-omitted", "valid-edge",
          fill(BASE_INTERACT, **dict(base, quasistatic="fix q all eq/quasistatic c")), Expect("ok"))
    # the contacts-ID: absent fix, wrong style, a fix eq/substrate
    for cid, pre, qline, kw in [
        ("nothere", "", "fix q all eq/quasistatic nothere", r"nothere"),
        ("fix-move", "fix mv all nve/noforce\n", "fix q all eq/quasistatic mv", r"\bmv\b|eq/contacts"),
        ("fix-substrate", "fix s all eq/substrate 1.0 sawtooth 1.0\n", "fix q all eq/quasistatic s",
         r"\bs\b|eq/contacts"),  # (pair zero: pair eq/elastic would refuse both fixes first)
        ("group-id", "", "fix q all eq/quasistatic all", r"\ball\b|eq/contacts"),
    ]:
        pair = (dict(pairstyle="pair_style zero 3.0", paircoeff="pair_coeff * *")
                if cid == "fix-substrate" else {})
        b.add(f"quasistatic.contacts-ID.{cid}", "wrong-id",
              fill(BASE_INTERACT, **dict(base, quasistatic=pre + qline, **pair)),
              Expect("error", "eq/quasistatic", kw))


def gen_substrate(b):
    """fix eq/substrate and its fix_modify keywords kc and velocity."""
    done = set()
    confs = [
        ("sawtooth", [P("uc", "1.0")], [
            ("dir", [style_word("dir", "x", ())]),
            ("drive", [P("K", "0.07"), P("v", "1e-4", valid=ANY)]),
            ("stage", [P("X0", "12.0", valid=ANY)]),
            ("reverse", [style_word("reverse", "periodic", ())]),
            ("crossing", [style_word("crossing", "exact", ())]),
            ("disorder", ["gaussian", P("mean", "1.0"), P("sd", "0.02"), P("seed", "9", "int")])]),
        ("smooth", [P("uc", "1.0")], [
            ("drive", ["0.07", "1e-4"]), ("reverse", ["break"]), ("crossing", ["step"]),
            ("disorder", ["uniform", P("lo", "0.9"), P("hi", "1.1"), P("seed", "3", "int")])]),
        ("table", [P("file", "sub.table", "infile"), P("key", "BLOCK", "key")], [
            ("drive", ["0.07", "1e-4"]),
            ("disorder", ["constant", P("seed", "5", "int")])]),
        # thermal hops: every value of thermal, barrier and seed
        ("sawtooth", [P("uc", "1.0")], [
            ("drive", ["0.07", "1e-4"]), ("reverse", ["break"]),
            ("thermal", [P("T", "0.05", valid=("zero",)), P("eps_a", "1.0"), P("omega", "1.0")]),
            ("barrier", [P("p", "2.0", valid=("zero",)), P("q", "0.25", valid=("zero",))]),
            ("seed", [P("S", "7", "int")])]),
        # velocity strengthening: A >= 0 (0 is the keyword off), v0 > 0
        # (A/(2 v0) = 5 < gamma_t 100 of the base: the lagged term is stable)
        ("sawtooth", [P("uc", "1.0")], [
            ("drive", ["0.07", "1e-4"]),
            ("rate", [P("A", "0.01", valid=("zero",)), P("v0", "1e-3")])]),
    ]
    kc_cmd = Cmd("modkc", r"fix_modify", ["fix_modify", "sub"], [],
                 [("kc", [P("group", "center", "group", nomissing=True), P("value", "0.5", valid=("zero",))])])
    vel_cmd = Cmd("modvel", r"fix_modify", ["fix_modify", "sub"], [],
                  [("velocity", [P("v", "-2e-4", valid=ANY)])])
    for k, (shape, sargs, extra) in enumerate(confs):
        pos = [P("kc", "1.0", valid=("zero",))] if k == 0 else [P("kc", "1.0")]
        cmd = Cmd("substrate", r"eq/substrate", ["fix", "sub", "all", "eq/substrate"], pos,
                  [(shape, sargs)] + extra, pinned=1)
        base = dict(substrate=cmd.line(), modkc=kc_cmd.line(), modvel=vel_cmd.line())
        b.add(f"substrate.control{k}", "control", fill(BASE_SUBSTRATE, **base), Expect("ok"),
              GOOD_FILES)
        for suffix, cls, line, kw, p, val in mutate_cmd(cmd, done):
            ocls, exp = mutation_expect(cmd, cls, kw, p, val)
            if suffix.startswith("disorder"):
                s0 = dict(extra)["disorder"][0]
                suffix = f"disorder-{s0}.{'.'.join(suffix.split('.')[1:])}"
            b.add(f"substrate.{suffix}", ocls, fill(BASE_SUBSTRATE, **dict(base, substrate=line)),
                  exp, GOOD_FILES)
        done |= {("", "kc")}
        for gkw, items in cmd.groups:
            for it in items:
                if isinstance(it, P) and gkw != "disorder":
                    done.add((gkw, it.name))
        if k == 0:
            for name, mc in (("modkc", kc_cmd), ("modvel", vel_cmd)):
                for suffix, cls, line, kw, p, val in mutate_cmd(mc):
                    ocls, exp = mutation_expect(mc, cls, kw, p, val)
                    b.add(f"fix_modify.{suffix}", ocls,
                          fill(BASE_SUBSTRATE, **dict(base, **{name: line})), exp, GOOD_FILES)
    base = dict(substrate="fix sub all eq/substrate 1.0 sawtooth 1.0 drive 0.07 1e-4",
                modkc=kc_cmd.line(), modvel=vel_cmd.line())
    good = base["substrate"]
    for bad in ("speed", "Dir", "drives", "stage0", "reversed", "crossings", "disorders", "period"):
        b.add(f"substrate.unknown.{bad}", "unknown-keyword",
              fill(BASE_SUBSTRATE, **dict(base, substrate=f"{good} {bad} 1")),
              Expect("error", "eq/substrate", rf"\b{re.escape(bad)}\b"))
    for cid, line, kw, cls in [
        ("shape.absent", "fix sub all eq/substrate 1.0 drive 0.07 1e-4", r"shape|sawtooth|\bdrive\b", "missing"),
        ("shape.unknown", "fix sub all eq/substrate 1.0 sine 1.0", r"shape|\bsine\b", "unknown-value"),
        ("shape.number", "fix sub all eq/substrate 1.0 1.0 1.0", r"shape|sawtooth", "wrong-type"),
        ("args.none", "fix sub all eq/substrate", r"\bkc\b|shape", "missing"),
        ("args.kc-only", "fix sub all eq/substrate 1.0", r"shape|sawtooth", "missing"),
        ("sawtooth.uc.missing-last", "fix sub all eq/substrate 1.0 sawtooth", r"sawtooth|\buc\b", "missing"),
        ("smooth.uc.missing-last", "fix sub all eq/substrate 1.0 smooth", r"smooth|\buc\b", "missing"),
        ("table.key.missing-last", "fix sub all eq/substrate 1.0 table sub.table", r"\btable\b", "missing"),
        ("stage.no-drive", "fix sub all eq/substrate 1.0 sawtooth 1.0 stage 3.0", r"\bstage\b|\bdrive\b", "conflict"),
        ("drive.v.missing-last", "fix sub all eq/substrate 1.0 sawtooth 1.0 drive 0.07", r"\bdrive\b", "missing"),
        ("disorder.seed.missing-last", "fix sub all eq/substrate 1.0 sawtooth 1.0 disorder gaussian 1.0 0.02",
         r"\bdisorder\b", "missing"),
        ("disorder.style.unknown", f"{good} disorder weibull 1 2 5", r"\bdisorder\b", "unknown-value"),
        ("disorder.style.missing-last", f"{good} disorder", r"\bdisorder\b", "missing"),
        ("disorder-uniform.equal", f"{good} disorder uniform 1.0 1.0 5", r"\bdisorder\b", "out-of-range"),
        ("disorder-uniform.lo.zero", f"{good} disorder uniform 0 1.1 5", r"\bdisorder\b", "zero"),
        ("disorder.constant.seed.missing-last", f"{good} disorder constant", r"\bdisorder\b", "missing"),
        ("dir.missing-last", f"{good} dir", r"\bdir\b", "missing"),
        ("reverse.missing-last", f"{good} reverse", r"\breverse\b", "missing"),
        ("crossing.missing-last", f"{good} crossing", r"\bcrossing\b", "missing"),
    ]:
        b.add(f"substrate.{cid}", cls, fill(BASE_SUBSTRATE, **dict(base, substrate=line)),
              Expect("error", "eq/substrate", kw), GOOD_FILES)
    b.add("substrate.kc.nan.variable", "nan",
          "variable k string -nan\n" + fill(BASE_SUBSTRATE, **dict(
              base, substrate="fix sub all eq/substrate ${k} sawtooth 1.0 drive 0.07 1e-4")),
          Expect("error", "eq/substrate", r"\bkc\b"))
    # fix_modify: keywords and values
    for cid, line, kw, cls in [
        ("unknown.speed", "fix_modify sub speed 1e-4", r"\bspeed\b", "unknown-keyword"),
        ("unknown.Kc", "fix_modify sub Kc center 0.5", r"\bKc\b", "unknown-keyword"),
        ("kc.args.none", "fix_modify sub kc", r"\bkc\b", "missing"),
        ("kc.value.missing", "fix_modify sub kc center", r"\bkc\b", "missing"),
        ("kc.group.nogroup", "fix_modify sub kc nogroup 0.5", r"\bkc\b|nogroup", "wrong-group"),
        ("velocity.args.none", "fix_modify sub velocity", r"\bvelocity\b", "missing"),
        ("kc.on-contacts", "fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25\nfix_modify c kc all 0.5",
         r"\bkc\b", "conflict"),
        ("velocity.on-contacts",
         "fix c all eq/contacts 1.0 5 threshold uniform 0.75 1.25\nfix_modify c velocity 1e-4",
         r"\bvelocity\b", "conflict"),
    ]:
        b.add(f"fix_modify.{cid}", cls, fill(BASE_SUBSTRATE, **dict(base, modkc=line)),
              Expect("error", r"fix_modify|eq/contacts|eq/substrate", kw), GOOD_FILES)
    b.add("fix_modify.velocity.no-drive", "conflict",
          fill(BASE_SUBSTRATE, **dict(base, substrate="fix sub all eq/substrate 1.0 sawtooth 1.0")),
          Expect("error", r"fix_modify", r"\bvelocity\b|\bdrive\b"), GOOD_FILES)
    b.add("fix_modify.kc.group-empty", "valid-edge",
          fill(BASE_SUBSTRATE, **dict(base, modkc="group nobody empty\nfix_modify sub kc nobody 0.5")),
          Expect("ok"))
    b.add("substrate.control-np2", "control", fill(BASE_SUBSTRATE, **base), Expect("ok"), np=2)


BASE_MESO = LAT2D.replace("0 10 0 10", "0 6 0 4") + """neighbor        0.5 bin
comm_modify     cutoff 2.0
{meso}
velocity        all set 0.01 0.0 0.0 units box
fix             mv all nve/noforce
timestep        1.0
thermo_style    custom step f_m f_m[1] f_m[2] f_m[3] f_m[4]
thermo_modify   norm no
thermo          5
run             30
"""


def gen_meso(b):
    """fix eq/meso: every value of every keyword (4 configurations of the
    distributions, as fix eq/contacts), the screening and its Pi0 >= 1."""
    done = set()
    big = (("1e300", "robust"), ("1e-300", "robust"))
    extras0 = [("grid", [P("du", "0.01", extreme=big)]),
               ("dir", [style_word("dir", "x", ("x", "y", "z"))]),
               ("crossing", [style_word("crossing", "exact", ("exact", "step"))]),
               ("start", [style_word("start", "relaxed", ("relaxed", "reform"))]),
               ("drive", [P("K", "0.5", extreme=big), P("v", "0.01", valid=ANY, extreme=big)]),
               ("stage", [P("X0", "0.5", valid=ANY, extreme=big)]),
               ("screen", [P("kappa", "0.001", valid=("zero",), extreme=big), P("lambda_c", "1.0", extreme=big),
                           P("rcut", "1.5", extreme=big)]),
               ("window", [P("w", "0.02", extreme=big)]),
               ("check", [P("N", "10", "int", valid=("zero",))])]
    extras1 = [("dir", ["y"]), ("crossing", ["step"]), ("start", ["reform"])]
    for k, (thr, ref, _stf) in enumerate(dist_groups()):
        thr = (thr[0], [style_word("style", thr[1][0], ("uniform", "gaussian", "realistic", "table"))]
               + thr[1][1:]) if k == 0 else thr
        ref = (ref[0], [style_word("style", ref[1][0], ("delta", "uniform", "gaussian", "none"))]
               + ref[1][1:]) if k == 0 else ref
        extra = extras0 if k == 0 else (extras1 if k == 1 else [])
        pos = [P("Nlambda", "100"), P("kc", "1.0")]
        cmd = Cmd("meso", r"eq/meso", ["fix", "m", "all", "eq/meso"], pos, [thr, ref] + extra)
        b.add(f"meso.control{k}", "control", fill(BASE_MESO, meso=cmd.line()), Expect("ok"), GOOD_FILES)
        for suffix, cls, line, kw, p, val in mutate_cmd(cmd, done):
            ocls, exp = mutation_expect(cmd, cls, kw, p, val)
            sub = thr[1][0] if suffix.startswith("threshold") else (
                ref[1][0] if suffix.startswith("reform.") else "")
            if isinstance(sub, P):
                sub = sub.value
            cid = f"meso.{suffix}" if not sub else f"meso.{suffix.split('.')[0]}-{sub}.{'.'.join(suffix.split('.')[1:])}"
            b.add(cid, ocls, fill(BASE_MESO, meso=line), exp, GOOD_FILES)
        done |= {("", "Nlambda"), ("", "kc")}
        done |= {(g, "style") for g in ("threshold", "reform")}
        done |= {(g, it.name) for g, its in extras0 for it in its if isinstance(it, P)}
    # temperature, the formation delay and aging: every value of the thermal
    # kernel's keywords (the distributions are fixed: the kernel takes
    # uniform thresholds re-forming at 0 here)
    thermal = [("threshold", ["uniform", "0.75", "1.25"]), ("grid", ["0.02"]),
               ("thermal", [P("T", "0.05"), P("eps_a", "1.0"), P("omega", "1.0")]),
               ("barrier", [P("p", "2.0", valid=("zero",)), P("q", "0.25", valid=("zero",))]),
               ("labels", [P("n", "8", "int")]),
               ("delay", [style_word("delay", "exp", ("none", "fixed", "exp")),
                          P("tau", "5.0", valid=("zero",))]),
               ("aging", [style_word("aging", "log", ("none", "log", "exp")),
                          P("beta", "0.05", valid=("zero",)), P("tau_a", "1.0")]),
               ("rest", [P("t_w", "10.0", valid=("zero",))])]
    cmd = Cmd("meso", r"eq/meso", ["fix", "m", "all", "eq/meso"], [P("Nlambda", "100"), P("kc", "1.0")],
              thermal)
    b.add("meso.control-thermal", "control", fill(BASE_MESO, meso=cmd.line()), Expect("ok"), GOOD_FILES)
    for suffix, cls, line, kw, p, val in mutate_cmd(cmd, done):
        ocls, exp = mutation_expect(cmd, cls, kw, p, val)
        b.add(f"meso.thermal-{suffix}", ocls, fill(BASE_MESO, meso=line), exp, GOOD_FILES)
    # at T = 0 aging and a delay take the same kernel at theta = 0: every
    # value of their keywords (one mutation leaves the other one on)
    cold = [kv for kv in thermal if kv[0] not in ("thermal", "barrier")]
    cmd = Cmd("meso", r"eq/meso", ["fix", "m", "all", "eq/meso"], [P("Nlambda", "100"), P("kc", "1.0")],
              cold)
    b.add("meso.control-cold-kernel", "control", fill(BASE_MESO, meso=cmd.line()), Expect("ok"),
          GOOD_FILES)
    for suffix, cls, line, kw, p, val in mutate_cmd(cmd, done):
        ocls, exp = mutation_expect(cmd, cls, kw, p, val)
        b.add(f"meso.cold-{suffix}", ocls, fill(BASE_MESO, meso=line), exp, GOOD_FILES)
    good = "fix m all eq/meso 100 1.0 threshold uniform 0.75 1.25"
    for bad in ("thresholds", "grids", "screening", "windows", "checks", "drives", "avalanches",
                "stiffness"):
        b.add(f"meso.unknown.{bad}", "unknown-keyword", fill(BASE_MESO, meso=f"{good} {bad} 1"),
              Expect("error", "eq/meso", rf"\b{re.escape(bad)}\b"))
    for cid, line, kw, cls in [
        ("threshold.absent", "fix m all eq/meso 100 1.0 reform delta 0.0", r"\bthreshold\b", "missing"),
        ("args.none", "fix m all eq/meso", r"Nlambda", "missing"),
        ("args.nlambda-only", "fix m all eq/meso 100", r"\bkc\b|Nlambda", "missing"),
        ("stage.no-drive", f"{good} stage 1.0", r"\bstage\b|\bdrive\b", "conflict"),
        ("dir.z-2d", f"{good} dir z", r"\bdir\b", "dimension"),
        ("grid.coarse", f"{good} grid 0.3", r"\bgrid\b", "out-of-range"),
        ("screen.pi0-above-one", f"{good} screen 0.5 1.0 1.5", r"\bscreen\b|Pi0", "out-of-range"),
        ("screen.rcut-beyond-ghosts", f"{good} screen 0.001 1.0 5.0", r"\bscreen\b|rcut", "out-of-range"),
        ("reform-delta-at-threshold", f"{good} reform delta 1.25", r"\breform\b", "out-of-range"),
        ("threshold-uniform-equal", "fix m all eq/meso 100 1.0 threshold uniform 1.0 1.0",
         r"\bthreshold\b", "out-of-range"),
        ("check.float", f"{good} check 2.5", r"\bcheck\b", "wrong-type"),
    ]:
        b.add(f"meso.{cid}", cls, fill(BASE_MESO, meso=line), Expect("error", "eq/meso", kw), GOOD_FILES)
    b.add("meso.group-empty", "wrong-group",
          fill(BASE_MESO, meso="group nobody empty\nfix m nobody eq/meso 100 1.0 threshold uniform 0.75 1.25"),
          Expect("error", "eq/meso", r"\bgroup\b|no atoms"))
    b.add("meso.fix_modify.unknown", "unknown-keyword",
          fill(BASE_MESO, meso=f"{good}\nfix_modify m speed 1.0"),
          Expect("error", r"fix_modify|eq/meso", r"\bspeed\b"))
    b.add("meso.control-np2", "control", fill(BASE_MESO, meso=f"{good} screen 0.001 1.0 1.5"),
          Expect("ok"), np=2)


# ----------------------------------------------------------------------------
# table files: missing, empty, garbled, non-monotonic, NaN, out of range


def junk_bytes(n=600, seed=11):
    rnd = random.Random(seed)
    return bytes(rnd.randrange(256) for _ in range(n))


def table_variants(kind):
    """(variant id, class, file content or None (no file), file name, key)
    for one table consumer.  kind: threshold, kernel, substrate."""
    if kind == "threshold":
        head, cols, good = "GOOD", 3, GOOD_THRESHOLD
        pts = [("0.5", "0.0"), ("0.8", "2.0"), ("1.0", "1.0"), ("1.3", "0.0")]
    elif kind == "kernel":
        head, cols, good = "KERN", 3, GOOD_KERNEL
        pts = [("1.0", "0.06"), ("2.0", "0.03"), ("3.0", "0.02"), ("4.0", "0.005")]
    else:
        head, cols, good = "BLOCK", 3, GOOD_SUBSTRATE
        pts = [("0.0", "0.0"), ("0.5", "1.0"), ("1.0", "0.8"), ("1.5", "0.5")]

    def sec(points, n=None, key="BAD", flag=""):
        n = len(points) if n is None else n
        lines = [f"{i + 1} {' '.join(p)}" for i, p in enumerate(points)]
        return f"# fuzzed table\n{key}\nN {n}{flag}\n\n" + "\n".join(lines) + "\n"

    def rep(i, j, v):
        q = [list(p) for p in pts]
        q[i][j] = v
        return [tuple(x) for x in q]

    out = [
        ("no-file", "file-missing", None, "no_such_file.table", head),
        ("directory", "file-missing", None, ".", head),
        ("no-section", "file-missing", good, "t.table", "NOPE"),
        ("key-case", "file-missing", good, "t.table", head.lower()),
        ("empty", "file-empty", "", "t.table", "BAD"),
        ("comments-only", "file-empty", "# nothing here\n# at all\n", "t.table", "BAD"),
        ("key-only", "file-empty", "# t\nBAD\n", "t.table", "BAD"),
        ("n-zero", "file-empty", "# t\nBAD\nN 0\n\n", "t.table", "BAD"),
        ("no-points", "file-empty", "# t\nBAD\nN 4\n\n", "t.table", "BAD"),
        ("binary", "file-garbled", junk_bytes(), "t.table", "BAD"),
        ("binary-after-key", "file-garbled", b"BAD\nN 4\n\n" + junk_bytes(200, 5), "t.table", "BAD"),
        ("no-n-line", "file-garbled", "# t\nBAD\n\n" + "\n".join(
            f"{i + 1} {' '.join(p)}" for i, p in enumerate(pts)) + "\n", "t.table", "BAD"),
        ("n-word", "file-garbled", sec(pts, "abc"), "t.table", "BAD"),
        ("n-negative", "file-garbled", sec(pts, "-2"), "t.table", "BAD"),
        ("n-real", "file-garbled", sec(pts, "2.5"), "t.table", "BAD"),
        ("n-huge", "file-garbled", sec(pts, "999999999999"), "t.table", "BAD"),
        ("n-too-big", "file-garbled", sec(pts, 6), "t.table", "BAD"),
        ("n-too-small", "file-garbled", sec(pts, 3), "t.table", "BAD"),
        ("letters", "file-garbled", sec(rep(1, 1, "two")), "t.table", "BAD"),
        ("comma-decimal", "file-garbled", sec(rep(1, 0, "0,8" if kind != "kernel" else "2,0")),
         "t.table", "BAD"),
        ("missing-column", "file-garbled", sec(pts[:1] + [(pts[1][0],)] + pts[2:]), "t.table", "BAD"),
        ("extra-column", "file-garbled", sec(pts[:1] + [pts[1] + ("7.0", "8.0")] + pts[2:]),
         "t.table", "BAD"),
        ("bad-flag", "file-garbled", sec(pts, flag=" iso"), "t.table", "BAD"),
        ("nonmonotonic", "file-nonmonotonic", sec([pts[0], pts[2], pts[1], pts[3]]), "t.table", "BAD"),
        ("duplicate-x", "file-nonmonotonic", sec(rep(2, 0, pts[1][0])), "t.table", "BAD"),
        ("reversed", "file-nonmonotonic", sec(list(reversed(pts))), "t.table", "BAD"),
        ("nan-x", "file-nan", sec(rep(2, 0, "nan")), "t.table", "BAD"),
        ("nan-y", "file-nan", sec(rep(1, 1, "nan")), "t.table", "BAD"),
        ("inf-y", "file-nan", sec(rep(1, 1, "inf")), "t.table", "BAD"),
        ("huge-y", "file-nan", sec(rep(1, 1, "1e400")), "t.table", "BAD"),
        ("inf-x-last", "file-nan", sec(rep(3, 0, "inf")), "t.table", "BAD"),
    ]
    if kind == "threshold":
        out += [
            ("negative-x", "file-range", sec(rep(0, 0, "-0.5")), "t.table", "BAD"),
            ("negative-density", "file-range", sec(rep(2, 1, "-1.0")), "t.table", "BAD"),
            ("zero-density", "file-range", sec([(p[0], "0.0") for p in pts]), "t.table", "BAD"),
            ("single-point", "file-range", sec([("0.8", "1.0")]), "t.table", "BAD"),
            ("huge-density", "extreme", sec(rep(1, 1, "1e300")), "t.table", "BAD"),
        ]
    elif kind == "kernel":
        out += [
            ("zero-r", "file-range", sec(rep(0, 0, "0.0")), "t.table", "BAD"),
            ("negative-r", "file-range", sec(rep(0, 0, "-1.0")), "t.table", "BAD"),
            ("aniso-3-columns", "file-garbled", sec(pts, flag=" aniso"), "t.table", "BAD"),
            ("aniso-nan-k2", "file-nan", sec([p + ("0.01",) for p in pts[:2]] + [pts[2] + ("nan",)]
                                             + [pts[3] + ("0.0",)], flag=" aniso"), "t.table", "BAD"),
            ("huge-k", "extreme", sec(rep(1, 1, "1e300")), "t.table", "BAD"),
        ]
    else:
        out += [
            ("first-u-nonzero", "file-range", sec(rep(0, 0, "0.1")), "t.table", "BAD"),
            ("negative-u", "file-range", sec(rep(0, 0, "-0.5")), "t.table", "BAD"),
            ("single-point", "file-range", sec([("0.0", "0.0")]), "t.table", "BAD"),
            ("huge-phi", "extreme", sec(rep(1, 1, "1e300")), "t.table", "BAD"),
        ]
    return out


def gen_tables(b):
    consumers = [
        ("contacts", "threshold", "eq/contacts", r"\bthreshold\b|\btable\b",
         lambda f, k: fill(BASE_CONTACTS, contacts=f"fix c all eq/contacts 1.0 4711 threshold table {f} {k}")),
        ("eqme", "threshold", "eq/me", r"\bthreshold\b|\btable\b",
         lambda f, k: fill(BASE_EQME, eqme=f"eq/me threshold table {f} {k} xmax 2 dx 0.01")),
        ("paircoeff", "kernel", r"eq/elastic|pair_coeff|pair coeff", r"\btable\b",
         lambda f, k: fill(BASE_INTERACT, pairstyle="pair_style eq/elastic 3.0",
                           paircoeff=f"pair_coeff * * table {f} {k}",
                           quasistatic="fix q all eq/quasistatic c max 0.02")),
        ("substrate", "substrate", "eq/substrate", r"\btable\b",
         lambda f, k: fill(BASE_SUBSTRATE, substrate=f"fix sub all eq/substrate 1.0 table {f} {k} drive 0.07 1e-4",
                           modkc="fix_modify sub kc center 0.5", modvel="fix_modify sub velocity -2e-4")),
    ]
    # one variant of each class also on 2 MPI ranks (rank 0 reads, others wait)
    for name, kind, cmd_re, kw_re, make in consumers:
        seen = set()
        for vid, cls, content, fname, key in table_variants(kind):
            files = dict(GOOD_FILES)
            if content is not None:
                files[fname] = content
            exp = Expect("robust" if cls == "extreme" else "error", cmd_re, kw_re)
            b.add(f"{name}.table.{vid}", cls, make(fname, key), exp, files)
            if cls not in seen and cls != "extreme":
                seen.add(cls)
                b.add(f"{name}.table.{vid}.np2", cls, make(fname, key), exp, files, np=2)


# ----------------------------------------------------------------------------
# groups, order, atom style, dimension, pair coefficients, run-time checks


def gen_misc(b):
    c_good = "fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25"
    s_good = "fix sub all eq/substrate 1.0 sawtooth 1.0 drive 0.07 1e-4"
    sub_base = dict(substrate=s_good, modkc="fix_modify sub kc center 0.5", modvel="")
    ibase = dict(pairstyle="pair_style eq/elastic 3.0", paircoeff="pair_coeff * * 0.06 3.0",
                 quasistatic="fix q all eq/quasistatic c max 0.02")
    # wrong group
    dyn = "region left block 0 5 INF INF INF INF\ngroup moving dynamic all region left\n"
    for cid, pre, line, cmd_re, kw in [
        ("contacts.group.nonexistent", "", c_good.replace(" all ", " nogroup "), r"\bfix\b|eq/contacts", r"group"),
        ("contacts.group.empty", "group nobody empty\n", c_good.replace(" all ", " nobody "), "eq/contacts", r"group"),
        ("contacts.group.dynamic", dyn, c_good.replace(" all ", " moving "), "eq/contacts", r"group|dynamic"),
    ]:
        b.add(cid, "wrong-group", fill(BASE_CONTACTS, contacts=pre + line), Expect("error", cmd_re, kw))
    for cid, pre, line, cmd_re, kw in [
        ("substrate.group.nonexistent", "", s_good.replace(" all ", " nogroup "), r"\bfix\b|eq/substrate", r"group"),
        ("substrate.group.empty", "group nobody empty\n", s_good.replace(" all ", " nobody "), "eq/substrate", r"group"),
        ("substrate.group.dynamic", dyn, s_good.replace(" all ", " moving "), "eq/substrate", r"group|dynamic"),
    ]:
        b.add(cid, "wrong-group", fill(BASE_SUBSTRATE, **dict(sub_base, substrate=pre + line)),
              Expect("error", cmd_re, kw))
    for cid, line, cmd_re, kw in [
        ("quasistatic.group.nonexistent", "fix q nogroup eq/quasistatic c max 0.02", r"\bfix\b|eq/quasistatic", "group"),
        ("quasistatic.group.partial", "group half id <= 10\nfix q half eq/quasistatic c max 0.02", "eq/quasistatic", r"group"),
        ("quasistatic.group.empty", "group nobody empty\nfix q nobody eq/quasistatic c max 0.02", "eq/quasistatic", r"group"),
        ("quasistatic.group.dynamic", dyn + "fix q moving eq/quasistatic c max 0.02", "eq/quasistatic", r"group|dynamic"),
    ]:
        b.add(cid, "wrong-group", fill(BASE_INTERACT, **dict(ibase, quasistatic=line)),
              Expect("error", cmd_re, kw))
    b.add("contacts.group.subset", "valid-edge",
          fill(BASE_CONTACTS, contacts="group half id <= 50\n" + c_good.replace(" all ", " half ")),
          Expect("ok"))

    # before the box exists (LAMMPS' own message naming the command is fine)
    pre = "units lj\ndimension 2\natom_style atomic\n"
    for cid, cmd, cmd_re, kw in [
        ("contacts", c_good, r"\bfix\b", r"\bbox\b"),
        ("substrate", s_good, r"\bfix\b", r"\bbox\b"),
        ("quasistatic", "fix q all eq/quasistatic c", r"\bfix\b", r"\bbox\b"),
        ("paircoeff", "pair_style eq/elastic 3.0\npair_coeff * * 0.06 3.0", r"pair_coeff", r"\bbox\b"),
        ("fix_modify", "fix_modify sub kc all 0.5", r"fix_modify", r"\bbox\b|\bID\b"),
        ("fix_modify-velocity", "fix_modify sub velocity 0.1", r"fix_modify", r"\bbox\b|\bID\b"),
    ]:
        b.add(f"{cid}.before-box", "before-box", pre + cmd + "\n" + LAT2D.split("\n", 3)[3] + "run 1\n",
              Expect("error", cmd_re, kw))
    b.add("pairstyle.before-box", "valid-edge",
          pre + "pair_style eq/elastic 3.0\n" + HEX2D.split("\n", 3)[3] +
          "pair_coeff * * 0.06 3.0\nneighbor 0.5 bin\n" + c_good + "\nrun 2\n", Expect("ok"))

    # atom styles: IDs are required; other atom styles work
    noid = LAT2D.replace("atom_style      atomic\n", "atom_style      atomic\natom_modify     id no\n")
    for cid, text, cmd_re in [
        ("contacts", noid + c_good + "\nrun 1\n", "eq/contacts"),
        ("substrate", noid + s_good + "\nrun 1\n", "eq/substrate"),
        ("paircoeff", noid + "pair_style eq/elastic 1.5\npair_coeff * * 1.0 1.0\n" + s_good + "\nrun 1\n",
         r"eq/substrate|eq/elastic"),
        ("paircoeff-contacts", noid + "pair_style eq/elastic 1.5\npair_coeff * * 1.0 1.0\nrun 1\n",
         r"eq/elastic"),
    ]:
        b.add(f"{cid}.atom-ids-off", "atom-style", text, Expect("error", cmd_re, r"\bIDs?\b|atom_modify"))
    for style in ("charge", "bond", "full", "sphere"):
        lat = LAT2D.replace("atom_style      atomic", f"atom_style      {style}")
        if style == "sphere":
            lat = lat.replace("mass            1 1.0\n", "")
        b.add(f"contacts.atom-style-{style}", "valid-edge",
              lat + "comm_modify cutoff 0.5\n" + c_good + "\nfix m all move linear 1.0 0 0 units box\n"
              "timestep 0.05\nthermo_style custom step f_c[1] f_c[3]\nrun 20\n", Expect("ok"))
        b.add(f"substrate.atom-style-{style}", "valid-edge",
              lat + s_good + "\nfix bd all brownian 1.0 1 rng none gamma_t 10.0\ntimestep 0.1\n"
              "thermo_style custom step f_sub[1] f_sub[5]\nrun 20\n", Expect("ok"))

    # dimension: dir z in 2d; in 3d it is valid
    b.add("contacts.dimension.dir-z-2d", "dimension", fill(BASE_CONTACTS, contacts=c_good + " dir z"),
          Expect("error", "eq/contacts", r"\bdir\b"))
    b.add("substrate.dimension.dir-z-2d", "dimension",
          fill(BASE_SUBSTRATE, **dict(sub_base, substrate=s_good + " dir z")),
          Expect("error", "eq/substrate", r"\bdir\b"))
    b.add("eqme.dimension.dir-z", "valid-edge", fill(BASE_EQME, eqme=(
        "eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 dir z")), Expect("ok"))
    l3d = ("units lj\natom_style atomic\nlattice sc 1.0\nregion box block 0 5 0 5 0 4\ncreate_box 1 box\n"
           "create_atoms 1 box\nmass 1 1.0\ncomm_modify cutoff 0.5\n")
    b.add("contacts.dimension.dir-z-3d", "valid-edge",
          l3d + c_good + " dir z\nfix m all move linear 0 0 1.0 units box\ntimestep 0.05\n"
          "thermo_style custom step f_c[1] f_c[3]\nrun 20\n", Expect("ok"))

    # pair coefficients
    pc_re = r"eq/elastic|pair_coeff|pair coeff"
    for cid, ps, pcl, kw, cls in [
        ("paircoeff.absent", "pair_style eq/elastic 3.0", "", r"coeff", "pair-coeff"),
        ("paircoeff.type-2-unset-table", "pair_style eq/elastic 3.0", "pair_coeff 1 1 table k.table KERN",
         r"pair_coeff|coeff|mix", "pair-coeff"),
        ("paircoeff.mixed-table", "pair_style eq/elastic 3.0",
         "pair_coeff 1 1 0.06 3.0\npair_coeff 2 2 table k.table KERN", r"pair_coeff|mix", "pair-coeff"),
        ("paircoeff.type-out-of-range", "pair_style eq/elastic 3.0", "pair_coeff 3 3 0.06 3.0",
         r"type|index|bounds", "pair-coeff"),
        ("paircoeff.type-zero", "pair_style eq/elastic 3.0", "pair_coeff 0 0 0.06 3.0",
         r"type|index|bounds", "pair-coeff"),
        ("paircoeff.type-word", "pair_style eq/elastic 3.0", "pair_coeff a b 0.06 3.0",
         r"type|index|bounds|integer", "pair-coeff"),
        ("paircoeff.before-pairstyle", "", "pair_coeff * * 0.06 3.0\npair_style eq/elastic 3.0",
         r"pair.?style", "pair-coeff"),
        ("paircoeff.rcut-beyond-global", "pair_style eq/elastic 1.0", "pair_coeff * * 0.06 3.0 2.5",
         r"rcut|cut", "extreme"),
    ]:
        exp = Expect("robust" if cls == "extreme" else "error",
                     pc_re if "before-pairstyle" not in cid else r"pair_coeff", kw)
        if cid == "paircoeff.absent":
            exp = Expect("error", r"pair", r"coeff")
        b.add(cid, cls, fill(BASE_INTERACT, **dict(ibase, pairstyle=ps, paircoeff=pcl)), exp, GOOD_FILES)
    b.add("paircoeff.mixed-numbers", "valid-edge",
          fill(BASE_INTERACT, **dict(ibase, paircoeff="pair_coeff 1 1 0.06 3.0\npair_coeff 2 2 0.03 2.0")),
          Expect("ok"))
    b.add("paircoeff.hybrid", "extreme",
          fill(BASE_INTERACT, **dict(ibase, pairstyle="pair_style hybrid eq/elastic 3.0 zero 3.0",
                                     paircoeff="pair_coeff * * eq/elastic 0.06 3.0")),
          Expect("robust", r"eq/elastic|hybrid", r"hybrid"))

    # conflicts between styles
    for cid, extra, cmd_re, kw in [
        ("pair.no-fix", "unfix q\nunfix c", r"eq/elastic", r"eq/contacts"),
        ("pair.two-contacts", "fix c2 all eq/contacts 1.0 5 threshold uniform 0.75 1.25", r"eq/elastic|eq/contacts", r"eq/contacts"),
        ("pair.contacts-and-substrate", "fix s all eq/substrate 1.0 sawtooth 1.0", r"eq/elastic", r"eq/substrate"),
        ("pair.respa", "run_style respa 2 2", r"eq/contacts|eq/elastic|eq/quasistatic", r"respa|verlet"),
        ("quasistatic.respa", "unfix q\nfix q all eq/quasistatic c max 0.02\nrun_style respa 2 2\npair_style zero 3.0\npair_coeff * *",
         r"eq/quasistatic|eq/contacts", r"respa|verlet"),
        ("pair.fix-adapt", "variable f equal 0.05\nfix a all adapt 1 pair eq/elastic ftilde * * v_f",
         r"eq/elastic", r"adapt"),
        ("quasistatic.second-driver", "fix mv all move linear 1.0 0 0 units box", r"eq/quasistatic|fix move|\bmove\b",
         r"move|eq/quasistatic"),
    ]:
        text = fill(BASE_INTERACT, **ibase).replace("thermo_style", extra + "\nthermo_style", 1)
        text = text.replace("f_q f_q[2]", "") if "unfix q" in extra else text
        if cid == "pair.no-fix":
            text = text.replace("thermo_style    custom step pe f_c[1] f_c[2] f_c[3] f_c[4] f_c[6] f_c[8] ",
                                "thermo_style    custom step pe ")
        cls = "conflict"
        exp = Expect("error", cmd_re, kw)
        if cid == "quasistatic.second-driver":
            exp = Expect("robust", cmd_re, kw)
            cls = "extreme"
        b.add(cid, cls, text, exp, GOOD_FILES)
    b.add("substrate.two-fixes-pair", "conflict",
          fill(BASE_SUBSTRATE, **dict(sub_base, substrate=s_good + "\nfix sub2 all eq/substrate 1.0 sawtooth 1.0"))
          .replace("f_sub f_sub[1]", "f_sub[1]"),
          Expect("error", r"eq/elastic", r"eq/substrate"))

    # run-time checks
    nanmove = ("variable big equal 1e308\nvariable nanx equal v_big*v_big-v_big*v_big\n")
    b.add("contacts.runtime.nan-position", "runtime",
          fill(BASE_CONTACTS, contacts=c_good).replace(
              "fix             m all move linear 1.0 0.5 0.0 units box",
              nanmove + "fix m all move variable v_nanx NULL NULL NULL NULL NULL"),
          Expect("error", "eq/contacts", r"nan|not a number|finite"))
    b.add("contacts.runtime.nan-position.np2", "runtime",
          fill(BASE_CONTACTS, contacts=c_good).replace(
              "fix             m all move linear 1.0 0.5 0.0 units box",
              nanmove + "fix m all move variable v_nanx NULL NULL NULL NULL NULL"),
          Expect("error", "eq/contacts", r"nan|not a number|finite"), np=2)
    b.add("contacts.runtime.breaks-1000", "runtime",
          fill(BASE_CONTACTS, contacts=c_good + " reform delta 1.249").replace(
              "move linear 1.0 0.5 0.0", "move linear 9.0 0.0 0.0").replace("timestep        0.05", "timestep 0.5"),
          Expect("error", "eq/contacts", r"1000|timestep"))
    b.add("interact.runtime.nan-position", "runtime",
          fill(BASE_INTERACT, **dict(ibase, quasistatic=nanmove + "fix q all move variable v_nanx NULL NULL NULL NULL NULL"))
          .replace("f_q f_q[2]", ""),
          Expect("error", r"eq/contacts|eq/elastic", r"nan|not a number|finite"))
    b.add("substrate.runtime.nan-position", "runtime",
          fill(BASE_SUBSTRATE, **sub_base).replace(
              "fix             bd all brownian 1.0 1 rng none gamma_t 100.0",
              nanmove + "fix bd all move variable v_nanx NULL NULL NULL NULL NULL"),
          Expect("error", r"eq/substrate|eq/elastic", r"nan|not a number|finite"))
    b.add("substrate.runtime.nan-position.np2", "runtime",
          fill(BASE_SUBSTRATE, **sub_base).replace(
              "fix             bd all brownian 1.0 1 rng none gamma_t 100.0",
              nanmove + "fix bd all move variable v_nanx NULL NULL NULL NULL NULL"),
          Expect("error", r"eq/substrate|eq/elastic", r"nan|not a number|finite"), np=2)
    b.add("substrate.runtime.skin", "runtime",
          fill(BASE_SUBSTRATE, **sub_base).replace("fix_modify      sub energy yes",
                                                   "fix_modify sub energy yes\ngroup left id <= 20\n"
                                                   "displace_atoms left move 0.7 0 0 units box"),
          Expect("error", r"eq/elastic", r"skin"))
    b.add("substrate.runtime.unstable", "runtime",
          fill(BASE_SUBSTRATE, **dict(sub_base, substrate="fix sub all eq/substrate 1.0 sawtooth 1.0 drive 0.07 1e-4"))
          .replace("fix             bd all brownian 1.0 1 rng none gamma_t 100.0",
                   "fix nve all nve\nvelocity all create 1.0 4 dist uniform")
          .replace("pair_coeff      1 1 25.0 1.0", "pair_coeff 1 1 1e6 1.0").replace("timestep        0.1", "timestep 1.0"),
          Expect("robust", r"eq/substrate|eq/elastic", r"nan|finite|skin|timestep|instab"))
    b.add("quasistatic.runtime.all-broken", "runtime",
          fill(BASE_INTERACT, **ibase).replace("threshold uniform 0.75 1.25", "threshold uniform 0.75 1.25 reform none")
          .replace("fix q all eq/quasistatic c max 0.02", "fix q all eq/quasistatic c").replace("run             30", "run 200"),
          Expect("error", "eq/quasistatic", r"contact|max"))
    b.add("quasistatic.runtime.all-broken-max", "valid-edge",
          fill(BASE_INTERACT, **ibase).replace("threshold uniform 0.75 1.25", "threshold uniform 0.75 1.25 reform none")
          .replace("run             30", "run 200").replace("max 0.02", "max 0.1"), Expect("ok"))
    b.add("contacts.runtime.all-broken-mean", "valid-edge",
          fill(BASE_CONTACTS, contacts="fix c all eq/contacts 1.0 4711 threshold uniform 0.01 0.02 reform none"),
          Expect("ok"))
    b.add("contacts.runtime.timestep-zero", "extreme",
          fill(BASE_CONTACTS, contacts=c_good).replace("timestep        0.05", "timestep 0.0"),
          Expect("robust", r"timestep", r"timestep"))
    b.add("substrate.runtime.timestep-zero", "extreme",
          fill(BASE_SUBSTRATE, **sub_base).replace("timestep        0.1", "timestep 0.0"),
          Expect("robust", r"timestep|eq/substrate|brownian", r"timestep|dt"))
    b.add("substrate.runtime.kc-huge-between-runs", "extreme",
          fill(BASE_SUBSTRATE, **sub_base) + "fix_modify sub kc all 1e300\nrun 10\n",
          Expect("robust", r"eq/substrate|fix_modify", r"\bkc\b"))
    b.add("substrate.runtime.velocity-huge", "extreme",
          fill(BASE_SUBSTRATE, **sub_base) + "fix_modify sub velocity 1e300\nrun 10\n",
          Expect("robust", r"eq/substrate|fix_modify", r"velocity|stage"))
    b.add("contacts.runtime.minimize", "valid-edge",
          fill(BASE_CONTACTS, contacts=c_good) + "unfix m\nminimize 0 1e-10 100 1000\n", Expect("ok"))
    b.add("contacts.runtime.restart-other-seed", "valid-edge",
          fill(BASE_CONTACTS, contacts=c_good) + "write_restart r.restart\nclear\nread_restart r.restart\n"
          "fix c all eq/contacts 1.0 99 threshold uniform 0.75 1.25\nfix m all move linear 1.0 0 0 units box\nrun 10\n",
          Expect("ok"))
    b.add("contacts.runtime.restart-garbage", "nan",
          fill(BASE_CONTACTS, contacts=c_good) + "write_restart r.restart\nclear\nread_restart r.restart\n"
          "fix c all eq/contacts nan 4711 threshold uniform 0.75 1.25\nrun 10\n",
          Expect("error", "eq/contacts", r"\bkc\b"))
    b.add("contacts.runtime.avalanches-np2", "control",
          fill(BASE_CONTACTS, contacts=c_good + " avalanches aval.dat"), Expect("ok"), np=2)
    b.add("contacts.avalanches.unwritable.np2", "file-unwritable",
          fill(BASE_CONTACTS, contacts=c_good + " avalanches /nonexistent/dir/a.dat"),
          Expect("error", "eq/contacts", r"avalanches"), np=2)
    b.add("eqme.force.unwritable.np2", "file-unwritable",
          fill(BASE_EQME, eqme="eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 force /nonexistent/dir/f.dat"),
          Expect("error", "eq/me", r"\bforce\b"), np=2)
    b.add("eqme.substrate.unwritable.np2", "file-unwritable",
          fill(BASE_EQME, eqme="eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 substrate /nonexistent/dir/s.table B 1.0"),
          Expect("error", "eq/me", r"\bsubstrate\b"), np=2)
    b.add("eqme.control-np2", "control",
          fill(BASE_EQME, eqme="eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 force f.dat substrate s.table B 1.0"),
          Expect("ok"), np=2)
    b.add("eqme.substrate-roundtrip", "control",
          fill(BASE_EQME, eqme="eq/me threshold uniform 0.75 1.25 xmax 2 dx 0.01 substrate s.table B 1.25")
          + CHAIN + "fix sub all eq/substrate 1.0 table s.table B drive 0.07 1e-4\n"
          "fix bd all brownian 1.0 1 rng none gamma_t 100.0\ntimestep 0.1\n"
          "thermo_style custom step f_sub[1] f_sub[5] f_sub[6]\nrun 20\n", Expect("ok"))


def generate(mpi=True):
    """All cases, in a fixed order (mpi=False drops the 2-rank ones)."""
    b = Builder()
    gen_contacts(b)
    gen_eqme(b)
    gen_interact(b)
    gen_substrate(b)
    gen_meso(b)
    gen_tables(b)
    gen_misc(b)
    cases = b.cases if mpi else [c for c in b.cases if c.np == 1]
    return cases


def shard(cases, index, count):
    return [c for i, c in enumerate(cases) if i % count == index]


# ----------------------------------------------------------------------------
# runner

ERROR_RE = re.compile(r"^\s*ERROR(?: on proc \d+)?:\s*(.*)$", re.M)
SRC_RE = re.compile(r"\s*\((?:/[^()]*|src/[^()]*|[\w./-]+\.(?:cpp|h)):\d+\)\s*$")
NAN_TOKEN = r"(?<![\w.])[-+]?(?:nan|inf|infinity)(?![\w])"
NAN_RE = re.compile(NAN_TOKEN, re.I)
ONLY_NAN_RE = re.compile(r"(?<![\w.])[-+]?nan(?![\w])", re.I)
NUMBER_RE = re.compile(r"^[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?|nan|inf|infinity)$",
                       re.I)
# a crash: a signal, an uncaught C++ exception (LAMMPS' main() prints
# "Exception: ..." and calls MPI_Abort), glibc's heap checks, a rank killed
CRASH_RE = re.compile(r"Segmentation fault|exited on signal \d+|Process received signal|"
                      r"terminate called|core dumped|^Exception: .*|double free|corrupted|"
                      r"stack smashing|std::bad_alloc|Floating point exception|"
                      r"malloc\(\)|free\(\): invalid|"
                      # a sanitizer build (./friction-eq test --sanitize) reporting to stderr
                      r"ERROR: (?:Address|Leak|Memory|Thread)Sanitizer|runtime error: |"
                      r"SUMMARY: UndefinedBehaviorSanitizer", re.M)
# LAMMPS' neighbor set-up lines (inf for a cutoff whose square overflows;
# LAMMPS then stops with its own error)
LAMMPS_INFO_RE = re.compile(r"(master list distance cutoff|ghost atom cutoff|binsize)\b")
LAMMPS_VERSION_RE = re.compile(r"(\d{1,2} \w{3} (\d{4}))")


def lmp_version(lmp):
    """'4 Jul 2026' and the year, from lmp -h."""
    try:
        out = subprocess.run([lmp, "-h"], capture_output=True, text=True, timeout=60,
                             env=run_env(1), errors="replace").stdout
    except (OSError, subprocess.TimeoutExpired):
        return "unknown", 0
    for line in out.splitlines():
        m = LAMMPS_VERSION_RE.search(line)
        if m and ("LAMMPS" in line or "Simulator" in line):
            return m.group(1), int(m.group(2))
    return "unknown", 0


def run_env(np, folder=None):
    env = dict(os.environ)
    env.setdefault("LAMMPS_POTENTIALS", str(ROOT / "potentials"))
    env.setdefault("OMP_NUM_THREADS", "1")
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    # Open MPI singletons start in ~0.05 s instead of ~0.4 s
    env.setdefault("OMPI_MCA_pml", "ob1")
    env.setdefault("OMPI_MCA_btl", "self,vader")
    if np == 1:
        env.setdefault("OMPI_MCA_ess_singleton_isolated", "1")
    else:
        # mpirun kills the other ranks at once when one exits with an error
        # (default: after 1 s; the ERROR line is printed before the exit)
        env.setdefault("OMPI_MCA_odls_base_sigkill_timeout", "0")
    if folder is not None:
        # a session directory per case: singletons started at the same
        # moment may otherwise collide in MPI_Init
        env["OMPI_MCA_orte_tmpdir_base"] = str(folder)
    return env


@dataclasses.dataclass
class Result:
    id: str
    cls: str
    outcome: str
    ok: bool
    rc: object
    seconds: float
    message: str = ""
    detail: str = ""
    np: int = 1
    tail: str = ""


def nan_in_output(case, out):
    """The first output line with NaN/inf: a thermo row (numbers only) with
    nan or inf, or any other line that LAMMPS or the styles printed with a
    nan (the input's echo, ERROR/WARNING lines and LAMMPS' echo of the last
    command do not count; LAMMPS' own set-up lines may print inf cutoffs)."""
    input_lines = {ln.strip() for ln in case.input.splitlines() if ln.strip()}
    # echoed commands (after variable substitution) start with a command word
    commands = {ln.split()[0] for ln in input_lines if not ln.startswith("#")}
    for ln in out.splitlines():
        s = ln.strip()
        if not s or s in input_lines or ERROR_RE.match(ln) or s.split()[0] in commands:
            continue
        if re.match(r"(ERROR|WARNING|Last (command|input line)|For more information)", s):
            continue
        toks = s.split()
        if len(toks) >= 2 and all(NUMBER_RE.match(t) for t in toks):
            if NAN_RE.search(s):
                return s
        elif ONLY_NAN_RE.search(s):
            return s
        elif re.search(r"=\s*[-+]?inf(?![\w])", s) and not LAMMPS_INFO_RE.match(s):
            return s
    return None


def classify(case, rc, out, timed_out):
    """(outcome, ok, message, detail) of one run."""
    if timed_out:
        return "hang", False, "", "timeout"
    errors = [SRC_RE.sub("", m.group(1)).strip() for m in ERROR_RE.finditer(out)]
    crash = None
    if isinstance(rc, int) and rc < 0:
        try:
            name = signal.Signals(-rc).name
        except ValueError:
            name = "?"
        crash = f"signal {-rc} ({name})"
    else:
        m = CRASH_RE.search(out)
        if m:
            crash = m.group(0).strip()
        elif rc != 0 and not errors:
            crash = f"exit status {rc} without ERROR"
    if crash:
        return "crash", False, errors[0] if errors else "", crash
    nan_line = nan_in_output(case, out)
    if nan_line:
        return "nan", False, errors[0] if errors else "", nan_line[:200]
    if errors:
        msg = errors[0]
        if case.expect.kind == "ok":
            return "rejected", False, msg, ""
        # the keyword must be named by the message itself, not only in its
        # list of the allowed keywords or values
        named = re.sub(r"[;,]?\s*allowed:.*$", "", msg)
        good = (re.search(case.expect.cmd, msg, re.I) and re.search(case.expect.kw, named, re.I))
        if good:
            return "error-ok", True, msg, ""
        if case.expect.kind == "robust":
            return "error-other", True, msg, ""
        return "error-vague", False, msg, ""
    finished = "Total wall time" in out
    if case.expect.kind == "error":
        return "accepted", False, "", "ran to the end" if finished else "ended without error"
    if not finished:
        return "incomplete", False, "", "no 'Total wall time'"
    return "ok", True, "", ""


def run_case(case, lmp, timeout=20.0, mpirun="mpirun", keep=None, tmp_root=None):
    folder = Path(tempfile.mkdtemp(prefix="feq_fuzz_", dir=tmp_root))
    try:
        case.write(folder)
        cmd = [lmp, "-in", "in.case", "-log", "none", "-nocite", "-echo", "screen"]
        if case.np > 1:
            cmd = [mpirun, "-np", str(case.np)] + cmd
        for attempt in range(3):
            t0 = time.time()
            timed_out = False
            proc = subprocess.Popen(cmd, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                    stdin=subprocess.DEVNULL, env=run_env(case.np, folder),
                                    start_new_session=True)
            try:
                raw, _ = proc.communicate(timeout=timeout * case.budget)
            except subprocess.TimeoutExpired:
                timed_out = True
                try:
                    os.killpg(proc.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                raw, _ = proc.communicate()
            dt = time.time() - t0
            out = raw.decode("utf-8", "replace")
            # Open MPI failed in MPI_Init (seen rarely with many concurrent
            # singletons): LAMMPS never printed its banner; try again
            if timed_out or "LAMMPS (" in out:
                break
        outcome, ok, msg, detail = classify(case, proc.returncode, out, timed_out)
        if keep is not None:
            kd = Path(keep) / case.id
            if kd.exists():
                shutil.rmtree(kd)
            shutil.copytree(folder, kd)
            (kd / "out.txt").write_text(out)
        tail = "" if ok else "\n".join(out.splitlines()[-25:])
        return Result(case.id, case.cls, outcome, ok, proc.returncode, round(dt, 3), msg, detail,
                      case.np, tail)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def run_cases(cases, lmp, jobs=None, timeout=20.0, mpirun=None, keep=None, progress=False):
    jobs = jobs or os.cpu_count() or 1
    lmp = os.path.abspath(lmp)
    mpirun = mpirun or shutil.which("mpirun") or "mpirun"
    results = [None] * len(cases)

    def one(i):
        results[i] = run_case(cases[i], lmp, timeout, mpirun, keep)
        if progress:
            r = results[i]
            print(f"  {r.outcome:12s} {r.seconds:6.2f}s {r.id}", file=sys.stderr, flush=True)

    # the 2-rank cases use both cores: run them alone, after the rest
    serial = [i for i, c in enumerate(cases) if c.np == 1]
    parallel = [i for i, c in enumerate(cases) if c.np > 1]
    with ThreadPoolExecutor(max_workers=jobs) as ex:
        list(ex.map(one, serial))
    for i in parallel:
        one(i)
    return results


def summarize(cases, results, out=sys.stdout, label=""):
    """The summary line (counts per outcome and per class/outcome), a table
    of counts per class, and every case that is not ok with its input."""
    by_id = {c.id: c for c in cases}
    tot = collections.Counter(r.outcome for r in results)
    per = collections.defaultdict(collections.Counter)
    for r in results:
        per[r.cls][r.outcome] += 1
    order = ["error-ok", "ok", "error-other", "error-vague", "rejected", "accepted", "nan", "crash", "hang",
             "incomplete"]
    outs = [o for o in order if tot[o]] + sorted(set(tot) - set(order))
    classes = [c for c in MALFORMED_CLASSES + OTHER_CLASSES if c in per]
    line = (f"FUZZ SUMMARY{(' ' + label) if label else ''}: {len(results)} cases; "
            + " ".join(f"{o}={tot[o]}" for o in outs) + " | "
            + "; ".join(f"{c}: " + ",".join(f"{o}={per[c][o]}" for o in order if per[c][o])
                        for c in classes))
    print(line, file=out)
    w = max(len(c) for c in classes) if classes else 5
    print(f"  {'class':{w}s} " + " ".join(f"{o:>11s}" for o in order), file=out)
    for c in classes:
        print(f"  {c:{w}s} " + " ".join(f"{per[c][o]:11d}" for o in order), file=out)
    print(f"  {'total':{w}s} " + " ".join(f"{tot[o]:11d}" for o in order), file=out)
    bad = [r for r in results if not r.ok]
    if bad:
        print(f"\nNOT OK: {len(bad)} case(s)", file=out)
        print(f"  {'outcome':12s} {'class':18s} {'id':58s} message / detail", file=out)
        for r in bad:
            print(f"  {r.outcome:12s} {r.cls:18s} {r.id:58s} {r.message or r.detail}", file=out)
        print("", file=out)
        for r in bad:
            c = by_id[r.id]
            print(f"---- {r.id} [{r.cls}] -> {r.outcome}" + (f" (np {c.np})" if c.np > 1 else ""),
                  file=out)
            print(f"     expected: {c.expect.text()}", file=out)
            if r.message:
                print(f"     ERROR: {r.message}", file=out)
            if r.detail:
                print(f"     detail: {r.detail}", file=out)
            for name, content in c.files.items():
                if name in GOOD_FILES and GOOD_FILES[name] == content:
                    continue
                shown = content if isinstance(content, str) else f"<{len(content)} bytes of binary>"
                print(f"     file {name}:", file=out)
                for ln in shown.splitlines()[:16]:
                    print(f"       | {ln}", file=out)
            print("     input:", file=out)
            for ln in c.input.splitlines():
                print(f"       {ln}", file=out)
    return line


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=os.environ.get("FEQ_LMP", str(ROOT / "build" / "lmp")))
    ap.add_argument("--jobs", type=int, default=os.cpu_count())
    ap.add_argument("--timeout", type=float, default=float(os.environ.get("FEQ_FUZZ_TIMEOUT", 20)))
    ap.add_argument("--filter", default=None, help="regex on case id or class")
    ap.add_argument("--shard", default=None, help="I/N: run shard I of N")
    ap.add_argument("--no-mpi", action="store_true", help="leave out the 2-rank cases")
    ap.add_argument("--list", action="store_true", help="list the cases and exit")
    ap.add_argument("--show", default=None, help="print one case's input and files and exit")
    ap.add_argument("--write", default=None, help="write every case into DIR/<id>/ and exit")
    ap.add_argument("--keep", default=None, help="keep the case folders with their output in DIR")
    ap.add_argument("--json", default=None, help="write the results to this JSON file")
    ap.add_argument("--progress", action="store_true")
    a = ap.parse_args(argv)

    cases = generate(mpi=not a.no_mpi)
    if a.filter:
        rx = re.compile(a.filter)
        cases = [c for c in cases if rx.search(c.id) or rx.fullmatch(c.cls)]
    if a.shard:
        i, n = (int(x) for x in a.shard.split("/"))
        cases = shard(cases, i, n)
    if a.list:
        for c in cases:
            print(f"{c.id:70s} {c.cls:18s} np{c.np} {c.expect.text()}")
        n_bad = sum(c.cls in MALFORMED_CLASSES or c.cls == "extreme" for c in cases)
        print(f"{len(cases)} cases ({n_bad} malformed, {len(cases) - n_bad} controls)")
        return 0
    if a.show:
        c = next(c for c in cases if c.id == a.show)
        print(f"# {c.id} [{c.cls}] np {c.np}: expected {c.expect.text()}")
        for name, content in c.files.items():
            print(f"# file {name}: " + (repr(content[:400]) if isinstance(content, bytes) else "\n" + content))
        print(c.input)
        return 0
    if a.write:
        write_cases(cases, a.write)
        return 0
    return run_and_summarize(cases, a, run_cases, summarize)


def write_cases(cases, folder):
    """Every case into folder/<id>/ with its expectation (expect.json)."""
    for c in cases:
        d = Path(folder) / c.id
        d.mkdir(parents=True, exist_ok=True)
        c.write(d)
        (d / "expect.json").write_text(json.dumps(dataclasses.asdict(c.expect)))


def write_report(results, path):
    Path(path).write_text(json.dumps([dataclasses.asdict(r) for r in results], indent=1))


def run_and_summarize(cases, a, run, summarize_fn):
    """The runners' main (this one's and the misuse generator's): run the
    cases with run(), print summarize_fn()'s table, write the --json report;
    exit status 0 when every case is ok."""
    version, _ = lmp_version(a.lmp)
    t0 = time.time()
    results = run(cases, a.lmp, a.jobs, a.timeout, keep=a.keep, progress=a.progress)
    dt = time.time() - t0
    summarize_fn(cases, results, label=f"[{a.lmp}, LAMMPS {version}, {dt:.1f} s, {a.jobs} jobs]")
    if a.json:
        write_report(results, a.json)
    return 0 if all(r.ok for r in results) else 1


def pytest_summary(results, by_id, summarize_fn, label, report_env, capsys):
    """test_summary of the pytest runners: one line of counts per class and
    outcome for the results of this run (printed past pytest's capture);
    the environment variable report_env names a JSON report to write."""
    if not results:
        return
    import io
    buf = io.StringIO()
    line = summarize_fn([by_id[r.id] for r in results], results, out=buf, label=label)
    with capsys.disabled():
        print("\n" + line)
    report = os.environ.get(report_env)
    if report:
        write_report(results, report)


if __name__ == "__main__":
    sys.exit(main())
