/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   LAMMPS development team: developers@lammps.org

   Copyright (2003) Sandia Corporation.  Under the terms of Contract
   DE-AC04-94AL85000 with Sandia Corporation, the U.S. Government retains
   certain rights in this software.  This software is distributed under
   the GNU General Public License.

   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: FRICTION-EQ developers
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   FRICTION-EQ package: master-equation jobs (see eq_me_job.h)
------------------------------------------------------------------------- */

#include "eq_me_job.h"

#include "eq_keywords.h"
#include "eq_renewal_exact.h"
#include "eq_substrate.h"
#include "eq_thermal_steady.h"

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace feq {

namespace {

std::ofstream open_out(const std::string &kw, const std::string &path)
{
  std::ofstream out(path);
  if (!out) throw SpecError(kw + ": cannot write file '" + path + "'");
  out << std::setprecision(12);
  return out;
}

// a number in a message: as std::to_string for everyday values (the
// messages' established form), %g for the very large and very small
std::string num(double v)
{
  const double a = std::fabs(v);
  if (v == 0.0 || (a >= 1e-4 && a < 1e15)) return std::to_string(v);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

std::string fmtg(double v)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

// size limits of the solver (lib/eq_master_equation.cpp stops at the same
// ones): grid points of the stretch grid, slider steps
const double MAX_GRID_POINTS = 2e8;
const double MAX_STEPS = 2e8;
// the exact renewal solution: Irwin-Hall terms for the whole table
// (RenewalUniform::work(); measured 0.17-0.3 us each: ~30 s)
const double EXACT_MAX_WORK = 1e8;
const double EXACT_SECONDS_PER_WORK = 3e-7;
// the renewal solution of the thermal terms: cells times kernel cells
// (eq_thermal_steady.cpp; measured ~0.7 ns each: ~20 s)
const double THERMAL_MAX_WORK = 3e10;
const double THERMAL_SECONDS_PER_WORK = 7e-10;

std::string format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char *fmt, ...)
{
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof(buf), fmt, ap);
  va_end(ap);
  return buf;
}

bool exact_applies(const MEJob &job)
{
  const Distribution &Pc = *job.threshold.dist;
  return Pc.kind() == DistKind::UNIFORM && job.reform.dist &&
      job.reform.dist->is_point() && job.reform.dist->mean() == 0.0 &&
      job.opt.start == MEStart::RELAXED && job.opt.crossing == Crossing::EXACT && Pc.lower() > 0.0;
}

bool is_keyword(const std::string &tok)
{
  static const char *const kws[] = {"threshold", "reform",   "stiffness", "dir",      "xmax",
                                    "dx",        "start",    "crossing",  "richardson", "force",
                                    "steady",    "snapshot", "summary",   "exact",    "substrate",
                                    "thermal",   "barrier",  "aging",     "delay",    "rest",
                                    "velocity",  "kinetic"};
  for (const char *k : kws)
    if (tok == k) return true;
  return false;
}

// the stretch grid of the solver (MasterEquation): from the most negative
// re-forming stretch to the largest threshold (or its 1e-17 tail)
void check_grid(const MEJob &job)
{
  const Distribution &Pc = *job.threshold.dist;
  double rlo = 0.0, rhi = 0.0;
  if (job.reform.dist) {
    const Distribution &R = *job.reform.dist;
    rlo = R.lower();
    rhi = R.upper();
    if (!std::isfinite(rlo)) rlo = R.quantile(1e-17);
    if (!std::isfinite(rhi)) rhi = R.isf(1e-17);
  }
  double top = Pc.upper();
  const bool bounded = std::isfinite(top);
  if (!bounded) top = Pc.isf(1e-17);
  // Richardson solves at dx/2 too
  const double h = job.richardson ? 0.5 * job.opt.dx : job.opt.dx;
  const double hi = std::max(top, std::max(rhi, -rlo)), lo = std::min(rlo, 0.0);
  const double points = std::ceil(-lo / h) + 2.0 + std::ceil((hi + 2.0 * h) / h) + 2.0;
  if (points <= MAX_GRID_POINTS) return;
  const bool by_threshold = !(std::max(rhi, -rlo) > top);
  const std::string who = by_threshold ? "threshold " + job.threshold.text
                                       : "reform " + job.reform.text;
  const std::string what = by_threshold
      ? (bounded ? "up to the largest threshold" : "up to the 1e-17 tail of the thresholds")
      : "over the re-forming stretches";
  throw SpecError(who + ": the stretch grid x in [" + fmtg(lo) + ", " + fmtg(hi) + "] (" + what +
                  ") would need " + fmtg(points) + " points at dx = " + fmtg(h) +
                  (job.richardson ? " (dx/2 of richardson)" : "") + ", at most " +
                  fmtg(MAX_GRID_POINTS) + "; raise dx");
}

// the exact renewal solution: its terms, its work for the whole table and
// the precision of its Irwin-Hall sums, before it is computed
void check_exact(const MEJob &job)
{
  const Distribution &Pc = *job.threshold.dist;
  const double lo = Pc.lower(), hi = Pc.upper(), X = job.opt.Xmax;
  const RenewalUniform exact(lo, hi);
  const std::string which = " (lo = " + fmtg(lo) + ", hi = " + fmtg(hi) + ", xmax = " + fmtg(X) + ")";
  // renewal terms per point: ~xmax/lo when lo and hi - lo are both small,
  // cut after ~e xmax/(hi - lo) while hi - lo is not
  const long cap = RenewalUniform::EXACT_MAX_TERMS;
  if (exact.terms(X, cap) > cap)
    throw SpecError("exact: lo is too small: the renewal sums need more than " +
                    std::to_string(cap) + " terms per point" + which +
                    "; the cost grows as xmax/lo when hi - lo is small too: raise lo or hi, or "
                    "lower xmax");
  const double digits =
      exact.lost_digits(X, 2.0 * RenewalUniform::EXACT_MAX_LOST_DIGITS) + std::log10(hi / (hi - lo));
  if (digits > RenewalUniform::EXACT_MAX_LOST_DIGITS)
    throw SpecError("exact: the Irwin-Hall sums of the renewal solution lose " + fmtg(digits) +
                    " digits at X = xmax (at most " + fmtg(RenewalUniform::EXACT_MAX_LOST_DIGITS) +
                    ")" + which + "; xmax must stay below ~60 mean lifetimes (lo + hi)/2 and "
                    "hi - lo not too small: lower xmax");
  // the table: a point every 0.01 in X (run_me_job), work sampled at up to
  // 100 of them
  const size_t stride = std::max<size_t>(1, static_cast<size_t>(std::llround(0.01 / job.opt.dx)));
  const double points = std::floor(X / (stride * job.opt.dx) + 0.5) + 1.0;
  const int samples = static_cast<int>(std::min(points, 100.0));
  double sum = 0.0;
  for (int i = 1; i <= samples; ++i) sum += exact.work(X * i / samples);
  const double total = sum * points / samples;
  if (total > EXACT_MAX_WORK)
    throw SpecError("exact: the renewal solution would take ~" +
                    fmtg(std::round(total * EXACT_SECONDS_PER_WORK)) + " s for " + fmtg(points) +
                    " points of X" + which + ", at most ~" +
                    fmtg(EXACT_MAX_WORK * EXACT_SECONDS_PER_WORK) + " s; lower xmax or raise lo");
}

}    // namespace

// Every output file can be written: opened for appending (created when
// missing, and then removed again), so that nothing is changed on disk
// and a bad name stops the job before it is solved.
void check_me_outputs(const MEJob &job)
{
  std::vector<std::pair<std::string, std::string>> files;
  if (!job.force_file.empty()) files.emplace_back("force", job.force_file);
  if (!job.steady_file.empty()) files.emplace_back("steady", job.steady_file);
  for (const auto &s : job.snapshots) files.emplace_back("snapshot", s.second);
  if (!job.summary_file.empty()) files.emplace_back("summary", job.summary_file);
  if (!job.exact_file.empty()) files.emplace_back("exact", job.exact_file);
  if (!job.substrate_file.empty()) files.emplace_back("substrate", job.substrate_file);
  if (!job.kinetic_file.empty()) files.emplace_back("kinetic", job.kinetic_file);
  for (const auto &f : files) {
    std::FILE *probe = std::fopen(f.second.c_str(), "r");
    const bool existed = probe != nullptr;
    if (probe) std::fclose(probe);
    std::FILE *out = std::fopen(f.second.c_str(), "a");
    if (!out)
      throw SpecError(f.first + ": cannot write file '" + f.second + "' (" +
                      std::string(std::strerror(errno)) + ")");
    std::fclose(out);
    if (!existed) std::remove(f.second.c_str());
  }
}

const char *me_job_keywords()
{
  return "threshold, reform, stiffness, dir, xmax, dx, start, crossing, richardson, force, steady, "
         "snapshot, summary, exact, substrate, thermal, barrier, aging, delay, rest, velocity, "
         "kinetic";
}

namespace {

// richardson keyword: not given (on with crossing exact), yes or no
enum class Richardson { AUTO, YES, NO };

// whether the job combines dx and dx/2 (Richardson) for this choice
bool use_richardson(Richardson richardson, Crossing crossing)
{
  return richardson == Richardson::AUTO ? crossing == Crossing::EXACT
                                        : richardson == Richardson::YES;
}

// the keyword arguments of a job, read one token at a time
class JobArgs {
 public:
  JobArgs(const std::vector<std::string> &args_, const NumberParser &number_) :
      args(args_), number(number_)
  {
  }

  bool more() const { return pos < args.size(); }
  // kw (just read) as one of the keywords shared with fix eq/contacts
  bool thermal_keyword(const std::string &kw, ThermalKeywords &t)
  {
    return parse_thermal_keyword(kw, args, pos, number, t);
  }
  const std::string &next() { return args[pos++]; }

  // the next token: the value of keyword kw
  const std::string &value(const std::string &kw)
  {
    if (pos >= args.size()) throw SpecError(kw + ": missing value");
    return args[pos++];
  }

  // the next token as a number
  double number_of(const std::string &kw)
  {
    const std::string &tok = value(kw);
    try {
      return number(tok);
    } catch (const SpecError &) {
      throw SpecError(kw + ": expected a number, got '" + tok + "'");
    }
  }

  // an output file name; a keyword in its place means the name is missing
  // (it would otherwise be taken as the name and its values as keywords)
  const std::string &file(const std::string &kw)
  {
    if (pos < args.size() && is_keyword(args[pos]))
      throw SpecError(kw + ": missing file name before the keyword '" + args[pos] + "'");
    return value(kw);
  }

  // a distribution of the given role from the next tokens
  DistributionSpec distribution(Role role, const FileLoader &load)
  {
    return parse_distribution(role, args, pos, number, load);
  }

  // the next token as one of words (its index)
  int choice(const std::string &kw, const std::vector<std::string> &words)
  {
    return parse_choice(args, pos, kw, words);
  }

  // the next token as a finite number >= lo (> lo when strict); what
  // names it in messages ("delay tau")
  double at_least(const std::string &what, double lo, bool strict)
  {
    const double v = parse_finite(args, pos, what, number);
    if (strict ? !(v > lo) : !(v >= lo))
      throw SpecError(what + ": must be " + (strict ? "> " : ">= ") + fmtg(lo) + " (got " +
                      args[pos - 1] + ")");
    return v;
  }

 private:
  const std::vector<std::string> &args;
  const NumberParser &number;
  size_t pos = 0;
};

// reads the value of a solver keyword (dir, xmax, dx, start, crossing,
// richardson) into job; false when kw is none of them
bool read_solver_keyword(JobArgs &in, const std::string &kw, MEJob &job, Richardson &richardson)
{
  if (kw == "dir") {
    const std::string &v = in.value(kw);
    if (v != "x" && v != "y" && v != "z")
      throw SpecError("dir: unknown value '" + v + "'; allowed: x, y, z");
  } else if (kw == "xmax") {
    job.opt.Xmax = in.number_of(kw);
    if (!(job.opt.Xmax > 0.0)) throw SpecError("xmax: must be > 0");
  } else if (kw == "dx") {
    job.opt.dx = in.number_of(kw);
    if (!(job.opt.dx > 0.0)) throw SpecError("dx: must be > 0");
  } else if (kw == "start") {
    const std::string &v = in.value(kw);
    if (v == "relaxed") job.opt.start = MEStart::RELAXED;
    else if (v == "reform") job.opt.start = MEStart::REFORM;
    else throw SpecError("start: unknown value '" + v + "'; allowed: relaxed, reform");
  } else if (kw == "crossing") {
    const std::string &v = in.value(kw);
    if (v == "exact") job.opt.crossing = Crossing::EXACT;
    else if (v == "step") job.opt.crossing = Crossing::STEP;
    else throw SpecError("crossing: unknown value '" + v + "'; allowed: exact, step");
  } else if (kw == "richardson") {
    const std::string &v = in.value(kw);
    if (v != "yes" && v != "no")
      throw SpecError("richardson: unknown value '" + v + "'; allowed: yes, no");
    richardson = (v == "yes") ? Richardson::YES : Richardson::NO;
  } else {
    return false;
  }
  return true;
}

// reads the values of an output keyword (force, steady, summary, exact,
// substrate, snapshot) into job; false when kw is none of them
bool read_output_keyword(JobArgs &in, const std::string &kw, MEJob &job)
{
  if (kw == "force") {
    job.force_file = in.file(kw);
  } else if (kw == "steady") {
    job.steady_file = in.file(kw);
  } else if (kw == "summary") {
    job.summary_file = in.file(kw);
  } else if (kw == "exact") {
    job.exact_file = in.file(kw);
  } else if (kw == "substrate") {
    job.substrate_file = in.file(kw);
    job.substrate_key = in.value(kw);
    job.substrate_uc = in.number_of(kw);
    if (!(job.substrate_uc > 0.0)) throw SpecError("substrate: uc must be > 0");
  } else if (kw == "snapshot") {
    const double X = in.number_of(kw);
    job.snapshots.emplace_back(X, in.file(kw));
    job.opt.snapshots.push_back(X);
  } else {
    return false;
  }
  return true;
}

// reads the values of a keyword of the thermal terms (thermal, barrier,
// aging, delay, rest, velocity, kinetic) into job; false when kw is none
// of them.  The syntax and messages of fix eq/contacts.
bool read_thermal_keyword(JobArgs &in, const std::string &kw, MEJob &job)
{
  // the keywords of fix eq/contacts: one parser for both (eq_thermal)
  ThermalKeywords t;
  t.temperature = job.temperature;
  t.eps_a = job.eps_a;
  t.spec = job.thermal;
  if (in.thermal_keyword(kw, t)) {
    job.temperature = t.temperature;
    job.eps_a = t.eps_a;
    job.thermal = t.spec;
  } else if (kw == "velocity") {
    job.velocity = in.at_least("velocity", 0.0, true);
  } else if (kw == "kinetic") {
    job.kinetic_file = in.file(kw);
    job.kinetic_vlo = in.at_least("kinetic vlo", 0.0, true);
    job.kinetic_vhi = in.at_least("kinetic vhi", 0.0, true);
    const double n = in.at_least("kinetic n", 1.0, false);
    if (n != std::floor(n) || n > 10000.0)
      throw SpecError("kinetic n: must be a whole number of velocities, 1 to 10000 (got " +
                      fmtg(n) + ")");
    job.kinetic_n = static_cast<int>(n);
    if (job.kinetic_vhi < job.kinetic_vlo)
      throw SpecError("kinetic: needs vlo <= vhi (got vlo = " + fmtg(job.kinetic_vlo) +
                      ", vhi = " + fmtg(job.kinetic_vhi) + ")");
    if ((job.kinetic_n == 1) != (job.kinetic_vhi == job.kinetic_vlo))
      throw SpecError("kinetic: n = 1 goes with vlo = vhi, n >= 2 with vlo < vhi");
  } else {
    return false;
  }
  return true;
}

// xmax on the grid: a whole number of steps of dx (Richardson needs the
// fine grid to end at the same X), within the solver's step limit
void round_xmax(MEJob &job, Richardson richardson)
{
  job.xmax_requested = job.opt.Xmax;
  // the number of steps in floating point first (xmax 1e300 must not
  // overflow the integer conversion); Richardson also solves at dx/2,
  // with twice the steps
  const double steps = job.opt.Xmax / job.opt.dx;
  const bool rich = use_richardson(richardson, job.opt.crossing);
  if (!(steps <= (rich ? 0.5 : 1.0) * MAX_STEPS))
    throw SpecError("xmax: xmax/dx = " + fmtg(steps) + " steps (xmax = " + fmtg(job.opt.Xmax) +
                    ", dx = " + fmtg(job.opt.dx) + "), at most " +
                    (rich ? fmtg(0.5 * MAX_STEPS) + " with richardson (" + fmtg(MAX_STEPS) +
                                " without)"
                          : fmtg(MAX_STEPS)) +
                    "; lower xmax or raise dx");
  const long nsteps = std::lround(steps);
  if (nsteps < 1)
    throw SpecError("xmax: must be at least dx (xmax = " + num(job.opt.Xmax) + ", dx = " +
                    num(job.opt.dx) + ")");
  job.opt.Xmax = nsteps * job.opt.dx;
}

// the checks of a job that need all its keywords, sizes included, before
// anything is allocated; sets job.richardson
void check_job(MEJob &job, Richardson richardson)
{
  if (job.opt.start == MEStart::REFORM && !job.reform.dist)
    throw SpecError("start reform: needs contacts that re-form (reform none given)");
  if (richardson == Richardson::YES && job.opt.crossing == Crossing::STEP)
    throw SpecError("richardson: only with crossing exact (the step model is first order by design)");
  // Richardson extrapolation of the second-order scheme by default: it
  // removes the O(dx^2) term at 5x the cost (measured: 100x smaller error
  // at equal run time, doc/src/eq_me.rst)
  job.richardson = use_richardson(richardson, job.opt.crossing);
  if (!job.steady_file.empty() && !job.reform.dist)
    throw SpecError("steady: contacts that never re-form have no steady state");
  if (!job.exact_file.empty() && !exact_applies(job))
    throw SpecError("exact: needs threshold uniform lo hi with lo > 0, reform delta 0, start "
                    "relaxed, crossing exact");
  // every size before anything is allocated
  check_grid(job);
  if (!job.exact_file.empty()) check_exact(job);
  if (!job.substrate_file.empty() && job.substrate_uc > job.opt.Xmax * (1.0 + 1e-12))
    throw SpecError("substrate: uc = " + num(job.substrate_uc) + " beyond xmax = " +
                    num(job.opt.Xmax) + "; raise xmax");
  for (const auto &s : job.snapshots)
    if (!(s.first >= 0.0 && s.first <= job.opt.Xmax + 0.5 * job.opt.dx))
      throw SpecError("snapshot: X = " + num(s.first) + " outside [0, xmax]");
}

// the keywords of the master-equation solver that the renewal solution of
// the thermal terms has no counterpart for
void refuse_with_thermal(const MEJob &job)
{
  const std::string why = " not available with thermal, aging, delay or rest (solved by the "
                          "renewal equation at the velocity v)";
  if (job.opt.crossing == Crossing::STEP)
    throw SpecError("crossing: step (the discrete model of fix eq/contacts) is" + why +
                    "; use crossing exact");
  if (!job.snapshots.empty()) throw SpecError("snapshot: Q(x;X) is" + why);
  if (!job.exact_file.empty())
    throw SpecError("exact: the Irwin-Hall reference (uniform thresholds at T = 0) is" + why);
  if (!job.substrate_file.empty())
    throw SpecError("substrate: the block's substrate shape is" + why);
  if (job.reform.dist && !job.reform.dist->is_point())
    throw SpecError("reform " + job.reform.text + ": with thermal, aging, delay or rest only "
                    "reform delta x0 or none");
}

// the checks of a job with the thermal terms (instead of check_job);
// sets job.richardson
void check_thermal_job(MEJob &job, Richardson richardson)
{
  if (!(job.velocity > 0.0))
    throw SpecError("velocity: required with thermal, aging, delay or rest (the slider "
                    "velocity v > 0)");
  refuse_with_thermal(job);
  if (job.opt.start == MEStart::REFORM && !job.reform.dist)
    throw SpecError("start reform: needs contacts that re-form (reform none given)");
  if (!job.steady_file.empty() && !job.reform.dist)
    throw SpecError("steady: contacts that never re-form have no steady state");
  job.richardson = use_richardson(richardson, job.opt.crossing);
  // cells times kernel cells of the renewal solution, before anything is
  // allocated (the longest life does not depend on the temperature)
  ThermalSlider s;
  s.Pc = job.threshold.dist;
  s.spec = job.thermal;
  s.v = job.velocity;
  s.reform = job.reform.dist != nullptr;
  s.r0 = s.reform ? job.reform.dist->mean() : 0.0;
  const double h = job.richardson ? 0.5 * job.opt.dx : job.opt.dx, cells = job.opt.Xmax / h;
  const double work =
      cells * std::min(cells, thermal_kernel_cells(s, h)) * (job.richardson ? 1.25 : 1.0);
  if (work > THERMAL_MAX_WORK)
    throw SpecError("dx: the renewal solution would take ~" +
                    fmtg(std::round(work * THERMAL_SECONDS_PER_WORK)) + " s (" + fmtg(work) +
                    " cell pairs at dx = " + fmtg(h) + (job.richardson ? " and 2 dx" : "") +
                    ", xmax = " + fmtg(job.opt.Xmax) + "), at most ~" +
                    fmtg(THERMAL_MAX_WORK * THERMAL_SECONDS_PER_WORK) + " s; raise dx or lower xmax");
}

}    // namespace

ThermalSpec MEJob::thermal_spec() const
{
  ThermalSpec s = thermal;
  s.theta = boltz * temperature / eps_a;
  if (!std::isfinite(s.theta) || s.theta < 0.0)
    throw SpecError("thermal: k_B T / eps_a = " + fmtg(s.theta) + " is not a finite number >= 0 "
                    "(T = " + fmtg(temperature) + ", eps_a = " + fmtg(eps_a) + ", k_B = " +
                    fmtg(boltz) + ")");
  s.xc = threshold.dist ? threshold.dist->mean() : 1.0;
  return s;
}

MEJob parse_me_job(const std::vector<std::string> &args, const NumberParser &number,
                   const FileLoader &load)
{
  MEJob job;
  job.reform.dist = make_delta(0.0);
  job.reform.text = "delta 0";
  job.stiffness.dist = make_delta(1.0);
  job.stiffness.text = "constant";
  bool have_threshold = false;
  Richardson richardson = Richardson::AUTO;
  JobArgs in(args, number);
  while (in.more()) {
    const std::string kw = in.next();
    if (kw == "threshold") {
      job.threshold = in.distribution(Role::THRESHOLD, load);
      have_threshold = true;
    } else if (kw == "reform") {
      job.reform = in.distribution(Role::REFORM, load);
    } else if (kw == "stiffness") {
      job.stiffness = in.distribution(Role::STIFFNESS, load);
    } else if (!read_solver_keyword(in, kw, job, richardson) &&
               !read_output_keyword(in, kw, job) && !read_thermal_keyword(in, kw, job)) {
      throw SpecError("unknown keyword '" + kw + "'; allowed: " + me_job_keywords());
    }
  }
  if (!have_threshold)
    throw SpecError(std::string("the threshold keyword is required; allowed styles: ") +
                    role_styles(Role::THRESHOLD));
  check_reform(*job.threshold.dist, job.reform);
  round_xmax(job, richardson);
  if (job.thermal_on()) check_thermal_job(job, richardson);
  else check_job(job, richardson);
  if (!job.kinetic_file.empty() && !job.reform.dist)
    throw SpecError("kinetic: contacts that never re-form have no kinetic friction");
  return job;
}

namespace {

// the solution of a job and what its report is made of
struct JobSolution {
  MEResult res;
  SteadyState ss;
  bool reform_as_point = false;    // reform too narrow: a point for the steady state
  double f1 = 1.0;                 // <f> of the per-contact stiffness
  double seconds = 0.0;
  Extremum peak, kstar;
};

// solves the master equation, at dx and dx/2 combined with Richardson
MEResult solve_job(const MEJob &job)
{
  const MEOptions &opt = job.opt;
  MEResult res = solve_master_equation(job.threshold.dist, job.reform.dist, opt);
  if (job.richardson) {
    MEOptions half = opt;
    half.dx = 0.5 * opt.dx;
    const MEResult fine = solve_master_equation(job.threshold.dist, job.reform.dist, half);
    if (!combine_richardson(res, fine))
      throw SpecError("richardson: fine grid does not end at xmax (internal error)");
  }
  return res;
}

// the stationary solution of contacts that re-form (sol.ss, sol.reform_as_point)
void solve_steady_state(const MEJob &job, JobSolution &sol)
{
  if (!job.reform.dist) return;
  // a re-forming distribution narrower than 1e-12 of the thresholds'
  // range (gaussian 0.1 1e-300) is a point for the stationary solution:
  // its quadrature over [r_lo, r_hi] would collapse to 0/0
  const Distribution &Pc = *job.threshold.dist;
  const Distribution &R = *job.reform.dist;
  double rlo = R.lower(), rhi = R.upper();
  if (!std::isfinite(rlo)) rlo = R.quantile(1e-17);
  if (!std::isfinite(rhi)) rhi = R.isf(1e-17);
  sol.reform_as_point = !R.is_point() && !(rhi - rlo > 1e-12 * Pc.effective_upper());
  sol.ss = sol.reform_as_point ? steady_state(Pc, *make_delta(R.mean())) : steady_state(Pc, R);
}

// per-contact stiffness k_i = kc f: F scales with <f>, the spread of one
// contact's force is sqrt(<f^2><x^2> - <f>^2<x>^2)
void scale_result(const MEJob &job, MEResult &res)
{
  const double f1 = job.stiffness.dist->mean(), f2 = job.stiffness.dist->second_moment();
  for (size_t k = 0; k < res.F.size(); ++k) {
    const double x1 = res.F[k], x2 = res.sd[k] * res.sd[k] + x1 * x1;
    res.F[k] = f1 * x1;
    res.sd[k] = std::sqrt(std::max(0.0, f2 * x2 - f1 * f1 * x1 * x1));
  }
}

void scale_by_stiffness(const MEJob &job, JobSolution &sol)
{
  const double f1 = job.stiffness.dist->mean();
  sol.f1 = f1;
  if (job.stiffness.constant()) return;
  scale_result(job, sol.res);
  sol.ss.F *= f1;
}

// the "name value" results of the report (rep.values); also those of a
// job with the thermal terms (ThermalSolution has the same members)
template <class Solution>
void report_values(const MEJob &job, const Solution &sol, std::map<std::string, double> &v)
{
  const Distribution &Pc = *job.threshold.dist;
  v["threshold_mean"] = Pc.mean();
  v["threshold_sd"] = std::sqrt(std::max(0.0, Pc.variance()));
  v["stiffness_mean"] = sol.f1;
  if (sol.peak.found) {
    v["static_peak"] = sol.peak.value;
    v["static_peak_X"] = sol.peak.X;
  }
  v["kstar"] = sol.kstar.value;
  if (sol.kstar.found) v["kstar_X"] = sol.kstar.X;
  v["force_at_xmax"] = sol.res.F.back();
  v["mass_error"] = sol.res.max_mass_error;
  v["seconds"] = sol.seconds;
  v["dx"] = job.opt.dx;
  v["xmax"] = job.opt.Xmax;
  if (job.reform.dist) {
    v["kinetic_force"] = sol.ss.F;
    v["steady_rate"] = sol.ss.Gamma;
  }
}

// the lines of the report on the job and its grid (up to the static peak)
std::string report_job_text(const MEJob &job, const JobSolution &sol, double threshold_sd)
{
  const MEOptions &opt = job.opt;
  std::string t = "FRICTION-EQ master equation of the EQ model (eq-me, eq/me)\n";
  t += format("  threshold    %s   <x_s> = %.10g, sd = %.6g\n", job.threshold.text.c_str(),
              job.threshold.dist->mean(), threshold_sd);
  t += format("  reform       %s\n", job.reform.text.c_str());
  if (!job.stiffness.constant())
    t += format("  stiffness    %s: <k_i> = %.10g k_c (F below includes it)\n",
                job.stiffness.text.c_str(), sol.f1);
  t += format("  grid         dx = %g, X in [0, %g], %zu stretch points, start %s, crossing %s%s\n",
              opt.dx, opt.Xmax, sol.res.x.size(),
              opt.start == MEStart::RELAXED ? "relaxed" : "reform",
              opt.crossing == Crossing::EXACT ? "exact" : "step",
              job.richardson ? ", Richardson (dx, dx/2)" : "");
  if (std::fabs(job.xmax_requested - opt.Xmax) > 1e-12 * opt.Xmax)
    t += format("  NOTE         xmax %g rounded to %g, a whole number of steps dx\n",
                job.xmax_requested, opt.Xmax);
  const double sd = threshold_sd;
  if (opt.crossing == Crossing::EXACT && opt.dx > 0.05 * sd)
    t += format("  WARNING      dx = %g is coarse against the spread of the thresholds (sd = %g): "
                "the error grows like dx^2; dx <= %g is recommended\n",
                opt.dx, sd, 0.05 * sd);
  return t;
}

// the lines of the report on the results (static peak to run time)
std::string report_result_text(const MEJob &job, const JobSolution &sol)
{
  const MEResult &res = sol.res;
  std::string t;
  if (sol.peak.found)
    t += format("  static peak  F_s/(N k_c) = %.10f at X = %.6f\n", sol.peak.value, sol.peak.X);
  else
    t += "  static peak  none: F still increases at xmax\n";
  if (job.reform.dist)
    t += format("  kinetic      F_k/(N k_c) = %.10f (stationary solution), Gamma_s = %.10f\n",
                sol.ss.F, sol.ss.Gamma);
  if (sol.reform_as_point)
    t += format("  NOTE         reform %s is narrower than 1e-12 of the thresholds' range: the "
                "stationary solution takes it as delta %g\n", job.reform.text.c_str(),
                job.reform.dist->mean());
  t += format("  F(xmax)      F/(N k_c)   = %.10f\n", res.F.back());
  if (sol.kstar.found)
    t += format("  stiffness    K*/K_s      = %.10f at X = %.6f\n", sol.kstar.value, sol.kstar.X);
  else
    t += "  stiffness    K*/K_s      = 0: F never decreases within [0, xmax]\n";
  t += format("  probability  max |int Q - 1| = %.3g\n", res.max_mass_error);
  t += format("  time         %.3f s\n", sol.seconds);
  return t;
}

// the exact renewal solution against the ME (exact keyword): its table
// (when write_files), exact_max_error and its report line
void compare_exact(const MEJob &job, const JobSolution &sol, bool write_files, MEReport &rep)
{
  const Distribution &Pc = *job.threshold.dist;
  const MEResult &res = sol.res;
  RenewalUniform exact(Pc.lower(), Pc.upper());
  std::ofstream out;
  if (write_files) {
    out = open_out("exact", job.exact_file);
    out << "# exact renewal solution: X <x> <x^2> Gamma; " << job.threshold.text << "\n";
  }
  double maxerr = 0.0;
  // the exact solution costs ~1e4 times more per point: every 0.01 in X
  const size_t stride = std::max<size_t>(1, static_cast<size_t>(std::llround(0.01 / job.opt.dx)));
  for (size_t k = 0; k < res.X.size(); k += stride) {
    const double m1 = exact.mean_stretch(res.X[k]);
    if (write_files)
      out << res.X[k] << " " << m1 << " " << exact.second_moment(res.X[k]) << " "
          << exact.rate(res.X[k]) << "\n";
    maxerr = std::max(maxerr, std::fabs(res.F[k] - sol.f1 * m1));    // F includes <f>
  }
  rep.values["exact_max_error"] = maxerr;
  rep.text += format("  exact        max |F_ME - F_exact|/(N k_c) = %.3e\n", maxerr);
}

// force table: X F/(N*kc) sd(x) Gamma attached skewness(x)
void write_force(const MEJob &job, const MEResult &res)
{
  std::ofstream out = open_out("force", job.force_file);
  out << "# eq-me: threshold " << job.threshold.text << ", reform " << job.reform.text << ", dx "
      << job.opt.dx << "\n# X F/(N*kc) sd(x) Gamma attached skewness(x)\n";
  for (size_t k = 0; k < res.X.size(); ++k)
    out << res.X[k] << " " << res.F[k] << " " << res.sd[k] << " " << res.Gamma[k] << " "
        << res.attached[k] << " " << res.skew[k] << "\n";
}

// steady-state table: x Q_s(x)
void write_steady(const MEJob &job, const SteadyState &ss)
{
  std::ofstream out = open_out("steady", job.steady_file);
  out << "# eq-me steady state: threshold " << job.threshold.text << ", reform "
      << job.reform.text << "\n# F_k/(N*kc) = " << ss.F << ", Gamma_s = " << ss.Gamma
      << "\n# x Q_s(x)\n";
  for (size_t i = 0; i < ss.x.size(); ++i) out << ss.x[i] << " " << ss.Q[i] << "\n";
}

// snapshot tables: x Q(x;X), one per snapshot the solver recorded
void write_snapshots(const MEJob &job, const MEResult &res)
{
  for (const auto &s : job.snapshots) {
    size_t idx = res.snapX.size();
    for (size_t i = 0; i < res.snapX.size(); ++i)
      if (std::fabs(res.snapX[i] - s.first) <= 0.5 * job.opt.dx) idx = i;
    if (idx == res.snapX.size()) continue;
    std::ofstream out = open_out("snapshot", s.second);
    out << "# eq-me Q(x;X) at X = " << res.snapX[idx] << "\n# x Q(x;X)\n";
    for (size_t j = 0; j < res.x.size(); ++j)
      if (res.snapQ[idx][j] != 0.0) out << res.x[j] << " " << res.snapQ[idx][j] << "\n";
  }
}

// F(X)/(N k_c) on [0, uc]: the grid points below uc (X = 0 always, also
// for a uc below 1e-9 dx), then uc itself (linear interpolation between
// the two grid points around it)
void substrate_shape(const MEJob &job, const MEResult &res, std::vector<double> &u,
                     std::vector<double> &phi)
{
  const double uc = job.substrate_uc;
  for (size_t k = 0; k < res.X.size() && (k == 0 || res.X[k] < uc - 1e-9 * job.opt.dx); ++k) {
    u.push_back(res.X[k]);
    phi.push_back(res.F[k]);
  }
  const size_t k = u.size();
  double last = res.F.back();
  if (k < res.X.size()) {
    const double t = (uc - res.X[k - 1]) / (res.X[k] - res.X[k - 1]);
    last = res.F[k - 1] + t * (res.F[k] - res.F[k - 1]);
  }
  u.push_back(uc);
  phi.push_back(last);
}

// substrate table for fix eq/substrate; returns its report line
std::string write_substrate(const MEJob &job, const MEResult &res)
{
  const MEOptions &opt = job.opt;
  std::vector<double> u, phi;
  substrate_shape(job, res, u, phi);
  const double uc = job.substrate_uc;
  const std::string comment =
      "FK-ME substrate shape phi(u) = F(u)/(N k_c) of a rigid block from the master equation\n"
      "(eq-me / eq/me): threshold " + job.threshold.text + ", reform " + job.reform.text +
      ", stiffness " + job.stiffness.text + ", start " +
      (opt.start == MEStart::RELAXED ? "relaxed" : "reform") + ", dx " + format("%g", opt.dx) +
      (job.richardson ? " (Richardson)" : "") + "\nperiod uc = " + format("%g", uc) +
      "; use: fix ID group eq/substrate kc table FILE " + job.substrate_key + "\ncolumns: index u phi(u)";
  // validated as fix eq/substrate will read it
  SubstrateShape::table(u, phi, job.substrate_file + " " + job.substrate_key);
  std::ofstream out = open_out("substrate", job.substrate_file);
  out << substrate_table_text(job.substrate_key, u, phi, comment);
  return format("  substrate    %s %s: phi(u) on [0, %g], %zu points, max phi = %.6f\n",
                job.substrate_file.c_str(), job.substrate_key.c_str(), uc, u.size(),
                *std::max_element(phi.begin(), phi.end()));
}

// summary file: "name value" lines of the report's values
void write_summary(const MEJob &job, const std::map<std::string, double> &v)
{
  std::ofstream out = open_out("summary", job.summary_file);
  out << std::setprecision(15);
  for (const auto &kv : v) out << kv.first << " " << kv.second << "\n";
}

/* ----------------------------------------------------------------------
   jobs with the thermal terms (thermal, aging, delay, rest): the renewal
   solution and the steady-state quadrature of eq_thermal_steady
------------------------------------------------------------------------- */

// the contacts of a job on a slider at velocity v
ThermalSlider job_slider(const MEJob &job, double v)
{
  ThermalSlider s;
  s.Pc = job.threshold.dist;
  s.spec = job.thermal_spec();
  s.v = v;
  s.reform = job.reform.dist != nullptr;
  s.r0 = s.reform ? job.reform.dist->mean() : 0.0;
  s.start = job.opt.start == MEStart::REFORM ? s.r0 : 0.0;
  return s;
}

struct ThermalSolution {
  MEResult res;
  ThermalSteady ss;
  double slope = 0.0;    // dF_k/d ln v
  double f1 = 1.0;
  double seconds = 0.0;
  Extremum peak, kstar;
};

// the job's settings of the thermal terms, one line each
std::string thermal_text(const MEJob &job, const ThermalSpec &t)
{
  std::string out;
  if (job.temperature > 0.0)
    out += format("  thermal      theta = k_B T/eps_a = %.6g (T = %g, eps_a = %g, k_B = %g), "
                  "omega = %g, barrier p = %g, q = %g\n", t.theta, job.temperature, job.eps_a,
                  job.boltz, t.omega, t.p, t.q);
  else
    out += "  thermal      none (T = 0): no thermally activated breaking\n";
  if (t.aging != AgingLaw::NONE)
    out += format("  aging        %s: x_s(t) = x_s0 A(t), beta = %g, tau_a = %g\n",
                  t.aging == AgingLaw::LOG ? "log" : "exp", t.beta, t.tau_a);
  if (t.delay != DelayKind::NONE && t.tau > 0.0)
    out += format("  delay        %s, tau = %g (v tau = %.6g)\n",
                  t.delay == DelayKind::FIXED ? "fixed" : "exponential", t.tau,
                  job.velocity * t.tau);
  if (t.rest > 0.0) out += format("  rest         t_w = %g: age of the contacts at X = 0\n", t.rest);
  out += format("  velocity     v = %g\n", job.velocity);
  return out;
}

std::string thermal_report_text(const MEJob &job, const ThermalSolution &sol,
                                const ThermalSpec &t, double threshold_sd)
{
  const MEOptions &opt = job.opt;
  std::string s = "FRICTION-EQ master equation of the EQ model (eq-me, eq/me)\n";
  s += format("  threshold    %s   <x_s> = %.10g, sd = %.6g\n", job.threshold.text.c_str(),
              job.threshold.dist->mean(), threshold_sd);
  s += format("  reform       %s\n", job.reform.text.c_str());
  if (!job.stiffness.constant())
    s += format("  stiffness    %s: <k_i> = %.10g k_c (F below includes it)\n",
                job.stiffness.text.c_str(), sol.f1);
  s += thermal_text(job, t);
  s += format("  grid         dx = %g, X in [0, %g], renewal equation on cells, start %s%s\n",
              opt.dx, opt.Xmax, opt.start == MEStart::RELAXED ? "relaxed" : "reform",
              job.richardson ? ", Richardson (dx, dx/2)" : "");
  if (std::fabs(job.xmax_requested - opt.Xmax) > 1e-12 * opt.Xmax)
    s += format("  NOTE         xmax %g rounded to %g, a whole number of steps dx\n",
                job.xmax_requested, opt.Xmax);
  if (sol.peak.found)
    s += format("  static peak  F_s/(N k_c) = %.10f at X = %.6f\n", sol.peak.value, sol.peak.X);
  else
    s += "  static peak  none: F still increases at xmax\n";
  if (job.reform.dist)
    s += format("  kinetic      F_k/(N k_c) = %.10f (steady state at v), dF_k/d ln v = %.6g, "
                "Gamma_s = %.10f, attached %.10f\n",
                sol.ss.F, sol.slope, sol.ss.Gamma, sol.ss.attached);
  s += format("  F(xmax)      F/(N k_c)   = %.10f\n", sol.res.F.back());
  if (sol.kstar.found)
    s += format("  stiffness    K*/K_s      = %.10f at X = %.6f\n", sol.kstar.value, sol.kstar.X);
  else
    s += "  stiffness    K*/K_s      = 0: F never decreases within [0, xmax]\n";
  s += format("  probability  max |attached + detached - 1| = %.3g\n", sol.res.max_mass_error);
  s += format("  time         %.3f s\n", sol.seconds);
  return s;
}

void thermal_values(const MEJob &job, const ThermalSolution &sol, const ThermalSpec &t,
                    std::map<std::string, double> &v)
{
  report_values(job, sol, v);
  v["theta"] = t.theta;
  v["velocity"] = job.velocity;
  if (job.reform.dist) {
    v["kinetic_slope"] = sol.slope;
    v["attached_fraction"] = sol.ss.attached;
    v["lifetime"] = sol.ss.lifetime;
  }
}

// force table of the transient: the columns of write_force
void write_thermal_force(const MEJob &job, const MEResult &res, const std::string &settings)
{
  std::ofstream out = open_out("force", job.force_file);
  out << "# eq-me: threshold " << job.threshold.text << ", reform " << job.reform.text << ", dx "
      << job.opt.dx << "\n# renewal equation from X = 0 (all contacts formed there, age t_w)\n"
      << settings << "# X F/(N*kc) sd(x) Gamma attached skewness(x)\n";
  for (size_t k = 0; k < res.X.size(); ++k)
    out << res.X[k] << " " << res.F[k] << " " << res.sd[k] << " " << res.Gamma[k] << " "
        << res.attached[k] << " " << res.skew[k] << "\n";
}

// steady table: x Q_s(x) = Gamma_s S(x - r0) (integrates to the attached
// fraction)
void write_thermal_steady(const MEJob &job, const ThermalTransient &tt, const ThermalSteady &ss,
                          double r0, const std::string &settings)
{
  const SurvivalTable &S = *tt.later_lives();
  std::ofstream out = open_out("steady", job.steady_file);
  out << "# eq-me steady state: threshold " << job.threshold.text << ", reform "
      << job.reform.text << "\n" << settings << "# F_k/(N*kc) = " << ss.F
      << ", Gamma_s = " << ss.Gamma << ", attached " << ss.attached << "\n# x Q_s(x)\n";
  const int npoints = 2001;
  const double top = S.end() > 0.0 ? S.end() : 1.0;
  for (int i = 0; i < npoints; ++i) {
    const double y = top * i / (npoints - 1);
    out << r0 + y << " " << ss.Gamma * S(y) << "\n";
  }
}

// the settings of the thermal terms as comment lines of a table
std::string settings_comment(const MEJob &job, const ThermalSpec &t)
{
  std::string text = thermal_text(job, t), out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out += "#" + line.substr(1) + "\n";
  return out;
}

// kinetic table: v F_k dF_k/dlnv attached_fraction Gamma_s; its report line
std::string write_kinetic(const MEJob &job, double f1, bool write_file)
{
  const ThermalSpec t = job.thermal_spec();
  const std::vector<KineticPoint> tab =
      kinetic_table(job_slider(job, job.kinetic_vlo), job.kinetic_vlo, job.kinetic_vhi,
                    job.kinetic_n);
  if (write_file) {
    std::ofstream out = open_out("kinetic", job.kinetic_file);
    out << "# eq-me kinetic friction (steady state): threshold " << job.threshold.text
        << ", reform " << job.reform.text << "\n" << settings_comment(job, t)
        << "# v F_k/(N*kc) dF_k/dlnv attached_fraction Gamma_s\n";
    out << std::setprecision(15);
    for (const KineticPoint &p : tab)
      out << p.v << " " << f1 * p.F << " " << f1 * p.slope << " " << p.attached << " " << p.Gamma
          << "\n";
  }
  return format("  kinetic      %s: F_k(v) at %d velocities in [%g, %g]: %.8f ... %.8f\n",
                job.kinetic_file.c_str(), job.kinetic_n, job.kinetic_vlo, job.kinetic_vhi,
                f1 * tab.front().F, f1 * tab.back().F);
}

MEReport run_thermal_job(const MEJob &job, bool write_files)
{
  const auto t0 = std::chrono::steady_clock::now();
  const ThermalSpec t = job.thermal_spec();
  const ThermalSlider s = job_slider(job, job.velocity);
  const ThermalTransient tt(s);
  ThermalSolution sol;
  sol.res = tt.solve(job.opt.dx, job.opt.Xmax, job.richardson);
  if (s.reform) {
    sol.ss = thermal_steady_state(s);
    sol.slope = kinetic_slope(s);
  }
  sol.f1 = job.stiffness.dist->mean();
  if (!job.stiffness.constant()) {
    scale_result(job, sol.res);
    sol.ss.F *= sol.f1;
    sol.slope *= sol.f1;
  }
  sol.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sol.peak = static_peak(sol.res);
  sol.kstar = critical_stiffness(sol.res);

  MEReport rep;
  thermal_values(job, sol, t, rep.values);
  rep.text = thermal_report_text(job, sol, t, rep.values["threshold_sd"]);
  if (!job.kinetic_file.empty()) rep.text += write_kinetic(job, sol.f1, write_files);
  if (!write_files) return rep;
  const std::string settings = settings_comment(job, t);
  if (!job.force_file.empty()) write_thermal_force(job, sol.res, settings);
  if (!job.steady_file.empty()) write_thermal_steady(job, tt, sol.ss, s.r0, settings);
  if (!job.summary_file.empty()) write_summary(job, rep.values);
  return rep;
}

}    // namespace

MEReport run_me_job(const MEJob &job, bool write_files)
{
  if (write_files) check_me_outputs(job);
  if (job.thermal_on()) return run_thermal_job(job, write_files);
  const auto t0 = std::chrono::steady_clock::now();
  JobSolution sol;
  sol.res = solve_job(job);
  solve_steady_state(job, sol);
  scale_by_stiffness(job, sol);
  sol.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sol.peak = static_peak(sol.res);
  sol.kstar = critical_stiffness(sol.res);

  MEReport rep;
  report_values(job, sol, rep.values);
  rep.text = report_job_text(job, sol, rep.values["threshold_sd"]);
  rep.text += report_result_text(job, sol);
  if (!job.exact_file.empty()) compare_exact(job, sol, write_files, rep);
  if (!job.kinetic_file.empty()) rep.text += write_kinetic(job, sol.f1, write_files);
  if (!write_files) return rep;

  if (!job.force_file.empty()) write_force(job, sol.res);
  if (!job.steady_file.empty()) write_steady(job, sol.ss);
  write_snapshots(job, sol.res);
  if (!job.substrate_file.empty()) rep.text += write_substrate(job, sol.res);
  if (!job.summary_file.empty()) write_summary(job, rep.values);
  return rep;
}

}    // namespace feq
