/* -*- c++ -*- ----------------------------------------------------------
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
   FRICTION-EQ package: temperature, velocity and aging of EQ contacts
   (Braun & Peyrard, PRE 83, 046129 (2011); the forms are the package's,
   see doc/src/fix_eq_contacts.rst).  LAMMPS-free.

   Thermally activated breaking: a contact at stretch |x| below its
   threshold x_s crosses a barrier E = eps_a (x_s/x_c)^p u^(3/2),
   u = 1 - |x|/x_s, at the rate nu = omega u^q exp(-E/k_B T); with
   theta = k_B T / eps_a, nu = omega u^q exp(-(x_s/x_c)^p u^(3/2)/theta).
   x_c is the mean threshold.  |x| >= x_s breaks at once, as at T = 0.

   Aging: the threshold grows with the contact's age t (time since it
   formed): x_s(t) = x_s0 A(t), A = 1 + beta ln(1 + t/tau_a) (log) or
   1 + beta (1 - exp(-t/tau_a)) (exp); the barrier uses x_s(t).  A broken
   contact may stay absent for a delay tau (fixed, or exponential with
   mean tau) before it re-forms.
------------------------------------------------------------------------- */

#ifndef FEQ_THERMAL_H
#define FEQ_THERMAL_H

#include "eq_distribution.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace feq {

enum class AgingLaw { NONE, LOG, EXP };
enum class DelayKind { NONE, FIXED, EXPONENTIAL };

struct ThermalSpec {
  double theta = 0.0;    // k_B T / eps_a; 0: athermal
  double omega = 1.0;    // attempt frequency (1/time)
  double p = 0.0;        // barrier scale (x_s/x_c)^p
  double q = 0.0;        // prefactor u^q
  double xc = 1.0;       // mean threshold (set from P_c)
  AgingLaw aging = AgingLaw::NONE;
  double beta = 0.0, tau_a = 1.0;
  DelayKind delay = DelayKind::NONE;
  double tau = 0.0;      // (mean) delay
  double rest = 0.0;     // age of the contacts when the fix is defined

  bool thermal() const { return theta > 0.0; }
  // anything beyond the athermal, ageless, instant-reform model
  bool active() const
  {
    return thermal() || aging != AgingLaw::NONE || (delay != DelayKind::NONE && tau > 0.0) ||
        rest > 0.0;
  }
};

// the breaking rate at one point of a contact's path: nu and, where the
// barrier is not yet 0 (u > 0), its logarithm psi = ln nu
struct RatePoint {
  double nu = 0.0;
  double psi = 0.0;
  bool smooth = false;    // u > 0: psi is ln nu
};

class ThermalModel {
 public:
  explicit ThermalModel(const ThermalSpec &s) :
      spec(s), inv_theta(s.theta > 0.0 ? 1.0 / s.theta : 0.0),
      inv_xc(s.xc > 0.0 ? 1.0 / s.xc : 1.0), ln_omega(std::log(s.omega)),
      top_rate(std::exp(ln_omega) * (1.0 + 1e-8))
  {
  }
  const ThermalSpec &params() const { return spec; }
  double log_omega() const { return ln_omega; }

  // threshold factor A(t) at age t >= 0 (A >= 1, increasing)
  double factor(double age) const
  {
    switch (spec.aging) {
      case AgingLaw::LOG: return 1.0 + spec.beta * std::log1p(age / spec.tau_a);
      case AgingLaw::EXP: return 1.0 - spec.beta * std::expm1(-age / spec.tau_a);
      default: return 1.0;
    }
  }

  // breaking rate at stretch |x| with current threshold xs; 0 at T = 0
  double rate(double x, double xs) const
  {
    if (!(spec.theta > 0.0)) return 0.0;
    return point(x, xs).nu;
  }

  // the rate at stretch x, threshold xs (theta > 0)
  RatePoint point(double x, double xs) const { return point_u(1.0 - std::fabs(x) / xs, xs); }

  // the rate at u = 1 - |x|/xs (theta > 0)
  RatePoint point_u(double u, double xs) const
  {
    RatePoint r;
    if (!(u > 0.0)) {    // at or beyond the threshold: the barrier is 0
      r.nu = spec.q > 0.0 ? 0.0 : spec.omega;
      return r;
    }
    r.psi = log_rate(u, xs);
    r.nu = std::exp(r.psi);
    r.smooth = std::isfinite(r.psi);    // (not with a rate of 0 from extreme exponents)
    return r;
  }

  // the rate at the start of a step: stretch x0, age a0, threshold x_s0 A(a0)
  RatePoint start_point(double x0, double a0, double xs0) const
  {
    return point(x0, spec.aging != AgingLaw::NONE ? xs0 * factor(a0) : xs0);
  }

  // the fraction of a step at which a budget r dH is used up, out of the
  // step's hazard dH (0 < r <= 1), for a rate that grows exponentially
  // from p0 to p1 over the step (exact for such a rate; linear, r, for a
  // constant one)
  static double budget_fraction(double r, const RatePoint &p0, const RatePoint &p1)
  {
    if (!(p0.smooth && p1.smooth)) return r;
    const double d = p1.psi - p0.psi;    // ln(nu1/nu0)
    if (!(std::fabs(d) > 1e-8)) return r;
    const double g = std::log1p(r * std::expm1(d)) / d;
    return g > 0.0 && g <= 1.0 ? g : r;
  }

  // hazard accumulated over a time h while the stretch goes linearly from
  // x0 to x1 and the age from a0 to a0 + h (Simpson's rule).  start: the
  // point at (x0, a0) when known (else nullptr); end (if not null)
  // receives the point at (x1, a0 + h).  The midpoint rate is
  // sqrt(nu0 nu1) exp(psi_m - (psi0 + psi1)/2): an identity, one
  // exponential less per step (a series where the bracket is small)
  double hazard(double x0, double x1, double a0, double h, double xs0,
                const RatePoint *start = nullptr, RatePoint *end = nullptr) const
  {
    if (!(spec.theta > 0.0) || !(h > 0.0)) return 0.0;
    const bool aging = spec.aging != AgingLaw::NONE;
    const double xs1 = aging ? xs0 * factor(a0 + h) : xs0;
    const double xsm = aging ? xs0 * factor(a0 + 0.5 * h) : xs0;
    // one division without aging (one threshold over the step)
    const double inv1 = 1.0 / xs1, invm = aging ? 1.0 / xsm : inv1;
    const RatePoint p0 = start ? *start : start_point(x0, a0, xs0);
    const RatePoint p1 = point_u(1.0 - std::fabs(x1) * inv1, xs1);
    if (end) *end = p1;
    const double xm = 0.5 * (x0 + x1);
    const double um = 1.0 - std::fabs(xm) * invm;
    double num;
    if (p0.smooth && p1.smooth && um > 0.0)
      num = std::sqrt(p0.nu * p1.nu) * exp_small(log_rate(um, xsm) - 0.5 * (p0.psi + p1.psi));
    else
      num = point(xm, xsm).nu;
    return h / 6.0 * (p0.nu + 4.0 * num + p1.nu);
  }

  // thinning of the break process (fix eq/contacts): a bound of the
  // rate, the largest nu at any stretch |x| <= s with any threshold
  // >= xs (theta > 0).  With u = 1 - |x|/x_s >= u_min = 1 - s/xs and the
  // barrier scale (x_s/x_c)^p >= (xs/x_c)^p (p >= 0), nu <= omega g(u),
  // g(u) = u^q exp(-c u^(3/2)), c = (xs/x_c)^p/theta, whose largest value
  // on [u_min, 1] is at u_min (q = 0), else at the peak
  // u* = (2q/(3c))^(2/3) clamped to [u_min, 1].  s >= xs: the largest
  // rate of all.  A relative margin of 1e-8 covers rounding.
  double rate_bound(double s, double xs) const
  {
    const double c = barrier_scale(xs) * inv_theta;
    // the top of a life's ladder (s >= xs, q = 0): e^(ln omega - c 0) margined, kept
    if (spec.q == 0.0 && !(s < xs) && std::isfinite(c)) return top_rate;
    double u = s < xs ? 1.0 - s / xs : 0.0;
    if (spec.q > 0.0) u = std::min(1.0, std::max(u, std::pow(2.0 * spec.q / (3.0 * c), 2.0 / 3.0)));
    const double pre = spec.q == 0.0 ? ln_omega : ln_omega + spec.q * std::log(u);
    return std::exp(pre - c * u * std::sqrt(u)) * (1.0 + 1e-8);
  }

  // ln nu at stretch x, threshold xs (theta > 0), to rounding; +infinity
  // at or beyond the threshold (where the barrier is 0)
  double log_rate_at(double x, double xs) const
  {
    const double u = 1.0 - std::fabs(x) / xs;
    if (!(u > 0.0)) return HUGE_VAL;
    const double pre = spec.q == 0.0 ? ln_omega : ln_omega + spec.q * std::log(u);
    return pre - barrier_scale(xs) * u * std::sqrt(u) * inv_theta;
  }

  // d ln nu / d|x| at stretch x, threshold xs (theta > 0, |x| < xs)
  double log_rate_slope(double x, double xs) const
  {
    const double u = 1.0 - std::fabs(x) / xs;
    const double g = 1.5 * barrier_scale(xs) * std::sqrt(u) * inv_theta;
    return (spec.q == 0.0 ? g : g - spec.q / u) / xs;
  }

  // ln omega - c u^(3/2): ln nu without the prefactor u^q <= 1 (an upper
  // bound of ln nu, increasing in |x|), +infinity at or beyond the
  // threshold (slope then unset); slope: its derivative in |x| (theta > 0)
  double log_barrier_rate_at(double x, double xs, double &slope) const
  {
    const double u = 1.0 - std::fabs(x) / xs;
    if (!(u > 0.0)) return HUGE_VAL;
    const double scale = barrier_scale(xs), root = std::sqrt(u);
    slope = 1.5 * scale * root * inv_theta / xs;
    return ln_omega - scale * u * root * inv_theta;
  }

  // the stretch |x| at which ln(omega) - c u^(3/2) (ln nu without the
  // prefactor u^q <= 1) equals L, threshold xs: where a bound of rate
  // about e^L can end; +infinity when L >= ln omega (any stretch),
  // negative when even |x| = 0 has a larger rate
  double bound_stretch(double L, double xs) const
  {
    if (!(L < ln_omega)) return HUGE_VAL;
    const double w = (ln_omega - L) / (barrier_scale(xs) * inv_theta);    // u^(3/2)
    return xs * (1.0 - std::cbrt(w * w));
  }

 private:
  ThermalSpec spec;
  double inv_theta, inv_xc, ln_omega;
  double top_rate;    // rate_bound() at s >= xs for q = 0

  // the barrier scale (x_s/x_c)^p at threshold xs (to rounding: the
  // bounds above carry a margin)
  double barrier_scale(double xs) const
  {
    if (spec.p == 0.0) return 1.0;
    const double r = xs * inv_xc;
    return spec.p == 2.0 ? r * r : spec.p == 1.0 ? r : std::pow(r, spec.p);
  }

  // ln nu at u = 1 - |x|/xs > 0
  double log_rate(double u, double xs) const
  {
    const double scale = spec.p == 0.0 ? 1.0 : std::pow(xs * inv_xc, spec.p);
    const double pre = spec.q == 0.0 ? ln_omega : ln_omega + spec.q * std::log(u);
    return pre - scale * u * std::sqrt(u) * inv_theta;
  }

  // e^d: a Taylor series to rounding for |d| < 2^-8, else std::exp
  static double exp_small(double d)
  {
    if (!(std::fabs(d) < 0.00390625)) return std::exp(d);
    return 1.0 + d * (1.0 + d * (0.5 + d * (1.0 / 6.0 + d * (1.0 / 24.0 + d * (1.0 / 120.0 +
                d * (1.0 / 720.0))))));
  }
};

/* ----------------------------------------------------------------------
   the keywords shared by fix eq/contacts and eq/me:
     thermal T eps_a omega     theta = k_B T / eps_a, attempt frequency
     barrier p q               exponents of the barrier scale and prefactor (0 0)
     aging none | log beta tau_a | exp beta tau_a
     delay none | fixed tau | exp tau
     rest t_w                  age of the contacts at the start
------------------------------------------------------------------------- */

struct ThermalKeywords {
  double temperature = 0.0, eps_a = 1.0;
  ThermalSpec spec;    // theta set by finish()
  // theta = boltz T / eps_a; xc: the mean threshold
  ThermalSpec finish(double boltz, double xc) const;
  // the settings in words (for the log), "" when none is on
  std::string text() const;
};

// kw = args[iarg - 1]: false when it is not one of the keywords above;
// else its values are parsed (iarg moves on; SpecError names the keyword)
bool parse_thermal_keyword(const std::string &kw, const std::vector<std::string> &args,
                           size_t &iarg, const NumberParser &number, ThermalKeywords &t);

constexpr const char *THERMAL_KEYWORDS = "thermal, barrier, aging, delay, rest";

}    // namespace feq

#endif
