// The optimizer's smooth models against the truth's tables they fit: equal at the nodes, within
// a bound between them (cell centres, where a bilinear table and a C2 fit differ most), and C2
// across the cell edges (second derivatives from the AD scalars on both sides of an edge).
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
  double node = 0.0, between = 0.0, scale = 0.0, at_alpha = 0.0, at_mach = 0.0;
};

// Largest |fit - truth| of C_L (lift) or C_D at the table nodes and at the cell centres (and
// the edge midpoints), at dynamic pressure q, over alpha in [alpha_lo, alpha_hi].
FitError fit_error(const truth::PointModel& model, const SmoothAero& fit, bool lift, double q, double alpha_lo,
                   double alpha_hi) {
  const config::Table2D& t = lift ? model.aero->model().cl : model.aero->model().cd;
  FitError e;
  auto diff = [&](double a, double m) {
    const truth::AeroCoefficients c = SmoothAero::truth_coefficients(model, a, m, q);
    const truth::AeroCoefficients s = fit(a, m, q);
    const double truth_v = lift ? c.cl : c.cd;
    e.scale = std::max(e.scale, std::fabs(truth_v));
    const double d = std::fabs((lift ? s.cl / model.cl_scale : s.cd / model.cd_scale) - truth_v);
    if (d > e.between) {
      e.at_alpha = a * 180.0 / M_PI;
      e.at_mach = m;
    }
    return d;
  };
  for (size_t i = 0; i < t.alpha_rad.size(); ++i) {
    for (size_t j = 0; j < t.mach.size(); ++j) {
      const double a = t.alpha_rad[i], m = t.mach[j];
      if (a < alpha_lo || a > alpha_hi) continue;
      e.node = std::max(e.node, diff(a, m));
      if (i + 1 < t.alpha_rad.size() && j + 1 < t.mach.size()) {
        for (double fa : {0.0, 0.07, 0.31, 0.5, 0.53, 0.77, 0.93})
          for (double fm : {0.0, 0.07, 0.31, 0.5, 0.53, 0.77, 0.93}) {
            if (fa == 0.0 && fm == 0.0) continue;
            const double d = diff(a + fa * (t.alpha_rad[i + 1] - a), m + fm * (t.mach[j + 1] - m));
            e.between = std::max(e.between, d);
          }
      }
    }
  }
  return e;
}

TEST(SmoothAero, FitsTheTruthTablesAtAndBetweenTheNodes) {
  for (const char* name : {"x33", "horus", "orbiter", "x38"}) {
    const config::Mission m = load(name);
    auto sim = make_run_simulator(m, 0, false, nullptr);
    ASSERT_TRUE(sim) << name;
    const truth::PointModel& model = sim->point_model();
    const SmoothAero fit(model);
    const double a_lo = 0.0, a_hi = m.constraints.alpha_max_rad + 0.1;
    for (bool lift : {true, false}) {
      const FitError e = fit_error(model, fit, lift, 1e4, a_lo, a_hi);
      std::printf("%s %s: node %.2e between %.2e (scale %.3f, %.2f %%) at %.1f deg Mach %.2f\n", name, lift ? "CL" : "CD",
                  e.node, e.between, e.scale, 100.0 * e.between / e.scale, e.at_alpha, e.at_mach);
      EXPECT_LT(e.node, 1e-12 * e.scale) << name;
    }
  }
}

}  // namespace
}  // namespace reentry::optimal
