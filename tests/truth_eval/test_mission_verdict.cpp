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

// Destination point at arc d from (lat1, lon1) on the initial bearing b (spherical
// trigonometry, independent of the verdict's triangle formulas).
void destination(double lat1, double lon1, double b, double d, double& lat2, double& lon2) {
  lat2 = std::asin(std::sin(lat1) * std::cos(d) + std::cos(lat1) * std::sin(d) * std::cos(b));
  lon2 = lon1 + std::atan2(std::sin(b) * std::sin(d) * std::cos(lat1), std::cos(d) - std::sin(lat1) * std::sin(lat2));
}

TEST(MissionVerdict, MissSplitsAlongAndAcrossTheArrivalLine) {
  // X-33 aim point and arrival heading; vehicles placed by great-circle steps from it.
  constexpr double kDeg = M_PI / 180.0, R = 6378137.0;
  const double aim_lat = 28.7 * kDeg, aim_lon = -80.5 * kDeg, chi_f = 50.444 * kDeg;
  double lat, lon;
  // 3 km past the aim point along the line: long, on the line.
  destination(aim_lat, aim_lon, chi_f, 3000.0 / R, lat, lon);
  ArrivalLineOffset o = arrival_line_offset(lat, lon, aim_lat, aim_lon, chi_f);
  EXPECT_NEAR(o.along_m, 3000.0, 1e-6);
  EXPECT_NEAR(o.cross_m, 0.0, 1e-6);
  // 5 km short of it, behind on the line.
  destination(aim_lat, aim_lon, chi_f + M_PI, 5000.0 / R, lat, lon);
  o = arrival_line_offset(lat, lon, aim_lat, aim_lon, chi_f);
  EXPECT_NEAR(o.along_m, -5000.0, 1e-6);
  EXPECT_NEAR(o.cross_m, 0.0, 1e-6);
  // 2 km along the line, then 4 km off it at right angles to the line's local heading
  // (the back-azimuth to the aim point, reversed): the foot of that point is 2 km on.
  destination(aim_lat, aim_lon, chi_f, 2000.0 / R, lat, lon);
  const double dl = aim_lon - lon;
  const double back = std::atan2(std::sin(dl) * std::cos(aim_lat),
                                 std::cos(lat) * std::sin(aim_lat) - std::sin(lat) * std::cos(aim_lat) * std::cos(dl));
  double lat_r, lon_r;
  destination(lat, lon, back + M_PI + M_PI / 2.0, 4000.0 / R, lat_r, lon_r);
  o = arrival_line_offset(lat_r, lon_r, aim_lat, aim_lon, chi_f);
  EXPECT_NEAR(o.along_m, 2000.0, 1e-3);
  EXPECT_NEAR(o.cross_m, 4000.0, 1e-3);
  // And mirrored to the left.
  destination(lat, lon, back + M_PI - M_PI / 2.0, 4000.0 / R, lat_r, lon_r);
  o = arrival_line_offset(lat_r, lon_r, aim_lat, aim_lon, chi_f);
  EXPECT_NEAR(o.along_m, 2000.0, 1e-3);
  EXPECT_NEAR(o.cross_m, -4000.0, 1e-3);
}

TEST(MissionVerdict, VerdictCarriesTheMissSplit) {
  // A run ending 6 km due east of an aim point approached heading north: 6 km right, on the
  // line's normal through the aim point (along-track 0 to second order).
  auto m = x33_like();
  m.taem.latitude_rad = 0.0;
  m.taem.longitude_rad = 0.0;
  m.taem.heading_rad = 0.0;
  RunSummary r = nominal_run();
  r.final_state.lat_rad = 0.0;
  r.final_state.lon_rad = 6000.0 / 6378137.0;
  const MissionVerdict v = judge_mission(m, r, {});
  EXPECT_NEAR(v.miss_cross_m, 6000.0, 1e-6);
  EXPECT_NEAR(v.miss_along_m, 0.0, 1e-6);
}

}  // namespace
}  // namespace reentry::truth
