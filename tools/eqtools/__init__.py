"""FRICTION-EQ analysis tools: run LAMMPS and the eq-me solver, read their
output, and compare EQ simulations with master-equation references using
statistics whose tolerances follow from the number of contacts.

Only numpy (and matplotlib for plots) is needed: Debian's python3-numpy.
"""
import math
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def build_dir():
    return Path(os.environ.get("FEQ_BUILD_DIR", ROOT / "build"))


def lmp_exe():
    return os.environ.get("FEQ_LMP", str(build_dir() / "lmp"))


def eqme_exe():
    return os.environ.get("FEQ_EQME", str(build_dir() / "eq-me"))


def mpi_env():
    env = dict(os.environ)
    env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                "OMPI_MCA_rmaps_base_oversubscribe": "1",
                "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
                "OMPI_MCA_hwloc_base_binding_policy": "none", "OMP_NUM_THREADS": "1"})
    # oversubscribed ranks yield the core while they wait; a benchmark on
    # a quiet machine with a core per rank may set 0 (busy polling)
    env.setdefault("OMPI_MCA_mpi_yield_when_idle", "1")
    return env


class RunError(RuntimeError):
    pass


def run_lammps(infile, variables=None, nprocs=1, cwd=".", log="none", extra=(), check=True):
    """Run lmp on `infile` with -var NAME VALUE pairs; returns stdout+stderr."""
    cmd = []
    if nprocs > 1:
        cmd += [os.environ.get("MPIEXEC") or shutil.which("mpirun") or "mpirun", "-np", str(nprocs)]
    cmd += [lmp_exe(), "-in", str(infile), "-log", log, "-nocite"]
    for k, v in (variables or {}).items():
        cmd += ["-var", str(k), str(v)]
    cmd += list(extra)
    p = subprocess.run(cmd, cwd=cwd, env=mpi_env(), stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    if check and (p.returncode != 0 or "ERROR" in p.stdout):
        raise RunError("LAMMPS failed (%s):\n%s" % (" ".join(cmd), p.stdout[-4000:]))
    return p.stdout


def run_eqme(args, cwd="."):
    """Run eq-me with keyword arguments (a list); returns its summary dict."""
    summary = Path(cwd) / "eqme_summary.txt"
    cmd = [eqme_exe()] + [str(a) for a in args] + ["summary", str(summary)]
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        raise RunError("eq-me failed (%s):\n%s" % (" ".join(cmd), p.stdout))
    out = {}
    for line in summary.read_text().splitlines():
        k, v = line.split()
        out[k] = float(v)
    out["stdout"] = p.stdout
    return out


def load(path):
    """Whitespace table with '#' comments as a 2-d array."""
    return np.atleast_2d(np.loadtxt(path, comments="#"))


def read_histo(path):
    """Last histogram of a fix ave/histo file: (centers, counts, total)."""
    lines = [l for l in Path(path).read_text().splitlines() if l and not l.startswith("#")]
    nbins = int(lines[-1].split()[0])
    # blocks: header line 'step nbins total missing min max' then nbins rows
    head = None
    for i, l in enumerate(lines):
        w = l.split()
        if len(w) == 6 and int(w[1]) == nbins:
            head = i
    rows = np.array([[float(v) for v in l.split()] for l in lines[head + 1:head + 1 + nbins]])
    total = float(lines[head].split()[2])
    return rows[:, 1], rows[:, 2], total


# ---------------------------------------------------------------- statistics

def gammaq(a, x):
    """Regularized upper incomplete gamma Q(a,x) (series / continued fraction)."""
    if x <= 0:
        return 1.0
    gln = math.lgamma(a)
    if x < a + 1.0:
        ap, s, d = a, 1.0 / a, 1.0 / a
        for _ in range(1000):
            ap += 1.0
            d *= x / ap
            s += d
            if abs(d) < abs(s) * 1e-15:
                break
        return 1.0 - s * math.exp(-x + a * math.log(x) - gln)
    b = x + 1.0 - a
    c, d = 1.0 / 1e-300, 1.0 / b
    h = d
    for i in range(1, 1000):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = 1e-300 if abs(d) < 1e-300 else d
        c = b + an / c
        c = 1e-300 if abs(c) < 1e-300 else c
        d = 1.0 / d
        h *= d * c
        if abs(d * c - 1.0) < 1e-15:
            break
    return math.exp(-x + a * math.log(x) - gln) * h


def chi2_sf(chi2, dof):
    """P(chi^2_dof > chi2)."""
    return gammaq(0.5 * dof, 0.5 * chi2)


def chi2_histogram(counts, probs, min_expected=5.0):
    """Pearson chi^2 of counts against bin probabilities (bins with small
    expectation merged).  Returns (chi2, dof, p-value)."""
    counts = np.asarray(counts, float)
    probs = np.asarray(probs, float)
    n = counts.sum()
    exp_ = probs / probs.sum() * n
    merged_c, merged_e, acc_c, acc_e = [], [], 0.0, 0.0
    for c, e in zip(counts, exp_):
        acc_c += c
        acc_e += e
        if acc_e >= min_expected:
            merged_c.append(acc_c)
            merged_e.append(acc_e)
            acc_c = acc_e = 0.0
    if acc_e > 0 and merged_e:
        merged_c[-1] += acc_c
        merged_e[-1] += acc_e
    mc, me = np.array(merged_c), np.array(merged_e)
    chi2 = float(np.sum((mc - me) ** 2 / me))
    dof = len(mc) - 1
    return chi2, dof, chi2_sf(chi2, dof)


def bin_probabilities(x, q, edges):
    """Integrate a tabulated density q(x) over histogram bins: trapezoid
    cumulative on the table's own points (zero outside the table, so a
    density that jumps at the table's ends, like Q_s at x = 0, is not
    smeared across the end), interpolated at the bin edges."""
    x = np.asarray(x, float)
    q = np.asarray(q, float)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (q[1:] + q[:-1]) * np.diff(x))])
    ce = np.interp(edges, x, cum, left=0.0, right=cum[-1])
    return np.diff(ce)


def zscores(f_eq, f_me, sd_me, n, skew=None, max_skew=0.05):
    """Deviation of an N-contact average from the ME mean in units of its
    standard error sd/sqrt(N) (sd of one contact from the ME).

    Where one contact's distribution is so skewed that the N-contact mean
    is not yet normal (rare breaks: a few events among N contacts), the
    point is left out (z = 0): with skew = third standardized moment, the
    Edgeworth correction to the normal tail at |z| = 5 is ~ 20 skew/sqrt(N),
    so points with |skew|/sqrt(N) > max_skew (factor-2 tail error) are not
    tested."""
    se = np.asarray(sd_me) / math.sqrt(n)
    ok = se > 0
    if skew is not None:
        ok &= np.abs(np.asarray(skew)) / math.sqrt(n) <= max_skew
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(ok, (np.asarray(f_eq) - np.asarray(f_me)) / np.where(ok, se, 1.0), 0.0)
    return z


# ---------------------------------------------------------------- eq-green
def eqgreen_exe():
    """The eq-green tool: FEQ_EQGREEN, else next to eq-me, else in the build."""
    if os.environ.get("FEQ_EQGREEN"):
        return os.environ["FEQ_EQGREEN"]
    if os.environ.get("FEQ_EQME"):
        return str(Path(os.environ["FEQ_EQME"]).parent / "eq-green")
    return str(build_dir() / "eq-green")


def run_eqgreen(args, cwd="."):
    """Run eq-green with keyword arguments (a list); returns its summary dict."""
    summary = Path(cwd) / "eqgreen_summary.txt"
    cmd = [eqgreen_exe()] + [str(a) for a in args] + ["summary", str(summary)]
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        raise RunError("eq-green failed (%s):\n%s" % (" ".join(cmd), p.stdout))
    out = {}
    for line in summary.read_text().splitlines():
        k, v = line.split()
        out[k] = float(v)
    out["stdout"] = p.stdout
    return out


def read_green_profile(path):
    """eq-green profile file as {dir: array[r, dfx, dfy, dfx_lin, dfy_lin, kernel_x]}."""
    rows = {}
    for line in Path(path).read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        w = line.split()
        rows.setdefault(w[0], []).append([float(x) for x in w[1:]])
    return {k: np.array(v) for k, v in rows.items()}
