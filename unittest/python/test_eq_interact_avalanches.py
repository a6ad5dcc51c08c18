"""Avalanche size of interacting contacts (pair eq/elastic, fix
eq/quasistatic): the size written by the *avalanches* keyword of fix
eq/contacts is the number of breaks in the step, a contact counted each
time it breaks.  Above the breakdown strength a contact can break more
than once within one avalanche, so sizes can exceed the number of
contacts (on 4080 contacts: 4095 breaks of 4079 contacts at kappa = 0.2,
8387 breaks of all 4080 at 0.5, up to 3 per contact; run_onset.py).

Checked against the per-contact break counters f_c[4] dumped every step:
size = sum of their increments, and at kappa = 0.5 the largest avalanche
has more breaks than distinct contacts, and more than N (480 contacts:
997 breaks of all 480, up to 3 per contact; 1.2 s).
"""
import numpy as np

import eqtools
from conftest import ROOT

INPUT = ROOT / "examples" / "eq-interact" / "in.eq-interact"


def read_counts(path):
    rows = np.loadtxt(path, skiprows=9)
    return rows[np.argsort(rows[:, 0]), 1]


def test_avalanche_size_counts_repeat_breaks(tmp_path):
    # the example input with a dump of every contact's break count
    text = INPUT.read_text().replace(
        "variable        Xend equal",
        "dump            d all custom 1 ${out}/nbreak.* id f_c[4]\n"
        "dump_modify     d sort id\n"
        "variable        Xend equal", 1)
    assert "nbreak" in text
    infile = tmp_path / "in.avalanche"
    infile.write_text(text)
    nx, ny = 20, 12
    N = 2 * nx * ny
    eqtools.run_lammps(infile, {"kappa": 0.5, "nx": nx, "ny": ny, "Xmax": 1.3, "dX": 0.005,
                                "out": tmp_path}, cwd=tmp_path)
    av = np.atleast_2d(np.loadtxt(tmp_path / "avalanches.dat"))
    for step, size in av[:, :2].astype(int):
        before = read_counts(tmp_path / ("nbreak.%d" % (step - 1)))
        after = read_counts(tmp_path / ("nbreak.%d" % step))
        assert int(np.sum(after - before)) == size, step
    i = int(np.argmax(av[:, 1]))
    step, size = int(av[i, 0]), int(av[i, 1])
    inc = read_counts(tmp_path / ("nbreak.%d" % step)) - read_counts(tmp_path / ("nbreak.%d" % (step - 1)))
    distinct = int(np.count_nonzero(inc))
    assert size > distinct and size > N, (size, distinct, N)
    assert inc.max() >= 2
