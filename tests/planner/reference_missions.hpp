// Thesis-geometry missions for the planner tests: HORUS and X-33 built from the DESIGN §7
// reading of thesis tables 3.1/3.3 with the public Orbiter aero tables (config/aero/STS_*.dat)
// as the documented stand-in aero model. The tests fly them beside the mission files
// (config/missions): the same geometry with a second aero model and the three-segment profile.
#pragma once

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <reentry/config/mission.hpp>

namespace reentry::planner_test {

inline constexpr double kDeg = M_PI / 180.0;

inline bool read_sts_table(const std::string& path, config::Table2D& t) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<double> row;
    double v;
    while (ls >> v) row.push_back(v);
    if (!row.empty()) rows.push_back(row);
  }
  if (rows.size() < 4) return false;
  t.alpha_rad = rows[1];
  t.mach = rows[2];
  t.values.clear();
  for (size_t i = 3; i < rows.size(); ++i) t.values.insert(t.values.end(), rows[i].begin(), rows[i].end());
  return t.values.size() == t.alpha_rad.size() * t.mach.size();
}

inline void common_fill(config::Mission& m) {
  const std::string dir = REENTRY_CONFIG_DIR_STR;
  read_sts_table(dir + "/aero/STS_CL.dat", m.vehicle.aero.cl);
  read_sts_table(dir + "/aero/STS_CD.dat", m.vehicle.aero.cd);
  m.alpha_profile.x = {0.0, 0.3, 0.6, 1.0};
  m.alpha_profile.y = {15.0 * kDeg, 20.0 * kDeg, 35.0 * kDeg, 40.0 * kDeg};
  m.guidance.drag_profile = "three_segment";
  m.guidance.onboard_atmosphere = "exponential";
  m.environment.us76_table = dir + "/environment/us76.dat";
}

/// HORUS (thesis table 3.1, DESIGN §7 reading).
inline config::Mission horus_fallback() {
  config::Mission m;
  m.name = "horus";
  m.vehicle.name = "HORUS";
  m.vehicle.mass_kg = 26029.0;
  m.vehicle.reference_area_m2 = 110.0;
  m.vehicle.nose_radius_m = 0.8;
  m.entry.altitude_m = 119960.0;
  m.entry.longitude_rad = -105.97 * kDeg;
  m.entry.latitude_rad = -22.06 * kDeg;
  m.entry.velocity_mps = 7438.1;
  m.entry.flight_path_rad = -1.4263 * kDeg;
  m.entry.heading_rad = 70.437 * kDeg;
  m.taem.altitude_m = 24859.7;
  m.taem.velocity_mps = 660.05;
  m.taem.longitude_rad = -53.736 * kDeg;
  m.taem.latitude_rad = 4.9537 * kDeg;
  m.constraints.heat_flux_max_Wpm2 = 530e3;
  m.constraints.load_factor_max_g = 2.5;
  m.constraints.q_alpha_max_Pa_rad = 191397.0 * kDeg;  // 191397 N deg / m^2
  m.constraints.alpha_max_rad = 43.9 * kDeg;
  m.constraints.sigma_rate_max_radps = 10.0 * kDeg;
  common_fill(m);
  return m;
}

/// X-33 (thesis table 3.3, DESIGN §7 reading; TAEM at Kennedy).
inline config::Mission x33_fallback() {
  config::Mission m;
  m.name = "x33";
  m.vehicle.name = "X-33";
  m.vehicle.mass_kg = 37650.0;
  m.vehicle.reference_area_m2 = 149.4;
  m.vehicle.nose_radius_m = 0.8;
  m.entry.altitude_m = 120100.0;
  m.entry.longitude_rad = 225.5 * kDeg;
  m.entry.latitude_rad = -23.75 * kDeg;
  m.entry.velocity_mps = 7627.0;
  m.entry.flight_path_rad = -1.249 * kDeg;
  m.entry.heading_rad = 49.59 * kDeg;
  m.taem.altitude_m = 29400.0;
  m.taem.velocity_mps = 918.8;
  m.taem.longitude_rad = 279.5 * kDeg;
  m.taem.latitude_rad = 28.7 * kDeg;
  m.constraints.heat_flux_max_Wpm2 = 75.0 * 11356.526682;  // 75 BTU/(ft^2 s)
  m.constraints.load_factor_max_g = 3.0;
  m.constraints.sigma_rate_max_radps = 10.0 * kDeg;
  common_fill(m);
  return m;
}

}  // namespace reentry::planner_test
