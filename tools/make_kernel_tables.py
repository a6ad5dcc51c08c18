#!/usr/bin/python3
"""Write potentials/eq_crossover.table: the crossover kernel of pair
eq/elastic (k = ftilde/r below lambda_c, ftilde lambda_c^2/r^3 beyond) in
the package's kernel-table format, for ftilde = 1 (scale with the
pair_coeff of a table? no: tables are used as written -- pick the section
for your ftilde or rescale the file), and an anisotropic example.

    /usr/bin/python3 tools/make_kernel_tables.py [potentials/eq_crossover.table]

Sections:
  CROSSOVER_L3   ftilde = 1, lambda_c = 3, r in [0.5, 10]
  CROSSOVER_L5   ftilde = 1, lambda_c = 5, r in [0.5, 15]
  ANISO_TEST     k0 = 1/r, k2 = 0.3/r, r in [0.5, 8] (harness test)
"""
import sys
from pathlib import Path

import numpy as np


def crossover(r, lam):
    return np.where(r <= lam, 1.0 / r, lam * lam / r ** 3)


def section(f, name, r, k0, k2=None, note=""):
    f.write("\n# %s\n%s\nN %d%s\n\n" % (note, name, len(r), " aniso" if k2 is not None else ""))
    for i in range(len(r)):
        if k2 is None:
            f.write("%d %.10g %.16g\n" % (i + 1, r[i], k0[i]))
        else:
            f.write("%d %.10g %.16g %.16g\n" % (i + 1, r[i], k0[i], k2[i]))


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else
               Path(__file__).resolve().parents[1] / "potentials" / "eq_crossover.table")
    with open(out, "w") as f:
        f.write("# FRICTION-EQ kernel tables for pair_style eq/elastic (pair_coeff I J table FILE KEYWORD)\n"
                "# format: KEYWORD / N n [aniso] / index r k0 [k2]; k(r,phi) = k0(r) + k2(r) cos(2 phi)\n"
                "# written by tools/make_kernel_tables.py\n")
        # points on the kinks: lambda_c is a grid point, so linear interpolation
        # of r k(r) is exact below lambda_c
        for lam, rmax in ((3.0, 10.0), (5.0, 15.0)):
            r = np.unique(np.concatenate([np.linspace(0.5, lam, 26), np.linspace(lam, rmax, 141)]))
            section(f, "CROSSOVER_L%d" % lam, r, crossover(r, lam),
                    note="ftilde = 1, lambda_c = %g: k = 1/r (r <= %g), %g/r^3 beyond" % (lam, lam, lam * lam))
        r = np.linspace(0.5, 8.0, 76)
        section(f, "ANISO_TEST", r, 1.0 / r, 0.3 / r, note="anisotropic test kernel k0 = 1/r, k2 = 0.3/r")
    print("wrote", out)


if __name__ == "__main__":
    main()
