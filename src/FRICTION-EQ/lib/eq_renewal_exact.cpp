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
   FRICTION-EQ package: exact renewal solution (see eq_renewal_exact.h)
------------------------------------------------------------------------- */

#include "eq_renewal_exact.h"

#include "eq_distribution.h"
#include "eq_master_equation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace feq {

RenewalUniform::RenewalUniform(double a_, double b_) : a(a_), b(b_), w(b_ - a_)
{
  if (!(a > 0.0 && b > a)) throw SpecError("exact renewal solution: need 0 < a < b");
}

double RenewalUniform::J(double y) const
{
  if (y <= a) return 1.0;
  if (y >= b) return 0.0;
  return (b - y) / w;
}

// Irwin-Hall density of the sum of n lifetimes
double RenewalUniform::density(int n, double s) const
{
  long double t = (s - n * a) / w;
  if (t <= 0.0L || t >= n) return 0.0;
  if (t > 0.5L * n) t = n - t;    // symmetric: fewer, smaller terms
  long double sum = 0.0L, binom = 1.0L;
  for (int k = 0; k <= static_cast<int>(std::floor(static_cast<double>(t))); ++k) {
    sum += ((k & 1) ? -1.0L : 1.0L) * binom * std::pow(t - k, (long double) (n - 1));
    binom = binom * (n - k) / (k + 1);
  }
  long double fact = 1.0L;
  for (int k = 2; k < n; ++k) fact *= k;
  return double(sum / fact / w);
}

// The terms n with n a < X, cut where the bound of their contribution,
// t^(n-1)/(n-1)! b/w with t = (X - n a)/w, has dropped below 1e-20 and
// falls for every larger n (n - 1 > t).  The moments and the rate are of
// order b^p and 1/b: relative to them every later term is smaller still.
long RenewalUniform::terms(double X, long cap) const
{
  const double log_tol = std::log(1e-20) - std::log(b / w);
  long n = 0;
  while (n <= cap) {
    const double m = double(n + 1);
    if (!(m * a < X)) break;
    const double t = (X - m * a) / w;
    if (m >= 2.0 && m - 1.0 > t && (m - 1.0) * std::log(t) - std::lgamma(m) < log_tol) break;
    ++n;
  }
  return n;
}

double RenewalUniform::work(double X) const
{
  const long N = terms(X, EXACT_MAX_TERMS);
  double sum = 0.0;
  for (long n = 1; n <= N; ++n) {
    // as moment(): pieces between the kinks within (lo, hi), 2 panels of
    // 10 nodes, each a sum of min(t, n - t) + 1 terms
    const double lo = std::max(n * a, X - b), hi = std::min(X, n * b);
    const double t = std::min((X - n * a) / w, 0.5 * n);
    const double pieces = hi > lo ? std::min(double(n), (hi - lo) / w) + 3.0 : 0.0;
    sum += (2.0 * 20.0 * pieces + 1.0) * (std::floor(std::max(t, 0.0)) + 1.0);
  }
  return sum;
}

double RenewalUniform::lost_digits(double X, double stop) const
{
  const long N = terms(X, EXACT_MAX_TERMS);
  double worst = 0.0;
  for (long n = 2; n <= N && worst <= stop; ++n) {
    // density(): terms C(n,k) (t-k)^(n-1)/(n-1)! for k <= t, t <= n/2;
    // each grows with t, so the largest is at the largest t reached
    const double t = std::min((X - n * a) / w, 0.5 * n);
    const double base = std::lgamma(n + 1.0) - std::lgamma(double(n));
    for (long k = 0; k < t; ++k) {
      const double lt = base - std::lgamma(k + 1.0) - std::lgamma(double(n - k) + 1.0) +
          (n - 1.0) * std::log(t - k);
      worst = std::max(worst, lt / std::log(10.0));
    }
  }
  return worst;
}

double RenewalUniform::rate(double X) const
{
  double g = 0.0;
  const long N = terms(X, std::numeric_limits<int>::max() - 1);
  for (int n = 1; n <= N; ++n) g += density(n, X);
  return g;
}

double RenewalUniform::moment(double X, int p) const
{
  double sum = std::pow(X, p) * J(X);
  const long N = terms(X, std::numeric_limits<int>::max() - 1);
  for (int n = 1; n <= N; ++n) {
    // J(X - s) = 0 below s = X - b: that part adds nothing
    const double lo = std::max(n * a, X - b), hi = std::min(X, n * b);
    if (!(hi > lo)) continue;
    // the kinks n a + k w of f_n within (lo, hi) only (k w < hi - n a)
    std::vector<double> breaks;
    const double kmax = std::min(double(n), std::floor((hi - n * a) / w) + 1.0);
    for (int k = 0; k <= static_cast<int>(kmax); ++k) breaks.push_back(n * a + k * w);
    breaks.push_back(X - a);
    breaks.push_back(X - b);
    sum += integrate([&](double s) { return density(n, s) * std::pow(X - s, p) * J(X - s); }, lo, hi,
                     breaks, 2);
  }
  return sum;
}

}    // namespace feq
