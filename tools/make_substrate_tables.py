#!/usr/bin/python3
"""Write potentials/eq_substrate.table: substrate shapes phi(u) = F(u)/(N k_c)
of a rigid lambda_c block from the master equation, for fix eq/substrate
... table (paper Sec. V B: "the substrate force F_s(u) is found from the
solution of the ME for the rigid lambda_c-block").  Each section is written
by the package's own solver (build/eq-me ... substrate FILE KEYWORD uc):

    /usr/bin/python3 tools/make_substrate_tables.py [potentials/eq_substrate.table]

Sections:
  UNIFORM_0.75_1.25  thresholds uniform on [0.75, 1.25], contacts re-form
                     unstretched, relaxed start; uc = 1.25 (every contact has
                     broken once): a rounded sawtooth, peak 0.75 at u = 0.75
  REALISTIC_1.0      the paper's realistic thresholds (x_s = 1), re-forming
                     unstretched; uc = 2.0
"""
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
from eqtools import eqme_exe  # noqa: E402

SECTIONS = [
    ("UNIFORM_0.75_1.25", ["threshold", "uniform", "0.75", "1.25"], 1.25, 2.0),
    ("REALISTIC_1.0", ["threshold", "realistic", "1.0"], 2.0, 3.0),
]


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "potentials" / "eq_substrate.table")
    parts = ["# FRICTION-EQ substrate shapes for fix eq/substrate (fix ID group eq/substrate kc table FILE KEYWORD)\n"
             "# format: KEYWORD / N n / index u phi(u); phi = F(u)/(N k_c) of a rigid block, master equation\n"
             "# written by tools/make_substrate_tables.py (build/eq-me ... dx 0.005 substrate FILE KEYWORD uc)\n"]
    with tempfile.TemporaryDirectory() as tmp:
        for key, spec, uc, xmax in SECTIONS:
            path = Path(tmp) / (key + ".table")
            subprocess.run([eqme_exe()] + spec + ["xmax", str(xmax), "dx", "0.005", "substrate",
                                                  str(path), key, str(uc)],
                           check=True, stdout=subprocess.DEVNULL)
            parts.append("\n" + path.read_text())
    out.write_text("".join(parts))
    print("wrote", out)


if __name__ == "__main__":
    main()
