"""Physics of fix eq/contacts with a rigid slider against the master
equation (ME) and the exact renewal solution (paper Sec. II, IV).

Statistics: the contacts are independent, so F_EQ(X)/(N k_c) is a mean of
N iid stretches; z = (F_EQ - F_ME)/(sd(X)/sqrt(N)) is standard normal at
each X, with sd(X) the one-contact spread from the ME.  A bound |z| < 5
over the 800 (correlated) sample points has a false-alarm probability below
800 * 5.7e-7 = 5e-4 even if they were independent (Bonferroni).
"""
import math
from pathlib import Path

import numpy as np
import pytest

import eqtools

ROOT = Path(__file__).resolve().parents[2]
RIGID = ROOT / "examples" / "eq-rigid" / "in.eq-rigid"
ZMAX = 5.0


def eq_run(tmp, nx=60, ny=34, seed=4711, dX=0.01, Xmax=8.0, contacts=None, move="1.0 0.0 0.0",
           nprocs=1):
    """Rigid-slider EQ run to Xmax; returns (X, F/(N k_c), breaks, attached, N)."""
    tmp.mkdir(parents=True, exist_ok=True)
    v = {"nx": nx, "ny": ny, "seed": seed, "dX": dX, "Xmax": Xmax, "Xsteady": Xmax, "out": tmp,
         "move": move}
    if contacts:
        v["contacts"] = contacts
    eqtools.run_lammps(RIGID, v, nprocs=nprocs, cwd=tmp)
    d = eqtools.load(tmp / "F.dat")
    return d[:, 1], d[:, 2], d[:, 3], d[:, 4], 2 * nx * ny


def me_run(tmp, args, dx=1e-3, Xmax=8.0):
    """ME solution on X = k dx: columns X F sd Gamma attached."""
    tmp.mkdir(parents=True, exist_ok=True)
    s = eqtools.run_eqme(list(args) + ["xmax", Xmax, "dx", dx, "force", "me.dat"], cwd=tmp)
    return eqtools.load(tmp / "me.dat"), s


def at(me, X, dx=1e-3):
    return me[np.rint(X / dx).astype(int)]


def test_flagship_agrees_with_master_equation(tmp_path):
    from conftest import load_example
    r = load_example("eq-rigid").run(out=tmp_path, plot=False, quiet=True)
    assert r["N"] == 4080
    assert r["me_exact"] < 1e-6              # ME (dx = 1e-3) vs exact renewal
    assert r["max_z"] < ZMAX                 # F(X) within its statistical error
    assert r["p"] > 1e-4                     # Q_s(x) histogram, chi^2
    assert abs(r["kinetic"] - 0.5104166666666667) < 1e-12    # <x_s^2>/(2<x_s>)
    assert abs(r["kstar"] - 1.5) < 2e-3      # K*/K_s, exact 1.5 (kink at X = 1.25)


def test_large_N_flagship(tmp_path):
    """The large-N variant (N = 261120: 8 times smaller statistical error)
    with slider step 0.05, which exact crossing allows without any step
    error.  At this N the chi^2 test of Q_s(x) resolves errors of 1% of a
    bin's expectation."""
    from conftest import load_example
    r = load_example("eq-rigid").run(out=tmp_path, scale=8, dX=0.05, plot=False, quiet=True)
    assert r["N"] == 261120
    assert r["max_z"] < ZMAX
    assert r["p"] > 1e-4


def test_exact_crossing_is_independent_of_the_slider_step(tmp_path):
    """Breaks are resolved at the threshold crossing, so F(X) at a given X
    does not depend on the step: same break sequence, F equal to rounding."""
    X1, F1, _, _, _ = eq_run(tmp_path / "a", nx=30, ny=17, dX=0.01)
    X5, F5, _, _, _ = eq_run(tmp_path / "b", nx=30, ny=17, dX=0.05)
    np.testing.assert_allclose(X1[::5], X5, atol=1e-12)
    assert np.max(np.abs(F1[::5] - F5)) < 1e-12


def test_deviation_shrinks_as_inverse_sqrt_N(tmp_path):
    """Mean squared deviation D^2 = <(F_EQ - F_ME)^2>_X over independent
    seeds: E[D^2] = <sd^2>_X / N exactly.  Fit log D^2 = a - s log N; the
    tolerance on s (and on the normalization) is t * SE from the scatter of
    the replicas themselves (Student t, p = 1e-3)."""
    me, _ = me_run(tmp_path / "me", ["threshold", "uniform", 0.75, 1.25])
    sizes = [(15, 17), (30, 34), (60, 68)]    # N = 510, 2040, 8160
    seeds = range(101, 109)
    logN, logD2, ratio = [], [], []
    for nx, ny in sizes:
        for seed in seeds:
            X, F, _, _, N = eq_run(tmp_path / f"n{nx}s{seed}", nx=nx, ny=ny, seed=seed)
            m = at(me, X)
            d2 = np.mean((F - m[:, 1]) ** 2)
            logN.append(math.log(N))
            logD2.append(math.log(d2))
            ratio.append(N * d2 / np.mean(m[:, 2] ** 2))
    from scipy import stats
    A = np.vstack([np.ones(len(logN)), logN]).T
    coef, res, _, _ = np.linalg.lstsq(A, np.array(logD2), rcond=None)
    dof = len(logN) - 2
    s2 = float(res[0]) / dof
    se_slope = math.sqrt(s2 * np.linalg.inv(A.T @ A)[1, 1])
    t = stats.t.ppf(1 - 0.5e-3, dof)        # two-sided p = 1e-3: 3.79 for 22 dof
    assert abs(coef[1] + 1.0) < t * se_slope, (coef[1], se_slope)
    r = np.array(ratio)
    t = stats.t.ppf(1 - 0.5e-3, len(r) - 1)  # 3.77 for 23 dof
    assert abs(r.mean() - 1.0) < t * r.std(ddof=1) / math.sqrt(len(r)), r


def test_step_crossing_is_first_order_and_matches_its_discrete_master_equation(tmp_path):
    """crossing step (cellular automaton): a contact re-forms at the end of
    the step.  eq-me ... crossing step solves that discrete model exactly;
    its distance to the continuous ME is first order in the step."""
    thr = ["threshold", "uniform", 0.75, 1.25]
    ex, _ = me_run(tmp_path / "ex", thr, dx=0.01)
    dev = []
    for dX in (0.04, 0.02, 0.01):
        st, _ = me_run(tmp_path / f"st{dX}", thr + ["crossing", "step"], dx=dX)
        k = np.rint(st[:, 0] / 0.01).astype(int)
        dev.append(np.max(np.abs(st[:, 1] - ex[k, 1])))
    assert 1.7 < dev[0] / dev[1] < 2.3 and 1.7 < dev[1] / dev[2] < 2.3, dev
    # the EQ model in step mode agrees with the discrete ME ...
    st, _ = me_run(tmp_path / "st", thr + ["crossing", "step"], dx=0.04)
    X, F, _, _, N = eq_run(tmp_path / "eq", nx=120, ny=68, dX=0.04,
                           contacts="threshold uniform 0.75 1.25 crossing step")
    a = at(st, X, 0.04)
    z = eqtools.zscores(F, a[:, 1], a[:, 2], N, a[:, 5])
    assert np.max(np.abs(z)) < ZMAX
    # ... and its first-order error is resolved at this N: the test has power
    b = at(ex, X, 0.01)
    zc = eqtools.zscores(F, b[:, 1], b[:, 2], N, b[:, 5])
    assert np.max(np.abs(zc)) > 2 * ZMAX


def test_mirror_symmetry_and_sliding_direction(tmp_path):
    """Sliding along -x mirrors F(X); sliding along y (dir y) equals x."""
    base = "threshold uniform 0.75 1.25 reform delta 0.1"
    _, Fp, bp, _, _ = eq_run(tmp_path / "p", nx=30, ny=17, Xmax=4.0, contacts=base)
    _, Fm, bm, _, _ = eq_run(tmp_path / "m", nx=30, ny=17, Xmax=4.0, contacts=base,
                              move="-1.0 0.0 0.0")
    _, Fy, by, _, _ = eq_run(tmp_path / "y", nx=30, ny=17, Xmax=4.0, contacts=base + " dir y",
                              move="0.0 1.0 0.0")
    assert np.max(np.abs(Fp + Fm)) < 1e-12 and np.array_equal(bp, bm)
    assert np.max(np.abs(Fp - Fy)) < 1e-12 and np.array_equal(bp, by)


def test_contacts_that_never_reform_debond_with_the_threshold_survival(tmp_path):
    """reform none: attached fraction = J_c(X) (binomial), F = X J_c(X)."""
    X, F, _, att, N = eq_run(tmp_path / "eq", nx=60, ny=34, Xmax=2.0,
                             contacts="threshold realistic 1.0 reform none")
    J = (1 + X ** 2) * np.exp(-X ** 2)
    sd = np.sqrt(J * (1 - J))
    skew = np.where(sd > 0, (1 - 2 * J) / np.where(sd > 0, sd, 1), 0)    # Bernoulli
    assert np.max(np.abs(eqtools.zscores(att / N, J, sd, N, skew))) < ZMAX
    me, _ = me_run(tmp_path / "me", ["threshold", "realistic", 1.0, "reform", "none"], Xmax=2.0)
    assert np.max(np.abs(at(me, X)[:, 1] - X * J)) < 1e-12
    m = at(me, X)
    assert np.max(np.abs(eqtools.zscores(F, X * J, m[:, 2], N, m[:, 5]))) < ZMAX


@pytest.mark.parametrize("contacts,me_args,kmoments", [
    # smeared re-forming overlapping the thresholds, started from R, per-contact stiffness
    ("threshold gaussian 1.0 0.2 reform gaussian 0.1 0.05 start reform stiffness uniform 0.5 1.5",
     ["threshold", "gaussian", 1.0, 0.2, "reform", "gaussian", 0.1, 0.05, "start", "reform"],
     (1.0, 13.0 / 12.0)),
    # tabulated bimodal thresholds, uniform re-forming
    ("threshold table {root}/potentials/eq_thresholds.table BIMODAL reform uniform 0.0 0.1",
     ["threshold", "table", "{root}/potentials/eq_thresholds.table", "BIMODAL",
      "reform", "uniform", 0.0, 0.1], (1.0, 1.0)),
])
def test_general_distributions_follow_the_master_equation(tmp_path, contacts, me_args, kmoments):
    """F/(N k_c) = <k>/k_c <x>_ME; the per-contact variance of k x is
    <k^2><x^2> - <k>^2<x>^2 (stiffness drawn independently of the stretch)."""
    root = str(ROOT)
    me, _ = me_run(tmp_path / "me", [str(a).format(root=root) for a in me_args])
    X, F, _, _, N = eq_run(tmp_path / "eq", nx=90, ny=51, contacts=contacts.format(root=root))
    m = at(me, X)
    k1, k2 = kmoments
    mean = k1 * m[:, 1]
    sd = np.sqrt(np.maximum(k2 * (m[:, 2] ** 2 + m[:, 1] ** 2) - mean ** 2, 0))
    assert np.max(np.abs(eqtools.zscores(F, mean, sd, N, m[:, 5]))) < ZMAX


@pytest.mark.parametrize("contacts,me_args", [
    # re-formed behind the anchor: held until the stretch reaches |r|
    ("threshold uniform 0.0 1.0 reform delta -0.5",
     ["threshold", "uniform", 0.0, 1.0, "reform", "delta", -0.5]),
    # the paper's untruncated Gaussian R(x) reaching below zero
    ("threshold gaussian 0.5 0.25 reform gaussian 0.0 0.2",
     ["threshold", "gaussian", 0.5, 0.25, "reform", "gaussian", 0.0, 0.2]),
])
def test_negative_reform_stretches_follow_the_master_equation(tmp_path, contacts, me_args):
    """A contact re-formed with r < 0 draws its threshold above |r| and so
    cannot break before its stretch reaches |r|; the ME solver holds such
    contacts the same way."""
    me, s = me_run(tmp_path / "me", me_args, Xmax=8.0)
    X, F, _, _, N = eq_run(tmp_path / "eq", nx=90, ny=51, contacts=contacts)
    m = at(me, X)
    assert np.max(np.abs(eqtools.zscores(F, m[:, 1], m[:, 2], N, m[:, 5]))) < ZMAX


def test_sliding_further_than_the_image_counter_reaches(tmp_path):
    """LAMMPS counts periodic images in 10 bits (+-512 box lengths); the fix
    undoes the wrap-around of the counter: sliding 1100 box lengths in a
    box of width 2 gives the same contacts as in a box 600 times wider."""
    def run(sub, width):
        d = tmp_path / sub
        d.mkdir()
        inp = d / "in.long"
        inp.write_text(f"""
units lj
dimension 2
atom_style atomic
boundary p p p
region box block 0 {width} 0 2 -0.5 0.5
create_box 1 box
region seed block 0 1.5 0 2 -0.5 0.5
lattice sq 1.0
create_atoms 1 region seed
mass 1 1.0
atom_modify sort 0 0.0
comm_modify cutoff 0.5
neighbor 0.5 bin
neigh_modify every 1 delay 0 check no
fix c all eq/contacts 1.0 3 threshold uniform 0.75 1.25
fix m all move linear 1.0 0.0 0.0 units box
timestep 0.5
thermo_style custom step f_c[1] f_c[3]
thermo_modify norm no format float %.15g
thermo 1100
run 4400
""")
        log = eqtools.run_lammps(inp, cwd=d)
        assert "Created 4 atoms" in log
        return [l.split() for l in log.splitlines() if l.split()[:1] == ["4400"]][-1]
    small, wide = run("small", 2), run("wide", 1200)
    assert small[2] == wide[2]                              # the same number of breaks
    assert abs(float(small[1]) - float(wide[1])) < 1e-9    # F equal to rounding
