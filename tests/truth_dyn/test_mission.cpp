#include "test_mission.hpp"

namespace truth_test {

reentry::config::Mission x33_test_mission() {
  reentry::config::Mission m;
  m.name = "x33_test";
  m.vehicle.name = "X-33";
  m.vehicle.mass_kg = 37650.0;        // table 3.3
  m.vehicle.reference_area_m2 = 149.4;
  m.vehicle.nose_radius_m = 0.8;
  auto& aero = m.vehicle.aero;
  aero.source = "synthetic test model: CL = 0.86 alpha, CD = 0.05 + 0.8 alpha";
  aero.reference_length_m = 19.3;
  for (double a = 0.0; a <= 60.0; a += 5.0) aero.cl.alpha_rad.push_back(a * kDeg);
  aero.cl.mach = {0.0, 5.0, 10.0, 20.0, 30.0};
  for (double a : aero.cl.alpha_rad)
    for (std::size_t j = 0; j < aero.cl.mach.size(); ++j) aero.cl.values.push_back(cl_of(a));
  aero.cd.alpha_rad = aero.cl.alpha_rad;
  aero.cd.mach = aero.cl.mach;
  for (double a : aero.cd.alpha_rad)
    for (std::size_t j = 0; j < aero.cd.mach.size(); ++j) aero.cd.values.push_back(cd_of(a));

  m.entry.altitude_m = 120.1e3;
  m.entry.longitude_rad = 225.5 * kDeg;
  m.entry.latitude_rad = -23.75 * kDeg;
  m.entry.velocity_mps = 7627.0;
  m.entry.flight_path_rad = -1.249 * kDeg;
  m.entry.heading_rad = 49.59 * kDeg;
  m.taem.altitude_m = 29.4e3;
  m.taem.velocity_mps = 918.8;
  m.taem.longitude_rad = 279.5 * kDeg;
  m.taem.latitude_rad = 28.7 * kDeg;
  m.constraints.alpha_max_rad = 50.0 * kDeg;
  m.constraints.alpha_rate_max_radps = 5.0 * kDeg;
  m.constraints.sigma_rate_max_radps = 5.0 * kDeg;
  m.alpha_profile.x = {0.0, 1.0};
  m.alpha_profile.y = {40.0 * kDeg, 40.0 * kDeg};

  m.sim.integrator = "rkf56";
  m.sim.rel_tol = 1e-10;
  m.sim.gravity = "central";
  m.sim.atmosphere = "exponential";
  m.sim.wind = false;
  m.sim.shape = "sphere";
  m.sim.trim = false;
  m.sim.attitude = "ideal";
  m.sim.time_limit_s = 4000.0;
  m.environment.us76_table = std::string(REENTRY_CONFIG_DIR) + "/environment/us76.dat";
  m.environment.gravity_coefficients = std::string(REENTRY_CONFIG_DIR) + "/environment/egm96_deg20.txt";
  m.environment.wind_profile = std::string(REENTRY_CONFIG_DIR) + "/environment/earthgram_nominal_wind.txt";
  using reentry::config::Distribution;
  m.dispersions.entry_flight_path_rad = reentry::config::Dispersion{0.2 * kDeg, Distribution::kUniform};
  m.dispersions.entry_heading_rad = reentry::config::Dispersion{0.1 * kDeg, Distribution::kUniform};
  m.dispersions.entry_velocity_mps = reentry::config::Dispersion{10.0, Distribution::kUniform};
  m.dispersions.entry_position_rad = reentry::config::Dispersion{0.05 * kDeg, Distribution::kUniform};
  m.dispersions.density_scale = reentry::config::Dispersion{0.15, Distribution::kUniform};
  m.dispersions.density_perturbation = 0.05;
  m.dispersions.cl_scale = reentry::config::Dispersion{0.1, Distribution::kUniform};
  m.dispersions.cd_scale = reentry::config::Dispersion{0.1, Distribution::kUniform};
  m.dispersions.mass_scale = reentry::config::Dispersion{0.05, Distribution::kUniform};
  m.dispersions.wind_scale_min = 0.5;
  m.dispersions.wind_scale_max = 1.5;
  m.dispersions.wind_scale_distribution = Distribution::kUniform;
  return m;
}

}  // namespace truth_test
