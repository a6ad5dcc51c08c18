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
   FRICTION-EQ package: the keywords of temperature, aging and delays
   (see eq_thermal.h)
------------------------------------------------------------------------- */

#include "eq_thermal.h"

#include "eq_keywords.h"

#include <sstream>

namespace feq {

namespace {
double at_least(const std::vector<std::string> &args, size_t &iarg, const std::string &what,
                const NumberParser &number, double lo, bool strict)
{
  const double v = parse_finite(args, iarg, what, number);
  if (strict ? !(v > lo) : !(v >= lo)) {
    std::ostringstream o;
    o << what << ": must be " << (strict ? "> " : ">= ") << lo << " (got " << args[iarg - 1]
      << ")";
    throw SpecError(o.str());
  }
  return v;
}
}    // namespace

bool parse_thermal_keyword(const std::string &kw, const std::vector<std::string> &args,
                           size_t &iarg, const NumberParser &number, ThermalKeywords &t)
{
  ThermalSpec &s = t.spec;
  if (kw == "thermal") {
    t.temperature = at_least(args, iarg, "thermal T", number, 0.0, false);
    t.eps_a = at_least(args, iarg, "thermal eps_a", number, 0.0, true);
    s.omega = at_least(args, iarg, "thermal omega", number, 0.0, true);
  } else if (kw == "barrier") {
    s.p = at_least(args, iarg, "barrier p", number, 0.0, false);
    s.q = at_least(args, iarg, "barrier q", number, 0.0, false);
  } else if (kw == "aging") {
    const int law = parse_choice(args, iarg, kw, {"none", "log", "exp"});
    s.aging = law == 0 ? AgingLaw::NONE : law == 1 ? AgingLaw::LOG : AgingLaw::EXP;
    if (law != 0) {
      s.beta = at_least(args, iarg, "aging beta", number, 0.0, false);
      s.tau_a = at_least(args, iarg, "aging tau_a", number, 0.0, true);
    }
  } else if (kw == "delay") {
    const int kind = parse_choice(args, iarg, kw, {"none", "fixed", "exp"});
    s.delay = kind == 0 ? DelayKind::NONE : kind == 1 ? DelayKind::FIXED : DelayKind::EXPONENTIAL;
    s.tau = kind == 0 ? 0.0 : at_least(args, iarg, "delay tau", number, 0.0, false);
  } else if (kw == "rest") {
    s.rest = at_least(args, iarg, "rest t_w", number, 0.0, false);
  } else {
    return false;
  }
  return true;
}

ThermalSpec ThermalKeywords::finish(double boltz, double xc) const
{
  ThermalSpec s = spec;
  s.theta = boltz * temperature / eps_a;
  if (!std::isfinite(s.theta))
    throw SpecError("thermal: k_B T / eps_a is not finite (T = " + std::to_string(temperature) +
                    ", eps_a = " + std::to_string(eps_a) + ")");
  s.xc = xc;
  return s;
}

std::string ThermalKeywords::text() const
{
  std::ostringstream o;
  o.precision(6);
  if (temperature > 0.0)
    o << "thermal T " << temperature << " eps_a " << eps_a << " omega " << spec.omega
      << " barrier " << spec.p << " " << spec.q << "; ";
  if (spec.aging != AgingLaw::NONE)
    o << "aging " << (spec.aging == AgingLaw::LOG ? "log" : "exp") << " beta " << spec.beta
      << " tau_a " << spec.tau_a << "; ";
  if (spec.delay != DelayKind::NONE && spec.tau > 0.0)
    o << "delay " << (spec.delay == DelayKind::FIXED ? "fixed" : "exp") << " " << spec.tau
      << "; ";
  if (spec.rest > 0.0) o << "rest " << spec.rest << "; ";
  std::string r = o.str();
  if (r.size() >= 2) r.resize(r.size() - 2);
  return r;
}

}    // namespace feq
