/* ----------------------------------------------------------------------
   FRICTION-EQ package: master-equation jobs (see eq_me_job.h)
------------------------------------------------------------------------- */

#include "eq_me_job.h"

#include "eq_renewal_exact.h"
#include "eq_substrate.h"

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace feq {

namespace {

std::ofstream open_out(const std::string &path)
{
  std::ofstream out(path);
  if (!out) throw SpecError("cannot write file '" + path + "'");
  out << std::setprecision(12);
  return out;
}

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
  return job.threshold.text.rfind("uniform", 0) == 0 && job.reform.dist &&
      job.reform.dist->is_point() && job.reform.dist->mean() == 0.0 &&
      job.opt.start == MEStart::RELAXED && job.opt.crossing == Crossing::EXACT && Pc.lower() > 0.0;
}

}    // namespace

const char *me_job_keywords()
{
  return "threshold, reform, stiffness, dir, xmax, dx, start, crossing, richardson, force, steady, "
         "snapshot, summary, exact, substrate";
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
  int richardson = -1;    // -1: not given (auto)
  size_t pos = 0;
  auto value = [&](const std::string &kw) -> const std::string & {
    if (pos >= args.size()) throw SpecError(kw + ": missing value");
    return args[pos++];
  };
  auto num = [&](const std::string &kw) {
    const std::string &tok = value(kw);
    try {
      return number(tok);
    } catch (const SpecError &) {
      throw SpecError(kw + ": expected a number, got '" + tok + "'");
    }
  };
  while (pos < args.size()) {
    const std::string kw = args[pos++];
    if (kw == "threshold") {
      job.threshold = parse_distribution(Role::THRESHOLD, args, pos, number, load);
      have_threshold = true;
    } else if (kw == "reform") {
      job.reform = parse_distribution(Role::REFORM, args, pos, number, load);
    } else if (kw == "stiffness") {
      job.stiffness = parse_distribution(Role::STIFFNESS, args, pos, number, load);
    } else if (kw == "dir") {
      const std::string &v = value(kw);
      if (v != "x" && v != "y" && v != "z")
        throw SpecError("dir: unknown value '" + v + "'; allowed: x, y, z");
    } else if (kw == "xmax") {
      job.opt.Xmax = num(kw);
      if (!(job.opt.Xmax > 0.0)) throw SpecError("xmax: must be > 0");
    } else if (kw == "dx") {
      job.opt.dx = num(kw);
      if (!(job.opt.dx > 0.0)) throw SpecError("dx: must be > 0");
    } else if (kw == "start") {
      const std::string &v = value(kw);
      if (v == "relaxed") job.opt.start = MEStart::RELAXED;
      else if (v == "reform") job.opt.start = MEStart::REFORM;
      else throw SpecError("start: unknown value '" + v + "'; allowed: relaxed, reform");
    } else if (kw == "crossing") {
      const std::string &v = value(kw);
      if (v == "exact") job.opt.crossing = Crossing::EXACT;
      else if (v == "step") job.opt.crossing = Crossing::STEP;
      else throw SpecError("crossing: unknown value '" + v + "'; allowed: exact, step");
    } else if (kw == "richardson") {
      const std::string &v = value(kw);
      if (v != "yes" && v != "no")
        throw SpecError("richardson: unknown value '" + v + "'; allowed: yes, no");
      richardson = (v == "yes") ? 1 : 0;
    } else if (kw == "force") {
      job.force_file = value(kw);
    } else if (kw == "steady") {
      job.steady_file = value(kw);
    } else if (kw == "summary") {
      job.summary_file = value(kw);
    } else if (kw == "exact") {
      job.exact_file = value(kw);
    } else if (kw == "substrate") {
      job.substrate_file = value(kw);
      job.substrate_key = value(kw);
      job.substrate_uc = num(kw);
      if (!(job.substrate_uc > 0.0)) throw SpecError("substrate: uc must be > 0");
    } else if (kw == "snapshot") {
      const double X = num(kw);
      job.snapshots.emplace_back(X, value(kw));
      job.opt.snapshots.push_back(X);
    } else {
      throw SpecError("unknown keyword '" + kw + "'; allowed: " + me_job_keywords());
    }
  }
  if (!have_threshold)
    throw SpecError(std::string("the threshold keyword is required; allowed styles: ") +
                    role_styles(Role::THRESHOLD));
  check_reform(*job.threshold.dist, job.reform);
  // xmax on the grid: a whole number of steps of dx (Richardson needs the
  // fine grid to end at the same X)
  job.xmax_requested = job.opt.Xmax;
  const long nsteps = std::lround(job.opt.Xmax / job.opt.dx);
  if (nsteps < 1)
    throw SpecError("xmax: must be at least dx (xmax = " + std::to_string(job.opt.Xmax) +
                    ", dx = " + std::to_string(job.opt.dx) + ")");
  job.opt.Xmax = nsteps * job.opt.dx;
  if (job.opt.start == MEStart::REFORM && !job.reform.dist)
    throw SpecError("start reform: needs contacts that re-form (reform none given)");
  if (richardson == 1 && job.opt.crossing == Crossing::STEP)
    throw SpecError("richardson: only with crossing exact (the step model is first order by design)");
  // Richardson extrapolation of the second-order scheme by default: it
  // removes the O(dx^2) term at 5x the cost (measured: 100x smaller error
  // at equal run time, doc/src/eq_me.rst)
  job.richardson = richardson < 0 ? job.opt.crossing == Crossing::EXACT : richardson == 1;
  if (!job.steady_file.empty() && !job.reform.dist)
    throw SpecError("steady: contacts that never re-form have no steady state");
  if (!job.exact_file.empty() && !exact_applies(job))
    throw SpecError("exact: needs threshold uniform lo hi with lo > 0, reform delta 0, start "
                    "relaxed, crossing exact");
  if (!job.substrate_file.empty() && job.substrate_uc > job.opt.Xmax * (1.0 + 1e-12))
    throw SpecError("substrate: uc = " + std::to_string(job.substrate_uc) +
                    " beyond xmax = " + std::to_string(job.opt.Xmax) + "; raise xmax");
  for (const auto &s : job.snapshots)
    if (!(s.first >= 0.0 && s.first <= job.opt.Xmax + 0.5 * job.opt.dx))
      throw SpecError("snapshot: X = " + std::to_string(s.first) + " outside [0, xmax]");
  return job;
}

MEReport run_me_job(const MEJob &job, bool write_files)
{
  const MEOptions &opt = job.opt;
  const auto t0 = std::chrono::steady_clock::now();
  MEResult res = solve_master_equation(job.threshold.dist, job.reform.dist, opt);
  if (job.richardson) {
    MEOptions half = opt;
    half.dx = 0.5 * opt.dx;
    const MEResult fine = solve_master_equation(job.threshold.dist, job.reform.dist, half);
    if (fine.F.size() != 2 * res.F.size() - 1)
      throw SpecError("richardson: fine grid does not end at xmax (internal error)");
    for (size_t k = 0; k < res.F.size(); ++k) {
      res.F[k] = (4.0 * fine.F[2 * k] - res.F[k]) / 3.0;
      res.sd[k] = fine.sd[2 * k];
      res.attached[k] = fine.attached[2 * k];
      res.skew[k] = fine.skew[2 * k];
    }
  }
  const Distribution &Pc = *job.threshold.dist;
  SteadyState ss;
  if (job.reform.dist) ss = steady_state(Pc, *job.reform.dist);

  // per-contact stiffness k_i = kc f: F scales with <f>, the spread of one
  // contact's force is sqrt(<f^2><x^2> - <f>^2<x>^2)
  const double f1 = job.stiffness.dist->mean(), f2 = job.stiffness.dist->second_moment();
  if (job.stiffness.text != "constant") {
    for (size_t k = 0; k < res.F.size(); ++k) {
      const double x1 = res.F[k], x2 = res.sd[k] * res.sd[k] + x1 * x1;
      res.F[k] = f1 * x1;
      res.sd[k] = std::sqrt(std::max(0.0, f2 * x2 - f1 * f1 * x1 * x1));
    }
    ss.F *= f1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  MEReport rep;
  auto &v = rep.values;
  v["threshold_mean"] = Pc.mean();
  v["threshold_sd"] = std::sqrt(std::max(0.0, Pc.variance()));
  v["stiffness_mean"] = f1;
  const Extremum peak = static_peak(res);
  const Extremum kstar = critical_stiffness(res);
  if (peak.found) {
    v["static_peak"] = peak.value;
    v["static_peak_X"] = peak.X;
  }
  v["kstar"] = kstar.value;
  if (kstar.found) v["kstar_X"] = kstar.X;
  v["force_at_xmax"] = res.F.back();
  v["mass_error"] = res.max_mass_error;
  v["seconds"] = seconds;
  v["dx"] = opt.dx;
  v["xmax"] = opt.Xmax;
  if (job.reform.dist) {
    v["kinetic_force"] = ss.F;
    v["steady_rate"] = ss.Gamma;
  }

  std::string &t = rep.text;
  t += "FRICTION-EQ master equation of the EQ model (eq-me, eq/me)\n";
  t += format("  threshold    %s   <x_s> = %.10g, sd = %.6g\n", job.threshold.text.c_str(),
              Pc.mean(), v["threshold_sd"]);
  t += format("  reform       %s\n", job.reform.text.c_str());
  if (job.stiffness.text != "constant")
    t += format("  stiffness    %s: <k_i> = %.10g k_c (F below includes it)\n",
                job.stiffness.text.c_str(), f1);
  t += format("  grid         dx = %g, X in [0, %g], %zu stretch points, start %s, crossing %s%s\n",
              opt.dx, opt.Xmax, res.x.size(), opt.start == MEStart::RELAXED ? "relaxed" : "reform",
              opt.crossing == Crossing::EXACT ? "exact" : "step",
              job.richardson ? ", Richardson (dx, dx/2)" : "");
  if (std::fabs(job.xmax_requested - opt.Xmax) > 1e-12 * opt.Xmax)
    t += format("  NOTE         xmax %g rounded to %g, a whole number of steps dx\n",
                job.xmax_requested, opt.Xmax);
  const double sd = v["threshold_sd"];
  if (opt.crossing == Crossing::EXACT && opt.dx > 0.05 * sd)
    t += format("  WARNING      dx = %g is coarse against the spread of the thresholds (sd = %g): "
                "the error grows like dx^2; dx <= %g is recommended\n",
                opt.dx, sd, 0.05 * sd);
  if (peak.found)
    t += format("  static peak  F_s/(N k_c) = %.10f at X = %.6f\n", peak.value, peak.X);
  else
    t += "  static peak  none: F still increases at xmax\n";
  if (job.reform.dist)
    t += format("  kinetic      F_k/(N k_c) = %.10f (stationary solution), Gamma_s = %.10f\n", ss.F,
                ss.Gamma);
  t += format("  F(xmax)      F/(N k_c)   = %.10f\n", res.F.back());
  if (kstar.found)
    t += format("  stiffness    K*/K_s      = %.10f at X = %.6f\n", kstar.value, kstar.X);
  else
    t += "  stiffness    K*/K_s      = 0: F never decreases within [0, xmax]\n";
  t += format("  probability  max |int Q - 1| = %.3g\n", res.max_mass_error);
  t += format("  time         %.3f s\n", seconds);

  if (!job.exact_file.empty()) {
    RenewalUniform exact(Pc.lower(), Pc.upper());
    std::ofstream out;
    if (write_files) {
      out = open_out(job.exact_file);
      out << "# exact renewal solution: X <x> <x^2> Gamma; " << job.threshold.text << "\n";
    }
    double maxerr = 0.0;
    // the exact solution costs ~1e4 times more per point: every 0.01 in X
    const size_t stride = std::max<size_t>(1, (size_t) std::llround(0.01 / opt.dx));
    for (size_t k = 0; k < res.X.size(); k += stride) {
      const double m1 = exact.mean_stretch(res.X[k]);
      if (write_files)
        out << res.X[k] << " " << m1 << " " << exact.second_moment(res.X[k]) << " "
            << exact.rate(res.X[k]) << "\n";
      maxerr = std::max(maxerr, std::fabs(res.F[k] - f1 * m1));    // F includes <f>
    }
    v["exact_max_error"] = maxerr;
    t += format("  exact        max |F_ME - F_exact|/(N k_c) = %.3e\n", maxerr);
  }
  if (!write_files) return rep;

  if (!job.force_file.empty()) {
    std::ofstream out = open_out(job.force_file);
    out << "# eq-me: threshold " << job.threshold.text << ", reform " << job.reform.text << ", dx "
        << opt.dx << "\n# X F/(N*kc) sd(x) Gamma attached skewness(x)\n";
    for (size_t k = 0; k < res.X.size(); ++k)
      out << res.X[k] << " " << res.F[k] << " " << res.sd[k] << " " << res.Gamma[k] << " "
          << res.attached[k] << " " << res.skew[k] << "\n";
  }
  if (!job.steady_file.empty()) {
    std::ofstream out = open_out(job.steady_file);
    out << "# eq-me steady state: threshold " << job.threshold.text << ", reform "
        << job.reform.text << "\n# F_k/(N*kc) = " << ss.F << ", Gamma_s = " << ss.Gamma
        << "\n# x Q_s(x)\n";
    for (size_t i = 0; i < ss.x.size(); ++i) out << ss.x[i] << " " << ss.Q[i] << "\n";
  }
  for (const auto &s : job.snapshots) {
    size_t idx = res.snapX.size();
    for (size_t i = 0; i < res.snapX.size(); ++i)
      if (std::fabs(res.snapX[i] - s.first) <= 0.5 * opt.dx) idx = i;
    if (idx == res.snapX.size()) continue;
    std::ofstream out = open_out(s.second);
    out << "# eq-me Q(x;X) at X = " << res.snapX[idx] << "\n# x Q(x;X)\n";
    for (size_t j = 0; j < res.x.size(); ++j)
      if (res.snapQ[idx][j] != 0.0) out << res.x[j] << " " << res.snapQ[idx][j] << "\n";
  }
  if (!job.substrate_file.empty()) {
    // F(X)/(N k_c) on [0, uc]: the grid points below uc, then uc itself
    // (linear interpolation between the two grid points around it)
    std::vector<double> u, phi;
    const double uc = job.substrate_uc;
    for (size_t k = 0; k < res.X.size() && res.X[k] < uc - 1e-9 * opt.dx; ++k) {
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
    const std::string comment =
        "FK-ME substrate shape phi(u) = F(u)/(N k_c) of a rigid block from the master equation\n"
        "(eq-me / eq/me): threshold " + job.threshold.text + ", reform " + job.reform.text +
        ", stiffness " + job.stiffness.text + ", start " +
        (opt.start == MEStart::RELAXED ? "relaxed" : "reform") + ", dx " + format("%g", opt.dx) +
        (job.richardson ? " (Richardson)" : "") + "\nperiod uc = " + format("%g", uc) +
        "; use: fix ID group eq/substrate kc table FILE " + job.substrate_key + "\ncolumns: index u phi(u)";
    // validated as fix eq/substrate will read it
    SubstrateShape::table(u, phi, job.substrate_file + " " + job.substrate_key);
    std::ofstream out = open_out(job.substrate_file);
    out << substrate_table_text(job.substrate_key, u, phi, comment);
    t += format("  substrate    %s %s: phi(u) on [0, %g], %zu points, max phi = %.6f\n",
                job.substrate_file.c_str(), job.substrate_key.c_str(), uc, u.size(),
                *std::max_element(phi.begin(), phi.end()));
  }
  if (!job.summary_file.empty()) {
    std::ofstream out = open_out(job.summary_file);
    out << std::setprecision(15);
    for (const auto &kv : v) out << kv.first << " " << kv.second << "\n";
  }
  return rep;
}

}    // namespace feq
