// Unit tests: temperature, aging and delays of one contact
// (lib/eq_thermal, ContactModel::advance()).  References: closed forms
// (a delay shifts re-formation by tau; a contact that ages breaks where
// x = x_s0 A(x/v)), the memoryless law of the
// break times over many contacts, and the athermal engine (resolve())
// for the same draws.
#include "eq_contact.h"
#include "eq_distribution.h"
#include "eq_keywords.h"
#include "eq_random.h"
#include "eq_thermal.h"

#include "gtest/gtest.h"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace feq;

namespace {

DistributionSpec spec(DistributionPtr d, const std::string &text)
{
  DistributionSpec s;
  s.dist = std::move(d);
  s.text = text;
  return s;
}

ContactModel model(const ThermalSpec &t, bool exact = true,
                   DistributionSpec threshold = spec(make_uniform(0.75, 1.25), "uniform 0.75 1.25"))
{
  return ContactModel(1.0, 4711, std::move(threshold), spec(make_delta(0.0), "delta 0"),
                      DistributionSpec{}, exact, true, false, t);
}

ThermalSpec thermal(double theta)
{
  ThermalSpec t;
  t.theta = theta;
  return t;
}

std::vector<double> row(const ContactModel &m, uint64_t tag)
{
  std::vector<double> r(m.columns(), 0.0);
  m.form(r.data(), tag, 0.0);
  return r;
}

}    // namespace

TEST(Thermal, LayoutOnlyWithTheNewTerms)
{
  EXPECT_EQ(model(ThermalSpec()).columns(), CS_NCOL);
  EXPECT_EQ(model(thermal(0.02)).columns(), CT_NCOL);
  ThermalSpec a;
  a.aging = AgingLaw::LOG;
  EXPECT_EQ(model(a).columns(), CT_NCOL);
}

// over many contacts the break times are exponential with mean 1/nu,
// with crossing step at the end of the step in which it happened
TEST(Thermal, BreakTimesAreExponential)
{
  const double theta = 0.1, dt = 2.0;
  for (const bool exact : {true, false}) {
    const ContactModel m = model(thermal(theta), exact, spec(make_delta(1.0), "delta 1"));
    const double x = 0.5, nu = m.thermal_model().rate(x, 1.0);
    const int n = 20000;
    double sum = 0.0;
    for (uint64_t tag = 1; tag <= static_cast<uint64_t>(n); ++tag) {
      std::vector<double> r = row(m, tag);
      r[CS_STRETCH] = x;
      long nb = 0;
      int k = 0;
      while (nb == 0) {
        m.advance(r.data(), tag, x, dt, nb);
        ++k;
      }
      sum += k * dt - r[CT_AGE];
    }
    const double mean = sum / n;
    // exact: mean 1/nu, sd 1/nu; step: the geometric law, mean dt/(1 - e^{-nu dt})
    const double expect = exact ? 1.0 / nu : dt / (1.0 - std::exp(-nu * dt));
    const double sd = exact ? 1.0 / nu : dt * std::sqrt(std::exp(-nu * dt)) / (1.0 - std::exp(-nu * dt));
    EXPECT_LT(std::fabs(mean - expect), 4.0 * sd / std::sqrt(n)) << exact << " " << mean << " " << expect;
  }
}

// at T = 0 without aging or delays (the thermal layout switched on by a
// rest age only) the contact breaks and carries its overshoot as the
// athermal engine does, draw for draw
TEST(Thermal, AthermalStepsMatchTheAthermalEngine)
{
  ThermalSpec t;
  t.rest = 5.0;
  for (const bool exact : {true, false}) {
    const ContactModel mt = model(t, exact);
    const ContactModel m0 = model(ThermalSpec(), exact);
    for (uint64_t tag = 1; tag <= 20; ++tag) {
      std::vector<double> a = row(mt, tag), b = row(m0, tag);
      long na = 0, nb = 0;
      double x = 0.0;
      for (int step = 0; step < 400; ++step) {
        x += 0.037;
        const ThermalStepResult res = mt.advance(a.data(), tag, x - a[CS_ANCHOR], 1.0, na);
        const double s = res.stretch;
        if (res.renewed) a[CS_ANCHOR] = x - s;
        const double s0 = m0.resolve(b.data(), tag, x - b[CS_ANCHOR], 0.0, nb);
        b[CS_ANCHOR] = x - s0;
        ASSERT_EQ(na, nb) << tag << " " << step;
        ASSERT_NEAR(s, s0, 1e-12) << tag << " " << step;
        ASSERT_EQ(a[CS_THRESHOLD], b[CS_THRESHOLD]);
      }
      EXPECT_GT(na, 10);
    }
  }
}

// a fixed delay: the contact re-forms tau after it broke (crossing
// exact), so at constant velocity its stretch at a step end is
// v (t_end - t_break - tau); it carries no force while it waits
TEST(Thermal, FixedDelayReformsTauAfterTheBreak)
{
  ThermalSpec t;
  t.delay = DelayKind::FIXED;
  t.tau = 2.3;
  const ContactModel m = model(t, true, spec(make_delta(1.0), "delta 1"));
  const double v = 0.1, dt = 0.7;
  std::vector<double> r = row(m, 3);
  long nb = 0;
  double x = 0.0, anchor = 0.0;
  int waits = 0;
  for (int step = 1; step <= 200; ++step) {
    x = v * dt * step;
    const double m_in = r[CT_WAIT] > 0.0 ? x - anchor : x - r[CS_ANCHOR];
    const ThermalStepResult res = m.advance(r.data(), 3, m_in, dt, nb);
    if (!res.attached) {
      anchor = x;
      ++waits;
      EXPECT_EQ(r[CS_STRETCH], 0.0);
      continue;
    }
    if (res.renewed) r[CS_ANCHOR] = x - res.stretch;    // as fix eq/contacts does
    // breaks at x_s = 1, i.e. every (1/v + tau) in time
    const double period = 1.0 / v + t.tau;
    const double t_end = dt * step;
    const double since = std::fmod(t_end, period);    // time since the last re-formation
    EXPECT_NEAR(res.stretch, v * since, 1e-9) << step;
  }
  EXPECT_GT(nb, 5);
  EXPECT_GT(waits, 5);
}

// threshold aging at T = 0: one threshold x_s0 = 1, log law; at velocity
// v the contact breaks where x = A(x/v), found here by bisection
TEST(Thermal, AgingContactBreaksWhereItsThresholdIsReached)
{
  ThermalSpec t;
  t.aging = AgingLaw::LOG;
  t.beta = 0.05;
  t.tau_a = 1.0;
  const ContactModel m = model(t, true, spec(make_delta(1.0), "delta 1"));
  for (const double v : {1e-2, 1e-4}) {
    double lo = 1.0, hi = 3.0;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (mid < m.thermal_model().factor(mid / v) ? lo : hi) = mid;
    }
    const double xstar = 0.5 * (lo + hi);
    std::vector<double> r = row(m, 9);
    long nb = 0;
    const double dt = 0.013 / v;    // dX = 0.013
    int n = 0;
    double x = 0.0;
    while (nb == 0) {
      x = v * dt * ++n;
      const ThermalStepResult res = m.advance(r.data(), 9, x - r[CS_ANCHOR], dt, nb);
      if (res.renewed) r[CS_ANCHOR] = x - res.stretch;
    }
    // the new contact started at the break and moved for its age since
    const double xb = x - v * r[CT_AGE];
    // linear interpolation of |s| - x_s(age) within a step: error ~ dX^2 A''
    EXPECT_NEAR(xb, xstar, 1e-3) << v;
    EXPECT_GT(xstar, 1.2);
  }
}

TEST(Thermal, KeywordsNameWhatIsWrong)
{
  const NumberParser number = [](const std::string &s) { return std::stod(s); };
  auto parse = [&](std::vector<std::string> args) {
    ThermalKeywords t;
    size_t iarg = 1;
    const bool known = parse_thermal_keyword(args[0], args, iarg, number, t);
    EXPECT_EQ(iarg, known ? args.size() : 1u);
    return t;
  };
  EXPECT_NEAR(parse({"thermal", "0.5", "25", "2"}).finish(1.0, 1.0).theta, 0.02, 1e-15);
  EXPECT_EQ(parse({"aging", "exp", "0.1", "3"}).spec.aging, AgingLaw::EXP);
  EXPECT_EQ(parse({"delay", "exp", "10"}).spec.delay, DelayKind::EXPONENTIAL);
  auto message = [&](std::vector<std::string> args) {
    try {
      parse(args);
    } catch (const SpecError &e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({"thermal", "1", "0", "1"}).find("thermal eps_a: must be > 0"), std::string::npos);
  EXPECT_NE(message({"aging", "cubic"}).find("aging: unknown value 'cubic'; allowed: none, log, exp"),
            std::string::npos);
  EXPECT_NE(message({"delay", "fixed", "-1"}).find("delay tau: must be >= 0"), std::string::npos);
  EXPECT_NE(message({"rest"}).find("rest t_w: missing value"), std::string::npos);
  EXPECT_NE(message({"barrier", "2"}).find("barrier q: missing value"), std::string::npos);
}

// the hazard of a step (the midpoint rate from the end rates and a series)
// equals Simpson's rule with three rates evaluated directly, to rounding,
// with and without aging, barrier exponents, cached start rates (the
// tolerance as for the rates below)
TEST(Thermal, HazardIsSimpsonsRule)
{
  for (const double p : {0.0, 2.0})
    for (const double q : {0.0, 0.25})
      for (const AgingLaw law : {AgingLaw::NONE, AgingLaw::LOG, AgingLaw::EXP}) {
        ThermalSpec t = thermal(0.03);
        t.p = p;
        t.q = q;
        t.aging = law;
        t.beta = 0.1;
        t.tau_a = 2.0;
        t.xc = 1.1;
        const ThermalModel m(t);
        for (const double h : {1e-3, 0.5, 40.0})
          for (const double x0 : {0.1, 0.6, -0.8}) {
            const double x1 = x0 + (x0 > 0 ? 0.002 : -0.002) * h, a0 = 3.0, xs0 = 1.05;
            auto nu = [&](double x, double a) { return m.rate(x, xs0 * m.factor(a)); };
            const double simpson =
                h / 6.0 * (nu(x0, a0) + 4.0 * nu(0.5 * (x0 + x1), a0 + 0.5 * h) + nu(x1, a0 + h));
            RatePoint end;
            const double direct = m.hazard(x0, x1, a0, h, xs0, nullptr, &end);
            EXPECT_NEAR(direct, simpson, 1e-13 * simpson) << p << q << h << x0;
            // rounding of the exponent psi (|psi| < 50 here) is amplified by
            // |psi|: a relative error of about |psi| 4 eps < 5e-14
            EXPECT_NEAR(end.nu, nu(x1, a0 + h), 1e-13 * end.nu);
            // the start from a cached point gives the same
            const RatePoint start = m.point(x0, xs0 * m.factor(a0));
            EXPECT_EQ(m.hazard(x0, x1, a0, h, xs0, &start, nullptr), direct);
            EXPECT_GT(simpson, 0.0);
          }
      }
}

// step(), the inline common case, gives advance()'s numbers to the last
// bit, step after step (thermal, aging, delays; both crossings)
TEST(Thermal, InlineStepIsAdvance)
{
  ThermalSpec t = thermal(0.05);
  t.aging = AgingLaw::LOG;
  t.beta = 0.05;
  t.delay = DelayKind::EXPONENTIAL;
  t.tau = 0.3;
  for (const bool exact : {true, false}) {
    const ContactModel m = model(t, exact);
    for (uint64_t tag = 1; tag <= 40; ++tag) {
      std::vector<double> a = row(m, tag), b = a;
      long na = 0, nb = 0;
      int fast = 0;
      for (int k = 1; k <= 2000; ++k) {
        const double x = 0.011 * k + 0.3 * std::sin(0.05 * k);    // back and forth
        const double dt = 0.2;
        // attached: the stretch x - anchor; waiting: the motion since the
        // anchor (the atom's position at the last step end)
        auto in = [&](const std::vector<double> &r) { return x - r[CS_ANCHOR]; };
        const bool quick = a[CT_WAIT] <= 0.0 && std::fabs(in(a)) < a[CT_XS_LOW];
        const ThermalStepResult ra = m.step(a.data(), tag, in(a), dt, na);
        const ThermalStepResult rb = m.advance(b.data(), tag, in(b), dt, nb);
        for (std::vector<double> *r : {&a, &b}) {    // as fix eq/contacts does
          const ThermalStepResult &res = r == &a ? ra : rb;
          if (!res.attached && (*r)[CS_THRESHOLD] > 0.0) (*r)[CS_ANCHOR] = x;
          else if (res.renewed) (*r)[CS_ANCHOR] = x - res.stretch;
        }
        fast += quick && !ra.renewed;
        ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(double))) << tag << " " << k;
        ASSERT_EQ(na, nb);
      }
      EXPECT_GT(na, 10);
      EXPECT_GT(fast, 1000);
    }
  }
}

// the law of thermal breaks of held and loaded contacts (thinning: exact
// in law for any step) is tested in test_eq_contact.cpp (Thinning.*)
