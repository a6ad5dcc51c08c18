#!/usr/bin/python3
"""Stateful misuse of the FRICTION-EQ styles: generator and runner.

fuzz_inputs.py mutates one command at a time; this generator misuses the
state that the styles keep between commands, between runs and in files:
partners removed or replaced during a run (run N pre no every M "...") or
between runs, restart files re-read with other arguments or garbled,
boxes and atoms changed between runs, products of finite arguments that
overflow, outputs read before the first run, and combinations the
documentation forbids.  Every input runs on 1 and on 2 MPI ranks (both are
cases).

Every case ends in exactly one of: a LAMMPS ERROR whose message matches the
case's regular expressions (a partner problem names both styles), or a run
to the end with finite output whose in-script checks pass.  The oracles of
a right result are in the LAMMPS input itself: it computes the value a
quantity must have and prints "CHECK FAILED <what> <got> <want>" when it
differs.  Outcomes, besides those of fuzz_inputs.py (error-ok, ok,
error-other, error-vague, rejected, accepted, nan, crash, hang,
incomplete):

  wrong       a line starting with "CHECK FAILED" (a silently wrong value)
  drift       pair eq/elastic's report "drift checks: max |h_incremental -
              h_full| = X (scale of h: Y)" with X > 1e-10 Y (the cases run
              pair_style eq/elastic RCUT check 1: every update is compared
              with a field computed from scratch)
  no-warning  a run that must warn (a restart with another seed) did not

    /usr/bin/python3 unittest/fuzz/misuse_inputs.py --lmp build/lmp --jobs 2
    /usr/bin/python3 unittest/fuzz/misuse_inputs.py --filter '^restart-args' --np 1
    /usr/bin/python3 unittest/fuzz/misuse_inputs.py --list
    /usr/bin/python3 unittest/fuzz/misuse_inputs.py --show unfix-within.contacts-elastic-qs.unfix-src.np1

The runner, the Case and Expect classes and the classifier are those of
fuzz_inputs.py (imported); this module adds the outcomes above.  Restart
files are written and garbled within one LAMMPS input (write_restart,
"shell python3 garble.py ...", clear, read_restart), so that every case is
one lmp invocation.  Python 3 standard library only; the generator is
deterministic.
"""

import argparse
import collections
import contextlib
import dataclasses
import os
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import fuzz_inputs as F  # noqa: E402

ROOT = F.ROOT
Case = F.Case
CLASSES = ("unfix-within", "unfix-between", "restart-args", "restart-garbled", "box-atoms",
           "overflow", "before-run", "forbidden")
OUTCOMES = ("error-ok", "ok", "error-other", "error-vague", "rejected", "accepted", "wrong", "drift",
            "no-warning", "nan", "crash", "hang", "incomplete")
DRIFT_TOL = 1e-10

# ----------------------------------------------------------------------------
# expectations and classification


@dataclasses.dataclass
class Expect(F.Expect):
    """fuzz_inputs.Expect, and: warn, a regex that a WARNING line must match
    (a run that must continue with a warning)."""
    warn: str = ""

    def text(self):
        s = super().text()
        return s + (f"; WARNING /{self.warn}/" if self.warn else "")


def ok(warn=""):
    return Expect("ok", warn=warn)


def err(cmd, kw="."):
    return Expect("error", cmd, kw)


def err_or_ok(cmd, kw="."):
    return Expect("error-or-ok", cmd, kw)


def robust(cmd=".", kw="."):
    return Expect("robust", cmd, kw)


CHECK_RE = re.compile(r"^CHECK FAILED\b.*$", re.M)
DRIFT_RE = re.compile(r"drift checks: max \|h_incremental - h_full\| = (\S+) \(scale of h: ([^)\s]+)\)")
WARNING_RE = re.compile(r"^\s*WARNING(?: on proc \d+)?:\s*(.*)$", re.M)
_BASE_CLASSIFY = F.classify


def classify(case, rc, out, timed_out):
    """fuzz_inputs.classify, then (for the cases of this module) wrong,
    drift and no-warning."""
    if not isinstance(case.expect, Expect):
        return _BASE_CLASSIFY(case, rc, out, timed_out)
    # a crash pattern within LAMMPS' own ERROR message is no crash
    # ("ERROR: Incomplete or corrupted LAMMPS restart file")
    out = F.ERROR_RE.sub(lambda m: F.CRASH_RE.sub(lambda k: "#" * len(k.group(0)), m.group(0)), out)
    outcome, good, msg, detail = _BASE_CLASSIFY(case, rc, out, timed_out)
    if outcome in ("crash", "hang", "nan"):
        return outcome, good, msg, detail
    m = CHECK_RE.search(out)
    if m:
        return "wrong", False, msg, m.group(0)[:200]
    for x, y in DRIFT_RE.findall(out):
        try:
            dx, scale = float(x), float(y)
        except ValueError:
            return "drift", False, msg, f"drift report not a number: {x} (scale {y})"
        if not dx <= DRIFT_TOL * scale:
            return "drift", False, msg, f"max |h_incremental - h_full| = {x} (scale of h: {y})"
    if outcome == "ok" and case.expect.warn:
        warnings = WARNING_RE.findall(out)
        if not any(re.search(case.expect.warn, w, re.I) for w in warnings):
            return "no-warning", False, "", f"no WARNING matching /{case.expect.warn}/"
    return outcome, good, msg, detail


@contextlib.contextmanager
def misuse_classifier():
    """fuzz_inputs' runner with this module's classify (it dispatches on the
    Expect class, so fuzz cases are classified as before)."""
    saved = F.classify
    F.classify = classify
    try:
        yield
    finally:
        F.classify = saved


def run_case(case, lmp, **kw):
    with misuse_classifier():
        return F.run_case(case, lmp, **kw)


def run_cases(cases, lmp, jobs=None, timeout=20.0, **kw):
    with misuse_classifier():
        return F.run_cases(cases, lmp, jobs, timeout, **kw)


# ----------------------------------------------------------------------------
# in-script oracles


def check(name, got, want, tol=1e-9, scale=None):
    """Input lines that print 'CHECK FAILED name got want' unless |got -
    want| <= tol (1 + |scale|), scale = want by default (NaN fails).  got
    and want are quoted formulas: no $ substitution in them."""
    v = "chk_" + re.sub(r"\W+", "_", name).strip("_")
    scale = scale or f"v_{v}_w"
    return (f"variable {v}_g equal \"{got}\"\n"
            f"variable {v}_w equal \"{want}\"\n"
            f"if \"$(!(abs(v_{v}_g-v_{v}_w)<={tol}*(1+abs({scale}))))\" then &\n"
            f"  \"print 'CHECK FAILED {name} $(v_{v}_g:%.17g) $(v_{v}_w:%.17g)'\"\n")


def capture(name, expr):
    """Store the current value of expr in variable name (immediate)."""
    return f"variable {name} equal $({expr}:%.17g)\n"


# ----------------------------------------------------------------------------
# small systems.  A System is an input up to (not including) the run
# command; its parts are kept so that a case can re-use them after a clear.

HEAD = """units           lj
dimension       2
atom_style      atomic
atom_modify     map array
boundary        p p p
"""


def box(lat="hex", nx=8, ny=5, ntypes=1):
    a = "1.1547005383792515" if lat == "hex" else "1.0"
    return (HEAD + f"lattice         {lat} {a}\nregion          box block 0 {nx} 0 {ny} -0.5 0.5\n"
            f"create_box      {ntypes} box\ncreate_atoms    1 box\nmass            * 1.0\n")


def chain(n=40, ntypes=1):
    return (HEAD + f"lattice         sq 1.0\nregion          box block 0 {n} -2 2 -0.5 0.5\n"
            f"create_box      {ntypes} box\nregion          line block 0 {n} -0.1 0.1 -0.5 0.5 units box\n"
            "create_atoms    1 region line\nmass            * 1.0\n")


C_ARGS = "1.0 99 threshold uniform 0.75 1.25"
# temperature, aging and a delay: 9 more values per contact
C_THERMAL = C_ARGS + " thermal 0.1 1.0 1.0 aging log 0.05 1.0 delay exp 0.1"
# interacting contacts at T > 0 with aging, and with delays (waiting
# contacts leave the field)
C_THERMAL_FIELD = C_ARGS + " thermal 0.1 1.0 1.0 aging log 0.05 1.0 rest 10"
C_DELAY_FIELD = C_ARGS + " thermal 0.1 1.0 1.0 delay exp 0.5"
S_ARGS = "1.0 sawtooth 1.0 drive 0.07 0.01 stage 14.5"
S_DISORDER = " disorder gaussian 1.0 0.05 9"
# thermal hops of the blocks (sawtooth wells, reverse break): 3 more values per block
S_THERMAL = S_ARGS + " reverse break thermal 0.3 1.0 5.0 seed 5"
MP_ARGS = "100 1.0 threshold gaussian 1.0 0.25 reform gaussian 0.05 0.1 drive 10.0 1.0 check 50"
MS_ARGS = "100 1.0 threshold uniform 0.75 1.25 reform delta 0.0 grid 0.02 screen 0.001 1.0 1.5"
# the blocks at T > 0 (the thermal kernel: anchors x 8 threshold panels)
MS_THERMAL = MS_ARGS + " thermal 0.05 1.0 1.0 labels 8"


def pair_lines(kind, rcut, coeff):
    """pair_style lines: none, elastic, hybrid-zero, hybrid-lj (lj/cut with
    epsilon 0 beside eq/elastic)."""
    if kind == "none":
        return "comm_modify     cutoff 2.0\n"
    if kind == "elastic":
        return f"pair_style      eq/elastic {rcut} check 1\npair_coeff      * * {coeff}\n"
    if kind == "hybrid-zero":
        return (f"pair_style      hybrid/overlay eq/elastic {rcut} check 1 zero {rcut}\n"
                f"pair_coeff      * * eq/elastic {coeff}\npair_coeff      * * zero\n")
    if kind == "hybrid-lj":
        return (f"pair_style      hybrid/overlay eq/elastic {rcut} check 1 lj/cut 1.0\n"
                f"pair_coeff      * * eq/elastic {coeff}\npair_coeff      * * lj/cut 0.0 1.0\n")
    raise ValueError(kind)


@dataclasses.dataclass
class System:
    name: str
    atoms: str          # box and atoms
    pair: str           # pair/comm lines
    neigh: str
    fixes: list         # [(fix ID, line)] in the order of definition
    tail: str           # timestep, velocities
    source: str         # ID of the coordinate source
    style: str          # its style (eq/contacts, eq/substrate, eq/meso)
    pairkind: str
    natoms: int
    thermo: str = "step pe"

    def fix_lines(self, skip=()):
        return "".join(line + "\n" for fid, line in self.fixes if fid not in skip)

    def text(self, pad=False, thermo=None, skip=(), computes=""):
        """The whole set-up.  pad: an inert fix defined last, so that a fix
        unfixed during a run is never the last one (LAMMPS keeps its fix
        lists by index during a run with pre no: the last slot would then
        hold a deleted fix, a crash of LAMMPS' own)."""
        return (self.atoms + self.pair + self.neigh + self.fix_lines(skip)
                + ("fix             pad all enforce2d\n" if pad else "") + self.tail + computes
                + f"thermo_style    custom {thermo or self.thermo}\nthermo_modify   norm no\nthermo          10\n")

    def after_restart(self, fixes=None, thermo=None, computes=""):
        """What to re-specify after read_restart (the pair style and its
        coefficients come from the file; LAMMPS' pair hybrid keeps no
        coefficients of its sub-styles there)."""
        pair = {"none": "comm_modify     cutoff 2.0\n", "elastic": ""}.get(
            self.pairkind, "".join(ln + "\n" for ln in self.pair.splitlines() if ln.startswith("pair_coeff")))
        tail = "\n".join(ln for ln in self.tail.splitlines() if not ln.startswith("velocity")) + "\n"
        lines = fixes if fixes is not None else self.fix_lines()
        return (pair + self.neigh + lines + tail + computes
                + f"thermo_style    custom {thermo or self.thermo}\nthermo_modify   norm no\nthermo          10\n")

    def line(self, fid):
        return dict(self.fixes)[fid]


def contacts_system(pair="elastic", drive="qs", cargs=C_ARGS, qfirst=True):
    """80 contacts (hex lattice, spacing 1), driven quasi-statically
    (qs: fix q eq/quasistatic, defined before fix c so that it keeps its
    slot when c is unfixed), by fix move or by nve/noforce."""
    c = ("c", f"fix             c all eq/contacts {cargs}")
    if drive == "qs":
        fixes = [("q", "fix             q all eq/quasistatic c"), c] if qfirst else \
            [c, ("q", "fix             q all eq/quasistatic c")]
        tail = ""
    elif drive == "move":
        fixes = [c, ("m", "fix             m all move linear 1.0 0.0 0.0 units box")]
        tail = "timestep        0.05\n"
    else:
        fixes = [c, ("m", "fix             m all nve/noforce")]
        tail = "velocity        all set 1.0 0.0 0.0 units box\ntimestep        0.05\n"
    return System(f"contacts-{pair}-{drive}", box(), pair_lines(pair, "3.0", "0.06 3.0"),
                  "neighbor        0.5 bin\nneigh_modify    every 1 delay 0 check yes\n",
                  fixes, tail, "c", "eq/contacts", pair, 80)


def substrate_system(pair="elastic", sargs=S_ARGS):
    """A chain of 40 FK-ME blocks, pulled through springs past the
    threshold (stage 14.5: f = 1.015), overdamped."""
    return System(f"substrate-{pair}", chain(40), pair_lines(pair, "1.5", "25.0 1.0"),
                  "neighbor        1.0 bin\nneigh_modify    every 1 delay 0 check yes\n",
                  [("bd", "fix             bd all brownian 1.0 1 rng none gamma_t 100.0"),
                   ("sub", f"fix             sub all eq/substrate {sargs}")],
                  "timestep        0.1\n", "sub", "eq/substrate", pair, 40)


def meso_system(pair="elastic", margs=None):
    """pair != none: a chain of 20 eq/meso blocks coupled by pair
    eq/elastic, pulled by springs, overdamped; none: 24 blocks on a square
    lattice sliding rigidly with screening."""
    if pair == "none":
        return System("meso-screen", box("sq", 6, 4), "comm_modify     cutoff 2.0\n",
                      "neighbor        0.5 bin\n",
                      [("mv", "fix             mv all nve/noforce"),
                       ("m", f"fix             m all eq/meso {margs or MS_ARGS}")],
                      "velocity        all set 0.05 0.0 0.0 units box\ntimestep        1.0\n",
                      "m", "eq/meso", pair, 24)
    return System(f"meso-{pair}", chain(20), pair_lines(pair, "1.5", "20.0 1.0"),
                  "neighbor        1.0 bin\nneigh_modify    every 1 delay 0 check yes\n",
                  [("bd", "fix             bd all brownian 1.0 1 rng none gamma_t 100.0"),
                   ("m", f"fix             m all eq/meso {margs or MP_ARGS}")],
                  "timestep        0.05\n", "m", "eq/meso", pair, 20)


# ----------------------------------------------------------------------------
# the messages of a partner removed or replaced (current wording of the styles)

QS_GONE = (r"Fix \S+ eq/quasistatic: fix \S+ eq/contacts, the contacts it drives, was removed or "
           r"replaced during the run")
PAIR_SRC_GONE = (r"Pair style eq/elastic: fix \S+ eq/(contacts|substrate|meso), the coordinate source "
                 r"found at the start of the run, was removed or replaced during the run")
C_FIELD_GONE = (r"Fix \S+ eq/contacts: pair style eq/elastic, the field of its contacts at the start "
                r"of the run, was removed or replaced during the run")
B_FIELD_GONE = (r"Fix \S+ eq/(substrate|meso): pair style eq/elastic, the field of its blocks at the "
                r"start of the run, was removed or replaced")
PAIR_NOT_SET = r"Pair style eq/elastic was not set up for this force evaluation"
PAIR_AGAIN = r"Pair eq/elastic: forces evaluated again without a new evaluation of fix \S+ eq/contacts"
PAIR_COEFF_RUN = r"Pair style eq/elastic: (pair_style or )?pair_coeff during a run"
PAIR_ATOMS_CHANGED = r"Pair style eq/elastic: the atoms changed .* without a new neighbor list"
SAME_PLACE = r"are at the same (position|site)"
# an interaction too strong for the contacts (names both styles)
AVALANCHE = r"Fix eq/contacts: avalanche did not stop .*pair eq/elastic"


def alt(*patterns):
    return "(" + "|".join(patterns) + ")"


def source_gone(system, qs):
    """The messages that may report the removal of system's source."""
    pats = []
    if qs:
        pats.append(QS_GONE)
    if system.pairkind != "none":
        pats.append(PAIR_SRC_GONE)
        if system.style == "eq/contacts":
            pats.append(PAIR_AGAIN)
    return alt(*pats)


def field_gone(system, new_elastic):
    pats = [C_FIELD_GONE if system.style == "eq/contacts" else B_FIELD_GONE]
    if new_elastic:
        # the new pair style's pair_coeff during the run is refused as such
        pats += [PAIR_NOT_SET, PAIR_COEFF_RUN]
    return alt(*pats)


# ----------------------------------------------------------------------------
# the cases


class Builder:
    def __init__(self, nps=(1, 2)):
        self.cases = []
        self.ids = set()
        self.nps = nps

    def add(self, cls, cid, text, expect, files=None, note="", budget=1.0):
        """One input, as one case per rank count (ids CLS.CID.npN); budget:
        its time limit in units of the runner's."""
        assert cls in CLASSES, cls
        assert isinstance(expect, Expect)
        for np in self.nps:
            full = f"{cls}.{cid}.np{np}"
            assert full not in self.ids, full
            self.ids.add(full)
            self.cases.append(F.Case(full, cls, text, expect, dict(files or {}), np, note, budget))


def run_every(steps, every, at, *cmds):
    """run steps pre no every M, the commands executed once, after step at
    (LAMMPS runs the every-commands after each chunk, the last included)."""
    once = " ".join(f"'{c}'" for c in cmds)
    return f"run             {steps} pre no every {every} \"if '$(step) == {at}' then {once}\"\n"


# -- 1. unfix-within ----------------------------------------------------------
# Partners removed or replaced during a run (run N pre no every M "...").
# The dependents are defined before the fix that is removed (LAMMPS keeps
# the lists of fixes by index during such a run: a fix after the removed
# one moves into its slot and is no longer called), and an inert fix pads
# the end of the list.  Thermo output names none of the fixes (LAMMPS'
# thermo would read a removed fix by its old index).
# Dropped (LAMMPS' own crash, no package style at fault): "unfix q" with
# fix q the last fix (LAMMPS calls the deleted fix through its lists), a
# pair_style lj/cut swapped in during a run (LAMMPS' lj/cut computes with
# the neighbor list it never requested).


def within_actions(system):
    """(action id, commands, expectation) for one system."""
    s, src = system, system.source
    qs = any(fid == "q" for fid, _ in s.fixes)
    gone = source_gone(s, qs)
    kw_src = rf"\b{src}\b|{re.escape(s.style)}"
    rcut, coeff, weaker = {"eq/contacts": ("3.0", "0.06 3.0", "0.03 3.0"),
                           "eq/substrate": ("1.5", "25.0 1.0", "12.5 1.0"),
                           "eq/meso": ("1.5", "20.0 1.0", "10.0 1.0")}[s.style]
    src_line = s.line(src).split(None, 1)[1]           # "ID group style args"
    # controls: commands that change nothing the styles hold
    out = [("noop", ["print noop"], ok()), ("thermo-modify", ["thermo_modify lost warn"], ok())]
    if gone != "()":
        out += [
            ("unfix-src", [f"unfix {src}"], err(gone, kw_src)),
            ("unfix-src-redefine", [f"unfix {src}", f"fix {src_line}"], err(gone, kw_src)),
            ("replace-src-same", [f"fix {src_line}"], err(gone, kw_src)),
            ("unfix-src-late", [f"unfix {src}"], err(gone, kw_src)),
        ]
        if s.style == "eq/contacts":
            out += [("replace-src-seed", [f"fix {src_line.replace(' 99 ', ' 7 ')}"], err(gone, kw_src)),
                    ("replace-src-kc", [f"fix {src_line.replace('eq/contacts 1.0', 'eq/contacts 2.0')}"],
                     err(gone, kw_src))]
    if s.pairkind != "none":
        out += [
            ("pair-elastic-again", [f"pair_style eq/elastic {rcut} check 1", f"pair_coeff * * {coeff}"],
             err(field_gone(s, True), r"eq/elastic")),
            ("pair-zero", [f"pair_style zero {rcut}", "pair_coeff * *"],
             (err if s.style == "eq/contacts" else err_or_ok)(field_gone(s, False), r"eq/elastic")),
            ("pair-hybrid", [f"pair_style hybrid/overlay eq/elastic {rcut} check 1 zero {rcut}",
                             f"pair_coeff * * eq/elastic {coeff}", "pair_coeff * * zero"],
             err(field_gone(s, True), r"eq/elastic")),
            ("pair-coeff", [f"pair_coeff * * {'eq/elastic ' if 'hybrid' in s.pairkind else ''}{weaker}"],
             err_or_ok(alt(PAIR_COEFF_RUN, field_gone(s, True)), r"eq/elastic|pair_coeff")),
        ]
    if qs:
        out += [
            ("unfix-q", ["unfix q"],
             err_or_ok(alt(QS_GONE, PAIR_AGAIN, PAIR_SRC_GONE), r"eq/quasistatic|eq/contacts")),
            ("replace-q", ["fix q all eq/quasistatic c"],
             err_or_ok(alt(QS_GONE, PAIR_AGAIN, PAIR_SRC_GONE, r"Fix \S+ eq/quasistatic"), r"eq/contacts")),
        ]
    if s.style != "eq/contacts":
        out.append(("unfix-integrator", ["unfix bd"],
                    err_or_ok(alt(PAIR_SRC_GONE, B_FIELD_GONE), r"eq/")))
    return out


def gen_unfix_within(b):
    systems = ([contacts_system(p, d) for p in ("elastic", "hybrid-zero", "hybrid-lj")
                for d in ("qs", "move")]
               + [contacts_system("none", "qs"), substrate_system("elastic"),
                  substrate_system("hybrid-zero"), meso_system("elastic"), meso_system("hybrid-zero")])
    thermal = contacts_system("none", "move", cargs=C_THERMAL)
    thermal.name += "-thermal"
    systems.append(thermal)
    field = contacts_system("elastic", "move", cargs=C_THERMAL_FIELD)
    field.name += "-thermal"
    systems.append(field)
    waits = contacts_system("elastic", "move", cargs=C_DELAY_FIELD)
    waits.name += "-delay"
    systems.append(waits)
    hops = substrate_system("elastic", S_THERMAL)
    hops.name += "-thermal"
    systems.append(hops)
    mt = meso_system("elastic", MP_ARGS.replace("reform gaussian 0.05 0.1", "reform delta 0.0")
                     + " grid 0.05 thermal 0.05 1.0 1.0 labels 8 aging log 0.05 1.0 rest 10")
    mt.name += "-thermal"
    systems.append(mt)
    for s in systems:
        for aid, cmds, exp in within_actions(s):
            every = 25 if aid.endswith("-late") else 10
            text = s.text(pad=True) + run_every(40, every, every, *cmds)
            b.add("unfix-within", f"{s.name}.{aid}", text, exp)


# -- 2. unfix-between ---------------------------------------------------------

QS_NOID = r"Fix \S+ eq/quasistatic: fix ID \S+ does not exist"
QS_WRONG = r"Fix \S+ eq/quasistatic: fix \S+ is a fix \S+, not eq/contacts"
PAIR_NEEDS = r"Pair style eq/elastic needs a fix eq/contacts"
PAIR_TWO = r"Pair style eq/elastic found \d+ fixes with coordinates"
QS_LEAVES = r"Fix eq/quasistatic: group \S+ leaves \d+ contacts of fix \S+"


# sum h and sum h^2 over the atoms (sum h = 0: the interaction only
# redistributes force).  sum |h| would be the natural scale of sum h and
# the measure of a field left behind, but compute reduce sumabs is newer
# than LAMMPS 2021; H_SCALE = sqrt(N sum h^2) >= sum |h| (Cauchy-Schwarz,
# N = count(all)) stands in for it in both.
H_THERMO = " c_hsum c_hsq"
H_SCALE = "sqrt(count(all)*c_hsq)"


def sum_h_zero():
    """The check sum h = 0, to 1e-9 of H_SCALE."""
    return check("sum_h", "c_hsum", "0", scale=H_SCALE)


def h_gone():
    """The check that no field is left: H_SCALE <= 1e-9."""
    return check("h_gone", H_SCALE, "0")


def sum_h_checks(system, col):
    """The computes of sum h and sum h^2 (thermo keywords H_THERMO)."""
    src = system.source
    return (f"compute         hsum all reduce sum f_{src}[{col}]\n"
            f"compute         hsq all reduce sumsq f_{src}[{col}]\n")


def between(system, cmds, *, run2="run 20", post="", pad=False, thermo=None, pre=""):
    return (system.text(pad=pad, thermo=thermo, computes=pre) + "run             20\n" + "".join(c + "\n" for c in cmds)
            + run2 + "\n" + post)


def gen_unfix_between(b):
    cls = "unfix-between"
    for pk in ("elastic", "hybrid-zero"):
        s = contacts_system(pk, "qs")
        sn = s.name
        pc = "pair_style eq/elastic 3.0 check 1\npair_coeff * * 0.06 3.0"
        b.add(cls, f"{sn}.unfix-c", between(s, ["unfix c"]), err(alt(QS_NOID, PAIR_NEEDS), r"\bc\b|eq/contacts"))
        b.add(cls, f"{sn}.unfix-c-move", between(s, ["unfix c", "fix c all move linear 1.0 0 0 units box"]),
              err(alt(QS_WRONG, PAIR_NEEDS), r"\bc\b.*move|move.*eq/contacts|eq/contacts"))
        b.add(cls, f"{sn}.unfix-c-substrate",
              between(s, ["unfix c", "fix c all eq/substrate 1.0 sawtooth 1.0"]),
              err(QS_WRONG, r"eq/substrate"))
        b.add(cls, f"{sn}.unfix-c-other-id",
              between(s, ["unfix c", f"fix c2 all eq/contacts {C_ARGS}"]),
              err(QS_NOID, r"\bc\b"))
        t = "step pe f_c[7] f_q" + H_THERMO
        post = (check("contacts", "f_c[7]", "80") + sum_h_zero())
        b.add(cls, f"{sn}.redefine-c-same",
              between(s, ["unfix c", f"fix c all eq/contacts {C_ARGS}"], thermo=t, post=post,
                      pre=sum_h_checks(s, 7)), ok())
        b.add(cls, f"{sn}.redefine-c-seed",
              between(s, ["unfix c", "fix c all eq/contacts 1.0 7 threshold uniform 0.75 1.25"], thermo=t,
                      post=post, pre=sum_h_checks(s, 7)), ok())
        b.add(cls, f"{sn}.redefine-c-in-place",
              between(s, [f"fix c all eq/contacts {C_ARGS} reform uniform 0.0 0.1"], thermo=t, post=post,
                      pre=sum_h_checks(s, 7)), ok())
        b.add(cls, f"{sn}.redefine-q",
              between(s, ["unfix q", "fix q all eq/quasistatic c max 0.05"], thermo=t,
                      post=post + check("q_advanced", "f_q > 0", "1"), pre=sum_h_checks(s, 7)), ok())
        b.add(cls, f"{sn}.unfix-q-run",
              between(s, ["unfix q"], thermo="step pe f_c[7]" + H_THERMO, post=post,
                      pre=sum_h_checks(s, 7)), ok())
        b.add(cls, f"{sn}.pair-zero",
              between(s, ["pair_style zero 3.0", "pair_coeff * *"], thermo=t, pre=sum_h_checks(s, 7),
                      post=h_gone()), ok())
        b.add(cls, f"{sn}.pair-none",
              between(s, ["pair_style none", "comm_modify cutoff 0.5"], thermo=t, pre=sum_h_checks(s, 7),
                      post=h_gone()), ok())
        other = ("pair_style hybrid/overlay eq/elastic 3.0 check 1 zero 3.0\npair_coeff * * eq/elastic 0.06 3.0\n"
                 "pair_coeff * * zero") if pk == "elastic" else pc
        b.add(cls, f"{sn}.pair-swap", between(s, [other], thermo=t, pre=sum_h_checks(s, 7), post=post), ok())
        b.add(cls, f"{sn}.pair-rcut", between(s, [pc.replace("3.0 check", "2.0 check")], thermo=t,
                                               pre=sum_h_checks(s, 7), post=post), ok())
        b.add(cls, f"{sn}.pair-coeff",
              between(s, ["pair_coeff * * 0.03 2.0" if pk == "elastic" else "pair_coeff * * eq/elastic 0.03 2.0"],
                      thermo=t, pre=sum_h_checks(s, 7), post=post), ok())
        b.add(cls, f"{sn}.q-group-partial",
              between(s, ["group half id <= 40", "unfix q", "fix q half eq/quasistatic c"]),
              err(QS_LEAVES, r"\bc\b"))
        b.add(cls, f"{sn}.second-source",
              between(s, ["fix s2 all eq/substrate 1.0 sawtooth 1.0"]),
              err(PAIR_TWO, r"eq/contacts.*eq/substrate|eq/substrate.*eq/contacts"))
        b.add(cls, f"{sn}.unfix-c-pre-no",
              between(s, ["unfix c"], run2="run 20 pre no", pad=True),
              err(alt(QS_GONE, PAIR_SRC_GONE, PAIR_AGAIN, QS_NOID, PAIR_NEEDS), r"\bc\b|eq/contacts"))
        b.add(cls, f"{sn}.pair-zero-pre-no",
              between(s, ["pair_style zero 3.0", "pair_coeff * *"], run2="run 20 pre no", pad=True),
              err(field_gone(s, False), r"eq/elastic"))
    s = contacts_system("none", "qs")
    b.add(cls, f"{s.name}.unfix-c", between(s, ["unfix c"]), err(QS_NOID, r"\bc\b"))
    b.add(cls, f"{s.name}.redefine-c", between(s, ["unfix c", f"fix c all eq/contacts {C_ARGS}"],
                                              post=check("contacts", "f_c[7]", "80"),
                                              thermo="step f_c[7] f_q"), ok())
    b.add(cls, f"{s.name}.pair-added",
          between(s, ["pair_style eq/elastic 3.0 check 1", "pair_coeff * * 0.06 3.0"], thermo="step pe f_c[7]"),
          ok())
    s = contacts_system("elastic", "move")
    b.add(cls, f"{s.name}.unfix-c", between(s, ["unfix c"]), err(PAIR_NEEDS, r"eq/contacts"))
    b.add(cls, f"{s.name}.unfix-c-new-id", between(s, ["unfix c", f"fix c2 all eq/contacts {C_ARGS}"],
                                                  thermo="step pe"), ok())
    for s, col in ((substrate_system("elastic"), 8), (substrate_system("hybrid-zero"), 8),
                   (meso_system("elastic"), 0), (meso_system("hybrid-zero"), 0)):
        src, sn, n = s.source, s.name, s.natoms
        ncount = f"f_{src}[10]" if s.style == "eq/substrate" else f"f_{src}[6]"
        line = s.line(src).split(None, 1)[1]
        pre = sum_h_checks(s, col) if col else ""
        t = f"step pe {ncount}" + (H_THERMO if col else "")
        post = check("blocks", ncount, str(n)) + (sum_h_zero() if col else "")
        b.add(cls, f"{sn}.unfix-src", between(s, [f"unfix {src}"]), err(PAIR_NEEDS, r"eq/substrate|eq/meso"))
        b.add(cls, f"{sn}.redefine-src", between(s, [f"unfix {src}", f"fix {line}"], thermo=t, pre=pre,
                                                 post=post), ok())
        b.add(cls, f"{sn}.redefine-src-in-place", between(s, [f"fix {line}"], thermo=t, pre=pre, post=post),
              ok())
        b.add(cls, f"{sn}.unfix-integrator", between(s, ["unfix bd"], thermo=t, pre=pre, post=post), ok())
        b.add(cls, f"{sn}.pair-zero", between(s, ["pair_style zero 1.5", "pair_coeff * *"], thermo=t, pre=pre,
                                              post=check("blocks", ncount, str(n))
                                              + (h_gone() if col else "")), ok())
        other = "eq/meso " + MP_ARGS if s.style == "eq/substrate" else "eq/substrate " + S_ARGS
        b.add(cls, f"{sn}.src-other-style", between(s, [f"unfix {src}", f"fix {src} all {other}"],
                                                    thermo="step pe"), ok())
        b.add(cls, f"{sn}.second-source",
              between(s, [f"fix c2 all eq/contacts {C_ARGS}"]),
              err(PAIR_TWO, rf"eq/contacts.*{s.style}|{s.style}.*eq/contacts"))
        b.add(cls, f"{sn}.unfix-src-pre-no", between(s, [f"unfix {src}"], run2="run 20 pre no", pad=True),
              err(alt(PAIR_SRC_GONE, PAIR_NEEDS), rf"\b{src}\b|{s.style}"))


# -- 3. restart-args ----------------------------------------------------------
# write_restart, clear, read_restart and the stateful fix re-specified
# with one argument changed.  Shaping arguments (what the stored state
# means) are an error naming the keyword and the restart; the others may
# change.  Unchanged arguments continue the uninterrupted run (in-script
# check against the value of the run that went on after writing).

def restart_case(system, new_line, refs, steps=30, thermo=None):
    """system runs `steps`, writes a restart file and runs `steps` more
    (the reference values refs: [(name, expr)]), then reads the file, defines
    the source fix as new_line and runs `steps`; the checks compare with
    the reference when refs is not empty."""
    src = system.source
    fixes = "".join((new_line if fid == src else line) + "\n" for fid, line in system.fixes)
    text = (system.text(thermo=thermo) + f"run             {steps}\nwrite_restart   r.restart\n"
            f"run             {steps}\n" + "".join(capture(f"ref_{i}", e) for i, (_, e) in enumerate(refs))
            + "clear\nread_restart    r.restart\n" + system.after_restart(fixes, thermo=thermo)
            + f"run             {steps}\n"
            + "".join(check(f"restart_{n}", e, f"v_ref_{i}", tol=1e-10) for i, (n, e) in enumerate(refs)))
    return text


def restart_err(style, kw):
    return err(rf"Fix \S+ {style}", rf"\b{kw}\b.*restart|restart.*\b{kw}\b")


def gen_restart_args(b):
    cls = "restart-args"
    files = dict(F.GOOD_FILES)
    # fix eq/contacts (nve/noforce: the velocities are in the file)
    base = contacts_system("none", "nve")
    fc = "fix             c all eq/contacts "
    shaping = [
        ("kc", "kc", "2.0 99 threshold uniform 0.75 1.25"),
        ("threshold-style", "threshold", "1.0 99 threshold gaussian 1.0 0.1"),
        ("threshold-lo", "threshold", "1.0 99 threshold uniform 0.7 1.25"),
        ("threshold-hi", "threshold", "1.0 99 threshold uniform 0.75 1.3"),
        ("threshold-realistic", "threshold", "1.0 99 threshold realistic 1.0"),
        ("threshold-table", "threshold", "1.0 99 threshold table th.table GOOD"),
        ("reform-delta", "reform", "1.0 99 threshold uniform 0.75 1.25 reform delta 0.1"),
        ("reform-uniform", "reform", "1.0 99 threshold uniform 0.75 1.25 reform uniform 0.0 0.1"),
        ("reform-none", "reform", "1.0 99 threshold uniform 0.75 1.25 reform none"),
        ("stiffness-uniform", "stiffness", "1.0 99 threshold uniform 0.75 1.25 stiffness uniform 0.5 1.5"),
        ("stiffness-gaussian", "stiffness", "1.0 99 threshold uniform 0.75 1.25 stiffness gaussian 1.0 0.1"),
        ("dir", "dir", "1.0 99 threshold uniform 0.75 1.25 dir y"),
    ]
    for aid, kw, args in shaping:
        b.add(cls, f"contacts.{aid}", restart_case(base, fc + args, []), restart_err("eq/contacts", kw), files)
    rich = ("1.0 99 threshold uniform 0.75 1.25 reform uniform 0.0 0.1 stiffness uniform 0.5 1.5")
    rbase = contacts_system("none", "nve", cargs=rich)
    b.add(cls, "contacts.stiffness-dropped", restart_case(
        rbase, fc + "1.0 99 threshold uniform 0.75 1.25 reform uniform 0.0 0.1", []),
        restart_err("eq/contacts", "stiffness"))
    b.add(cls, "contacts.reform-dropped", restart_case(
        rbase, fc + "1.0 99 threshold uniform 0.75 1.25 stiffness uniform 0.5 1.5", []),
        restart_err("eq/contacts", "reform"))
    refs = [("F", "f_c[1]"), ("breaks", "f_c[3]"), ("attached", "f_c[4]")]
    th = "step pe f_c[1] f_c[3]"
    b.add(cls, "contacts.seed", restart_case(base, fc + "1.0 7 threshold uniform 0.75 1.25", [], thermo=th),
          ok(warn=r"\bseed\b"))
    b.add(cls, "contacts.seed-rich", restart_case(rbase, fc + rich.replace(" 99 ", " 12345 "), [], thermo=th),
          ok(warn=r"\bseed\b"))
    free = [("crossing", f"{C_ARGS} crossing step", False), ("start", f"{C_ARGS} start reform", False),
            ("reform_as", f"{C_ARGS} reform_as stretch", True), ("avalanches", f"{C_ARGS} avalanches a.dat", True)]
    for aid, args, same in free:
        b.add(cls, f"contacts.{aid}", restart_case(base, fc + args, refs if same else [], thermo=th), ok())
    b.add(cls, "contacts.unchanged", restart_case(base, fc + C_ARGS, refs, thermo=th), ok())
    # the thermal keywords change the per-atom layout: added or dropped is
    # an error naming them; their values may change (a temperature jump)
    tbase = contacts_system("none", "nve", cargs=C_THERMAL)
    b.add(cls, "contacts.thermal-added", restart_case(base, fc + C_THERMAL, []),
          err(r"Fix \S+ eq/contacts", r"restart.*\bthermal\b"), files)
    b.add(cls, "contacts.thermal-dropped", restart_case(tbase, fc + C_ARGS, []),
          err(r"Fix \S+ eq/contacts", r"restart.*\bthermal\b"), files)
    b.add(cls, "contacts.thermal-unchanged", restart_case(tbase, fc + C_THERMAL, refs, thermo=th), ok())
    b.add(cls, "contacts.thermal-values", restart_case(
        tbase, fc + C_ARGS + " thermal 0.3 1.0 2.0 aging exp 0.1 3.0 delay fixed 0.2 rest 5", [],
        thermo=th), ok())
    b.add(cls, "contacts.unchanged-rich", restart_case(rbase, fc + rich, refs, thermo=th), ok())
    qs = contacts_system("elastic", "qs")
    b.add(cls, "contacts-elastic-qs.unchanged",
          restart_case(qs, fc + C_ARGS, refs + [("X", "f_q")], thermo=th + " f_q"), ok())
    b.add(cls, "contacts-elastic-qs.kc", restart_case(qs, fc + "2.0 99 threshold uniform 0.75 1.25", []),
          restart_err("eq/contacts", "kc"))
    hy = contacts_system("hybrid-zero", "nve")
    b.add(cls, "contacts-hybrid.unchanged", restart_case(hy, fc + C_ARGS, refs, thermo=th), ok())
    b.add(cls, "contacts-hybrid.threshold", restart_case(hy, fc + "1.0 99 threshold gaussian 1.0 0.1", []),
          restart_err("eq/contacts", "threshold"))

    # fix eq/substrate
    fs = "fix             sub all eq/substrate "
    sbase = substrate_system("elastic")
    shaping = [
        ("kc", "kc", S_ARGS.replace("1.0 sawtooth", "2.0 sawtooth")),
        ("shape", "shape|smooth|sawtooth", S_ARGS.replace("sawtooth", "smooth")),
        ("uc", "uc|sawtooth", S_ARGS.replace("sawtooth 1.0", "sawtooth 1.5")),
        ("table", "table|shape", S_ARGS.replace("sawtooth 1.0", "table sub.table BLOCK")),
        ("dir", "dir", S_ARGS + " dir y"),
        ("reverse", "reverse", S_ARGS + " reverse break"),
        ("disorder-added", "disorder", S_ARGS + S_DISORDER),
    ]
    for aid, kw, args in shaping:
        b.add(cls, f"substrate.{aid}", restart_case(sbase, fs + args, []),
              restart_err("eq/substrate", f"(?:{kw})"), files)
    # disorder in the file (the quenched factors of the blocks)
    dbase = substrate_system("elastic", S_ARGS + S_DISORDER)
    for aid, new in [("disorder-style", "uniform 0.9 1.1 9"), ("disorder-sd", "gaussian 1.0 0.1 9"),
                     ("disorder-seed", "gaussian 1.0 0.05 10"), ("disorder-constant", "constant 9")]:
        b.add(cls, f"substrate.{aid}", restart_case(dbase, fs + S_ARGS + " disorder " + new, []),
              restart_err("eq/substrate", "disorder"))
    b.add(cls, "substrate.disorder-dropped", restart_case(dbase, fs + S_ARGS, []),
          restart_err("eq/substrate", "disorder"))
    refs = [("u", "f_sub[5]"), ("Fs", "f_sub[6]"), ("stage", "f_sub[2]")]
    th = "step pe f_sub[5] f_sub[6]"
    free = [("crossing", S_ARGS + " crossing step", False),
            ("drive-K", S_ARGS.replace("drive 0.07", "drive 0.1"), False),
            ("drive-v", S_ARGS.replace("0.07 0.01", "0.07 0.02"), False),
            ("stage", S_ARGS.replace("stage 14.5", "stage 3.0"), True)]
    for aid, args, same in free:
        b.add(cls, f"substrate.{aid}", restart_case(sbase, fs + args, refs if same else [], thermo=th), ok())
    b.add(cls, "substrate.unchanged", restart_case(sbase, fs + S_ARGS, refs, thermo=th), ok())
    # rate (velocity strengthening) stores nothing: added, dropped or
    # changed at a restart the run goes on; unchanged it continues the run
    # (fix brownian: the velocities it reads are in the file)
    S_RATE = S_ARGS + " rate 0.01 1e-3"
    rbase = substrate_system("elastic", S_RATE)
    b.add(cls, "substrate.rate-added", restart_case(sbase, fs + S_RATE, [], thermo=th), ok())
    b.add(cls, "substrate.rate-dropped", restart_case(rbase, fs + S_ARGS, [], thermo=th), ok())
    b.add(cls, "substrate.rate-values", restart_case(rbase, fs + S_ARGS + " rate 0.02 2e-3", [],
                                                     thermo=th), ok())
    b.add(cls, "substrate.rate-unchanged", restart_case(rbase, fs + S_RATE, refs, thermo=th), ok())
    b.add(cls, "substrate.unchanged-disorder", restart_case(dbase, fs + S_ARGS + S_DISORDER, refs, thermo=th),
          ok())
    b.add(cls, "substrate-hybrid.unchanged",
          restart_case(substrate_system("hybrid-zero"), fs + S_ARGS, refs, thermo=th), ok())
    # thermal hops add three columns per block (budget, life, hops): added
    # or dropped is an error naming thermal; T, eps_a, omega, barrier may
    # change (a temperature jump); another seed keys the budgets of the new
    # lives (documented: the budgets drawn are kept)
    sbreak = substrate_system("elastic", S_ARGS + " reverse break")
    tsub = substrate_system("elastic", S_THERMAL)
    href = refs + [("hops", "f_sub[11]")]
    hth = th + " f_sub[11]"
    b.add(cls, "substrate.thermal-added", restart_case(sbreak, fs + S_THERMAL, []),
          err(r"Fix \S+ eq/substrate", r"\bthermal\b"), files)
    b.add(cls, "substrate.thermal-dropped", restart_case(tsub, fs + S_ARGS + " reverse break", []),
          err(r"Fix \S+ eq/substrate", r"\bthermal\b"), files)
    b.add(cls, "substrate.thermal-unchanged", restart_case(tsub, fs + S_THERMAL, href, thermo=hth), ok())
    b.add(cls, "substrate.thermal-values", restart_case(
        tsub, fs + S_THERMAL.replace("thermal 0.3 1.0 5.0", "thermal 0.2 2.0 3.0 barrier 1 0.5"), [],
        thermo=hth), ok())
    b.add(cls, "substrate.thermal-seed", restart_case(
        tsub, fs + S_THERMAL.replace("seed 5", "seed 6"), [], thermo=hth), ok())
    b.add(cls, "substrate-hybrid.kc", restart_case(
        substrate_system("hybrid-zero"), fs + S_ARGS.replace("1.0 sawtooth", "0.5 sawtooth"), []),
        restart_err("eq/substrate", "kc"))

    # fix eq/meso (rigid blocks with screening; a coupled chain)
    fm = "fix             m all eq/meso "
    mbase = meso_system("none")
    shaping = [
        ("Nlambda", "Nlambda", MS_ARGS.replace("100 1.0", "150 1.0", 1)),
        ("kc", "kc", MS_ARGS.replace("100 1.0", "100 2.0", 1)),
        ("threshold-style", "threshold", MS_ARGS.replace("uniform 0.75 1.25", "gaussian 1.0 0.1")),
        ("threshold-lo", "threshold", MS_ARGS.replace("uniform 0.75 1.25", "uniform 0.5 1.25")),
        ("threshold-hi", "threshold", MS_ARGS.replace("uniform 0.75 1.25", "uniform 0.75 1.5")),
        ("reform-delta", "reform", MS_ARGS.replace("delta 0.0", "delta 0.1")),
        ("reform-none", "reform", MS_ARGS.replace("delta 0.0", "none")),
        ("grid", "grid", MS_ARGS.replace("grid 0.02", "grid 0.01")),
        ("grid-default", "grid", MS_ARGS.replace(" grid 0.02", "")),
        ("dir", "dir", MS_ARGS + " dir y"),
    ]
    for aid, kw, args in shaping:
        b.add(cls, f"meso.{aid}", restart_case(mbase, fm + args, []), restart_err("eq/meso", kw))
    refs = [("F", "f_m[1]"), ("X", "f_m[4]"), ("Gamma", "f_m[2]")]
    th = "step f_m[1] f_m[2] f_m[4]"
    free = [("crossing", MS_ARGS + " crossing step", False), ("start", MS_ARGS + " start reform", True),
            ("window", MS_ARGS + " window 0.5", False), ("check", MS_ARGS + " check 10", True),
            ("screen", MS_ARGS.replace("screen 0.001", "screen 0.0015"), False),
            ("drive", MS_ARGS + " drive 10.0 0.05", False)]
    for aid, args, same in free:
        b.add(cls, f"meso.{aid}", restart_case(mbase, fm + args, refs if same else [], thermo=th), ok())
    b.add(cls, "meso.unchanged", restart_case(mbase, fm + MS_ARGS, refs, thermo=th), ok())
    # at T > 0: another kind of state (thermal added or dropped), and the
    # thermal values are in the signature (the stored panels and
    # histories belong to them); crossing and window may change
    tm = meso_system("none", MS_THERMAL)
    tm.name += "-thermal"
    for aid, args, expect in [
            ("thermal-added", MS_THERMAL, err(r"Fix \S+ eq/meso", r"\bthermal\b")),
            ("T", MS_THERMAL.replace("thermal 0.05", "thermal 0.1"), restart_err("eq/meso", "thermal")),
            ("labels", MS_THERMAL.replace("labels 8", "labels 16"), restart_err("eq/meso", "thermal"))]:
        b.add(cls, f"meso-thermal.{aid}", restart_case(mbase if aid == "thermal-added" else tm,
                                                       fm + args, []), expect)
    b.add(cls, "meso-thermal.dropped", restart_case(tm, fm + MS_ARGS, []),
          err(r"Fix \S+ eq/meso", r"\bthermal\b"))
    b.add(cls, "meso-thermal.unchanged", restart_case(tm, fm + MS_THERMAL, refs, thermo=th), ok())
    b.add(cls, "meso-thermal.window", restart_case(tm, fm + MS_THERMAL + " window 0.5", [], thermo=th),
          ok())
    pm = meso_system("elastic")
    b.add(cls, "meso-elastic.unchanged",
          restart_case(pm, fm + MP_ARGS, [("F", "f_m[1]"), ("X", "f_m[4]"), ("stage", "f_m[7]")],
                       thermo="step pe f_m[1] f_m[4]"), ok())
    b.add(cls, "meso-elastic.Nlambda", restart_case(pm, fm + MP_ARGS.replace("100 1.0", "50 1.0", 1), []),
          restart_err("eq/meso", "Nlambda"))


# -- 4. restart-garbled -------------------------------------------------------
# A restart file written by the case, garbled by garble.py (run from the
# input with LAMMPS' shell command, on rank 0, which alone reads the file)
# and read again.  Truncated files and NaN/inf in the styles' records must
# give an ERROR; other garbled values an ERROR or a run with finite output.

GARBLE_PY = '''\
"""Garble a LAMMPS restart file in place (misuse_inputs.py)."""
import random, struct, sys

path, mode, args = sys.argv[1], sys.argv[2], sys.argv[3:]
d = bytearray(open(path, "rb").read())


def lstring(s):
    b = s.encode() + b"\\0"
    return struct.pack("i", len(b)) + b


def find_record(name, nth):
    """offset just after the nth (0: global, 1: per-atom list) length-prefixed name"""
    pos, k = -1, -1
    while k < nth:
        pos = d.find(lstring(name), pos + 1)
        if pos < 0:
            sys.exit(f"garble.py: {name} #{nth} not in {path}")
        k += 1
    return pos + len(lstring(name))


def dbl(o):
    return struct.unpack_from("d", d, o)[0]


def atom_records():
    """offsets of the atoms' restart records (buf[0] = length m, then x, tag,
    type, mask, image, v, then the fixes' values, each fix's first the count)"""
    start = find_record(sys_style, 1)
    n = len(d)
    for o in range(start, n - 24):
        m = dbl(o)
        if not (12 <= m <= 400 and m == int(m)):
            continue
        m = int(m)
        if o + 8 * m + 8 <= n and dbl(o + 8 * m) == m and o + 16 * m + 8 <= n and dbl(o + 16 * m) == m:
            break
    else:
        sys.exit("garble.py: no atom records found")
    recs, o = [], o
    while o + 8 <= n:
        if dbl(o) == m and o + 8 * m <= n:
            recs.append(o)
            o += 8 * m
        else:
            o += 1
    return recs, m


def value(s):
    return float(s)


sys_style = args[0] if args else ""
if mode == "truncate":
    d = d[: int(len(d) * float(args[0]))]
elif mode == "cut-after":            # style nth extra-bytes
    d = d[: find_record(args[0], int(args[1])) + int(args[2])]
elif mode == "global":               # style index value: a double of the fix's global record
    o = find_record(args[0], 0) + 4 + 8 * int(args[1])
    struct.pack_into("d", d, o, value(args[2]))
elif mode == "global-size":          # style value: the byte count of the global record
    struct.pack_into("i", d, find_record(args[0], 0), int(args[1]))
elif mode == "flip":                 # style nth offset: invert one byte after the name
    d[find_record(args[0], int(args[1])) + int(args[2])] ^= 0xFF
elif mode == "peratom":              # style column value atom|all: the fix's per-atom value
    recs, m = atom_records()
    col, val = int(args[1]), value(args[2])
    pick = recs if args[3] == "all" else [recs[int(args[3]) % len(recs)]]
    for o in pick:
        struct.pack_into("d", d, o + 8 * (11 + col), val)
elif mode == "atom-length":          # style value: the record length of one atom
    recs, m = atom_records()
    struct.pack_into("d", d, recs[len(recs) // 2], value(args[1]))
elif mode == "random":               # style seed count: invert bits of the fix's per-atom values
    recs, m = atom_records()         # (x, tag, type, ... are LAMMPS' own: not touched)
    rnd = random.Random(int(args[1]))
    for _ in range(int(args[2])):
        o = rnd.choice(recs) + 8 * rnd.randrange(12, m)
        d[o + rnd.randrange(8)] ^= 1 << rnd.randrange(8)
elif mode == "rename":               # old new: every length-prefixed string old becomes new
    d = bytearray(bytes(d).replace(lstring(args[0]), lstring(args[1])))
else:
    sys.exit("garble.py: unknown mode " + mode)
open(path, "wb").write(bytes(d))
'''


# per-atom values: (case, column (1-based, after the count), value, atom index or all, kind)
PERATOM_VALUES = {
    "eq/contacts": [   # stretch, threshold, force, breaks, stiffness, anchor, field
        ("stretch-nan", 1, "nan", "0", "robust"), ("threshold-nan", 2, "nan", "0", "error"),
        ("threshold-inf", 2, "inf", "all", "error"), ("threshold-negative", 2, "-1", "all", "robust"),
        ("threshold-huge", 2, "1e300", "3", "robust"), ("force-nan", 3, "nan", "all", "robust"),
        ("breaks-nan", 4, "nan", "0", "error"), ("breaks-huge", 4, "1e300", "0", "error"),
        ("breaks-negative", 4, "-1", "all", "robust"), ("breaks-fraction", 4, "2.5", "all", "robust"),
        ("stiffness-nan", 5, "nan", "0", "error"), ("stiffness-inf", 5, "inf", "0", "error"),
        ("stiffness-zero", 5, "0", "all", "robust"), ("stiffness-negative", 5, "-1", "all", "robust"),
        ("anchor-nan", 6, "nan", "0", "error"), ("anchor-inf", 6, "inf", "all", "error"),
        ("anchor-huge", 6, "1e300", "2", "robust"), ("field-nan", 7, "nan", "all", "robust")],
    "eq/substrate": [  # u, F_s, spring force, kc, disorder, well origin, site, field
        ("u-nan", 1, "nan", "0", "robust"), ("fsub-nan", 2, "nan", "all", "robust"),
        ("kc-nan", 4, "nan", "0", "error"), ("kc-inf", 4, "inf", "all", "error"),
        ("kc-negative", 4, "-1", "all", "robust"), ("disorder-nan", 5, "nan", "0", "error"),
        ("disorder-zero", 5, "0", "all", "robust"), ("origin-nan", 6, "nan", "0", "error"),
        ("origin-inf", 6, "inf", "all", "error"), ("origin-fraction", 6, "0.5", "all", "robust"),
        ("site-nan", 7, "nan", "0", "error"), ("site-inf", 7, "inf", "all", "error"),
        ("site-huge", 7, "1e300", "0", "robust"), ("field-nan", 8, "nan", "all", "robust")],
    "eq/meso": [       # X, F, rate, eps, spring force, attached, site, flag, then the ME state
        ("X-nan", 1, "nan", "0", "robust"), ("rate-nan", 3, "nan", "0", "error"),
        ("rate-negative", 3, "-1", "all", "robust"), ("eps-nan", 4, "nan", "all", "robust"),
        ("attached-two", 6, "2", "all", "robust"), ("site-nan", 7, "nan", "0", "error"),
        ("site-inf", 7, "inf", "all", "error"), ("flag-nan", 8, "nan", "0", "error"),
        ("state-9-nan", 9, "nan", "0", "error"), ("state-12-nan", 12, "nan", "all", "error"),
        ("state-12-huge", 12, "1e300", "all", "robust")],
}


def garbled_case(system, garble, new_fixes=None, first="run             20\n"):
    """system runs, writes r.restart; garble.py changes it; the file is
    read and the system's fixes defined again (or new_fixes)."""
    py = sys.executable or "/usr/bin/python3"
    fixes = new_fixes if new_fixes is not None else system.fix_lines()
    return (system.text() + first + "write_restart   r.restart\n"
            + f"shell           {py} garble.py r.restart {garble}\n"
            + "clear\nread_restart    r.restart\n" + system.after_restart(fixes) + "run             20\n")


RESTART_ERR = r"restart|read_restart|file"


def gen_restart_garbled(b):
    cls = "restart-garbled"
    files = {"garble.py": GARBLE_PY}
    thermal = contacts_system("none", "nve", cargs=C_THERMAL)
    systems = [contacts_system("elastic", "nve"), substrate_system("elastic"), meso_system("none"),
               thermal]
    for s in systems:
        tag, style = s.style.split("/")[1], s.style
        if s is thermal:
            tag += "-thermal"
        for frac in ("0.05", "0.2", "0.4", "0.6", "0.8", "0.97"):
            b.add(cls, f"{tag}.truncate-{frac}", garbled_case(s, f"truncate {frac}"), err(RESTART_ERR), files)
        b.add(cls, f"{tag}.cut-in-global", garbled_case(s, f"cut-after {style} 0 6"), err(RESTART_ERR), files)
        b.add(cls, f"{tag}.cut-in-peratom-list", garbled_case(s, f"cut-after {style} 1 2"), err(RESTART_ERR),
              files)
        for off in (4, 9, 11, 12, 19):     # bytes of the first two doubles (11, 19: sign and exponent)
            b.add(cls, f"{tag}.flip-global-{off}", garbled_case(s, f"flip {style} 0 {off}"),
                  robust(RESTART_ERR), files)
        b.add(cls, f"{tag}.flip-peratom-size", garbled_case(s, f"flip {style} 1 1"), robust(RESTART_ERR), files)
        b.add(cls, f"{tag}.global-size", garbled_case(s, f"global-size {style} 4"), robust(RESTART_ERR), files)
        # (a garbled record length of the atoms is LAMMPS' own field: on 2 ranks
        # LAMMPS' read_restart hangs with it; not a case)
        for seed in (1, 2):
            b.add(cls, f"{tag}.random-{seed}", garbled_case(s, f"random {style} {seed} 40"),
                  robust(RESTART_ERR), files)
        # the fix's per-atom count and values (error: NaN/inf in a value the
        # fix keeps; robust: finite values, and values it derives anew)
        for aid, col, val, who, kind in [("count-small", 0, "3", "all", "error"),
                                         ("count-huge", 0, "1e9", "0", "error"),
                                         ("count-nan", 0, "nan", "0", "error"),
                                         ("count-negative", 0, "-2", "all", "error")] + PERATOM_VALUES[style]:
            exp = err(RESTART_ERR + r"|nan|finite|not a number|" + re.escape(style), r".") if kind == "error" \
                else robust(RESTART_ERR)
            b.add(cls, f"{tag}.peratom-{aid}", garbled_case(s, f"peratom {style} {col} {val} {who}"), exp, files)
    # two fixes with per-atom records: the first one's count locates the second's
    two = System("two-fixes", box(), "comm_modify     cutoff 2.0\n", "neighbor        0.5 bin\n",
                 [("c", f"fix             c left eq/contacts {C_ARGS}"),
                  ("sub", "fix             sub right eq/substrate 1.0 sawtooth 1.0"),
                  ("m", "fix             m all nve/noforce")],
                 "velocity        all set 1.0 0.0 0.0 units box\ntimestep        0.05\n", "c", "eq/contacts",
                 "none", 80)
    two.atoms += "group           left id <= 40\ngroup           right id > 40\n"
    for aid, val in [("small", "3"), ("huge", "1e9"), ("nan", "nan"), ("negative", "-2"), ("zero", "0")]:
        b.add(cls, f"two-fixes.count-{aid}", garbled_case(two, f"peratom eq/contacts 0 {val} all"),
              err(RESTART_ERR + r"|eq/contacts|eq/substrate"), files)
    b.add(cls, "two-fixes.control", garbled_case(two, "truncate 1.0"), ok(), files)
    # global records: the contacts' total breaks and seed, the stage of the blocks
    s = systems[0]
    for aid, idx, val, kind in [("breaks-nan", 0, "nan", "error"), ("breaks-inf", 0, "inf", "error"),
                                ("breaks-negative", 0, "-5", "robust"), ("breaks-huge", 0, "1e300", "error"),
                                ("seed-nan", 1, "nan", "error"), ("seed-zero", 1, "0", "robust"),
                                ("seed-fraction", 1, "99.5", "robust"), ("seed-huge", 1, "1e300", "error")]:
        exp = err(RESTART_ERR + r"|eq/contacts") if kind == "error" else robust(RESTART_ERR)
        b.add(cls, f"contacts.global-{aid}", garbled_case(s, f"global eq/contacts {idx} {val}"), exp, files)
    for s in systems[1:]:
        tag, style = s.style.split("/")[1], s.style
        for aid, idx, val, kind in [("0-nan", 0, "nan", "error"), ("1-inf", 1, "inf", "error"),
                                    ("2-nan", 2, "nan", "error"), ("2-three", 2, "3", "robust"),
                                    ("3-nan", 3, "nan", "error")]:
            exp = err(RESTART_ERR + "|" + re.escape(style)) if kind == "error" else robust(RESTART_ERR)
            b.add(cls, f"{tag}.global-{aid}", garbled_case(s, f"global {style} {idx} {val}"), exp, files)
    # per-atom records of one style read by a fix of another style or ID
    sc, ss, sm = systems[:3]
    for aid, s, old, new, fixes in [
        ("contacts-as-substrate", sc, "eq/contacts", "eq/substrate",
         "fix c all eq/substrate 1.0 sawtooth 1.0\nfix m all nve/noforce\n"),
        ("contacts-as-meso", sc, "eq/contacts", "eq/meso",
         f"fix c all eq/meso {MS_ARGS}\nfix m all nve/noforce\n"),
        ("substrate-as-contacts", ss, "eq/substrate", "eq/contacts",
         f"fix bd all brownian 1.0 1 rng none gamma_t 100.0\nfix sub all eq/contacts {C_ARGS}\n"),
        ("substrate-as-meso", ss, "eq/substrate", "eq/meso",
         f"fix bd all brownian 1.0 1 rng none gamma_t 100.0\nfix sub all eq/meso {MP_ARGS}\n"),
        ("meso-as-substrate", sm, "eq/meso", "eq/substrate",
         "fix mv all nve/noforce\nfix m all eq/substrate 1.0 sawtooth 1.0\n"),
        ("meso-as-contacts", sm, "eq/meso", "eq/contacts",
         f"fix mv all nve/noforce\nfix m all eq/contacts {C_ARGS}\n"),
    ]:
        b.add(cls, f"rename.{aid}", garbled_case(s, f"rename {old} {new}", new_fixes=fixes),
              err(RESTART_ERR + r"|values per|size", r"."), files)
    b.add(cls, "rename.contacts-id", garbled_case(sc, "rename c d", new_fixes=(
        f"fix d all eq/contacts {C_ARGS}\nfix m all nve/noforce\n")), ok(), files)
    # data files: garbled, and two atoms at one place
    gen_data_files(b)


def data_file(points, natoms=None, box=(0, 10, -2, 2), extra_atoms="", header_extra=""):
    n = len(points) if natoms is None else natoms
    rows = "".join(f"{i + 1} 1 {x} {y} 0.0\n" for i, (x, y) in enumerate(points)) + extra_atoms
    return (f"LAMMPS data file (misuse_inputs.py)\n\n{n} atoms\n1 atom types\n{header_extra}\n"
            f"{box[0]} {box[1]} xlo xhi\n{box[2]} {box[3]} ylo yhi\n-0.5 0.5 zlo zhi\n\n"
            f"Masses\n\n1 1.0\n\nAtoms # atomic\n\n{rows}")


def data_case(system):
    head = HEAD + "read_data       d.data\n"
    return head + system.pair + system.neigh + system.fix_lines() + system.tail + "run             20\n"


def gen_data_files(b):
    cls = "restart-garbled"
    line = [(float(i), 0.0) for i in range(10)]
    same = line[:5] + [(4.0, 0.0)] + line[6:]
    lattice = [(float(i), float(j)) for j in range(-1, 2) for i in range(10)]
    systems = [contacts_system("elastic", "move"), substrate_system("elastic"), meso_system("elastic"),
               contacts_system("hybrid-zero", "qs")]
    for s in systems:
        tag = s.name
        b.add(cls, f"data.{tag}.same-position", data_case(s),
              err(SAME_PLACE, re.escape(s.style) + r"|\bblocks?\b|contacts"), {"d.data": data_file(same)})
        b.add(cls, f"data.{tag}.same-position-lattice", data_case(s),
              err(SAME_PLACE, re.escape(s.style) + r"|\bblocks?\b|contacts"),
              {"d.data": data_file(lattice[:14] + [lattice[3]] + lattice[15:])})
        b.add(cls, f"data.{tag}.control", data_case(s), ok(), {"d.data": data_file(line)})
    s = systems[0]
    bad = {
        "count-too-big": data_file(line, natoms=12),
        "count-too-small": data_file(line, natoms=8),
        "coordinate-nan": data_file(line[:3] + [("nan", 0.0)] + line[4:]),
        "coordinate-word": data_file(line[:3] + [("abc", 0.0)] + line[4:]),
        "duplicate-id": data_file(line, natoms=11, extra_atoms="3 1 5.5 0.5 0.0\n"),
        "type-out-of-range": data_file(line, natoms=11, extra_atoms="11 2 5.5 0.5 0.0\n"),
        "truncated": data_file(line)[:-40],
        # without quote bytes: LAMMPS before 2026 reads one byte past an
        # unterminated quote in utils::split_words (read_data's header), and
        # throws std::out_of_range now and then (seen on 4 Feb 2025)
        "binary": bytes(c for c in F.junk_bytes(500, 3) if c not in b"'\""),
        "box-inverted": data_file(line, box=(10, 0, -2, 2)),
    }
    for aid, content in bad.items():
        b.add(cls, f"data.{aid}", data_case(s), err(r"read_data|data file|Atoms|atom|box|Invalid|Unexpected"),
              {"d.data": content})


# -- 5. box-atoms -------------------------------------------------------------
# The box and the atoms changed between two runs (and by fix deform within
# one), with pair eq/elastic checking every update against a field from
# scratch.  Checks: the count of contacts/blocks, sum_i h_i = 0.

def box_systems():
    return [contacts_system("elastic", "move"), contacts_system("elastic", "qs"),
            contacts_system("hybrid-lj", "nve"), substrate_system("elastic"), meso_system("elastic")]


def count_expr(s):
    return {"eq/contacts": "f_c[7]", "eq/substrate": "f_sub[10]", "eq/meso": "f_m[6]"}[s.style]


def h_col(s):
    return {"eq/contacts": 7, "eq/substrate": 8}.get(s.style, 0)


def box_case(s, cmds, during="", natoms="count(all)", second="run             20\n"):
    col = h_col(s)
    pre = sum_h_checks(s, col) if col else ""
    thermo = f"step pe {count_expr(s)}" + (H_THERMO if col else "")
    post = check("count", count_expr(s), natoms)
    if col:
        post += sum_h_zero()
    return (s.text(thermo=thermo, computes=pre) + "run             20\n" + "".join(c + "\n" for c in cmds)
            + during + second + post)


def gen_box_atoms(b):
    cls = "box-atoms"
    overlap = err_or_ok(SAME_PLACE, r"eq/|contacts|blocks")
    for s in box_systems():
        sn = s.name
        site = s.style != "eq/contacts"
        computes = sum_h_checks(s, h_col(s)) if h_col(s) else ""
        thermo = f"step pe {count_expr(s)}" + (H_THERMO if h_col(s) else "")
        ops = [
            ("x-scale", ["change_box all x scale 1.1"], ok()),
            ("x-scale-remap", ["change_box all x scale 1.1 remap"], ok()),
            ("y-scale-remap", ["change_box all y scale 0.97 remap"], ok()),
            ("boundary-s", ["change_box all boundary p s p" if s.natoms > 40 else "change_box all boundary p f p"],
             ok()),
            ("boundary-f", ["change_box all boundary p f p"], ok()),
            ("triclinic", ["change_box all triclinic"], ok()),
            ("tilt", ["change_box all triclinic", "change_box all xy final 0.5 remap"], ok()),
            ("displace-move", ["displace_atoms all move 0.3 0.0 0.0 units box"], ok()),
            ("displace-move-y", ["displace_atoms all move 0.0 0.4 0.0 units box"], ok()),
            ("displace-random", ["displace_atoms all random 0.05 0.05 0.0 4711 units box"], ok()),
            ("delete", ["group gone id 3 17 22", "delete_atoms group gone"], ok()),
            ("create", ["create_atoms 1 single 0.5 0.5 0.0 units box"], ok()),
            ("create-on-atom", ["variable xa equal x[5]", "variable ya equal y[5]",
                                "create_atoms 1 single ${xa} ${ya} 0.0 units box"],
             # contacts: one place; blocks: a new site where block 5 is now
             err(SAME_PLACE, r"eq/|contacts|blocks") if not site else
             err_or_ok(alt(SAME_PLACE, r"displacements of coupled blocks \d+ and \d+ differ"), r"eq/|blocks")),
            ("image", ["set atom 1 image 1 0 0"], ok()),
            ("image-all", ["set group all image 0 0 0"], ok()),
            ("sort", ["atom_modify sort 1 1.0"], ok()),
            ("pair-coeff", ["pair_coeff * * " + ("0.03 2.0" if s.style == "eq/contacts" else "10.0 1.0")
                            if s.pairkind == "elastic" else
                            "pair_coeff * * eq/elastic 0.03 2.0"], ok()),
            ("write-read-data", ["write_data d.data", "clear", HEAD.strip(), "read_data d.data",
                                 s.pair.strip(), s.neigh.strip(), s.fix_lines().strip(),
                                 s.tail.replace("velocity", "#velocity").strip(), computes.strip(),
                                 f"thermo_style custom {thermo}", "thermo_modify norm no"], ok()),
            ("write-read-restart", ["write_restart r.restart", "clear", "read_restart r.restart",
                                    s.after_restart(thermo=thermo, computes=computes).strip()], ok()),
        ]
        if site:
            # the chain's sites are x = 0..n-1 at y = 0: a block created on one
            ops += [("x-scale-remap-shrink", ["change_box all x scale 0.99 remap"], ok()),
                    ("create-on-site", ["create_atoms 1 single 4.0 0.0 0.0 units box"],
                     err(SAME_PLACE, r"eq/|blocks"))]
        for aid, cmds, exp in ops:
            b.add(cls, f"{sn}.{aid}", box_case(s, cmds), exp)
        # during a run: fix deform
        for aid, pre, dline in [
            ("deform-x", "", "fix df all deform 1 x scale 1.05 remap x"),
            ("deform-x-none", "", "fix df all deform 1 x scale 1.05 remap none"),
            ("deform-erate", "", "fix df all deform 1 y erate 0.001 remap x"),
            ("deform-xy", "change_box all triclinic\n", "fix df all deform 1 xy final 0.4 remap x"),
        ]:
            b.add(cls, f"{sn}.{aid}", box_case(s, [], during=pre + dline + "\n"), ok())
    # quenched disorder: blocks slip one by one (the plain chain slips as one)
    s = substrate_system("elastic", S_ARGS + S_DISORDER)
    for aid, cmds in [("plain", []), ("displace-random", ["displace_atoms all random 0.05 0.05 0.0 4711 units box"]),
                      ("delete", ["group gone id 3 17 22", "delete_atoms group gone"])]:
        b.add(cls, f"substrate-disorder.{aid}", box_case(s, cmds), ok())
    # meso blocks at T > 0: their panels migrate with them
    s = meso_system("none", MS_THERMAL)
    for aid, cmds in [("plain", []), ("displace-random", ["displace_atoms all random 0.05 0.05 0.0 4711 units box"]),
                      ("delete", ["group gone id 3 17 22", "delete_atoms group gone"])]:
        b.add(cls, f"meso-thermal.{aid}", box_case(s, cmds), ok())
    # thermal hops: the blocks' budgets and lives migrate with them
    s = substrate_system("elastic", S_THERMAL)
    for aid, cmds in [("plain", []), ("displace-random", ["displace_atoms all random 0.05 0.05 0.0 4711 units box"]),
                      ("delete", ["group gone id 3 17 22", "delete_atoms group gone"]),
                      ("change_box", ["change_box all x final -1 41 remap"])]:
        b.add(cls, f"substrate-thermal.{aid}", box_case(s, cmds), ok())
    # fix move keeps its original positions: a remapped box puts atoms back
    s = contacts_system("elastic", "move")
    b.add(cls, f"{s.name}.move-remap-shrink", box_case(s, ["change_box all x scale 0.8 remap"]), overlap)
    b.add(cls, f"{s.name}.move-remap-grow", box_case(s, ["change_box all x scale 1.25 remap"]), overlap)


# -- 6. overflow ----------------------------------------------------------------
# Finite arguments whose products or sums overflow: an ERROR at the
# definition naming both keywords.

def both(a, b_):
    return rf"\b({a})\b.*\b({b_})\b|\b({b_})\b.*\b({a})\b"


def gen_overflow(b):
    cls = "overflow"
    ms = meso_system("none")
    mp = meso_system("elastic")
    for aid, s, args, kw in [
        ("nlambda-kc", ms, "1e200 1e200 threshold uniform 0.75 1.25", both("Nlambda", "kc")),
        ("nlambda-kc-300", ms, "1e300 10.0 threshold uniform 0.75 1.25", both("Nlambda", "kc")),
        ("nlambda-kc-160", ms, "1e160 1e160 threshold uniform 0.75 1.25", both("Nlambda", "kc")),
        ("kc-threshold", ms, "100 1e300 threshold uniform 1e10 2e10", both("kc", "threshold")),
        ("kc-threshold-gaussian", ms, "1 1e300 threshold gaussian 1e10 1e9", both("kc", "threshold")),
        ("nlambda-threshold", ms, "1e300 1.0 threshold realistic 1e10", both("Nlambda", "threshold")),
        ("drive-stage", mp, "100 1.0 threshold uniform 0.75 1.25 drive 1e300 1.0 stage 1e10", both("drive", "stage")),
        ("drive-v", mp, "100 1.0 threshold uniform 0.75 1.25 drive 1e300 1e300", both("drive", "drive|v")),
        ("drive-nlambda", mp, "1e300 1e10 threshold uniform 0.75 1.25 drive 1e300 1.0", both("Nlambda|drive", "kc|drive")),
        ("screen-nlambda", ms, "1e200 1.0 threshold uniform 0.75 1.25 screen 1e200 1.0 1.5",
         alt(both("Nlambda", "screen"), r"screen: Pi0 = .*\b(inf|nan)\b")),
    ]:
        b.add(cls, f"meso.{aid}", s.text().replace(MS_ARGS if s is ms else MP_ARGS, args) + "run 20\n",
              err(r"eq/meso", kw))
    cs = contacts_system("none", "nve")
    cp = contacts_system("elastic", "move")
    for aid, s, args, kw in [
        ("kc-uniform", cs, "1e300 99 threshold uniform 1e10 2e10", both("kc", "threshold")),
        ("kc-gaussian", cs, "1e300 99 threshold gaussian 1e10 1e9", both("kc", "threshold")),
        ("kc-realistic", cs, "1e300 99 threshold realistic 1e10", both("kc", "threshold")),
        ("kc-energy", cs, "1e200 99 threshold uniform 1e60 2e60", both("kc", "threshold")),
        ("kc-stiffness", cs, "1e300 99 threshold uniform 0.75 1.25 stiffness uniform 1.0 1e10",
         both("kc", "stiffness")),
        ("kc-stiffness-gaussian", cs, "1e300 99 threshold uniform 0.75 1.25 stiffness gaussian 1e10 1.0",
         both("kc", "stiffness")),
        ("kc-reform", cs, "1e300 99 threshold uniform 1e9 2e10 reform delta 1e8", both("kc", "threshold|reform")),
        ("kc-uniform-pair", cp, "1e300 99 threshold uniform 1e10 2e10", both("kc", "threshold")),
        ("kc-start-reform", cs, "1e300 99 threshold uniform 1e10 2e10 reform uniform 1e9 5e9 start reform",
         both("kc", "threshold|reform")),
    ]:
        b.add(cls, f"contacts.{aid}", s.text().replace(C_ARGS, args) + "run 20\n", err(r"eq/contacts", kw))
    ss = substrate_system("elastic")
    for aid, args, kw in [
        ("kc-uc", "1e300 sawtooth 1e10", both("kc", "uc|sawtooth")),
        ("kc-uc-smooth", "1e300 smooth 1e10", both("kc", "uc|smooth")),
        ("kc-energy", "1e200 sawtooth 1e60", both("kc", "uc|sawtooth")),
        ("drive-stage", "1.0 sawtooth 1.0 drive 1e300 0.01 stage 1e10", both("drive", "stage")),

        ("drive-K-v", "1.0 sawtooth 1.0 drive 1e300 1e300", both("drive", "drive|v")),
        ("drive-energy", "1.0 sawtooth 1.0 drive 1e200 0.01 stage 1e60", both("drive", "stage")),
        ("kc-disorder", "1e300 sawtooth 1.0 disorder gaussian 1e10 1e9 5", both("kc", "disorder")),
        ("kc-disorder-uniform", "1e300 sawtooth 1.0 disorder uniform 1.0 1e10 5", both("kc", "disorder")),
        ("kc-table", "1e300 table big.table BIG", both("kc", "table")),
    ]:
        b.add(cls, f"substrate.{aid}", ss.text().replace(S_ARGS, args) + "run 20\n", err(r"eq/substrate", kw),
              {"big.table": "# big\nBIG\nN 3\n\n1 0.0 0.0\n2 1.0 1e10\n3 2.0 1e12\n"})
    # v = 1e300 on a soft spring: K v = 7e298 is finite, the stage outruns
    # the box in one step and LAMMPS stops with its own error (lost atoms):
    # any ERROR, never a crash or NaN
    b.add(cls, "substrate.drive-v", ss.text().replace(S_ARGS, "1.0 sawtooth 1.0 drive 0.07 1e300")
          + "run 20\n", robust(r"eq/substrate", r"drive|v"))
    b.add(cls, "substrate.fix_modify-velocity", ss.text().replace(S_ARGS, "1.0 sawtooth 1.0 drive 1.0 0.01")
          + "run 10\nfix_modify sub velocity 1e301\nrun 10\n",
          err(r"eq/substrate|fix_modify", both("K", "velocity|v")))
    b.add(cls, "substrate.drive-stage-sum", ss.text().replace(S_ARGS, "1.0 sawtooth 1.0 drive 1.0 1.7e308 stage 1.7e308")
          + "run 20\n", err(r"eq/substrate", both("drive", "stage|v")))
    b.add(cls, "substrate.fix_modify-kc", ss.text().replace(S_ARGS, "1.0 sawtooth 1e10") + "run 10\n"
          "fix_modify sub kc all 1e300\nrun 10\n", err(r"eq/substrate|fix_modify", both("kc", "uc|sawtooth")))
    cq = contacts_system("elastic", "qs")
    for aid, coeff, kw in [
        ("ftilde-lambda-big", "1e300 1e10 3.0", both("ftilde", "lambda_c")),
        ("ftilde-lambda-tiny", "1e300 1e-300", both("ftilde", "lambda_c")),
        ("ftilde-lambda-rcut", "1e300 1e-10 3.0", both("ftilde", "lambda_c")),
        ("ftilde-kc", "1e300 3.0", alt(both("ftilde", "kc|lambda_c"), AVALANCHE)),
        ("ftilde-lambda-150", "1e150 1e150 3.0", both("ftilde", "lambda_c")),
    ]:
        # (ftilde-kc ends in the avalanche's limit of 100000 rounds, each
        # with a reduction: 3 s of CPU, 9-20 s on 2 ranks of a loaded
        # 2-core machine; 5 times the time limit of a hang)
        b.add(cls, f"pair.{aid}", cq.text().replace("pair_coeff      * * 0.06 3.0", f"pair_coeff * * {coeff}")
              + "run 20\n", err(r"eq/elastic|pair_coeff|pair coeff", kw),
              budget=5.0 if aid == "ftilde-kc" else 1.0)
    big = "# big kernel\nBIG\nN 3\n\n1 1.0 1e300\n2 2.0 1e300\n3 3.0 1e300\n"
    # (ends in the avalanche's limit too, as ftilde-kc: 4 s on 2 ranks of
    # a quiet machine, a timeout of the plain budget on 2 ranks of a loaded one)
    b.add(cls, "pair.table-huge", cq.text().replace("pair_coeff      * * 0.06 3.0", "pair_coeff * * table big.table BIG")
          + "run 20\n", err(r"eq/elastic|pair_coeff|pair coeff", alt(r"\btable\b", AVALANCHE)), {"big.table": big},
          budget=5.0)
    b.add(cls, "meso.window-grid", ms.text().replace(MS_ARGS, "1e300 1e300 threshold uniform 0.75 1.25 window 1e300")
          + "run 20\n", err(r"eq/meso", both("Nlambda", "kc")))
    # large products that do not overflow: no error needed, no NaN allowed
    for aid, s, old, new in [
        ("meso-large", ms, MS_ARGS, "1e100 1e100 threshold uniform 0.75 1.25"),
        ("contacts-large", cs, C_ARGS, "1e100 99 threshold uniform 1e100 2e100"),
        ("substrate-large", ss, S_ARGS, "1e100 sawtooth 1e100 drive 1e100 0.01 stage 1e100"),
        ("pair-large", cq, "pair_coeff      * * 0.06 3.0", "pair_coeff * * 1e100 3.0"),
    ]:
        b.add(cls, f"control.{aid}", s.text().replace(old, new) + "run 20\n", robust())


# -- 7. before-run --------------------------------------------------------------
# Outputs read before the first run (and right after run 0), compared in
# the input with the value they must have.  A LAMMPS ERROR saying that the
# value is not available yet is also right.

NOT_YET = (r"not (yet )?(available|current|computed|set up|initialized|tallied)|before (the first|a|any) run|"
           r"before initialization|compatible time|run 0|requires thermo to use/init")


def before_case(setup, checks, run0=False):
    return setup + ("run             0\n" if run0 else "") + "".join(check(n, g, w) for n, g, w in checks) \
        + "run             5\n"


def gen_before_run(b):
    cls = "before-run"
    exp = err_or_ok(NOT_YET, r".")
    n = 80
    plain = box() + "comm_modify     cutoff 0.5\nneighbor 0.5 bin\n"
    pair = box() + "pair_style eq/elastic 3.0\npair_coeff * * 0.06 3.0\nneighbor 0.5 bin\n"
    drive = "fix m all move linear 1.0 0.0 0.0 units box\ntimestep 0.02\n"
    contacts = [
        ("count", plain, C_ARGS, "f_c[7]", str(n)),
        ("attached", plain, C_ARGS, "f_c[4]", str(n)),
        ("friction", plain, C_ARGS, "f_c[1]", "0"),
        ("breaks", plain, C_ARGS, "f_c[3]", "0"),
        ("energy", plain, C_ARGS, "f_c", "0"),
        ("energy-5", plain, C_ARGS, "f_c[5]", "0"),
        ("start-reform-F", plain, C_ARGS + " reform delta 0.1 start reform", "f_c[1]", str(0.1 * n)),
        ("start-reform-mean", plain, C_ARGS + " reform delta 0.1 start reform", "f_c[6]", "0.1"),
        ("start-reform-energy", plain, C_ARGS + " reform delta 0.1 start reform", "f_c[5]", str(0.5 * 0.01 * n)),
        ("kc2-start-reform-F", plain, "2.0 99 threshold uniform 0.75 1.25 reform delta 0.1 start reform",
         "f_c[1]", str(2 * 0.1 * n)),
        ("pair-count", pair, C_ARGS, "f_c[7]", str(n)),
        ("pair-start-reform-F", pair, C_ARGS + " reform delta 0.1 start reform", "f_c[1]", str(0.1 * n)),
        ("pair-energy", pair, C_ARGS + " reform delta 0.1 start reform", "pe", "0"),
        ("group-count", plain + "group half id <= 30\n", C_ARGS, "f_c[7]", "30"),
        ("dir-y-count", plain, C_ARGS + " dir y", "f_c[4]", str(n)),
        ("reform-none-attached", plain, C_ARGS + " reform none", "f_c[4]", str(n)),
        ("rounds", plain, C_ARGS, "f_c[8]", "0"),
    ]
    for aid, setup, args, got, want in contacts:
        grp = "half" if "group half" in setup else "all"
        s = setup + f"fix c {grp} eq/contacts {args}\n" + drive
        b.add(cls, f"contacts.{aid}", before_case(s, [(aid, got, want)]), exp)
        if aid in ("count", "friction", "start-reform-F", "pair-start-reform-F"):
            b.add(cls, f"contacts.{aid}.run0", before_case(s, [(aid, got, want)], run0=True), ok())
    # per-atom columns through compute reduce: after run 0, or an error before it.
    # c_r and c_xs are thermo keywords so that run 0 invokes them: LAMMPS 2021
    # refuses a compute in a variable between runs unless it is current
    # (2025 and later invoke an initialized compute on demand).
    s = plain + f"fix c all eq/contacts {C_ARGS}\n" + drive
    for aid, comp, want in [("thresholds-min", "min f_c[2]", "0.75"), ("stretch-sum", "sum f_c[1]", "0"),
                            ("anchor-sum", "sum f_c[6]", "v_xsum"), ("stiffness-sum", "sum f_c[5]", str(n)),
                            ("field-sum", "sum f_c[7]", "0")]:
        body = (s + f"compute r all reduce {comp}\ncompute xs all reduce sum x\nvariable xsum equal c_xs\n"
                "thermo_style custom step c_r c_xs\n")
        chk = [(aid, "c_r", want)] if aid != "thresholds-min" else [(aid, "c_r >= 0.75", "1")]
        b.add(cls, f"contacts.reduce-{aid}", before_case(body, chk), exp)
        b.add(cls, f"contacts.reduce-{aid}.run0", before_case(body, chk, run0=True), ok())
    # fix eq/substrate: K X0 and the spring forces at u = 0; u after displace_atoms
    ss = chain(40) + "pair_style eq/elastic 1.5\npair_coeff 1 1 25.0 1.0\nneighbor 1.0 bin\n"
    sarg = "1.0 sawtooth 1.0 drive 0.07 0.01 stage 12.0"
    brown = "fix bd all brownian 1.0 1 rng none gamma_t 100.0\ntimestep 0.1\n"
    for aid, extra, got, want in [
        ("count", "", "f_sub[10]", "40"), ("drive-force", "", "f_sub[1]", str(0.07 * 12)),
        ("stage", "", "f_sub[2]", "12"), ("velocity", "", "f_sub[3]", "0.01"),
        ("spring-total", "", "f_sub[7]", str(40 * 0.07 * 12)), ("friction", "", "f_sub[6]", "0"),
        ("mean-u", "", "f_sub[5]", "0"), ("spring-energy", "", "f_sub[9]", str(40 * 0.035 * 144)),
        ("u-displaced", "displace_atoms all move 0.3 0 0 units box\n", "f_sub[5]", "0.3"),
        ("friction-displaced", "displace_atoms all move 0.3 0 0 units box\n", "f_sub[6]", str(40 * 0.3)),
        ("spring-displaced", "displace_atoms all move 0.3 0 0 units box\n", "f_sub[7]",
         str(40 * 0.07 * (12 - 0.3))),
        ("energy-displaced", "displace_atoms all move 0.3 0 0 units box\n", "f_sub[8]", str(40 * 0.045)),
        ("kc-modified", "group half id <= 20\nfix_modify sub kc half 0.5\ndisplace_atoms all move 0.3 0 0 units box\n",
         "f_sub[6]", str(20 * 0.3 + 20 * 0.15)),
    ]:
        s = ss + f"fix sub all eq/substrate {sarg}\n" + extra + brown
        b.add(cls, f"substrate.{aid}", before_case(s, [(aid, got, want)]), exp)
        if aid in ("count", "drive-force", "u-displaced"):
            b.add(cls, f"substrate.{aid}.run0", before_case(s, [(aid, got, want)], run0=True), ok())
    # fix eq/meso
    sm = box("sq", 6, 4) + "comm_modify cutoff 2.0\nneighbor 0.5 bin\n"
    mv = "velocity all set 0.05 0 0 units box\nfix mv all nve/noforce\ntimestep 1.0\n"
    pi0 = 100 * 0.001 * (4 + 4 / 2 ** 1.5)
    for aid, args, got, want in [
        ("count", MS_ARGS, "f_m[6]", "24"), ("friction", MS_ARGS, "f_m[1]", "0"),
        ("mean-X", MS_ARGS, "f_m[4]", "0"), ("rate", MS_ARGS, "f_m[2]", "0"),
        ("screening", MS_ARGS, "f_m[3]", "0"), ("norm-error", MS_ARGS, "f_m[8]", "0"),
        ("pi0", MS_ARGS, "f_m[9]", repr(pi0)),
        ("stage", "100 1.0 threshold uniform 0.75 1.25 drive 10.0 0.01 stage 0.5", "f_m[7]", "0.5"),
        ("drive-force", "100 1.0 threshold uniform 0.75 1.25 drive 10.0 0.01 stage 0.5", "f_m[5]", str(24 * 5.0)),
        ("scalar", MS_ARGS, "f_m", "0"),
        ("start-reform-F", "100 1.0 threshold uniform 0.75 1.25 reform delta 0.1 start reform", "f_m[1]",
         str(24 * 100 * 0.1)),
    ]:
        s = sm + f"fix m all eq/meso {args}\n" + mv
        b.add(cls, f"meso.{aid}", before_case(s, [(aid, got, want)]), exp)
        if aid in ("count", "pi0", "drive-force"):
            b.add(cls, f"meso.{aid}.run0", before_case(s, [(aid, got, want)], run0=True), ok())
    # fix eq/quasistatic
    q = pair + f"fix c all eq/contacts {C_ARGS}\nfix q all eq/quasistatic c max 0.02\n"
    for aid, got in (("X", "f_q"), ("X-1", "f_q[1]"), ("advance", "f_q[2]")):
        b.add(cls, f"quasistatic.{aid}", before_case(q, [(aid, got, "0")]), exp)


# -- 8. forbidden ---------------------------------------------------------------

QS_BOTH = r"Fix \S+ eq/quasistatic and fix \S+ \S+ both move"
MIN_ENERGY = r"minimize.*fix_modify \S+ energy yes"
INTEGRATORS = r"integrator verlet or integrator overdamped"
SUBSTYLES = r"sub-styles eq/elastic"
RESPA = r"respa"


def gen_forbidden(b):
    cls = "forbidden"
    cq = contacts_system("elastic", "qs")
    cn = contacts_system("none", "qs")
    for aid, s, line in [
        ("move", cq, "fix mv all move linear 1.0 0 0 units box"),
        ("move-subset", cq, "group few id 1 2 3\nfix mv few move linear 1.0 0 0 units box"),
        ("nve", cq, "fix nv all nve"),
        ("nve-noforce", cq, "fix nv all nve/noforce"),
        ("brownian", cq, "fix br all brownian 1.0 1 rng none gamma_t 1.0"),
        ("nve-no-pair", cn, "fix nv all nve"),
        ("move-no-pair", cn, "fix mv all move linear 1.0 0 0 units box"),
        ("rigid", cq, "fix rg all rigid single"),
        ("nve-limit", cn, "fix nl all nve/limit 0.1"),
    ]:
        b.add(cls, f"quasistatic.{aid}", cq_text(s, line), err(QS_BOTH, r"eq/quasistatic"))
    b.add(cls, "quasistatic.move-empty-group", cq_text(cq, "group none empty\nfix mv none move linear 1.0 0 0 units box"),
          ok())
    b.add(cls, "quasistatic.move-after-unfix", cq_text(cq, "fix mv all move linear 1.0 0 0 units box\nunfix q"), ok())
    # minimize with fix eq/substrate and no fix_modify energy yes
    for aid, pk, extra, style, exp in [
        ("cg", "elastic", "", "cg", err(MIN_ENERGY, r"eq/substrate|\bsub\b")),
        ("sd", "elastic", "", "sd", err(MIN_ENERGY, r"eq/substrate|\bsub\b")),
        ("fire", "elastic", "", "fire", err_or_ok(MIN_ENERGY, r"eq/substrate|\bsub\b")),
        ("quickmin", "elastic", "", "quickmin", err_or_ok(MIN_ENERGY, r"eq/substrate|\bsub\b")),
        ("cg-hybrid", "hybrid-zero", "", "cg", err(MIN_ENERGY, r"eq/substrate|\bsub\b")),
        ("cg-energy-no", "elastic", "fix_modify sub energy no\n", "cg", err(MIN_ENERGY, r"eq/substrate|\bsub\b")),
        ("cg-energy-yes", "elastic", "fix_modify sub energy yes\n", "cg", ok()),
        ("cg-energy-yes-hybrid", "hybrid-zero", "fix_modify sub energy yes\n", "cg", ok()),
    ]:
        s = substrate_system(pk)
        b.add(cls, f"minimize.{aid}", s.text() + extra + "run 10\nunfix bd\n"
              f"min_style {style}\nmin_modify dmax 0.01\nminimize 0.0 1e-8 50 500\n", exp)
    s = substrate_system("elastic").text().replace("drive 0.07 0.01 stage 14.5", "")
    b.add(cls, "minimize.cg-no-drive", s + "unfix bd\nminimize 0.0 1e-8 50 500\n",
          err(MIN_ENERGY, r"eq/substrate|\bsub\b"))
    b.add(cls, "minimize.meso-forcezero", meso_system("elastic").text() + "run 10\nunfix bd\n"
          "min_modify line forcezero\nminimize 0.0 1e-8 50 500\n", ok())
    # fix eq/substrate crossing exact moved by a first-order and a velocity-Verlet integrator
    base = substrate_system("elastic").text()
    brown = "fix             bd all brownian 1.0 1 rng none gamma_t 100.0"
    halves = "group left id <= 20\ngroup right id > 20\nfix bd left brownian 1.0 1 rng none gamma_t 100.0\n"
    for aid, integ, sargs, exp in [
        ("brownian-nve", halves + "fix nv right nve", S_ARGS, err(INTEGRATORS, r"eq/substrate")),
        ("brownian-nve-limit", halves + "fix nv right nve/limit 0.1", S_ARGS, err(INTEGRATORS, r"eq/substrate")),
        ("brownian-nve-one", "group one id 7\ngroup rest subtract all one\n"
         "fix bd rest brownian 1.0 1 rng none gamma_t 100.0\nfix nv one nve", S_ARGS,
         err(INTEGRATORS, r"eq/substrate")),
        ("brownian-nve-crossing-step", halves + "fix nv right nve", S_ARGS + " crossing step", ok()),
        ("nve-viscous", "fix nv all nve\nfix vis all viscous 10.0", S_ARGS, ok()),
        ("integrator-overdamped", halves + "fix nv right nve\nfix vis right viscous 10.0",
         S_ARGS + " integrator overdamped", ok()),
        ("integrator-verlet", halves + "fix nv right nve\nfix vis right viscous 10.0",
         S_ARGS + " integrator verlet", ok()),
    ]:
        text = base.replace(brown, integ).replace(S_ARGS, sargs)
        b.add(cls, f"substrate.{aid}", text + "run 20\n", exp)
    # two coordinate sources with pair eq/elastic
    for aid, s, line, kw in [
        ("contacts-substrate", cq, "fix s2 all eq/substrate 1.0 sawtooth 1.0", both("eq/contacts", "eq/substrate")),
        ("contacts-meso", cq, f"fix m2 all eq/meso {MS_ARGS}", both("eq/contacts", "eq/meso")),
        ("contacts-contacts", cq, f"fix c2 all eq/contacts {C_ARGS}", r"eq/contacts.*eq/contacts|\bc2\b"),
        ("substrate-meso", substrate_system("elastic"), f"fix m2 all eq/meso {MP_ARGS}",
         both("eq/substrate", "eq/meso")),
        ("substrate-substrate", substrate_system("elastic"), "fix s2 all eq/substrate 1.0 sawtooth 1.0",
         r"eq/substrate.*eq/substrate|\bs2\b"),
        ("meso-meso", meso_system("elastic"), f"fix m2 all eq/meso {MP_ARGS}", r"eq/meso.*eq/meso|\bm2\b"),
        ("substrate-contacts-subset", substrate_system("elastic"),
         f"group few id 1 2\nfix c2 few eq/contacts {C_ARGS}", both("eq/substrate", "eq/contacts")),
        ("hybrid-contacts-substrate", contacts_system("hybrid-zero", "qs"), "fix s2 all eq/substrate 1.0 sawtooth 1.0",
         both("eq/contacts", "eq/substrate")),
    ]:
        b.add(cls, f"sources.{aid}", s.text() + line + "\nrun 10\n", err(PAIR_TWO + r"|exactly one", kw))
    # two eq/elastic sub-styles of a hybrid pair style
    two = box(ntypes=2) + "set group all type/fraction 2 0.5 4711\n"
    for aid, ps, pcs in [
        ("hybrid", "hybrid eq/elastic 3.0 eq/elastic 3.0",
         "pair_coeff 1 1 eq/elastic 1 0.06 3.0\npair_coeff 2 2 eq/elastic 2 0.06 3.0\npair_coeff 1 2 eq/elastic 1 0.06 3.0"),
        ("overlay", "hybrid/overlay eq/elastic 3.0 eq/elastic 3.0",
         "pair_coeff * * eq/elastic 1 0.06 3.0\npair_coeff * * eq/elastic 2 0.03 3.0"),
        ("overlay-zero", "hybrid/overlay eq/elastic 3.0 zero 3.0 eq/elastic 2.0",
         "pair_coeff * * eq/elastic 1 0.06 3.0\npair_coeff * * zero\npair_coeff * * eq/elastic 2 0.03 2.0"),
        ("scaled", "hybrid/scaled 0.5 eq/elastic 3.0 0.5 eq/elastic 3.0",
         "pair_coeff * * eq/elastic 1 0.06 3.0\npair_coeff * * eq/elastic 2 0.06 3.0"),
    ]:
        for src in ("contacts", "substrate"):
            fx = (f"fix c all eq/contacts {C_ARGS}\nfix m all move linear 1.0 0 0 units box\n" if src == "contacts"
                  else "fix sub all eq/substrate 1.0 sawtooth 1.0\nfix bd all brownian 1.0 1 rng none gamma_t 100.0\n")
            b.add(cls, f"substyles.{aid}-{src}", two + f"pair_style {ps}\n{pcs}\nneighbor 0.5 bin\n" + fx
                  + "timestep 0.02\nrun 10\n", err(SUBSTYLES, r"eq/elastic"))
    # r-RESPA
    for aid, text, exp in [
        ("contacts-pair", cq.text().replace("fix             q all eq/quasistatic c\n", "")
         + "fix m all move linear 1.0 0 0 units box\ntimestep 0.02\nrun_style respa 2 2\nrun 10\n",
         err(RESPA, r"eq/contacts|eq/elastic")),
        ("contacts-pair-level", cq.text().replace("fix             q all eq/quasistatic c\n", "")
         + "fix m all move linear 1.0 0 0 units box\ntimestep 0.02\nrun_style respa 2 2 pair 1\nrun 10\n",
         err(RESPA, r"eq/contacts|eq/elastic")),
        ("quasistatic", cn.text() + "run_style respa 2 2\nrun 10\n", err(RESPA + r"|verlet", r"eq/quasistatic")),
        ("quasistatic-pair", cq.text() + "run_style respa 2 2\nrun 10\n",
         err(RESPA + r"|verlet", r"eq/quasistatic|eq/contacts|eq/elastic")),
        ("substrate-inner", substrate_system("elastic").text().replace(
            "fix             bd all brownian 1.0 1 rng none gamma_t 100.0", "fix nv all nve\nfix vis all viscous 10.0")
         + "run_style respa 3 2 2 inner 1 0.5 0.8 middle 2 1.0 1.2 outer 3\nrun 10\n",
         err(RESPA + r"|inner|level", r"eq/substrate|eq/elastic|Pair style")),
        ("substrate-pair-level", substrate_system("elastic").text().replace(
            "fix             bd all brownian 1.0 1 rng none gamma_t 100.0", "fix nv all nve\nfix vis all viscous 10.0")
         + "run_style respa 2 2 pair 2\nrun 10\n", ok()),
        ("contacts-no-pair", contacts_system("none", "move").text() + "run_style respa 2 2\nrun 10\n", ok()),
    ]:
        b.add(cls, f"respa.{aid}", text, exp)


def cq_text(s, line):
    return s.text() + line + "\nrun 10\n"


# ----------------------------------------------------------------------------

def generate(mpi=True, nps=None):
    """All cases, in a fixed order; mpi=False or nps=(1,) leaves out the
    2-rank ones."""
    nps = nps or ((1, 2) if mpi else (1,))
    b = Builder(tuple(nps))
    gen_unfix_within(b)
    gen_unfix_between(b)
    gen_restart_args(b)
    gen_restart_garbled(b)
    gen_box_atoms(b)
    gen_overflow(b)
    gen_before_run(b)
    gen_forbidden(b)
    return b.cases


def shard(cases, index, count):
    return F.shard(cases, index, count)


def summarize(cases, results, out=sys.stdout, label=""):
    """The summary line, a table of counts per class and outcome, and every
    case that is not ok with its input."""
    by_id = {c.id: c for c in cases}
    tot = collections.Counter(r.outcome for r in results)
    per = collections.defaultdict(collections.Counter)
    for r in results:
        per[r.cls][r.outcome] += 1
    outs = [o for o in OUTCOMES if tot[o]] + sorted(set(tot) - set(OUTCOMES))
    classes = [c for c in CLASSES if c in per]
    line = (f"MISUSE SUMMARY{(' ' + label) if label else ''}: {len(results)} cases; "
            + " ".join(f"{o}={tot[o]}" for o in outs) + " | "
            + "; ".join(f"{c}: " + ",".join(f"{o}={per[c][o]}" for o in outs if per[c][o]) for c in classes))
    print(line, file=out)
    cols = [o for o in OUTCOMES if tot[o] or o in ("error-ok", "ok")] + sorted(set(tot) - set(OUTCOMES))
    w = max([len(c) for c in classes] + [5])
    print(f"  {'class':{w}s} " + " ".join(f"{o:>11s}" for o in cols) + f" {'not ok':>7s}", file=out)
    for c in classes + ["total"]:
        cnt = tot if c == "total" else per[c]
        bad = sum(1 for r in results if not r.ok and (c == "total" or r.cls == c))
        print(f"  {c:{w}s} " + " ".join(f"{cnt[o]:11d}" for o in cols) + f" {bad:7d}", file=out)
    bad = [r for r in results if not r.ok]
    if bad:
        print(f"\nNOT OK: {len(bad)} case(s)", file=out)
        for r in bad:
            print(f"  {r.outcome:11s} {r.id:70s} {(r.message or r.detail)[:160]}", file=out)
        print("", file=out)
        for r in bad:
            c = by_id[r.id]
            print(f"---- {r.id} [{r.cls}] -> {r.outcome} (np {c.np})", file=out)
            print(f"     expected: {c.expect.text()}", file=out)
            if r.message:
                print(f"     ERROR: {r.message}", file=out)
            if r.detail:
                print(f"     detail: {r.detail}", file=out)
            for ln in r.tail.splitlines()[-8:]:
                print(f"     | {ln}", file=out)
    return line


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=os.environ.get("FEQ_LMP", str(ROOT / "build" / "lmp")))
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--np", type=int, choices=(1, 2), default=None, help="only the cases on this many ranks")
    ap.add_argument("--timeout", type=float, default=float(os.environ.get("FEQ_FUZZ_TIMEOUT", 20)))
    ap.add_argument("--filter", default=None, help="regex on case id or class")
    ap.add_argument("--shard", default=None, help="I/N: run shard I of N")
    ap.add_argument("--list", action="store_true", help="list the cases and exit")
    ap.add_argument("--show", default=None, help="print one case's input and files and exit")
    ap.add_argument("--write", default=None, help="write every case into DIR/<id>/ and exit")
    ap.add_argument("--keep", default=None, help="keep the case folders with their output in DIR")
    ap.add_argument("--json", default=None, help="write the results to this JSON file")
    ap.add_argument("--progress", action="store_true")
    a = ap.parse_args(argv)

    cases = generate(nps=(a.np,) if a.np else None)
    if a.filter:
        rx = re.compile(a.filter)
        cases = [c for c in cases if rx.search(c.id) or rx.fullmatch(c.cls)]
    if a.shard:
        i, n = (int(x) for x in a.shard.split("/"))
        cases = shard(cases, i, n)
    if a.list:
        for c in cases:
            print(f"{c.id:78s} {c.expect.text()}")
        per = collections.Counter(c.cls for c in cases)
        print(f"{len(cases)} cases: " + ", ".join(f"{k} {per[k]}" for k in CLASSES if per[k]))
        return 0
    if a.show:
        c = next(c for c in generate() if c.id == a.show)
        print(f"# {c.id} [{c.cls}] np {c.np}: expected {c.expect.text()}")
        for name, content in c.files.items():
            if name == "garble.py":
                continue
            print(f"# file {name}: " + (repr(content[:400]) if isinstance(content, bytes) else "\n" + content))
        print(c.input)
        return 0
    if a.write:
        F.write_cases(cases, a.write)
        return 0
    return F.run_and_summarize(cases, a, run_cases, summarize)


if __name__ == "__main__":
    sys.exit(main())
