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

// ---------------------------------------------------------------------------
// thermally activated hops of a sawtooth block (BlockHops)

namespace {
feq::ThermalSpec hop_spec(double theta, double omega, double p = 0.0, double q = 0.0)
{
  feq::ThermalSpec s;
  s.theta = theta;
  s.omega = omega;
  s.p = p;
  s.q = q;
  s.xc = 1.0;
  return s;
}
}    // namespace

TEST(SubstrateHops, AthermalCrossingIsTheEndOfTheWell)
{
  // T = 0: only the ends of the well; the change at the linear crossing
  const feq::BlockHops hop(hop_spec(0.0, 1.0), 1.0, 7);
  feq::HopState st;
  st.budget = hop.budget(3, 0);
  feq::WellChange ch[feq::BlockHops::MAX_CHANGES];
  int n = hop.step(3, 0.9, 1.3, 1.0, 0.1, true, st, ch);
  ASSERT_EQ(n, 1);
  EXPECT_NEAR(ch[0].theta, 0.25, 1e-15);
  EXPECT_EQ(ch[0].sign, 1);
  EXPECT_FALSE(ch[0].thermal);
  EXPECT_EQ(st.anchor, 1.0);
  EXPECT_EQ(st.life, 1.0);
  EXPECT_EQ(st.hops, 0.0);
  EXPECT_EQ(st.budget, hop.budget(3, 1));
  // backward through -u_c twice with crossing step (both at the end)
  n = hop.step(3, 1.3, -1.5, 1.0, 0.1, false, st, ch);
  ASSERT_EQ(n, 2);
  EXPECT_EQ(ch[0].sign, -1);
  EXPECT_EQ(ch[1].sign, -1);
  EXPECT_EQ(ch[0].theta, 1.0);
  EXPECT_EQ(st.anchor, -1.0);
  EXPECT_EQ(st.life, 3.0);
}

TEST(SubstrateHops, HopAtFixedStretchIsWhereTheBudgetRunsOut)
{
  // a block held at s: the hazard nu t reaches the budget b at t = b / nu,
  // nu = omega exp(-(1 - s)^(3/2) / theta) (written out here)
  const double theta = 0.05, omega = 2.0, s = 0.7, dt = 0.37;
  const double nu = omega * std::exp(-std::pow(1.0 - s, 1.5) / theta);
  const feq::BlockHops hop(hop_spec(theta, omega), 1.0, 11);
  EXPECT_NEAR(hop.rate(s, 1.0), nu, 1e-14 * nu);
  for (uint64_t tag = 1; tag <= 20; ++tag) {
    feq::HopState st;
    st.budget = hop.budget(tag, 0);
    const double t_hop = st.budget / nu;
    feq::WellChange ch[feq::BlockHops::MAX_CHANGES];
    int k = 0, n = 0;
    while (n == 0 && k < 1000000) n = hop.step(tag, s, s, 1.0, dt, true, st, ch), ++k;
    ASSERT_EQ(n, 1);
    EXPECT_TRUE(ch[0].thermal);
    EXPECT_EQ(ch[0].sign, 1);
    EXPECT_NEAR((k - 1 + ch[0].theta) * dt, t_hop, 1e-9 * t_hop + 1e-12);
    EXPECT_EQ(st.anchor, 1.0);
    EXPECT_EQ(st.hops, 1.0);
    EXPECT_EQ(st.life, 1.0);
  }
}

TEST(SubstrateHops, MovingBlockHopsWhereTheHazardIntegralReachesTheBudget)
{
  // stretch linear in time over one step: the hop fraction against the
  // root of an independent quadrature of the rate (Simpson, 20000 panels).
  // The library's one Simpson panel over the step errs by h^5 max|nu^(4)|
  // / 2880, nu^(4) ~ nu (dpsi/h)^4 for psi = ln nu nearly linear over the
  // step (dpsi = psi(s1) - psi(s0)): a relative error dpsi^4 / 2880 of the
  // step's hazard (x 1.5 for the curvature of psi); the hop fraction errs
  // by that hazard error over nu(s_hop) dt
  const double theta = 0.02, omega = 1e3, d = 1.3, p = 1.0, q = 0.5;
  const feq::BlockHops hop(hop_spec(theta, omega, p, q), 1.0, 5);
  auto nu = [&](double s) {
    const double u = 1.0 - s;
    return omega * std::pow(u, q) * std::exp(-std::pow(d, p) * std::pow(u, 1.5) / theta);
  };
  const double s0 = 0.80, s1 = 0.83, dt = 1.0;
  auto H = [&](double f) {
    return simpson([&](double t) { return nu(s0 + (s1 - s0) * t); }, 0.0, f, 20000) * dt;
  };
  const double Hstep = H(1.0);
  feq::HopState st;
  st.budget = 0.37 * Hstep;
  feq::WellChange ch[feq::BlockHops::MAX_CHANGES];
  const int n = hop.step(9, s0, s1, d, dt, true, st, ch);
  ASSERT_EQ(n, 1);
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (H(mid) < 0.37 * Hstep ? lo : hi) = mid;
  }
  const double dpsi = std::log(nu(s1) / nu(s0));
  const double errH = 1.5 * std::pow(dpsi, 4) / 2880.0 * Hstep;
  const double fhop = 0.5 * (lo + hi);
  EXPECT_NEAR(ch[0].theta, fhop, errH / (nu(s0 + (s1 - s0) * fhop) * dt));
  EXPECT_GT(errH, 1e-5 * Hstep);    // (the bound is not vacuous: Simpson's error is seen)
  // no hop: the budget loses the step's hazard
  feq::HopState st2;
  st2.budget = 2.0 * Hstep;
  EXPECT_EQ(hop.step(9, s0, s1, d, dt, true, st2, ch), 0);
  EXPECT_NEAR(st2.budget, Hstep, errH);
}

TEST(SubstrateHops, BudgetsAreExponentialAndKeyedByTagAndLife)
{
  const feq::BlockHops a(hop_spec(0.1, 1.0), 1.0, 3), b(hop_spec(0.1, 1.0), 1.0, 4);
  EXPECT_EQ(a.budget(5, 2), a.budget(5, 2));
  EXPECT_NE(a.budget(5, 2), a.budget(5, 3));
  EXPECT_NE(a.budget(5, 2), a.budget(6, 2));
  EXPECT_NE(a.budget(5, 2), b.budget(5, 2));
  // mean 1 and P(b > 1) = 1/e within 5 standard errors of n draws
  const int n = 40000;
  double sum = 0.0, above = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = a.budget(1 + k % 200, k / 200);
    sum += x;
    above += x > 1.0;
  }
  EXPECT_NEAR(sum / n, 1.0, 5.0 / std::sqrt(n));
  const double pe = std::exp(-1.0);
  EXPECT_NEAR(above / n, pe, 5.0 * std::sqrt(pe * (1 - pe) / n));
}
