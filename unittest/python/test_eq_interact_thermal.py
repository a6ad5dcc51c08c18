"""Interacting contacts (pair eq/elastic) at T > 0 and with aging (issue
23, item 1 for the interacting path; fix eq/contacts thermal, barrier,
aging, rest with pair eq/elastic).

Each step first samples the thermal breaks of the formed contacts along
their effective stretch e = s + h/k, linear from the end of the last step
to the new positions in the field of the step's start
(ContactModel::probe(), the thinning sampler of the plain path, up to the
aged threshold); the thermally broken contacts break in the avalanche's
first round, at the |e| where they broke, the motion since carried; the
avalanche tests the aged thresholds x_s0 A(age).  References:

- without coupling (kappa = 0) the path is the plain thermal fix
  (tested against the master equation in test_eq_thermal.py), the same
  draws: F(X) within one standard deviation of F for N contacts, the
  breaks within 1 %;
- at theta = 0 with vanishing aging the thermo output is the athermal
  interacting fix's, character for character;
- 1, 2, 4 ranks: the same breaks of every contact, values to rounding;
  a run split by a restart continues it the same way;
- with coupling, F_k falls as v falls (thermal creep: velocity
  strengthening), by far more than its scatter;
- a delay is an error naming the keyword; contacts that wait in a
  restart file written with one re-form at the set-up.
"""
import numpy as np
import pytest

import eqtools
from conftest import ROOT

INPUT = ROOT / "unittest" / "python" / "inputs" / "in.interact-thermal"
N = 480


def thermo(log):
    """Rows step X F/(N k_c) breaks rounds of the run."""
    rows = []
    for line in log.splitlines():
        parts = line.split()
        if len(parts) == 5:
            try:
                rows.append([float(x) for x in parts])
            except ValueError:
                pass
    return np.array(rows)


def run(d, nprocs=1, **var):
    d.mkdir(parents=True, exist_ok=True)
    return eqtools.run_lammps(INPUT, dict(var, out=d), nprocs=nprocs, cwd=d)


def state(d):
    text = (d / "state.dump").read_text().split("ITEM: ATOMS")[-1].splitlines()[1:]
    return np.array([[float(x) for x in l.split()] for l in text if l.strip()])


@pytest.mark.parametrize("extra", ["thermal 0.03 1.0 1.0",
                                   "thermal 0.05 1.0 1.0 barrier 2 0.25",
                                   "thermal 0.03 1.0 1.0 aging log 0.05 1.0 rest 10"])
def test_without_coupling_it_is_the_plain_thermal_path(tmp_path, extra):
    """kappa = 0: pair eq/elastic with no interaction against the fix
    without a pair style.  Both draw the same numbers; they differ where
    the plain path samples a new life over the rest of its step (the
    interacting one from the next step) and, with aging, where a crossing
    of the aged threshold is placed (within the step, or at its end).
    Bound: max |dF| below 1/sqrt(N) (0.046; F's standard deviation for N
    contacts is about 0.25/sqrt(N)), the mean below a quarter of that,
    the breaks within 1 % (measured: max 3.4e-3, 2.0e-3, 7.3e-3 and mean
    3.4e-4, 3.2e-4, 8.8e-4 over the samples every 0.05 x_c; the breaks
    equal to +-2)."""
    a = thermo(run(tmp_path / "pair", kappa=0.0, extra=extra))
    b = thermo(run(tmp_path / "plain", pair="no", extra=extra))
    assert a.shape == b.shape and a[-1, 1] == pytest.approx(4.0)
    dF = np.abs(a[:, 2] - b[:, 2])
    assert dF.max() < 1.0 / np.sqrt(N), dF.max()
    assert dF.mean() < 0.25 / np.sqrt(N), dF.mean()
    assert abs(a[-1, 3] - b[-1, 3]) <= 0.01 * b[-1, 3]
    assert b[-1, 3] > 3 * N    # each contact broke several times
    # the keywords matter: the athermal run is off by more than 5 standard
    # deviations of F somewhere
    c = thermo(run(tmp_path / "athermal", kappa=0.0, more=""))
    assert np.abs(a[:, 2] - c[:, 2]).max() > 5 * 0.25 / np.sqrt(N), np.abs(a[:, 2] - c[:, 2]).max()


def test_vanishing_aging_at_zero_temperature_is_the_athermal_path(tmp_path):
    """theta = 0 with aging of strength 1e-300 takes the thermal layout and
    the probe (ages, aged thresholds A = 1 to the bit) and must give the
    athermal interacting run to the last printed digit."""
    a = run(tmp_path / "aged", extra="aging log 1e-300 1.0", Xmax=2.0)
    b = run(tmp_path / "plain", Xmax=2.0, more="")
    ta, tb = thermo(a), thermo(b)
    assert ta.shape == tb.shape and ta[-1, 3] > N
    assert np.array_equal(ta, tb)


def test_ranks_and_restart(tmp_path):
    """kappa = 0.06, theta = 0.03, aging after a rest: 1, 2, 4 ranks give
    every contact's break count exactly and its stretch, threshold,
    anchor, field, budget and age to 1e-9 (the field is a sum whose order
    follows the neighbour lists: rounding; test_eq_interact_parallel.py);
    a run split by write_restart/read_restart on 2 -> 4 ranks continues
    it the same way."""
    extra = "thermal 0.03 1.0 1.0 aging log 0.05 1.0 rest 10"
    data = tmp_path / "contacts.data"    # the same atom IDs at the same sites
    (tmp_path / "in.data").write_text(
        "units lj\ndimension 2\natom_style atomic\nboundary p p p\n"
        "lattice hex 1.1547005383792515\nregion box block 0 20 0 12 -0.5 0.5\n"
        "create_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\nwrite_data %s\n" % data)
    eqtools.run_lammps(tmp_path / "in.data", {}, cwd=tmp_path)
    ref = None
    for n in (1, 2, 4):
        d = tmp_path / f"np{n}"
        run(d, nprocs=n, extra=extra, Xmax=2.0, start="data", file=str(data))
        got = state(d)
        if ref is None:
            ref = got
            assert ref[:, 3].sum() > N    # breaks
        else:
            assert np.array_equal(got[:, [0, 3]], ref[:, [0, 3]]), n
            assert np.allclose(got, ref, rtol=1e-9, atol=1e-9), n
    d = tmp_path / "split"
    run(d, nprocs=2, extra=extra, Xmax=1.0, wr="half.restart", start="data", file=str(data))
    run(d, nprocs=4, extra=extra, Xmax=2.0, start="restart", file="half.restart")
    got = state(d)
    assert np.array_equal(got[:, [0, 3]], ref[:, [0, 3]])
    assert np.allclose(got, ref, rtol=1e-9, atol=1e-9)


def test_friction_falls_with_velocity(tmp_path):
    """kappa = 0.06, theta = 0.03: the mean F/(N k_c) over X in [2, 4] at
    v = 0.1, 0.01, 0.001 decreases (thermal breaks below the thresholds
    grow as loading slows), each time by more than 0.02.  Measured (seeds
    11, 12, 13, 4711): 0.504-0.508, 0.452-0.456, 0.399-0.402 (standard
    deviation between seeds 0.0015, so the bound is 13 of them; the
    athermal run 0.534)."""
    means = []
    for v in (0.1, 0.01, 0.001):
        t = thermo(run(tmp_path / f"v{v}", v=v, extra="thermal 0.03 1.0 1.0"))
        means.append(t[t[:, 1] >= 2.0, 2].mean())
    assert means[0] - means[1] > 0.02 and means[1] - means[2] > 0.02, means


def test_waiting_contacts_of_a_restart_reform(tmp_path):
    """A restart file of independent contacts with a delay (86 of the
    480 waiting at X = 1) continued with the pair style, whose contacts take no
    delay: the waiting ones re-form at the set-up, so that after one step
    none waits and every contact carries force again (F far above the
    waiting state's)."""
    extra = "thermal 0.03 1.0 1.0"
    run(tmp_path, pair="no", extra=extra + " delay exp 10.0", Xmax=1.0, wr="w.restart",
        more="f_c[10]")
    waiting = state(tmp_path)[:, -1]
    assert (waiting > 0).sum() > N / 10    # many wait
    t = thermo(run(tmp_path, extra=extra, Xmax=1.002, start="restart", file="w.restart",
                   more="f_c[10]"))
    assert (state(tmp_path)[:, -1] == 0.0).all()
    assert np.isfinite(t[:, 2]).all()


def test_delay_is_an_error(tmp_path):
    log = eqtools.run_lammps(INPUT, {"out": tmp_path, "extra": "delay exp 10.0"}, cwd=tmp_path,
                             check=False)
    assert "Fix c eq/contacts delay: not supported with pair style eq/elastic" in log, log[-2000:]
