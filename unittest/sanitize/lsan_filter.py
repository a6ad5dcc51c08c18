#!/usr/bin/python3
"""Sort the sanitizer reports of ./friction-eq test --sanitize.

LeakSanitizer's suppressions match a function anywhere in an allocation's
stack, which is too wide for LAMMPS' own leaks: a suppression of
Input::ifthenelse() would also hide every leak of a command that an input
runs through 'if ... then', the package's commands included.  This filter
is narrower: a leak report is LAMMPS' own when every *direct* leak in it
was allocated by one of the functions below itself (frame #1, the caller
of operator new); indirect leaks are reachable only from direct ones and
go with them.  A generic allocator (utils::strdup) counts only where
its caller (frame #2) is one of LAMMPS' functions listed with it.  Any
other report (a direct leak elsewhere, any AddressSanitizer error, any
UBSan finding) is a finding.  One exception, said in the output: the
last block of a report cut off before its first frame (a process that
mpirun killed while LeakSanitizer was writing, when the other rank
stopped with an error) is 'truncated', and the report is LAMMPS' own
when all its complete direct leaks are.  A report cut off before any
leak (its header alone, or its first block without a frame) tells
nothing: it is 'cut', printed, not a finding.  This assumes that the
cut report's process was a rank that mpirun killed when another rank
of the same run stopped with an error: every input of the misuse and
fuzz runners, where mpirun kills ranks at once, also runs on one rank,
whose report is whole, and a rank killed for a timeout fails its test.

    lsan_filter.py REPORT...     prints a line per report; exit 1 on a finding
"""
import re
import sys

# function (frame #1 of a direct leak) -> what LAMMPS does there
KNOWN = {
    "LAMMPS_NS::Input::ifthenelse": (
        "src/input.cpp: 'if ... then \"cmd\" ...' copies its commands into new[]'ed strings and "
        "deletes them after running them; when one stops with an error (an exception with "
        "LAMMPS_EXCEPTIONS) the copies are never deleted"),
    "command_creator": (
        "src/input.cpp: Input::execute_command() creates a command object with new, calls its "
        "command() and deletes it; when command() stops with an error the object is never "
        "deleted (its members are the indirect leaks)"),
    "LAMMPS_NS::Run::command": (
        "src/run.cpp: 'run N every M \"cmd\" ...' keeps its commands in new[]'ed arrays that it "
        "deletes after the run; an error during the run leaves them"),
    "LAMMPS_NS::PairHybrid::save_special": (
        "src/pair_hybrid.cpp: init_one() saves special_lj/coul into a new[]'ed array and "
        "restore_special() deletes it; an error of a sub-style's init_one() in between leaves it"),
    "LAMMPS_NS::Variable::evaluate": (
        "src/variable.cpp: evaluate() copies each word of a formula into a new[]'ed string and "
        "deletes it when the word is done; an error while evaluating the word (e.g. a fix's "
        "output refused) leaves it"),
    "LAMMPS_NS::Variable::find_matching_paren": (
        "src/variable.cpp: copies the contents of a parenthesis into a new[]'ed string that the "
        "caller deletes after evaluating it; an error in between leaves it"),
    "LAMMPS_NS::ReadRestart::check_eof_magic": (
        "src/read_restart.cpp: reads the end-of-file magic into a new[]'ed string and deletes it "
        "after the check; a truncated or garbled file stops with an error before that"),
}
# generic allocators: LAMMPS' own only when called (frame #2) by one of these
# (each copies a string, runs what may stop with an error, then deletes it:
# run's commands, a math function's arguments, an immediate $(...)
# variable, read_restart's file name)
KNOWN_CALLERS = {
    "LAMMPS_NS::utils::strdup": ("LAMMPS_NS::Run::command", "LAMMPS_NS::Variable::parse_args",
                                 "LAMMPS_NS::Variable::compute_equal", "LAMMPS_NS::Input::ifthenelse",
                                 "LAMMPS_NS::ReadRestart::command"),
}

LSAN_HEAD = "ERROR: LeakSanitizer: detected memory leaks"
BLOCK_RE = re.compile(r"^(Direct|Indirect) leak of (\d+) byte", re.M)
FRAME1_RE = re.compile(r"^\s*#1 0x[0-9a-f]+ in (.+?)(?: \S+:\d+(?::\d+)?)?$", re.M)
FRAME2_RE = re.compile(r"^\s*#2 0x[0-9a-f]+ in (.+?)(?: \S+:\d+(?::\d+)?)?$", re.M)
FRAME_RE = re.compile(r"^\s*#\d+ 0x", re.M)


def known_site(block):
    """the KNOWN key (or allocator <- caller) of a direct leak block, or None"""
    m = FRAME1_RE.search(block)
    func = m.group(1) if m else "?"
    for k in KNOWN:
        if k in func:
            return k
    for alloc, callers in KNOWN_CALLERS.items():
        if alloc in func:
            m2 = FRAME2_RE.search(block)
            caller = m2.group(1) if m2 else "?"
            for c in callers:
                if c in caller:
                    return f"{alloc} <- {c}"
    return None


def classify(text):
    """(kind, detail): kind 'lammps' (only known direct leaks), 'cut' (no complete direct
    leak: cut off) or 'finding'."""
    if re.search(r"ERROR: AddressSanitizer|runtime error: ", text):
        return "finding", "AddressSanitizer/UBSan error"
    if LSAN_HEAD not in text:
        return "finding", "unrecognised report"
    starts = [m.start() for m in BLOCK_RE.finditer(text)] + [len(text)]
    known, truncated, cut_first = set(), False, False
    for n, (a, b) in enumerate(zip(starts, starts[1:])):
        block = text[a:b]
        if not block.startswith("Direct"):
            continue
        if b == len(text) and not FRAME_RE.search(block) and "SUMMARY:" not in block:
            truncated, cut_first = True, n == 0
            continue
        site = known_site(block)
        if site is None:
            m = FRAME1_RE.search(block)
            return "finding", f"direct leak allocated in {m.group(1) if m else '?'}"
        known.add(site)
    # cut off before its first block (LeakSanitizer writes the direct
    # leaks first): nothing after the header, or one block without a frame
    header_only = len(starts) == 1 and not text[text.index(LSAN_HEAD) + len(LSAN_HEAD):].strip()
    if not known and (header_only or cut_first):
        return "cut", "report cut off before its first complete leak (a process killed while writing it)"
    if not known:
        return "finding", "leak report without a direct leak"
    return "lammps", ", ".join(sorted(known)) + (" (report cut off at its end)" if truncated else "")


def main(paths):
    findings = 0
    for p in paths:
        with open(p, errors="replace") as fh:
            kind, detail = classify(fh.read())
        findings += kind == "finding"
        print(f"{ {'finding': 'FINDING', 'cut': 'CUT    '}.get(kind, 'LAMMPS ')} {p}: {detail}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
