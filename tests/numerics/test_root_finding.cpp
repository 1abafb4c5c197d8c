#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "numerics/root_finding.hpp"

namespace rn = reentry::numerics;

namespace {
constexpr double kRoot = 0.865474033101614;  // published root of cos x = x^3
double g(double x) { return std::cos(x) - x * x * x; }
}  // namespace

TEST(RootFinding, BrentFindsRootOfCosMinusCube) {
  int evals = 0;
  const auto r = rn::brent([&](double x) { ++evals; return g(x); }, 0.0, 1.0, 1e-14, 100);
  ASSERT_EQ(r.status, rn::NumStatus::kOk);
  EXPECT_NEAR(r.x, kRoot, 1e-12);
  EXPECT_NEAR(r.f, g(r.x), 0.0);
  EXPECT_LT(r.iterations, 20);
  std::printf("brent: |x - root| = %.3e in %d iterations\n", std::fabs(r.x - kRoot), r.iterations);
}

TEST(RootFinding, BracketedSecantFindsRootOfCosMinusCube) {
  const auto r = rn::bracketed_secant(g, 0.0, 1.0, 1e-14, 100);
  ASSERT_EQ(r.status, rn::NumStatus::kOk);
  EXPECT_NEAR(r.x, kRoot, 1e-12);
  EXPECT_LT(r.iterations, 30);
  std::printf("bracketed_secant: |x - root| = %.3e in %d iterations\n", std::fabs(r.x - kRoot), r.iterations);
  // Reversed bracket works too.
  const auto r2 = rn::bracketed_secant(g, 1.0, 0.0, 1e-14, 100);
  ASSERT_EQ(r2.status, rn::NumStatus::kOk);
  EXPECT_NEAR(r2.x, kRoot, 1e-12);
}

TEST(RootFinding, SecantConverges) {
  const auto r = rn::secant(g, 0.5, 1.0, 1e-14, 50);
  ASSERT_EQ(r.status, rn::NumStatus::kOk);
  EXPECT_NEAR(r.x, kRoot, 1e-12);
  std::printf("secant: |x - root| = %.3e in %d iterations\n", std::fabs(r.x - kRoot), r.iterations);
}

TEST(RootFinding, BrentFunctionToleranceStopsOnTheResidual) {
  // |f| <= f_tol ends the search (the planner's length and reversal solves stop on a range
  // residual); the point returned satisfies it, and by the mean-value theorem lies within
  // f_tol / min |f'| of the root (|g'| = |sin x + 3 x^2| > 1.5 near the root 0.865).
  int evals_tight = 0, evals_loose = 0;
  const auto tight = rn::brent([&](double x) { ++evals_tight; return g(x); }, 0.0, 1.0, 1e-14, 100);
  const auto loose = rn::brent([&](double x) { ++evals_loose; return g(x); }, 0.0, 1.0, 1e-14, 100, 1e-3);
  ASSERT_EQ(loose.status, rn::NumStatus::kOk);
  ASSERT_EQ(tight.status, rn::NumStatus::kOk);
  EXPECT_LE(std::fabs(g(loose.x)), 1e-3);
  EXPECT_NEAR(loose.x, kRoot, 1e-3 / 1.5);
  EXPECT_LT(evals_loose, evals_tight);
}

TEST(RootFinding, NoBracketReported) {
  // cos x - x^3 < 0 on [2, 3].
  EXPECT_EQ(rn::brent(g, 2.0, 3.0, 1e-12, 50).status, rn::NumStatus::kNoBracket);
  EXPECT_EQ(rn::bracketed_secant(g, 2.0, 3.0, 1e-12, 50).status, rn::NumStatus::kNoBracket);
}

TEST(RootFinding, MaxIterationsReported) {
  EXPECT_EQ(rn::brent(g, 0.0, 1.0, 1e-14, 2).status, rn::NumStatus::kMaxIterations);
  EXPECT_EQ(rn::bracketed_secant(g, 0.0, 1.0, 1e-14, 2).status, rn::NumStatus::kMaxIterations);
  EXPECT_EQ(rn::secant(g, 0.0, 1.0, 1e-14, 2).status, rn::NumStatus::kMaxIterations);
}

TEST(RootFinding, NonFiniteReported) {
  auto nan_at_end = [](double x) { return x > 0.99 ? std::nan("") : g(x); };
  EXPECT_EQ(rn::brent(nan_at_end, 0.0, 1.0, 1e-12, 50).status, rn::NumStatus::kNonFinite);
  EXPECT_EQ(rn::bracketed_secant(nan_at_end, 0.0, 1.0, 1e-12, 50).status, rn::NumStatus::kNonFinite);
  EXPECT_EQ(rn::secant(nan_at_end, 0.5, 1.0, 1e-12, 50).status, rn::NumStatus::kNonFinite);
  // NaN met during the iteration: the secant of sqrt(x) + 1 from (1, 0.5) jumps to x < 0.
  auto sqrt_plus_one = [](double x) { return std::sqrt(x) + 1.0; };
  EXPECT_EQ(rn::secant(sqrt_plus_one, 1.0, 0.5, 1e-12, 50).status, rn::NumStatus::kNonFinite);
  // NaN inside the bracket.
  auto nan_inside = [](double x) { return (x > 0.3 && x < 0.95) ? std::nan("") : g(x); };
  EXPECT_EQ(rn::brent(nan_inside, 0.0, 1.0, 1e-12, 50).status, rn::NumStatus::kNonFinite);
  EXPECT_EQ(rn::bracketed_secant(nan_inside, 0.0, 1.0, 1e-12, 50).status, rn::NumStatus::kNonFinite);
}

TEST(RootFinding, InvalidInputReported) {
  EXPECT_EQ(rn::brent(g, 0.0, 1.0, 0.0, 50).status, rn::NumStatus::kInvalidInput);
  EXPECT_EQ(rn::bracketed_secant(g, 0.0, 1.0, 1e-12, 0).status, rn::NumStatus::kInvalidInput);
  EXPECT_EQ(rn::secant(g, 1.0, 1.0, 1e-12, 10).status, rn::NumStatus::kInvalidInput);
}
