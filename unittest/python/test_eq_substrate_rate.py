"""fix eq/substrate rate A v0: the velocity-dependent block law of FK-ME
kinks at T > 0, F_rate = A asinh(u'/(2 v0)) opposing a block's velocity,
against independent references (examples/eq-thermal/kink_rate.py).

* A = 0 is the keyword-off run bit for bit; a tiny A slows the kink by no
  more than the viscous bound A/(2 v0 gamma);
* v0 far above every block velocity: the rate term is the viscous drag
  A/(2 v0), i.e. the run with LAMMPS' fix viscous of that gamma, with fix
  brownian and with fix nve, to the asinh linearisation (bounded) and
  rounding;
* a running kink in the logarithmic regime (A = 0.01, v0 = 1e-4, u' up to
  1.2e-2): the kink velocity of LAMMPS (Richardson over dt, dt/2, dt/4)
  against an RK4 integration of the implicit chain equations written in
  the example, the tolerance from the extrapolation's own error; and the
  slowdown between the viscous drags that bound the concave rate force;
* 1 and 2 MPI ranks, a restart (no per-block state: bit for bit), the
  keyword added or dropped at a restart, no rate force in a minimization;
* errors: bad or missing values name fix eq/substrate and the keyword.
"""
import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from eqtools import fkme, run_lammps

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("eq_thermal_kink_rate",
                                               ROOT / "examples" / "eq-thermal" / "kink_rate.py")
kr = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(kr)

EPS = np.finfo(float).eps
F = 0.8                                     # v_k = 0.0503 at A = 0 (f_+ = 0.6214)
T_END = 1.3 * (kr.TRACK[1] - kr.SEED1 + 10) / fkme.vk_discrete(F, kr.G, kr.KC, kr.UC, kr.K, 1.0,
                                                               kr.GAMMA)


def run(d, **var):
    d = Path(d)
    d.mkdir(parents=True, exist_ok=True)
    base = dict(f=F, dt=kr.DT, steps=int(math.ceil(T_END / kr.DT)), out=".")
    base.update(var)
    return run_lammps(kr.INPUT, variables=base, cwd=d)


def last(path):
    _, cols = fkme.read_dump(path)
    return {k: v[-1] for k, v in cols.items() if k != "box"}


# ------------------------------------------------------------- 1. A -> 0
def test_zero_amplitude_is_the_keyword_off_run(tmp_path):
    """rate 0 v0 against no keyword: the tracked positions of every step
    and the final state bit for bit.  A = 1e-9: the kink is slower, by at
    most the viscous bound gamma_hi/(gamma + gamma_hi), gamma_hi = A/(2 v0)
    = 5e-6 (the rate force lies below gamma_hi |u'|), i.e. 5e-8, and not
    faster (a larger drag cannot speed up the monotone overdamped chain:
    comparison principle); the crossing times are read to ~1e-13 relative,
    far below."""
    v = {}
    for name, A in (("off", -1), ("zero", 0.0), ("tiny", 1e-9)):
        run(tmp_path / name, A=A, dumpevery=int(math.ceil(T_END / kr.DT)))
        tc = kr.crossing_times(tmp_path / name / "track.dat")
        v[name] = (kr.TRACK[1] - kr.TRACK[0]) / (tc[1] - tc[0])
    assert (tmp_path / "off" / "track.dat").read_bytes() == (tmp_path / "zero" / "track.dat").read_bytes()
    assert (tmp_path / "off" / "kink.dump").read_bytes() == (tmp_path / "zero" / "kink.dump").read_bytes()
    # sanity only (a kink at all, of the right chain): the tracked blocks are
    # 18-48 sites from the seed, where the kink still approaches its steady
    # shape (1.3e-5 from the exact travelling wave; a wrong set-up, e.g.
    # another f or gamma, is off by percents)
    assert abs(v["off"] / fkme.vk_discrete(F, kr.G, kr.KC, kr.UC, kr.K, 1.0, kr.GAMMA) - 1) < 2e-3
    g_hi = 1e-9 / (2 * kr.V0)
    slow = 1 - v["tiny"] / v["off"]
    assert -1e-12 <= slow <= g_hi / (kr.GAMMA + g_hi) + 1e-12, slow


# ------------------------------------------------- 2. the linear limit
@pytest.mark.parametrize("integ", ["brownian", "nve", "brownian-kc"])
def test_linear_limit_is_fix_viscous(tmp_path, integ):
    """v0 = 1e5 (brownian; 1e7 nve) far above every block velocity w: the
    rate force A asinh(w/(2 v0)) = gamma_r w (1 - x^2/6 + ...), x = w/(2
    v0), gamma_r = A/(2 v0) = 20 (0.5 with nve, eta = 1, dt = 0.02).  The
    same run with 'fix viscous gamma_r' instead: both read the same
    velocity (fix brownian's dx/dt, or the half-step velocity of nve), so
    the forces differ by gamma_r |w| x^2/6 <= gamma_r w_max^3/(24 v0^2)
    (w_max < 5: 3e-13 and 2e-16 relative) plus rounding.  Bound on the
    positions of every step: (n_steps + 1) * 8 EPS * max|x| (a few ulp per
    step, accumulated linearly; the damped chain does not amplify them)
    plus the linearisation, (w_max/(2 v0))^2/6 times the largest
    displacement.  brownian-kc: every block's k_c set to 0.4 of the
    fix's kc (fix_modify kc): the rate term scales with the block's
    contacts as its shape does, so the equivalent drag is 0.4 gamma_r."""
    scale = 1.0
    if integ.startswith("brownian"):
        var = dict(integ="brownian", steps=int(math.ceil(T_END / kr.DT)))
        A, v0, g_r = 4e6, 1e5, 20.0
        if integ == "brownian-kc":
            var["kcall"] = scale = 0.4
    else:
        var = dict(integ="nve", eta=1.0, dt=0.02, steps=3000)
        A, v0, g_r = 1e7, 1e7, 0.5
    assert A / (2 * v0) == g_r
    run(tmp_path / "rate", A=A, v0=v0, dumpevery=var["steps"], **var)
    run(tmp_path / "visc", A=-1, visc=scale * g_r, dumpevery=var["steps"], **var)
    tr = np.loadtxt(tmp_path / "rate" / "track.dat")
    tv = np.loadtxt(tmp_path / "visc" / "track.dat")
    r, v = last(tmp_path / "rate" / "kink.dump"), last(tmp_path / "visc" / "kink.dump")
    wmax = max(np.abs(r["vx"]).max(), 5.0)
    assert np.abs(r["vx"]).max() < 5.0
    disp = np.abs(r["f_sub[1]"]).max()
    bound = (var["steps"] + 1) * 8 * EPS * kr.N + (wmax / (2 * v0)) ** 2 / 6 * disp
    assert np.abs(tr - tv).max() <= bound, (np.abs(tr - tv).max(), bound)
    assert np.abs(r["x"] - v["x"]).max() <= bound
    # the kink has run: the tracked blocks slipped in both runs
    assert kr.crossing_times(tmp_path / "rate" / "track.dat")[1] > 0


# ---------------------------------------- 3. the nonlinear running kink
def test_running_kink_against_the_implicit_chain(tmp_path):
    """A = 0.01, v0 = 1e-4 (A/(2 v0) = 50 < gamma = 100: the lagged rate
    term of fix brownian is stable), f = 0.8: the blocks of the kink slip
    at up to 1.2e-2 = 120 v0 (asinh ~ ln, the nonlinear regime).

    LAMMPS: fix brownian is first order in dt, and its error a smooth
    series (the crossings corrected exactly; the rate term lags by one
    step, a smooth O(dt) term): with v(h) the kink velocity at step h,
    E1 = 2 v(dt/2) - v(dt) and E2 = 2 v(dt/4) - v(dt/2) remove the first
    order; their errors c h^2 + O(h^3) give E1 - E2 = (3/4) c dt^2, so E2
    is off by (E1 - E2)/3, doubled for the O(h^3) rest (checked: the raw
    differences halve with h, the first order dominates).  The reference:
    RK4 on the implicit equations (kink_rate.reference_velocity), its
    error |v(h) - v(2h)|/15 at h = 0.2.  Tolerance: 2|E1 - E2|/3 + the
    reference's error.

    Sanity: the rate force is concave in u' >= 0, so gamma_lo u' <=
    F_rate(u') <= gamma_hi u' on [0, u'_max] with gamma_lo = A asinh(
    u'_max/(2 v0))/u'_max (the secant) and gamma_hi = A/(2 v0): the kink
    is slower than with viscous gamma_lo and faster than with gamma_hi
    (comparison principle of the monotone chain; the block velocities stay
    >= -2e-6, where the bracket holds to ~1e-4 of the drag).  The note's
    estimate eta_T/eta = A/(u' gamma) (the differential damping) is far
    below the slowdown: the rate force is A ln(u'/v0) ~ 5 A at these
    velocities, not A."""
    A, v0 = kr.A_RATE, kr.V0
    v, ext = kr.lammps_extrapolated(F, A, v0, tmp_path, levels=3)
    assert 1.8 < (v[0] - v[1]) / (v[1] - v[2]) < 2.2    # first order
    ref, ref_err, wmax, wmin = kr.reference_velocity(F, A, v0, h=0.2)
    tol = 2 * abs(ext[0] - ext[1]) / 3 + ref_err
    assert abs(ext[1] - ref) <= tol, (ext, ref, tol)
    # the comparison resolves the rate term: the tolerance is below 1e-3 of
    # the slowdown it causes (12 %)
    v_off = fkme.vk_discrete(F, kr.G, kr.KC, kr.UC, kr.K, 1.0, kr.GAMMA)
    assert tol < 1e-3 * (v_off - ref)
    # sanity bounds of the slowdown, A = 0 from the exact travelling wave
    g_lo = A * math.asinh(wmax / (2 * v0)) / wmax
    g_hi = A / (2 * v0)
    # blocks moving backward (wmin < 0) feel at most gamma_hi |wmin|, below
    # 1e-3 of the drag of the kink's blocks: the bracket holds to that
    assert g_hi * -wmin < 1e-3 * kr.GAMMA * wmax
    slow = 1 - ref / v_off
    lo, hi = 1 - kr.GAMMA / (kr.GAMMA + g_lo), 1 - kr.GAMMA / (kr.GAMMA + g_hi)
    assert lo < slow < hi, (lo, slow, hi)
    eta_T = A / wmax
    assert eta_T / kr.GAMMA < slow


# --------------------------------------------- 4. ranks and restarts
def test_ranks_and_restart(tmp_path):
    """rate 0.01 1e-4, 6000 steps (the kink running): 2 ranks against 1 to
    rounding (pair sums in another order); 3000 + write_restart +
    read_restart + 3000 bit for bit (the term has no state: it reads the
    velocities, which the restart file holds, and fix brownian does not
    change them between runs); a file written without the keyword read
    with it runs (and vice versa)."""
    common = dict(A=kr.A_RATE, v0=kr.V0)
    run(tmp_path / "p1", steps=6000, dumpevery=6000, **common)
    d2 = tmp_path / "p2"
    d2.mkdir()
    run_lammps(kr.INPUT, variables=dict(f=F, steps=6000, dumpevery=6000, out=".", **common),
               nprocs=2, cwd=d2)
    r1, r2 = last(tmp_path / "p1" / "kink.dump"), last(d2 / "kink.dump")
    assert np.abs(r1["x"] - r2["x"]).max() < 1e-10
    assert np.array_equal(r1["f_sub[6]"], r2["f_sub[6]"])
    d = tmp_path / "split"
    (d / "r").mkdir(parents=True)
    run(d, steps=3000, restartfile="half", **common)
    run(d, steps=3000, readrestart="half", dumpevery=3000, out="r", **common)
    rs = last(d / "r" / "kink.dump")
    for c in ("x", "vx", "f_sub[1]", "f_sub[2]", "f_sub[6]"):
        assert np.array_equal(r1[c], rs[c]), c
    d = tmp_path / "layouts"
    run(d, steps=10, restartfile="without", A=-1)
    run(d, steps=10, readrestart="without", **common)
    run(d, steps=10, restartfile="with", **common)
    run(d, steps=10, readrestart="with", A=-1)


MINIMIZE = """
units           lj
dimension       2
atom_style      atomic
atom_modify     map array
lattice         sq 1.0
region          box block 0 20 0 1 -0.5 0.5
create_box      1 box
create_atoms    1 box
mass            1 1.0
pair_style      eq/elastic 1.5
pair_coeff      1 1 25.0 1.0
neighbor        2.0 bin
fix             sub all eq/substrate 1.0 sawtooth 1.0 drive 0.07 0.0 stage 5.0 ${rk}
fix_modify      sub energy yes
velocity        all set 0.3 0 0
min_modify      dmax 0.01
minimize        0 1e-12 10000 100000
write_dump      all custom min.dump id x modify sort id format float %.17g
"""


def test_no_rate_force_in_a_minimization(tmp_path):
    """Velocities of 0.3 (rate force 0.01 asinh(1500) = 0.08 if it acted):
    the minimized positions with and without the keyword are the same bit
    for bit (no time passes in a minimization, as for the thermal hops)."""
    for name, rk in (("off", ""), ("on", "rate 0.01 1e-4")):
        (tmp_path / name).mkdir()
        inp = tmp_path / name / "in.min"
        inp.write_text(MINIMIZE.replace("${rk}", rk))
        run_lammps(inp, cwd=tmp_path / name)
    assert (tmp_path / "off" / "min.dump").read_bytes() == (tmp_path / "on" / "min.dump").read_bytes()


# ------------------------------------------------------------ 5. errors
@pytest.mark.parametrize("args, message", [
    ("rate -0.01 1e-4", "rate A: must be finite and >= 0 (got -0.01)"),
    ("rate 0.01 0", "rate v0: must be finite and > 0 (got 0)"),
    ("rate 0.01 -1e-4", "rate v0: must be finite and > 0"),
    ("rate 1e299 1", "rate A: 1e+299 would make the rate force"),
    ("rate 1e400 1", "rate A: expected a finite number"),
    ("rate 0.01 1e400", "rate v0: expected a finite number"),
    ("rate abc 1e-4", "rate A: expected a number, got 'abc'"),
    ("rate 0.01 v0", "rate v0: expected a number, got 'v0'"),
    ("rate 0.01", "rate: expected 2 values (A v0), got 1"),
    ("rate", "rate: expected 2 values (A v0), got 0"),
])
def test_bad_rate_values_are_errors(tmp_path, args, message):
    inp = tmp_path / "in.e"
    inp.write_text(MINIMIZE.replace("${rk}", args))
    out = run_lammps(inp, cwd=tmp_path, check=False)
    assert "ERROR" in out and "Fix eq/substrate " + message in out, out[-1500:]
