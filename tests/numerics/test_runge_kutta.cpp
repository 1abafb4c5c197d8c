#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "numerics/runge_kutta.hpp"

namespace rn = reentry::numerics;

namespace {

// Order conditions of the quadrature part: sum_k w_k alpha_k^(q-1) = 1/q for q = 1..order,
// and row sums of beta equal alpha (consistency). These are mathematical identities, independent
// of the integrator code.
void check_tableau(const rn::detail::RkfTableau& tb, int propagated_order) {
  for (int s = 0; s < tb.stages; ++s) {
    double row = 0.0;
    for (int l = 0; l < s; ++l) row += tb.beta[s][l];
    EXPECT_NEAR(row, tb.alpha[s], 1e-14) << "stage " << s;
  }
  double sum_e = 0.0;
  for (int s = 0; s < tb.stages; ++s) sum_e += tb.e[s];
  EXPECT_NEAR(sum_e, 0.0, 1e-15);
  for (int q = 1; q <= propagated_order + 1; ++q) {
    double low = 0.0;
    double high = 0.0;
    for (int s = 0; s < tb.stages; ++s) {
      low += tb.c[s] * std::pow(tb.alpha[s], q - 1);
      high += (tb.c[s] + tb.e[s]) * std::pow(tb.alpha[s], q - 1);
    }
    if (q <= propagated_order) {
      EXPECT_NEAR(low, 1.0 / q, 1e-14) << "q " << q;
    }
    EXPECT_NEAR(high, 1.0 / q, 1e-14) << "q " << q;
  }
  // Second family of conditions: sum_k w_k sum_l beta_kl alpha_l = 1/6 (order >= 3) and
  // sum_k w_k alpha_k sum_l beta_kl alpha_l = 1/8 (order >= 4).
  double c3 = 0.0, c4 = 0.0;
  for (int s = 0; s < tb.stages; ++s) {
    double inner = 0.0;
    for (int l = 0; l < s; ++l) inner += tb.beta[s][l] * tb.alpha[l];
    c3 += tb.c[s] * inner;
    c4 += tb.c[s] * tb.alpha[s] * inner;
  }
  EXPECT_NEAR(c3, 1.0 / 6.0, 1e-14);
  EXPECT_NEAR(c4, 1.0 / 8.0, 1e-14);
}

// Fehlberg's test problem: x' = -2 t x ln y, y' = 2 t y ln x; x = exp(cos t^2), y = exp(sin t^2).
struct FehlbergProblem {
  void operator()(double t, const rn::State<2>& y, rn::State<2>& dydt) const {
    dydt[0] = -2.0 * t * y[0] * std::log(y[1]);
    dydt[1] = 2.0 * t * y[1] * std::log(y[0]);
  }
};

constexpr double kMuEarth = 3.986004418e14;  // m^3/s^2

struct TwoBody {
  void operator()(double, const rn::State<6>& s, rn::State<6>& d) const {
    const double r = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    const double k = -kMuEarth / (r * r * r);
    d[0] = s[3];
    d[1] = s[4];
    d[2] = s[5];
    d[3] = k * s[0];
    d[4] = k * s[1];
    d[5] = k * s[2];
  }
};

double energy(const rn::State<6>& s) {
  const double r = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  return 0.5 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]) - kMuEarth / r;
}
double angular_momentum_z(const rn::State<6>& s) { return s[0] * s[4] - s[1] * s[3]; }

}  // namespace

TEST(RungeKutta, FehlbergTableausSatisfyOrderConditions) {
  check_tableau(rn::detail::kFehlberg56, 5);
  check_tableau(rn::detail::kFehlberg78, 7);
  EXPECT_EQ(rn::detail::kFehlberg56.stages, 8);
  EXPECT_EQ(rn::detail::kFehlberg78.stages, 13);
}

TEST(RungeKutta, Rk4ExactForQuarticSolution) {
  // y' = t^3 -> y = t^4 / 4: RK4 (Simpson's rule here) integrates cubics exactly.
  auto f = [](double t, const rn::State<1>&, rn::State<1>& d) { d[0] = t * t * t; };
  rn::State<1> y{0.0};
  double t = 0.0;
  const double h = 0.1;
  for (int i = 0; i < 20; ++i) {
    rn::State<1> next{};
    rn::rk4_step<1>(f, t, y, h, next);
    y = next;
    t = (i + 1) * h;
  }
  EXPECT_NEAR(y[0], std::pow(2.0, 4) / 4.0, 1e-13);
}

TEST(RungeKutta, Rk4FourthOrderConvergence) {
  // y' = y: halving h must reduce the error at t = 1 by ~16.
  auto f = [](double, const rn::State<1>& y, rn::State<1>& d) { d[0] = y[0]; };
  double err[2];
  for (int pass = 0; pass < 2; ++pass) {
    const int n = pass == 0 ? 20 : 40;
    rn::State<1> y{1.0};
    for (int i = 0; i < n; ++i) {
      rn::State<1> next{};
      rn::rk4_step<1>(f, i * (1.0 / n), y, 1.0 / n, next);
      y = next;
    }
    err[pass] = std::fabs(y[0] - std::exp(1.0));
  }
  EXPECT_NEAR(err[0] / err[1], 16.0, 1.0);
}

TEST(RungeKutta, Rkf56FehlbergTestProblem) {
  const auto tol = rn::RkfTolerances<2>::uniform(1e-10, 1e-10);
  const rn::State<2> y0{std::exp(1.0), 1.0};
  const auto res = rn::integrate(rn::RkfMethod::kRkf56, FehlbergProblem{}, 0.0, y0, 5.0, 1e-3, tol, 100000);
  ASSERT_EQ(res.status, rn::NumStatus::kOk);
  EXPECT_EQ(res.t, 5.0);
  const double ex = std::exp(std::cos(25.0));
  const double ey = std::exp(std::sin(25.0));
  const double err = std::fmax(std::fabs(res.y[0] - ex) / ex, std::fabs(res.y[1] - ey) / ey);
  std::printf("RKF5(6) Fehlberg problem t=5: max rel err %.3e, %d evals, %d accepted, %d rejected\n", err,
              res.evaluations, res.accepted_steps, res.rejected_steps);
  // Global error accumulates over ~300 steps of local tolerance 1e-10 (measured 4.4e-8).
  EXPECT_LT(err, 1e-7);
  EXPECT_EQ(res.evaluations, 8 * (res.accepted_steps + res.rejected_steps));
  // Same problem with RKF7(8).
  const auto res78 = rn::integrate(rn::RkfMethod::kRkf78, FehlbergProblem{}, 0.0, y0, 5.0, 1e-3, tol, 100000);
  ASSERT_EQ(res78.status, rn::NumStatus::kOk);
  const double err78 = std::fmax(std::fabs(res78.y[0] - ex) / ex, std::fabs(res78.y[1] - ey) / ey);
  std::printf("RKF7(8) Fehlberg problem t=5: max rel err %.3e, %d evals, %d accepted, %d rejected\n", err78,
              res78.evaluations, res78.accepted_steps, res78.rejected_steps);
  EXPECT_LT(err78, 1e-8);  // measured 4.5e-9
}

TEST(RungeKutta, PropagatedSolutionHasTheLowerOrder) {
  // Fixed steps (huge tolerance so all are accepted). The observed order log2(err(h)/err(h/2)) must be
  // ~5 for RKF5(6) and ~7 for RKF7(8): this also checks the thesis convention that the lower-order
  // solution is propagated (propagating the higher one would show ~6 resp. ~8).
  // RKF5(6): y' = cos(t) y, y = exp(sin t) on [0, 1].
  {
    auto f = [](double t, const rn::State<1>& y, rn::State<1>& d) { d[0] = std::cos(t) * y[0]; };
    const auto loose = rn::RkfTolerances<1>::uniform(1e6, 1e6);
    const rn::EmbeddedRungeKutta<1> rk(rn::RkfMethod::kRkf56);
    double err[2];
    for (int pass = 0; pass < 2; ++pass) {
      const int n = pass == 0 ? 10 : 20;
      const double h = 1.0 / n;
      rn::State<1> y{1.0};
      for (int i = 0; i < n; ++i) {
        const auto s = rk.step(f, i * h, y, h, loose);
        ASSERT_TRUE(s.accepted);
        y = s.y;
      }
      err[pass] = std::fabs(y[0] - std::exp(std::sin(1.0)));
    }
    const double order = std::log2(err[0] / err[1]);
    std::printf("RKF5(6) observed order %.2f\n", order);
    EXPECT_GT(order, 4.6);
    EXPECT_LT(order, 5.8);
  }
  // RKF7(8): Fehlberg's problem on [0, 1.5].
  {
    const auto loose = rn::RkfTolerances<2>::uniform(1e6, 1e6);
    const rn::EmbeddedRungeKutta<2> rk(rn::RkfMethod::kRkf78);
    double err[2];
    for (int pass = 0; pass < 2; ++pass) {
      const int n = pass == 0 ? 10 : 20;
      const double h = 1.5 / n;
      rn::State<2> y{std::exp(1.0), 1.0};
      for (int i = 0; i < n; ++i) {
        const auto s = rk.step(FehlbergProblem{}, i * h, y, h, loose);
        ASSERT_TRUE(s.accepted);
        y = s.y;
      }
      err[pass] = std::fabs(y[0] - std::exp(std::cos(2.25)));
    }
    const double order = std::log2(err[0] / err[1]);
    std::printf("RKF7(8) observed order %.2f\n", order);
    EXPECT_GT(order, 6.6);
    EXPECT_LT(order, 7.8);
  }
}

TEST(RungeKutta, Rkf78KeplerOrbitConservesAndMatchesKeplerEquation) {
  const double a = 7.0e6;
  const double e = 0.1;
  const double rp = a * (1.0 - e);
  const double vp = std::sqrt(kMuEarth * (1.0 + e) / rp);
  const rn::State<6> y0{rp, 0.0, 0.0, 0.0, vp, 0.0};
  const double n_mean = std::sqrt(kMuEarth / (a * a * a));
  const double period = 2.0 * M_PI / n_mean;
  const double t_end = 10.25 * period;  // ends away from periapsis
  rn::RkfTolerances<6> tol{};
  for (int i = 0; i < 3; ++i) {
    tol.abs[i] = 1e-6;      // m
    tol.abs[i + 3] = 1e-9;  // m/s
    tol.rel[i] = 1e-13;
    tol.rel[i + 3] = 1e-13;
  }
  const auto res = rn::integrate(rn::RkfMethod::kRkf78, TwoBody{}, 0.0, y0, t_end, 10.0, tol, 200000);
  ASSERT_EQ(res.status, rn::NumStatus::kOk);
  EXPECT_EQ(res.t, t_end);
  const double de = std::fabs((energy(res.y) - energy(y0)) / energy(y0));
  const double dh = std::fabs((angular_momentum_z(res.y) - angular_momentum_z(y0)) / angular_momentum_z(y0));
  EXPECT_LT(de, 1e-9);
  EXPECT_LT(dh, 1e-9);
  // Analytic position: Kepler's equation M = E - e sin E solved by Newton in this test.
  const double mean_anomaly = std::fmod(n_mean * t_end, 2.0 * M_PI);
  double ecc_anomaly = mean_anomaly;
  for (int i = 0; i < 50; ++i) {
    ecc_anomaly -= (ecc_anomaly - e * std::sin(ecc_anomaly) - mean_anomaly) / (1.0 - e * std::cos(ecc_anomaly));
  }
  const double x_true = a * (std::cos(ecc_anomaly) - e);
  const double y_true = a * std::sqrt(1.0 - e * e) * std::sin(ecc_anomaly);
  const double pos_err = std::hypot(res.y[0] - x_true, res.y[1] - y_true);
  std::printf("RKF7(8) Kepler 10.25 periods: |dE/E| %.3e, |dh/h| %.3e, position error %.3e m, %d evals, %d acc, %d rej\n",
              de, dh, pos_err, res.evaluations, res.accepted_steps, res.rejected_steps);
  EXPECT_LT(pos_err, 0.1);  // metres, after ~4.5e8 m of flight (measured 3.4e-2 m)
  EXPECT_NEAR(res.y[2], 0.0, 0.0);
  // The same orbit with RKF5(6) at the same tolerance also conserves the invariants.
  const auto res56 = rn::integrate(rn::RkfMethod::kRkf56, TwoBody{}, 0.0, y0, t_end, 10.0, tol, 400000);
  ASSERT_EQ(res56.status, rn::NumStatus::kOk);
  const double de56 = std::fabs((energy(res56.y) - energy(y0)) / energy(y0));
  const double pos_err56 = std::hypot(res56.y[0] - x_true, res56.y[1] - y_true);
  std::printf("RKF5(6) Kepler 10.25 periods: |dE/E| %.3e, position error %.3e m, %d evals\n", de56, pos_err56,
              res56.evaluations);
  EXPECT_LT(de56, 1e-9);
  EXPECT_LT(pos_err56, 0.3);  // measured 8.9e-2 m
}

TEST(RungeKutta, ConstantAccelerationExactForBothMethods) {
  // x'' = a: x = x0 + v0 t + a t^2 / 2 is a polynomial both pairs integrate exactly.
  const double acc = -3.7;
  auto f = [acc](double, const rn::State<2>& y, rn::State<2>& d) {
    d[0] = y[1];
    d[1] = acc;
  };
  const rn::State<2> y0{100.0, 25.0};
  const auto tol = rn::RkfTolerances<2>::uniform(1e-12, 1e-12);
  for (const auto method : {rn::RkfMethod::kRkf56, rn::RkfMethod::kRkf78}) {
    const auto res = rn::integrate(method, f, 0.0, y0, 17.3, 0.01, tol, 1000);
    ASSERT_EQ(res.status, rn::NumStatus::kOk);
    const double t = 17.3;
    EXPECT_NEAR(res.y[0], 100.0 + 25.0 * t + 0.5 * acc * t * t, 1e-12 * 600.0);
    EXPECT_NEAR(res.y[1], 25.0 + acc * t, 1e-13 * 50.0);
    EXPECT_EQ(res.rejected_steps, 0);
    // Backwards in time back to the start.
    const auto back = rn::integrate(method, f, 17.3, res.y, 0.0, 1.0, tol, 1000);
    ASSERT_EQ(back.status, rn::NumStatus::kOk);
    EXPECT_EQ(back.t, 0.0);
    EXPECT_NEAR(back.y[0], y0[0], 1e-11);
    EXPECT_NEAR(back.y[1], y0[1], 1e-12);
  }
}

TEST(RungeKutta, StepControlRejectsLargeStepAndMeetsTolerance) {
  // Harmonic oscillator x'' = -x from (1, 0): exact (cos t, -sin t).
  auto f = [](double, const rn::State<2>& y, rn::State<2>& d) {
    d[0] = y[1];
    d[1] = -y[0];
  };
  const auto tol = rn::RkfTolerances<2>::uniform(1e-10, 1e-10);
  for (const auto method : {rn::RkfMethod::kRkf56, rn::RkfMethod::kRkf78}) {
    const rn::EmbeddedRungeKutta<2> rk(method);
    const rn::State<2> y0{1.0, 0.0};
    // A single step of 3 time units is far too large.
    const auto big = rk.step(f, 0.0, y0, 3.0, tol);
    EXPECT_EQ(big.status, rn::NumStatus::kOk);
    EXPECT_FALSE(big.accepted);
    EXPECT_GT(big.error_norm, 1.0);
    EXPECT_LT(big.h_next, 3.0);
    EXPECT_GE(big.h_next, 0.3 - 1e-15);  // shrink limited to 0.1x
    // Walk with the controller from an oversized step: every accepted step's true local error
    // (vs the exact solution started from the same point) must be within a small multiple of the
    // scaled tolerance, and the first attempt must have been rejected.
    double t = 0.0;
    rn::State<2> y = y0;
    double h = 3.0;
    int rejected = 0;
    int accepted = 0;
    double worst_local = 0.0;
    for (int i = 0; i < 1000 && t < 20.0; ++i) {
      const auto s = rk.step(f, t, y, h, tol);
      ASSERT_EQ(s.status, rn::NumStatus::kOk);
      if (s.accepted) {
        ++accepted;
        // Exact propagation of the current state over h: rotation.
        const double c = std::cos(h);
        const double sn = std::sin(h);
        const double x_ex = y[0] * c + y[1] * sn;
        const double v_ex = -y[0] * sn + y[1] * c;
        const double e0 = std::fabs(s.y[0] - x_ex) / (1e-10 + 1e-10 * std::fabs(x_ex));
        const double e1 = std::fabs(s.y[1] - v_ex) / (1e-10 + 1e-10 * std::fabs(v_ex));
        worst_local = std::fmax(worst_local, std::sqrt(0.5 * (e0 * e0 + e1 * e1)));
        y = s.y;
        t += h;
        EXPECT_LE(s.h_next, 5.0 * h + 1e-12);
      } else {
        ++rejected;
        EXPECT_LT(s.h_next, h);
      }
      h = s.h_next;
    }
    EXPECT_GE(rejected, 1);
    EXPECT_GT(accepted, 10);
    EXPECT_LT(worst_local, 1.5);
    std::printf("%s step control: %d rejected, %d accepted, worst true local scaled error %.3f\n",
                method == rn::RkfMethod::kRkf56 ? "RKF5(6)" : "RKF7(8)", rejected, accepted, worst_local);
    // integrate() from an oversized h0 also reports rejections and ends on the exact solution.
    const auto res = rk.integrate(f, 0.0, y0, 20.0, 20.0, tol, 10000);
    ASSERT_EQ(res.status, rn::NumStatus::kOk);
    EXPECT_GE(res.rejected_steps, 1);
    // Global error after ~3 periods at local tolerance 1e-10 (measured <= 3e-8).
    EXPECT_NEAR(res.y[0], std::cos(20.0), 1e-7);
    EXPECT_NEAR(res.y[1], -std::sin(20.0), 1e-7);
  }
}

TEST(RungeKutta, IntegrateReportsFailures) {
  auto f = [](double, const rn::State<1>& y, rn::State<1>& d) { d[0] = y[0]; };
  const auto tol = rn::RkfTolerances<1>::uniform(1e-12, 1e-12);
  const rn::State<1> y0{1.0};
  // Step budget too small.
  EXPECT_EQ(rn::integrate(rn::RkfMethod::kRkf56, f, 0.0, y0, 10.0, 0.1, tol, 3).status, rn::NumStatus::kMaxIterations);
  // Invalid inputs.
  EXPECT_EQ(rn::integrate(rn::RkfMethod::kRkf56, f, 0.0, y0, 1.0, 0.0, tol, 10).status, rn::NumStatus::kInvalidInput);
  // Finite-time blow-up y' = y^2 (y = 1/(1 - t)): the step collapses before t = 1.
  auto blowup = [](double, const rn::State<1>& y, rn::State<1>& d) { d[0] = y[0] * y[0]; };
  const auto r = rn::integrate(rn::RkfMethod::kRkf78, blowup, 0.0, y0, 2.0, 0.1, tol, 100000, 1e-10);
  EXPECT_TRUE(r.status == rn::NumStatus::kStepTooSmall || r.status == rn::NumStatus::kNonFinite);
  EXPECT_LT(r.t, 1.0 + 1e-9);  // stops at the pole t = 1 (a last stage may straddle it)
  EXPECT_GT(r.t, 0.999);
  // NaN in the derivative.
  auto nan_f = [](double t, const rn::State<1>&, rn::State<1>& d) { d[0] = t > 0.5 ? std::nan("") : 1.0; };
  const auto rn_ = rn::integrate(rn::RkfMethod::kRkf56, nan_f, 0.0, y0, 1.0, 0.1, tol, 100000);
  EXPECT_EQ(rn_.status, rn::NumStatus::kNonFinite);
  EXPECT_LE(rn_.t, 0.5);
}
