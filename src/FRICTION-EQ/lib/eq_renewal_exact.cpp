/* ----------------------------------------------------------------------
   FRICTION-EQ package: exact renewal solution (see eq_renewal_exact.h)
------------------------------------------------------------------------- */

#include "eq_renewal_exact.h"

#include "eq_distribution.h"
#include "eq_master_equation.h"

#include <cmath>

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
  for (int k = 0; k <= (int) std::floor((double) t); ++k) {
    sum += ((k & 1) ? -1.0L : 1.0L) * binom * std::pow(t - k, (long double) (n - 1));
    binom = binom * (n - k) / (k + 1);
  }
  long double fact = 1.0L;
  for (int k = 2; k < n; ++k) fact *= k;
  return double(sum / fact / w);
}

double RenewalUniform::rate(double X) const
{
  double g = 0.0;
  for (int n = 1; n * a < X; ++n) g += density(n, X);
  return g;
}

double RenewalUniform::moment(double X, int p) const
{
  double sum = std::pow(X, p) * J(X);
  for (int n = 1; n * a < X; ++n) {
    std::vector<double> breaks;
    for (int k = 0; k <= n; ++k) breaks.push_back(n * a + k * w);
    breaks.push_back(X - a);
    breaks.push_back(X - b);
    const double lo = n * a, hi = std::min(X, n * b);
    sum += integrate([&](double s) { return density(n, s) * std::pow(X - s, p) * J(X - s); }, lo, hi,
                     breaks, 2);
  }
  return sum;
}

}    // namespace feq
