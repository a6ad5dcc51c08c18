"""fix eq/contacts at T > 0, with aging and delays (issue 23; spec
shared/notes/thermal-aging.md), against the independent reference
eqtools.thermal (written apart from the C++ code: renewal quadrature of the
continuous model, and the exact expectation of the discrete rule).

Statistics: the contacts are independent.
- Transient (crossing step): F_EQ(X_j) is a mean of N iid per-contact
  stretches whose mean F and second moment F2 the lattice renewal equation
  gives exactly, so z = (F_EQ - F)/sqrt((F2 - F^2)/N) is standard normal
  at each X_j; |z| < 5 over the ~2000 (correlated) points has a false-alarm
  probability below 2000 * 5.7e-7 = 1.1e-3 (Bonferroni).  Where the
  expected number of breaks is small (the first thermal breaks: 0.015
  expected at one point) F_EQ is not normal: a single break moves it by up
  to x_max/N, z = 1/sqrt(0.015) = 8.  So the bound is 5 sd plus RARE = 3
  contacts' worth of stretch (x_max = 2 bounds every stretch here, aging
  included): k unexpected breaks with k > 3 where 0.015 are expected have
  probability 2e-9, and in the bulk (sd ~ 2.5e-3) the extra 6e-4 is a
  quarter of one sd.
- Steady state (crossing exact): each contact's stretch averaged over the
  second half of the run is independent between contacts; their mean has
  the standard error sd/sqrt(N) from the N values themselves.  The run
  starts from fresh contacts, so the window must begin after the
  transient: the reference's transient says how far it has decayed (the
  bound below).
"""
import math
from pathlib import Path

import numpy as np
import pytest

import eqtools
from eqtools import thermal as ref

ROOT = Path(__file__).resolve().parents[2]
INPUT = ROOT / "examples" / "eq-thermal" / "in.eq-thermal"
STATE = ROOT / "unittest" / "python" / "inputs" / "in.contacts-state"
ZMAX = 5.0
RARE, X_MAX = 3, 2.0    # breaks beyond the normal law where few are expected; largest stretch


def run(tmp, contacts, v, dX=2e-3, Xhalf=2.0, n=100, nprocs=1, seed=4711):
    tmp.mkdir(parents=True, exist_ok=True)
    log = eqtools.run_lammps(INPUT, {"n": n, "v": v, "dX": dX, "Xhalf": Xhalf, "seed": seed,
                                     "contacts": contacts, "out": tmp}, nprocs=nprocs, cwd=tmp)
    d = eqtools.load(tmp / "F.dat")
    return d[:, 1], d[:, 2], log


def contact_means(tmp):
    rows = (tmp / "avg.dump").read_text().split("ITEM: ATOMS")[-1].strip().splitlines()[1:]
    return np.array([float(r.split()[1]) for r in rows])


def keywords(p):
    """fix eq/contacts keywords for reference parameters p (eps_a = omega = 1, k_B = 1)."""
    kind = p.thresholds[0]
    th = {"uniform": "uniform {} {}", "gaussian": "gaussian {} {}", "delta": "delta {}"}[kind]
    kw = ["threshold " + th.format(*p.thresholds[1:])]
    if p.theta > 0:
        kw.append(f"thermal {p.theta} 1.0 1.0 barrier {p.p} {p.q}")
    if p.aging:
        kw.append(f"aging {p.aging} {p.beta} {p.tau_a}")
    if p.delay:
        kw.append(f"delay {p.delay} {p.tau}")
    return " ".join(kw)


# the rows of the note's table (d) and further cases
CASES = {
    "thermal": dict(theta=0.02),
    "thermal-hot-barrier": dict(theta=0.05, p=2.0, q=0.25),
    "gaussian": dict(theta=0.02, thresholds=("gaussian", 1.0, 0.1)),
    "aging": dict(aging="log", beta=0.05, tau_a=1.0),
    "aging-exp-fixed-delay": dict(theta=0.02, aging="exp", beta=0.1, tau_a=100.0, delay="fixed",
                                  tau=30.0),
    "combined": dict(theta=0.02, aging="log", beta=0.05, tau_a=1.0, delay="exp", tau=10.0),
}


def test_the_new_keywords_off_change_nothing(tmp_path):
    """Check (f) 1: T = 0 gives today's fix; a thermal layout without any
    physics in it (rest only, T = 0, no aging) gives today's numbers."""
    base = "threshold uniform 0.75 1.25"
    X0, F0, _ = run(tmp_path / "plain", base, v=1.0, dX=0.01, n=40)
    X1, F1, _ = run(tmp_path / "T0", base + " thermal 0.0 1.0 1.0", v=1.0, dX=0.01, n=40)
    X2, F2, _ = run(tmp_path / "rest", base + " rest 5.0", v=1.0, dX=0.01, n=40)
    assert np.array_equal(F0, F1)
    assert np.max(np.abs(F2 - F0)) < 1e-12
    d0, d2 = eqtools.load(tmp_path / "plain" / "F.dat"), eqtools.load(tmp_path / "rest" / "F.dat")
    assert np.array_equal(d0[:, 3], d2[:, 3])    # breaks per step
    assert d0[:, 3].sum() > 3000
    assert abs(F0[len(F0) // 2:].mean() - 0.5104166667) < 0.01


@pytest.mark.parametrize("case,v", [("thermal", 1e-4), ("thermal-hot-barrier", 1e-2),
                                    ("gaussian", 1e-2), ("aging", 1e-2),
                                    ("aging-exp-fixed-delay", 1e-1), ("combined", 1e-4)])
def test_transient_follows_the_discrete_rule(tmp_path, case, v):
    """crossing step: F(X) from fresh contacts against the exact expectation
    of the discrete rule (lattice renewal equation), at every step."""
    p = ref.make_params(**CASES[case])
    dX = 2e-3
    X, F, _ = run(tmp_path, keywords(p) + " crossing step", v=v, dX=dX, Xhalf=2.0)
    N = 100 * 100
    Xr, Fr, F2r = ref.discrete_transient_force(v, dX, len(F) - 1, p)
    assert np.allclose(X, Xr)
    # before the first breaks every contact has the same stretch: the
    # spread is 0 and only rounding (x - anchor) is left
    sd = np.sqrt(np.maximum(F2r - Fr ** 2, 0.0) / N) + 1e-12 * (1.0 + Fr)
    z = (F - Fr)[1:] / sd[1:]
    bound = ZMAX * sd[1:] + RARE * X_MAX / N
    worst = np.argmax(np.abs(F - Fr)[1:] / bound)
    assert np.all(np.abs(F - Fr)[1:] < bound), (case, worst, z[worst], (F - Fr)[1 + worst])
    # the curve is not trivially matched: it rises and has broken contacts
    assert Fr.max() > 0.2


def test_static_friction_grows_with_the_rest_time(tmp_path):
    """Check (f) 7 and the note's peaks after a rest t_w (T = 0, log aging
    beta = 0.05, tau_a = 1, v = 1e-2, dX = 2e-3): the peak of F(X) against
    the discrete rule's, and about linear in ln t_w."""
    p = ref.make_params(aging="log", beta=0.05, tau_a=1.0)
    peaks = []
    for tw in (0.0, 1e2, 1e4, 1e6):
        X, F, _ = run(tmp_path / f"tw{tw:g}", keywords(p) + f" rest {tw} crossing step", v=1e-2,
                      Xhalf=1.0)
        Xr, Fr, F2r = ref.discrete_transient_force(1e-2, 2e-3, len(F) - 1, p, t_w=tw)
        k = np.argmax(Fr)
        sd = math.sqrt(max(F2r[k] - Fr[k] ** 2, 0.0) / 1e4) + 1e-12
        assert abs(F[k] - Fr[k]) < ZMAX * sd
        peaks.append(F.max())
    assert all(b > a for a, b in zip(peaks, peaks[1:]))
    # the note's values (3 digits)
    assert np.allclose(peaks, [0.920, 0.948, 1.096, 1.268], atol=0.01)


@pytest.mark.parametrize("case,v", [("thermal", 1e-6), ("thermal", 1e-4), ("thermal", 1e-2),
                                    ("gaussian", 1e-4), ("aging", 1e-4), ("combined", 1e-4)])
def test_steady_friction_matches_the_quadrature(tmp_path, case, v):
    """Check (f) 3 with crossing exact (no step error to extrapolate):
    N = 20164 contacts, the mean of the per-contact time averages over
    X in [4, 8] against the renewal quadrature of the continuous model."""
    p = ref.make_params(**CASES[case])
    X, F, _ = run(tmp_path, keywords(p) + " crossing exact", v=v, dX=2e-3, Xhalf=4.0, n=142)
    means = contact_means(tmp_path)
    assert len(means) == 142 * 142
    Fk = ref.steady_force(v, p)
    se = means.std(ddof=1) / math.sqrt(len(means))
    # what is left of the transient in the window: from the discrete rule's
    # renewal equation at the same step (its remainder differs from that
    # of crossing exact by a shift of about dX/2 in X: a bound 10 dX |left|
    # for decay lengths >= 0.1)
    Xr, Fr, _ = ref.discrete_transient_force(v, 2e-3, len(F) - 1, p)
    left = Fr[len(Fr) // 2 + 1:].mean() - ref.discrete_steady_force(v, 2e-3, p)
    err = means.mean() - (Fk + left)
    assert abs(err) < 4.0 * se + 10 * 2e-3 * abs(left), (means.mean(), Fk, left, se)
    # the thermal, aging and delay terms matter here: far from T = 0
    assert abs(Fk - 0.5104166667) > 20 * se


@pytest.mark.parametrize("grid", [(1, "* * *"), (4, "4 1 1"), (4, "2 2 1")])
def test_any_processor_grid_and_restart_give_the_same_contacts(tmp_path, grid):
    """Counter-keyed budgets and delays, ages and budgets in the per-atom
    state: the contacts (stretch, threshold, breaks, anchor) on 1 and 4
    ranks, and after a restart file read on that grid, are those of the
    uninterrupted 1-rank run, to the last bit (the contacts of
    test_reliability_ranks, IDs from a data file)."""
    from test_reliability_ranks import CONTACTS, data_file
    extra = "reform uniform 0.0 0.2 thermal 0.2 1.0 1.0 aging exp 0.1 2.0 delay exp 0.05 rest 1"
    base = dict(kappa=0.0, drive="move", dX=0.01, steps=400, half=250, every=50, extra=extra,
                out=tmp_path, data=data_file("contacts", tmp_path))
    eqtools.run_lammps(CONTACTS, dict(base, tag="ref", wrestart=1), cwd=tmp_path)
    n, g = grid
    eqtools.run_lammps(CONTACTS, dict(base, tag="grid", grid=g), nprocs=n, cwd=tmp_path)
    eqtools.run_lammps(CONTACTS, dict(base, tag="read", grid=g, mode="read"), nprocs=n,
                       cwd=tmp_path)

    def frames(tag):
        text = (tmp_path / f"dump.{tag}").read_text()
        return {int(f.split("ITEM: NUMBER")[0].split()[0]): f.split("ITEM: ATOMS")[1]
                for f in text.split("ITEM: TIMESTEP")[1:]}

    def cols(frame):    # id xu stretch threshold breaks stiffness anchor field
        rows = [l.split() for l in frame.strip().splitlines()[1:]]
        return [[r[0], r[3]] + r[7:] for r in rows]

    ref, other, read = frames("ref"), frames("grid"), frames("read")
    assert sorted(ref) == sorted(other) and max(read) == 400
    for step in ref:
        assert cols(ref[step]) == cols(other[step]), step
    for step in read:
        assert cols(ref[step]) == cols(read[step]), step
    breaks = [float(r[4]) for r in cols(ref[400])]
    assert min(breaks) >= 1 and sum(breaks) > 2 * len(breaks)


@pytest.mark.parametrize("units,boltz", [("lj", 1.0), ("real", 0.0019872067)])
def test_eq_me_command_with_the_thermal_terms(tmp_path, units, boltz):
    """The eq/me command (theta = k_B T / eps_a with LAMMPS' k_B of the
    units) against the independent quadrature: theta = 0.02, v = 1e-4, and
    the note's combined row (aging, exponential delay)."""
    T = 300.0 if units == "real" else 0.02
    eps = boltz * T / 0.02
    inp = tmp_path / "in.me"
    inp.write_text(f"""units {units}
eq/me threshold uniform 0.75 1.25 thermal {T} {eps!r} 1.0 velocity 1e-4 xmax 2.0 dx 0.002
print "A ${{eq_me_kinetic_force}} ${{eq_me_kinetic_slope}} ${{eq_me_static_peak}}"
eq/me threshold uniform 0.75 1.25 thermal {T} {eps!r} 1.0 aging log 0.05 1.0 delay exp 10.0 &
      velocity 1e-4 xmax 2.0 dx 0.002
print "B ${{eq_me_kinetic_force}}"
""")
    log = eqtools.run_lammps(inp, {}, cwd=tmp_path)
    a = [float(v) for v in next(l for l in log.splitlines() if l.startswith("A ")).split()[1:]]
    b = float(next(l for l in log.splitlines() if l.startswith("B ")).split()[1])
    p = ref.make_params(theta=0.02)
    assert abs(a[0] - ref.steady_force(1e-4, p)) < 1e-7
    # the slope against a centred difference of the reference (ln v +- 0.05)
    h = 0.05
    slope = (ref.steady_force(1e-4 * math.exp(h), p) - ref.steady_force(1e-4 * math.exp(-h), p)) / (2 * h)
    assert abs(a[1] - slope) < 1e-4
    # the static peak against the exact expectation of the discrete rule
    # (which lowers F by about (dX/2) x the broken fraction, < 1e-4 here)
    X, F, _ = ref.discrete_transient_force(1e-4, 2e-3, 1000, p)
    assert abs(a[2] - F.max()) < 1e-4
    pc = ref.make_params(theta=0.02, aging="log", beta=0.05, tau_a=1.0, delay="exp", tau=10.0)
    assert abs(b - ref.steady_force(1e-4, pc)) < 1e-7


DETACH = """
units lj
dimension 2
atom_style atomic
boundary p p p
lattice hex 1.1547005383792515
region box block 0 10 0 20 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
atom_modify sort 0 0.0
comm_modify cutoff 0.5
fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25 reform none thermal 0.1 1.0 1.0
fix slide all move linear 0.005 0.0 0.0 units box
timestep 0.2
thermo_style custom step f_c[1] f_c[3] f_c[4]
thermo_modify format float %.17g norm no
thermo 50
"""


def test_detached_contacts_stay_detached_through_runs_and_restarts(tmp_path):
    """reform none at T > 0: a contact breaks (thermally or at its
    threshold) once and stays detached; its row keeps no rate bound, so
    that the loop's common step, which tests only the bound at T > 0, never
    takes it for attached.  The attached count only falls, each break
    detaches one contact (breaks + attached = N), detached contacts carry
    no force, and runs split with 'pre no' and by a restart file give the
    uninterrupted run's numbers to the last bit (fix move: positions
    x0 + v t, independent of when LAMMPS re-wraps them)."""
    def go(tag, body):
        d = tmp_path / tag
        d.mkdir()
        (d / "in.detach").write_text(DETACH + body)
        log = eqtools.run_lammps(d / "in.detach", cwd=d)
        rows = {}
        for line in log.splitlines():
            f = line.split()
            if len(f) == 4 and f[0].isdigit():
                rows[int(f[0])] = f[1:]
        return rows, d

    dump = "dump d all custom 600 dump.final id f_c[2] f_c[3]\ndump_modify d sort id\n"
    ref, dref = go("ref", dump + "run 600\n")
    after = ("fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25 reform none "
             "thermal 0.1 1.0 1.0\nfix slide all move linear 0.005 0.0 0.0 units box\n"
             "thermo_style custom step f_c[1] f_c[3] f_c[4]\nthermo_modify format float %.17g norm no\n"
             "thermo 50\n")
    split, dsplit = go("split", "run 200\nrun 200 pre no\nwrite_restart detach.rst\nclear\n"
                       "read_restart detach.rst\natom_modify sort 0 0.0\n" + after + dump + "run 200\n")
    n = 2 * 10 * 20
    steps = sorted(ref)
    attached = [float(ref[s][2]) for s in steps]
    breaks = [float(ref[s][1]) for s in steps]
    assert all(b <= a for a, b in zip(attached, attached[1:])), attached
    assert all(a + b == n for a, b in zip(attached, breaks)), (attached, breaks)
    assert 0.2 * n < breaks[-1] < n    # many detached, some still attached
    assert max(split) == 600
    for s in split:
        assert split[s] == ref[s], s
    final = [l.split() for l in (dref / "dump.final").read_text().split("ITEM: ATOMS")[-1]
             .strip().splitlines()[1:]]
    gone = [r for r in final if float(r[1]) < 0.0]
    assert len(gone) == breaks[-1] and all(float(r[2]) == 0.0 for r in gone)
    assert (dsplit / "dump.final").read_text().split("ITEM: ATOMS")[-1] == \
        (dref / "dump.final").read_text().split("ITEM: ATOMS")[-1]


# 240 contacts on a hex lattice, re-forming in [-0.2, 0.2]: the start of
# the inputs below (the keywords of fix c follow)
HEX240 = """
units lj
dimension 2
atom_style atomic
boundary p p p
lattice hex 1.1547005383792515
region box block 0 10 0 12 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
comm_modify cutoff 0.5
fix c all eq/contacts 1.0 4711 threshold uniform 0.75 1.25 reform uniform -0.2 0.2 &
"""

AGES = HEX240 + """    thermal 0.1 1.0 1.0 aging log 0.2 1.0 rest 3.0 crossing ${crossing}
fix slide all move linear 0.05 0.0 0.0 units box
timestep 0.25
variable clock equal f_c[9]
thermo_style custom step v_clock
thermo_modify format float %.17g
thermo 1
dump d all custom 1 ages.* id f_c[4] f_c[8] f_c[9]
dump_modify d sort id format float %.17g
run 400
"""


@pytest.mark.parametrize("crossing", ["step", "exact"])
def test_formation_times_follow_the_breaks(tmp_path, crossing):
    """Per-atom columns 8 and 9 are times on the fix's clock (global entry
    9): the time the budget runs out and the time the contact formed.
    Against bookkeeping of the break counts (column 4) dumped every step,
    independent of how the fix keeps them: the clock is the sum of the
    steps; a contact formed at the fix's definition has age rest + clock;
    one that broke in step k formed at its end with crossing step, within
    it with crossing exact; no age is negative, and no budget that a bound
    counts down has run out before the clock (a candidate is never in the
    past).  240 contacts,
    about 4 lives each in 400 steps of 0.25 at v = 0.05."""
    (tmp_path / "in.ages").write_text(AGES)
    log = eqtools.run_lammps(tmp_path / "in.ages", {"crossing": crossing}, cwd=tmp_path)
    clock = {}
    for line in log.splitlines():
        f = line.split()
        if len(f) == 2 and f[0].isdigit():
            clock[int(f[0])] = float(f[1])
    dt = 0.25
    assert len(clock) == 401
    assert all(abs(clock[k] - k * dt) <= 1e-12 * (1 + k) for k in clock)

    def frame(k):
        rows = (tmp_path / f"ages.{k}").read_text().split("ITEM: ATOMS")[1].strip().splitlines()[1:]
        return np.array([[float(x) for x in r.split()] for r in rows])

    prev = frame(0)
    assert np.all(prev[:, 3] == -3.0)    # formed at the definition, rest 3 before
    last_break = np.full(len(prev), -1)
    renewed = fresh_steps = counted = 0
    for k in range(1, 401):
        cur = frame(k)
        t0, t1 = clock[k - 1], clock[k]
        broke = cur[:, 1] > prev[:, 1]
        last_break[broke] = k
        formed = cur[:, 3]
        fresh = last_break < 0
        fresh_steps += fresh.sum()
        assert np.all(formed[fresh] == -3.0), k
        if crossing == "step":
            assert np.all(np.abs(formed[broke] - t1) <= 1e-12 * t1), k
        else:
            assert np.all((formed[broke] >= t0 - 1e-12 * t1) & (formed[broke] <= t1 * (1 + 1e-12))), k
        held = ~broke & ~fresh
        assert np.all(formed[held] == prev[held, 3]), k    # the time it formed stays
        assert np.all(formed <= t1 * (1 + 1e-12) + 1e-12), k    # no negative age
        counting = ~np.signbit(cur[:, 2])    # (else minus the budget: no bound counts it down)
        assert np.all(cur[counting, 2] >= t1 * (1 - 1e-12)), k    # run-outs ahead of the clock
        counted += counting.sum()
        renewed += broke.sum()
        prev = cur
    n = len(prev)
    assert renewed > 2 * n and fresh_steps > 10 * n    # many lives, first lives checked
    assert counted > 0.9 * 400 * n    # almost every contact within a bound, almost always


RESPA = HEX240 + """    thermal 0.1 1.0 1.0 aging log 0.2 1.0 delay exp 0.5 crossing exact
velocity all set 0.05 0.0 0.0 units box
fix slide all nve
fix hold all setforce 0.0 0.0 0.0
neigh_modify every ${nevery} delay 0 check no
timestep ${dt}
if "${respa} > 0" then "run_style respa 2 2" "fix_modify c respa ${level}"
variable clock equal f_c[9]
thermo_style custom step v_clock f_c[3] f_c[4]
thermo_modify format float %.17g norm no
thermo ${n}
dump d all custom ${n} final.dump id f_c[1] f_c[4] f_c[8] f_c[9]
dump_modify d sort id format float %.17g
run ${n}
"""


@pytest.mark.parametrize("level", [1, 2])
def test_respa_level_takes_its_own_step(tmp_path, level):
    """r-RESPA with 2 levels (loop 2), the slider moved by fix nve with
    zero forces: at the inner level (fix_modify respa 1) the fix runs at
    every inner step, each dt/2 long, so that the thermal run (breaks,
    ages, budgets, delays) is the Verlet run at dt/2 to the last bit; at
    the outer level (the default) it is the Verlet run at dt.  The clock
    (global entry 9) is the time run in both.  (An inner level once
    counted dt per inner step: twice the time.)"""
    (tmp_path / "in.respa").write_text(RESPA)
    dt, n = 0.25, 200

    def go(tag, v):
        d = tmp_path / tag
        d.mkdir()
        log = eqtools.run_lammps(tmp_path / "in.respa", v, cwd=d)
        last = [l.split() for l in log.splitlines() if l.split()[:1] == [str(v["n"])]][-1]
        atoms = (d / "final.dump").read_text().split("ITEM: ATOMS")[-1].strip().splitlines()[1:]
        return [float(x) for x in last[1:]], np.array([[float(x) for x in r.split()] for r in atoms])

    inner = level == 1
    # atoms are wrapped into the box at the same times in both (at the
    # outer steps), which the unwrapped positions' last bits depend on
    (clock, breaks, att), a = go("respa", {"dt": dt, "respa": 1, "level": level, "n": n,
                                          "nevery": 1})
    (vclock, vbreaks, vatt), b = go("verlet", {"dt": dt / 2 if inner else dt, "respa": 0,
                                               "level": level, "n": 2 * n if inner else n,
                                               "nevery": 2 if inner else 1})
    assert abs(clock - n * dt) <= 1e-12 * n * dt and abs(vclock - n * dt) <= 1e-12 * n * dt
    assert breaks > 240 and (breaks, att) == (vbreaks, vatt)
    if inner:
        assert np.array_equal(a, b)
    else:    # positions moved by two half steps against one whole: rounding
        assert np.array_equal(a[:, 2], b[:, 2]) and np.allclose(a, b, rtol=1e-9, atol=1e-9)


COMPACT = """
units lj
dimension 2
atom_style atomic
boundary p p p
if "${mode} == read" then "read_restart mid.105" else &
  "lattice hex 1.1547005383792515" "region box block 0 10 0 12 -0.5 0.5" "create_box 1 box" &
  "create_atoms 1 box" "mass 1 1.0" "velocity all set 0.05 0.02 0.0 units box" &
  "group sub id 1:200" "if '${tri} == 1' then 'change_box all triclinic'"
atom_modify sort 7 0.5
comm_modify cutoff 0.5
neighbor 0.3 bin
neigh_modify every 1 delay 0 check yes
fix c ${grp} eq/contacts 1.0 4711 threshold uniform 0.75 1.25 reform uniform -0.2 0.2 &
    ${kw} crossing exact ${extra}
fix slide all nve/noforce
timestep 0.25
thermo_style custom step f_c f_c[1] f_c[2] f_c[3] f_c[4] f_c[9]
thermo_modify format float %.17g norm no
thermo 1
dump d all custom 10 d.* id f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8] f_c[9] &
    f_c[10] f_c[11]
dump_modify d sort id format float %.17g
if "${mode} == write" then "restart 105 mid.*" "run 300" else "run 95" "run 100 pre no"
"""


@pytest.mark.parametrize("nprocs,layout", [(1, "all"), (4, "all"), (1, "subgroup"), (2, "triclinic")])
@pytest.mark.parametrize("kw", ["thermal 0.1 1.0 1.0 aging log 0.2 1.0 delay exp 0.5",
                                "aging exp 0.3 2.0 delay fixed 0.5"])
def test_compact_rows_give_the_default_to_the_bit(tmp_path, kw, nprocs, layout):
    """Keyword peratom 10 (the common step on compact rows, the per-atom
    output written back every 10 steps): the global output at every step
    and the per-atom output every 10 steps are those of the default to the
    last bit, with atoms migrating between ranks and sorted every 7 steps
    (their compact rows go with them), a restart file written in the run
    at a step where the per-atom output is not due (step 105: rows written
    back as they are packed; the file is the default's byte for byte) and
    continued by read_restart, in a run and a second one with pre no
    (compact rows made anew from the state rows).  At T > 0 and at T = 0 (aging and delays
    alone: no rate bound).  On group all, on a group of 200 of the 240
    atoms (the loop reads the masks) and in a triclinic box (the general
    unwrap).  The continued run's output is that of the
    default continued the same way; its per-atom output is the
    uninterrupted run's up to the second run (read_restart orders the
    atoms anew, and the sums with them; a run with pre no wraps the
    positions into the box at other steps, which changes the unwrapped
    positions in their last bits)."""
    (tmp_path / "in.compact").write_text(COMPACT)

    def go(tag, extra, mode, src=None):
        d = tmp_path / tag
        d.mkdir()
        if mode == "read":
            (d / "mid.105").write_bytes((tmp_path / src / "mid.105").read_bytes())
        v = {"kw": kw, "extra": extra, "mode": mode, "grp": "sub" if layout == "subgroup" else "all",
             "tri": int(layout == "triclinic")}
        log = eqtools.run_lammps(tmp_path / "in.compact", v, nprocs=nprocs, cwd=d)
        thermo = {}
        for line in log.splitlines():
            f = line.split()
            if len(f) == 7 and f[0].isdigit():
                thermo[int(f[0])] = f[1:]
        dumps = {int(p.name[2:]): p.read_text().split("ITEM: ATOMS")[1] for p in d.glob("d.*")}
        return thermo, dumps

    ref_t, ref_d = go("default", "", "write")
    hot_t, hot_d = go("compact", "peratom 10", "write")
    for k in (105, 210):
        assert (tmp_path / "compact" / f"mid.{k}").read_bytes() == \
            (tmp_path / "default" / f"mid.{k}").read_bytes()
    cont_t, cont_d = go("continued", "peratom 10", "read", "compact")
    cref_t, cref_d = go("continued-default", "", "read", "default")
    assert sorted(ref_t) == list(range(301)) and sorted(ref_d) == list(range(0, 301, 10))
    assert float(ref_t[300][3]) > 240    # breaks (entry 3): more than one per contact
    if layout == "subgroup":    # the others have no contact
        assert all(r.split()[1:] == ["0"] * 11 for r in ref_d[300].strip().splitlines()[201:])
    assert hot_t == ref_t and hot_d == ref_d
    assert sorted(cont_d) == list(range(110, 301, 10))
    assert cont_t == cref_t and sorted(cont_t) == list(range(105, 301)) and cont_d == cref_d
    if layout != "triclinic":    # (a restart of a triclinic box moves positions in their last bits)
        assert all(cont_d[k] == ref_d[k] for k in range(110, 201, 10))
