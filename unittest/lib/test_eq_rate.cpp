// Unit tests of the velocity strengthening of an FK-ME block
// (lib/eq_substrate RateLaw, fix eq/substrate ... rate A v0):
// F_rate(w) = A asinh(w/(2 v0)) against independent forms (the logarithm,
// its series at small and large w), its derivative against central
// differences, A = 0, oddness, extreme velocities and the checks of A and
// v0.  Every tolerance is a bound of the neglected series term plus
// rounding, derived in the comments.
#include "eq_distribution.h"
#include "eq_substrate.h"

#include "gtest/gtest.h"

#include <cfloat>
#include <cmath>
#include <limits>
#include <string>

using feq::RateLaw;

namespace {

const double EPS = std::numeric_limits<double>::epsilon();

// the error message of constructing RateLaw(A, v0), "" if it is accepted
std::string message_of(double A, double v0)
{
  try {
    RateLaw r(A, v0);
  } catch (const feq::SpecError &e) {
    return e.what();
  }
  return "";
}

}    // namespace

TEST(Rate, ZeroAmplitudeIsInactiveAndGivesNoForce)
{
  const RateLaw off;
  EXPECT_FALSE(off.active());
  const RateLaw zero(0.0, 1e-3);
  EXPECT_FALSE(zero.active());
  for (double w : {-1e300, -3.0, -1e-300, 0.0, 1e-12, 2.5, 1e300}) {
    EXPECT_EQ(zero.force(w), 0.0) << w;
    EXPECT_EQ(zero.slope(w), 0.0) << w;
  }
  EXPECT_TRUE(RateLaw(1e-300, 1.0).active());
}

TEST(Rate, ForceIsOddAndOpposesNothingAtRest)
{
  const RateLaw r(0.7, 2e-3);
  EXPECT_EQ(r.force(0.0), 0.0);
  for (double w : {1e-9, 1e-4, 3e-3, 0.1, 7.0, 1e10}) {
    EXPECT_GT(r.force(w), 0.0);
    EXPECT_EQ(r.force(-w), -r.force(w)) << w;    // asinh is odd (sign handled exactly)
  }
}

// against ln(x + sqrt(x^2 + 1)), x = w/(2 v0) > 0: the argument y = x +
// sqrt(x^2 + 1) >= 1 is formed with three roundings, a relative error <=
// 2 EPS, which the logarithm turns into an absolute error <= 2 EPS (large
// against the result at small x: ln y ~ x); the logarithm and the
// library's asinh add a few ulp of the result: bound A (4 EPS + 8 EPS |asinh x|)
TEST(Rate, ForceIsTheRegularisedLogarithm)
{
  const double A = 1.3, v0 = 0.25;
  const RateLaw r(A, v0);
  for (double w : {1e-3, 0.1, 0.5, 1.0, 3.0, 40.0, 1e4}) {
    const double x = w / (2.0 * v0);
    const double ref = A * std::log(x + std::sqrt(x * x + 1.0));
    EXPECT_NEAR(r.force(w), ref, 4.0 * EPS * A + 8.0 * EPS * std::fabs(ref)) << w;
  }
}

// w >> v0: asinh x = ln 2x + 1/(4x^2) - 3/(32 x^4) + ..., alternating with
// decreasing terms for x > 1, so with x = w/(2 v0)
//   F - A ln(w/v0) = A v0^2/w^2 - (3/2) A v0^4/w^4 + ...
// and |F - A ln(w/v0) - A v0^2/w^2| <= (3/2) A v0^4/w^4; the rounding of
// A ln(w/v0) ~ 2 EPS A |ln(w/v0)| comes on top
TEST(Rate, LogarithmicAboveV0)
{
  const double A = 0.02, v0 = 1e-6;
  const RateLaw r(A, v0);
  for (double w : {1e-4, 1e-3, 0.05, 1.0, 1e3}) {
    const double L = std::log(w / v0);
    const double rest = r.force(w) - A * L;
    const double bound = 1.5 * A * std::pow(v0 / w, 4) + 4.0 * EPS * A * L;
    EXPECT_NEAR(rest, A * v0 * v0 / (w * w), bound) << w;
    // the slope per e-fold of velocity tends to A: A w/sqrt(w^2 + 4 v0^2)
    EXPECT_NEAR(r.log_slope(w), A, 2.0 * A * v0 * v0 / (w * w) + 4.0 * EPS * A) << w;
  }
}

// |w| << v0: asinh x = x - x^3/6 + 3 x^5/40 - ..., alternating, so
// |F - A x + A x^3/6| <= (3/40) A |x|^5: viscous damping A/(2 v0) with the
// relative correction -x^2/6 (the bound the LAMMPS test against fix viscous uses)
TEST(Rate, ViscousBelowV0)
{
  const double A = 4.0, v0 = 0.5;
  const RateLaw r(A, v0);
  EXPECT_DOUBLE_EQ(r.linear_gamma(), A / (2.0 * v0));
  EXPECT_DOUBLE_EQ(r.slope(0.0), r.linear_gamma());
  for (double w : {1e-8, -1e-5, 1e-3, -0.02, 0.1}) {
    const double x = w / (2.0 * v0);
    const double cubic = A * (x - x * x * x / 6.0);
    EXPECT_NEAR(r.force(w), cubic, 0.075 * A * std::pow(std::fabs(x), 5) + 4.0 * EPS * A * std::fabs(x))
        << w;
  }
}

// the derivative against a central difference with step h: truncation
// h^2 max|F3|/6, F3 = d^3F/dw^3 = A (2w^2 - 4 v0^2)/(w^2 + 4 v0^2)^(5/2), whose
// largest magnitude is A/(8 v0^3) at w = 0, plus the rounding of the
// difference, 2 EPS |F| / (2h)
TEST(Rate, SlopeIsTheDerivative)
{
  const double A = 0.9, v0 = 0.05;
  const RateLaw r(A, v0);
  for (double w : {0.0, 1e-3, -0.02, 0.1, 0.7, 5.0}) {
    const double h = 1e-4;
    const double fd = (r.force(w + h) - r.force(w - h)) / (2.0 * h);
    const double bound = h * h * A / (8.0 * v0 * v0 * v0) / 6.0 +
        2.0 * EPS * std::fabs(r.force(w + h)) / (2.0 * h) + 4.0 * EPS * r.slope(w);
    EXPECT_NEAR(r.slope(w), fd, bound) << w;
    EXPECT_NEAR(r.slope(w), A / std::sqrt(w * w + 4.0 * v0 * v0), 4.0 * EPS * r.slope(w)) << w;
  }
}

// no overflow at extreme velocities: w^2 is not formed
TEST(Rate, ExtremeVelocitiesStayFinite)
{
  // |F_rate| <= A (ln 2 + ln DBL_MAX - ln(2 v0)) <= 1455 A for any v0 > 0
  for (double v0 : {1.0, 1e-10, 1e-300, 4.9e-324}) {
    const RateLaw r(RateLaw::A_MAX, v0);
    for (double w : {DBL_MAX, -DBL_MAX, 1e300, DBL_MIN, -DBL_MIN}) {
      EXPECT_TRUE(std::isfinite(r.force(w))) << w << " v0 " << v0;
      // the slope is at most A / (2 v0): finite where that is
      if (std::isfinite(r.linear_gamma())) EXPECT_TRUE(std::isfinite(r.slope(w))) << w << " v0 " << v0;
      EXPECT_LE(std::fabs(r.force(w)), 1455.0 * RateLaw::A_MAX) << w << " v0 " << v0;
    }
    EXPECT_GT(r.slope(DBL_MAX), 0.0);
  }
}

TEST(Rate, LogarithmContinuesWhereTheArgumentOverflows)
{
  // v0 = 1e-10: w / (2 v0) overflows above w_o = 2e-10 DBL_MAX; on both
  // sides F = ln 2x + 1/(4x^2) with 1/(4x^2) ~ 1e-617, so the two values
  // differ by ln(1.001/0.999) to the rounding of asinh and log at ~700
  // (a few ulps of 700: 1e-12 is a generous bound)
  const RateLaw r(1.0, 1e-10);
  const double wo = 2e-10 * DBL_MAX;
  const double below = r.force(0.999 * wo), above = r.force(1.001 * wo);
  EXPECT_NEAR(above - below, std::log(1.001 / 0.999), 1e-12);
  EXPECT_EQ(r.force(-1.001 * wo), -above);
}

TEST(Rate, BadValuesNameTheirParameter)
{
  EXPECT_EQ(message_of(1.0, 1.0), "");
  EXPECT_EQ(message_of(0.0, 1e-30), "");
  for (double A : {-1.0, -1e-300, std::nan(""), HUGE_VAL, -HUGE_VAL})
    EXPECT_NE(message_of(A, 1.0).find("rate A: must be finite and >= 0"), std::string::npos) << A;
  EXPECT_NE(message_of(1e299, 1.0).find("rate A:"), std::string::npos);
  EXPECT_NE(message_of(1e299, 1.0).find("overflow"), std::string::npos);
  for (double v0 : {0.0, -1.0, std::nan(""), HUGE_VAL})
    EXPECT_NE(message_of(1.0, v0).find("rate v0: must be finite and > 0"), std::string::npos) << v0;
}
