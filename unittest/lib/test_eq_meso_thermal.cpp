// Unit tests: far-zone block at T > 0 with screening (ThermalMesoModel)
// against the independent single-slider renewal solver (ThermalTransient,
// thermal_steady_state: a block with constant eps is a slider loaded at
// w = (1 + eps) v), the athermal block kernel (MesoModel) and the exact
// renewal solution at T = 0, the exact decay at rest, and its conservation
// and state-handling guarantees.
#include "eq_distribution.h"
#include "eq_meso.h"
#include "eq_meso_thermal.h"
#include "eq_renewal_exact.h"
#include "eq_thermal_steady.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <cstdio>
#include <random>
#include <vector>

using namespace feq;
using ::testing::HasSubstr;

namespace {

ThermalSpec thermal(double theta, double p = 0.0, double q = 0.0)
{
  ThermalSpec s;
  s.theta = theta;
  s.xc = 1.0;
  s.p = p;
  s.q = q;
  return s;
}

struct Block {
  const ThermalMesoModel &m;
  std::vector<double> s;
  Block(const ThermalMesoModel &model) : m(model), s(model.width()) { m.init(s.data(), 0.0); }
  double go(double X, double eps, double h) { return m.advance(s.data(), X, eps, h); }
  double F() const { return m.mean_stretch(s.data()); }
};

// max over X in (0, Xmax] (every 4th step) of |(1 + eps) F(X) - F_1((1 + eps) X)|,
// F_1 the slider master equation loaded at w = (1 + eps) v (Richardson,
// dx = 5e-4: error ~1e-9), for a block moved at v with steps dX (time
// dX/v each); also the final F against the steady state
struct VelocityError {
  double transient, steady, relax;    // relax: |F_1 at the end - F_k| (not yet steady)
};
// (the attached fraction likewise, against the reference's)
VelocityError error_vs_slider(const ThermalSpec &spec, double v, double eps, double du,
                              int labels, double dX, double Xmax, double *attached_error = nullptr)
{
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, spec, labels);
  ThermalSlider sl;
  sl.Pc = make_uniform(0.75, 1.25);
  sl.spec = spec;
  sl.v = (1.0 + eps) * v;
  const double dx = 5e-4;
  const MEResult ref = thermal_transient(sl, dx, (1.0 + eps) * Xmax + 0.01, true);
  Block b(m);
  double e = 0.0, ea = 0.0;
  const long n = long(std::llround(Xmax / dX));
  for (long k = 1; k <= n; ++k) {
    const double X = double(k) * dX;
    b.go(X, eps, dX / v);
    if (k % 4) continue;
    // reference at Y = (1 + eps) X, linear interpolation (error ~ F'' dx^2/8 ~ 1e-7)
    const double Y = (1.0 + eps) * X, f = Y / dx;
    const size_t i = size_t(f);
    const double t = f - double(i);
    const double Fr = (1.0 - t) * ref.F[i] + t * ref.F[i + 1];
    e = std::max(e, std::fabs((1.0 + eps) * b.F() - Fr));
    const double Ar = (1.0 - t) * ref.attached[i] + t * ref.attached[i + 1];
    ea = std::max(ea, std::fabs(m.attached(b.s.data()) - Ar));
  }
  if (attached_error) *attached_error = ea;
  const double Fk = thermal_steady_state(sl).F;
  const double Fend = ref.F[size_t(std::llround((1.0 + eps) * double(n) * dX / dx))];
  return {e, std::fabs((1.0 + eps) * b.F() - Fk), std::fabs(Fend - Fk)};
}
VelocityError error_vs_slider(double theta, double v, double eps, double du, int labels,
                              double dX, double Xmax, double p = 0.0, double q = 0.0)
{
  return error_vs_slider(thermal(theta, p, q), v, eps, du, labels, dX, Xmax);
}

// 3000 random forward and backward moves, rests and jumps of eps: the
// largest normalization error (infinite once a state is not valid)
double random_moves(const ThermalMesoModel &m, Block &b, unsigned seed)
{
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double X = 0.0, worst = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const double r = U(gen);
    if (r < 0.1) X -= 0.05 * U(gen);
    else if (r < 0.9) X += 0.02 * U(gen);
    const double eps = 3.0 * U(gen) * U(gen);
    b.go(X, eps, r < 0.95 ? 0.3 * U(gen) : 0.0);
    worst = std::max(worst, m.normalization_error(b.s.data()));
    if (!m.valid(b.s.data())) {
      ADD_FAILURE() << "state not valid after call " << k;
      return HUGE_VAL;
    }
  }
  return worst;
}

ThermalSpec delayed(double theta, double tau, DelayKind kind = DelayKind::EXPONENTIAL)
{
  ThermalSpec s = thermal(theta);
  s.delay = kind;
  s.tau = tau;
  return s;
}

}    // namespace

/* ----------------------------------------------------------------------
   1. conservation and state handling
------------------------------------------------------------------------- */

// random forward/backward moves, rests and jumps of eps: attached (+
// detached with reform none) stays 1 to rounding
TEST(MesoThermal, ProbabilityConserved)
{
  for (bool reform : {true, false}) {
    const ThermalMesoModel m(make_uniform(0.75, 1.25), reform ? make_delta(0.0) : nullptr, 0.01,
                             thermal(0.05), 16);
    Block b(m);
    EXPECT_LT(random_moves(m, b, 7), 1e-13);
    if (reform) EXPECT_NEAR(m.attached(b.s.data()), 1.0, 1e-13);
    else EXPECT_NEAR(m.attached(b.s.data()) + m.detached(b.s.data()), 1.0, 1e-13);
  }
}

TEST(MesoThermal, StateHandling)
{
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01, thermal(0.05), 8);
  Block b(m);
  EXPECT_EQ(m.attached(b.s.data()), 1.0);
  EXPECT_EQ(m.mean_stretch(b.s.data()), 0.0);
  b.go(0.3, 0.5, 1.0);
  const std::vector<double> before = b.s;
  EXPECT_EQ(b.go(0.3, 0.7, 0.0), 0.0);    // no move, no time: untouched
  EXPECT_EQ(0, std::memcmp(before.data(), b.s.data(), before.size() * sizeof(double)));
  EXPECT_GT(b.go(0.3, 0.5, 1.0), 0.0);    // rest at T > 0: thermal breaks
  EXPECT_EQ(m.rate(b.s.data()), 0.0);
  EXPECT_THROW(b.go(NAN, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(b.go(0.4, -0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(b.go(0.4, 0.1, -1.0), std::invalid_argument);
  // another model's state is not valid here
  const ThermalMesoModel m2(make_uniform(0.75, 1.25), make_delta(0.0), 0.01, thermal(0.05), 9);
  EXPECT_FALSE(m2.valid(b.s.data()));
  const MesoModel athermal(make_uniform(0.75, 1.25), make_delta(0.0), 0.01);
  std::vector<double> sa(std::max(athermal.width(), m.width()));
  athermal.init(sa.data(), 0.0);
  EXPECT_FALSE(m.valid(sa.data()));
}

TEST(MesoThermal, Unsupported)
{
  auto make = [](DistributionPtr R, ThermalSpec s) {
    ThermalMesoModel m(make_uniform(0.75, 1.25), std::move(R), 0.01, s);
  };
  try {
    make(make_uniform(-0.1, 0.1), thermal(0.05));
    FAIL();
  } catch (const SpecError &e) {
    EXPECT_THAT(e.what(), HasSubstr("reform delta 0"));
  }
  EXPECT_THROW(ThermalMesoModel(make_uniform(0.75, 1.25), make_delta(0.0), 0.2, thermal(0.05)),
               GridError);
  EXPECT_THROW(ThermalMesoModel(make_uniform(0.75, 1.25), make_delta(0.0), 1e-5, thermal(0.05)),
               GridError);
}

/* ----------------------------------------------------------------------
   2. rest: one threshold, no re-forming: the attached fraction decays as
   exp(-nu t), nu = omega exp(-(1 - y/x_s)^{3/2}/theta), y = (1 + eps) X
   (constant rate: Simpson is exact, so to rounding)
------------------------------------------------------------------------- */

TEST(MesoThermal, RestDecay)
{
  for (double eps : {0.0, 0.5}) {
    const ThermalMesoModel m(make_delta(1.0), nullptr, 0.01, thermal(0.05));
    Block b(m);
    b.go(0.5, eps, 0.0);    // at once, no time: nothing breaks
    EXPECT_EQ(m.attached(b.s.data()), 1.0);
    const double w = 1.0 - (1.0 + eps) * 0.5;
    const double nu = std::exp(-w * std::sqrt(w) / 0.05);
    double t = 0.0;
    for (int k = 0; k < 50; ++k) {
      const double h = 1.0 / nu / 17.0;
      b.go(0.5, eps, h);
      t += h;
      EXPECT_NEAR(m.attached(b.s.data()), std::exp(-nu * t), 1e-14) << "eps " << eps;
    }
    EXPECT_NEAR(m.mean_stretch(b.s.data()), 0.5 * std::exp(-nu * t), 1e-14);
  }
  // eps jumps so that (1 + eps) X >= x_s: broken at once (threshold picture)
  const ThermalMesoModel m(make_delta(1.0), nullptr, 0.01, thermal(0.05));
  Block b(m);
  b.go(0.5, 0.0, 0.0);
  b.go(0.5, 1.0, 1e-9);
  EXPECT_EQ(m.attached(b.s.data()), 0.0);
}

// a step nominally du but longer by rounding is one sub-step: the result
// is continuous in the step there (the same to 1e-12 for dX = du (1 +- 1e-12))
TEST(MesoThermal, SubstepCountStable)
{
  const double du = 0.01;
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, thermal(0.05), 8);
  Block a(m), b(m);
  for (int k = 1; k <= 500; ++k) {
    a.go(k * du * (1.0 - 1e-12), 1.5, 1.0);
    b.go(k * du * (1.0 + 1e-12), 1.5, 1.0);
  }
  EXPECT_NEAR(a.F(), b.F(), 1e-10);
}

/* ----------------------------------------------------------------------
   3. T -> 0: the athermal block.  At theta = 0 (and theta = 1e-3 at
   v = 1e4, where a contact spends < 1e-6 time units within 1e-2 of its
   threshold: thermal breaks < 1e-6) a rigidly moved block with constant
   eps follows the exact renewal solution F_exact((1 + eps) X)/(1 + eps) (thresholds
   uniform [0.75,1.25]/(1 + eps)) to the scheme's O(du^2) error, as
   MesoModel does (0.78 du^2, eq_meso.h): bound C du^2 with C = 2
   (measured 0.70 du^2 at eps = 0, 1.03 du^2 at eps = 0.5: increments
   0.37 du, du = 0.005 ... 0.02 alike), and the two kernels agree within
   the sum of their bounds.
------------------------------------------------------------------------- */

TEST(MesoThermal, AthermalLimit)
{
  const double du = 0.01, inc = 0.37 * du;
  for (double eps : {0.0, 0.5}) {
    for (double theta : {0.0, 1e-3}) {
      const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, thermal(theta), 16);
      const MesoModel ma(make_uniform(0.75, 1.25), make_delta(0.0), du);
      const RenewalUniform ex(0.75 / (1.0 + eps), 1.25 / (1.0 + eps));
      Block b(m);
      std::vector<double> sa(ma.width());
      ma.init(sa.data(), 0.0);
      double e = 0.0, ea = 0.0;
      for (long k = 1; double(k) * inc <= 8.0; ++k) {
        const double X = double(k) * inc;
        b.go(X, eps, inc / 1e4);
        ma.advance(sa.data(), X, eps);
        if (k % 3) continue;
        e = std::max(e, std::fabs(b.F() - ex.mean_stretch(X)));
        ea = std::max(ea, std::fabs(b.F() - ma.mean_stretch(sa.data())));
      }
      EXPECT_LT(e, 2.0 * du * du) << "eps " << eps << " theta " << theta;
      EXPECT_LT(ea, 3.0 * du * du) << "eps " << eps << " theta " << theta;
    }
  }
}

// crossing step (every break of a move re-forms at its end, the cellular-
// automaton convention): at theta = 0 and steps below du the two kernels
// take the same breaks (exact survival of uniform thresholds in both) and
// re-form them at the same point: equal to rounding (measured 2e-14)
TEST(MesoThermal, AthermalLimitCrossingStep)
{
  const double du = 0.01, inc = 0.37 * du;
  for (double eps : {0.0, 0.5}) {
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, thermal(0.0), 16,
                             Crossing::STEP);
    const MesoModel ma(make_uniform(0.75, 1.25), make_delta(0.0), du, Crossing::STEP);
    Block b(m);
    std::vector<double> sa(ma.width());
    ma.init(sa.data(), 0.0);
    double e = 0.0;
    for (long k = 1; double(k) * inc <= 8.0; ++k) {
      b.go(double(k) * inc, eps, 0.0);
      ma.advance(sa.data(), double(k) * inc, eps);
      e = std::max(e, std::fabs(b.F() - ma.mean_stretch(sa.data())));
    }
    EXPECT_LT(e, 1e-12) << "eps " << eps;
  }
}

/* ----------------------------------------------------------------------
   4. T > 0 at constant velocity against the slider master equation
   loaded at (1 + eps) v.  Second order: the error on (du, 2 du panels,
   dX) and on (du/2, ..., dX/2) has a ratio near 4 (3 ... 5.5: the three
   error terms are all second order); the absolute bound is C du_eff^2,
   du_eff = (1 + eps) du the grid in effective stretch, with dX = du/2 and
   panels of 0.5/labels = 3.1 du_eff (here) ... 6.2 du_eff: measured
   C = 2.95 ... 3.35 on both grids; bound C = 5.  The final F against the
   steady state F_k within that bound plus what the reference itself
   still lacks of F_k at the end (relaxation).
------------------------------------------------------------------------- */

TEST(MesoThermal, ConstantVelocity)
{
  struct Run {
    double theta, v, eps;
  };
  for (const Run &r : {Run{0.05, 1e-2, 0.0}, Run{0.05, 1e-3, 2.0}, Run{0.1, 1e-1, 1.0}}) {
    const double du = 0.02 / (1.0 + r.eps);
    const VelocityError c = error_vs_slider(r.theta, r.v, r.eps, du, 8, 0.5 * du, 4.0);
    const VelocityError f = error_vs_slider(r.theta, r.v, r.eps, 0.5 * du, 16, 0.25 * du, 4.0);
    const double ratio = c.transient / f.transient;
    EXPECT_GT(ratio, 3.0) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(ratio, 5.5) << r.theta << " " << r.v << " " << r.eps;
    const double eff = (1.0 + r.eps) * du;    // the coarse grid in effective stretch
    const double fine = 0.5 * eff;
    EXPECT_LT(c.transient, 5.0 * eff * eff) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(f.transient, 5.0 * fine * fine) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(f.steady, 5.0 * fine * fine + f.relax) << r.theta << " " << r.v << " " << r.eps;
    std::printf("theta %g v %g eps %g: coarse %.3e (%.2f du_eff^2) fine %.3e (%.2f du_eff^2) "
                "ratio %.3f steady %.3e relax %.3e\n", r.theta, r.v, r.eps, c.transient,
                c.transient / (eff * eff), f.transient, f.transient / (fine * fine), ratio,
                f.steady, f.relax);
  }
}

/* ----------------------------------------------------------------------
   5. the barrier's exponents: p = 2 (scale (x_s/x_c)^2), q = 0.25
   (prefactor u^1/4) at constant velocity, as 4.  The panel midpoint
   threshold now also enters the barrier's scale, a larger second-order
   term: measured C = 4.9 ... 5.2 du_eff^2 (p = 2, with and without q, du
   = 0.01 ... 0.0025, converging at second order: ratio near 4); bound
   C = 8.
------------------------------------------------------------------------- */

TEST(MesoThermal, ConstantVelocityBarrier)
{
  const double du = 0.02;
  for (double q : {0.0, 0.25}) {
    const VelocityError c = error_vs_slider(0.05, 1e-2, 0.0, du, 8, 0.5 * du, 4.0, 2.0, q);
    const VelocityError f = error_vs_slider(0.05, 1e-2, 0.0, 0.5 * du, 16, 0.25 * du, 4.0, 2.0, q);
    const double ratio = c.transient / f.transient;
    EXPECT_GT(ratio, 3.0) << "q " << q;
    EXPECT_LT(ratio, 5.5) << "q " << q;
    EXPECT_LT(c.transient, 8.0 * du * du) << "q " << q;
    EXPECT_LT(f.transient, 8.0 * 0.25 * du * du) << "q " << q;
    std::printf("barrier 2 %g: coarse %.3e (%.2f du^2) fine %.3e (%.2f du^2) ratio %.3f\n", q,
                c.transient, c.transient / (du * du), f.transient,
                f.transient / (0.25 * du * du), ratio);
  }
}

/* ----------------------------------------------------------------------
   6. backward moves.  Breaking is one-sided, as in MesoModel (and the
   master equation): a compressed contact is loaded as an unstretched one,
   so that at theta -> 0 a block moved forward, back beyond most of its
   thresholds and forward again is the athermal block (within the two kernels'
   discretization errors, as AthermalLimit), and a backward move breaks
   (next to) nothing.
------------------------------------------------------------------------- */

TEST(MesoThermal, BackwardMovesAthermalLimit)
{
  const double du = 0.01, inc = 0.37 * du;
  for (double eps : {0.0, 0.5}) {
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, thermal(1e-3), 16);
    const MesoModel ma(make_uniform(0.75, 1.25), make_delta(0.0), du);
    Block b(m);
    std::vector<double> sa(ma.width());
    ma.init(sa.data(), 0.0);
    double X = 0.0, e = 0.0;
    // forward 2, back 1.2 (compressed beyond most thresholds, within the
    // largest: u >= -1.2 > -1.25), forward 3
    for (const auto &leg : {std::make_pair(+1, 2.0), std::make_pair(-1, 1.2),
                            std::make_pair(+1, 3.0)}) {
      const long n = long(std::llround(leg.second / inc));
      double broken_back = 0.0;
      for (long k = 0; k < n; ++k) {
        X += leg.first * inc;
        const double bb = b.go(X, eps, inc / 1e4);
        if (leg.first < 0) broken_back += bb;
        ma.advance(sa.data(), X, eps);
        e = std::max(e, std::fabs(b.F() - ma.mean_stretch(sa.data())));
      }
      // only thermal breaks of contacts still stretched as the leg begins
      // (theta = 1e-3 at these speeds: measured 4e-9 ... 8e-9); with the
      // two-sided threshold of before, 1/3 of the contacts broke compressed
      if (leg.first < 0) EXPECT_LT(broken_back, 1e-6) << "eps " << eps;
    }
    EXPECT_LT(e, 3.0 * du * du) << "eps " << eps;
  }
}

/* ----------------------------------------------------------------------
   7. the grid's limits in the load factor: beyond eps_valid() ((1 + eps)
   du past the median threshold) advance() throws GridError, also for a
   block at rest; eps_accurate() (a quarter of the sd) lies below it; a
   displacement beyond 4e15 cells is refused (as MesoModel).
------------------------------------------------------------------------- */

TEST(MesoThermal, GridLimits)
{
  const double du = 0.01;
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, thermal(0.05), 16);
  const double sd = 0.5 / std::sqrt(12.0);
  EXPECT_NEAR(m.eps_accurate(), 0.25 * sd / du - 1.0, 1e-12);
  EXPECT_NEAR(m.eps_valid(), 1.0 / du - 1.0, 1e-9);
  Block b(m);
  b.go(0.5, 1.0, 1.0);
  EXPECT_NO_THROW(b.go(0.5, m.eps_valid() * (1.0 - 1e-9), 0.0));
  EXPECT_THROW(b.go(0.5, m.eps_valid() * (1.0 + 1e-9), 1.0), GridError);
  EXPECT_THROW(b.go(0.6, 1e3, 0.0), GridError);
  EXPECT_THROW(b.go(5e13, 0.0, 1.0), std::invalid_argument);
  // a point threshold: no conditioning on eps, no limit
  const ThermalMesoModel mp(make_delta(1.0), make_delta(0.0), du, thermal(0.05), 16);
  EXPECT_EQ(mp.eps_valid(), HUGE_VAL);
}

// compressed beyond the largest threshold (u <= -1.25 here) a contact
// breaks (and re-forms): the anchors held stay within the ring, however
// far and long the block moves back at T > 0 (before: the ring overflowed)
TEST(MesoThermal, LongBackwardMove)
{
  const double du = 0.01;
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, thermal(0.2), 16);
  Block b(m);
  double X = 0.0;
  for (int k = 0; k < 300; ++k) b.go(X += 0.005, 0.0, 0.01);
  double broken = 0.0;
  for (int k = 0; k < 2000; ++k) broken += b.go(X -= 0.005, 0.0, 1.0);
  EXPECT_GT(broken, 0.99);    // all were compressed beyond 1.25 or broke thermally
  EXPECT_LT(m.normalization_error(b.s.data()), 1e-12);
  EXPECT_LE(m.rows(b.s.data()), long(2.0 * std::ceil(m.top() / du) + 8.0));
  EXPECT_LT(std::fabs(b.F()), 1.25);
}

/* ----------------------------------------------------------------------
   8. exponential formation delay (spec (b) 1): a broken contact waits in
   a pool of the state and re-forms at the rate 1/tau, unstretched where
   the block is then.
------------------------------------------------------------------------- */

// attached + waiting = 1 to rounding under random moves, rests, eps jumps
// and time steps from << tau to >> tau; the force counts the attached only
TEST(MesoThermalDelay, ProbabilityConserved)
{
  for (DelayKind kind : {DelayKind::EXPONENTIAL, DelayKind::FIXED})
  for (double tau : {0.05, 0.7, 50.0}) {
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                             delayed(0.05, tau, kind), 16);
    Block b(m);
    std::mt19937_64 gen(11);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    double X = 0.0, worst = 0.0, wmax = 0.0;
    for (int k = 0; k < 3000; ++k) {
      const double r = U(gen);
      if (r < 0.1) X -= 0.05 * U(gen);
      else if (r < 0.9) X += 0.02 * U(gen);
      b.go(X, 3.0 * U(gen) * U(gen), r < 0.95 ? 0.3 * U(gen) : 0.0);
      worst = std::max(worst, m.normalization_error(b.s.data()));
      wmax = std::max(wmax, m.waiting(b.s.data()));
      ASSERT_TRUE(m.valid(b.s.data()));
      ASSERT_EQ(m.detached(b.s.data()), 0.0);
    }
    EXPECT_LT(worst, 1e-13) << "tau " << tau << " kind " << int(kind);
    EXPECT_GT(wmax, 0.01) << "tau " << tau << " kind " << int(kind);    // the pool was used
    EXPECT_NEAR(m.attached(b.s.data()) + m.waiting(b.s.data()), 1.0, 1e-13);
  }
}

// the pool is one double after the rows; delay 0 or none: the no-delay
// model, bit for bit (same width, same tag, same numbers)
TEST(MesoThermalDelay, OffIsUnchanged)
{
  const ThermalMesoModel m0(make_uniform(0.75, 1.25), make_delta(0.0), 0.01, thermal(0.05), 16);
  const ThermalMesoModel mz(make_uniform(0.75, 1.25), make_delta(0.0), 0.01, delayed(0.05, 0.0),
                            16);
  const ThermalMesoModel md(make_uniform(0.75, 1.25), make_delta(0.0), 0.01, delayed(0.05, 1.0),
                            16);
  EXPECT_EQ(mz.width(), m0.width());
  EXPECT_EQ(md.width(), m0.width() + 1);
  EXPECT_FALSE(md.valid(Block(m0).s.data()));
  const ThermalMesoModel mf(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                            delayed(0.05, 1.0, DelayKind::FIXED), 16);
  EXPECT_EQ(mf.width(), m0.width() + 2 + 3 * MESO_DELAY_BINS);
  EXPECT_FALSE(mf.valid(Block(md).s.data()));
  Block a(m0), z(mz);
  for (int k = 1; k <= 400; ++k) {
    a.go(0.004 * k, 0.3, 0.1);
    z.go(0.004 * k, 0.3, 0.1);
  }
  EXPECT_EQ(0, std::memcmp(a.s.data(), z.s.data(), a.s.size() * sizeof(double)));
}

// the pool at rest, nothing attached breaking (theta = 0, X fixed): it
// empties as exp(-t/tau) exactly, in one call or in many (to rounding)
TEST(MesoThermalDelay, PoolDecayAtRest)
{
  const double tau = 2.0;
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01, delayed(0.0, tau),
                           8);
  Block b(m);
  b.go(2.0, 0.0, 1e-300);    // everything broken once at least; nearly no time
  const double W0 = m.waiting(b.s.data());
  ASSERT_GT(W0, 0.3);
  Block c = b;
  b.go(2.0, 0.0, 3.0);
  for (int k = 0; k < 30; ++k) c.go(2.0, 0.0, 0.1);
  EXPECT_NEAR(m.waiting(b.s.data()), W0 * std::exp(-3.0 / tau), 1e-15);
  EXPECT_NEAR(m.waiting(c.s.data()), W0 * std::exp(-3.0 / tau), 1e-14);
  EXPECT_NEAR(m.attached(b.s.data()) + m.waiting(b.s.data()), 1.0, 1e-14);
}

// fixed delay at rest: the mass broken at t = 0 waits exactly tau, then
// re-forms at once (at the block's position); a delay of more than
// MESO_DELAY_BINS - 2 steps overflows the FIFO (an error)
TEST(MesoThermalDelay, FixedDelayAtRest)
{
  const double tau = 2.0;
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                           delayed(0.0, tau, DelayKind::FIXED), 8);
  Block b(m);
  b.go(2.0, 0.0, 1e-300);    // everything broken once at least; nearly no time
  const double W0 = m.waiting(b.s.data());
  ASSERT_GT(W0, 0.3);
  for (int k = 1; k <= 19; ++k) b.go(2.0, 0.0, 0.1);    // t = 1.9 < tau
  EXPECT_EQ(m.waiting(b.s.data()), W0);
  b.go(2.0, 0.0, 0.2);    // t = 2.1 > tau
  EXPECT_EQ(m.waiting(b.s.data()), 0.0);
  EXPECT_NEAR(m.attached(b.s.data()), 1.0, 1e-14);
  EXPECT_NEAR(m.mean_stretch(b.s.data()), 0.0, 1e-14);    // re-formed unstretched at X = 2
  // overflow: tau = 2000 steps of 1e-3, contacts breaking (thermally, at
  // rest at X = 0.9) at every step
  const ThermalMesoModel mo(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                            delayed(0.05, 2.0, DelayKind::FIXED), 8);
  Block o(mo);
  o.go(0.7, 0.0, 0.0);
  try {
    for (int k = 1; k <= 3000; ++k) o.go(0.9, 0.0, 1e-3);
    FAIL() << "no overflow";
  } catch (const std::runtime_error &e) {
    EXPECT_THAT(e.what(), HasSubstr("more than 1024 bins"));
  }
}

// T = 0, constant velocity, constant eps: a block is a slider loaded at
// w = (1 + eps) v.  Steady state in closed form (spec (c), R = delta(0),
// exponential delay of mean tau): F_k/(N k_c) = <x_s^2>/(2 (<x_s> + w tau)) / (1 + eps),
// n_a = <x_s>/(<x_s> + w tau); uniform [0.75, 1.25]: <x_s> = 1, <x_s^2> =
// 1 + 1/48.  Errors: the grid's O(du_eff^2) (bound 2 du_eff^2 as
// AthermalLimit, which measured <= 1.1 du_eff^2) and the step's: the
// re-forming within a step is exact in time, the break time taken at the
// mean break position; with dX = 0.37 du their sum is below the bound.
// Run to X = 12 (n_a relaxes as exp(-X/(v tau)), the lives' oscillations
// decay within a few <L>); also delay -> 0 gives the no-delay block.
TEST(MesoThermalDelay, SteadyAthermalClosedForm)
{
  const double du = 0.01, inc = 0.37 * du, v = 0.1, x2 = 1.0 + 1.0 / 48.0;
  const DelayKind kind = DelayKind::EXPONENTIAL;
  for (double eps : {0.0, 0.5}) {
    for (double tau : {2.0, 10.0}) {
      const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du,
                               delayed(0.0, tau, kind), 16);
      Block b(m);
      for (long k = 1; double(k) * inc <= 30.0; ++k) b.go(double(k) * inc, eps, inc / v);
      const double w = (1.0 + eps) * v, eff = (1.0 + eps) * du;
      const double Fk = x2 / (2.0 * (1.0 + w * tau)) / (1.0 + eps), na = 1.0 / (1.0 + w * tau);
      const double eF = std::fabs(b.F() - Fk), ea = std::fabs(m.attached(b.s.data()) - na);
      EXPECT_LT(eF, 2.0 * eff * eff) << "eps " << eps << " tau " << tau;
      EXPECT_LT(ea, 2.0 * eff * eff) << "eps " << eps << " tau " << tau;
      EXPECT_NEAR(m.attached(b.s.data()) + m.waiting(b.s.data()), 1.0, 1e-13);
      std::printf("T=0 delay %s %g eps %g: F %.8f closed %.8f (%.3f du_eff^2) n_a %.8f closed "
                  "%.8f (%.3f du_eff^2)\n", kind == DelayKind::FIXED ? "fixed" : "exp", tau, eps, b.F(), Fk, eF / (eff * eff),
                  m.attached(b.s.data()), na, ea / (eff * eff));
    }
  }
  // tau -> 0: the no-delay block, the difference O(v tau) (F_k changes by
  // -F_k v tau/<x_s> to first order)
  const ThermalMesoModel m0(make_uniform(0.75, 1.25), make_delta(0.0), du, thermal(0.0), 16);
  const ThermalMesoModel ms(make_uniform(0.75, 1.25), make_delta(0.0), du, delayed(0.0, 1e-4),
                            16);
  Block a(m0), s(ms);
  double e = 0.0;
  for (long k = 1; double(k) * inc <= 8.0; ++k) {
    a.go(double(k) * inc, 0.0, inc / v);
    s.go(double(k) * inc, 0.0, inc / v);
    e = std::max(e, std::fabs(a.F() - s.F()));
  }
  EXPECT_LT(e, 2.0 * v * 1e-4);
  EXPECT_GT(e, 0.0);
}

// T = 0 with a fixed delay: the lives' oscillations decay slowly (all
// contacts broken together re-form together), so F(X) and n_a(X) over X
// in [0, 8] against the slider renewal equation with the fixed delay
// (thermal_transient: exact survival at T = 0, kinks off its grid: error
// ~3e-7), bound 2 du_eff^2 as AthermalLimit; also with every contact
// waiting at once (a jump beyond every threshold, no time)
TEST(MesoThermalDelay, FixedAthermalTransient)
{
  const double du = 0.01, inc = 0.37 * du, v = 0.1;
  for (double eps : {0.0, 0.5}) {
    for (double tau : {2.0, 10.0}) {
      const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du,
                               delayed(0.0, tau, DelayKind::FIXED), 16);
      ThermalSlider sl;
      sl.Pc = make_uniform(0.75, 1.25);
      sl.spec = delayed(0.0, tau, DelayKind::FIXED);
      sl.v = (1.0 + eps) * v;
      const double dx = 5e-4;
      const MEResult ref = thermal_transient(sl, dx, (1.0 + eps) * 8.0 + 0.01, true);
      Block b(m);
      double eF = 0.0, ea = 0.0;
      for (long k = 1; double(k) * inc <= 8.0; ++k) {
        const double X = double(k) * inc;
        b.go(X, eps, inc / v);
        if (k % 3) continue;
        const double f = (1.0 + eps) * X / dx;
        const size_t i = size_t(f);
        const double t = f - double(i);
        eF = std::max(eF, std::fabs((1.0 + eps) * b.F() - ((1.0 - t) * ref.F[i] + t * ref.F[i + 1])));
        ea = std::max(ea, std::fabs(m.attached(b.s.data()) -
                                    ((1.0 - t) * ref.attached[i] + t * ref.attached[i + 1])));
      }
      const double eff = (1.0 + eps) * du;
      EXPECT_LT(eF, 2.0 * eff * eff) << "eps " << eps << " tau " << tau;
      EXPECT_LT(ea, 2.0 * eff * eff) << "eps " << eps << " tau " << tau;
      std::printf("T=0 delay fixed %g eps %g: max |F - F_ref| %.3e (%.3f du_eff^2), n_a %.3e "
                  "(%.3f du_eff^2)\n", tau, eps, eF, eF / (eff * eff), ea, ea / (eff * eff));
    }
  }
  for (DelayKind kind : {DelayKind::EXPONENTIAL, DelayKind::FIXED}) {
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du,
                             delayed(0.0, 1.0, kind), 16);
    Block b(m);
    b.go(3.0, 0.0, 0.0);
    EXPECT_EQ(m.attached(b.s.data()), 0.0);
    EXPECT_EQ(m.rows(b.s.data()), 0);
    b.go(3.0, 0.0, 5.0);
    EXPECT_EQ(m.rows(b.s.data()), 1);    // re-formed at X = 3, one anchor
    EXPECT_NEAR(m.attached(b.s.data()), kind == DelayKind::FIXED ? 1.0 : 1.0 - std::exp(-5.0),
                1e-14);
    EXPECT_NEAR(m.attached(b.s.data()) + m.waiting(b.s.data()), 1.0, 1e-14);
  }
}

// T > 0 with an exponential or a fixed delay against the slider renewal
// equation (thermal_transient, which has its own delay treatment) and the
// steady state quadrature (thermal_steady_state): as ConstantVelocity
// (bounds 5 du_eff^2, second-order ratio 3 ... 5.5), F(X) and the
// attached fraction n_a(X) over X in [0, 4]
TEST(MesoThermalDelay, ConstantVelocity)
{
  struct Run {
    double theta, v, eps, tau;
    DelayKind kind;
  };
  const DelayKind E = DelayKind::EXPONENTIAL, Fx = DelayKind::FIXED;
  for (const Run &r : {Run{0.05, 1e-2, 0.0, 30.0, E}, Run{0.05, 1e-2, 1.0, 100.0, E},
                       Run{0.1, 1e-1, 0.0, 3.0, E}, Run{0.05, 1e-2, 0.0, 30.0, Fx},
                       Run{0.05, 1e-2, 1.0, 100.0, Fx}, Run{0.1, 1e-1, 0.0, 3.0, Fx}}) {
    const double du = 0.02 / (1.0 + r.eps);
    double ac = 0.0, af = 0.0;
    const VelocityError c =
        error_vs_slider(delayed(r.theta, r.tau, r.kind), r.v, r.eps, du, 8, 0.5 * du, 4.0, &ac);
    const VelocityError f =
        error_vs_slider(delayed(r.theta, r.tau, r.kind), r.v, r.eps, 0.5 * du, 16, 0.25 * du, 4.0, &af);
    const double ratio = c.transient / f.transient;
    const double eff = (1.0 + r.eps) * du, fine = 0.5 * eff;
    EXPECT_GT(ratio, 3.0) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(ratio, 5.5) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(c.transient, 5.0 * eff * eff) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(f.transient, 5.0 * fine * fine) << r.theta << " " << r.v << " " << r.eps;
    // n_a = 1 - (B(X) - B(X - v tau)) with a fixed delay, B the broken
    // mass so far: the O(du^2) error of B enters at both ends (bound
    // doubled); an exponential delay averages the second end
    const double ca = r.kind == Fx ? 10.0 : 5.0;
    EXPECT_LT(ac, ca * eff * eff) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(af, ca * fine * fine) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_GT(ac / af, 3.0) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(ac / af, 5.5) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(f.steady, 5.0 * fine * fine + f.relax) << r.theta << " " << r.v << " " << r.eps;
    std::printf("delay %s %g theta %g v %g eps %g: coarse %.3e (%.2f du_eff^2) fine %.3e (%.2f "
                "du_eff^2) ratio %.3f n_a %.3e %.3e steady %.3e relax %.3e\n",
                r.kind == Fx ? "fixed" : "exp", r.tau, r.theta,
                r.v, r.eps, c.transient, c.transient / (eff * eff), f.transient,
                f.transient / (fine * fine), ratio, ac, af, f.steady, f.relax);
  }
}

// the breaks of an eps jump happen at the start of the call, at rest as
// in motion: T = 0, tau = 1, the block moved to X = 0.9 in no time (0.3
// broken, waiting), then eps 0 -> 0.2 over a call of h = 0.6 breaks 0.36
// more at t = 0 (thresholds uniform [0.75, 1.25], all on the anchor 0:
// exact).  delay exp: 0.66 e^{-0.6} waits at t = 0.6; delay fixed: 0.66
// waits at t = 0.6, none at t = 1.1 (due at t = 1).  The same at rest and
// with dX = 1e-12 (continuity)
TEST(MesoThermalDelay, EpsJumpBreaksAtStart)
{
  for (DelayKind kind : {DelayKind::EXPONENTIAL, DelayKind::FIXED}) {
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                             delayed(0.0, 1.0, kind), 8);
    double w[2];
    for (int i = 0; i < 2; ++i) {
      const double X = 0.9 + (i ? 1e-12 : 0.0);
      Block b(m);
      b.go(0.9, 0.0, 0.0);
      ASSERT_NEAR(m.waiting(b.s.data()), 0.3, 1e-14);
      b.go(X, 0.2, 0.6);
      w[i] = m.waiting(b.s.data());
      const double exact = kind == DelayKind::FIXED ? 0.66 : 0.66 * std::exp(-0.6);
      EXPECT_NEAR(w[i], exact, 1e-11) << "kind " << int(kind) << " dX " << X - 0.9;
      b.go(X, 0.2, 0.5);
      if (kind == DelayKind::FIXED) {
        EXPECT_EQ(m.waiting(b.s.data()), 0.0) << "dX " << X - 0.9;
        EXPECT_NEAR(m.attached(b.s.data()), 1.0, 1e-14);
      } else {
        EXPECT_NEAR(m.waiting(b.s.data()), 0.66 * std::exp(-1.1), 1e-12) << "dX " << X - 0.9;
      }
    }
    EXPECT_NEAR(w[0], w[1], 1e-11) << "kind " << int(kind);
  }
}

// a fixed delay with steps of several du (several sub-steps per call):
// one FIFO bin per sub-step, so the error is that of steps of du (bounds
// as ConstantVelocity at dX = du/2: 5 du^2 for F, 10 du^2 for n_a; a bin
// per call spread over the call's window made n_a first order in the
// step: 30 du^2 at dX = 4 du, 105 du^2 at 8 du); the exponential delay
// likewise
TEST(MesoThermalDelay, FixedDelayLongSteps)
{
  const double du = 0.01, v = 1e-2;
  for (DelayKind kind : {DelayKind::FIXED, DelayKind::EXPONENTIAL}) {
    for (double n : {0.5, 4.0, 8.0}) {
      double ea = 0.0;
      const VelocityError e =
          error_vs_slider(delayed(0.05, 30.0, kind), v, 0.0, du, 16, n * du, 4.0, &ea);
      std::printf("delay %s 30 dX = %g du: max |F - F_ref| %.3e (%.2f du^2), n_a %.3e (%.2f "
                  "du^2)\n", kind == DelayKind::FIXED ? "fixed" : "exp", n, e.transient,
                  e.transient / (du * du), ea, ea / (du * du));
      EXPECT_LT(e.transient, 5.0 * du * du) << "dX " << n << " du";
      EXPECT_LT(ea, 10.0 * du * du) << "dX " << n << " du";
    }
  }
}

// a fixed delay holds one bin per sub-step in flight: a block moving
// 4 du per step (back and forth, contacts breaking thermally in every
// sub-step) overflows with tau = 300 steps (1200 sub-steps), naming the
// cause
TEST(MesoThermalDelay, FixedDelayCapacitySubsteps)
{
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                           delayed(0.05, 300.0, DelayKind::FIXED), 8);
  Block b(m);
  b.go(0.3, 0.0, 0.0);
  try {
    for (int k = 1; k <= 400; ++k) b.go(k % 2 ? 0.34 : 0.3, 0.0, 1.0);
    FAIL() << "no overflow";
  } catch (const std::runtime_error &e) {
    EXPECT_THAT(e.what(), HasSubstr("delay fixed: tau = 300"));
    EXPECT_THAT(e.what(), HasSubstr("this step moved it 4 du in sub-steps of time 0.25, tau = 1200 of them"));
  }
}

TEST(MesoThermalDelay, Unsupported)
{
  auto make = [](DistributionPtr R, ThermalSpec s) {
    ThermalMesoModel m(make_uniform(0.75, 1.25), std::move(R), 0.01, s);
  };
  auto message = [&](DistributionPtr R, ThermalSpec s) -> std::string {
    try {
      make(std::move(R), s);
    } catch (const SpecError &e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_THAT(message(nullptr, delayed(0.05, 1.0, DelayKind::FIXED)), HasSubstr("reform none"));
  EXPECT_THAT(message(nullptr, delayed(0.05, 1.0)), HasSubstr("reform none"));
  EXPECT_THAT(message(make_delta(0.0), delayed(0.05, -1.0)), HasSubstr("tau must be"));
}

// a fixed delay's state (migrated, read from a restart) with a bin in
// flight whose window is not finite or whose mass is negative is not
// valid: such a bin would hold its mass for ever or hide it in the sum
TEST(MesoThermalDelay, ValidRejectsCorruptBins)
{
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                           delayed(0.05, 5.0, DelayKind::FIXED), 16);
  Block b(m);
  double X = 0.0;
  for (int k = 0; k < 240; ++k) b.go(X += 0.005, 0.0, 0.5);
  ASSERT_TRUE(m.valid(b.s.data()));
  // the FIFO (head, count, then 3 numbers per bin) closes the state
  const std::size_t fifo = m.width() - (2 + 3 * MESO_DELAY_BINS);
  const long head = long(b.s[fifo]), count = long(b.s[fifo + 1]);
  ASSERT_GT(count, 1);
  double *last = &b.s[fifo + 2 + 3 * ((head + count - 1) % MESO_DELAY_BINS)];
  ASSERT_GT(last[2], 0.0);
  for (int slot : {0, 1}) {
    Block c = b;
    (&c.s[0])[&last[slot] - b.s.data()] = NAN;
    EXPECT_FALSE(m.valid(c.s.data())) << slot;
  }
  Block c = b;
  (&c.s[0])[&last[2] - b.s.data()] = -0.1;
  EXPECT_FALSE(m.valid(c.s.data()));
}

/* ----------------------------------------------------------------------
   threshold aging (x_s = x_s0 A(t), ages one per anchor row) and rest
   ages, against the slider master equation with the same aging at
   w = (1 + eps) v (the age of a contact at stretch y is y/w in both)
------------------------------------------------------------------------- */

namespace {

ThermalSpec aged(double theta, AgingLaw law, double beta, double tau_a, double rest = 0.0)
{
  ThermalSpec s = thermal(theta);
  s.aging = law;
  s.beta = beta;
  s.tau_a = tau_a;
  s.rest = rest;
  return s;
}

}    // namespace

// random moves, rests and eps jumps with log aging, a rest age and an
// exponential delay: probability conserved, every row's age finite
TEST(MesoThermalAging, ProbabilityConserved)
{
  for (DelayKind kind : {DelayKind::NONE, DelayKind::EXPONENTIAL, DelayKind::FIXED}) {
    ThermalSpec spec = aged(0.05, AgingLaw::LOG, 0.1, 2.0, 50.0);
    spec.delay = kind;
    spec.tau = kind == DelayKind::NONE ? 0.0 : 3.0;
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01, spec, 16);
    Block b(m);
    EXPECT_LT(random_moves(m, b, 11), 1e-13);
    EXPECT_NEAR(m.attached(b.s.data()) + m.waiting(b.s.data()), 1.0, 1e-13);
  }
}

// the block at constant eps against the slider master equation at
// (1 + eps) v with the same aging law (log and exp), at T > 0: F(X)
// second order (ratio ~4 on halving du, dX and the panels), and of the
// kernel's accuracy without aging: within twice the error of the same run
// without aging (whose constant grows as theta falls: ~3 du_eff^2 at
// theta 0.05 ... 0.1, ~8 at 0.02), and within 5 du_eff^2 where that run's
// bound holds (theta >= 0.05)
TEST(MesoThermalAging, ConstantVelocity)
{
  struct Run {
    double theta, v, eps;
    AgingLaw law;
    double beta, tau_a;
  };
  const AgingLaw L = AgingLaw::LOG, E = AgingLaw::EXP;
  for (const Run &r : {Run{0.05, 1e-2, 0.0, L, 0.05, 1.0}, Run{0.05, 1e-2, 1.0, L, 0.1, 10.0},
                       Run{0.02, 1e-3, 0.0, L, 0.05, 1.0}, Run{0.05, 1e-2, 0.0, E, 0.2, 30.0},
                       Run{0.1, 1e-1, 1.0, E, 0.3, 3.0}}) {
    const ThermalSpec spec = aged(r.theta, r.law, r.beta, r.tau_a);
    const double du = 0.02 / (1.0 + r.eps);
    const VelocityError c = error_vs_slider(spec, r.v, r.eps, du, 8, 0.5 * du, 4.0);
    const VelocityError f = error_vs_slider(spec, r.v, r.eps, 0.5 * du, 16, 0.25 * du, 4.0);
    const VelocityError c0 = error_vs_slider(thermal(r.theta), r.v, r.eps, du, 8, 0.5 * du, 4.0);
    const double ratio = c.transient / f.transient;
    const double eff = (1.0 + r.eps) * du, fine = 0.5 * eff;
    std::printf("aging %s beta %g tau_a %g theta %g v %g eps %g: coarse %.3e (%.2f du_eff^2; "
                "without aging %.2f) fine %.3e (%.2f du_eff^2) ratio %.3f steady %.3e relax "
                "%.3e\n",
                r.law == L ? "log" : "exp", r.beta, r.tau_a, r.theta, r.v, r.eps, c.transient,
                c.transient / (eff * eff), c0.transient / (eff * eff), f.transient,
                f.transient / (fine * fine), ratio, f.steady, f.relax);
    EXPECT_GT(ratio, 3.0) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(ratio, 5.5) << r.theta << " " << r.v << " " << r.eps;
    EXPECT_LT(c.transient, 2.0 * c0.transient) << r.theta << " " << r.v << " " << r.eps;
    if (r.theta >= 0.05) {
      EXPECT_LT(c.transient, 5.0 * eff * eff) << r.theta << " " << r.v << " " << r.eps;
      EXPECT_LT(f.transient, 5.0 * fine * fine) << r.theta << " " << r.v << " " << r.eps;
    }
    EXPECT_LT(f.steady, 5.0 * fine * fine + f.relax) << r.theta << " " << r.v << " " << r.eps;
  }
}

// contacts aged by a rest t_w before the block moves: F(X) (its static
// peak) against the slider master equation whose first life starts at
// age t_w, at T > 0 (theta 0.05): second order, within 5 du^2 (the
// kernel's bound at this theta); and the peak grows with t_w
TEST(MesoThermalAging, RestAge)
{
  double last_peak = 0.0;
  for (double tw : {0.0, 1e2, 1e4}) {
    const ThermalSpec spec = aged(0.05, AgingLaw::LOG, 0.05, 1.0, tw);
    const double du = 0.02;
    const VelocityError c = error_vs_slider(spec, 1e-2, 0.0, du, 8, 0.5 * du, 3.0);
    const VelocityError f = error_vs_slider(spec, 1e-2, 0.0, 0.5 * du, 16, 0.25 * du, 3.0);
    std::printf("rest %g: coarse %.3e (%.2f du^2) fine %.3e (%.2f du^2) ratio %.3f\n", tw,
                c.transient, c.transient / (du * du), f.transient,
                f.transient / (0.25 * du * du), c.transient / f.transient);
    EXPECT_LT(c.transient, 5.0 * du * du) << tw;
    EXPECT_LT(f.transient, 5.0 * 0.25 * du * du) << tw;
    EXPECT_GT(c.transient / f.transient, 3.0) << tw;
    EXPECT_LT(c.transient / f.transient, 5.5) << tw;
    // the static peak
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.5 * du, spec, 16);
    Block b(m);
    double peak = 0.0;
    for (int k = 1; k <= 400; ++k) {
      b.go(k * 0.25 * du, 0.0, 0.25 * du / 1e-2);
      peak = std::max(peak, b.F());
    }
    EXPECT_GT(peak, last_peak + 0.01) << tw;
    last_peak = peak;
  }
}

// T = 0 (theta = 0: the kernel without thermal breaks), log aging beta =
// 0.05, tau_a = 1, v = 1e-2: the peak of F(X) after a rest t_w against
// the spec's independent solver (shared/notes/thermal-aging.md (d):
// 0.920, 0.948, 1.096, 1.268, three digits, from EQ runs with dX = 2e-3,
// whose step bias -0.257 dX = -5e-4 the bound 2e-3 covers)
TEST(MesoThermalAging, StaticPeakAtZeroTemperature)
{
  const double want[] = {0.920, 0.948, 1.096, 1.268};
  int k = 0;
  for (double tw : {0.0, 1e2, 1e4, 1e6}) {
    const ThermalSpec spec = aged(0.0, AgingLaw::LOG, 0.05, 1.0, tw);
    const double du = 0.004;
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), du, spec, 32);
    Block b(m);
    double peak = 0.0;
    for (int n = 1; n <= 1000; ++n) {
      b.go(n * 0.5 * du, 0.0, 0.5 * du / 1e-2);
      peak = std::max(peak, b.F());
    }
    std::printf("T = 0, rest %g: peak %.5f (spec %.3f)\n", tw, peak, want[k]);
    EXPECT_NEAR(peak, want[k], 2e-3) << tw;
    ++k;
  }
}

// an age that is not finite or negative is not a valid state; aging with
// a bad beta or tau_a is a SpecError naming aging
TEST(MesoThermalAging, ValidAndErrors)
{
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                           aged(0.05, AgingLaw::LOG, 0.05, 1.0), 16);
  Block b(m);
  for (int k = 1; k <= 100; ++k) b.go(0.005 * k, 0.0, 0.5);
  ASSERT_TRUE(m.valid(b.s.data()));
  // the ages: one per ring row, after the rows (here the state's end)
  bool hit = false;
  for (double bad : {double(NAN), -1.0, double(INFINITY)}) {
    Block c = b;
    // the age of the most stretched row (JLO, slot 2 of the header)
    const long jlo = long(c.s[2]);
    const long ncap = (m.width() - 8) / (16 + 2);
    c.s[8 + ncap * 17 + ((jlo % ncap) + ncap) % ncap] = bad;
    EXPECT_FALSE(m.valid(c.s.data())) << bad;
    hit = true;
  }
  EXPECT_TRUE(hit);
  for (auto [beta, tau_a] : {std::pair<double, double>{-0.1, 1.0}, {0.1, 0.0}, {NAN, 1.0}}) {
    try {
      ThermalMesoModel(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                       aged(0.05, AgingLaw::LOG, beta, tau_a), 16);
      ADD_FAILURE() << beta << " " << tau_a;
    } catch (const SpecError &e) {
      EXPECT_THAT(e.what(), HasSubstr("aging"));
    }
  }
  EXPECT_THROW(ThermalMesoModel(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                                aged(0.05, AgingLaw::LOG, 0.05, 1.0, -1.0), 16),
               SpecError);
}

// log aging: the ring holds thresholds up to x_top A(1e8 tau_a)
// = 1.25 (1 + 0.05 ln(1 + 1e8)) (= 2.4; with the room for backward moves
// the ring spans 248 rows of 0.02, 4.96); with tau_a = 1e-200 a contact
// of age 1 already has A = 24: the first contacts break near X = 18 and
// re-form there while others still hold at anchor 0, beyond the ring: a
// runtime error naming aging and tau_a, not a silent cut
TEST(MesoThermalAging, RingOverflowIsAnError)
{
  const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.02,
                           aged(0.0, AgingLaw::LOG, 0.05, 1e-200), 8);
  Block b(m);
  try {
    for (int k = 1; k <= 4000; ++k) b.go(0.01 * k, 0.0, 1.0);
    FAIL() << "no error";
  } catch (const std::runtime_error &e) {
    EXPECT_THAT(e.what(), HasSubstr("aging"));
    EXPECT_THAT(e.what(), HasSubstr("tau_a"));
  }
}

/* ----------------------------------------------------------------------
   the age bookkeeping directly (cases built so that the ages are known in
   closed form; suggested by a review: each catches an error of the fresh
   contacts' age, the merge or the aged compressed-row rule that the
   comparisons with the master equation above are too coarse to see)
------------------------------------------------------------------------- */

namespace {

// the age slot of row j (layout: 8 header doubles, ncap rows of nl + 1,
// ncap ages; no delay)
double row_age(const ThermalMesoModel &m, const std::vector<double> &s, long j)
{
  const int nl = m.labels();
  const long ncap = (m.width() - 8) / (nl + 2);
  return s[8 + ncap * (nl + 1) + ((j % ncap) + ncap) % ncap];
}

}    // namespace

// T = 0, one threshold x_s0 = 1, log aging: contacts stretched to 0.9
// (no time), then moved to 1.1 over h = 10: y/A passes 1 at the fraction c
// of the step (linear between start, middle, end); they re-form there with
// the age h (1 - c), on two rows that held nothing (no merge); the old row
// keeps nothing.  Catches age_new = 0 or h, aging the fresh contacts
// again (grow_old after reform), a wrong crossing time.
TEST(MesoThermalAging, FreshAgeAfterCrossing)
{
  const ThermalSpec spec = aged(0.0, AgingLaw::LOG, 1e-3, 1.0);
  const ThermalModel law(spec);
  const ThermalMesoModel m(make_delta(1.0), make_delta(0.0), 0.25, spec, 1);
  std::vector<double> s(m.width());
  m.init(s.data(), 0.0);
  m.advance(s.data(), 0.9, 0.0, 0.0);
  EXPECT_EQ(m.attached(s.data()), 1.0);
  EXPECT_DOUBLE_EQ(row_age(m, s, 0), 0.0);
  const double h = 10.0;
  EXPECT_NEAR(m.advance(s.data(), 1.1, 0.0, h), 1.0, 1e-15);
  const double zm = 1.0 / law.factor(0.5 * h), z1 = 1.1 / law.factor(h);
  const double c = 0.5 + 0.5 * (1.0 - zm) / (z1 - zm);
  const double pos = 0.9 + 0.2 * c;
  const long j = long(std::floor(pos / 0.25));
  EXPECT_NEAR(m.mean_stretch(s.data()), 1.1 - pos, 1e-12);
  EXPECT_NEAR(row_age(m, s, j), h * (1.0 - c), 1e-12);
  EXPECT_NEAR(row_age(m, s, j + 1), h * (1.0 - c), 1e-12);
  // a rest of 5 ages them by 5 (grow_old on the rows holding mass)
  m.advance(s.data(), 1.1, 0.0, 5.0);
  EXPECT_NEAR(row_age(m, s, j), h * (1.0 - c) + 5.0, 1e-12);
}

// fresh contacts onto a row that holds others: the mass-weighted mean age
// (T = 0: nothing breaks at rest; an eps jump breaks at the start, age h)
TEST(MesoThermalAging, MergedAgeIsMassWeighted)
{
  const ThermalSpec spec = aged(0.0, AgingLaw::LOG, 1e-3, 1.0, 7.0);
  const ThermalMesoModel m(make_delta(1.0), make_delta(0.0), 0.25, spec, 1);
  std::vector<double> s(m.width());
  m.init(s.data(), 0.1);    // rows 0 (0.6) and 1 (0.4), age 7
  m.advance(s.data(), 0.8, 0.0, 0.0);    // stretched 0.8 and 0.55
  // eps 0.5: y = 1.2 and 0.825: row 0 breaks at the start, re-forms at 0.8
  // (rows 3 and 4: 0.8/0.25 = 3.2), which are empty: age h = 2
  EXPECT_NEAR(m.advance(s.data(), 0.8, 0.5, 2.0), 0.6, 1e-15);
  EXPECT_NEAR(row_age(m, s, 1), 9.0, 1e-12);
  EXPECT_NEAR(row_age(m, s, 3), 2.0, 1e-12);
  EXPECT_NEAR(row_age(m, s, 4), 2.0, 1e-12);
  // eps 1.5: row 1 (stretched 0.55, y = 1.375) breaks at once: 0.4 onto
  // rows 3 (0.8 x 0.4) and 4 (0.2 x 0.4) holding 0.48 and 0.12 of age 2 + 3
  m.advance(s.data(), 0.8, 1.5, 3.0);
  EXPECT_NEAR(row_age(m, s, 3), (0.48 * 5.0 + 0.32 * 3.0) / 0.8, 1e-12);
  EXPECT_NEAR(row_age(m, s, 4), (0.12 * 5.0 + 0.08 * 3.0) / 0.2, 1e-12);
}

// compressed contacts break beyond the largest AGED threshold: after a rest
// of 1e6 (A = 1 + 0.05 ln(1 + 1e6) = 1.69) a backward move of 1.5 > x_top
// = 1.25 breaks nothing; without the rest everything breaks
TEST(MesoThermalAging, CompressedBeyondAgedThreshold)
{
  for (double tw : {0.0, 1e6}) {
    const ThermalMesoModel m(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                             aged(0.0, AgingLaw::LOG, 0.05, 1.0, tw), 8);
    std::vector<double> s(m.width());
    m.init(s.data(), 0.0);
    double broken = 0.0;
    for (int k = 1; k <= 150; ++k) broken += m.advance(s.data(), -0.01 * k, 0.0, 0.0);
    if (tw > 0.0) {
      EXPECT_EQ(broken, 0.0);
      EXPECT_NEAR(m.mean_stretch(s.data()), -1.5, 1e-12);
    } else {
      EXPECT_NEAR(broken, 1.0, 1e-12);
    }
  }
}

// the block's state (its width) depends on neither rest nor tau_a, so a
// restart with another rest reads its blocks back; a rest beyond 1e8
// tau_a (log) is a SpecError naming rest
TEST(MesoThermalAging, WidthIndependentOfRest)
{
  auto width = [](double tau_a, double tw) {
    return ThermalMesoModel(make_uniform(0.75, 1.25), make_delta(0.0), 0.01,
                            aged(0.05, AgingLaw::LOG, 0.05, tau_a, tw), 16)
        .width();
  };
  const int w = width(1.0, 0.0);
  EXPECT_EQ(width(1e-3, 0.0), w);
  EXPECT_EQ(width(1e-3, 1e4), w);
  EXPECT_EQ(width(1.0, 1e8), w);
  EXPECT_EQ(width(1e300, 1e6), w);
  try {
    width(1e-3, 1e6);
    FAIL() << "no error";
  } catch (const SpecError &e) {
    EXPECT_THAT(e.what(), HasSubstr("rest"));
  }
}
