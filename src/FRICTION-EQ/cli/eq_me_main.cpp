/* ----------------------------------------------------------------------
   eq-me: command-line front end of the FRICTION-EQ master-equation solver

   eq-me threshold STYLE values [keyword values ...]

   keywords (same syntax as fix eq/contacts where they overlap):
     threshold uniform lo hi | gaussian mean sd | realistic xs | table file key
     reform    delta x0 | uniform lo hi | gaussian mean sd | none   (delta 0)
     xmax X          largest slider displacement                  (8)
     dx h            stretch grid spacing = slider step           (1e-3)
     start relaxed|reform   Q(x;0) = delta(x) or R(x)             (relaxed)
     crossing exact|step    continuous ME, or the discrete model of
                            fix eq/contacts ... crossing step     (exact)
     richardson yes|no      combine dx and dx/2 (4 F_h/2 - F_h)/3  (no)
     force FILE      table: X  F/(N kc)  sd(x)  Gamma  attached  skewness(x)
     steady FILE     table: x  Q_s(x)   (analytic stationary solution)
     snapshot X FILE table: x  Q(x;X)   (may be repeated)
     summary FILE    "name value" lines of the printed summary
     exact FILE      uniform thresholds, reform delta 0, relaxed start:
                     the exact renewal solution X <x> <x^2> Gamma (every
                     0.01 in X), and the maximum deviation of the ME from it
------------------------------------------------------------------------- */

#include "eq_distribution.h"
#include "eq_master_equation.h"
#include "eq_renewal_exact.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace feq;

namespace {

[[noreturn]] void die(const std::string &msg)
{
  std::cerr << "eq-me: ERROR: " << msg << "\n";
  std::exit(1);
}

void usage()
{
  std::cout << "usage: eq-me threshold STYLE values [reform STYLE values] [xmax X] [dx h]\n"
               "             [start relaxed|reform] [crossing exact|step] [richardson yes|no]\n"
               "             [force FILE] [steady FILE] [snapshot X FILE] [summary FILE]\n"
               "             [exact FILE]\n"
               "threshold styles: "
            << role_styles(Role::THRESHOLD) << "\nreform styles:    " << role_styles(Role::REFORM)
            << "\nsee doc/src/eq_me.rst\n";
}

std::ofstream open_out(const std::string &path)
{
  std::ofstream out(path);
  if (!out) die("cannot write file '" + path + "'");
  out << std::setprecision(12);
  return out;
}

}    // namespace

int main(int argc, char **argv)
{
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help") {
    usage();
    return args.empty() ? 2 : 0;
  }

  DistributionSpec thr, ref;
  ref.dist = make_delta(0.0);
  ref.text = "delta 0";
  bool have_thr = false, richardson = false;
  MEOptions opt;
  std::string force_file, steady_file, summary_file, exact_file;
  std::vector<std::pair<double, std::string>> snaps;

  try {
    size_t pos = 0;
    auto need = [&](const std::string &kw, size_t n) {
      if (pos + n > args.size())
        die(kw + ": expected " + std::to_string(n) + " value" + (n > 1 ? "s" : ""));
    };
    auto num = [&](const std::string &kw, const std::string &tok) {
      try {
        return parse_number(tok);
      } catch (SpecError &) {
        die(kw + ": expected a number, got '" + tok + "'");
      }
    };
    while (pos < args.size()) {
      const std::string kw = args[pos++];
      if (kw == "threshold") {
        thr = parse_distribution(Role::THRESHOLD, args, pos, parse_number);
        have_thr = true;
      } else if (kw == "reform") {
        ref = parse_distribution(Role::REFORM, args, pos, parse_number);
      } else if (kw == "xmax") {
        need(kw, 1);
        opt.Xmax = num(kw, args[pos++]);
        if (!(opt.Xmax > 0.0)) die("xmax: must be > 0");
      } else if (kw == "dx") {
        need(kw, 1);
        opt.dx = num(kw, args[pos++]);
        if (!(opt.dx > 0.0)) die("dx: must be > 0");
      } else if (kw == "start") {
        need(kw, 1);
        const std::string v = args[pos++];
        if (v == "relaxed") opt.start = MEStart::RELAXED;
        else if (v == "reform") opt.start = MEStart::REFORM;
        else die("start: unknown value '" + v + "'; allowed: relaxed, reform");
      } else if (kw == "crossing") {
        need(kw, 1);
        const std::string v = args[pos++];
        if (v == "exact") opt.crossing = Crossing::EXACT;
        else if (v == "step") opt.crossing = Crossing::STEP;
        else die("crossing: unknown value '" + v + "'; allowed: exact, step");
      } else if (kw == "richardson") {
        need(kw, 1);
        const std::string v = args[pos++];
        if (v != "yes" && v != "no") die("richardson: allowed values: yes, no");
        richardson = (v == "yes");
      } else if (kw == "force") {
        need(kw, 1);
        force_file = args[pos++];
      } else if (kw == "steady") {
        need(kw, 1);
        steady_file = args[pos++];
      } else if (kw == "summary") {
        need(kw, 1);
        summary_file = args[pos++];
      } else if (kw == "exact") {
        need(kw, 1);
        exact_file = args[pos++];
      } else if (kw == "snapshot") {
        need(kw, 2);
        const double X = num(kw, args[pos++]);
        snaps.emplace_back(X, args[pos++]);
        opt.snapshots.push_back(X);
      } else {
        die("unknown keyword '" + kw +
            "'; allowed: threshold, reform, xmax, dx, start, crossing, richardson, force, "
            "steady, snapshot, summary, exact");
      }
    }
  } catch (const SpecError &e) {
    die(e.what());
  }
  if (!have_thr) die("the threshold keyword is required");
  if (opt.start == MEStart::REFORM && !ref.dist) die("start reform: needs contacts that re-form");
  if (richardson && opt.crossing == Crossing::STEP)
    die("richardson: only with crossing exact (the step model is first order by design)");

  const auto t0 = std::chrono::steady_clock::now();
  MEResult res;
  try {
    res = solve_master_equation(thr.dist, ref.dist, opt);
    if (richardson) {
      MEOptions half = opt;
      half.dx = 0.5 * opt.dx;
      const MEResult fine = solve_master_equation(thr.dist, ref.dist, half);
      for (size_t k = 0; k < res.F.size(); ++k) {
        res.F[k] = (4.0 * fine.F[2 * k] - res.F[k]) / 3.0;
        res.sd[k] = fine.sd[2 * k];
        res.attached[k] = fine.attached[2 * k];
      }
    }
  } catch (const SpecError &e) {
    die(e.what());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::map<std::string, double> summary;
  const Distribution &Pc = *thr.dist;
  summary["threshold_mean"] = Pc.mean();
  summary["threshold_sd"] = std::sqrt(std::max(0.0, Pc.variance()));
  const Extremum peak = static_peak(res);
  const Extremum kstar = critical_stiffness(res);
  summary["static_peak"] = peak.value;
  summary["static_peak_X"] = peak.X;
  summary["kstar"] = kstar.value;
  summary["kstar_X"] = kstar.X;
  summary["force_at_xmax"] = res.F.back();
  summary["mass_error"] = res.max_mass_error;
  summary["seconds"] = seconds;
  summary["dx"] = opt.dx;
  SteadyState ss;
  if (ref.dist) {
    ss = steady_state(Pc, *ref.dist);
    summary["kinetic_force"] = ss.F;
    summary["steady_rate"] = ss.Gamma;
  }

  std::printf("eq-me: master equation of the EQ model (FRICTION-EQ)\n");
  std::printf("  threshold    %s   <x_s> = %.10g, sd = %.6g\n", thr.text.c_str(), Pc.mean(),
              summary["threshold_sd"]);
  std::printf("  reform       %s\n", ref.text.c_str());
  std::printf("  grid         dx = %g, X in [0, %g], %zu stretch points, start %s, crossing %s%s\n",
              opt.dx, opt.Xmax, res.x.size(), opt.start == MEStart::RELAXED ? "relaxed" : "reform",
              opt.crossing == Crossing::EXACT ? "exact" : "step",
              richardson ? ", Richardson (dx, dx/2)" : "");
  std::printf("  static peak  F_s/(N k_c) = %.10f at X = %.6f\n", peak.value, peak.X);
  if (ref.dist)
    std::printf("  kinetic      F_k/(N k_c) = %.10f (stationary solution), Gamma_s = %.10f\n",
                ss.F, ss.Gamma);
  std::printf("  F(xmax)      F/(N k_c)   = %.10f\n", res.F.back());
  std::printf("  stiffness    K*/K_s      = %.10f at X = %.6f\n", kstar.value, kstar.X);
  std::printf("  probability  max |int Q - 1| = %.3g\n", res.max_mass_error);
  std::printf("  time         %.3f s\n", seconds);

  if (!exact_file.empty()) {
    const bool ok = thr.text.rfind("uniform", 0) == 0 && ref.dist && ref.dist->is_point() &&
        ref.dist->mean() == 0.0 && opt.start == MEStart::RELAXED && Pc.lower() > 0.0;
    if (!ok) die("exact: needs threshold uniform lo hi (lo > 0), reform delta 0, start relaxed");
    RenewalUniform exact(Pc.lower(), Pc.upper());
    std::ofstream out = open_out(exact_file);
    out << "# exact renewal solution: X <x> <x^2> Gamma; " << thr.text << "\n";
    double maxerr = 0.0;
    // the exact solution costs ~1e4 times more per point: every 0.01 in X
    const size_t stride = std::max<size_t>(1, (size_t) std::llround(0.01 / opt.dx));
    for (size_t k = 0; k < res.X.size(); k += stride) {
      const double m1 = exact.mean_stretch(res.X[k]);
      out << res.X[k] << " " << m1 << " " << exact.second_moment(res.X[k]) << " "
          << exact.rate(res.X[k]) << "\n";
      maxerr = std::max(maxerr, std::fabs(res.F[k] - m1));
    }
    summary["exact_max_error"] = maxerr;
    std::printf("  exact        max |F_ME - F_exact|/(N k_c) = %.3e\n", maxerr);
  }
  if (!force_file.empty()) {
    std::ofstream out = open_out(force_file);
    out << "# eq-me: threshold " << thr.text << ", reform " << ref.text << ", dx " << opt.dx
        << "\n# X F/(N*kc) sd(x) Gamma attached skewness(x)\n";
    for (size_t k = 0; k < res.X.size(); ++k)
      out << res.X[k] << " " << res.F[k] << " " << res.sd[k] << " " << res.Gamma[k] << " "
          << res.attached[k] << " " << res.skew[k] << "\n";
  }
  if (!steady_file.empty()) {
    if (!ref.dist) die("steady: contacts that never re-form have no steady state");
    std::ofstream out = open_out(steady_file);
    out << "# eq-me steady state: threshold " << thr.text << ", reform " << ref.text
        << "\n# F_k/(N*kc) = " << ss.F << ", Gamma_s = " << ss.Gamma << "\n# x Q_s(x)\n";
    for (size_t i = 0; i < ss.x.size(); ++i) out << ss.x[i] << " " << ss.Q[i] << "\n";
  }
  for (const auto &s : snaps) {
    size_t idx = res.snapX.size();
    for (size_t i = 0; i < res.snapX.size(); ++i)
      if (std::fabs(res.snapX[i] - s.first) <= 0.5 * opt.dx) idx = i;
    if (idx == res.snapX.size()) die("snapshot: X = " + std::to_string(s.first) + " beyond xmax");
    std::ofstream out = open_out(s.second);
    out << "# eq-me Q(x;X) at X = " << res.snapX[idx] << "\n# x Q(x;X)\n";
    for (size_t j = 0; j < res.x.size(); ++j)
      if (res.snapQ[idx][j] != 0.0) out << res.x[j] << " " << res.snapQ[idx][j] << "\n";
  }
  if (!summary_file.empty()) {
    std::ofstream out = open_out(summary_file);
    out << std::setprecision(15);
    for (const auto &kv : summary) out << kv.first << " " << kv.second << "\n";
  }
  return 0;
}
