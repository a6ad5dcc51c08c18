// Interaction kernel k(r) of pair eq/elastic (lib/eq_kernel.h).
#include "eq_distribution.h"
#include "eq_kernel.h"

#include "gtest/gtest.h"

#include <cmath>
#include <string>

using namespace feq;

TEST(Kernel, CrossoverIsContinuousWithTheRightPowers)
{
  const Kernel k = make_crossover(0.3, 3.0);
  EXPECT_DOUBLE_EQ(k.eval(1.0), 0.3);
  EXPECT_DOUBLE_EQ(k.eval(3.0), 0.1);
  EXPECT_NEAR(k.eval(3.0 * (1 + 1e-12)), 0.1, 1e-12);    // continuous at lambda_c
  // r^-1 below, r^-3 beyond: local exponents d ln k / d ln r
  auto slope = [&](double r) { return std::log(k.eval(r * 1.001) / k.eval(r)) / std::log(1.001); };
  EXPECT_NEAR(slope(1.5), -1.0, 1e-9);
  EXPECT_NEAR(slope(6.0), -3.0, 1e-9);
  EXPECT_TRUE(std::isinf(k.range()));
  EXPECT_THROW(make_crossover(-1.0, 3.0), SpecError);
  EXPECT_THROW(make_crossover(1.0, 0.0), SpecError);
}

TEST(Kernel, TableInterpolatesRkLinearly)
{
  const std::string text = "# test\nK\nN 3 aniso\n\n1 1.0 2.0 0.2\n2 2.0 0.5 0.1\n3 4.0 0.25 0.0\n";
  const Kernel k = read_kernel_table(text, "t", "K");
  ASSERT_EQ(k.r.size(), 3u);
  EXPECT_TRUE(k.anisotropic());
  EXPECT_DOUBLE_EQ(k.range(), 4.0);
  // at the points: k0 + k2 cos(2 phi)
  EXPECT_DOUBLE_EQ(k.eval(2.0, 1.0), 0.6);
  EXPECT_DOUBLE_EQ(k.eval(2.0, -1.0), 0.4);
  // between points r k is linear: r k0 at 1.5 = (2 + 1)/2
  EXPECT_DOUBLE_EQ(k.eval(1.5, 0.0), 1.5 / 1.5);
  // below the first point: k(r_1) r_1 / r; beyond the last: 0
  EXPECT_DOUBLE_EQ(k.eval(0.5, 0.0), 4.0);
  EXPECT_EQ(k.eval(4.0001, 0.0), 0.0);
  // a tabulated 1/r kernel is reproduced exactly
  const Kernel inv = read_kernel_table("A\nN 2\n1 1.0 1.0\n2 5.0 0.2\n", "t", "A");
  for (double r : {1.0, 1.3, 2.7, 4.99}) EXPECT_NEAR(inv.eval(r), 1.0 / r, 1e-15);
}

TEST(Kernel, TableErrorsNameFileAndLine)
{
  auto msg = [](const std::string &text, const std::string &kw) {
    try {
      read_kernel_table(text, "f.table", kw);
    } catch (const SpecError &e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(msg("A\nN 2\n1 1 1\n2 2 1\n", "B"), "keyword 'B' not found in table file 'f.table'");
  EXPECT_EQ(msg("A\nN 2\n1 1 1\n2 1 1\n", "A"), "table file 'f.table' line 4: r must increase strictly");
  EXPECT_EQ(msg("A\nN 2\n1 1 1\n3 2 1\n", "A"),
            "table file 'f.table' line 4: index 3 out of sequence (expected 2)");
  EXPECT_EQ(msg("A\nN 2\n1 1 x\n2 2 1\n", "A"), "table file 'f.table' line 3: not a finite number");
  EXPECT_EQ(msg("A\nN 1\n1 1 1\n", "A"),
            "table file 'f.table' line 2: expected 'N <count> [aniso]' with count >= 2 after keyword 'A'");
  EXPECT_EQ(msg("A\nN 3\n1 1 1\n2 2 1\nB\n", "A"),
            "table file 'f.table' section 'A': expected 3 points, found 2");
}
