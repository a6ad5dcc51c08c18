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
   FRICTION-EQ package: substrate force of an FK-ME block (eq_substrate.h)
------------------------------------------------------------------------- */

#include "eq_substrate.h"
#include "eq_text.h"

#include "eq_distribution.h"    // SpecError
#include "eq_random.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace feq {

namespace {
std::string num(double v) { return format_number(v, 10); }
}    // namespace

SubstrateShape SubstrateShape::sawtooth(double uc)
{
  if (!(uc > 0.0) || !std::isfinite(uc)) throw SpecError("sawtooth: need uc > 0 (got " + num(uc) + ")");
  SubstrateShape s;
  s.kind_ = SAWTOOTH;
  s.uc = uc;
  s.text = "sawtooth (uc = " + num(uc) + ")";
  s.finish();
  return s;
}

SubstrateShape SubstrateShape::smooth(double uc)
{
  if (!(uc > 0.0) || !std::isfinite(uc)) throw SpecError("smooth: need uc > 0 (got " + num(uc) + ")");
  SubstrateShape s;
  s.kind_ = SMOOTH;
  s.uc = uc;
  s.text = "smooth (uc = " + num(uc) + ")";
  s.finish();
  return s;
}

SubstrateShape SubstrateShape::table(const std::vector<double> &v, const std::vector<double> &phi,
                                     const std::string &label)
{
  const size_t n = v.size();
  if (n < 2 || phi.size() != n)
    throw SpecError("table " + label + ": need at least 2 points (u, phi)");
  if (v[0] != 0.0)
    throw SpecError("table " + label + ": the first point must be u = 0 (got " + num(v[0]) + ")");
  for (size_t k = 1; k < n; ++k)
    if (!(v[k] > v[k - 1]))
      throw SpecError("table " + label + ": u must increase (point " + std::to_string(k + 1) +
                      ": u = " + num(v[k]) + " after " + num(v[k - 1]) + ")");
  for (size_t k = 0; k < n; ++k)
    if (!std::isfinite(phi[k]))
      throw SpecError("table " + label + ": phi at point " + std::to_string(k + 1) + " is not finite");
  SubstrateShape s;
  s.kind_ = TABLE;
  s.uc = v.back();
  s.tv = v;
  s.tphi = phi;
  s.tV.assign(n, 0.0);
  for (size_t k = 1; k < n; ++k)
    s.tV[k] = s.tV[k - 1] + 0.5 * (phi[k] + phi[k - 1]) * (v[k] - v[k - 1]);
  s.text = "table " + label + " (uc = " + num(s.uc) + ", " + std::to_string(n) + " points)";
  s.finish();
  return s;
}

void SubstrateShape::finish()
{
  W = V0(uc);
  if (kind_ == SAWTOOTH) {
    phimax = uc;    // supremum, approached at the end of the period
    vmax = uc;
  } else if (kind_ == TABLE) {
    const auto it = std::max_element(tphi.begin(), tphi.end());
    phimax = *it;
    vmax = tv[it - tphi.begin()];
  } else {
    // fine scan, then golden-section refinement around the best point
    const int n = 4000;
    int best = 0;
    double pb = phi0(0.0);
    for (int k = 1; k < n; ++k) {
      const double p = phi0(uc * k / n);
      if (p > pb) pb = p, best = k;
    }
    double a = uc * std::max(0, best - 1) / n, b = uc * std::min(n - 1, best + 1) / n;
    const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 100 && b - a > 1e-15 * uc; ++it) {
      const double c = b - gr * (b - a), d = a + gr * (b - a);
      if (phi0(c) > phi0(d)) b = d;
      else a = c;
    }
    vmax = 0.5 * (a + b);
    phimax = std::max(pb, phi0(vmax));
  }
}

void SubstrateShape::reduce(double u, double &n, double &r) const
{
  n = std::floor(u / uc);
  r = u - n * uc;
  // rounding can put r at u_c (or just below 0): keep 0 <= r < u_c
  if (r >= uc) {
    r -= uc;
    n += 1.0;
  }
  if (r < 0.0) r = 0.0;
}

double SubstrateShape::phi0(double r) const
{
  switch (kind_) {
    case SAWTOOTH: return r;
    case SMOOTH: return std::tanh(r) + 1.5 * std::exp(-r) * std::sin(3.0 * r);
    default: {
      const size_t k = std::upper_bound(tv.begin(), tv.end(), r) - tv.begin();
      if (k == 0) return tphi.front();
      if (k >= tv.size()) return tphi.back();
      const double t = (r - tv[k - 1]) / (tv[k] - tv[k - 1]);
      return tphi[k - 1] + t * (tphi[k] - tphi[k - 1]);
    }
  }
}

double SubstrateShape::V0(double r) const
{
  switch (kind_) {
    case SAWTOOTH: return 0.5 * r * r;
    case SMOOTH: {
      // int_0^r tanh = log cosh r (in a form that does not overflow);
      // int_0^r e^{-s} sin 3s ds = [3 - e^{-r} (sin 3r + 3 cos 3r)] / 10
      const double lc = r + std::log1p(std::exp(-2.0 * r)) - std::log(2.0);
      return lc + 0.15 * (3.0 - std::exp(-r) * (std::sin(3.0 * r) + 3.0 * std::cos(3.0 * r)));
    }
    default: {
      const size_t k = std::upper_bound(tv.begin(), tv.end(), r) - tv.begin();
      if (k == 0) return 0.0;
      if (k >= tv.size()) return tV.back();
      const double h = r - tv[k - 1];
      const double slope = (tphi[k] - tphi[k - 1]) / (tv[k] - tv[k - 1]);
      return tV[k - 1] + h * (tphi[k - 1] + 0.5 * slope * h);
    }
  }
}

double SubstrateShape::phi(double u) const
{
  double n, r;
  reduce(u, n, r);
  return phi0(r);
}

double SubstrateShape::potential(double u) const
{
  double n, r;
  reduce(u, n, r);
  return n * W + V0(r);
}

std::string substrate_table_text(const std::string &keyword, const std::vector<double> &v,
                                 const std::vector<double> &phi, const std::string &comment)
{
  std::ostringstream out;
  out << std::setprecision(12);
  std::istringstream lines(comment);
  std::string line;
  while (std::getline(lines, line)) out << "# " << line << "\n";
  out << "\n" << keyword << "\nN " << v.size() << "\n\n";
  for (size_t k = 0; k < v.size(); ++k) out << k + 1 << " " << v[k] << " " << phi[k] << "\n";
  return out.str();
}

RateLaw::RateLaw(double A, double v0) : A_(A), v0_(v0)
{
  if (!(A >= 0.0) || !std::isfinite(A))
    throw SpecError("rate A: must be finite and >= 0 (got " + num(A) + ")");
  if (!(A <= A_MAX))
    throw SpecError("rate A: " + num(A) + " would make the rate force A asinh(w/(2 v0)) overflow; "
                    "allowed: A <= " + num(A_MAX));
  if (!(v0 > 0.0) || !std::isfinite(v0))
    throw SpecError("rate v0: must be finite and > 0 (got " + num(v0) + ")");
}

// asinh(x) of the C library: odd, accurate to an ulp or two for all x
// (no cancellation at small x, no overflow of x^2 at large x); where
// w / (2 v0) overflows (v0 < 1/2), asinh x = ln 2 + ln |x| + O(1/x^2)
// from the logarithms of its factors
double RateLaw::force(double w) const
{
  const double x = w / (2.0 * v0_);
  if (std::isfinite(x) || !std::isfinite(w)) return A_ * std::asinh(x);
  const double lnx = std::log(std::fabs(w)) - std::log(2.0 * v0_);
  return std::copysign(A_ * (std::log(2.0) + lnx), w);
}

// A / sqrt(w^2 + 4 v0^2) with hypot: no overflow of w^2
double RateLaw::slope(double w) const
{
  return A_ / std::hypot(w, 2.0 * v0_);
}

BlockHops::BlockHops(const ThermalSpec &spec, double uc_, uint64_t seed_) :
    model(spec), uc(uc_), seed(seed_)
{
}

double BlockHops::budget(uint64_t tag, uint64_t life) const
{
  return exponential(draw(seed, tag, life, STREAM_BUDGET));
}

void BlockHops::new_life(uint64_t tag, HopState &st) const
{
  st.life += 1.0;
  st.budget = budget(tag, static_cast<uint64_t>(st.life));
}

/* ----------------------------------------------------------------------
   the step is walked in pieces [f, 1] of its duration, as ContactModel::
   advance() walks a contact's: a piece ends where the stretch reaches
   +-u_c, where the hazard (Simpson's rule over the piece) exhausts the
   budget, whichever comes first, or at the end of the step
------------------------------------------------------------------------- */

int BlockHops::step(uint64_t tag, double u0, double u1, double d, double dt, bool exact,
                    HopState &st, WellChange *changes) const
{
  const double motion = u1 - u0;    // per unit fraction of the step
  const double xs = uc * d;         // the law in units of k_c: x = d s, x_s = d u_c
  double s_a = u0 - st.anchor;
  double f = 0.0;
  int n = 0;
  while (true) {
    const double h = (1.0 - f) * dt;
    const double s_b = f == 0.0 ? u1 - st.anchor : s_a + motion * (1.0 - f);
    double g = 1.0;    // fraction of the piece at which the block leaves its well
    int sign = 0;
    bool thermal = false;
    if (s_b >= uc) {
      g = s_a < uc ? (uc - s_a) / (s_b - s_a) : 0.0;
      sign = 1;
    } else if (s_b <= -uc) {
      g = s_a > -uc ? (-uc - s_a) / (s_b - s_a) : 0.0;
      sign = -1;
    }
    if (h > 0.0 && model.params().thermal()) {
      const double s_g = g == 1.0 ? s_b : s_a + (s_b - s_a) * g;
      RatePoint start, end;
      start = model.point(s_a * d, xs);
      const double dH = model.hazard(s_a * d, s_g * d, 0.0, h * g, xs, &start, &end);
      if (dH > 0.0 && dH >= st.budget) {    // first: where the budget runs out
        g *= ThermalModel::budget_fraction(st.budget / dH, start, end);
        thermal = true;
      } else {
        st.budget -= dH;
      }
    }
    if (sign == 0 && !thermal) return n;
    // the change, at fraction fb of the step (the end with crossing step)
    const double fb = exact ? std::min(1.0, f + g * (1.0 - f)) : 1.0;
    const double s_c = fb == 1.0 ? u1 - st.anchor : s_a + motion * (fb - f);
    if (thermal) sign = s_c >= 0.0 ? 1 : -1;
    if (n >= MAX_CHANGES)
      throw SpecError("block " + std::to_string(tag) + " changed wells more than " +
                      std::to_string(MAX_CHANGES) + " times in one step (from u = " + num(u0) +
                      " to " + num(u1) + ", hop rate " + num(rate(0.0, d)) +
                      " at zero stretch): reduce the timestep or the attempt frequency omega");
    changes[n].theta = fb;
    changes[n].sign = sign;
    changes[n].thermal = thermal;
    ++n;
    st.anchor += sign * uc;
    if (thermal) st.hops += 1.0;
    new_life(tag, st);
    s_a = fb == 1.0 ? u1 - st.anchor : s_c - sign * uc;
    f = fb;
  }
}

}    // namespace feq
