"""The plugin route: LAMMPS built from the same source tree without the
package (PLUGIN package on, LAMMPS' own CMake) loads frictioneqplugin.so,
built by src/FRICTION-EQ/plugin as a user would, and runs the flagship and
the force-style inputs with the numbers of the build with the package
compiled in.

- The host has none of the package's styles; `plugin load` gives it every
  style the compiled-in build has.  From LAMMPS 2022 on, LAMMPS_PLUGIN_PATH
  loads it without a command.
- The flagship (examples/eq-rigid, shortened) writes the same F(X) and
  stretch histogram files, byte for byte, from both builds.
- The inputs of the package's force-style YAML files are run as LAMMPS'
  harness runs them (unittest/force-styles: in.fourmol, the harness force
  field, the YAML's commands, run 0, run 4): the plugin build reproduces
  the YAML reference data within the YAML's epsilon, as the harness
  checks the compiled-in build, and both builds agree to the last bit.
"""
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import eqtools  # noqa: E402

HOST = os.environ.get("FEQ_HOST_LMP")
PLUGIN = os.environ.get("FEQ_PLUGIN")
LMP = eqtools.lmp_exe()
LAMMPS_DIR = Path(os.environ.get("FEQ_LAMMPS_DIR", ""))
VERSION = int(os.environ.get("FEQ_LAMMPS_VERSION", "0"))
TESTS = LAMMPS_DIR / "unittest" / "force-styles" / "tests"
YAMLS = sorted((ROOT / "unittest" / "force-styles").glob("*.yaml"))

# the force field of LAMMPS' fix harness (coeffs.fourmol in 2026; written
# into test_fix_timestep.cpp in 2021)
HARNESS_FF = """pair_style lj/cut 8.0
pair_coeff  1 1  0.02   2.5
pair_coeff  2 2  0.005  1.0
pair_coeff  2 4  0.005  0.5
pair_coeff  3 3  0.02   3.2
pair_coeff  4 4  0.015  3.1
pair_coeff  5 5  0.015  3.1
bond_style harmonic
bond_coeff  1 250.0 1.5
bond_coeff  2 300.0 1.1
bond_coeff  3 350.0 1.3
bond_coeff  4 650.0 1.2
bond_coeff  5 450.0 1.0
angle_style harmonic
angle_coeff  1  75.0 110.1
angle_coeff  2  45.0 111.0
angle_coeff  3  50.0 120.0
angle_coeff  4 100.0 108.5
group solute  molecule 1:2
group solvent molecule 3:5
"""

pytestmark = pytest.mark.skipif(not (HOST and PLUGIN), reason="FEQ_HOST_LMP / FEQ_PLUGIN not set")


def run(exe, text, cwd, plugin, env_extra=None):
    """Run an input given as text with lmp `exe`; with plugin, `plugin load`
    comes first."""
    head = f"plugin load {PLUGIN}\n" if plugin else ""
    infile = Path(cwd) / ("in.plugin" if plugin else "in.builtin")
    infile.write_text(head + text)
    env = eqtools.mpi_env()
    env["LAMMPS_POTENTIALS"] = str(ROOT / "potentials")
    env.update(env_extra or {})
    p = subprocess.run([exe, "-in", infile.name, "-log", "none", "-nocite"], cwd=cwd, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert p.returncode == 0 and "ERROR" not in p.stdout, p.stdout[-3000:]
    return p.stdout


def eq_styles(help_text):
    """FRICTION-EQ styles named in the output of lmp -h (or plugin list)."""
    return sorted(set(re.findall(r"\beq/[a-z/]+", help_text)))


# every style of the package (sorted), compiled in and in the plugin
STYLES = ["eq/contacts", "eq/elastic", "eq/me", "eq/meso", "eq/quasistatic", "eq/substrate"]


def test_host_is_lammps_without_the_package(tmp_path):
    host_help = subprocess.run([HOST, "-h"], stdout=subprocess.PIPE, text=True).stdout
    assert eq_styles(host_help) == []
    assert "PLUGIN" in host_help
    lmp_help = subprocess.run([LMP, "-h"], stdout=subprocess.PIPE, text=True).stdout
    compiled_in = eq_styles(lmp_help)
    assert compiled_in == STYLES
    out = run(HOST, "plugin list\n", tmp_path, plugin=True)
    assert eq_styles(out) == compiled_in
    # the plugin was built for this LAMMPS: no version warning
    assert "WARNING" not in out, out


def test_plugin_path_loads_without_a_command(tmp_path):
    """LAMMPS_PLUGIN_PATH (from the 2022 releases on; 29 Sep 2021 has only
    `plugin load`)"""
    env = {"LAMMPS_PLUGIN_PATH": str(Path(PLUGIN).parent)}
    text = "plugin list\n"
    if VERSION >= 20220217:
        out = run(HOST, text, tmp_path, plugin=False, env_extra=env)
        assert eq_styles(out) == STYLES
    else:
        out = run(HOST, text, tmp_path, plugin=False, env_extra=env)
        assert eq_styles(out) == []


def test_flagship_identical(tmp_path):
    """examples/eq-rigid with X up to 10 (F(X) on [0, 4], histogram at 10)."""
    outs = {}
    for name, exe, plugin in (("builtin", LMP, False), ("plugin", HOST, True)):
        d = tmp_path / name
        d.mkdir()
        text = (f"variable Xmax index 4.0\nvariable Xsteady index 10.0\nvariable out index {d}\n"
                f"include {ROOT / 'examples' / 'eq-rigid' / 'in.eq-rigid'}\n")
        run(exe, text, d, plugin)
        outs[name] = {f: (d / f).read_bytes() for f in ("F.dat", "Qs.dat")}
    F = eqtools.load(tmp_path / "plugin" / "F.dat")
    assert F.shape[0] == 401 and F[:, 2].max() > 0.7    # the static peak was reached
    for f in ("F.dat", "Qs.dat"):
        assert outs["plugin"][f] == outs["builtin"][f], f


def harness_input(cfg, kind):
    """The commands LAMMPS' harness runs for a YAML file (fix: FixTimestep
    plain; pair: PairStyle plain, newton on), ending with a dump of every
    atom and the fix's global output."""
    lines = [f"variable input_dir index {TESTS}"]
    if kind == "pair":
        lines.insert(0, "variable newton_pair index on")
    lines += (cfg.get("pre_commands") or "").splitlines()
    lines.append(f"include {TESTS / cfg['input_file']}")
    if kind == "fix":
        coeffs = TESTS / (cfg.get("input_coeffs") or "coeffs.fourmol")
        lines += [f"include {coeffs}"] if coeffs.exists() else HARNESS_FF.splitlines()
        lines += (cfg.get("post_commands") or "").splitlines()
        # as test_fix_timestep.cpp (2021 to 2026): 4 steps, a restart file,
        # 4 more steps; the YAML holds the state after all 8
        lines += ["timestep 0.25", "run 0 post no", "thermo 2", "run 4 post no start 0 stop 8",
                  "write_restart harness.restart", "run 4 post no start 0 stop 8"]
    else:
        lines.append("pair_style " + cfg["pair_style"])
        lines += ["pair_coeff " + l for l in (cfg.get("pair_coeff") or "").splitlines() if l.strip()]
        lines += ["pair_modify table 0"]
        lines += (cfg.get("post_commands") or "").splitlines()
        lines += ["run 0 post no", 'print "EVDWL $(evdwl:%.17g)"']
    lines.append("write_dump all custom atoms.dump id x y z vx vy vz fx fy fz "
                 "modify sort id format float %.17g")
    if kind == "fix" and cfg.get("global_scalar") is not None:
        lines.append('print "SCALAR $(f_test:%.17g)"')
    if kind == "fix" and cfg.get("global_vector"):
        n = int(str(cfg["global_vector"]).split()[0])
        lines += [f'print "VECTOR {i} $(f_test[{i}]:%.17g)"' for i in range(1, n + 1)]
    return "\n".join(lines) + "\n"


def printed(out):
    """SCALAR, VECTOR<i>, EVDWL lines printed by harness_input()."""
    nums = {}
    for line in out.splitlines():
        w = line.split()
        if w and w[0] in ("SCALAR", "EVDWL"):
            nums[w[0]] = float(w[1])
        elif w and w[0] == "VECTOR":
            nums["VECTOR" + w[1]] = float(w[2])
    return nums


def per_atom_ref(block):
    rows = [l.split() for l in str(block).strip().splitlines()]
    return {int(r[0]): np.array([float(v) for v in r[1:4]]) for r in rows}


def rel_err(val, ref):
    """LAMMPS' harness measure (EXPECT_FP_LE_WITH_EPS)."""
    diff = abs(val - ref)
    div = min(abs(val), abs(ref))
    return diff if div == 0.0 else diff / div


@pytest.mark.parametrize("path", YAMLS, ids=[p.stem for p in YAMLS])
def test_force_style_inputs(tmp_path, path):
    cfg = yaml.safe_load(path.read_text())
    kind = "pair" if "-pair-" in path.name else "fix"
    text = harness_input(cfg, kind)
    res = {}
    for name, exe, plugin in (("builtin", LMP, False), ("plugin", HOST, True)):
        d = tmp_path / name
        d.mkdir()
        out = run(exe, text, d, plugin)
        dump = (d / "atoms.dump").read_text().splitlines()
        start = dump.index(next(l for l in dump if l.startswith("ITEM: ATOMS"))) + 1
        atoms = np.array([[float(v) for v in l.split()] for l in dump[start:]])
        res[name] = (out, atoms)
    # both builds: the same numbers to the last bit
    assert np.array_equal(res["plugin"][1], res["builtin"][1])
    out, atoms = res["plugin"]
    nums = printed(out)
    assert nums == printed(res["builtin"][0])
    eps = float(cfg["epsilon"])
    byid = {int(r[0]): r for r in atoms}
    checked = 0
    if kind == "fix":
        for key, cols in (("run_pos", slice(1, 4)), ("run_vel", slice(4, 7))):
            for tag, ref in per_atom_ref(cfg[key]).items():
                for v, r in zip(byid[tag][cols], ref):
                    assert rel_err(v, r) <= eps, (key, tag, v, r)
                    checked += 1
        if cfg.get("global_scalar") is not None:
            assert rel_err(nums["SCALAR"], float(cfg["global_scalar"])) <= eps
        if cfg.get("global_vector"):
            vals = str(cfg["global_vector"]).split()[1:]
            for i, r in enumerate(vals, 1):
                assert rel_err(nums[f"VECTOR{i}"], float(r)) <= eps, (i, nums[f"VECTOR{i}"], r)
    else:
        for tag, ref in per_atom_ref(cfg["init_forces"]).items():
            for v, r in zip(byid[tag][7:10], ref):
                assert rel_err(v, r) <= eps, ("init_forces", tag, v, r)
                checked += 1
        assert rel_err(nums["EVDWL"], float(cfg["init_vdwl"])) <= eps
    assert checked == 3 * int(cfg["natoms"]) * (2 if kind == "fix" else 1)
