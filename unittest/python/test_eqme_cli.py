"""The eq-me command-line tool: outputs, accuracy options, and errors that
name the keyword and the allowed values."""
import subprocess

import numpy as np
import pytest

import eqtools


def eqme(args, cwd):
    return subprocess.run([eqtools.eqme_exe()] + [str(a) for a in args], cwd=cwd,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def test_usage(tmp_path):
    p = eqme([], tmp_path)
    assert p.returncode == 2 and "usage: eq-me threshold STYLE" in p.stdout


@pytest.mark.parametrize("args,message", [
    (["threshold", "uniform", 1.25, 0.75], "threshold uniform: need 0 <= lo < hi (got lo = 1.25, hi = 0.75)"),
    (["threshold", "lognormal", 1, 1], "threshold unknown style 'lognormal'; allowed: uniform, gaussian, realistic, table"),
    (["reform", "delta", 0], "the threshold keyword is required; allowed styles: uniform, gaussian, realistic, table"),
    (["threshold", "realistic", 1, "dx", -1], "dx: must be > 0"),
    (["threshold", "realistic", 1, "dx", "abc"], "dx: expected a number, got 'abc'"),
    (["threshold", "realistic", 1, "xmax"], "xmax: missing value"),
    (["threshold", "realistic", 1, "foo", 1], "unknown keyword 'foo'; allowed: threshold, reform, stiffness, dir, xmax, dx, start, crossing, richardson, force, steady, snapshot, summary, exact"),
    (["threshold", "realistic", 1, "dir", "w"], "dir: unknown value 'w'; allowed: x, y, z"),
    (["threshold", "realistic", 1, "stiffness", "uniform", 0, 1], "stiffness uniform: need 0 < lo < hi"),
    (["threshold", "realistic", 1, "xmax", 1e-4], "xmax: must be at least dx"),
    (["threshold", "uniform", 0.75, 1.25, "reform", "uniform", 0.5, 1.3], "reform uniform 0.5 1.3: re-forming stretches reach the largest breaking threshold 1.25 (probability 0.0625)"),
    (["threshold", "gaussian", 1.0, 0.01, "reform", "delta", 1.5], "reform delta 1.5: re-forming stretches reach the largest breaking threshold 1.37"),
    (["threshold", "realistic", 1.0, "reform", "delta", 40], "reform delta 40: re-forming stretches reach the largest breaking threshold 26.4"),
    (["threshold", "realistic", 1, "start", "hot"], "start: unknown value 'hot'; allowed: relaxed, reform"),
    (["threshold", "realistic", 1, "crossing", "half"], "crossing: unknown value 'half'; allowed: exact, step"),
    (["threshold", "realistic", 1, "crossing", "step", "richardson", "yes"], "richardson: only with crossing exact"),
    (["threshold", "realistic", 1, "reform", "none", "steady", "q.dat"], "steady: contacts that never re-form have no steady state"),
    (["threshold", "realistic", 1, "reform", "none", "start", "reform"], "start reform: needs contacts that re-form"),
    (["threshold", "realistic", 1, "exact", "e.dat"], "exact: needs threshold uniform lo hi with lo > 0"),
    (["threshold", "realistic", 1, "xmax", 2, "snapshot", 3, "q.dat"], "snapshot: X = 3.000000 outside [0, xmax]"),
    (["threshold", "table", "nofile.table", "K"], "threshold table: cannot open table file 'nofile.table'"),
    (["threshold", "realistic", 1, "force", "/no/such/dir/f.dat"], "cannot write file '/no/such/dir/f.dat'"),
])
def test_errors_name_the_keyword(tmp_path, args, message):
    p = eqme(args, tmp_path)
    assert p.returncode == 1
    assert p.stderr.startswith("eq-me: ERROR: ") and message in p.stderr, p.stderr


def test_tables_and_summary(tmp_path):
    s = eqtools.run_eqme(["threshold", "realistic", 1.0, "reform", "gaussian", 0.2, 0.05,
                          "xmax", 6, "dx", 2e-3, "force", "f.dat", "steady", "q.dat",
                          "snapshot", 2.5, "s.dat"], cwd=tmp_path)
    f = eqtools.load(tmp_path / "f.dat")
    assert f.shape == (3001, 6)
    assert np.allclose(f[:, 4], 1.0, atol=1e-12)                # all attached
    q = eqtools.load(tmp_path / "q.dat")
    assert abs(np.trapz(q[:, 1], q[:, 0]) - 1.0) < 1e-4          # Q_s normalized
    assert abs(np.trapz(q[:, 0] * q[:, 1], q[:, 0]) - s["kinetic_force"]) < 1e-4
    sn = eqtools.load(tmp_path / "s.dat")
    assert abs(np.sum(sn[:, 1]) * 2e-3 - 1.0) < 1e-12           # masses sum to one
    for key in ("kstar", "kstar_X", "static_peak", "kinetic_force", "steady_rate", "mass_error"):
        assert key in s
    assert s["mass_error"] < 1e-12


def test_richardson_removes_the_second_order_error(tmp_path):
    """Exact renewal reference (uniform thresholds): plain second order at
    dx = 1e-3 gives 5.1e-7; Richardson (dx, dx/2) gives ~1e-13 when the
    kinks of P_c lie on the grid."""
    base = ["threshold", "uniform", 0.75, 1.25, "dx", 1e-3, "exact", "e.dat"]
    plain = eqtools.run_eqme(base + ["richardson", "no"], cwd=tmp_path)
    rich = eqtools.run_eqme(base, cwd=tmp_path)
    assert 4e-7 < plain["exact_max_error"] < 6e-7
    assert rich["exact_max_error"] < 1e-11


def test_grid_that_does_not_divide_xmax(tmp_path):
    """xmax is rounded to a whole number of steps, so that Richardson's
    fine grid ends at the same X (this once read past its end)."""
    s = eqtools.run_eqme(["threshold", "realistic", 1.0, "xmax", 4, "dx", 0.0015], cwd=tmp_path)
    assert "NOTE         xmax 4 rounded to 4.0005" in s["stdout"]
    assert abs(s["kstar"] - 0.174250) < 1e-5
    assert abs(s["xmax"] - 4.0005) < 1e-12


def test_contacts_that_never_reform(tmp_path):
    s = eqtools.run_eqme(["threshold", "uniform", 0.75, 1.25, "reform", "none", "xmax", 20,
                          "force", "f.dat"], cwd=tmp_path)
    f = eqtools.load(tmp_path / "f.dat")
    X = f[:, 0]
    J = np.clip((1.25 - X) / 0.5, 0, 1)
    assert np.max(np.abs(f[:, 1] - X * J)) < 1e-12
    assert "kinetic_force" not in s and abs(s["kstar"] - 2.5) < 3e-3


def test_stiffness_distribution_scales_the_force(tmp_path):
    base = ["threshold", "realistic", 1.0, "xmax", 6]
    plain = eqtools.run_eqme(base, cwd=tmp_path)
    f = eqtools.run_eqme(base + ["stiffness", "gaussian", 1.0, 0.5, "dir", "y"], cwd=tmp_path)
    assert abs(f["stiffness_mean"] - 1.0276239) < 1e-6          # truncated at 0
    for key in ("kinetic_force", "kstar", "static_peak"):
        assert abs(f[key] - f["stiffness_mean"] * plain[key]) < 1e-12 * max(1, plain[key])


def test_static_peak_and_kstar_when_nothing_breaks(tmp_path):
    s = eqtools.run_eqme(["threshold", "uniform", 0.5, 1.5, "xmax", 0.01, "dx", 1e-4], cwd=tmp_path)
    assert "static peak  none: F still increases at xmax" in s["stdout"]
    assert s["kstar"] == 0.0 and "static_peak" not in s


def test_table_found_through_lammps_potentials(tmp_path):
    import os
    env = dict(os.environ, LAMMPS_POTENTIALS=str(eqtools.ROOT / "potentials"))
    p = subprocess.run([eqtools.eqme_exe(), "threshold", "table", "eq_thresholds.table", "BIMODAL",
                        "xmax", "2"], cwd=tmp_path, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    assert p.returncode == 0 and "table eq_thresholds.table BIMODAL" in p.stdout


def test_static_peak_at_a_kink_and_exact_with_stiffness(tmp_path):
    s = eqtools.run_eqme(["threshold", "uniform", 0.75, 1.25, "stiffness", "uniform", 0.5, 2.0,
                          "exact", "e.dat"], cwd=tmp_path)
    # peak of <x> at the kink X = 0.75, scaled by <f> = 1.25; the exact
    # solution is compared after the same scaling
    assert abs(s["static_peak"] - 1.25 * 0.75) < 1e-10 and abs(s["static_peak_X"] - 0.75) < 1e-12
    assert s["exact_max_error"] < 1e-11


def test_fixed_delay_beyond_xmax(tmp_path):
    """A fixed delay whose re-formations lie beyond xmax re-forms nothing
    within it, however long (v tau / dx = 1e10 cells: before, the kernel
    was allocated for all of them, std::bad_alloc): F(X) equal to that of
    a delay of v tau = 10 > xmax, to the last digit."""
    base = ["threshold", "uniform", 0.75, 1.25, "velocity", 1e-3, "xmax", 2]
    far = eqtools.run_eqme(base + ["delay", "fixed", 1e9, "force", "far.dat"], cwd=tmp_path)
    near = eqtools.run_eqme(base + ["delay", "fixed", 1e4, "force", "near.dat"], cwd=tmp_path)
    a, b = np.loadtxt(tmp_path / "far.dat"), np.loadtxt(tmp_path / "near.dat")
    assert a.shape == b.shape and np.array_equal(a[:, 1], b[:, 1])
    assert a[:, 1].max() == far["static_peak"] == near["static_peak"] == 0.75


def test_lifetime_underflow_is_an_error(tmp_path):
    """At a velocity so small that a life is shorter than the smallest
    double (creep), an error naming velocity, not NaN with status 0."""
    p = eqme(["threshold", "uniform", 0.75, 1.25, "xmax", 2, "thermal", 0.02, 1, 1,
              "velocity", 1e-300], tmp_path)
    assert p.returncode == 1 and "velocity 1e-300: the contacts' lifetime" in p.stderr, \
        (p.stdout, p.stderr)
    # v = 1e-30 still gives the creep force
    s = eqtools.run_eqme(["threshold", "uniform", 0.75, 1.25, "xmax", 2, "thermal", 0.02, 1, 1,
                          "velocity", 1e-30], cwd=tmp_path)
    assert 0.0 < s["kinetic_force"] < 1e-6
