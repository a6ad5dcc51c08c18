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

class ThermalModel {
 public:
  explicit ThermalModel(const ThermalSpec &s) :
      spec(s), inv_theta(s.theta > 0.0 ? 1.0 / s.theta : 0.0),
      inv_xc(s.xc > 0.0 ? 1.0 / s.xc : 1.0)
  {
  }
  const ThermalSpec &params() const { return spec; }

  // threshold factor A(t) at age t >= 0
  double factor(double age) const
  {
    switch (spec.aging) {
      case AgingLaw::LOG: return 1.0 + spec.beta * std::log1p(age / spec.tau_a);
      case AgingLaw::EXP: return 1.0 - spec.beta * std::expm1(-age / spec.tau_a);
      default: return 1.0;
    }
  }

  // breaking rate at stretch |x| < xs (current threshold); 0 at T = 0
  double rate(double x, double xs) const
  {
    if (!(spec.theta > 0.0)) return 0.0;
    return rate_u(1.0 - std::fabs(x) / xs, xs);
  }

  // the rate at stretch x and age a of a contact with threshold x_s0 A(a)
  // (the value the hazard uses at either end of a step)
  double rate_at(double x, double a, double xs0) const
  {
    if (!(spec.theta > 0.0)) return 0.0;
    if (spec.aging == AgingLaw::NONE) return rate_u(1.0 - std::fabs(x) * (1.0 / xs0), xs0);
    return rate(x, xs0 * factor(a));
  }

  // hazard accumulated over a time h while the stretch goes linearly from
  // x0 to x1 and the age from a0 to a0 + h (Simpson's rule).  nu0: the
  // rate at the start, rate_at(x0, a0, xs0), when known (else NaN); nu1
  // (if not null) receives rate_at(x1, a0 + h, xs0)
  double hazard(double x0, double x1, double a0, double h, double xs0,
                double nu0 = std::nan(""), double *nu1 = nullptr) const
  {
    if (!(spec.theta > 0.0) || !(h > 0.0)) return 0.0;
    if (std::isnan(nu0)) nu0 = rate_at(x0, a0, xs0);
    const double nm = rate_at(0.5 * (x0 + x1), a0 + 0.5 * h, xs0);
    const double n1 = rate_at(x1, a0 + h, xs0);
    if (nu1) *nu1 = n1;
    return h / 6.0 * (nu0 + 4.0 * nm + n1);
  }

 private:
  ThermalSpec spec;
  double inv_theta, inv_xc;

  // the rate at u = 1 - |x|/xs (theta > 0)
  double rate_u(double u, double xs) const
  {
    if (!(u > 0.0)) return spec.q > 0.0 ? 0.0 : spec.omega;
    const double scale = spec.p == 0.0 ? 1.0 : std::pow(xs * inv_xc, spec.p);
    const double pre = spec.q == 0.0 ? spec.omega : spec.omega * std::pow(u, spec.q);
    return pre * std::exp(-scale * u * std::sqrt(u) * inv_theta);
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
