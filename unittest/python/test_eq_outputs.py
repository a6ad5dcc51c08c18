"""Outputs and hooks of fix eq/contacts: fix_modify energy, the global
vector against compute reduce over the per-atom array, minimization (the
contacts hold and the slider relaxes onto the anchors), and atoms created
after the fix."""
from pathlib import Path

import eqtools

INPUT = Path(__file__).resolve().parent / "inputs" / "in.outputs"


def thermo_rows(log):
    rows = []
    for line in log.splitlines():
        w = line.split()
        if len(w) == 10 and w[0].isdigit():
            rows.append([float(v) for v in w])
    return rows


def test_outputs_energy_minimize_and_new_atoms(tmp_path):
    log = eqtools.run_lammps(INPUT, {"out": tmp_path}, cwd=tmp_path)
    rows = thermo_rows(log)
    # columns: step pe f_c f_c[5] f_c[1] c_F f_c[3] c_B f_c[4] f_c[7]
    for step, pe, scalar, energy, F, sumF, total, sumB, att, n in rows:
        assert pe == scalar == energy                     # fix_modify energy yes
        assert abs(F - sumF) <= 1e-12 * max(1.0, abs(F))  # global F = sum of per-atom forces
        assert total == sumB                              # total breaks = sum of per-atom counts
        assert att == n
    run = [r for r in rows if r[0] <= 250]
    assert run[-1][6] > 500                               # contacts broke while sliding
    # minimization: nothing breaks, the slider relaxes onto the anchors
    after = [r for r in rows if r[0] > 250 and r[9] == 400]
    assert after and after[-1][6] == run[-1][6]
    assert after[-1][1] < 1e-20 and abs(after[-1][4]) < 1e-12
    # an atom created after the fix is a contact (relaxed where it appears)
    last = rows[-1]
    assert last[9] == 401 and last[8] == 401 and last[6] > run[-1][6]
