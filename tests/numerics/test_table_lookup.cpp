#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "numerics/table_lookup.hpp"

namespace rn = reentry::numerics;

namespace {
// Independent truth: linear scan for the clamped interval.
int scan_index(const std::vector<double>& x, double xq) {
  const int n = static_cast<int>(x.size());
  if (xq <= x[0]) return 0;
  if (xq >= x[n - 1]) return n - 2;
  for (int j = 0; j < n - 1; ++j) {
    if (x[j] <= xq && xq < x[j + 1]) return j;
  }
  return n - 2;
}
}  // namespace

TEST(TableLookup, BracketIndexMatchesLinearScanWithAndWithoutHint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(0.01, 2.0);
  std::vector<double> x(57);
  x[0] = -3.0;
  for (std::size_t i = 1; i < x.size(); ++i) x[i] = x[i - 1] + step(rng);
  std::uniform_real_distribution<double> q(x.front() - 1.0, x.back() + 1.0);
  const int n = static_cast<int>(x.size());
  int hint = 0;
  for (int k = 0; k < 5000; ++k) {
    const double xq = q(rng);
    const int truth = scan_index(x, xq);
    const int no_hint = rn::bracket_index(x.data(), n, xq);
    const int with_hint = rn::bracket_index(x.data(), n, xq, hint);
    const int bad_hint = rn::bracket_index(x.data(), n, xq, 1000);
    ASSERT_EQ(no_hint, truth) << xq;
    ASSERT_EQ(with_hint, truth) << xq;
    ASSERT_EQ(bad_hint, truth) << xq;
    hint = with_hint;
  }
  // Knots themselves: x[j] starts interval j (n-2 for the last knot), whatever the hint.
  for (int j = 0; j < n; ++j) {
    const int expected = j < n - 1 ? j : n - 2;
    for (int h = -1; h < n; ++h) ASSERT_EQ(rn::bracket_index(x.data(), n, x[j], h), expected) << j << " " << h;
    EXPECT_EQ(scan_index(x, x[j]), expected);
  }
}

TEST(TableLookup, LinearExactForLinearFunctionAndClamps) {
  const double x[] = {0.0, 0.5, 2.0, 3.5, 10.0};
  double y[5];
  for (int i = 0; i < 5; ++i) y[i] = 4.0 - 1.5 * x[i];
  int hint = -1;
  for (double xq = 0.0; xq <= 10.0; xq += 0.137) {
    EXPECT_NEAR(rn::linear(x, y, 5, xq, &hint), 4.0 - 1.5 * xq, 1e-13);
  }
  EXPECT_DOUBLE_EQ(rn::linear(x, y, 5, -5.0), y[0]);
  EXPECT_DOUBLE_EQ(rn::linear(x, y, 5, 50.0), y[4]);
}

TEST(TableLookup, BilinearExactForBilinearFunction) {
  const double x[] = {-2.0, -0.5, 0.0, 1.25, 4.0};
  const double y[] = {10.0, 11.0, 15.0, 30.0};
  const double a = 1.3, b = -0.7, c = 0.25, d = 0.05;
  auto f = [&](double xx, double yy) { return a + b * xx + c * yy + d * xx * yy; };
  double v[5 * 4];
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) v[i * 4 + j] = f(x[i], y[j]);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> qx(-2.0, 4.0);
  std::uniform_real_distribution<double> qy(10.0, 30.0);
  int hx = -1, hy = -1;
  for (int k = 0; k < 2000; ++k) {
    const double xq = qx(rng);
    const double yq = qy(rng);
    ASSERT_NEAR(rn::bilinear(x, 5, y, 4, v, xq, yq, &hx, &hy), f(xq, yq), 1e-12);
  }
  // Clamping: outside the grid the value equals the one at the nearest edge.
  EXPECT_NEAR(rn::bilinear(x, 5, y, 4, v, -10.0, 12.0), f(-2.0, 12.0), 1e-12);
  EXPECT_NEAR(rn::bilinear(x, 5, y, 4, v, 9.0, 12.0), f(4.0, 12.0), 1e-12);
  EXPECT_NEAR(rn::bilinear(x, 5, y, 4, v, 0.3, 1.0), f(0.3, 10.0), 1e-12);
  EXPECT_NEAR(rn::bilinear(x, 5, y, 4, v, 0.3, 99.0), f(0.3, 30.0), 1e-12);
  EXPECT_NEAR(rn::bilinear(x, 5, y, 4, v, 100.0, -100.0), f(4.0, 10.0), 1e-12);
}
