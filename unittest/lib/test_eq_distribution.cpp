// Unit tests: distributions of FRICTION-EQ (thresholds, reform stretches,
// stiffness factors) against independent quadrature and analytic forms.
#include "eq_distribution.h"
#include "eq_master_equation.h"
#include "eq_random.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

using namespace feq;
using ::testing::HasSubstr;

#ifndef FEQ_SOURCE_DIR
#define FEQ_SOURCE_DIR "."
#endif

namespace {

const double INF = std::numeric_limits<double>::infinity();

struct Case {
  const char *name;
  DistributionPtr d;
  double lo, hi;    // finite range that holds all but ~1e-15 of the mass
};

std::vector<Case> cases()
{
  std::vector<double> tx, tp;
  for (int i = 0; i <= 40; ++i) {
    tx.push_back(0.5 + 0.025 * i);
    tp.push_back(1.0 + std::sin(0.3 * i) * 0.8);
  }
  return {{"uniform", make_uniform(0.75, 1.25), 0.7, 1.3},
          {"gaussian_truncated", make_gaussian(0.4, 0.3, 0.0), -0.1, 3.0},
          {"gaussian", make_gaussian(-0.2, 0.1, -INF), -1.2, 0.8},
          {"realistic", make_realistic(1.3), -0.1, 9.0},
          {"table", make_table(tx, tp, "sine"), 0.4, 1.6}};
}

double quad(const std::function<double(double)> &f, const Distribution &d, double a, double b)
{
  return integrate(f, a, b, d.breakpoints(), 400);
}

}    // namespace

TEST(Normal, QuantileInvertsCdf)
{
  for (double p : {1e-300, 1e-100, 1e-20, 1e-8, 0.01, 0.2, 0.5, 0.7, 0.975, 1 - 1e-9, 1 - 1e-15}) {
    const double z = normal_quantile(p);
    const double back = p < 0.5 ? normal_cdf(z) : 1.0 - normal_sf(z);
    // relative error in z of ~1e-16 moves p by ~z^2 1e-16 in the far tail
    EXPECT_NEAR(back / p, 1.0, 4e-16 * (8.0 + z * z)) << "p = " << p;
  }
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-15);
}

TEST(Distributions, NormalizedAndConsistentTails)
{
  for (const auto &c : cases()) {
    const Distribution &d = *c.d;
    EXPECT_NEAR(quad([&](double x) { return d.pdf(x); }, d, c.lo, c.hi), 1.0, 1e-12) << c.name;
    for (int i = 0; i <= 200; ++i) {
      const double x = c.lo + (c.hi - c.lo) * i / 200.0;
      EXPECT_NEAR(d.cdf(x) + d.sf(x), 1.0, 2e-15) << c.name << " x = " << x;
      // cdf from independent quadrature of the density
      EXPECT_NEAR(d.cdf(x), quad([&](double t) { return d.pdf(t); }, d, c.lo, x), 1e-12)
          << c.name << " x = " << x;
    }
  }
}

TEST(Distributions, InverseTailsRoundTrip)
{
  for (const auto &c : cases()) {
    const Distribution &d = *c.d;
    for (double p : {1e-14, 1e-9, 1e-5, 0.001, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999}) {
      // x itself is only resolved to ~1e-16 absolute near a finite end of
      // the support: a relative tolerance in p plus that absolute one
      const double x = d.quantile(p);
      EXPECT_NEAR(d.cdf(x), p, 1e-12 * p + 4e-16 * (1.0 + std::fabs(x)) * d.pdf(x) + 1e-17)
          << c.name << " p = " << p;
      const double y = d.isf(p);
      EXPECT_NEAR(d.sf(y), p, 1e-12 * p + 4e-16 * (1.0 + std::fabs(y)) * d.pdf(y) + 1e-17)
          << c.name << " q = " << p;
    }
  }
  // tails that only an upper-tail implementation resolves
  EXPECT_NEAR(make_realistic(1.0)->sf(make_realistic(1.0)->isf(1e-200)) / 1e-200, 1.0, 1e-12);
  EXPECT_NEAR(make_gaussian(1.0, 0.1, 0.0)->sf(make_gaussian(1.0, 0.1, 0.0)->isf(1e-200)) / 1e-200, 1.0,
              1e-10);
}

TEST(Distributions, IntegralsAndMomentsMatchQuadrature)
{
  for (const auto &c : cases()) {
    const Distribution &d = *c.d;
    const double m1 = quad([&](double x) { return x * d.pdf(x); }, d, c.lo, c.hi);
    const double m2 = quad([&](double x) { return x * x * d.pdf(x); }, d, c.lo, c.hi);
    EXPECT_NEAR(d.mean(), m1, 1e-12) << c.name;
    EXPECT_NEAR(d.second_moment(), m2, 1e-12) << c.name;
    EXPECT_NEAR(d.partial_mean(c.lo, c.hi), m1, 1e-12) << c.name;
    const double a = c.lo + 0.3 * (c.hi - c.lo), b = c.lo + 0.6 * (c.hi - c.lo);
    EXPECT_NEAR(d.partial_mean(a, b), quad([&](double x) { return x * d.pdf(x); }, d, a, b), 1e-12)
        << c.name;
    EXPECT_NEAR(d.sf_integral(c.lo - 0.5, b), quad([&](double x) { return d.sf(x); }, d, c.lo - 0.5, b),
                1e-12)
        << c.name;
    // mean of a non-negative variable: int_0^inf sf
    if (d.lower() >= 0.0) EXPECT_NEAR(d.sf_integral(0.0, c.hi), d.mean(), 1e-12) << c.name;
  }
}

TEST(Distributions, RealisticClosedForms)
{
  const auto d = make_realistic(1.0);
  EXPECT_NEAR(d->mean(), 0.75 * std::sqrt(M_PI), 1e-15);
  EXPECT_NEAR(d->second_moment(), 2.0, 1e-15);
  for (double x : {0.01, 0.3, 1.0, 2.0, 4.0}) {
    EXPECT_NEAR(d->hazard(x), 2.0 * x * x * x / (1.0 + x * x), 1e-13 * (1 + x * x * x));
    EXPECT_NEAR(d->sf(x), (1.0 + x * x) * std::exp(-x * x), 1e-16);
  }
  // small-x cdf keeps relative precision: cdf = W^2/2 - W^3/3 + W^4/8 ..., W = x^2
  const double W = 1e-6;
  EXPECT_NEAR(d->cdf(1e-3) / (W * W / 2 - W * W * W / 3 + W * W * W * W / 8), 1.0, 1e-14);
  EXPECT_NEAR(d->quantile(d->cdf(1e-3)) / 1e-3, 1.0, 1e-13);
}

// The densities and moments against their closed forms, written out here
// (the tests above check each distribution only against itself: cdf against
// the quadrature of its own pdf).  Tolerance 1e-14: a few ulp of the O(1)
// values (the closed forms use erfc and exp, each correct to ~1 ulp).
namespace {
double phi_n(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * M_PI); }
double Phi_upper(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }
}    // namespace

TEST(Distributions, DensitiesAndMomentsAgainstClosedForms)
{
  // normal truncated to x > a: Z = P(N > alpha), lambda = phi(alpha)/Z, mean
  // mu + sd lambda, variance sd^2 (1 + alpha lambda - lambda^2)
  const double mu = 0.4, sd = 0.3, a = 0.0, alpha = (a - mu) / sd;
  const double Z = Phi_upper(alpha), lam = phi_n(alpha) / Z;
  const auto g = make_gaussian(mu, sd, a);
  const double mean = mu + sd * lam, var = sd * sd * (1.0 + alpha * lam - lam * lam);
  EXPECT_NEAR(g->mean(), mean, 1e-14);
  EXPECT_NEAR(g->second_moment(), var + mean * mean, 1e-14);
  for (double x : {-0.1, 0.05, 0.4, 0.9, 1.7}) {
    const double z = (x - mu) / sd;
    EXPECT_NEAR(g->pdf(x), x > a ? phi_n(z) / (sd * Z) : 0.0, 1e-14) << x;
    EXPECT_NEAR(g->sf(x), x > a ? Phi_upper(z) / Z : 1.0, 1e-14) << x;
  }
  // untruncated normal
  const auto n = make_gaussian(-0.2, 0.1, -INF);
  EXPECT_NEAR(n->mean(), -0.2, 1e-14);
  EXPECT_NEAR(n->second_moment(), 0.01 + 0.04, 1e-14);
  for (double x : {-0.5, -0.2, 0.0, 0.1}) EXPECT_NEAR(n->pdf(x), phi_n((x + 0.2) / 0.1) / 0.1, 1e-13) << x;
  // realistic with xs != 1: (2/xs) u^3 exp(-u^2), u = x/xs; mean 0.75 sqrt(pi) xs, <x^2> = 2 xs^2
  const double xs = 1.3;
  const auto r = make_realistic(xs);
  EXPECT_NEAR(r->mean(), 0.75 * std::sqrt(M_PI) * xs, 1e-14);
  EXPECT_NEAR(r->second_moment(), 2.0 * xs * xs, 1e-14);
  for (double x : {0.1, 0.7, 1.3, 2.9}) {
    const double u = x / xs;
    EXPECT_NEAR(r->pdf(x), 2.0 / xs * u * u * u * std::exp(-u * u), 1e-14) << x;
    EXPECT_NEAR(r->sf(x), (1.0 + u * u) * std::exp(-u * u), 1e-14) << x;
  }
  // uniform [lo, hi]: 1/(hi-lo), mean (lo+hi)/2, <x^2> = (lo^2 + lo hi + hi^2)/3
  const auto un = make_uniform(0.75, 1.25);
  EXPECT_NEAR(un->mean(), 1.0, 1e-15);
  EXPECT_NEAR(un->second_moment(), (0.5625 + 0.9375 + 1.5625) / 3.0, 1e-15);
  EXPECT_EQ(un->pdf(1.0), 2.0);
  EXPECT_EQ(un->pdf(0.7), 0.0);
  EXPECT_EQ(un->pdf(1.3), 0.0);
}

// A table is the piecewise-linear density through its points, normalized
// by its trapezoid integral: density, cdf and moments of that interpolant
// computed here segment by segment (exact sums; rounding ~1e-15 over 40
// segments).
TEST(Distributions, TableIsTheNormalizedLinearInterpolant)
{
  std::vector<double> tx, tp;
  for (int i = 0; i <= 40; ++i) {
    tx.push_back(0.5 + 0.025 * i);
    tp.push_back(1.0 + std::sin(0.3 * i) * 0.8);
  }
  const auto t = make_table(tx, tp, "sine");
  double total = 0.0, m1 = 0.0, m2 = 0.0;
  std::vector<double> cum{0.0};
  for (size_t k = 0; k + 1 < tx.size(); ++k) {
    const double h = tx[k + 1] - tx[k], x0 = tx[k], p0 = tp[k], dp = tp[k + 1] - tp[k];
    total += h * (p0 + 0.5 * dp);
    cum.push_back(total);
    // int_0^h (x0 + y)^n (p0 + dp y/h) dy, n = 1, 2
    m1 += x0 * h * (p0 + 0.5 * dp) + h * h * (p0 / 2 + dp / 3);
    m2 += x0 * x0 * h * (p0 + 0.5 * dp) + 2 * x0 * h * h * (p0 / 2 + dp / 3) + h * h * h * (p0 / 3 + dp / 4);
  }
  for (size_t k = 0; k < tx.size(); ++k) {
    EXPECT_NEAR(t->pdf(tx[k]), tp[k] / total, 1e-14) << tx[k];
    EXPECT_NEAR(t->cdf(tx[k]), cum[k] / total, 1e-14) << tx[k];
    if (k + 1 < tx.size()) {
      const double xm = 0.5 * (tx[k] + tx[k + 1]);
      EXPECT_NEAR(t->pdf(xm), 0.5 * (tp[k] + tp[k + 1]) / total, 1e-14) << xm;
    }
  }
  EXPECT_EQ(t->pdf(0.49), 0.0);
  EXPECT_EQ(t->pdf(1.51), 0.0);
  EXPECT_NEAR(t->mean(), m1 / total, 1e-14);
  EXPECT_NEAR(t->second_moment(), m2 / total, 1e-14);
}

// Conditioned draws X > lo reproduce the conditional distribution (KS).
TEST(Distributions, SampleAboveIsConditional)
{
  for (const auto &c : cases()) {
    const Distribution &d = *c.d;
    const double lo = d.quantile(0.4);
    const double slo = d.sf(lo);
    const int n = 20000;
    std::vector<double> v(n);
    for (int i = 0; i < n; ++i) {
      v[i] = d.sample_above(lo, draw(9, i, 0, STREAM_THRESHOLD));
      ASSERT_GT(v[i], lo) << c.name;
    }
    std::sort(v.begin(), v.end());
    double dmax = 0.0;
    for (int i = 0; i < n; ++i) {
      const double F = 1.0 - d.sf(v[i]) / slo;
      dmax = std::max(dmax, std::max(std::fabs(F - double(i) / n), std::fabs((i + 1.0) / n - F)));
    }
    EXPECT_LT(dmax, std::sqrt(-std::log(0.5e-4) / 2.0 / n)) << c.name;
    // below the support: an ordinary draw
    EXPECT_EQ(d.sample_above(-1e300, draw(1, 2, 3, STREAM_THRESHOLD)),
              d.sample(draw(1, 2, 3, STREAM_THRESHOLD)));
  }
  // nothing above the support
  EXPECT_TRUE(std::isnan(make_uniform(0.75, 1.25)->sample_above(1.3, draw(1, 1, 1, 0))));
}

// the inverse-transform draw, written out: the upper tail below u = 1/2,
// the lower above (a family's own sample(), as the uniform's branch-free
// one, must give these numbers to the bit)
TEST(Distributions, SampleIsTheInverseTransformOfTheBetterTail)
{
  std::vector<Uniform> us;
  for (const uint64_t k : {uint64_t(0), uint64_t(1), (uint64_t(1) << 51) - 1, uint64_t(1) << 51,
                           (uint64_t(1) << 51) + 1, (uint64_t(1) << 52) - 1})
    us.push_back(uniform_from_bits(k << 12));
  for (int i = 0; i < 4000; ++i) us.push_back(draw(3, i, 7, STREAM_THRESHOLD));
  // on [0.75, 1.25] the two tails round alike at these u; on [-0.3, 0.3]
  // they differ in the last bit at ~40 % of them (a swap of the tails fails)
  std::vector<Case> all = cases();
  all.push_back({"uniform_about_0", make_uniform(-0.3, 0.3), -0.3, 0.3});
  for (const auto &c : all) {
    const Distribution &d = *c.d;
    int low = 0;
    for (const Uniform &u : us) {
      const double want = u.u < 0.5 ? d.isf(u.u) : d.quantile(u.one_minus_u);
      const double got = d.sample(u);
      const double base = d.Distribution::sample(u);
      ASSERT_EQ(std::memcmp(&want, &got, sizeof want), 0) << c.name << " u " << u.u;
      ASSERT_EQ(std::memcmp(&base, &got, sizeof base), 0) << c.name << " u " << u.u;
      low += u.u < 0.5;
    }
    EXPECT_GT(low, 1000) << c.name;    // both tails taken
    EXPECT_LT(low, 3000) << c.name;
  }
}

TEST(Distributions, DeltaIsAPointMass)
{
  const auto d = make_delta(0.2);
  EXPECT_TRUE(d->is_point());
  EXPECT_EQ(d->sample(draw(1, 1, 1, 1)), 0.2);
  EXPECT_EQ(d->cdf(0.1999), 0.0);
  EXPECT_EQ(d->cdf(0.2), 1.0);
  EXPECT_NEAR(d->sf_integral(-1.0, 1.0), 1.2, 1e-15);
}

/* ---------------------------------------------------------------------- */

namespace {
std::string parse_error(Role role, std::vector<std::string> args)
{
  size_t pos = 0;
  try {
    parse_distribution(role, args, pos, parse_number);
  } catch (const SpecError &e) {
    return e.what();
  }
  return "no error";
}
}    // namespace

TEST(Tables, ReadPotentialsFile)
{
  const std::string path = std::string(FEQ_SOURCE_DIR) + "/potentials/eq_thresholds.table";
  std::vector<double> x, p;
  read_table_file(path, "UNIFORM_0.75_1.25", x, p);
  const auto t = make_table(x, p, "u");
  const auto u = make_uniform(0.75, 1.25);
  for (double v : {0.7, 0.8, 1.0, 1.2, 1.3}) {
    EXPECT_NEAR(t->cdf(v), u->cdf(v), 1e-15);
    EXPECT_NEAR(t->sf_integral(0.0, v), u->sf_integral(0.0, v), 1e-15);
  }
  read_table_file(path, "REALISTIC_1.0", x, p);
  // the shipped points are the paper's P_c0(x) = 2 x^3 exp(-x^2) on x = 0.01 i,
  // i = 0..600, to the 15 printed digits (5e-15 relative), plus the
  // abscissa's own rounding (x printed to 10 digits, computed as 0.01 i: an
  // ulp, which moves ln P_c by |3 - 2x^2| eps) and exp's (a few eps)
  ASSERT_EQ(x.size(), 601u);
  const double eps = std::numeric_limits<double>::epsilon();
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_NEAR(x[i], 0.01 * i, 1e-15 * (1 + x[i]));
    const double rel = 5e-15 + (std::fabs(3.0 - 2.0 * x[i] * x[i]) + 4.0) * eps;
    EXPECT_NEAR(p[i], 2.0 * x[i] * x[i] * x[i] * std::exp(-x[i] * x[i]), rel * p[i] + 1e-300) << x[i];
  }
  const auto r = make_table(x, p, "r");
  const auto ra = make_realistic(1.0);
  // linear interpolation on a 0.01 grid: error ~ h^2 f''/8
  for (double v : {0.3, 0.9, 1.5, 2.5}) EXPECT_NEAR(r->cdf(v), ra->cdf(v), 2e-5);
  EXPECT_NEAR(r->mean(), ra->mean(), 2e-5);
}

TEST(Tables, ErrorsNameFileKeywordAndLine)
{
  std::vector<double> x, p;
  try {
    read_table_file("/nonexistent/file.table", "K", x, p);
    FAIL();
  } catch (const SpecError &e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot open table file '/nonexistent/file.table'"));
  }
  const std::string path = std::string(FEQ_SOURCE_DIR) + "/potentials/eq_thresholds.table";
  try {
    read_table_file(path, "NO_SUCH_KEY", x, p);
    FAIL();
  } catch (const SpecError &e) {
    EXPECT_THAT(e.what(), HasSubstr("keyword 'NO_SUCH_KEY' not found"));
  }
  const std::string bad = "bad_table.tmp";
  {
    std::ofstream out(bad);
    out << "KEY\nN 3\n\n1 0.5 1.0\n2 0.7 abc\n3 0.9 1.0\n"
        << "SHORT\nN 4\n\n1 0.1 1\n2 0.2 1\n"
        << "NEG\nN 2\n\n1 0.1 -1\n2 0.2 1\n";
  }
  try {
    read_table_file(bad, "KEY", x, p);
    FAIL();
  } catch (const SpecError &e) {
    EXPECT_THAT(e.what(), HasSubstr("line 5"));
  }
  try {
    read_table_file(bad, "SHORT", x, p);
    FAIL();
  } catch (const SpecError &e) {
    EXPECT_THAT(e.what(), HasSubstr("expected 4 points"));
  }
  read_table_file(bad, "NEG", x, p);
  EXPECT_THROW(make_table(x, p, "neg"), SpecError);
  std::remove(bad.c_str());
}

// A path that is a directory opens as a stream on Linux and reads as
// empty: the message said "keyword ... not found"; it names the cause
TEST(Tables, DirectoryIsNamedAsSuch)
{
  std::vector<double> x, p;
  const std::string dir = std::string(FEQ_SOURCE_DIR) + "/potentials";
  try {
    read_table_file(dir, "K", x, p);
    FAIL();
  } catch (const SpecError &e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot open table file '" + dir + "': it is a directory, not a file");
  }
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"table", ".", "K"}),
              "threshold table: cannot open table file '.': it is a directory, not a file");
  try {
    load_file("/nonexistent/file.table");
    FAIL();
  } catch (const SpecError &e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot open table file '/nonexistent/file.table' (No such file or directory)");
  }
}

// Numbers of tables: strtod reads subnormal and out-of-range values (most
// with ERANGE): they were all "expected a number", and an exact subnormal
// (0x1p-1030, no ERANGE) was read silently
TEST(Tables, NumbersNameTheCause)
{
  EXPECT_EQ(parse_number("2.2250738585072014e-308"), std::numeric_limits<double>::min());
  EXPECT_EQ(parse_number("-0"), 0.0);
  EXPECT_EQ(parse_number("1e-300"), 1e-300);
  EXPECT_EQ(parse_number("1.7976931348623157e308"), std::numeric_limits<double>::max());
  auto why = [](const std::string &tok) -> std::string {
    try {
      parse_number(tok);
    } catch (const SpecError &e) {
      return e.what();
    }
    return "no error";
  };
  const std::string sub = "is subnormal (nonzero and smaller in magnitude than 2.225073859e-308, "
                          "the smallest normal double: it would lose precision); write 0 or a "
                          "normal number";
  EXPECT_EQ(why("1e-310"), "value '1e-310' " + sub);
  EXPECT_EQ(why("-1e-310"), "value '-1e-310' " + sub);
  EXPECT_EQ(why("4.9e-324"), "value '4.9e-324' " + sub);
  EXPECT_EQ(why("0x1p-1030"), "value '0x1p-1030' " + sub);
  EXPECT_EQ(why("2.2250738585072009e-308"), "value '2.2250738585072009e-308' " + sub);
  EXPECT_EQ(why("1e-400"), "value '1e-400' is below the subnormal range of a double (it would be "
                           "read as 0); write 0 or a normal number");
  EXPECT_EQ(why("1e400"),
            "value '1e400' is beyond the range of a double (largest 1.797693135e+308)");
  EXPECT_EQ(why("-inf"), "value '-inf' is infinite");
  EXPECT_EQ(why("nan"), "value 'nan' is not a number (NaN)");
  EXPECT_EQ(why("abc"), "expected a number, got 'abc'");
  EXPECT_EQ(why("1.5x"), "expected a number, got '1.5x'");
  EXPECT_EQ(why(""), "expected a number, got ''");

  // in a table: file, line and value
  std::vector<double> x, p;
  auto table_error = [&](const std::string &text) -> std::string {
    try {
      read_table_text(text, "t.table", "K", x, p);
    } catch (const SpecError &e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(table_error("# c\nK\nN 3\n\n1 0.5 0.0\n2 0.8 1e-310\n3 1.0 0.0\n"),
            "table file 't.table' line 6: value '1e-310' " + sub);
  EXPECT_EQ(table_error("K\nN 3\n\n1 0.5 0.0\n2 1e-320 1.0\n3 1.0 0.0\n"),
            "table file 't.table' line 5: value '1e-320' " + sub);
  EXPECT_EQ(table_error("K\nN 3\n\n1 0.5 0.0\n2 0.8 1e-400\n3 1.0 0.0\n"),
            "table file 't.table' line 5: value '1e-400' is below the subnormal range of a "
            "double (it would be read as 0); write 0 or a normal number");
  EXPECT_EQ(table_error("K\nN 3\n\n1 0.5 0.0\n2 0.8 2.2250738585072014e-308\n3 1.0 0.0\n"),
            "no error");
  // the command line: the cause after the keyword and the value's name
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"uniform", "1e-310", "1.25"}),
            "threshold uniform: lo: value '1e-310' " + sub);
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"uniform", "0.75", "x2"}),
            "threshold uniform: expected a number for hi, got 'x2'");
}

// The 'N n' line and the point count (fuzz: 'N 2.5' was read as N 2, more
// points than N were dropped, a flag after N was ignored)
TEST(Tables, CountLineAndPointCountAreExact)
{
  const std::string pts = "\n1 0.5 0.0\n2 0.8 2.0\n3 1.0 1.0\n4 1.3 0.0\n";
  auto error = [](const std::string &text, const std::string &key = "BAD") -> std::string {
    std::vector<double> x, p;
    try {
      read_table_text(text, "t.table", key, x, p);
    } catch (const SpecError &e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error("# t\nBAD\nN 2.5\n" + pts),
            "table file 't.table' line 3: expected 'N <count>' with count >= 2 after keyword "
            "'BAD' (got 'N 2.5': not an integer)");
  EXPECT_THAT(error("BAD\nN 4x\n" + pts), HasSubstr("(got 'N 4x': not an integer)"));
  EXPECT_THAT(error("BAD\nN 1\n" + pts), HasSubstr("count >= 2 after keyword 'BAD' (got 'N 1')"));
  EXPECT_EQ(error("# t\nBAD\nN 3\n" + pts),
            "table file 't.table' section 'BAD': more points than 'N 3' (line 3) says: point 4 "
            "on line 8; the point count must equal N");
  EXPECT_EQ(error("# t\nBAD\nN 4 iso\n" + pts),
            "table file 't.table' line 3: unknown flag 'iso' after 'N 4' (threshold and "
            "substrate tables take no flags)");
  EXPECT_THAT(error("BAD\nN 4 aniso\n" + pts), HasSubstr("unknown flag 'aniso'"));
  // exact counts pass, with comments and blank lines after the points and
  // the next section right behind
  std::vector<double> x, p;
  read_table_text("BAD\nN 4\n" + pts + "\n# next\n\nOTHER\nN 2\n\n1 0 1\n2 1 1\n", "t", "BAD",
                  x, p);
  EXPECT_EQ(x.size(), 4u);
  read_table_text("BAD\nN 4\n" + pts + "\n# next\n\nOTHER\nN 2\n\n1 0 1\n2 1 1\n", "t",
                  "OTHER", x, p);
  EXPECT_EQ(x.size(), 2u);
  EXPECT_EQ(error("BAD\nN 4\n" + pts + "# end\n"), "no error");
}

// Every shipped threshold table has exactly the points its N line says.
TEST(Tables, ShippedThresholdTablesAreExact)
{
  const std::string path = std::string(FEQ_SOURCE_DIR) + "/potentials/eq_thresholds.table";
  std::ifstream in(path);
  std::string line;
  int sections = 0;
  std::vector<std::string> keys;
  std::string prev;
  while (std::getline(in, line)) {
    if (line.rfind("N ", 0) == 0 && !prev.empty()) keys.push_back(prev);
    std::istringstream ws(line);
    std::string w;
    if (ws >> w && w[0] != '#') prev = w;
  }
  for (const auto &k : keys) {
    std::vector<double> x, p;
    EXPECT_NO_THROW(read_table_file(path, k, x, p)) << k;
    ++sections;
  }
  EXPECT_GE(sections, 2);
}

/* ---------------------------------------------------------------------- */

TEST(Parse, ValidSpecs)
{
  size_t pos = 0;
  std::vector<std::string> a{"uniform", "0.75", "1.25", "next"};
  auto s = parse_distribution(Role::THRESHOLD, a, pos, parse_number);
  EXPECT_EQ(pos, 3u);
  EXPECT_EQ(s.text, "uniform 0.75 1.25");
  pos = 0;
  std::vector<std::string> b{"none"};
  EXPECT_EQ(parse_distribution(Role::REFORM, b, pos, parse_number).dist, nullptr);
  pos = 0;
  std::vector<std::string> c{"constant"};
  EXPECT_EQ(parse_distribution(Role::STIFFNESS, c, pos, parse_number).dist->mean(), 1.0);
}

TEST(Parse, ErrorsNameKeywordAndAllowedValues)
{
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"uniform", "1.25", "0.75"}),
            "threshold uniform: need 0 <= lo < hi (got lo = 1.25, hi = 0.75)");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"uniform", "-0.1", "0.75"}),
            "threshold uniform: need 0 <= lo < hi (got lo = -0.1, hi = 0.75)");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"uniform", "1.0"}),
            "threshold uniform: expected 2 values (lo hi), got 1");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"uniform", "1.0", "x2"}),
            "threshold uniform: expected a number for hi, got 'x2'");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"weibull", "1"}),
            "threshold unknown style 'weibull'; allowed: uniform, gaussian, realistic, table");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {}),
            "threshold: missing style; allowed: uniform, gaussian, realistic, table");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"gaussian", "1.0", "0"}),
            "threshold gaussian: need a finite mean and sd > 0 (got mean = 1, sd = 0)");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"gaussian", "-1.0", "0.1"}),
            "threshold gaussian: need mean > 0 (got -1)");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"realistic", "0"}), "threshold realistic: need xs > 0 (got 0)");
  EXPECT_EQ(parse_error(Role::THRESHOLD, {"table", "f"}),
            "threshold table: expected 2 values (file keyword), got 1");
  EXPECT_THAT(parse_error(Role::THRESHOLD, {"table", "/no/file", "K"}),
              HasSubstr("threshold table: cannot open table file '/no/file'"));
  EXPECT_EQ(parse_error(Role::REFORM, {"realistic", "1"}),
            "reform unknown style 'realistic'; allowed: delta, uniform, gaussian, none");
  EXPECT_EQ(parse_error(Role::REFORM, {"uniform", "0.2", "0.1"}),
            "reform uniform: need lo < hi (got lo = 0.2, hi = 0.1)");
  EXPECT_EQ(parse_error(Role::STIFFNESS, {"uniform", "0", "2"}),
            "stiffness uniform: need 0 < lo < hi (got lo = 0, hi = 2)");
  EXPECT_EQ(parse_error(Role::STIFFNESS, {"gaussian", "-1", "0.2"}),
            "stiffness gaussian: need mean > 0 (got -1)");
  EXPECT_EQ(parse_error(Role::STIFFNESS, {"delta", "1"}),
            "stiffness unknown style 'delta'; allowed: constant, uniform, gaussian");
}
