"""tools/eqtools/fkme.py: the FK-ME chain of paper Sec. V B.  Closed forms
against their own expansions and the travelling-wave equation, the numpy
reference integrator against exact solutions, the kink analysis on
synthetic kinks, and the LAMMPS readers on small files.  All fast (no
LAMMPS)."""
import math

import numpy as np
import pytest

from eqtools import fkme

# the paper's chain (Figs. crack.A04a, crack.A05)
P = dict(kc=1.0, uc=1.0, K=0.07, m=1.0, eta=100.0)
KC, UC, K = P["kc"], P["uc"], P["K"]


# ------------------------------------------------------------ closed forms

def test_thresholds_and_uniform_states_balance_forces():
    f = np.linspace(0.6, 1.05, 10)
    ur, ul = fkme.uniform_positions(f, KC, UC, K)
    np.testing.assert_allclose(KC * ur + K * ur, f, rtol=1e-14)
    np.testing.assert_allclose(KC * (ul - UC) + K * ul, f, rtol=1e-14)
    np.testing.assert_allclose(ul - ur, fkme.kink_jump(KC, UC, K), rtol=1e-13)
    assert fkme.f_min(KC, UC, K) == pytest.approx(0.57)
    assert fkme.f_max(KC, UC, K) == pytest.approx(1.07)
    # f_max: the unrelaxed block sits at the top of the sawtooth
    assert fkme.uniform_positions(fkme.f_max(KC, UC, K), KC, UC, K)[0] == pytest.approx(UC)
    assert fkme.beta(fkme.f_min(KC, UC, K), KC, UC, K) == pytest.approx(2.0)
    assert fkme.beta(fkme.f_max(KC, UC, K), KC, UC, K) == pytest.approx(1.0)


def test_vk_overdamped_domain_and_limits():
    g = 25.0
    fmin, fmax = fkme.f_min(KC, UC, K), fkme.f_max(KC, UC, K)
    assert fkme.vk_overdamped(fmin, g, **P) == 0.0
    assert np.isnan(fkme.vk_overdamped(fmin - 1e-9, g, **P))
    assert np.isnan(fkme.vk_overdamped(fmax, g, **P))
    f = np.linspace(fmin, fmax, 200, endpoint=False)
    assert np.all(np.diff(fkme.vk_overdamped(f, g, **P)) > 0)
    # -> infinity at f_max like the high-velocity formula; the ratio's
    # deviation from 1 is first order in (f_max - f)
    dev = []
    for d in (1e-3, 1e-4, 1e-5):
        ratio = fkme.vk_overdamped(fmax - d, g, **P) / fkme.vk_high_overdamped(fmax - d, g, **P)
        dev.append(abs(ratio - 1.0))
    assert dev[0] < 1e-2
    assert dev[0] / dev[1] == pytest.approx(10.0, rel=0.05)
    assert dev[1] / dev[2] == pytest.approx(10.0, rel=0.05)
    assert fkme.vk_overdamped(fmax - 1e-12, g, **P) > 1e3 * fkme.vk_overdamped(0.8, g, **P)


def test_low_velocity_law_is_first_order_of_eqi04():
    """dv_k/df at f_min+ from Eq. crack.eqi04 is 1/(m_k eta) (Eq. crack.v1);
    the finite-difference error is first order in the increment."""
    for g in (5.0, 25.0, 100.0):
        fmin = fkme.f_min(KC, UC, K)
        slope = 1.0 / (fkme.kink_mass(P["m"], g, KC, UC, K) * P["eta"])
        errs = []
        for e in (1e-2, 1e-3, 1e-4):
            d = fkme.vk_overdamped(fmin + e, g, **P) / e
            errs.append(d / slope - 1.0)
            assert fkme.vk_low(fmin + e, g, **P) / e == pytest.approx(slope, rel=1e-12)
        # the error is even second order: with d = (f - f_min)/(kc uc),
        # 2 - beta = 4d - 8d^2 + .. and 1/sqrt(beta - 1) = 1 + 2d + .., so the
        # d^2 terms of sqrt(X) = (2 - beta)/sqrt(beta - 1) = 4d + O(d^3) cancel
        assert abs(errs[0]) < 1e-3
        assert errs[0] / errs[1] == pytest.approx(100.0, rel=0.05)
        assert errs[1] / errs[2] == pytest.approx(100.0, rel=0.05)


def test_inertial_formula_limits():
    g = 25.0
    f = np.array([0.6, 0.75, 0.9, 1.0, 1.06])
    # with g -> g (1 - v^2/c0^2): v_in = v_od / sqrt(1 + v_od^2/c0^2) exactly,
    # so at fixed m*eta and m -> 0 (c0 -> inf) it reduces to Eq. crack.eqi04
    meta = P["m"] * P["eta"]
    for m in (1e-2, 1e-4, 1e-6):
        v_od = fkme.vk_overdamped(f, g, KC, UC, K, m, meta / m)
        v_in = fkme.vk_inertial(f, g, KC, UC, K, m, meta / m)
        c2 = fkme.sound_speed(g, m) ** 2
        np.testing.assert_allclose(v_in, v_od / np.sqrt(1 + v_od ** 2 / c2), rtol=1e-12)
        assert np.max(np.abs(v_in / v_od - 1)) <= 0.5 * np.max(v_od) ** 2 / c2
    # -> c0 at f_max, like the high-velocity inertial formula
    c0 = fkme.sound_speed(g, P["m"])
    fmax = fkme.f_max(KC, UC, K)
    for d in (1e-6, 1e-8):
        v = fkme.vk_inertial(fmax - d, g, **P)
        assert v < c0
        assert v == pytest.approx(c0, rel=1e4 * d)          # 1 - v/c0 ~ m eta^2 d/(2 kc kappa uc)
        assert v == pytest.approx(fkme.vk_high_inertial(fmax - d, g, **P), rel=10 * d)
    # inertia only slows the kink down
    assert np.all(fkme.vk_inertial(f, g, **P) < fkme.vk_overdamped(f, g, **P))


def test_kink_profile_solves_the_travelling_wave_equation():
    """g u'' + m eta v u' = F_s(u) + K u - f (Eq. crack.eqi04h) away from the
    kink centre, u = uc and a continuous u' at the centre, u_R/u_L far away:
    checks the derivation of Eq. crack.eqi04 independently of its algebra."""
    for g, f, inertia in ((25.0, 0.75, False), (5.0, 1.0, False), (25.0, 1.05, True)):
        v = (fkme.vk_inertial if inertia else fkme.vk_overdamped)(f, g, **P)
        geff = g - P["m"] * v * v if inertia else g
        h = 1e-4
        x = np.concatenate([np.linspace(-30, -0.01, 300), np.linspace(0.01, 30, 300)])
        u = lambda y: fkme.kink_profile(y, f, g, **P, inertia=inertia)
        up = (u(x + h) - u(x - h)) / (2 * h)
        upp = (u(x + h) - 2 * u(x) + u(x - h)) / (h * h)
        rhs = fkme.substrate_force(u(x), KC, UC) + K * u(x) - f
        lhs = geff * upp + P["m"] * P["eta"] * v * up
        # central differences: truncation h^2 u''''/12 ~ 1e-9, rounding in
        # u'' ~ 1e-16 u/h^2 ~ 1e-8, times g = 25: ~1e-6 << 1e-5
        np.testing.assert_allclose(lhs, rhs, atol=1e-5)
        assert float(u(0.0)) == pytest.approx(UC)
        left = (u(0.0) - u(-1e-7)) / 1e-7
        right = (u(1e-7) - u(0.0)) / 1e-7
        assert left == pytest.approx(right, rel=1e-4)
        ur, ul = fkme.uniform_positions(f, KC, UC, K)
        assert float(u(-1e6)) == pytest.approx(ul, abs=1e-14)
        assert float(u(1e6)) == pytest.approx(ur, abs=1e-14)


def test_discrete_velocity_limits():
    """The exact discrete travelling wave: -> Eq. crack.eqi04 for g -> inf,
    -> 0 at the static depinning force f_+, grows without bound at f_max."""
    f = np.array([0.75, 0.85, 1.0])
    devs = []
    for g in (25.0, 250.0, 2500.0):
        devs.append(np.abs(fkme.vk_discrete(f, g, **P) / fkme.vk_overdamped(f, g, **P) - 1))
    assert np.all(devs[1] < devs[0]) and np.all(devs[2] < devs[1])
    assert np.all(devs[2] < 5e-3)             # discreteness ~ 2e-3 at g = 2500
    # the discrete kink is slower than the continuum one
    assert np.all(fkme.vk_discrete(f, 25.0, **P) < fkme.vk_overdamped(f, 25.0, **P))
    for g in (5.0, 25.0):
        fm, fp = fkme.discrete_depinning_force(g, KC, UC, K)
        assert fm < fkme.f_min(KC, UC, K) < fp
        assert 0.5 * (fm + fp) == pytest.approx(fkme.f_min(KC, UC, K))
        # the p -> 0 limit of the velocity equation is exactly f_+
        j0 = fkme._discrete_integral(1e-12, g, KC + K)
        assert j0 == pytest.approx((fp - fkme.f_min(KC, UC, K)) / (KC * UC * (KC + K)), rel=1e-9)
        assert fkme.vk_discrete(fp - 1e-9, g, **P) == 0.0
        v1, v2 = fkme.vk_discrete([fp + 1e-3, fp + 1e-2], g, **P)
        assert 0 < v1 < v2
        assert fkme.vk_discrete(fkme.f_max(KC, UC, K) - 1e-8, g, **P) > 100 * v2
    # continuum limit of the depinning range
    fm, fp = fkme.discrete_depinning_force(1e6, KC, UC, K)
    assert fp - fm < 2e-3


# -------------------------------------------------------------- integrator

def test_single_block_rk4_fourth_order_over_the_sawtooth():
    """One overdamped block pulled over the sawtooth (N = 1: no neighbours)
    against the exact piecewise-exponential solution: 3 discontinuities
    located as events, global error O(dt^4)."""
    kc, uc, k, meta, v, u0, T = 1.0, 1.0, 0.5, 1.0, 0.3, 0.2, 20.0
    exact, tcross = fkme.single_block_exact(np.array([T]), kc, uc, k, meta, v, u0)
    assert len(tcross) == 3
    errs, cerrs = [], []
    for dt in (0.2, 0.1, 0.05):
        r = fkme.simulate(1, 0.0, kc, uc, k, 1.0, meta, f0=0.0, v=v, u0=[u0], dt=dt,
                          t_end=T, every=0)
        assert r.nevents == 3
        errs.append(abs(r.u[0] - exact[0]))
        cerrs.append(np.max(np.abs(r.crossings[:, 0] - tcross)))
    order = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    corder = np.log2(np.array(cerrs[:-1]) / np.array(cerrs[1:]))
    # RK4 with events located on the Hermite interpolant: order 4 (measured
    # 4.1-4.2 at these steps, the asymptotic regime is approached from above)
    assert np.all((order > 3.6) & (order < 4.6)), order
    assert np.all((corder > 3.6) & (corder < 4.6)), corder
    assert errs[-1] < 1e-7


def test_single_block_exact_solution_is_consistent():
    """The exact solution itself: it satisfies the ODE (finite differences)
    on each branch and is continuous at the crossings."""
    kc, uc, k, meta, v = 1.0, 1.0, 0.5, 2.0, 0.3
    t = np.linspace(0.0, 40.0, 40001)
    u, tc = fkme.single_block_exact(t, kc, uc, k, meta, v, 0.0)
    du = np.gradient(u, t)
    rhs = (-kc * np.mod(u, uc) - k * (u - v * t)) / meta
    far = np.min(np.abs(t[:, None] - np.array(tc)[None, :]), axis=1) > 3e-3
    far[[0, -1]] = False                   # one-sided differences at the ends
    # central differences, step 1e-3: error h^2 u'''/6 ~ 1e-7
    np.testing.assert_allclose(du[far], rhs[far], atol=1e-6)
    assert np.max(np.abs(np.diff(u))) < 1e-3         # no jumps in u


def test_underdamped_block_fourth_order():
    """Underdamped single block (m = 1, eta = 0.5) over the sawtooth:
    self-convergence (reference dt/8 of the finest) of order 4."""
    kw = dict(kc=1.0, uc=1.0, K=0.5, m=1.0, eta=0.5, f0=0.0, v=0.3, u0=[0.2],
              overdamped=False, t_end=20.0, every=0)
    ref = fkme.simulate(1, 0.0, dt=0.00625, **kw)
    errs = []
    for dt in (0.2, 0.1, 0.05):
        r = fkme.simulate(1, 0.0, dt=dt, **kw)
        assert r.nevents == ref.nevents == 3
        errs.append(math.hypot(r.u[0] - ref.u[0], r.udot[0] - ref.udot[0]))
    order = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all((order > 3.5) & (order < 4.6)), order


def test_energy_of_undamped_harmonic_chain():
    """eta = 0, kc = 0: H = sum m w^2/2 + g (du)^2/2 + K u^2/2 is conserved by
    the dynamics; RK4 multiplies the energy of mode q by |R(i w_q h)|^2 per
    step (R the RK4 polynomial), so E(t)/E(0) lies between the smallest and
    largest of |R(i w_q h)|^(2n) -- an exact bound, not a tolerance."""
    N, g, k, m, dt, T = 32, 1.0, 0.1, 1.0, 0.1, 50.0
    rng = np.random.default_rng(3)
    ueq = 0.5                                  # equilibrium of the stage spring
    u0 = ueq + 0.05 * rng.standard_normal(N)   # stays inside (0, uc): no events
    r = fkme.simulate(N, g, kc=0.0, uc=1.0, K=k, m=m, eta=0.0, f0=k * ueq, v=0.0, u0=u0,
                      overdamped=False, dt=dt, t_end=T, every=0)
    assert r.nevents == 0 and r.nsteps == 500

    def energy(u, w):
        return 0.5 * m * np.sum(w * w) + 0.5 * g * np.sum((np.roll(u, -1) - u) ** 2) \
            + 0.5 * k * np.sum((u - ueq) ** 2)

    ratio = energy(r.u, r.udot) / energy(u0, np.zeros(N))
    w = np.sqrt((4 * g * np.sin(np.pi * np.arange(N) / N) ** 2 + k) / m)
    z = 1j * w * dt
    amp = np.abs(1 + z + z ** 2 / 2 + z ** 3 / 6 + z ** 4 / 24) ** (2 * r.nsteps)
    assert amp.min() - 1e-12 <= ratio <= amp.max() + 1e-12
    assert 1.0 - ratio < 1e-3


def test_chain_kink_velocity_matches_exact_discrete_travelling_wave():
    """Overdamped chain (N = 200, g = 25, f = 0.85) opened by a pre-displaced
    patch: the steady crossing rate equals vk_discrete (an independent
    semi-analytic solution); tracked velocity maxima and the mean chain
    velocity give the same v_k."""
    N, g, f = 200, 25.0, 0.85
    u0 = fkme.seeded_chain(N, f, KC, UC, K, width=20)
    r = fkme.simulate(N, g, f0=f, u0=u0, dt=0.5, t_end=1200.0, every=4, **P)
    vd = fkme.vk_discrete(f, g, **P)
    # window 135..165: > 25 sites from the seed (transient < 1e-6) and far
    # from the meeting point; RK4 error at dt = 0.5 is ~1e-9 (see the
    # order test), the transient residual ~1e-6
    assert fkme.crossing_velocity(r.crossings, 135, 165, 1) == pytest.approx(vd, rel=1e-5)
    assert fkme.crossing_velocity(r.crossings, 35, 65, 1) == pytest.approx(-vd, rel=1e-5)
    # discreteness: 5 % slower than the continuum Eq. crack.eqi04
    assert vd / fkme.vk_overdamped(f, g, **P) == pytest.approx(0.95, abs=0.01)
    tracks = fkme.track_kinks(r.t, r.kinks, N)
    assert len(tracks) == 2
    vt = sorted(fkme.kink_velocity(t, x, N, tmin=400.0) for t, x in tracks)
    # position of the velocity maximum oscillates by ~1 site per PN period;
    # over 800 time units (~50 sites) this is ~2e-2/50 relative
    assert vt[0] == pytest.approx(-vd, rel=2e-3)
    assert vt[1] == pytest.approx(vd, rel=2e-3)
    # mean chain velocity over ~53 PN periods (not an integer number: 2e-3)
    late = r.t >= 400.0
    jump = fkme.kink_jump(KC, UC, K)
    vm = fkme.kink_velocity_from_mean(r.vmean[late].mean(), N, 2, 0.0, jump)
    assert vm == pytest.approx(vd, rel=3e-3)
    # the paper's formula (jump = 1) is off by the factor kc/(kc + K)
    vpaper = fkme.kink_velocity_from_mean(r.vmean[late].mean(), N, 2, 0.0, 1.0)
    assert vpaper / vm == pytest.approx(KC / (KC + K), rel=1e-12)


def test_peierls_nabarro_pinning_in_the_chain():
    """g = 5: below the static depinning force f_+ the opened patch stops
    (no crossings late in the run), above it the kinks run at vk_discrete."""
    N, g = 120, 5.0
    fm, fp = fkme.discrete_depinning_force(g, KC, UC, K)
    T = 3000.0
    below = fkme.simulate(N, g, f0=fp - 0.005, u0=fkme.seeded_chain(N, fp - 0.005, KC, UC, K, 40),
                          dt=2.0, t_end=T, every=0, **P)
    assert np.all(below.crossings[:, 0] < 0.2 * T)
    f = fp + 0.02
    above = fkme.simulate(N, g, f0=f, u0=fkme.seeded_chain(N, f, KC, UC, K, 40),
                          dt=2.0, t_end=T, every=0, **P)
    vd = fkme.vk_discrete(f, g, **P)
    assert fkme.crossing_velocity(above.crossings, 85, 100, 1) == pytest.approx(vd, rel=1e-3)


def test_paper_protocol_weak_blocks_ramp_and_reversal():
    """Nucleation as in Figs. crack.A04a/A05: two weak blocks (kc' = 0.5),
    the stage ramped at v until the weak pair crosses uc, then kc restored
    and the stage reversed (v_b).  The pair breaks at the force where the
    static chain (g L - diag(kc + K)) u = -f first reaches uc, and the two
    kinks run at vk_discrete of the current force."""
    N, g, vb = 160, 5.0, -4e-5
    kc = fkme.weak_center_kc(N, 1.0, 0.5, 2)
    lap = -2 * np.eye(N) + np.roll(np.eye(N), 1, 0) + np.roll(np.eye(N), -1, 0)
    f_nuc = 1.0 / np.linalg.solve(g * lap - np.diag(kc + K), -np.ones(N)).max()
    f0, v = f_nuc - 0.02, 1e-4
    r = fkme.simulate(N, g, kc=kc, uc=UC, K=K, m=1.0, eta=100.0, f0=f0, v=v, dt=2.0,
                      t_end=30000.0, every=5,
                      schedule=[(lambda t, u, ud: np.any(u >= UC), {"v": vb, "kc": 1.0})],
                      stop=lambda t, u, ud: np.all(u >= UC))
    tb = r.crossings[0, 0]
    assert sorted(r.crossings[:2, 1]) == [N // 2 - 1, N // 2]      # the weak pair
    # quasi-static ramp: the lag is K v times the relaxation time of the
    # weak site, m eta/(kc' + K) ~ 175, i.e. ~1e-3 in force
    assert f0 + K * v * tb == pytest.approx(f_nuc, abs=2e-3)
    assert r.params["v"] == vb and np.all(r.params["kc"] == 1.0)
    assert r.t_end < 30000.0                   # stopped: all blocks slipped
    window = (r.t > tb + 300) & (r.t < r.t_end - 300)
    vref = np.mean(fkme.vk_discrete(r.f[window][::10], g, **P))
    long = [(t, x) for t, x in fkme.track_kinks(r.t, r.kinks, N) if len(t) > 100]
    assert len(long) == 2
    vt = sorted(fkme.kink_velocity(t, x, N, tb + 300, r.t_end - 300) for t, x in long)
    # the velocity maximum jumps by ~1 site per PN period over ~70 sites
    assert vt[0] == pytest.approx(-vref, rel=2e-2) and vt[1] == pytest.approx(vref, rel=2e-2)
    vm = fkme.kink_velocity_from_mean(r.vmean[window], N, 2, fkme.background_velocity(vb, 1.0, K),
                                      fkme.kink_jump(1.0, UC, K))
    assert vm.mean() == pytest.approx(vref, rel=1e-2)


def test_smooth_shape_kink_fourth_order():
    """Smooth F_s (also discontinuous at u = uc): a kink at g = 25, f = 1.3
    (the relaxed patch shrinks back below ~1.2); self-convergence in dt."""
    N, f = 100, 1.3
    u0 = fkme.seeded_chain(N, f, KC, UC, K, width=20, shape="smooth")
    runs = [fkme.simulate(N, 25.0, f0=f, u0=u0, dt=dt, t_end=600.0, every=0, shape="smooth", **P)
            for dt in (0.4, 0.2, 0.1)]
    assert runs[0].nevents == runs[2].nevents
    # the sharp edges of the patch first fall back once, then the kinks run
    assert np.sum(runs[2].crossings[:, 2] == 1) > 20
    assert np.all(runs[2].crossings[runs[2].crossings[:, 0] > 100.0, 2] == 1)
    e1 = np.max(np.abs(runs[0].u - runs[2].u))
    e2 = np.max(np.abs(runs[1].u - runs[2].u))
    # errors C h^p: (e(h) - e(h/4))/(e(h/2) - e(h/4)) = (1 - 4^-p)/(2^-p - 4^-p),
    # 17 for p = 4; the window 12..30 is p = 3.5..4.9
    assert 12 < e1 / e2 < 30, (e1, e2)


def test_schedule_stage_velocity_and_kc_switch():
    N = 8
    kc = fkme.weak_center_kc(N, 1.0, 0.5, 2)
    assert list(kc) == [1, 1, 1, 0.5, 0.5, 1, 1, 1]
    fired = []

    def trigger(t, u, udot):
        fired.append(t)
        return t >= 3.0

    r = fkme.simulate(N, 1.0, kc=kc, uc=1.0, K=0.1, m=1.0, eta=1.0, f0=0.0, v=1.0, dt=0.3,
                      t_end=6.0, every=1, schedule=[(2.05, {"v": -2.0}),
                                                   (trigger, {"kc": 1.0})])
    # f(t) = K v t, then slope K * (-2) from t = 2.05 (the step is cut there)
    fexp = np.where(r.t <= 2.05, 0.1 * r.t, 0.205 - 0.2 * (r.t - 2.05))
    np.testing.assert_allclose(r.f, fexp, atol=1e-14)
    assert fired[-1] == pytest.approx(3.0) and r.params["kc"].min() == 1.0
    assert r.params["v"] == -2.0


def test_smooth_shape_and_uniform_equilibrium():
    s = np.linspace(0, 0.999, 50)
    np.testing.assert_allclose(fkme.substrate_force(s + 3.0, 2.0, 1.0, "smooth"),
                               2.0 * (np.tanh(s) + 1.5 * np.exp(-s) * np.sin(3 * s)), rtol=1e-10)
    for shape in ("sawtooth", "smooth"):
        for branch in (0, 1):
            u = fkme.uniform_equilibrium(0.6, KC, UC, K, shape, branch)
            assert branch * UC <= u < (branch + 1) * UC
            assert fkme.substrate_force(u, KC, UC, shape) + K * u == pytest.approx(0.6, abs=1e-12)
    # a smooth-shape chain relaxes at rest from the seeded state's far field
    r = fkme.simulate(16, 5.0, f0=0.6, shape="smooth", dt=0.5, t_end=20.0, every=0, **P)
    assert np.max(np.abs(r.udot)) < 1e-12 and r.nevents == 0


# ------------------------------------------------------------ kink analysis

def sech2_velocity(N, centres, width, amp=1.0):
    n = np.arange(N)[None, :]
    d = np.mod(n - np.asarray(centres, float)[:, None] + N / 2, N) - N / 2
    return np.sum(amp / np.cosh(d / width) ** 2, axis=0)


def test_find_and_track_synthetic_kinks_across_the_boundary():
    """Velocity profiles of tanh kinks, v_n = sech^2((n - x_k(t))/w), one
    moving right through the periodic boundary, one moving left."""
    N, w, nfr = 100, 3.0, 60
    t = np.arange(nfr) * 2.0
    vr, vl = 0.35, -0.15                       # sites per time unit
    xr = np.mod(80.0 + vr * t, N)              # 80 -> 121.3 = 21.3: wraps
    xl = np.mod(60.0 + vl * t, N)              # 60 -> 42.3: always > 6 w apart
    frames = [sech2_velocity(N, [a, b], w) + 1e-3 * np.cos(0.7 * np.arange(N))
              for a, b in zip(xr, xl)]
    found = fkme.find_kinks(np.array(frames), threshold=0.3)
    # the parabola through 3 samples of sech^2 has a vertex bias
    # ~ (2/3) delta (1 - 5 delta^2)/w^2 (quartic term; delta the sub-site
    # offset) <= 0.13/w^2 sites; allow 0.3/w^2 for the higher orders, the
    # ripple (shift ~ 0.7e-3 w^2/2) and the other kink's tail (~4 e^-12)
    tol = 0.3 / w ** 2
    for xs, a, b in zip(found, xr, xl):
        assert len(xs) == 2
        err = np.sort([min(fkme.periodic_distance(x, a, N), fkme.periodic_distance(x, b, N))
                       for x in xs])
        assert err[-1] < tol
    tracks = fkme.track_kinks(t, found, N, max_jump=2.0)
    assert len(tracks) == 2 and all(len(tt) == nfr for tt, _ in tracks)
    v = sorted(fkme.kink_velocity(tt, x, N) for tt, x in tracks)
    # least-squares slope with errors bounded by tol: |dv| <= 3 tol/duration
    bound = 3 * tol / (t[-1] - t[0])
    assert abs(v[0] - vl) < bound and abs(v[1] - vr) < bound
    # a single kink moving left through n = 0
    xs = np.mod(5.0 - 0.4 * t, N)
    fr = [fkme.find_kinks(sech2_velocity(N, [x], w), 0.3) for x in xs]
    (tt, x), = fkme.track_kinks(t, fr, N)
    assert np.ptp(x) > 50                      # it did wrap
    assert fkme.kink_velocity(tt, x, N) == pytest.approx(-0.4, abs=bound)
    np.testing.assert_allclose(fkme.unwrap_positions(x, N)[-1] - x[0], -0.4 * t[-1], atol=tol)


def test_find_kinks_threshold_and_separation():
    v = np.zeros(20)
    v[[3, 4, 5]] = [0.5, 1.0, 0.5]             # symmetric: exact centre 4
    v[[11, 12, 13]] = [0.2, 0.1, 0.05]         # a maximum at 11 with v = 0.2:
    x11 = 11 + 0.5 * (0.0 - 0.1) / (0.0 - 2 * 0.2 + 0.1)     # vertex 11 + 1/6
    v[[15]] = 0.9
    assert list(fkme.find_kinks(v, 0.05)) == pytest.approx([4.0, x11, 15.0])
    assert list(fkme.find_kinks(v, 0.3)) == pytest.approx([4.0, 15.0])
    assert list(fkme.find_kinks(v, 0.05, min_separation=5.0)) == pytest.approx([4.0, 15.0])
    v2 = np.zeros(10)
    v2[[9, 0, 1]] = [0.5, 1.0, 0.7]            # maximum at 0, wrapped neighbour
    x, = fkme.find_kinks(v2)
    assert x == pytest.approx(0.5 * (0.5 - 0.7) / (0.5 - 2.0 + 0.7))


def test_vk_curve_from_mean_and_background():
    vb = -2e-4
    vbar = fkme.background_velocity(vb, KC, K)
    assert vbar == pytest.approx(vb * 0.07 / 1.07)
    N, nk, jump = 3000, 2, fkme.kink_jump(KC, UC, K)
    f = np.linspace(0.9, 0.7, 401)
    vk = fkme.vk_overdamped(f, 25.0, **P)
    mean = vbar + nk * vk * jump / N           # d/dt sum u = N vbar + n_k v_k jump
    ff, vv = fkme.vk_curve_from_mean(f, mean, N, nk, vbar, jump)
    np.testing.assert_allclose(vv, vk, rtol=1e-12)
    fb, vbin = fkme.vk_curve_from_mean(f, mean, N, nk, vbar, jump, nbins=10)
    assert len(fb) == 10 and np.all(np.diff(fb) > 0)
    np.testing.assert_allclose(vbin, fkme.vk_overdamped(fb, 25.0, **P), rtol=1e-3)


def test_spacetime_map_and_plot():
    snap_t = np.arange(5) * 0.5
    snaps = np.arange(5 * 7, dtype=float).reshape(5, 7)
    arr, extent = fkme.spacetime_map(snap_t, snaps)
    assert arr.shape == (7, 5) and arr[3, 2] == snaps[2, 3]
    assert extent == (0.0, 2.0, -0.5, 6.5)
    fig = fkme.plot_spacetime(snap_t, snaps, kinks=[(snap_t, np.ones(5))], title="x")
    ax = fig.axes[0]
    assert ax.images[0].get_array().shape == (7, 5)


def test_simulate_snapshots_and_time_series():
    N, f = 60, 0.9
    r = fkme.simulate(N, 5.0, f0=f, u0=fkme.seeded_chain(N, f, KC, UC, K, 10), dt=1.0,
                      t_end=100.0, every=5, snap_every=20, **P)
    assert r.snap_u.shape == (6, N) and r.snap_udot.shape == (6, N)
    assert len(r.t) == len(r.f) == len(r.vmean) == len(r.kinks) == 21
    np.testing.assert_allclose(r.f, f)
    # mean velocity = mean of the snapshot velocities at common times
    i = np.searchsorted(r.t, r.snap_t)
    np.testing.assert_allclose(r.vmean[i], r.snap_udot.mean(axis=1), rtol=1e-12)
    assert np.all([len(k) == 2 for k in r.kinks[2:]])
    # crossings come in mirror pairs around the seed (symmetric start)
    c = r.crossings
    assert len(c) > 4 and len(c) % 2 == 0
    np.testing.assert_allclose(c[0::2, 0], c[1::2, 0], rtol=1e-12)
    np.testing.assert_array_equal(c[0::2, 1] + c[1::2, 1], 2 * (N // 2) - 1)


# ----------------------------------------------------------------- readers

DUMP = """ITEM: TIMESTEP
0
ITEM: NUMBER OF ATOMS
3
ITEM: BOX BOUNDS pp pp pp
0.0 3.0
-0.5 0.5
-0.5 0.5
ITEM: ATOMS id type x vx
3 1 2.0 0.3
1 1 0.0 0.1
2 1 1.0 0.2
ITEM: TIMESTEP
100
ITEM: NUMBER OF ATOMS
3
ITEM: BOX BOUNDS pp pp pp
0.0 3.0
-0.5 0.5
-0.5 0.5
ITEM: ATOMS id type x vx
2 1 1.5 0.25
3 1 2.5 0.35
1 1 0.5 0.15
"""


def test_read_dump(tmp_path):
    p = tmp_path / "dump.fk"
    p.write_text(DUMP)
    steps, d = fkme.read_dump(p)
    assert list(steps) == [0, 100]
    assert d["id"].tolist() == [[1, 2, 3], [1, 2, 3]]
    np.testing.assert_array_equal(d["x"], [[0.0, 1.0, 2.0], [0.5, 1.5, 2.5]])
    np.testing.assert_array_equal(d["vx"], [[0.1, 0.2, 0.3], [0.15, 0.25, 0.35]])
    assert d["box"].shape == (2, 3, 2) and d["box"][1, 0, 1] == 3.0
    steps, d = fkme.read_dump(p, columns=["vx"])
    assert set(d) == {"id", "vx", "box"}


LOG = """LAMMPS (2 Aug 2023)
units lj
thermo 100
Per MPI rank memory allocation (min/avg/max) = 3.1 | 3.1 | 3.1 Mbytes
   Step          Temp          v_f     
         0   0              0.5          
       100   1.5e-3         0.6          
WARNING: Something happened (src/foo.cpp:12)
       200   2.5e-3         0.7          
Loop time of 0.01 on 1 procs for 200 steps with 10 atoms

Step Temp v_f
       200   2.5e-3         0.7          
       300   3.5e-3         0.8          
Loop time of 0.01 on 1 procs for 100 steps with 10 atoms
run 100
   Step          Temp          v_f     
       300   3.5e-3         0.8          
       400   4.5e-3         0.9          
"""


def test_read_log(tmp_path):
    p = tmp_path / "log.lammps"
    p.write_text(LOG)
    blocks = fkme.read_log_blocks(p)
    assert len(blocks) == 3                    # the last one truncated (no Loop time)
    assert blocks[0]["Step"].tolist() == [0, 100, 200]
    assert blocks[2]["v_f"].tolist() == [0.8, 0.9]
    d = fkme.read_log(p)
    assert d["Step"].tolist() == [0, 100, 200, 200, 300, 300, 400]
    assert d["Temp"][1] == 1.5e-3
    assert fkme.read_log(p, block=1)["Step"].tolist() == [200, 300]
    q = tmp_path / "log2"
    q.write_text(LOG.replace("Step Temp v_f", "Step v_f"))
    with pytest.raises(ValueError):
        fkme.read_log(q)


def test_read_ave_time(tmp_path):
    p = tmp_path / "ave.txt"
    p.write_text("# Time-averaged data for fix a\n# TimeStep v_f c_vm\n"
                 "100 0.5 1e-3\n200 0.6 2e-3\n")
    d = fkme.read_ave_time(p)
    assert d["TimeStep"].tolist() == [100, 200] and d["c_vm"].tolist() == [1e-3, 2e-3]
    q = tmp_path / "prof.txt"
    q.write_text("# Time-averaged data for fix p\n# TimeStep Number-of-rows\n"
                 "# Row c_v[1] c_v[2]\n100 2\n1 0.1 0.2\n2 0.3 0.4\n"
                 "200 2\n1 1.1 1.2\n2 1.3 1.4\n")
    d = fkme.read_ave_time(q)
    assert d["TimeStep"].tolist() == [100, 200]
    assert d["c_v[2]"].shape == (2, 2) and d["c_v[2]"][1].tolist() == [1.2, 1.4]
    assert d["Row"][0].tolist() == [1, 2]
