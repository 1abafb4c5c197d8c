#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <random>
#include <vector>

#include "dense_solve.hpp"
#include "numerics/cubic_spline.hpp"

namespace rn = reentry::numerics;

TEST(CubicSpline, ReproducesSineOnFineGrid) {
  // sin has zero curvature at 0 and pi, so the natural end conditions are consistent with it.
  constexpr int kN = 101;
  double x[kN];
  double y[kN];
  for (int i = 0; i < kN; ++i) {
    x[i] = M_PI * i / (kN - 1);
    y[i] = std::sin(x[i]);
  }
  rn::NaturalCubicSpline<128> s;
  ASSERT_EQ(s.fit(x, y, kN), rn::NumStatus::kOk);
  ASSERT_EQ(s.size(), kN);
  double max_v = 0.0, max_d = 0.0, max_dd = 0.0;
  for (int k = 0; k <= 10000; ++k) {
    const double xq = M_PI * k / 10000.0;
    max_v = std::fmax(max_v, std::fabs(s.value(xq) - std::sin(xq)));
    max_d = std::fmax(max_d, std::fabs(s.derivative(xq) - std::cos(xq)));
    max_dd = std::fmax(max_dd, std::fabs(s.second_derivative(xq) + std::sin(xq)));
  }
  // h = pi/100: interpolation error ~ 5/384 h^4 ~ 1.3e-8, second derivative error ~ h^2/12 ~ 1e-4.
  EXPECT_LT(max_v, 2e-8);
  EXPECT_LT(max_d, 2e-5);
  EXPECT_LT(max_dd, 2e-4);
  RecordProperty("sin_value_max_err", std::to_string(max_v));
  RecordProperty("sin_second_derivative_max_err", std::to_string(max_dd));
  std::printf("spline sin: max|value err| = %.3e, max|dy err| = %.3e, max|d2y err| = %.3e\n", max_v, max_d, max_dd);
}

TEST(CubicSpline, NaturalEndConditionsAndKnotInterpolation) {
  // exp has non-zero curvature at the ends; the natural spline must still have y'' = 0 there.
  constexpr int kN = 12;
  double x[kN];
  double y[kN];
  for (int i = 0; i < kN; ++i) {
    x[i] = 0.3 * i + 0.01 * i * i;
    y[i] = std::exp(x[i]);
  }
  rn::NaturalCubicSpline<kN> s;
  ASSERT_EQ(s.fit(x, y, kN), rn::NumStatus::kOk);
  EXPECT_EQ(s.second_derivative(x[0]), 0.0);
  EXPECT_EQ(s.second_derivative(x[kN - 1]), 0.0);
  EXPECT_EQ(s.knot_second_derivative(0), 0.0);
  EXPECT_EQ(s.knot_second_derivative(kN - 1), 0.0);
  for (int i = 0; i < kN; ++i) EXPECT_NEAR(s.value(x[i]), y[i], 1e-13 * std::fabs(y[i]));
  // Continuity of the first derivative across every interior knot.
  for (int i = 1; i < kN - 1; ++i) {
    int left = i - 1;
    int right = i;
    const double eps = 1e-9;
    EXPECT_NEAR(s.derivative(x[i] - eps, &left), s.derivative(x[i] + eps, &right), 1e-6);
  }
  // Linear extrapolation outside the knots with the end slopes.
  const double slope0 = s.derivative(x[0]);
  EXPECT_NEAR(s.value(x[0] - 0.5), y[0] - 0.5 * slope0, 1e-12);
  const double slope1 = s.derivative(x[kN - 1]);
  EXPECT_NEAR(s.value(x[kN - 1] + 0.25), y[kN - 1] + 0.25 * slope1, 1e-12);
  EXPECT_EQ(s.second_derivative(x[kN - 1] + 1.0), 0.0);
}

TEST(CubicSpline, ReproducesLinearFunctionExactly) {
  const double x[] = {1.0, 1.5, 4.0, 4.1, 9.0};
  double y[5];
  for (int i = 0; i < 5; ++i) y[i] = -2.0 + 0.75 * x[i];
  rn::NaturalCubicSpline<8> s;
  ASSERT_EQ(s.fit(x, y, 5), rn::NumStatus::kOk);
  for (double xq = 0.0; xq < 10.0; xq += 0.0917) {
    EXPECT_NEAR(s.value(xq), -2.0 + 0.75 * xq, 1e-13);
    EXPECT_NEAR(s.derivative(xq), 0.75, 1e-13);
  }
}

TEST(CubicSpline, SecondDerivativesMatchDenseSolveOfEq48) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> step(0.05, 3.0);
  std::uniform_real_distribution<double> val(-5.0, 5.0);
  constexpr int kN = 40;
  double x[kN];
  double y[kN];
  x[0] = 0.0;
  for (int i = 0; i < kN; ++i) {
    if (i > 0) x[i] = x[i - 1] + step(rng);
    y[i] = val(rng);
  }
  rn::NaturalCubicSpline<kN> s;
  ASSERT_EQ(s.fit(x, y, kN), rn::NumStatus::kOk);
  // Dense (4.8) for unknowns y2[1..n-2].
  const int m = kN - 2;
  std::vector<std::vector<double>> a(m, std::vector<double>(m, 0.0));
  std::vector<double> b(m, 0.0);
  for (int r = 0; r < m; ++r) {
    const int j = r + 1;
    const double h0 = x[j] - x[j - 1];
    const double h1 = x[j + 1] - x[j];
    if (r > 0) a[r][r - 1] = h0;
    a[r][r] = 2.0 * (h0 + h1);
    if (r < m - 1) a[r][r + 1] = h1;
    b[r] = 6.0 * ((y[j + 1] - y[j]) / h1 - (y[j] - y[j - 1]) / h0);
  }
  const std::vector<double> truth = rn::test::dense_solve(a, b);
  for (int r = 0; r < m; ++r) EXPECT_NEAR(s.knot_second_derivative(r + 1), truth[r], 1e-11 * (1.0 + std::fabs(truth[r])));
}

TEST(CubicSpline, TridiagonalSolverMatchesDenseSolve) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr int kN = 25;
  double sub[kN], diag[kN], sup[kN], rhs[kN], x[kN], work[kN];
  std::vector<std::vector<double>> a(kN, std::vector<double>(kN, 0.0));
  std::vector<double> b(kN);
  for (int i = 0; i < kN; ++i) {
    sub[i] = u(rng);
    sup[i] = u(rng);
    diag[i] = 2.5 + u(rng);  // diagonally dominant
    rhs[i] = 10.0 * u(rng);
    b[i] = rhs[i];
    a[i][i] = diag[i];
    if (i > 0) a[i][i - 1] = sub[i];
    if (i < kN - 1) a[i][i + 1] = sup[i];
  }
  ASSERT_EQ(rn::solve_tridiagonal(sub, diag, sup, rhs, x, kN, work), rn::NumStatus::kOk);
  const std::vector<double> truth = rn::test::dense_solve(a, b);
  for (int i = 0; i < kN; ++i) EXPECT_NEAR(x[i], truth[i], 1e-12 * (1.0 + std::fabs(truth[i])));
  diag[0] = 0.0;
  EXPECT_EQ(rn::solve_tridiagonal(sub, diag, sup, rhs, x, kN, work), rn::NumStatus::kNonFinite);
  EXPECT_EQ(rn::solve_tridiagonal(sub, diag, sup, rhs, x, 0, work), rn::NumStatus::kInvalidInput);
}

TEST(CubicSpline, HintedLookupGivesSameIntervalAsBisection) {
  constexpr int kN = 200;
  double x[kN], y[kN];
  for (int i = 0; i < kN; ++i) {
    x[i] = std::pow(1.03, i);
    y[i] = std::log(x[i]);
  }
  rn::NaturalCubicSpline<kN> s;
  ASSERT_EQ(s.fit(x, y, kN), rn::NumStatus::kOk);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> q(0.5, x[kN - 1] + 2.0);
  int explicit_hint = 0;
  for (int k = 0; k < 3000; ++k) {
    // Alternate random jumps and small monotone moves (the typical trajectory pattern).
    const double xq = (k % 3 == 0) ? q(rng) : std::fmin(x[kN - 1] + 1.0, q(rng) * 0.999);
    const int truth = rn::bracket_index(x, kN, xq);
    ASSERT_EQ(s.interval(xq), truth);
    ASSERT_EQ(s.interval(xq, &explicit_hint), truth);
    int fresh = -1;
    ASSERT_EQ(s.value(xq), s.value(xq, &fresh));
  }
}

TEST(CubicSpline, RejectsInvalidInput) {
  rn::NaturalCubicSpline<4> s;
  const double x_ok[] = {0.0, 1.0, 2.0, 3.0, 4.0};
  const double y_ok[] = {0.0, 1.0, 0.0, 1.0, 0.0};
  EXPECT_EQ(s.fit(x_ok, y_ok, 1), rn::NumStatus::kInvalidInput);
  EXPECT_EQ(s.fit(x_ok, y_ok, 5), rn::NumStatus::kInvalidInput);  // over capacity
  const double x_bad[] = {0.0, 1.0, 1.0, 3.0};
  EXPECT_EQ(s.fit(x_bad, y_ok, 4), rn::NumStatus::kInvalidInput);
  const double y_nan[] = {0.0, NAN, 0.0, 1.0};
  EXPECT_EQ(s.fit(x_ok, y_nan, 4), rn::NumStatus::kNonFinite);
  EXPECT_EQ(s.size(), 0);
  EXPECT_EQ(s.fit(x_ok, y_ok, 2), rn::NumStatus::kOk);  // two knots: straight line
  EXPECT_NEAR(s.value(0.25), 0.25, 1e-15);
}
