// The referee's verdict: each tolerance and constraint is checked on hand-built runs whose
// answer is known, including limits met exactly (not a violation) and just exceeded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "evaluation/mission_verdict.hpp"

namespace reentry::truth {
namespace {

config::Mission x33_like() {
  config::Mission m;
  m.name = "verdict_test";
  m.taem.altitude_m = 29400.0;
  m.taem.heading_rad = 50.0 * M_PI / 180.0;
  m.taem.range_tol_m = 11000.0;
  m.taem.altitude_tol_m = 1800.0;
  m.taem.heading_tol_rad = 10.0 * M_PI / 180.0;
  m.constraints.heat_flux_max_Wpm2 = 851739.5;
  m.constraints.load_factor_max_g = 3.0;
  m.constraints.dynamic_pressure_max_Pa = 14364.0;
  m.constraints.alpha_rate_max_radps = 5.0 * M_PI / 180.0;
  m.constraints.sigma_rate_max_radps = 5.0 * M_PI / 180.0;
  return m;
}

RunSummary nominal_run() {
  RunSummary r;
  r.event = SimEvent::kTaemEnergy;
  r.final_state.range_to_taem_m = 3000.0;
  r.final_state.h_m = 29000.0;
  r.final_state.chi_rad = 55.0 * M_PI / 180.0;
  r.final_state.mach = 3.1;
  r.maxima.qdot_Wpm2 = 400000.0;
  r.maxima.n_g = 2.0;
  r.maxima.q_Pa = 10000.0;
  return r;
}

bool has(const MissionVerdict& v, const char* name) {
  return std::find(v.violations.begin(), v.violations.end(), name) != v.violations.end();
}

TEST(MissionVerdict, NominalRunSucceedsWithHandComputedErrors) {
  const MissionVerdict v = judge_mission(x33_like(), nominal_run(), {});
  EXPECT_TRUE(v.success);
  EXPECT_TRUE(v.violations.empty());
  EXPECT_DOUBLE_EQ(v.taem_miss_m, 3000.0);
  EXPECT_DOUBLE_EQ(v.altitude_err_m, -400.0);
  EXPECT_NEAR(v.heading_err_rad, 5.0 * M_PI / 180.0, 1e-15);
}

TEST(MissionVerdict, EachToleranceIsChecked) {
  const auto m = x33_like();
  RunSummary r = nominal_run();
  r.final_state.range_to_taem_m = 11000.1;
  EXPECT_TRUE(has(judge_mission(m, r, {}), "taem_range"));
  r = nominal_run();
  r.final_state.h_m = 29400.0 + 1800.1;
  EXPECT_TRUE(has(judge_mission(m, r, {}), "taem_altitude"));
  r = nominal_run();
  r.final_state.chi_rad = m.taem.heading_rad - 10.1 * M_PI / 180.0;
  EXPECT_TRUE(has(judge_mission(m, r, {}), "taem_heading"));
  r = nominal_run();
  r.event = SimEvent::kGroundImpact;
  const MissionVerdict v = judge_mission(m, r, {});
  EXPECT_FALSE(v.success);
  EXPECT_FALSE(v.reached_taem);
  EXPECT_TRUE(has(v, "event_ground_impact"));
}

TEST(MissionVerdict, HeadingErrorWrapsAcrossNorth) {
  auto m = x33_like();
  m.taem.heading_rad = 355.0 * M_PI / 180.0;
  RunSummary r = nominal_run();
  r.final_state.chi_rad = 3.0 * M_PI / 180.0;  // 8 deg right of 355 deg
  const MissionVerdict v = judge_mission(m, r, {});
  EXPECT_NEAR(v.heading_err_rad, 8.0 * M_PI / 180.0, 1e-12);
  EXPECT_TRUE(v.success);
}

TEST(MissionVerdict, PathAndControlConstraintsAtAndAboveTheLimit) {
  const auto m = x33_like();
  RunSummary r = nominal_run();
  r.maxima.qdot_Wpm2 = m.constraints.heat_flux_max_Wpm2;  // exactly at the limit: allowed
  r.maxima.n_g = 3.0;
  EXPECT_TRUE(judge_mission(m, r, {}).success);
  r.maxima.qdot_Wpm2 *= 1.001;
  r.maxima.n_g = 3.01;
  r.maxima.q_Pa = 14400.0;
  CommandRateMaxima rates;
  rates.sigma_rate_radps = 5.5 * M_PI / 180.0;
  rates.alpha_rate_radps = 4.0 * M_PI / 180.0;
  const MissionVerdict v = judge_mission(m, r, rates);
  EXPECT_TRUE(has(v, "heat_flux"));
  EXPECT_TRUE(has(v, "load_factor"));
  EXPECT_TRUE(has(v, "dynamic_pressure"));
  EXPECT_TRUE(has(v, "sigma_rate"));
  EXPECT_FALSE(has(v, "alpha_rate"));
  EXPECT_FALSE(has(v, "q_alpha"));  // not constrained for this mission
}

TEST(MissionVerdict, MachAndFlightPathOnlyWhenTheMissionSpecifiesThem) {
  auto m = x33_like();
  RunSummary r = nominal_run();
  r.final_state.mach = 9.0;
  r.final_state.gamma_rad = -0.5;
  EXPECT_TRUE(judge_mission(m, r, {}).success);  // X-33 style: no Mach / gamma tolerance
  m.taem.mach_target = 2.5;                      // HORUS style: 2.5 +- 0.3, gamma -7 +- 5 deg
  m.taem.mach_tol = 0.3;
  m.taem.flight_path_rad = -7.0 * M_PI / 180.0;
  m.taem.flight_path_tol_rad = 5.0 * M_PI / 180.0;
  r.final_state.mach = 2.75;
  r.final_state.gamma_rad = -11.0 * M_PI / 180.0;
  EXPECT_TRUE(judge_mission(m, r, {}).success);
  r.final_state.mach = 2.85;
  r.final_state.gamma_rad = -12.5 * M_PI / 180.0;
  const MissionVerdict v = judge_mission(m, r, {});
  EXPECT_TRUE(has(v, "taem_mach"));
  EXPECT_TRUE(has(v, "taem_flight_path"));
  EXPECT_NEAR(v.mach_err, 0.35, 1e-12);
}

}  // namespace
}  // namespace reentry::truth
