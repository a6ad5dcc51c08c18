#!/usr/bin/python3
"""Include structure of the FRICTION-EQ sources: a check anyone can run.

  /usr/bin/python3 tools/check_includes.py [src/FRICTION-EQ]

Checks, over the package's own files (src/FRICTION-EQ/*.{h,cpp} and
lib/*.{h,cpp}; LAMMPS' and system headers are not followed):

1. no include cycle among the package's files;
2. no style includes another style's header: a style (a file that
   registers FixStyle/PairStyle/CommandStyle) meets the others only
   through the interfaces in eq_field.h;
3. the LAMMPS-free kernels in lib/ include nothing of LAMMPS and nothing
   outside lib/.

Prints the include graph of the styles and exits 1 on any violation.
"""
import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
STYLE = re.compile(r"^(Fix|Pair|Command)Style\(", re.M)


def main(argv):
    root = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parents[1] / "src" / "FRICTION-EQ"
    files = {}
    for p in sorted(root.glob("*.h")) + sorted(root.glob("*.cpp")) + \
            sorted((root / "lib").glob("*.h")) + sorted((root / "lib").glob("*.cpp")):
        files[p.name] = p
    graph = {name: [inc for inc in INCLUDE.findall(p.read_text()) if inc in files]
             for name, p in files.items()}
    problems = []

    # 1. cycles (depth-first search with colours)
    colour = {n: 0 for n in graph}
    stack = []

    def visit(n):
        colour[n] = 1
        stack.append(n)
        for m in graph[n]:
            if colour[m] == 1:
                cyc = stack[stack.index(m):] + [m]
                problems.append("include cycle: " + " -> ".join(cyc))
            elif colour[m] == 0:
                visit(m)
        stack.pop()
        colour[n] = 2

    for n in graph:
        if colour[n] == 0:
            visit(n)

    # 2. styles include no other style's header
    style_headers = {n for n, p in files.items() if n.endswith(".h") and STYLE.search(p.read_text())}
    for n, incs in graph.items():
        own = n.rsplit(".", 1)[0] + ".h"
        for inc in incs:
            if inc in style_headers and inc != own:
                problems.append(f"{n} includes the style header {inc} (use eq_field.h)")

    # 3. lib/ is LAMMPS-free
    for n, p in files.items():
        if p.parent.name != "lib":
            continue
        for inc in INCLUDE.findall(p.read_text()):
            if inc not in files or files[inc].parent.name != "lib":
                problems.append(f"lib/{n} includes {inc}, which is not a LAMMPS-free kernel")

    print(f"{len(files)} files, {sum(len(v) for v in graph.values())} includes among them; "
          f"styles: {', '.join(sorted(style_headers))}")
    for n in sorted(graph):
        if not n.endswith(".cpp") or files[n].parent.name == "lib":
            continue
        print(f"  {n}: {', '.join(graph[n]) or '-'}")
    for p in problems:
        print("PROBLEM:", p)
    print("include structure:", "OK" if not problems else f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
