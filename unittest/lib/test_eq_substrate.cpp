// Unit tests of the FK-ME substrate shapes (lib/eq_substrate): periodic
// prolongation, the potential against independent quadrature, the jumps
// of the sawtooth, tables, and the table writer read back by the reader
// fix eq/substrate uses.
#include "eq_distribution.h"
#include "eq_substrate.h"

#include "gtest/gtest.h"

#include <cmath>
#include <string>
#include <vector>

using feq::SubstrateShape;

namespace {

// composite Simpson rule with n (even) panels: independent of the
// closed forms in the library
template <class F> double simpson(F f, double a, double b, int n = 20000)
{
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(a + k * h);
  return s * h / 3.0;
}

double smooth_phi(double v)
{
  return std::tanh(v) + 1.5 * std::exp(-v) * std::sin(3.0 * v);
}

}    // namespace

TEST(Substrate, SawtoothIsPeriodicWithJumps)
{
  const SubstrateShape s = SubstrateShape::sawtooth(2.0);
  EXPECT_DOUBLE_EQ(s.period(), 2.0);
  EXPECT_DOUBLE_EQ(s.phi(0.0), 0.0);
  EXPECT_DOUBLE_EQ(s.phi(0.5), 0.5);
  EXPECT_NEAR(s.phi(std::nextafter(2.0, 0.0)), 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.phi(2.0), 0.0);    // the block has slipped: force from the next well
  EXPECT_DOUBLE_EQ(s.phi(-0.5), 1.5);
  EXPECT_DOUBLE_EQ(s.phi(7.25), 1.25);
  EXPECT_DOUBLE_EQ(s.work(), 2.0);    // uc^2 / 2
  EXPECT_DOUBLE_EQ(s.max_phi(), 2.0);
  // continuous potential, one work W per period
  for (int n = -3; n <= 3; ++n) {
    EXPECT_NEAR(s.potential(2.0 * n), n * s.work(), 1e-13);
    EXPECT_NEAR(s.potential(std::nextafter(2.0 * n, -1e9)), n * s.work(), 1e-12);
  }
  // rounding: u - floor(u/uc) uc evaluates to uc for u = -1e-17; the
  // reduction keeps 0 <= r < uc (the block is at the start of its well)
  EXPECT_GE(s.phi(-1e-17), 0.0);
  EXPECT_LT(s.phi(-1e-17), 2.0);
  EXPECT_NEAR(s.potential(-1e-17), 0.0, 1e-15);
}

TEST(Substrate, PotentialIsTheIntegralOfPhi)
{
  const std::vector<SubstrateShape> shapes = {SubstrateShape::sawtooth(1.0),
                                              SubstrateShape::smooth(1.0),
                                              SubstrateShape::smooth(2.5)};
  for (const auto &s : shapes) {
    const double uc = s.period();
    // W by quadrature of phi over one period
    EXPECT_NEAR(s.work(), simpson([&](double v) { return s.phi(v); }, 0.0, std::nextafter(uc, 0.0)),
                1e-10)
        << s.describe();
    // dV/du = phi away from the jumps (central differences, error h^2)
    const double h = 1e-5;
    for (double u = -2.3; u < 4.0; u += 0.137) {
      const double r = u - uc * std::floor(u / uc);
      if (r < 2 * h || r > uc - 2 * h) continue;
      EXPECT_NEAR((s.potential(u + h) - s.potential(u - h)) / (2 * h), s.phi(u), 1e-8)
          << s.describe() << " u = " << u;
    }
  }
}

TEST(Substrate, SmoothShapeMatchesThePaper)
{
  const SubstrateShape s = SubstrateShape::smooth(1.0);
  for (double v = 0.0; v < 1.0; v += 0.0625) EXPECT_NEAR(s.phi(v), smooth_phi(v), 1e-15);
  EXPECT_NEAR(s.phi(1.3), smooth_phi(0.3), 1e-14);
  // the static peak: phi' = 0 there and no grid point is higher
  const double v0 = s.argmax_phi();
  EXPECT_GT(v0, 0.0);
  EXPECT_LT(v0, 1.0);
  const double d = 1e-6;
  EXPECT_NEAR((smooth_phi(v0 + d) - smooth_phi(v0 - d)) / (2 * d), 0.0, 1e-7);
  for (int k = 0; k <= 100000; ++k) EXPECT_LE(smooth_phi(k * 1e-5), s.max_phi() + 1e-15);
  // a long period: log cosh does not overflow
  const SubstrateShape big = SubstrateShape::smooth(800.0);
  EXPECT_TRUE(std::isfinite(big.work()));
  EXPECT_NEAR(big.potential(700.0) - big.potential(699.0),
              simpson([&](double v) { return smooth_phi(v); }, 699.0, 700.0, 2000), 1e-9);
}

TEST(Substrate, TableInterpolatesLinearly)
{
  const std::vector<double> u = {0.0, 0.25, 0.5, 1.0}, p = {0.0, 1.0, 0.5, 0.8};
  const SubstrateShape s = SubstrateShape::table(u, p, "test T");
  EXPECT_EQ(s.kind(), SubstrateShape::TABLE);
  EXPECT_DOUBLE_EQ(s.period(), 1.0);
  EXPECT_DOUBLE_EQ(s.phi(0.125), 0.5);
  EXPECT_DOUBLE_EQ(s.phi(0.375), 0.75);
  EXPECT_DOUBLE_EQ(s.phi(0.75), 0.65);
  EXPECT_DOUBLE_EQ(s.phi(1.125), 0.5);
  EXPECT_DOUBLE_EQ(s.max_phi(), 1.0);
  EXPECT_DOUBLE_EQ(s.argmax_phi(), 0.25);
  // trapezoids are exact for a piecewise linear phi
  EXPECT_NEAR(s.work(), 0.125 + 0.1875 + 0.325, 1e-15);
  EXPECT_NEAR(s.potential(0.375), 0.125 + 0.125 * 0.875, 1e-15);
  EXPECT_NEAR(s.potential(-0.625), -s.work() + s.potential(0.375), 1e-15);
}

TEST(Substrate, TableOfTheSmoothShapeConverges)
{
  // a table sampled from the smooth shape approaches it at second order
  double err[2];
  for (int m = 0; m < 2; ++m) {
    const int n = m ? 400 : 200;
    std::vector<double> u(n + 1), p(n + 1);
    for (int k = 0; k <= n; ++k) u[k] = double(k) / n, p[k] = smooth_phi(u[k]);
    const SubstrateShape t = SubstrateShape::table(u, p, "smooth sampled");
    err[m] = 0.0;
    for (double v = 0.001; v < 1.0; v += 0.00731) err[m] = std::max(err[m], std::fabs(t.phi(v) - smooth_phi(v)));
  }
  EXPECT_GT(err[0] / err[1], 3.5);
  EXPECT_LT(err[0] / err[1], 4.5);
}

TEST(Substrate, BadInputIsRejected)
{
  EXPECT_THROW(SubstrateShape::sawtooth(0.0), feq::SpecError);
  EXPECT_THROW(SubstrateShape::smooth(-1.0), feq::SpecError);
  EXPECT_THROW(SubstrateShape::table({0.0}, {1.0}, "one"), feq::SpecError);
  EXPECT_THROW(SubstrateShape::table({0.1, 1.0}, {0.0, 1.0}, "start"), feq::SpecError);
  EXPECT_THROW(SubstrateShape::table({0.0, 0.5, 0.5}, {0.0, 1.0, 1.0}, "order"), feq::SpecError);
  EXPECT_THROW(SubstrateShape::table({0.0, 1.0}, {0.0, NAN}, "nan"), feq::SpecError);
  try {
    SubstrateShape::table({0.0, 0.5, 0.4}, {0.0, 1.0, 1.0}, "f.table KEY");
    FAIL();
  } catch (const feq::SpecError &e) {
    EXPECT_NE(std::string(e.what()).find("f.table KEY"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("must increase"), std::string::npos);
  }
}

TEST(Substrate, TableTextRoundTrip)
{
  const std::vector<double> u = {0.0, 0.1, 0.35, 1.0}, p = {0.0, 0.2, 1.25, 0.9};
  const std::string text = feq::substrate_table_text("BLOCK", u, p, "two\nlines");
  std::vector<double> u2, p2;
  feq::read_table_text(text, "mem", "BLOCK", u2, p2);
  ASSERT_EQ(u2.size(), u.size());
  for (size_t k = 0; k < u.size(); ++k) {
    EXPECT_DOUBLE_EQ(u2[k], u[k]);
    EXPECT_DOUBLE_EQ(p2[k], p[k]);
  }
}
