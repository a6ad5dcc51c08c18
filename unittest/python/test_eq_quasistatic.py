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
from eqtools import fkme

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


def test_induced_break_carry_and_reset(tmp_path):
    """The rule for a contact pushed past its threshold by a partner's
    break, against the model worked out by hand for two contacts (k = 1,
    k_12 = c = 1/r, r = |(0.1, 1)|, re-forming relaxed in the field,
    r_reform = 0): the slider advances until contact 1 reaches x_s1 and
    breaks, s1' = c s2/(1 + c); contact 2 is then at e2 = s2 + c (s2 - s1')
    > x_s2 and breaks in round 2.  crossing exact carries the overshoot
    e2 - x_s2 into the new contact (its force after the break is
    k (e2 - x_s2)); crossing step resets it to force 0."""
    c = 1.0 / np.hypot(0.1, 1.0)
    for crossing in ("exact", "step"):
        d = tmp_path / crossing
        d.mkdir()
        eqtools.run_lammps(INPUT.parent / "in.two-contacts", {"crossing": crossing, "out": d},
                           cwd=d)
        _, dump = fkme.read_dump(d / "d.dump")   # sorted by id, one row per frame
        s, th, fc, nb, h = (dump[k] for k in ("f_c[1]", "f_c[2]", "f_c[3]", "f_c[4]", "f_c[7]"))
        th1, th2 = th[0]
        assert np.allclose(s[0], [0.3, 0.2], atol=1e-12)
        adv = th1 - 0.3 - c * 0.1                # advance to contact 1's threshold
        s1, s2 = 0.3 + adv, 0.2 + adv
        s1n = c * s2 / (1 + c)
        e2 = s2 + c * (s2 - s1n)
        assert e2 - th2 > 0.1                    # contact 2 is pushed well past
        carry = e2 - th2 if crossing == "exact" else 0.0
        s2n = (carry + c * s1n) / (1 + c)
        assert np.array_equal(nb[1], [1, 1])     # each broke once
        assert np.allclose(s[1], [s1n, s2n], rtol=0, atol=1e-12), (crossing, s[1])
        h1 = c * (s1n - s2n)
        assert np.allclose(h[1], [h1, -h1], rtol=0, atol=1e-12)
        # contact 2's force after the break: the carried overshoot, or 0
        assert abs(fc[1, 1] + h[1, 1] - carry) < 1e-12
        av = np.loadtxt(d / "av.dat")
        assert list(av) == [1, 2, 1, 2]          # step, size, trigger, rounds
