"""Bad LAMMPS trees and tarballs are refused with a clear message, at
configure time (the wrapper CMake, the plugin CMake) and by the driver:

- a LAMMPS older than 29 Sep 2021: the version found and the supported ones;
- a tree without a package folder the build needs (MOLECULE, ...): which;
- a source tarball whose SHA256 does not match the pinned one: refused
  (the driver reads it from a local mirror here, FEQ_DEBIAN_MIRROR=file://);
- an unknown FEQ_LAMMPS value: the allowed ones.
"""
import os
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def fake_tree(path, version, packages=()):
    (path / "cmake").mkdir(parents=True)
    (path / "cmake" / "CMakeLists.txt").write_text("")
    (path / "src").mkdir()
    (path / "src" / "version.h").write_text(f'#define LAMMPS_VERSION "{version}"\n')
    (path / "src" / "lammpsplugin.h").write_text("")
    for p in packages:
        (path / "src" / p).mkdir()
    return path


def configure(source, lammps, build):
    p = subprocess.run(["cmake", "-S", str(source), "-B", str(build), f"-DLAMMPS_DIR={lammps}"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode, " ".join(p.stdout.split())


def test_old_lammps_is_refused(tmp_path):
    tree = fake_tree(tmp_path / "old", "22 Aug 2018", ["MOLECULE", "RIGID", "EXTRA-FIX", "BROWNIAN"])
    for source in (ROOT, ROOT / "src" / "FRICTION-EQ" / "plugin"):
        rc, out = configure(source, tree, tmp_path / f"b{source.name}")
        assert rc != 0
        assert ("the LAMMPS tree %s is version '22 Aug 2018' (20180822); supported: 29 Sep 2021 "
                "(20210929) and later" % tree) in out, out


def test_missing_package_is_named(tmp_path):
    tree = fake_tree(tmp_path / "nomol", "29 Sep 2021", ["RIGID", "BROWNIAN"])
    rc, out = configure(ROOT, tree, tmp_path / "b")
    assert rc != 0
    assert "has no package folder for MOLECULE, EXTRA-FIX in src/; the build needs MOLECULE, " \
           "RIGID, EXTRA-FIX, BROWNIAN" in out, out


def driver_copy(tmp_path):
    """The driver alone in a folder of its own (its .cache is there)."""
    d = tmp_path / "repo"
    d.mkdir()
    shutil.copy(ROOT / "friction-eq", d / "friction-eq")
    return d


def test_tarball_with_wrong_hash_is_refused(tmp_path):
    mirror = tmp_path / "mirror" / "pool" / "main" / "l" / "lammps"
    mirror.mkdir(parents=True)
    (mirror / "lammps_20250204+dfsg.1.orig.tar.xz").write_bytes(b"not the LAMMPS tarball\n")
    d = driver_copy(tmp_path)
    env = dict(os.environ, FEQ_DEBIAN_MIRROR=f"file://{tmp_path / 'mirror'}", FEQ_LAMMPS="2025")
    p = subprocess.run([str(d / "friction-eq"), "setup"], cwd=d, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=600)
    assert p.returncode != 0
    assert "SHA256 of lammps_20250204+dfsg.1.orig.tar.xz does not match the pinned " \
           "3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7: refusing to use it" \
           in p.stdout, p.stdout[-2000:]
    assert not (d / ".cache" / "lammps-2025").exists()
    assert not (d / ".cache" / "download" / "lammps_20250204+dfsg.1.orig.tar.xz").exists()


def test_unknown_version_key(tmp_path):
    d = driver_copy(tmp_path)
    env = dict(os.environ, FEQ_LAMMPS="2019")
    p = subprocess.run([str(d / "friction-eq"), "setup"], cwd=d, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=600)
    assert p.returncode != 0
    assert "FEQ_LAMMPS=2019: unknown version; allowed: 2021 2025 2026" in p.stdout, p.stdout[-2000:]
