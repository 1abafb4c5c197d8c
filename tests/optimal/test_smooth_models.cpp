// The optimizer's smooth models against the truth's tables they fit: equal at the nodes, within
// a bound between them (inside the cells, where a bilinear table and a C2 fit differ most), and
// C2 across the cell edges (second derivatives from the AD scalars on both sides of an edge).
#include <gtest/gtest.h>

#include <cmath>

#include "ad.hpp"
#include "run_oracle.hpp"
#include "smooth_models.hpp"

namespace reentry::optimal {
namespace {

config::Mission load(const std::string& name) {
  const config::LoadResult r = config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

struct FitError {
  double node = 0.0, between = 0.0, scale = 0.0;
};

// Largest |fit - truth| of C_L (lift) or C_D at the table nodes and inside the cells (fractions
// of the cell that are no sample of the fit), at dynamic pressure q, alpha up to alpha_hi.
FitError fit_error(const truth::PointModel& model, const SmoothAero& fit, bool lift, double q, double alpha_hi) {
  const config::Table2D& t = lift ? model.aero->model().cl : model.aero->model().cd;
  FitError e;
  auto diff = [&](double a, double m) {
    const truth::AeroCoefficients c = SmoothAero::truth_coefficients(model, a, m, q);
    const truth::AeroCoefficients s = fit(a, m, q);
    const double truth_v = lift ? c.cl : c.cd;
    e.scale = std::max(e.scale, std::fabs(truth_v));
    return std::fabs((lift ? s.cl / model.cl_scale : s.cd / model.cd_scale) - truth_v);
  };
  for (size_t i = 0; i < t.alpha_rad.size() && t.alpha_rad[i] <= alpha_hi; ++i) {
    for (size_t j = 0; j < t.mach.size(); ++j) {
      const double a = t.alpha_rad[i], m = t.mach[j];
      e.node = std::max(e.node, diff(a, m));
      if (i + 1 >= t.alpha_rad.size() || j + 1 >= t.mach.size()) continue;
      for (double fa : {0.0, 0.07, 0.31, 0.53, 0.77, 0.93})
        for (double fm : {0.0, 0.07, 0.31, 0.53, 0.77, 0.93})
          if (fa > 0.0 || fm > 0.0) e.between = std::max(e.between, diff(a + fa * (t.alpha_rad[i + 1] - a), m + fm * (t.mach[j + 1] - m)));
    }
  }
  return e;
}

// Dispersed runs (C_L and C_D scales away from 1), HORUS trimmed: the fits reproduce the truth
// at the table nodes to round-off, and stay within 2 % of the coefficient's range in between
// (measured: at most 1.35 %, HORUS C_D near Mach 2 where its table's Mach slope jumps).
TEST(SmoothAero, FitsTheTruthTablesAtAndBetweenTheNodes) {
  for (const char* name : {"x33", "horus", "orbiter", "x38"}) {
    const config::Mission m = load(name);
    auto sim = make_run_simulator(m, 4, true, nullptr);
    ASSERT_TRUE(sim) << name;
    const truth::PointModel& model = sim->point_model();
    const SmoothAero fit(model);
    for (bool lift : {true, false}) {
      const FitError e = fit_error(model, fit, lift, 1e4, m.constraints.alpha_max_rad + 0.1);
      EXPECT_LT(e.node, 1e-12 * e.scale) << name << (lift ? " C_L" : " C_D");
      EXPECT_LT(e.between, 0.02 * e.scale) << name << (lift ? " C_L" : " C_D");
    }
  }
}

// Below the fixed-flap dynamic pressure the fits are the fixed-flap truth, above the blend the
// trimmed one, and in the blend in between.
TEST(SmoothAero, FixedFlapBelowTheSwitchTrimmedAbove) {
  const config::Mission m = load("horus");
  auto sim = make_run_simulator(m, 0, false, nullptr);
  const truth::PointModel& model = sim->point_model();
  const SmoothAero fit(model);
  ASSERT_TRUE(fit.blended());
  const double a = 40.0 * M_PI / 180.0, mach = 20.0, q0 = fit.switch_q_Pa();
  const double low = SmoothAero::truth_coefficients(model, a, mach, 0.5 * q0).cl;
  const double high = SmoothAero::truth_coefficients(model, a, mach, 2.0 * q0).cl;
  ASSERT_GT(std::fabs(low - high), 1e-3);  // the flap setting matters
  EXPECT_NEAR(fit(a, mach, 0.5 * q0).cl, low, 1e-12);
  EXPECT_NEAR(fit(a, mach, 2.0 * q0).cl, high, 1e-12);
  const double mid = fit(a, mach, q0).cl;
  EXPECT_GT(mid, std::min(low, high));
  EXPECT_LT(mid, std::max(low, high));
}

// Second derivative of f along one axis at x from the AD scalars.
template <class F>
double second_derivative(const F& f, double x) {
  Ad2<1> a[1];
  seed<1>(&x, a);
  return f(a[0]).derivatives()[0].derivatives()[0];
}

TEST(BicubicSpline, InterpolatesAndIsTwiceContinuouslyDifferentiableAcrossItsCells) {
  const std::vector<double> x = {0.0, 0.7, 1.0, 2.5, 3.0}, y = {1.0, 2.0, 4.0, 8.0};
  std::vector<double> v;
  for (double xi : x)
    for (double yj : y) v.push_back(std::sin(2.0 * xi) * std::log(yj + 1.0) + (xi > 1.5 ? 2.0 * xi : 0.0));
  const BicubicSpline s = BicubicSpline::fit(x, y, v);
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = 0; j < y.size(); ++j) EXPECT_NEAR(s(x[i], y[j]), v[i * y.size() + j], 1e-12);
  const double eps = 1e-7;
  for (size_t i = 1; i + 1 < x.size(); ++i) {  // across the x edges at y = 3
    auto along_x = [&](const auto& t) { using T = std::decay_t<decltype(t)>;
      return s(t, T(3.0)); };
    EXPECT_NEAR(second_derivative(along_x, x[i] - eps), second_derivative(along_x, x[i] + eps), 1e-5) << "x edge " << i;
  }
  for (size_t j = 1; j + 1 < y.size(); ++j) {  // across the y edges at x = 1.7
    auto along_y = [&](const auto& t) { using T = std::decay_t<decltype(t)>;
      return s(T(1.7), t); };
    EXPECT_NEAR(second_derivative(along_y, y[j] - eps), second_derivative(along_y, y[j] + eps), 1e-5) << "y edge " << j;
  }
}

TEST(SmoothPiecewiseLinear, IsTheTableOutsideItsCornersAndC2AtThem) {
  const std::vector<double> x = {0.0, 0.016, 0.05, 0.135, 1.0}, y = {17.0, 17.0, 30.0, 43.9, 43.9};
  const SmoothPiecewiseLinear f(x, y, 1.0);  // windows a quarter interval wide (the deviation allows them)
  EXPECT_DOUBLE_EQ(f(-0.5), 17.0);
  EXPECT_NEAR(f(1.5), 43.9, 1e-12);
  EXPECT_NEAR(f(0.03), 17.0 + 13.0 * (0.03 - 0.016) / 0.034, 1e-12);  // between the corner windows
  EXPECT_NEAR(f(0.5), 43.9, 1e-12);
  // Corners rounded over a quarter of the shorter neighbouring interval on each side.
  const std::pair<double, double> corners[] = {{0.016, 0.004}, {0.05, 0.0085}, {0.135, 0.02125}};
  auto g = [&](const auto& t) { return f(t); };
  for (const auto& [c, w] : corners) {
    EXPECT_LT(std::fabs(f(c) - (c == 0.016 ? 17.0 : c == 0.05 ? 30.0 : 43.9)), 1.0) << c;
    // Curvature continuous at the window's edges (zero outside, the kernel's zero inside) and
    // nonzero in its middle.
    EXPECT_NEAR(second_derivative(g, c - w - 1e-9), second_derivative(g, c - w + 1e-9), 1e-3) << c;
    EXPECT_NEAR(second_derivative(g, c + w - 1e-9), second_derivative(g, c + w + 1e-9), 1e-3) << c;
    EXPECT_GT(std::fabs(second_derivative(g, c)), 1.0) << c;
  }
  // A smaller deviation narrows the windows: at most that far from the table at its corners.
  const SmoothPiecewiseLinear tight(x, y, 0.1);
  EXPECT_NEAR(tight(0.05), 30.0, 0.1 + 1e-12);
  EXPECT_NEAR(tight(0.05 - 0.0085), 30.0 - 13.0 * 0.0085 / 0.034, 1e-12);  // outside its narrower window
}

}  // namespace
}  // namespace reentry::optimal
