"""fix eq/quasistatic: the slider advances exactly to the next break.

* Without interaction, F(X) between two events is linear (all attached
  contacts stretch at the same rate), so the quasi-static record gives F at
  any X exactly; fixed-step driving with exact crossing is also exact at
  its grid points (issue 2): the two must agree to rounding.
* With interaction (pair eq/elastic), fixed steps resolve the breaks of a
  step together (cellular automaton).  With reform_as force (default) the
  cascade is Abelian and the step ends are exact; with reform_as stretch
  the lumped events carry an error that falls with dX.
"""
from pathlib import Path

import numpy as np

import eqtools

ROOT = Path(__file__).resolve().parents[2]
INPUT = ROOT / "unittest" / "python" / "inputs" / "in.quasistatic"


def run(tmp, **var):
    tmp.mkdir(parents=True, exist_ok=True)
    eqtools.run_lammps(INPUT, dict(var, out=tmp), cwd=tmp)
    d = eqtools.load(tmp / "F.dat")
    return d[:, 1], d[:, 2], d[:, 3], d[:, 4]


def qs_force_at(Xq, Fq, attq, Xg):
    """F/(N k_c) at Xg from a quasi-static record (k_c = 1): the value
    after the last event at or before Xg plus the uniform stretching."""
    i = np.searchsorted(Xq, Xg, side="right") - 1
    n = 480.0
    return Fq[i] + (Xg - Xq[i]) * attq[i] / n


def test_quasistatic_is_exact_without_interaction(tmp_path):
    Xq, Fq, attq, bq = run(tmp_path / "qs", drive="qs", dX=0.05)
    Xs, Fs, _, _ = run(tmp_path / "step", drive="step", dX=0.013)
    assert bq.sum() > 2 * 480              # every contact broke, twice on average
    m = (Xs > 0) & (Xs <= Xq[-1])
    assert np.max(np.abs(qs_force_at(Xq, Fq, attq, Xs[m]) - Fs[m])) < 1e-11
    # one step per break (ties aside) and no advance beyond the max keyword
    assert np.all(np.diff(Xq) <= 0.05 + 1e-15)
    assert np.mean(bq[1:] == 1) > 0.95


def test_fixed_steps_exact_at_step_ends_with_reform_as_force(tmp_path):
    """With reform_as force a break lowers the contact's own stretch by
    k (x_s - r)/(k + K), whatever its neighbours did, and raises their
    forces: breaks only promote breaks (an Abelian cascade), so the state
    at the end of a step does not depend on the order of the breaks within
    it.  Fixed steps then give the exact F at every step end, for any dX."""
    kappa = 0.04
    Xq, Fq, attq, _ = run(tmp_path / "qs", drive="qs", kappa=kappa, Xmax=2.5)
    for dX in (0.04, 0.013):
        Xs, Fs, _, bs = run(tmp_path / f"step{dX}", drive="step", kappa=kappa, dX=dX, Xmax=2.4)
        assert np.max(bs) >= 3                      # steps with several breaks
        m = Xs > 0
        assert np.max(np.abs(qs_force_at(Xq, Fq, attq, Xs[m]) - Fs[m])) < 1e-11


def test_fixed_steps_converge_with_reform_as_stretch(tmp_path):
    """reform_as stretch: the re-formed stretch does not depend on the
    field, the cascade is not Abelian and fixed steps lump the events of a
    step: an error that falls with dX."""
    kappa = 0.04
    Xq, Fq, attq, _ = run(tmp_path / "qs", drive="qs", kappa=kappa, rmode="stretch", Xmax=2.5)
    errs = []
    for dX in (0.04, 0.01, 0.0025):
        Xs, Fs, _, _ = run(tmp_path / f"step{dX}", drive="step", kappa=kappa, dX=dX,
                           rmode="stretch", Xmax=2.4)
        m = Xs > 0
        errs.append(np.sqrt(np.mean((qs_force_at(Xq, Fq, attq, Xs[m]) - Fs[m]) ** 2)))
    assert errs[0] > 1e-3, errs
    assert errs[0] > errs[1] > errs[2], errs
