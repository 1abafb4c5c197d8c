// The predictor-corrector's path-constraint drag limit against the truth simulator's own
// constraint models: at the drag the law allows, the density it implies (D = rho V^2 C_D S / 2m)
// gives, through sim_truth's heat-flux model (Chapman (3.5) for the X-33, Betts's leading edge
// for the Orbiter), q = rho V^2 / 2, q alpha and the aerodynamic load hypot(L, D), values within
// the planned fraction of every limit, and one of them on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "guidance/mission_adapter.hpp"
#include "predictor_corrector/pc_guidance.hpp"
#include "reentry/config/mission.hpp"
#include "vehicle/heating.hpp"

namespace reentry::fsw {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Largest ratio of a constrained quantity to its planned limit at the drag the law allows.
double largest_limit_ratio(const config::Mission& m, const OnboardModels& models, const PcLimits& lim, double v_mps,
                           double alpha_rad) {
  const double mach = v_mps / 300.0;
  double cl = 0.0, cd = 0.0;
  models.aero().coefficients(alpha_rad, mach, cl, cd);
  const double d = constraint_drag_limit_mps2(models, lim, v_mps, alpha_rad, cl, cd);
  const double rho = 2.0 * d / (v_mps * v_mps * cd * models.area_over_mass());
  const double q = 0.5 * rho * v_mps * v_mps;
  double ratio = 0.0;
  if (lim.heat_flux_max_Wpm2 > 0.0) {
    const double qdot = truth::heat_flux_Wpm2(m.vehicle.heating_model, rho, v_mps, alpha_rad, m.vehicle.nose_radius_m);
    ratio = std::max(ratio, qdot / lim.heat_flux_max_Wpm2);
  }
  if (lim.q_max_Pa > 0.0) ratio = std::max(ratio, q / lim.q_max_Pa);
  if (lim.q_alpha_max_Pa_rad > 0.0) ratio = std::max(ratio, q * alpha_rad / lim.q_alpha_max_Pa_rad);
  if (lim.load_factor_max_mps2 > 0.0) {
    ratio = std::max(ratio, q * models.area_over_mass() * std::hypot(cl, cd) / lim.load_factor_max_mps2);
  }
  return ratio;
}

void expect_on_the_tightest_limit(const char* name) {
  const auto r = config::load_mission(name);
  ASSERT_TRUE(r.ok) << r.error;
  auto models = std::make_unique<OnboardModels>();
  ASSERT_EQ(init_from_mission(*models, r.mission), Status::kOk);
  const PcLimits lim = pc_limits_from(to_guidance_mission(r.mission).limits, 0.97);
  for (double v : {7200.0, 6000.0, 4500.0, 3000.0, 1500.0}) {
    for (double alpha_deg : {15.0, 30.0, 40.0}) {
      EXPECT_NEAR(largest_limit_ratio(r.mission, *models, lim, v, alpha_deg * kDeg), 1.0, 1e-3)
          << name << " V " << v << " m/s alpha " << alpha_deg << " deg";
    }
  }
}

TEST(PcConstraintDragLimit, X33SitsOnItsTightestLimitByTheTruthModels) { expect_on_the_tightest_limit("x33"); }
TEST(PcConstraintDragLimit, OrbiterSitsOnItsTightestLimitByTheTruthModels) { expect_on_the_tightest_limit("orbiter"); }

// A lower margin lowers the allowed drag in proportion for the q-type limits and by the square
// of the margin for heat flux (q ~ sqrt(rho)).
TEST(PcConstraintDragLimit, HeatFluxLimitScalesWithTheSquareOfTheMargin) {
  const auto r = config::load_mission("x33");
  ASSERT_TRUE(r.ok) << r.error;
  auto models = std::make_unique<OnboardModels>();
  ASSERT_EQ(init_from_mission(*models, r.mission), Status::kOk);
  PathLimits heat_only;
  heat_only.heat_flux_max_Wpm2 = to_guidance_mission(r.mission).limits.heat_flux_max_Wpm2;
  double cl = 0.0, cd = 0.0;
  models->aero().coefficients(40.0 * kDeg, 20.0, cl, cd);
  const double d1 = constraint_drag_limit_mps2(*models, pc_limits_from(heat_only, 1.0), 6000.0, 40.0 * kDeg, cl, cd);
  const double d2 = constraint_drag_limit_mps2(*models, pc_limits_from(heat_only, 0.8), 6000.0, 40.0 * kDeg, cl, cd);
  EXPECT_NEAR(d2 / d1, 0.64, 1e-9);
}

}  // namespace
}  // namespace reentry::fsw
