"""Velocity-dependent stick-slip at T > 0 (issue 23, item 4): a slider of
EQ contacts (fix eq/contacts ... thermal, N = 1020) pulled through a spring
by a stage at velocity v (examples/eq-thermal/in.eq-thermal-stickslip)
against the master equation in time coupled to the slider's equation of
motion (tools/eqtools/slider.py, written apart from the C++ and tested on
its own in test_eqtools_slider.py); and one fix eq/meso block at T > 0 in
place of the EQ slider (in.eq-thermal-meso-stickslip) against the same ME.

Five independent seeds give the mean and its standard error of each
measured quantity; the tolerance is Student's t (4 dof, two-sided p =
1e-3) times that error plus the ME's own grid error (its F is within 2e-4
of the converged one: a slider position within 2e-4/K)."""
import importlib.util
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
T_4DOF = 8.61
SEEDS = (1, 2, 3, 4, 5)


def _load():
    spec = importlib.util.spec_from_file_location(
        "example_eq_thermal_stickslip", ROOT / "examples" / "eq-thermal" / "stickslip.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


ss = _load()


def mean_se(values):
    a = np.asarray(values, dtype=float)
    return a.mean(), a.std(ddof=1) / math.sqrt(len(a))


def test_slip_follows_the_master_equation_in_time(tmp_path):
    """theta = 0.05, v = 1e-3, K = 0.5 N k_c: the loading branch, where the
    slip starts and how far the slider jumps, EQ against the ME in time."""
    th, v, K = 0.05, 1e-3, 0.5
    me = ss.me_run(th, v, K)
    me_onset, me_jump = max(ss.fast_stretches(me), key=lambda s: s[1])
    assert me_jump > 2 * ss.SLIP          # a real slip, not the threshold's edge
    onset, jump, branch = [], [], []
    for seed in SEEDS:
        d = ss.eq_run(tmp_path / f"s{seed}", th, v, K, seed=seed)
        o, j = max(ss.fast_stretches(d), key=lambda s: s[1])
        onset.append(o)
        jump.append(j)
        # the loading branch, up to 0.2 before the ME's slip: slider position
        pre = d["stage"] < me_onset - 0.2
        branch.append(np.mean(d["X"][pre] - np.interp(d["stage"][pre], me["stage"], me["X"])))
    grid = 2e-4 / K
    for name, values, ref in (("onset", onset, me_onset), ("jump", jump, me_jump),
                              ("branch", branch, 0.0)):
        m, se = mean_se(values)
        tol = T_4DOF * se + grid + (ss.WINDOW if name == "onset" else 0.0)
        assert abs(m - ref) < tol, (name, values, ref, tol)


def test_slips_fade_with_velocity_where_kstar_says_unstable(tmp_path):
    """K = 0.75 N k_c, theta = 0.05: K*(v) of the constant-velocity ME is
    1.04 at v = 0.1 and 0.99 at v = 1e-5, so the quasi-static criterion K <
    K*(v) predicts a slip at both.  The ME in time slips at v = 0.1 only
    (during a slip the contacts are loaded faster and break less by
    activation), and so do the EQ runs."""
    th, K = 0.05, 0.75
    for v, slip in ((0.1, True), (1e-5, False)):
        ks = ss.kstar(th, v, tmp_path / f"me{v:g}")
        assert K < ks - 0.2, (v, ks)
        me_jump = ss.largest_jump(ss.me_run(th, v, K))
        assert (me_jump > 2 * ss.SLIP) if slip else (me_jump < 0.5 * ss.SLIP), (v, me_jump)
        jumps = [ss.largest_jump(ss.eq_run(tmp_path / f"v{v:g}s{seed}", th, v, K, seed=seed))
                 for seed in SEEDS]
        assert all((j > ss.SLIP) == slip for j in jumps), (v, jumps, me_jump)
        if slip:
            m, se = mean_se(jumps)
            assert abs(m - me_jump) < T_4DOF * se + 2e-4 / K, (v, jumps, me_jump)


def test_meso_block_is_the_master_equation_in_time(tmp_path):
    """One fix eq/meso block at T > 0 (its contacts are their master
    equation) in place of the EQ slider, theta = 0.05, v = 1e-3, K = 0.5:
    the C++ block kernel and tools/eqtools/slider.py discretize the same
    ME on the same grid (anchor cells 4e-3, 16 threshold panels) and were
    written apart, so their trajectories must agree far below the scheme's
    own error, measured here as the change of slider.py's trajectory on
    halving its cells and doubling its panels (a bug of either code, e.g.
    a rate without its prefactor or a hazard of the wrong step, moves a
    trajectory by the order of that error or more).  The slip itself:
    onset and jump as the ME's."""
    th, v, K = 0.05, 1e-3, 0.5
    meso = ss.meso_run(tmp_path / "meso", th, v, K)
    me = ss.me_run(th, v, K)
    fine = ss.slider.slider_me(K, v, th, lo=ss.LO, hi=ss.HI, slow=ss.SLOW, dX=ss.DX,
                               Xend=ss.xend(K), n_labels=2 * ss.ME_GRID["n_labels"],
                               dA=ss.ME_GRID["dA"] / 2)
    n = min(len(meso["X"]), len(me["X"]), len(fine["X"]))
    assert n == len(me["X"])
    scheme_error = np.max(np.abs(fine["X"][:n] - me["X"][:n]))
    assert scheme_error > 1e-5                  # the comparison resolves the scheme
    dev = np.max(np.abs(meso["X"][:n] - me["X"][:n]))
    assert dev < 0.05 * scheme_error, (dev, scheme_error)
    (o1, j1), (o2, j2) = (max(ss.fast_stretches(r), key=lambda s: s[1]) for r in (meso, me))
    assert j2 > 2 * ss.SLIP
    assert abs(o1 - o2) <= ss.WINDOW and abs(j1 - j2) < 0.1 * scheme_error, (o1, o2, j1, j2)


def test_meso_block_slips_fade_with_velocity(tmp_path):
    """The velocity transition of test_slips_fade_with_velocity_where_kstar_says_unstable
    for one fix eq/meso block: K = 0.75 N k_c, theta = 0.05 slips at v =
    0.1 and slides smoothly at v = 1e-5, as the ME in time (and unlike
    the quasi-static criterion K < K*(v), which predicts slips at both)."""
    th, K = 0.05, 0.75
    for v, slip in ((0.1, True), (1e-5, False)):
        jump = ss.largest_jump(ss.meso_run(tmp_path / f"v{v:g}", th, v, K))
        assert (jump > 2 * ss.SLIP) if slip else (jump < 0.5 * ss.SLIP), (v, jump)
