// Unit tests: counter-based random numbers (Philox4x32-10) of FRICTION-EQ.
#include "eq_random.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

using namespace feq;

// Known-answer tests of Random123 (kat_vectors): counter, key -> output.
TEST(Philox, KnownAnswers)
{
  EXPECT_EQ(philox4x32({0, 0, 0, 0}, {0, 0}),
            (Philox4x32{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}));
  EXPECT_EQ(philox4x32({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}, {0xffffffffu, 0xffffffffu}),
            (Philox4x32{0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}));
  EXPECT_EQ(philox4x32({0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}, {0xa4093822u, 0x299f31d0u}),
            (Philox4x32{0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}));
}

TEST(Uniform, OpenIntervalAndExactComplement)
{
  for (uint64_t bits : {uint64_t(0), ~uint64_t(0), uint64_t(1) << 63, uint64_t(12345678901234567ULL)}) {
    const Uniform u = uniform_from_bits(bits);
    EXPECT_GT(u.u, 0.0);
    EXPECT_LT(u.u, 1.0);
    EXPECT_GT(u.one_minus_u, 0.0);
    EXPECT_EQ(u.u + u.one_minus_u, 1.0);    // both exact on the 2^-53 grid
  }
}

TEST(Draw, DeterministicAndKeyed)
{
  const Uniform a = draw(42, 7, 3, STREAM_THRESHOLD);
  const Uniform b = draw(42, 7, 3, STREAM_THRESHOLD);
  EXPECT_EQ(a.u, b.u);
  // every key component changes the draw
  EXPECT_NE(a.u, draw(43, 7, 3, STREAM_THRESHOLD).u);
  EXPECT_NE(a.u, draw(42, 8, 3, STREAM_THRESHOLD).u);
  EXPECT_NE(a.u, draw(42, 7, 4, STREAM_THRESHOLD).u);
  EXPECT_NE(a.u, draw(42, 7, 3, STREAM_REFORM).u);
  EXPECT_NE(a.u, draw(42, uint64_t(7) | (uint64_t(1) << 32), 3, STREAM_THRESHOLD).u);
}

// draw_pair(): its first uniform is draw()'s to the bit; its second is
// uniform and uncorrelated with the first (a contact's threshold and its
// life's hazard budget come from one block)
TEST(Draw, PairFirstIsDrawSecondIndependent)
{
  const int n = 200000;
  double m2 = 0.0, c12 = 0.0, cc[2][2] = {{0, 0}, {0, 0}};
  for (int i = 0; i < n; ++i) {
    const UniformPair p = draw_pair(4711, 1 + i / 100, i % 100, STREAM_THRESHOLD);
    const Uniform d = draw(4711, 1 + i / 100, i % 100, STREAM_THRESHOLD);
    ASSERT_EQ(p.first.u, d.u);
    ASSERT_EQ(p.first.one_minus_u, d.one_minus_u);
    ASSERT_EQ(p.second.u + p.second.one_minus_u, 1.0);
    m2 += p.second.u;
    c12 += (p.first.u - 0.5) * (p.second.u - 0.5);
    cc[p.first.u < 0.5][p.second.u < 0.5] += 1.0;
  }
  // means and the covariance within 5 standard errors (Var u = 1/12,
  // Var of a product of two independent centred uniforms = 1/144)
  EXPECT_NEAR(m2 / n, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(c12 / n, 0.0, 5.0 * std::sqrt(1.0 / 144.0 / n));
  const double m = n / 4.0;
  double chi2 = 0.0;
  for (auto &row : cc)
    for (double v : row) chi2 += (v - m) * (v - m) / m;
  EXPECT_LT(chi2, 20.0);    // p ~ 1e-4 for 3 dof
}

// Kolmogorov-Smirnov test of uniformity over (tag, event) pairs, and of
// independence of neighbouring keys (pairs u_i, u_{i+1} in quadrants).
TEST(Draw, UniformAndIndependent)
{
  const int n = 200000;
  std::vector<double> u(n);
  for (int i = 0; i < n; ++i) u[i] = draw(1, 1 + i / 100, i % 100, STREAM_REFORM).u;
  double mean = 0.0;
  for (double v : u) mean += v;
  mean /= n;
  EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  std::vector<double> s = u;
  std::sort(s.begin(), s.end());
  double dmax = 0.0;
  for (int i = 0; i < n; ++i)
    dmax = std::max(dmax, std::max(std::fabs((i + 1.0) / n - s[i]), std::fabs(s[i] - double(i) / n)));
  // KS critical value at significance 1e-4: sqrt(-ln(1e-4/2)/2)/sqrt(n)
  EXPECT_LT(dmax, std::sqrt(-std::log(0.5e-4) / 2.0) / std::sqrt(double(n)));
  // 2x2 contingency of consecutive draws: chi^2 with 1 dof
  double c[2][2] = {{0, 0}, {0, 0}};
  for (int i = 0; i + 1 < n; i += 2) c[u[i] < 0.5][u[i + 1] < 0.5] += 1.0;
  const double m = (n / 2) / 4.0;
  double chi2 = 0.0;
  for (auto &row : c)
    for (double v : row) chi2 += (v - m) * (v - m) / m;
  EXPECT_LT(chi2, 20.0);    // p ~ 1e-4 for 3 dof
}
