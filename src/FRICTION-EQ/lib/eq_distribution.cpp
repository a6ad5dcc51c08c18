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
   FRICTION-EQ package: distributions (see eq_distribution.h)
------------------------------------------------------------------------- */

#include "eq_distribution.h"
#include "eq_text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include <sys/stat.h>

namespace feq {

namespace {

const double INF = std::numeric_limits<double>::infinity();
const double NaN = std::numeric_limits<double>::quiet_NaN();
const double SQRTPI = 1.7724538509055160273;
const double SQRT2 = 1.4142135623730950488;
const double INV_SQRT2PI = 0.39894228040143267794;
const double EPS = std::numeric_limits<double>::epsilon();

std::string fmtnum(double v) { return format_number(v, 10); }

double clamp(double x, double lo, double hi)
{
  return x < lo ? lo : (x > hi ? hi : x);
}

// yes ? a : b by the bits (compilers turn the plain conditional into a branch)
double select_bits(bool yes, double a, double b)
{
  uint64_t ia, ib;
  std::memcpy(&ia, &a, sizeof ia);
  std::memcpy(&ib, &b, sizeof ib);
  const uint64_t m = uint64_t(0) - static_cast<uint64_t>(yes);
  const uint64_t r = (ia & m) | (ib & ~m);
  double out;
  std::memcpy(&out, &r, sizeof out);
  return out;
}

double normal_pdf(double z)
{
  return INV_SQRT2PI * std::exp(-0.5 * z * z);
}

// int Phi_c(z) dz = z Phi_c(z) - phi(z)   (finite at both ends)
double normal_sf_antideriv(double z)
{
  if (z == -INF) return -INF;
  if (z == INF) return 0.0;
  return z * normal_sf(z) - normal_pdf(z);
}

/* ---------------------------------------------------------------------- */

class UniformDist final : public Distribution {
 public:
  UniformDist(double a, double b) : a(a), b(b), w(b - a) {}
  DistKind kind() const override { return DistKind::UNIFORM; }
  std::string describe() const override { return "uniform " + fmtnum(a) + " " + fmtnum(b); }
  double lower() const override { return a; }
  double upper() const override { return b; }
  double pdf(double x) const override { return (x >= a && x <= b) ? 1.0 / w : 0.0; }
  double cdf(double x) const override { return clamp((x - a) / w, 0.0, 1.0); }
  double sf(double x) const override { return clamp((b - x) / w, 0.0, 1.0); }
  double quantile(double p) const override { return a + clamp(p, 0.0, 1.0) * w; }
  double isf(double q) const override { return b - clamp(q, 0.0, 1.0) * w; }
  // Distribution::sample()'s numbers: both tails computed, one chosen
  // without a branch (u < 1/2 is a coin flip the processor cannot predict;
  // a break of fix eq/contacts draws its threshold here)
  double sample(const Uniform &u) const override
  {
    return select_bits(u.u < 0.5, isf(u.u), quantile(u.one_minus_u));
  }
  double sf_integral(double lo, double hi) const override { return G(hi) - G(lo); }
  double partial_mean(double lo, double hi) const override
  {
    lo = clamp(lo, a, b);
    hi = clamp(hi, a, b);
    return (hi * hi - lo * lo) / (2.0 * w);
  }
  double mean() const override { return 0.5 * (a + b); }
  double second_moment() const override { return (a * a + a * b + b * b) / 3.0; }
  std::vector<double> breakpoints() const override { return {a, b}; }

 private:
  double a, b, w;
  // antiderivative of sf, continuous, G(a) = a
  double G(double x) const
  {
    if (x <= a) return x;
    if (x >= b) return a + 0.5 * w;
    const double t = x - a;
    return a + t - t * t / (2.0 * w);
  }
};

/* ---------------------------------------------------------------------- */

class GaussianDist : public Distribution {
 public:
  GaussianDist(double mu, double sd, double trunc) : mu(mu), sd(sd), L(trunc)
  {
    zL = (L == -INF) ? -INF : (L - mu) / sd;
    Z = (L == -INF) ? 1.0 : normal_sf(zL);
    PhiL = (L == -INF) ? 0.0 : normal_cdf(zL);
  }
  DistKind kind() const override { return DistKind::GAUSSIAN; }
  std::string describe() const override
  {
    std::string s = "gaussian " + fmtnum(mu) + " " + fmtnum(sd);
    if (L != -INF) s += " (truncated to x > " + fmtnum(L) + ")";
    return s;
  }
  double lower() const override { return L; }
  double upper() const override { return INF; }
  double pdf(double x) const override
  {
    if (x < L) return 0.0;
    return normal_pdf((x - mu) / sd) / (sd * Z);
  }
  double cdf(double x) const override
  {
    if (x <= L) return 0.0;
    const double z = (x - mu) / sd;
    if (z < 0.0) return (normal_cdf(z) - PhiL) / Z;
    return 1.0 - normal_sf(z) / Z;
  }
  double sf(double x) const override
  {
    if (x <= L) return 1.0;
    const double z = (x - mu) / sd;
    if (z > 0.0) return normal_sf(z) / Z;
    return 1.0 - (normal_cdf(z) - PhiL) / Z;
  }
  double quantile(double p) const override
  {
    if (p <= 0.0) return L;
    if (p >= 1.0) return INF;
    const double target = PhiL + p * Z;    // Phi(z) = target
    if (target < 0.5) return mu + sd * normal_quantile(target);
    return mu - sd * normal_quantile(Z * (1.0 - p));    // Phi_c(z) = Z (1-p)
  }
  double isf(double q) const override
  {
    if (q <= 0.0) return INF;
    if (q >= 1.0) return L;
    const double t = q * Z;    // Phi_c(z) = t
    if (t < 0.5) return mu - sd * normal_quantile(t);
    return quantile(1.0 - q);
  }
  double sf_integral(double a, double b) const override
  {
    // sf = 1 below L; above L sf = Phi_c(z)/Z
    double sum = 0.0;
    if (a < L) {
      const double top = std::min(b, L);
      sum += top - a;
      a = top;
    }
    if (b > a) sum += sd / Z * (normal_sf_antideriv((b - mu) / sd) - normal_sf_antideriv((a - mu) / sd));
    return sum;
  }
  double partial_mean(double a, double b) const override
  {
    a = std::max(a, L);
    if (b <= a) return 0.0;
    const double za = (a - mu) / sd, zb = (b - mu) / sd;
    const double mass = (zb > 0.0 && za > 0.0) ? normal_sf(za) - normal_sf(zb)
                                               : normal_cdf(zb) - normal_cdf(za);
    const double pa = (za == -INF) ? 0.0 : normal_pdf(za);
    const double pb = (zb == INF) ? 0.0 : normal_pdf(zb);
    return (mu * mass - sd * (pb - pa)) / Z;
  }
  double mean() const override
  {
    if (L == -INF) return mu;
    return mu + sd * normal_pdf(zL) / Z;
  }
  double second_moment() const override
  {
    if (L == -INF) return mu * mu + sd * sd;
    const double lam = normal_pdf(zL) / Z;
    return mu * mu + 2.0 * mu * sd * lam + sd * sd * (1.0 + zL * lam);
  }
  std::vector<double> breakpoints() const override
  {
    if (L == -INF) return {};
    return {L};
  }

 private:
  double mu, sd, L, zL, Z, PhiL;
};

/* ----------------------------------------------------------------------
   P_c0(x) = (2/xs) u^3 exp(-u^2), u = x/xs.  With W = u^2:
   sf = (1+W) e^-W, cdf = 1 - (1+W) e^-W, hazard = (2/xs) u^3/(1+u^2).
------------------------------------------------------------------------- */

class RealisticDist : public Distribution {
 public:
  explicit RealisticDist(double xs) : xs(xs) {}
  DistKind kind() const override { return DistKind::REALISTIC; }
  std::string describe() const override { return "realistic " + fmtnum(xs); }
  double lower() const override { return 0.0; }
  double upper() const override { return INF; }
  double pdf(double x) const override
  {
    if (x <= 0.0) return 0.0;
    const double u = x / xs;
    return 2.0 / xs * u * u * u * std::exp(-u * u);
  }
  double cdf(double x) const override { return x <= 0.0 ? 0.0 : cdfW((x / xs) * (x / xs)); }
  double sf(double x) const override
  {
    if (x <= 0.0) return 1.0;
    const double W = (x / xs) * (x / xs);
    return (1.0 + W) * std::exp(-W);
  }
  double quantile(double p) const override
  {
    if (p <= 0.0) return 0.0;
    if (p >= 1.0) return INF;
    if (p > 0.5) return isf(1.0 - p);
    // cdf = W^2/2 - W^3/3 + ...: invert the series for the start, then
    // Newton (cdf is increasing, convex below W = 1: one overshoot, then
    // monotone quadratic convergence)
    const double r = std::sqrt(2.0 * p);
    double W = r * (1.0 + r / 3.0);
    for (int it = 0; it < 60; ++it) {
      const double d = W * std::exp(-W);
      const double dW = (cdfW(W) - p) / d;
      W = std::min(std::max(W - dW, 0.5 * W), 1.7);
      if (std::fabs(dW) <= 4.0 * EPS * W) break;
    }
    return xs * std::sqrt(W);
  }
  double isf(double q) const override
  {
    if (q >= 1.0) return 0.0;
    if (q <= 0.0) return INF;
    if (q > 0.5) return quantile(1.0 - q);
    // (1+W) e^-W = q:  W = L + log(1+W), L = -log q; two fixed-point steps
    // for the start, then Newton on g(W) = log(1+W) - W + L (decreasing,
    // concave: quadratic convergence after at most one overshoot)
    const double L = -std::log(q);
    double W = L + std::log1p(L + std::log1p(L));
    for (int it = 0; it < 60; ++it) {
      const double g = std::log1p(W) - W + L;
      const double dW = g * (1.0 + W) / W;    // -g/g'
      W = std::max(W + dW, 0.5 * W);
      if (std::fabs(dW) <= 4.0 * EPS * W) break;
    }
    return xs * std::sqrt(W);
  }
  double sf_integral(double a, double b) const override { return G(b) - G(a); }
  double partial_mean(double a, double b) const override { return M(b) - M(a); }
  double mean() const override { return 0.75 * SQRTPI * xs; }
  double second_moment() const override { return 2.0 * xs * xs; }
  std::vector<double> breakpoints() const override { return {0.0}; }

 private:
  double xs;
  static double cdfW(double W)
  {
    if (W < 0.5) {
      // 1 - (1+W)e^-W = sum_{n>=2} (-1)^n (n-1) W^n / n!
      double term = W * W / 2.0, sum = 0.0;    // W^n/n! for n = 2
      for (int n = 2; n < 40; ++n) {
        const double t = ((n & 1) ? -1.0 : 1.0) * (n - 1) * term;
        sum += t;
        if (std::fabs(t) < 1e-18 * sum) break;
        term *= W / (n + 1);
      }
      return sum;
    }
    return 1.0 - (1.0 + W) * std::exp(-W);
  }
  // antiderivative of sf
  double G(double x) const
  {
    if (x <= 0.0) return x;
    if (x == INF) return xs * 0.75 * SQRTPI;
    const double u = x / xs;
    return xs * (0.75 * SQRTPI * std::erf(u) - 0.5 * u * std::exp(-u * u));
  }
  // antiderivative of x pdf(x)
  double M(double x) const
  {
    if (x <= 0.0) return 0.0;
    if (x == INF) return mean();
    const double u = x / xs;
    return xs * (0.75 * SQRTPI * std::erf(u) - (u * u * u + 1.5 * u) * std::exp(-u * u));
  }
};

/* ---------------------------------------------------------------------- */

class DeltaDist : public Distribution {
 public:
  explicit DeltaDist(double x0) : x0(x0) {}
  DistKind kind() const override { return DistKind::DELTA; }
  std::string describe() const override { return "delta " + fmtnum(x0); }
  double lower() const override { return x0; }
  double upper() const override { return x0; }
  double pdf(double) const override { return 0.0; }
  double cdf(double x) const override { return x >= x0 ? 1.0 : 0.0; }
  double sf(double x) const override { return x < x0 ? 1.0 : 0.0; }
  double quantile(double) const override { return x0; }
  double isf(double) const override { return x0; }
  double sf_integral(double a, double b) const override
  {
    return std::max(0.0, std::min(b, x0) - a);
  }
  double partial_mean(double a, double b) const override { return (a < x0 && x0 <= b) ? x0 : 0.0; }
  double mean() const override { return x0; }
  double second_moment() const override { return x0 * x0; }
  std::vector<double> breakpoints() const override { return {x0}; }

 private:
  double x0;
};

/* ----------------------------------------------------------------------
   density linear between table points; C = cumulative mass at the
   points, S = mass to the right of the points (exact upper tail)
------------------------------------------------------------------------- */

class TableDist : public Distribution {
 public:
  TableDist(const std::vector<double> &xin, const std::vector<double> &pin, const std::string &label) :
      x(xin), p(pin), label(label)
  {
    const size_t n = x.size();
    double total = 0.0;
    for (size_t k = 0; k + 1 < n; ++k) total += 0.5 * (p[k] + p[k + 1]) * (x[k + 1] - x[k]);
    for (auto &v : p) v /= total;
    C.assign(n, 0.0);
    S.assign(n, 0.0);
    for (size_t k = 0; k + 1 < n; ++k) C[k + 1] = C[k] + seg(k);
    for (size_t k = n - 1; k-- > 0;) S[k] = S[k + 1] + seg(k);
    m1 = partial_mean(x.front(), x.back());
    m2 = 0.0;
    for (size_t k = 0; k + 1 < n; ++k) {
      // int x^2 (p_k + s t) dt over the segment, x = x_k + t
      const double h = x[k + 1] - x[k], s = (p[k + 1] - p[k]) / h, a = x[k];
      m2 += p[k] * (a * a * h + a * h * h + h * h * h / 3.0) +
          s * (a * a * h * h / 2.0 + 2.0 * a * h * h * h / 3.0 + h * h * h * h / 4.0);
    }
  }
  DistKind kind() const override { return DistKind::TABLE; }
  std::string describe() const override { return "table " + label; }
  double lower() const override { return x.front(); }
  double upper() const override { return x.back(); }
  double pdf(double xx) const override
  {
    if (xx < x.front() || xx > x.back()) return 0.0;
    const size_t k = segment(xx);
    const double t = (xx - x[k]) / (x[k + 1] - x[k]);
    return p[k] + t * (p[k + 1] - p[k]);
  }
  double cdf(double xx) const override
  {
    if (xx <= x.front()) return 0.0;
    if (xx >= x.back()) return 1.0;
    const size_t k = segment(xx);
    const double h = x[k + 1] - x[k], s = (p[k + 1] - p[k]) / h, t = xx - x[k];
    return std::min(1.0, C[k] + p[k] * t + 0.5 * s * t * t);
  }
  double sf(double xx) const override
  {
    if (xx <= x.front()) return 1.0;
    if (xx >= x.back()) return 0.0;
    const size_t k = segment(xx);
    const double h = x[k + 1] - x[k], s = (p[k + 1] - p[k]) / h, tau = x[k + 1] - xx;
    return std::min(1.0, S[k + 1] + p[k + 1] * tau - 0.5 * s * tau * tau);
  }
  double quantile(double pp) const override
  {
    if (pp <= 0.0) return x.front();
    if (pp >= 1.0) return x.back();
    // first segment whose right cumulative exceeds pp
    size_t k = std::upper_bound(C.begin(), C.end(), pp) - C.begin();
    k = std::min(std::max<size_t>(k, 1), x.size() - 1) - 1;
    const double h = x[k + 1] - x[k], s = (p[k + 1] - p[k]) / h, d = pp - C[k];
    const double disc = std::max(0.0, p[k] * p[k] + 2.0 * s * d);
    const double den = p[k] + std::sqrt(disc);
    const double t = den > 0.0 ? 2.0 * d / den : 0.0;
    return std::min(x[k + 1], x[k] + t);
  }
  double isf(double q) const override
  {
    if (q >= 1.0) return x.front();
    if (q <= 0.0) return x.back();
    // S is decreasing: last point with S >= q
    size_t k = std::upper_bound(S.rbegin(), S.rend(), q) - S.rbegin();    // points from right with S < q
    size_t j = x.size() - k;    // S[j] >= q > S[j+1]  (j = index of left end of segment)
    j = std::min(std::max<size_t>(j, 1), x.size() - 1) - 1;
    const double h = x[j + 1] - x[j], s = (p[j + 1] - p[j]) / h, d = q - S[j + 1];
    const double disc = std::max(0.0, p[j + 1] * p[j + 1] - 2.0 * s * d);
    const double den = p[j + 1] + std::sqrt(disc);
    const double tau = den > 0.0 ? 2.0 * d / den : 0.0;
    return std::max(x[j], x[j + 1] - tau);
  }
  double sf_integral(double a, double b) const override { return G(b) - G(a); }
  double partial_mean(double a, double b) const override { return M(b) - M(a); }
  double mean() const override { return m1; }
  double second_moment() const override { return m2; }
  std::vector<double> breakpoints() const override { return x; }

 private:
  std::vector<double> x, p, C, S;
  std::string label;
  double m1, m2;

  double seg(size_t k) const { return 0.5 * (p[k] + p[k + 1]) * (x[k + 1] - x[k]); }
  size_t segment(double xx) const
  {
    size_t k = std::upper_bound(x.begin(), x.end(), xx) - x.begin();
    return std::min(std::max<size_t>(k, 1), x.size() - 1) - 1;
  }
  // antiderivative of sf, G(x) = x for x <= x_0
  double G(double xx) const
  {
    if (xx <= x.front()) return xx;
    double acc = x.front();
    const size_t kmax = xx >= x.back() ? x.size() - 1 : segment(xx) + 1;
    for (size_t k = 0; k < kmax; ++k) {
      const double h = x[k + 1] - x[k], s = (p[k + 1] - p[k]) / h;
      const double t = std::min(xx, x[k + 1]) - x[k];
      // sf(x_k + t) = S_{k+1} + p_k (h - t) + s (h^2 - t^2)/2
      acc += S[k + 1] * t + p[k] * (h * t - 0.5 * t * t) + 0.5 * s * (h * h * t - t * t * t / 3.0);
    }
    return acc;
  }
  double M(double xx) const
  {
    if (xx <= x.front()) return 0.0;
    double acc = 0.0;
    const size_t kmax = xx >= x.back() ? x.size() - 1 : segment(xx) + 1;
    for (size_t k = 0; k < kmax; ++k) {
      const double h = x[k + 1] - x[k], s = (p[k + 1] - p[k]) / h;
      const double t = std::min(xx, x[k + 1]) - x[k];
      acc += x[k] * (p[k] * t + 0.5 * s * t * t) + 0.5 * p[k] * t * t + s * t * t * t / 3.0;
    }
    return acc;
  }
};

}    // namespace

/* ---------------------------------------------------------------------- */

double normal_cdf(double z)
{
  return 0.5 * std::erfc(-z / SQRT2);
}

double normal_sf(double z)
{
  return 0.5 * std::erfc(z / SQRT2);
}

double normal_quantile(double p)
{
  if (p <= 0.0) return -INF;
  if (p >= 1.0) return INF;
  const double q = p - 0.5;
  if (std::fabs(q) <= 0.425) {
    const double r = 0.180625 - q * q;
    return q *
        (((((((2.5090809287301226727e+3 * r + 3.3430575583588128105e+4) * r +
              6.7265770927008700853e+4) * r + 4.5921953931549871457e+4) * r +
            1.3731693765509461125e+4) * r + 1.9715909503065514427e+3) * r +
          1.3314166789178437745e+2) * r + 3.3871328727963666080e0) /
        (((((((5.2264952788528545610e+3 * r + 2.8729085735721942674e+4) * r +
              3.9307895800092710610e+4) * r + 2.1213794301586595867e+4) * r +
            5.3941960214247511077e+3) * r + 6.8718700749205790830e+2) * r +
          4.2313330701600911252e+1) * r + 1.0);
  }
  double r = std::sqrt(-std::log(q < 0.0 ? p : 1.0 - p));
  double val;
  if (r <= 5.0) {
    r -= 1.6;
    val = (((((((7.74545014278341407640e-4 * r + 2.27238449892691845833e-2) * r +
                2.41780725177450611770e-1) * r + 1.27045825245236838258e0) * r +
              3.64784832476320460504e0) * r + 5.76949722146069140550e0) * r +
            4.63033784615654529590e0) * r + 1.42343711074968357734e0) /
        (((((((1.05075007164441684324e-9 * r + 5.47593808499534494600e-4) * r +
              1.51986665636164571966e-2) * r + 1.48103976427480074590e-1) * r +
            6.89767334985100004550e-1) * r + 1.67638483018380384940e0) * r +
          2.05319162663775882187e0) * r + 1.0);
  } else {
    r -= 5.0;
    val = (((((((2.01033439929228813265e-7 * r + 2.71155556874348757815e-5) * r +
                1.24266094738807843860e-3) * r + 2.65321895265761230930e-2) * r +
              2.96560571828504891230e-1) * r + 1.78482653991729133580e0) * r +
            5.46378491116411436990e0) * r + 6.65790464350110377720e0) /
        (((((((2.04426310338993978564e-15 * r + 1.42151175831644588870e-7) * r +
              1.84631831751005468180e-5) * r + 7.86869131145613259100e-4) * r +
            1.48753612908506148525e-2) * r + 1.36929880922735805310e-1) * r +
          5.99832206555887937690e-1) * r + 1.0);
  }
  return q < 0.0 ? -val : val;
}

/* ---------------------------------------------------------------------- */

double Distribution::effective_upper() const
{
  const double u = upper();
  return std::isfinite(u) ? u : isf(1e-300);
}

double Distribution::hazard(double x) const
{
  const double s = sf(x);
  return s > 0.0 ? pdf(x) / s : INF;
}

// u maps to the upper tail (x = isf(u)), as in sample_above(), so that a
// conditioned draw with P(X > lo) = 1 equals the plain draw
double Distribution::sample(const Uniform &u) const
{
  return (u.u < 0.5) ? isf(u.u) : quantile(u.one_minus_u);
}

double Distribution::sample_above(double lo, const Uniform &u) const
{
  if (lo < lower()) return sample(u);
  const double s = sf(lo);
  if (!(s > 0.0)) return NaN;
  const double q = u.u * s;    // target survival
  double x = (q < 0.5) ? isf(q) : quantile(u.one_minus_u + u.u * cdf(lo));
  const double above = std::nextafter(lo, INF);
  return x < above ? above : x;
}

/* ---------------------------------------------------------------------- */

DistributionPtr make_uniform(double lo, double hi)
{
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
    throw SpecError("uniform: need lo < hi (got lo = " + fmtnum(lo) + ", hi = " + fmtnum(hi) + ")");
  return std::make_shared<UniformDist>(lo, hi);
}

DistributionPtr make_gaussian(double mean, double sd, double trunc)
{
  if (!std::isfinite(mean) || !(sd > 0.0) || !std::isfinite(sd))
    throw SpecError("gaussian: need a finite mean and sd > 0 (got mean = " + fmtnum(mean) +
                    ", sd = " + fmtnum(sd) + ")");
  if (trunc != -INF && normal_sf((trunc - mean) / sd) < 1e-12)
    throw SpecError("gaussian: almost no weight above " + fmtnum(trunc) + " (mean = " +
                    fmtnum(mean) + ", sd = " + fmtnum(sd) + ")");
  return std::make_shared<GaussianDist>(mean, sd, trunc);
}

DistributionPtr make_realistic(double xs)
{
  if (!(xs > 0.0) || !std::isfinite(xs))
    throw SpecError("realistic: need xs > 0 (got " + fmtnum(xs) + ")");
  return std::make_shared<RealisticDist>(xs);
}

DistributionPtr make_delta(double x0)
{
  if (!std::isfinite(x0)) throw SpecError("delta: need a finite value (got " + fmtnum(x0) + ")");
  return std::make_shared<DeltaDist>(x0);
}

DistributionPtr make_table(const std::vector<double> &x, const std::vector<double> &p,
                           const std::string &label)
{
  if (x.size() != p.size() || x.size() < 2)
    throw SpecError("table " + label + ": need at least 2 points");
  double total = 0.0;
  for (size_t k = 0; k < x.size(); ++k) {
    if (!std::isfinite(x[k]) || !std::isfinite(p[k]))
      throw SpecError("table " + label + ": non-finite value at point " + std::to_string(k + 1));
    if (p[k] < 0.0)
      throw SpecError("table " + label + ": negative density " + fmtnum(p[k]) + " at point " +
                      std::to_string(k + 1));
    if (k > 0 && !(x[k] > x[k - 1]))
      throw SpecError("table " + label + ": stretches must increase strictly (point " +
                      std::to_string(k + 1) + ")");
    if (k > 0) total += 0.5 * (p[k] + p[k - 1]) * (x[k] - x[k - 1]);
  }
  if (!(total > 0.0)) throw SpecError("table " + label + ": density integrates to zero");
  return std::make_shared<TableDist>(x, p, label);
}

/* ---------------------------------------------------------------------- */

std::string load_file(const std::string &path)
{
  // a directory opens as a stream on Linux and then reads as empty: the
  // message would be "keyword ... not found"
  struct stat sb;
  if (::stat(path.c_str(), &sb) == 0 && (sb.st_mode & S_IFMT) == S_IFDIR)
    throw SpecError("cannot open table file '" + path + "': it is a directory, not a file");
  errno = 0;
  std::ifstream in(path);
  if (!in) {
    const int err = errno;
    throw SpecError("cannot open table file '" + path + "'" +
                    (err ? " (" + std::string(std::strerror(err)) + ")" : std::string()));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void read_table_file(const std::string &path, const std::string &keyword, std::vector<double> &x,
                     std::vector<double> &p)
{
  read_table_text(load_file(path), path, keyword, x, p);
}

void read_table_text(const std::string &text, const std::string &path, const std::string &keyword,
                     std::vector<double> &x, std::vector<double> &p)
{
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  bool found = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::string word;
    if ((ws >> word) && word == keyword) {
      found = true;
      break;
    }
  }
  if (!found) throw SpecError("keyword '" + keyword + "' not found in table file '" + path + "'");
  auto where = [&]() { return "table file '" + path + "' line " + std::to_string(lineno); };

  // an integer written as such ('2.5', '4x' and '' are not)
  auto integer = [](const std::string &tok, long &v) {
    if (tok.empty()) return false;
    errno = 0;
    char *end = nullptr;
    v = std::strtol(tok.c_str(), &end, 10);
    return end != tok.c_str() && *end == '\0' && errno != ERANGE;
  };
  long n = -1;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::string word, count, flag;
    if (!(ws >> word) || word[0] == '#') continue;
    if (word != "N" || !(ws >> count) || !integer(count, n) || n < 2) {
      const std::string got = (word == "N" && !count.empty()) ? " (got 'N " + count + "'" +
              (integer(count, n) ? "" : ": not an integer") + ")" : "";
      throw SpecError(where() + ": expected 'N <count>' with count >= 2 after keyword '" + keyword +
                      "'" + got);
    }
    // these tables have no flags ('N n aniso' is for kernel tables)
    if (ws >> flag)
      throw SpecError(where() + ": unknown flag '" + flag + "' after 'N " + count +
                      "' (threshold and substrate tables take no flags)");
    break;
  }
  if (n < 0) throw SpecError("table file '" + path + "': missing 'N <count>' after '" + keyword + "'");
  const int nline = lineno;
  x.clear();
  p.clear();
  while (static_cast<long>(x.size()) < n && std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::string a, b, c, extra;
    if (!(ws >> a)) continue;
    if (a[0] == '#') continue;
    long idx;
    if (!integer(a, idx)) break;    // the next section begins: too few points
    if (!(ws >> b >> c) || (ws >> extra))
      throw SpecError(where() + ": expected 'index x P(x)'");
    if (idx != static_cast<long>(x.size()) + 1)
      throw SpecError(where() + ": index " + a + " out of sequence (expected " +
                      std::to_string(x.size() + 1) + ")");
    double xv, pv;
    try {
      xv = parse_number(b);
      pv = parse_number(c);
    } catch (const SpecError &e) {
      throw SpecError(where() + ": " + e.what());
    }
    x.push_back(xv);
    p.push_back(pv);
  }
  if (static_cast<long>(x.size()) < n)
    throw SpecError("table file '" + path + "' section '" + keyword + "': expected " +
                    std::to_string(n) + " points, found " + std::to_string(x.size()));
  // a point line after the last one: the section has more points than its
  // 'N n' line says (they would be dropped silently)
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::string a;
    if (!(ws >> a) || a[0] == '#') continue;
    long idx;
    if (integer(a, idx))
      throw SpecError("table file '" + path + "' section '" + keyword + "': more points than " +
                      "'N " + std::to_string(n) + "' (line " + std::to_string(nline) +
                      ") says: point " + a + " on line " + std::to_string(lineno) +
                      "; the point count must equal N");
    break;    // the next section
  }
}

/* ---------------------------------------------------------------------- */

double reform_beyond_thresholds(const Distribution &Pc, const Distribution &R)
{
  const double top = Pc.effective_upper();
  const double above = 1.0 - R.cdf(std::nextafter(top, -INF));    // P(r >= top)
  const double below = R.cdf(-top);                               // P(r <= -top)
  return std::min(1.0, above + below);
}

void check_reform(const Distribution &Pc, const DistributionSpec &reform)
{
  if (!reform.dist) return;
  const double w = reform_beyond_thresholds(Pc, *reform.dist);
  if (w > REFORM_BEYOND_TOLERANCE)
    throw SpecError("reform " + reform.text + ": re-forming stretches reach the largest breaking "
                    "threshold " + fmtnum(Pc.effective_upper()) + " (probability " + fmtnum(w) +
                    "); a contact must form below its threshold");
}

/* ---------------------------------------------------------------------- */

double parse_number(const std::string &token)
{
  errno = 0;
  char *end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  const bool range = errno == ERANGE;
  if (token.empty() || end == token.c_str() || *end != '\0')
    throw SpecError("expected a number, got '" + token + "'");
  // strtod reads them all, the causes differ: say which
  if (std::isnan(v)) throw NumberError("value '" + token + "' is not a number (NaN)");
  if (std::isinf(v))
    throw NumberError("value '" + token + "' is " +
                      (range ? "beyond the range of a double (largest " +
                                   fmtnum(std::numeric_limits<double>::max()) + ")"
                             : std::string("infinite")));
  if (std::fpclassify(v) == FP_SUBNORMAL)
    throw NumberError("value '" + token + "' is subnormal (nonzero and smaller in magnitude than " +
                      fmtnum(std::numeric_limits<double>::min()) +
                      ", the smallest normal double: it would lose precision); write 0 or a "
                      "normal number");
  if (v == 0.0 && range)
    throw NumberError("value '" + token + "' is below the subnormal range of a double (it would "
                      "be read as 0); write 0 or a normal number");
  return v;
}

const char *role_keyword(Role role)
{
  switch (role) {
    case Role::THRESHOLD: return "threshold";
    case Role::REFORM: return "reform";
    default: return "stiffness";
  }
}

const char *role_styles(Role role)
{
  switch (role) {
    case Role::THRESHOLD: return "uniform, gaussian, realistic, table";
    case Role::REFORM: return "delta, uniform, gaussian, none";
    default: return "constant, uniform, gaussian";
  }
}

// Every message names the keyword first: the ones made here and the
// factories' start with the style, and the keyword is put before them.
DistributionSpec parse_distribution(Role role, const std::vector<std::string> &args, size_t &pos,
                                    const NumberParser &number, const FileLoader &load,
                                    const SpecWording &wording)
{
  const std::string kw = wording.keyword.empty() ? role_keyword(role) : wording.keyword;
  if (pos >= args.size())
    throw SpecError(kw + ": missing style; allowed: " + role_styles(role));
  const std::string style = args[pos++];

  auto values = [&](size_t n, const char *names) {
    size_t avail = 0;
    while (avail < n && pos + avail < args.size()) ++avail;
    if (avail < n)
      throw SpecError(style + ": expected " + std::to_string(n) + " value" + (n > 1 ? "s" : "") +
                      " (" + names + "), got " + std::to_string(avail));
    std::istringstream nm(names);
    std::vector<double> v;
    for (size_t i = 0; i < n; ++i) {
      std::string name;
      nm >> name;
      const std::string &tok = args[pos++];
      try {
        v.push_back(number(tok));
      } catch (const NumberError &e) {
        // a number that is not usable (subnormal, out of range): its cause
        throw SpecError(style + ": " + name + ": " + e.what());
      } catch (const SpecError &) {
        throw SpecError(style + ": expected " + wording.number + " for " + name + ", got '" + tok +
                        "'");
      }
    }
    return v;
  };

  DistributionSpec spec;
  try {
    if (style == "uniform") {
      const auto v = values(2, "lo hi");
      if (role == Role::THRESHOLD && !(v[0] >= 0.0 && v[0] < v[1]))
        throw SpecError("uniform: need 0 <= lo < hi (got lo = " + fmtnum(v[0]) + ", hi = " +
                        fmtnum(v[1]) + ")");
      if (role == Role::STIFFNESS && !(v[0] > 0.0 && v[0] < v[1]))
        throw SpecError("uniform: need 0 < lo < hi (got lo = " + fmtnum(v[0]) + ", hi = " +
                        fmtnum(v[1]) + ")");
      spec.dist = make_uniform(v[0], v[1]);
    } else if (style == "gaussian") {
      const auto v = values(2, "mean sd");
      if (role != Role::REFORM && !(v[0] > 0.0))
        throw SpecError("gaussian: need mean > 0 (got " + fmtnum(v[0]) + ")");
      spec.dist = make_gaussian(v[0], v[1], role == Role::REFORM ? -INF : 0.0);
    } else if (style == "realistic" && role == Role::THRESHOLD) {
      const auto v = values(1, "xs");
      spec.dist = make_realistic(v[0]);
    } else if (style == "table" && role == Role::THRESHOLD) {
      if (pos + 2 > args.size())
        throw SpecError("table: expected 2 values (file keyword), got " +
                        std::to_string(args.size() - pos));
      const std::string file = args[pos++];
      const std::string key = args[pos++];
      std::vector<double> x, p;
      try {
        read_table_text(load ? load(file) : load_file(file), file, key, x, p);
      } catch (const SpecError &e) {
        throw SpecError(std::string("table: ") + e.what());
      }
      if (x.front() < 0.0)
        throw SpecError("table: breaking stretches must be >= 0 (first point x = " +
                        fmtnum(x.front()) + " in '" + file + "' section '" + key + "')");
      spec.dist = make_table(x, p, file + " " + key);
    } else if (style == "delta" && role == Role::REFORM) {
      const auto v = values(1, "x0");
      spec.dist = make_delta(v[0]);
    } else if (style == "none" && role == Role::REFORM) {
      spec.dist = nullptr;
      spec.text = "none";
      return spec;
    } else if (style == "constant" && role == Role::STIFFNESS) {
      spec.dist = make_delta(1.0);
      spec.text = "constant";
      return spec;
    } else {
      throw SpecError("unknown style '" + style + "'; allowed: " + role_styles(role));
    }
  } catch (const SpecError &e) {
    throw SpecError(kw + " " + e.what());
  }
  spec.text = spec.dist->describe();
  return spec;
}

}    // namespace feq
