"""Stability stress of the package's styles: every case either runs
correctly (checked against an analytic, conservation or master-equation
reference) or stops with an error (or, where the run can go on, a
warning) that names the cause and the parameter to change.

Inputs: inputs/in.reliability-stress-contacts (fix eq/contacts, pair
eq/elastic, fix eq/quasistatic; n x n contacts) and
inputs/in.reliability-stress-blocks (fix eq/substrate, fix eq/meso; a
chain of n blocks).  Cases:

* empty group (N = 0): an error at the fix command; all atoms deleted
  after the fix: the run goes on with zero output (quasistatic without a
  cap: an error);
* one contact / one block (N = 1): exact bookkeeping (anchor increments =
  thresholds, quasistatic advances = distance to the threshold, substrate
  energy and forces = the closed forms, the crossing impulse = (1 - theta)
  J); one contact with pair eq/elastic in a box shorter than the cutoff
  (its own periodic images);
* drive too fast: several thresholds per step (exact crossing: F(X)
  against the master equation; meso blocks: independent of the step);
  more than 1000 breaks of a contact in a step (error); a slider step
  beyond half the box (silent: a bug); the stage of fix eq/substrate
  faster than half a period per step (warning);
* timestep too large / stiff coupling: the overdamped integrators beyond
  their stability limit;
* interaction strong enough for runaway avalanches; re-forming next to the
  threshold; thresholds near zero: either every avalanche is resolved
  (no contact left above its threshold after a step, energy and force
  sums consistent) or an error names the pair coefficients / reform_as;
* a long run: 99856 contacts x 2000 steps = 2.0e8 contact-steps (about
  5 s on one rank), checked against the master equation (force, breaks,
  energy) and the per-contact invariants.
"""
import math
import os
import re
from pathlib import Path

import numpy as np
import pytest

import eqtools
from eqtools import fkme

# up to 4 ranks share 2 cores: a rank that waits must give the core back
# (Open MPI's busy polling makes such runs up to 100 times slower on a
# loaded machine); inherited by the runs of this file only
os.environ.setdefault("OMPI_MCA_mpi_yield_when_idle", "1")

INPUTS = Path(__file__).resolve().parent / "inputs"
CONTACTS = INPUTS / "in.reliability-stress-contacts"
BLOCKS = INPUTS / "in.reliability-stress-blocks"
EPS = np.finfo(float).eps


def lmp(infile, tmp_path, nprocs=1, **var):
    """Run LAMMPS, return (ok, output); never raises on a LAMMPS error."""
    tmp_path.mkdir(parents=True, exist_ok=True)
    p = eqtools.run_lammps(infile, dict(var, out=tmp_path), nprocs=nprocs, cwd=tmp_path,
                           check=False)
    return "ERROR" not in p and "Total wall time" in p, p


def ok(infile, tmp_path, **var):
    good, out = lmp(infile, tmp_path, **var)
    assert good, out[-3000:]
    return out


def error(infile, tmp_path, pattern, **var):
    """The run stops with an error matching `pattern` (a regex)."""
    good, out = lmp(infile, tmp_path, **var)
    assert not good, out[-3000:]
    lines = [l for l in out.splitlines() if "ERROR" in l]
    assert lines, out[-3000:]
    assert re.search(pattern, lines[0]), lines[0]
    return lines[0]


def thermo(out, ncol):
    rows = []
    for line in out.splitlines():
        w = line.split()
        if len(w) == ncol and w[0].isdigit():
            try:
                rows.append([float(v) for v in w])
            except ValueError:
                pass
    return np.array(rows)


# columns of in.reliability-stress-contacts' thermo: step pe f_c f_c[1..8]
# (0 step, 1 pe, 2 contact energy, 3 F, 4 breaks in the step, 5 total
# breaks, 6 attached, 7 energy, 8 mean stretch, 9 contacts, 10 rounds)
TH_C = 11


# ------------------------------------------------------------------ N = 0
@pytest.mark.parametrize("infile,style", [(CONTACTS, "contacts"), (BLOCKS, "substrate"),
                                          (BLOCKS, "meso")])
def test_empty_group_is_an_error(tmp_path, infile, style):
    var = {} if style == "contacts" else {"style": style}
    error(infile, tmp_path, rf"Fix eq/{style}: group all has no atoms", n=0, **var)


@pytest.mark.parametrize("case", ["contacts", "contacts-pair", "quasistatic", "substrate",
                                  "meso"])
def test_all_atoms_deleted_the_run_goes_on(tmp_path, case):
    """The group's atoms deleted after the fix command: the run (on 2
    ranks) completes and every output is zero (no contact, no block)."""
    if case.startswith(("contacts", "quasistatic")):
        var = dict(kappa=0.1 if case == "contacts-pair" else 0.0,
                   drive="qs" if case == "quasistatic" else "move")
        good, out = lmp(CONTACTS, tmp_path, nprocs=2, n=4, delete=1, steps=20, thermo=10, **var)
        assert good, out[-3000:]
        rows = thermo(out, TH_C)
        assert len(rows) == 3 and np.all(rows[:, 1:] == 0), rows
    else:
        good, out = lmp(BLOCKS, tmp_path, nprocs=2, n=4, delete=1, steps=20, thermo=10,
                        style=case)
        assert good, out[-3000:]
        rows = thermo(out, 4)
        assert len(rows) == 3 and np.all(rows[:, 1:] == 0), rows


def test_quasistatic_without_contacts_and_cap_is_an_error(tmp_path):
    """Without contacts nothing can break; without max the advance is
    undefined: an error that says so."""
    error(CONTACTS, tmp_path, r"Fix eq/quasistatic: no attached contact left in fix c", n=2,
          delete=1, drive="qs", dX=0, steps=5)


# ------------------------------------------------------------------ N = 1
def test_one_contact_bookkeeping(tmp_path):
    """One contact (reform delta 0, crossing exact), slider by fix move:
    every break moves the anchor by exactly the threshold it broke at (the
    overshoot is carried into the new contact), the stretch is xu - anchor
    and stays below the threshold.  Driven quasi-statically (no cap) every
    step advances the slider by exactly the distance to the threshold."""
    ok(CONTACTS, tmp_path / "move", n=1, a=8.0, steps=600, every=1)
    steps, d = fkme.read_dump(tmp_path / "move" / "contacts.dump")
    xu, s, th, nb, a = (d[c][:, 0] for c in ("xu", "f_c[1]", "f_c[2]", "f_c[4]", "f_c[6]"))
    k = np.nonzero(np.diff(nb))[0]
    assert len(k) >= 4 and np.all(np.diff(nb) <= 1)
    assert np.allclose(a[k + 1] - a[k], th[k], rtol=0, atol=8 * EPS * np.abs(xu).max())
    assert np.allclose(s, xu - a, rtol=0, atol=4 * EPS * np.abs(xu).max())
    assert np.all(np.abs(s) < th)
    ok(CONTACTS, tmp_path / "qs", n=1, a=8.0, drive="qs", dX=100.0, steps=50, every=1)
    steps, d = fkme.read_dump(tmp_path / "qs" / "contacts.dump")
    xu, s, th, nb = (d[c][:, 0] for c in ("xu", "f_c[1]", "f_c[2]", "f_c[4]"))
    assert np.array_equal(nb, np.arange(51))                # one break per step
    assert np.allclose(np.diff(xu), (th - s)[:-1], rtol=0, atol=8 * EPS * np.abs(xu).max())


def test_one_contact_with_pair_in_a_box_shorter_than_the_cutoff(tmp_path):
    """One contact with pair eq/elastic: its only partners are its own
    periodic images, whose stretch is always its own, so the field is 0
    and the contact must behave as without interaction: the same breaks
    at the same slider positions, the same stretches."""
    ok(CONTACTS, tmp_path / "free", n=1, a=1.0, steps=300, every=1)
    ok(CONTACTS, tmp_path / "pair", n=1, a=1.0, kappa=0.1, steps=300, every=1)
    _, a = fkme.read_dump(tmp_path / "free" / "contacts.dump")
    _, b = fkme.read_dump(tmp_path / "pair" / "contacts.dump")
    assert np.all(b["f_c[7]"] == 0) or np.abs(b["f_c[7]"]).max() < 1e-12
    assert np.array_equal(a["f_c[4]"], b["f_c[4]"])
    assert np.abs(a["f_c[1]"] - b["f_c[1]"]).max() < 1e-12


def test_one_block_energy_and_forces_are_the_closed_forms(tmp_path):
    """One fix eq/substrate block (sawtooth, k_c = 1, u_c = 1, reverse
    periodic), K = 0.5, stage from 0 at v = 0.2, fix brownian: at every
    step the energy (fix_modify energy yes) is k_c [W a + (u - a)^2/2] +
    K/2 (u - X_s)^2 (W = 1/2, a = floor(u)), the driving force K (X_s - u),
    the substrate force -(u - a); at a step that crosses into the next
    well the crossing impulse (1 - theta) J, J = 1, theta the crossing
    fraction linear between the two positions (fix brownian: w = 1)."""
    out = ok(BLOCKS, tmp_path, n=1, g=0, K=0.5, v=0.2, eta=1.0, f0=0.0, steps=300, every=1,
             thermo=1)
    rows = thermo(out, 4)
    steps, d = fkme.read_dump(tmp_path / "blocks.dump")
    assert np.array_equal(rows[:, 0], steps)
    u = d["f_sub[1]"][:, 0]
    Xs = 0.2 * 0.1 * np.asarray(steps, float)
    a = np.floor(u)
    E = 0.5 * a + 0.5 * (u - a) ** 2 + 0.25 * (u - Xs) ** 2
    # rounding: the squares of coordinates up to |u| + |X_s| (about 7)
    tol = 64 * EPS * (1.0 + np.abs(u).max() + np.abs(Xs).max()) ** 2
    assert np.abs(rows[:, 3] - E).max() < tol
    assert np.abs(d["f_sub[3]"][:, 0] - 0.5 * (Xs - u)).max() < tol
    cross = np.nonzero(np.diff(a))[0] + 1
    assert len(cross) >= 3
    plain = np.ones(len(u), bool)
    plain[cross] = False
    assert np.abs(d["f_sub[2]"][plain, 0] + (u - a)[plain]).max() < 8 * EPS * u.max()
    theta = (a[cross] - u[cross - 1]) / (u[cross] - u[cross - 1])
    impulse = d["f_sub[2]"][cross, 0] + (u - a)[cross]
    assert np.allclose(impulse, 1.0 - theta, rtol=0, atol=1e-12), (impulse, 1 - theta)


# -------------------------------------------------------- drive too fast
def test_contacts_several_thresholds_per_step(tmp_path):
    """4096 contacts, the slider advances 1.7 (1.7 mean thresholds) per
    step for 60 steps: with exact crossing every contact breaks up to
    three times within a step and F(X) at the step ends is the master
    equation's (z = (F - F_ME)/(sd/sqrt(N)): |z| < 5 at every step, mean
    z^2 about 1); the anchors moved by the thresholds broken at, the
    stretch is xu - anchor and below the threshold."""
    out = ok(CONTACTS, tmp_path, n=64, dX=1.7, steps=60, thermo=1, every=60)
    rows = thermo(out, TH_C)
    eqtools.run_eqme(["threshold", "uniform", 0.75, 1.25, "reform", "delta", 0.0, "dx", 0.01,
                      "xmax", 105, "force", "me.dat"], cwd=tmp_path)
    tab = eqtools.load(tmp_path / "me.dat")
    N = 4096
    X = 1.7 * rows[:, 0]
    k = np.rint(X / 0.01).astype(int)
    F, Fme, sd = rows[:, 3] / N, tab[k, 1], tab[k, 2]
    m = sd > 0
    z = (F[m] - Fme[m]) / (sd[m] / math.sqrt(N))
    assert m.sum() >= 55 and rows[-1, 5] > 0.9 * N * 60 * 1.7          # about one per threshold
    assert np.abs(z).max() < 5.0, z
    assert np.mean(z * z) < 1.0 + 9.0 * math.sqrt(2.0 / m.sum()), np.mean(z * z)
    assert rows[:, 4].max() >= N * 1.7 / 1.25                        # breaks in one step
    steps, d = fkme.read_dump(tmp_path / "contacts.dump")
    xu, s, th, nb, a = (d[c] for c in ("xu", "f_c[1]", "f_c[2]", "f_c[4]", "f_c[6]"))
    tol = 8 * EPS * np.abs(xu).max() * nb[-1].max()
    da = a[-1] - a[0]
    assert np.all(0.75 * nb[-1] - tol <= da) and np.all(da <= 1.25 * nb[-1] + tol)
    assert np.abs(s[-1] - (xu[-1] - a[-1])).max() <= 4 * EPS * np.abs(xu).max()
    assert np.all(np.abs(s[-1]) < th[-1]) and nb[-1].sum() == rows[-1, 5]


def test_more_than_1000_breaks_in_a_step_is_an_error(tmp_path):
    """A slider step of 1500 thresholds (box 4000), or thresholds near
    zero: a contact would break more than 1000 times in one step."""
    msg = r"contact \d+ broke more than 1000 times in one step.*reduce the timestep"
    error(CONTACTS, tmp_path / "step", msg, n=4, box=4000, dX=1500, steps=3)
    error(CONTACTS, tmp_path / "thr", msg + r" or check the reform and threshold distributions",
          n=4, threshold="uniform 0.0 1e-6", steps=3)


@pytest.mark.xfail(strict=True, reason="silent wrong result, not caught: a slider step of more "
                   "than half the box (fix move 3.3 per step, box 4) is folded by LAMMPS' fix "
                   "move (Domain::remap_near) to the nearest periodic image (-0.7) before any "
                   "fix sees it: the contacts are loaded backwards (mean stretch -0.6 while the "
                   "slider moves +x); the package could compare v dt with half the box every "
                   "step, which it does not (documented restriction, not checked)")
def test_slider_step_beyond_half_the_box_is_reported(tmp_path):
    """The documented restriction (do not move an atom more than half a
    box length in one step) must be enforced: an error naming the step,
    or at least a result with the sign of the motion."""
    good, out = lmp(CONTACTS, tmp_path, n=4, dX=3.3, steps=30, thermo=10)
    if not good:
        assert re.search(r"half|box|timestep|time step", out), out[-2000:]
        return
    rows = thermo(out, TH_C)
    assert rows[-1, 8] > 0, rows           # mean stretch along the motion


def test_meso_blocks_several_thresholds_per_step(tmp_path):
    """Four rigid fix eq/meso blocks advanced 3.7 mean thresholds per
    step: the kernel splits a move at its grid points, so F(X) does not
    depend on the step (to rounding: against steps of 0.37) and is the
    master equation's to the grid error (<= 5e-4 of N k_c; measured
    2.2e-4 at any step)."""
    eqtools.run_eqme(["threshold", "uniform", 0.75, 1.25, "reform", "delta", 0.0,
                      "dx", 0.001, "xmax", 45, "force", "me.dat"], cwd=tmp_path)
    me = eqtools.load(tmp_path / "me.dat")
    F = {}
    for v, n in ((3.7, 10), (0.37, 100)):
        d = tmp_path / f"v{v}"
        ok(BLOCKS, d, style="meso", n=4, g=0, integ="rigid", dt=1.0, v=v, steps=n, every=1)
        steps, dd = fkme.read_dump(d / "blocks.dump")
        X, Fn = dd["f_sub[1]"][:, 0], dd["f_sub[2]"] / 100.0
        assert np.ptp(Fn, axis=1).max() < 1e-13           # the four blocks alike
        assert np.abs(Fn[:, 0] - np.interp(X, me[:, 0], me[:, 1])).max() <= 5e-4
        F[v] = (X, Fn[:, 0])
    Xa, Fa = F[3.7]
    Xb, Fb = F[0.37]
    j = [int(np.argmin(np.abs(Xb - x))) for x in Xa]
    assert np.abs(Xb[j] - Xa).max() < 1e-12
    assert np.abs(Fb[j] - Fa).max() < 1e-12


def test_substrate_stage_beyond_half_a_period_per_step_warns(tmp_path):
    """A stage at v = 100 (10 periods per step): the blocks jump by more
    than half a period per step; the run goes on and warns, naming the
    number of such moves and the time step."""
    out = ok(BLOCKS, tmp_path, v=100, g=2, steps=200, extra="disorder gaussian 1.0 0.05 7")
    assert re.search(r"WARNING: Fix eq/substrate: \d+ moves of a block by more than half the "
                     r"substrate period 1 in one step.*the time step is too large",
                     out), out[-2000:]


# ------------------------------------------- timestep too large, stiff coupling
def test_substrate_time_step_too_large_for_the_substrate_warns(tmp_path):
    """No coupling, dt = 5 (k_c dt/gamma = 0.5: stable, but the blocks
    pass half a well per step): the run goes on with the warning."""
    out = ok(BLOCKS, tmp_path, g=0, dt=5.0, steps=200)
    assert "the time step is too large to resolve F_s" in out


UNSTABLE = {
    "substrate-dt": dict(style="substrate", g=2.0, dt=5.0, extra="disorder gaussian 1.0 0.05 7"),
    "substrate-stiff": dict(style="substrate", g=100.0, dt=0.1,
                            extra="disorder gaussian 1.0 0.05 7"),
    "meso-stiff": dict(style="meso", g=5000.0, K=10, v=1.0, eta=100.0, dt=0.05, jiggle=0.01),
}


@pytest.mark.parametrize("case", sorted(UNSTABLE))
def test_unstable_integration_names_the_time_step(tmp_path, case):
    msg = error(BLOCKS, tmp_path, r".", steps=200, **UNSTABLE[case])
    assert re.search(r"time ?step", msg), msg


@pytest.mark.xfail(strict=True, reason="vague error: a slider or block that the integrator "
                   "moves by more than the box in one step (time step beyond the stability "
                   "limit) ends in LAMMPS' 'Lost atoms' before the package's 'numerical "
                   "instability: check the timestep' can be reached")
@pytest.mark.parametrize("infile,var", [
    (CONTACTS, dict(n=4, drive="dyn", dX=10.0, steps=300)),
    (BLOCKS, dict(style="meso", n=1, g=0, K=10, v=0.01, eta=100.0, dt=5.0)),
])
def test_integrator_blow_up_names_the_time_step(tmp_path, infile, var):
    msg = error(infile, tmp_path, r".", **var)
    assert re.search(r"time ?step", msg), msg


def test_screening_above_one_is_an_error(tmp_path):
    """Pi0 = sum_m Pi_mn >= 1: no screened solution; the error names
    kappa and rcut."""
    error(BLOCKS, tmp_path, r"Pi0 = sum_m Pi_mn = 60 >= 1 at block \d+: no screened solution.*"
          r"lower kappa \(0.3\) or rcut \(1.01\)", style="meso", n=4, g=0, integ="rigid", dt=1.0,
          v=0.01, skappa=0.3, skin=0.3, steps=5)


# ------------------------------------------------------------- avalanches
def check_resolved(folder, out):
    """After every dumped step no contact is at or above its threshold
    (|s + h/k| < x_s: the avalanche is resolved completely), the field
    sums to zero (to 1e-9 n max|h|, the drift the pair style itself
    accepts for its incremental updates), the energy (fix_modify energy yes + the pair energy
    1/2 sum s h) and the friction force are the sums over the contacts."""
    steps, d = fkme.read_dump(folder / "contacts.dump")
    rows = {int(r[0]): r for r in thermo(out, TH_C)}
    for k, step in enumerate(steps):
        s, th, kk, h = d["f_c[1]"][k], d["f_c[2]"][k], d["f_c[5]"][k], d["f_c[7]"][k]
        assert np.all(np.abs(s + h / kk) < th * (1 + 1e-12)), step
        n = len(s)
        assert abs(h.sum()) <= 1e-9 * n * np.abs(h).max() + 1e-300, step
        r = rows[step]
        F, E = np.sum(kk * s), 0.5 * np.sum(kk * s * s) + 0.5 * np.sum(s * h)
        scale = np.sum(np.abs(kk * s)) + np.sum(np.abs(s * h))
        assert abs(r[3] - F) <= 4 * n * EPS * scale + 1e-300, step
        assert abs(r[1] - E) <= 4 * n * EPS * scale + 1e-300, step
        assert r[5] == d["f_c[4]"][k].sum(), step
    return rows


@pytest.mark.parametrize("case,var", [
    ("stiff", dict(kappa=10.0)),
    ("reform-at-threshold", dict(kappa=0.2, reform="delta 1.249")),
    ("thresholds-near-zero", dict(kappa=0.1, threshold="uniform 0.0 0.01")),
])
def test_strong_interaction_avalanches_are_resolved(tmp_path, case, var):
    """100 contacts with pair eq/elastic (reform_as force): a coupling 100
    times kappa_c, contacts that re-form 0.001 below the largest
    threshold, or thresholds in [0, 0.01]: avalanches of up to all
    contacts, many times over, within a step; every one is resolved
    (see check_resolved), and they are large."""
    out = ok(CONTACTS, tmp_path, n=10, steps=300, every=20, thermo=20, **var)
    rows = check_resolved(tmp_path, out)
    assert max(r[4] for r in rows.values()) >= 100          # breaks in one step >= N


def test_reform_as_stretch_runaway_is_an_error(tmp_path):
    """With reform_as stretch a re-formed contact keeps its partners'
    field and can break without end: the error names reform_as and the
    coefficient."""
    error(CONTACTS, tmp_path, r"numerical instability.*with reform_as stretch.*use reform_as "
          r"force or a smaller ftilde", n=10, kappa=1.0, rmode="stretch", steps=300)


def test_stiff_coupling_with_per_contact_stiffness_is_an_error(tmp_path):
    """Stiffness factors from 0.01 to 10 with kappa = 10 and contacts that
    re-form next to their thresholds: the cascade is not Abelian and runs
    away; the error names the pair eq/elastic coefficients."""
    error(CONTACTS, tmp_path, r"force of contact \d+ is -?inf \(numerical instability: check the "
          r"timestep, the forces, the integrator and the pair eq/elastic coefficients",
          n=10, kappa=10.0, extra="stiffness uniform 0.01 10", reform="delta 1.2", steps=300)


# ------------------------------------------------------------- long run
def test_long_run_against_the_master_equation(tmp_path):
    """99856 contacts (316 x 316), uniform thresholds [0.75, 1.25], re-forming
    at 0, rigid slider by fix move, dX = 0.01, 2000 steps (X = 20): 2.0e8
    contact-steps on one rank.  Checked:

    * F(X)/(N k_c) every 20 steps against the master equation (eq-me):
      |z| < 5 and mean z^2 about 1, z = (F - F_ME)/(sd/sqrt(N));
    * the total breaks against N int_0^X Gamma dX of the master equation,
      within 5 standard deviations of a renewal count (variance
      sigma^2 X / mu^3 + 1/4 per contact);
    * the energy at X = 20: the fix's (fix_modify energy yes) equals
      1/2 sum k s^2 from the dump to rounding, and the master equation's
      N k_c (sd^2 + <x>^2)/2 within 5 standard errors;
    * the friction force equals sum k s and -sum f_x to rounding;
    * every contact: s = xu - anchor, 0 <= s < threshold, the anchor moved
      by between 0.75 and 1.25 per break, the breaks sum to the total."""
    N, steps, dX = 316 * 316, 2000, 0.01
    out = ok(CONTACTS, tmp_path, n=316, dX=dX, steps=steps, thermo=20, every=steps)
    rows = thermo(out, TH_C)
    assert len(rows) == steps // 20 + 1
    eqtools.run_eqme(["threshold", "uniform", 0.75, 1.25, "reform", "delta", 0.0, "dx", dX,
                      "xmax", 21, "force", "me.dat"], cwd=tmp_path)
    tab = eqtools.load(tmp_path / "me.dat")
    k = rows[:, 0].astype(int)
    F, Fme, sd = rows[:, 3] / N, tab[k, 1], tab[k, 2]
    m = sd > 0
    z = (F[m] - Fme[m]) / (sd[m] / math.sqrt(N))
    assert np.abs(z).max() < 5.0, z
    assert np.mean(z * z) < 1.0 + 9.0 * math.sqrt(2.0 / m.sum()), np.mean(z * z)
    # breaks: the renewal count of the master equation
    gam = tab[: steps + 1, 3]
    expected = N * dX * (gam.sum() - 0.5 * (gam[0] + gam[-1]))
    mu, var = 1.0, (0.5 ** 2) / 12
    sd_total = math.sqrt(N * (var * steps * dX / mu ** 3 + 0.25))
    total = rows[-1, 5]
    assert abs(total - expected) < 5 * sd_total + 1e-3 * N * dX, (total, expected, sd_total)
    # the final state
    _, d = fkme.read_dump(tmp_path / "contacts.dump")
    xu, fx, s, th, nb, kk, a = (d[c] for c in ("xu", "fx", "f_c[1]", "f_c[2]", "f_c[4]",
                                               "f_c[5]", "f_c[6]"))
    assert len(xu[0]) == N
    ulp = 4 * EPS * np.abs(xu).max()
    assert np.abs(s[-1] - (xu[-1] - a[-1])).max() <= ulp
    assert np.all(s[-1] >= -ulp) and np.all(s[-1] < th[-1])
    da = a[-1] - a[0]
    assert np.all(da >= 0.75 * nb[-1] - ulp * nb[-1]) and np.all(da <= 1.25 * nb[-1] + ulp * nb[-1])
    assert nb[-1].sum() == total
    E = 0.5 * np.sum(kk[-1] * s[-1] ** 2)
    r = rows[-1]
    assert abs(r[1] - E) <= 2 * N * EPS * E and abs(r[2] - E) <= 2 * N * EPS * E
    Fsum = np.sum(kk[-1] * s[-1])
    assert abs(r[3] - Fsum) <= 2 * N * EPS * Fsum
    assert abs(r[3] + fx[-1].sum()) <= 2 * N * EPS * Fsum
    # energy against the master equation at X = 20
    e_me = 0.5 * N * (tab[steps, 2] ** 2 + tab[steps, 1] ** 2)
    se = np.std(0.5 * s[-1] ** 2) * math.sqrt(N)
    assert abs(E - e_me) < 5 * se, (E, e_me, se)
