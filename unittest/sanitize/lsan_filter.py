#!/usr/bin/python3
"""Sort the sanitizer reports of ./friction-eq test --sanitize.

LeakSanitizer's suppressions match a function anywhere in an allocation's
stack, which is too wide for LAMMPS' own leaks: a suppression of
Input::ifthenelse() would also hide every leak of a command that an input
runs through 'if ... then', the package's commands included.  This filter
is narrower: a leak report is LAMMPS' own when every *direct* leak in it
was allocated by one of the functions below itself (frame #1, the caller
of operator new); indirect leaks are reachable only from direct ones and
go with them.  Any other report (a direct leak elsewhere, any
AddressSanitizer error, any UBSan finding) is a finding.

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
}

BLOCK_RE = re.compile(r"^(Direct|Indirect) leak of (\d+) byte", re.M)
FRAME1_RE = re.compile(r"^\s*#1 0x[0-9a-f]+ in (.+?)(?: \S+:\d+(?::\d+)?)?$", re.M)


def classify(text):
    """(kind, detail): kind 'lammps' (only known direct leaks) or 'finding'."""
    if re.search(r"ERROR: AddressSanitizer|runtime error: ", text):
        return "finding", "AddressSanitizer/UBSan error"
    if "ERROR: LeakSanitizer" not in text:
        return "finding", "unrecognised report"
    starts = [m.start() for m in BLOCK_RE.finditer(text)] + [len(text)]
    known = set()
    for a, b in zip(starts, starts[1:]):
        block = text[a:b]
        if not block.startswith("Direct"):
            continue
        m = FRAME1_RE.search(block)
        func = m.group(1) if m else "?"
        hit = [k for k in KNOWN if k in func]
        if not hit:
            return "finding", f"direct leak allocated in {func}"
        known |= set(hit)
    if not known:
        return "finding", "leak report without a direct leak"
    return "lammps", ", ".join(sorted(known))


def main(paths):
    findings = 0
    for p in paths:
        with open(p, errors="replace") as fh:
            kind, detail = classify(fh.read())
        findings += kind == "finding"
        print(f"{'FINDING' if kind == 'finding' else 'LAMMPS '} {p}: {detail}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
