"""fix eq/meso at T > 0 (keywords thermal, barrier, labels, delay, aging, rest; lib
eq_meso_thermal) and the screening length lambda_s(v, T) (spec
shared/notes/thermal-aging.md (e), check (f) 8), against independent
references:

- one unscreened block moved at constant velocity: F(X) and the kinetic
  force of the slider master equation at T > 0 (eq-me velocity v thermal,
  the renewal solver ThermalTransient / thermal_steady_state);
- a ring of blocks with one pinned block sliding at v: the steady eps_n
  profile's decay length against the same fit of the nonlinear lattice
  solution (eqtools.thermal_screening.chain_lattice, Gamma(eps) =
  r((1 + eps) v)/v), and apart from the seed formula lambda_c (eps0/2)^1/2
  where the two differ;
- with delay exp or fixed tau: F(X) and the attached fraction against eq-me with
  the same delay, the end against the steady state of
  tools/eqtools/thermal.py; 1, 2 ranks and a restart bit for bit;
- with aging log or exp, a rest age, aging with a delay: F(X) against eq-me
  with the same keywords; 1, 2 ranks and a restart bit for bit;
- at T = 0 with aging or a delay (the thermal kernel at theta = 0): F(X)
  against eq-me at theta = 0; 1, 2 ranks and a restart bit for bit;
- 1, 2, 4 ranks and a restart: the same blocks to the last bit;
- without screening the default grid at T > 0 and with aging or a delay;
- errors of the keywords.
"""
import importlib.util
import math
import re
from pathlib import Path

import numpy as np
import pytest

import eqtools
from eqtools import thermal
from eqtools import thermal_screening as ts

ROOT = Path(__file__).resolve().parents[2]
SCREEN = ROOT / "examples" / "eq-thermal" / "in.eq-thermal-screen"

_spec = importlib.util.spec_from_file_location(
    "example_eq_thermal_screening", ROOT / "examples" / "eq-thermal" / "screening.py")
screening = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(screening)

BLOCK = """units lj
dimension 2
atom_style atomic
boundary p p p
region box block -0.5 0.5 -0.5 0.5 -0.5 0.5
create_box 1 box
create_atoms 1 single 0.0 0.0 0.0 units box
mass 1 1.0
fix m all eq/meso 100 1.0 threshold uniform 0.75 1.25 reform delta 0.0 grid {du!r} &
    thermal {T!r} 1.0 1.0 labels {labels}
velocity all set {v!r} 0.0 0.0 units box
fix mv all nve/noforce
timestep {dt!r}
thermo_style custom step f_m[4] f_m[1]
thermo_modify format float %.17g
thermo {every}
run {nsteps}
"""


def thermo_rows(log):
    """Rows of numbers after the thermo header 'Step f_m[4] f_m[1]'."""
    rows, on = [], False
    for line in log.splitlines():
        parts = line.split()
        if parts[:1] == ["Step"]:
            on = True
            continue
        if on:
            try:
                rows.append([float(x) for x in parts])
            except ValueError:
                on = False
    return np.array(rows)


# ---------------------------------------------------------- one block
@pytest.mark.parametrize("T,v", [(0.05, 1e-2), (0.05, 1e-3), (0.1, 1e-1)])
def test_block_at_constant_velocity_follows_the_slider_master_equation(tmp_path, T, v):
    """One unscreened block (eps = 0) moved at v with steps dX = du/2
    (time dX/v each): F(X)/(N k_c) against eq-me velocity v thermal T 1 1
    (the renewal solver, Richardson, error ~1e-9) at every 10th step, X up
    to 4 x_c.  Bound: the kernel's O(du^2) error, 2.95-3.35 du^2 measured
    (gtest MesoThermal.ConstantVelocity, the same dX = du/2 and panels of
    3.1 du), bounded by 5 du^2 = 5e-4 at du = 0.01.  The last F against the
    kinetic force within that bound plus what the exact F(X) itself still
    lacks of it at X = 4."""
    du, labels = 0.01, 16
    dX = 0.5 * du
    nsteps = 800
    inp = tmp_path / "in.block"
    inp.write_text(BLOCK.format(du=du, T=T, labels=labels, v=v, dt=dX / v, every=10,
                                nsteps=nsteps))
    rows = thermo_rows(eqtools.run_lammps(inp, {}, cwd=tmp_path))
    X, F = rows[:, 1], rows[:, 2] / 100.0    # <X>, sum F = N_lambda k_c <u>
    me = eqtools.run_eqme(["threshold", "uniform", "0.75", "1.25", "reform", "delta", "0.0",
                           "thermal", T, 1.0, 1.0, "velocity", v, "dx", 5e-4, "xmax", 4.1,
                           "force", "me.dat"], cwd=tmp_path)
    ref = eqtools.load(tmp_path / "me.dat")
    Fref = np.interp(X, ref[:, 0], ref[:, 1])
    assert abs(X[-1] - nsteps * dX) < 1e-9 and F.max() > 0.4
    err = np.abs(F - Fref).max()
    assert err < 5.0 * du * du, err
    relax = abs(np.interp(X[-1], ref[:, 0], ref[:, 1]) - me["kinetic_force"])
    assert abs(F[-1] - me["kinetic_force"]) < 5.0 * du * du + relax


# ---------------------------------------------------------- delay exp
DELAYED = BLOCK.replace("labels {labels}\n", "labels {labels} delay {kind} {tau!r}\n").replace(
    "thermo_style custom step f_m[4] f_m[1]",
    "compute na all reduce sum f_m[6]\nthermo_style custom step f_m[4] f_m[1] c_na")


@pytest.mark.parametrize("kind,tau", [("exp", 30.0), ("exp", 100.0), ("fixed", 30.0)])
def test_block_with_delay_follows_the_slider_master_equation(tmp_path, kind, tau):
    """delay exp or fixed tau (v tau = 0.3, 1): one unscreened block moved
    at v = 1e-2, theta = 0.05, steps dX = du/2: F(X)/(N k_c) and the
    attached fraction against eq-me with the same delay (the renewal
    solver, Richardson) at every 10th step, X up to 4 x_c.  Bound 5 du^2
    as the run without delay (gtest MesoThermalDelay.ConstantVelocity
    measured 2.8-3.4 du_eff^2 for F, 3.4-4.1 du_eff^2 for the attached
    fraction with delay exp, converging at second order); with delay
    fixed the attached fraction 1 - (B(X) - B(X - v tau)), B the broken
    mass, carries the error of B at both ends: bound 10 du^2 (measured
    6.5 du_eff^2).  The last F
    and attached fraction against the steady state of the independent
    quadrature tools/eqtools/thermal.py (F_k = int x S/(<L> + v tau), n_a
    = <L>/(<L> + v tau)) within that bound plus what the exact F(X) still
    lacks of it at X = 4; eq-me's steady state is the same to 1e-10."""
    T, v, du, labels = 0.05, 1e-2, 0.01, 16
    dX = 0.5 * du
    nsteps = 800
    inp = tmp_path / "in.block"
    inp.write_text(DELAYED.format(du=du, T=T, labels=labels, kind=kind, tau=tau, v=v, dt=dX / v,
                                  every=10, nsteps=nsteps))
    log = eqtools.run_lammps(inp, {}, cwd=tmp_path)
    assert "delay " + kind in log
    rows = thermo_rows(log)
    X, F, na = rows[:, 1], rows[:, 2] / 100.0, rows[:, 3]
    me = eqtools.run_eqme(["threshold", "uniform", "0.75", "1.25", "reform", "delta", "0.0",
                           "thermal", T, 1.0, 1.0, "delay", kind, tau, "velocity", v,
                           "dx", 5e-4, "xmax", 4.1, "force", "me.dat"], cwd=tmp_path)
    ref = eqtools.load(tmp_path / "me.dat")    # X F sd Gamma attached skewness
    assert abs(X[-1] - nsteps * dX) < 1e-9 and F.max() > 0.4
    tol = 5.0 * du * du
    tola = (10.0 if kind == "fixed" else 5.0) * du * du
    assert np.abs(F - np.interp(X, ref[:, 0], ref[:, 1])).max() < tol
    assert np.abs(na - np.interp(X, ref[:, 0], ref[:, 4])).max() < tola
    steady = thermal.steady_force(v, theta=T, delay=kind, tau=tau, full=True)
    assert abs(steady["F"] - me["kinetic_force"]) < 1e-10
    assert abs(steady["n_a"] - me["attached_fraction"]) < 1e-10
    assert steady["n_a"] < 0.75    # the delay matters: a third or more waits
    relaxF = abs(np.interp(X[-1], ref[:, 0], ref[:, 1]) - steady["F"])
    relaxA = abs(np.interp(X[-1], ref[:, 0], ref[:, 4]) - steady["n_a"])
    assert abs(F[-1] - steady["F"]) < tol + relaxF
    assert abs(na[-1] - steady["n_a"]) < tola + relaxA


# ---------------------------------------------------------- aging
AGED = BLOCK.replace("labels {labels}\n", "labels {labels} {extra}\n")


@pytest.mark.parametrize("extra", ["aging log 0.05 1.0", "aging exp 0.2 30.0",
                                   "aging log 0.05 1.0 rest 10000.0",
                                   "aging log 0.1 10.0 rest 100.0 delay exp 30.0"])
def test_block_with_aging_follows_the_slider_master_equation(tmp_path, extra):
    """Threshold aging (log, exp), a rest age and aging with a delay: one
    unscreened block moved at v = 1e-2, theta = 0.05, steps dX = du/2:
    F(X)/(N k_c) against eq-me with the same keywords (the renewal solver,
    Richardson; its first life starts at the rest age) at every 10th step,
    X up to 4 x_c.  Bound 5 du^2 as without aging (gtest
    MesoThermalAging.ConstantVelocity and RestAge measured 3.6-4.2 du^2 at
    theta = 0.05, second order).  The aging is felt: F at its peak differs
    from the run without it by more than 20 times the bound."""
    T, v, du, labels = 0.05, 1e-2, 0.01, 16
    dX = 0.5 * du
    nsteps = 800
    runs, logs = {}, {}
    for name, kw in (("aged", extra), ("plain", "")):
        d = tmp_path / name
        d.mkdir()
        inp = d / "in.block"
        inp.write_text(AGED.format(du=du, T=T, labels=labels, extra=kw, v=v, dt=dX / v,
                                   every=10, nsteps=nsteps))
        logs[name] = eqtools.run_lammps(inp, {}, cwd=d)
        runs[name] = thermo_rows(logs[name])
    assert "aging " + extra.split()[1] in logs["aged"], logs["aged"][-2000:]
    X, F = runs["aged"][:, 1], runs["aged"][:, 2] / 100.0
    me = eqtools.run_eqme(["threshold", "uniform", "0.75", "1.25", "reform", "delta", "0.0",
                           "thermal", T, 1.0, 1.0, *extra.split(), "velocity", v,
                           "dx", 5e-4, "xmax", 4.1, "force", "me.dat"], cwd=tmp_path)
    ref = eqtools.load(tmp_path / "me.dat")
    assert abs(X[-1] - nsteps * dX) < 1e-9 and F.max() > 0.4
    tol = 5.0 * du * du
    err = np.abs(F - np.interp(X, ref[:, 0], ref[:, 1])).max()
    assert err < tol, err
    assert abs(F.max() - runs["plain"][:, 2].max() / 100.0) > 20.0 * tol


@pytest.mark.parametrize("extra", ["aging log 0.05 1.0 rest 10000.0",
                                   "aging exp 0.2 30.0 delay exp 30.0", "delay fixed 30.0"])
def test_block_at_zero_temperature_with_aging_or_delay_follows_the_master_equation(tmp_path,
                                                                                   extra):
    """At T = 0 aging and delays use the thermal kernel at theta = 0 (no
    thermal breaks): one unscreened block moved at v = 1e-2 with steps
    dX = du/2, F(X)/(N k_c) against eq-me with the same keywords at
    theta = 0 (the renewal solver) at every 10th step, X up to 4 x_c,
    within 5 du^2 as at T > 0 (measured 0.3-0.6 du^2).  The keywords are
    felt: F differs from the athermal kernel's run without them by more
    than 20 times the bound somewhere."""
    v, du, labels = 1e-2, 0.01, 16
    dX = 0.5 * du
    nsteps = 800
    runs, logs = {}, {}
    for name, kw in (("kept", "labels 16 " + extra), ("plain", "")):
        d = tmp_path / name
        d.mkdir()
        inp = d / "in.block"
        text = BLOCK.replace("    thermal {T!r} 1.0 1.0 labels {labels}\n", "    {extra}\n")
        inp.write_text(text.format(du=du, extra=kw, v=v, dt=dX / v, every=10, nsteps=nsteps))
        logs[name] = eqtools.run_lammps(inp, {}, cwd=d)
        runs[name] = thermo_rows(logs[name])
    assert "theta = k_B T/eps_a = 0)" in logs["kept"], logs["kept"][-2000:]
    assert "threshold panels" not in logs["plain"]    # the athermal kernel
    X, F = runs["kept"][:, 1], runs["kept"][:, 2] / 100.0
    me = eqtools.run_eqme(["threshold", "uniform", "0.75", "1.25", "reform", "delta", "0.0",
                           *extra.split(), "velocity", v, "dx", 5e-4, "xmax", 4.1, "force",
                           "me.dat"], cwd=tmp_path)
    ref = eqtools.load(tmp_path / "me.dat")
    assert abs(X[-1] - nsteps * dX) < 1e-9 and F.max() > 0.4
    tol = 5.0 * du * du
    err = np.abs(F - np.interp(X, ref[:, 0], ref[:, 1])).max()
    assert err < tol, err
    assert np.abs(F - runs["plain"][:, 2] / 100.0).max() > 20.0 * tol


@pytest.mark.parametrize("extra", ["thermal 0.05 1.0 1.0", "aging log 0.05 1.0 delay exp 30.0"])
def test_default_grid_without_screening(tmp_path, extra):
    """Without screen (eps = 0) the thermal kernel takes the default grid
    of the athermal one, sd/8 of the thresholds (uniform [0.75, 1.25]:
    0.5/sqrt(12)/8 = 0.0180422): at T > 0, and at T = 0 with aging and a
    delay, one block moved at v = 1e-2 with steps dX = du/2 follows eq-me
    within the kernel's bound 5 du^2 as on a grid set by hand."""
    v = 1e-2
    du = 0.5 / math.sqrt(12.0) / 8.0
    dX = 0.5 * du
    nsteps = int(4.0 / dX)
    inp = tmp_path / "in.block"
    text = BLOCK.replace(" grid {du!r} &\n    thermal {T!r} 1.0 1.0 labels {labels}\n",
                         " {extra}\n")
    inp.write_text(text.format(extra=extra, v=v, dt=dX / v, every=10, nsteps=nsteps))
    log = eqtools.run_lammps(inp, {}, cwd=tmp_path)
    assert f"grid {du:.6g} (" in log, log[-2000:]
    rows = thermo_rows(log)
    X, F = rows[:, 1], rows[:, 2] / 100.0
    me = eqtools.run_eqme(["threshold", "uniform", "0.75", "1.25", "reform", "delta", "0.0",
                           *extra.split(), "velocity", v, "dx", 5e-4, "xmax", 4.1, "force",
                           "me.dat"], cwd=tmp_path)
    ref = eqtools.load(tmp_path / "me.dat")
    assert abs(X[-1] - nsteps * dX) < 1e-9 and F.max() > 0.4
    err = np.abs(F - np.interp(X, ref[:, 0], ref[:, 1])).max()
    assert err < 5.0 * du * du, (err, du)


DRIVE = Path(__file__).resolve().parent / "inputs" / "in.meso-thermal-drive"


def drive_eps(log):
    """<eps> at the thermo steps of in.meso-thermal-drive."""
    rows = []
    for line in log.split("Step")[-1].splitlines()[1:]:
        f = line.split()
        if len(f) != 3:
            break
        rows.append([float(x) for x in f])
    return np.array(rows)[:, 1]


def test_default_grid_with_screening_at_the_drive_velocity(tmp_path):
    """With screen at T > 0 and drive K v, no grid keyword: the default grid
    is 1/8 of the screened thresholds' sd/(1 + eps0), eps0 the root of
    eps0 = Pi0 x_c Gamma(eps0) at v.  A ring of 12 blocks (Pi0 = 0.6,
    theta = 0.05, v = 1e-2, all sliding at v, steps dX = du/2 in x_c)
    - logs eps0 equal to eqtools.thermal_screening.eps0 (an independent
      quadrature of the continuous model) to 1e-9 and the grid from it;
    - slides to that eps0: the steady <eps>, extrapolated from X = 12, 14,
      16 x_c (geometric relaxation, Aitken), within the kernel's bound
      5 du^2 relative, du = (1 + eps0) du_grid/x_c = sd/8 the grid of the
      effective stretches (the athermal eps0 = Pi0/(1 - Pi0) = 1.5 is 40 %
      off);
    - 2 ranks choose the same grid (the run to X = 2 to the last digit)."""
    v, pi0, theta, xc = 1e-2, 0.6, 0.05, 1e-4
    e0 = ts.eps0(v, theta=theta, Pi0=pi0)
    sd = 0.5 / math.sqrt(12.0)
    du_grid = 0.125 * sd * xc / (1.0 + e0)
    log = eqtools.run_lammps(DRIVE, {"v": v, "pi0": pi0, "T": theta, "Xmax": 16.0,
                                     "dX": 0.5 * du_grid / xc}, cwd=tmp_path)
    m = re.search(r"fix eq/meso: grid (\S+) for the screened thresholds .*eps0 = (\S+) the steady "
                  r"load factor at the drive's velocity", log)
    assert m, log[-3000:]
    grid, eps_logged = float(m.group(1)), float(m.group(2))
    assert abs(eps_logged - e0) < 1e-5 * e0    # (printed to 6 digits)
    assert abs(grid - du_grid) < 1e-9 * du_grid, (grid, du_grid)
    eps = drive_eps(log)
    assert len(eps) == 9, eps
    a, b, c = eps[-3:]
    steady = c - (c - b) ** 2 / ((c - b) - (b - a))
    du = 0.125 * sd
    assert abs(steady - e0) < 5.0 * du * du * (1.0 + e0), (steady, e0)
    assert abs(steady - pi0 / (1.0 - pi0)) > 0.3 * e0
    ends = []
    for n in (1, 2):
        d = tmp_path / f"np{n}"
        d.mkdir()
        ends.append(eqtools.run_lammps(DRIVE, {"Xmax": 2.0, "dX": 0.5 * du_grid / xc}, nprocs=n,
                                       cwd=d).split("EPS_END")[-1].split()[0])
    assert ends[0] == ends[1], ends


def test_default_grid_with_screening_needs_a_velocity(tmp_path):
    """drive with v = 0 at the first run: an error naming drive (the
    default grid is made for the steady state at v); fix_modify velocity
    before the run gives the grid of that velocity."""
    log = eqtools.run_lammps(DRIVE, {"vdrive": 0.0, "Xmax": 0.01}, cwd=tmp_path, check=False)
    assert "eq/meso drive: the default grid with screen at T > 0" in log, log[-2000:]
    inp = tmp_path / "in.later"
    inp.write_text(DRIVE.read_text().replace(
        "velocity        all", "fix_modify      m velocity $(v_v*v_xc)\nvelocity        all"))
    log = eqtools.run_lammps(inp, {"vdrive": 0.0, "Xmax": 0.01}, cwd=tmp_path)
    assert re.search(r"eps0 = 2\.445\d* the steady load factor at the drive's velocity 1e-06", log), \
        log[-3000:]


def test_default_grid_kept_velocity_new_partners(tmp_path):
    """run 0 makes the grid at the drive's velocity; after fix_modify
    velocity 0 and new blocks between the old ones (Pi0 0.05 -> 0.45,
    nothing moved yet), the next set-up makes it anew for the new Pi0 at
    the earlier velocity: eps0 as eqtools' for Pi0 = 0.45."""
    inp = tmp_path / "in.new"
    inp.write_text(f"include {DRIVE}\nfix_modify m velocity 0.0\n"
                   "variable j loop ${M}\nlabel mid\n"
                   "create_atoms 1 single $(v_j-1.5) 0.0 0.0 units box\n"
                   "next j\njump SELF mid\nrun 0\n")
    log = eqtools.run_lammps(inp, {"pi0": 0.05, "Xmax": 0.0}, cwd=tmp_path)
    found = re.findall(r"grid (\S+) for the screened thresholds \(Pi0 = (\S+): .*eps0 = (\S+) the "
                       r"steady load factor at the (drive's|earlier) velocity 1e-06", log)
    assert len(found) == 2, log[-3000:]
    assert abs(float(found[0][1]) - 0.05) < 1e-9 and found[0][3] == "drive's"
    assert abs(float(found[1][1]) - 0.45) < 1e-9 and found[1][3] == "earlier"
    e0 = ts.eps0(1e-2, theta=0.05, Pi0=0.45)
    assert abs(float(found[1][2]) - e0) < 1e-5 * e0, (found, e0)
    du = 0.125 * 0.5 / math.sqrt(12.0) * 1e-4 / (1.0 + e0)
    assert abs(float(found[1][0]) - du) < 1e-9 * du


def test_default_grid_from_a_restart_needs_no_drive(tmp_path):
    """Blocks written with the default grid of drive continue from a
    restart file in a fix without drive and without grid (the file's
    grid), the same as with drive: the blocks' load factors to the last
    digit after 40 more steps.  Fresh blocks without drive: the error."""
    (tmp_path / "in.w").write_text(f"include {DRIVE}\nwrite_restart r.bin\n")
    eqtools.run_lammps(tmp_path / "in.w", {"Xmax": 0.1}, cwd=tmp_path)
    fix = ("fix m all eq/meso 100 1.0 threshold uniform 7.5e-05 0.000125 screen 0.003 1.0 1.01 "
           "thermal 0.05 1.0 1.0 check 0 {drive}\n")
    body = ("neighbor 0.3 bin\ncomm_modify cutoff 1.7\nfix mv all nve/noforce\n"
            "thermo_style custom step f_m[3]\nthermo_modify format float %.17g\nrun 40\n"
            "print \"EPS_END $(f_m[3]:%.17g)\"\n")
    ends = []
    for drive in ("", "drive 1.0 1e-6"):
        (tmp_path / "in.r").write_text("read_restart r.bin\n" + fix.format(drive=drive) + body)
        log = eqtools.run_lammps(tmp_path / "in.r", {}, cwd=tmp_path)
        assert "of the restart file's blocks" in log, log[-2000:]
        ends.append(log.split("EPS_END")[-1].split()[0])
    assert ends[0] == ends[1] and float(ends[0]) > 0.0, ends
    # blocks written before they moved (run 0): the file's grid and drive
    # velocity serve a fix without drive, as a fix with it
    (tmp_path / "in.w0").write_text(f"include {DRIVE}\nwrite_restart r0.bin\n")
    eqtools.run_lammps(tmp_path / "in.w0", {"Xmax": 0.0}, cwd=tmp_path)
    fresh = []
    for drive in ("", "drive 1.0 1e-6"):
        (tmp_path / "in.r0").write_text("read_restart r0.bin\n" + fix.format(drive=drive) +
                                        "velocity all set 1e-6 0.0 0.0 units box\n" + body)
        log = eqtools.run_lammps(tmp_path / "in.r0", {}, cwd=tmp_path)
        fresh.append(log.split("EPS_END")[-1].split()[0])
    assert fresh[0] == fresh[1] and float(fresh[0]) > 0.0, fresh
    # ... and its drive velocity makes the grid anew where partners come
    # (Pi0 0.05 -> 0.45 with blocks between the old ones, nothing moved)
    (tmp_path / "in.wp").write_text(f"include {DRIVE}\nwrite_restart rp.bin\n")
    eqtools.run_lammps(tmp_path / "in.wp", {"Xmax": 0.0, "pi0": 0.05}, cwd=tmp_path)
    (tmp_path / "in.rp").write_text(
        "read_restart rp.bin\n" + fix.format(drive="").replace("0.003", "0.00025") +
        body.replace("run 40", "run 0") +    # (create_atoms needs a run after read_restart)
        "variable j loop 12\nlabel mid\ncreate_atoms 1 single $(v_j-1.5) 0.0 0.0 units box\n"
        "next j\njump SELF mid\nrun 0\n")
    log = eqtools.run_lammps(tmp_path / "in.rp", {}, cwd=tmp_path)
    m = re.search(r"\(Pi0 = (\S+): .*eps0 = (\S+) the steady load factor at the earlier velocity "
                  r"1e-06", log)
    assert m and abs(float(m.group(1)) - 0.45) < 1e-9, log[-3000:]
    e0 = ts.eps0(1e-2, theta=0.05, Pi0=0.45)
    assert abs(float(m.group(2)) - e0) < 1e-5 * e0
    # a file written before any run holds no grid for the screening: the
    # reader without drive stops as a fix that was never written
    (tmp_path / "in.wa").write_text(
        DRIVE.read_text().replace("drive 1.0 $(v_vdrive*v_xc) ", "")
        .replace("run             ${nsteps}", "write_restart ra.bin").replace("print", "#"))
    eqtools.run_lammps(tmp_path / "in.wa", {}, cwd=tmp_path)
    (tmp_path / "in.ra").write_text("read_restart ra.bin\n" + fix.format(drive="") + body)
    log = eqtools.run_lammps(tmp_path / "in.ra", {}, cwd=tmp_path, check=False)
    assert "Fix m eq/meso thermal: with screen needs the grid keyword, or drive" in log, \
        log[-2000:]
    (tmp_path / "in.f").write_text(DRIVE.read_text().replace("drive 1.0 $(v_vdrive*v_xc) ", ""))
    log = eqtools.run_lammps(tmp_path / "in.f", {"Xmax": 0.01}, cwd=tmp_path, check=False)
    assert "Fix m eq/meso thermal: with screen needs the grid keyword, or drive" in log, log[-2000:]


def test_default_grid_restart_keeps_the_grids_velocity(tmp_path):
    """A restart file holds the velocity its default grid was made for:
    run 0 makes the grid at the drive's velocity, fix_modify velocity 0,
    write_restart; a reader (without drive, or with drive at velocity 0)
    given blocks between the old ones (Pi0 0.05 -> 0.45, nothing moved)
    makes the grid anew at that velocity, as the writer itself does
    (test_default_grid_kept_velocity_new_partners), not keeping the file's
    grid of Pi0 = 0.05 (the code before: the record had only the stage's
    velocity, 0)."""
    (tmp_path / "in.w").write_text(f"include {DRIVE}\nfix_modify m velocity 0.0\n"
                                   "write_restart rv.bin\n")
    eqtools.run_lammps(tmp_path / "in.w", {"Xmax": 0.0, "pi0": 0.05}, cwd=tmp_path)
    e0 = ts.eps0(1e-2, theta=0.05, Pi0=0.45)
    du = 0.125 * 0.5 / math.sqrt(12.0) * 1e-4 / (1.0 + e0)
    for drive in ("", "drive 1.0 0.0"):
        (tmp_path / "in.r").write_text(
            "read_restart rv.bin\n"
            "fix m all eq/meso 100 1.0 threshold uniform 7.5e-05 0.000125 screen 0.00025 1.0 1.01 "
            f"thermal 0.05 1.0 1.0 check 0 {drive}\n"
            "neighbor 0.3 bin\ncomm_modify cutoff 1.7\nfix mv all nve/noforce\nrun 0\n"
            "variable j loop 12\nlabel mid\ncreate_atoms 1 single $(v_j-1.5) 0.0 0.0 units box\n"
            "next j\njump SELF mid\nrun 0\n")
        log = eqtools.run_lammps(tmp_path / "in.r", {}, cwd=tmp_path)
        m = re.search(r"grid (\S+) for the screened thresholds \(Pi0 = (\S+): .*eps0 = (\S+) the "
                      r"steady load factor at the earlier velocity 1e-06", log)
        assert m and abs(float(m.group(2)) - 0.45) < 1e-9, (drive, log[-3000:])
        assert abs(float(m.group(3)) - e0) < 1e-5 * e0
        assert abs(float(m.group(1)) - du) < 1e-9 * du


# ---------------------------------------------------------- screening length
# measured: at cells = 4 (du = sd/(4 (1 + eps0))) and dX = du/2 the fitted
# length is 0.3-0.4 % below the lattice's; with dX = du 1.3 %: the step and
# grid errors are O(du^2) and the bound is 3 % (8x the measured offset)
# plus the steadiness of the run (screening.steadiness)
LENGTH_TOL = 0.03


@pytest.mark.parametrize("v", [1e-1, 1e-2, 1e-3])
def test_screening_length_follows_the_lattice_not_the_seed(tmp_path, v):
    """Ring of 24 blocks, Pi0 = 0.6 (nearest neighbours), theta = 0.05,
    block 0 pinned, sliding at v (examples/eq-thermal/in.eq-thermal-screen,
    settings of screening.settings): eps averaged over the last quarter of
    the run; its decay length (fit of e0 + A (rho^n + rho^(M-n))) matches
    the same fit of the nonlinear lattice solution within LENGTH_TOL, and
    where the seed formula differs from it by more than 3 LENGTH_TOL
    (v = 1e-2: 10 %, 1e-3: 19 %) the measurement is more than LENGTH_TOL
    from the seed.  eps0 (the fit's e0) within 1 % of (1 + eps0) of the
    uniform solution (grid error of Gamma amplified by 1/(1 - c)).  The
    run is steady: the snapshot at the end equals the average within 1e-3
    (1 + eps0) (no relaxation oscillations)."""
    r = screening.run(v, tmp_path)
    ell, e0 = screening.fit_length(r["eps"])
    ell_mid, _ = screening.fit_length(r["eps_mid"])
    now = screening.read_eps(tmp_path / "eps_now.dump")
    ref = screening.references(v)
    steady = screening.steadiness(ell, ell_mid, r["settings"])
    tol = LENGTH_TOL * ref["lattice"] + steady
    assert np.abs(now - r["eps"]).max() < 1e-3 * (1.0 + ref["eps0"])
    assert abs(e0 - ref["eps0"]) < 0.01 * (1.0 + ref["eps0"]), (e0, ref["eps0"])
    assert abs(ell - ref["lattice"]) < tol, (ell, ref["lattice"], tol)
    if abs(ref["seed"] - ref["lattice"]) > 3 * tol:
        assert abs(ell - ref["seed"]) > tol, (ell, ref["seed"])


# ---------------------------------------------------------- ranks, restart
def ring_blocks(d):
    """Every block's row of the screened ring's last dump."""
    text = (d / "eps_now.dump").read_text().split("ITEM: ATOMS")[-1].splitlines()[1:]
    return np.array([[float(x) for x in l.split()] for l in text if l.strip()])


@pytest.mark.parametrize("delay,aging,ranks,T", [("none", "none", (1, 2, 4), 0.05),
                                                 ("exp 30", "none", (1, 2), 0.05),
                                                 ("fixed 30", "none", (1, 2), 0.05),
                                                 ("none", "log 0.1 1", (1, 2), 0.05),
                                                 ("exp 30", "log 0.1 1", (1, 2), 0.0)])
def test_ranks_and_restart_identical(tmp_path, delay, aging, ranks, T):
    """A ring of 12 blocks at T > 0 (and at T = 0 with aging and a delay,
    the thermal kernel at theta = 0) with screening (partners summed in
    the order of their atom IDs), without and with a formation delay (exp
    or fixed 30: v tau = 0.3 x_c) or threshold aging (log, after a rest of
    100): 1, 2 (and 4) ranks give every block's state to the last bit, a
    run split by write_restart/read_restart (2 -> the last rank count)
    continues it bit for bit (the ages travel in the blocks' state), and
    the delay or the aging changes the run."""
    # at T = 0 the aged contacts (A(100) = 1.46) hold beyond X = 1: slide to 2
    base = dict(M=12, v=1e-2, grid=0.01, dX=0.005, Xmax=1.0 if T > 0 else 2.0, labels=8,
                delay=delay, aging=aging, rest=100 if aging != "none" else 0, T=T)
    ref = None
    for n in ranks:
        d = tmp_path / f"np{n}"
        d.mkdir()
        eqtools.run_lammps(SCREEN, dict(base, out=d), nprocs=n, cwd=d)
        got = ring_blocks(d)
        if ref is None:
            ref = got
        else:
            assert np.array_equal(got, ref), n
    assert ref[:, 2].max() > 0.3    # screened (eps0 = 2.4 when steady, without delay)
    d = tmp_path / "split"
    d.mkdir()
    half = 0.5 * base["Xmax"]
    eqtools.run_lammps(SCREEN, dict(base, out=d, Xmax=half, restartfile="half_restart"),
                       nprocs=2, cwd=d)
    eqtools.run_lammps(SCREEN, dict(base, out=d, Xmax=half, readrestart="half_restart"),
                       nprocs=ranks[-1], cwd=d)
    assert np.array_equal(ring_blocks(d), ref)
    if delay != "none" or aging != "none":
        d = tmp_path / "plain"
        d.mkdir()
        # (at T = 0 without aging and delay the athermal kernel refuses labels:
        # there the delay alone is dropped)
        plain = dict(delay="none") if T == 0 else dict(delay="none", aging="none", rest=0)
        eqtools.run_lammps(SCREEN, dict(base, out=d, **plain), cwd=d)
        # eps: fewer attached (delay), later breaks (aging); at T = 0 and X = 2
        # the delay changes eps by 5e-5 but the force (column 4) by half
        got = ring_blocks(d)
        if T > 0:
            assert np.abs(got[:, 2] - ref[:, 2]).max() > 1e-3
        else:
            assert np.abs(got[:, 4] - ref[:, 4]).max() > 0.1 * np.abs(ref[:, 4]).max()


# ---------------------------------------------------------- errors
HEAD = """units lj
atom_style atomic
region box block 0 2 0 2 0 2
create_box 1 box
create_atoms 1 single 1.0 1.0 1.0 units box
mass 1 1.0
"""
FIX = "fix m all eq/meso 100 1.0 threshold uniform 0.75 1.25 "


@pytest.mark.parametrize("args,needle", [
    ("grid 0.01 thermal -1 1.0 1.0", "Fix eq/meso thermal T: must be >= 0"),
    ("grid 0.01 thermal 0.05 0.0 1.0", "Fix eq/meso thermal eps_a: must be > 0"),
    ("grid 0.01 thermal 0.05 1.0 1.0 barrier -1 0", "Fix eq/meso barrier p: must be >= 0"),
    ("grid 0.01 barrier 1 0", "Fix eq/meso barrier: needs thermal with T > 0"),
    ("grid 0.01 aging log 0.1 1.0 barrier 1 0", "Fix eq/meso barrier: needs thermal with T > 0"),
    ("grid 0.01 labels 8", "Fix eq/meso labels: needs thermal"),
    ("grid 0.01 thermal 0.05 1.0 1.0 labels 0", "Fix eq/meso labels: expected an integer"),
    ("grid 0.01 thermal 0.0 1.0 1.0 rest 10", "Fix eq/meso rest: needs aging, delay or thermal"),
    ("grid 0.01 aging log 0.0 1.0 rest 10", "Fix eq/meso rest: needs aging, delay or thermal"),
    ("grid 0.01 thermal 0.05 1.0 1.0 aging exp 0.1 0", "Fix eq/meso aging tau_a: must be > 0"),
    ("grid 0.01 thermal 0.05 1.0 1.0 delay exp -1", "Fix eq/meso delay tau: must be >= 0"),
    ("grid 0.01 thermal 0.05 1.0 1.0 delay fixed 10\nrun 1",
     "Fix m eq/meso delay fixed: tau = 10 is 2000 time steps, more than the 1022"),
    ("grid 0.01 thermal 0.05 1.0 1.0 reform uniform -0.1 0.1",
     "with the thermal kernel (thermal at T > 0, aging or delay), contacts re-form unstretched"),
    ("grid 0.01 aging log 0.1 1.0 reform uniform -0.1 0.1",
     "with the thermal kernel (thermal at T > 0, aging or delay), contacts re-form unstretched"),
])
# (with screen and without grid or drive: errors at a run's set-up with
# screening partners, in unittest/commands/test_eq_meso_errors.cpp)
def test_errors_name_the_keyword(tmp_path, args, needle):
    inp = tmp_path / "in.err"
    inp.write_text(HEAD + FIX + args + "\n")
    log = eqtools.run_lammps(inp, {}, cwd=tmp_path, check=False)
    assert needle in log, log[-2000:]


def test_restart_of_the_other_kind_is_an_error(tmp_path):
    """A restart file written athermal and read with thermal (and the
    reverse) is an error naming the keyword thermal."""
    for write, read, needle in (("", "thermal 0.05 1.0 1.0", "were made athermal"),
                                ("thermal 0.05 1.0 1.0", "", "were made by the thermal kernel"),
                                ("aging log 0.1 1.0", "", "were made by the thermal kernel"),
                                ("", "delay exp 10", "were made athermal")):
        inp = tmp_path / "in.w"
        inp.write_text(HEAD + FIX + "grid 0.01 " + write + "\nrun 1\nwrite_restart r.bin\n")
        eqtools.run_lammps(inp, {}, cwd=tmp_path)
        inp = tmp_path / "in.r"
        inp.write_text("read_restart r.bin\n" + FIX + "grid 0.01 " + read + "\nrun 1\n")
        log = eqtools.run_lammps(inp, {}, cwd=tmp_path, check=False)
        assert needle in log and "thermal" in log.split("ERROR")[-1], log[-2000:]
    # at T = 0 omega shapes nothing: the blocks continue with another one
    inp = tmp_path / "in.w"
    inp.write_text(HEAD + FIX + "grid 0.01 thermal 0.0 1.0 5.0 aging log 0.1 1.0\nrun 1\n"
                   "write_restart r.bin\n")
    eqtools.run_lammps(inp, {}, cwd=tmp_path)
    inp = tmp_path / "in.r"
    inp.write_text("read_restart r.bin\n" + FIX + "grid 0.01 aging log 0.1 1.0\nrun 1\n")
    assert "ERROR" not in eqtools.run_lammps(inp, {}, cwd=tmp_path)
