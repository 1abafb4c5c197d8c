// The rules a mission must meet to be flown (check_mission): shared by the loader and the
// truth simulator, so that a mission one accepts the other flies.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "reentry/config/environment_files.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::config {
namespace {

constexpr double kRadToDeg = physics::kDegPerRad;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// Integration tolerances below what double arithmetic resolves are silently ineffective: the
// relative one below 100 eps, the absolute ones below 10 eps of an Earth radius (position) and
// of an orbital speed (velocity).
constexpr double kRelTolMin = 100.0 * kEps;
constexpr double kRelTolMax = 1e-2;
constexpr double kAbsTolPositionMin_m = 10.0 * kEps * physics::kEarthEquatorialRadius_m;
constexpr double kAbsTolVelocityMin_mps = 10.0 * kEps * 8000.0;

std::string num(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

std::string key_error(const Mission& m, const std::string& key, const std::string& what) {
  return m.source_file + ": key '" + key + "': " + what;
}

double widest(const Mission& m, Dispersion Dispersions::*field) {
  double v = (m.dispersions.*field).value;
  if (m.has_stress_dispersions) v = std::max(v, (m.stress_dispersions.*field).value);
  return v;
}

std::string check_entry(const Mission& m) {
  const double lat_deg = std::fabs(m.entry.latitude_rad) * kRadToDeg;
  const double pos_deg = widest(m, &Dispersions::entry_position_rad) * kRadToDeg;
  if (!(lat_deg + pos_deg < 90.0)) {
    return key_error(m, "entry.latitude_deg", "value " + num(m.entry.latitude_rad * kRadToDeg) +
                                                  " with the entry-position dispersion " + num(pos_deg) +
                                                  " deg reaches a pole (|latitude| must stay below 90 deg)");
  }
  if (!(m.entry.altitude_m > 0.0)) return key_error(m, "entry.altitude_m", "value " + num(m.entry.altitude_m) + " must be positive");
  const double dv = widest(m, &Dispersions::entry_velocity_mps);
  if (!(m.entry.velocity_mps - dv > 0.0)) {
    return key_error(m, "entry.velocity_mps", "value " + num(m.entry.velocity_mps) + " minus the velocity dispersion " +
                                                  num(dv) + " m/s is not positive");
  }
  return {};
}

std::string check_sim(const Mission& m) {
  const SimParams& s = m.sim;
  if (!(s.rel_tol >= kRelTolMin && s.rel_tol <= kRelTolMax)) {
    return key_error(m, "sim.rel_tol", "value " + num(s.rel_tol) + " out of range [" + num(kRelTolMin) + ", " +
                                           num(kRelTolMax) + "] (below it double arithmetic cannot meet it)");
  }
  if (!(s.abs_tol_position_m >= kAbsTolPositionMin_m)) {
    return key_error(m, "sim.abs_tol_position_m", "value " + num(s.abs_tol_position_m) + " below " +
                                                      num(kAbsTolPositionMin_m) + " m (the resolution of a double at an Earth radius)");
  }
  if (!(s.abs_tol_velocity_mps >= kAbsTolVelocityMin_mps)) {
    return key_error(m, "sim.abs_tol_velocity_mps", "value " + num(s.abs_tol_velocity_mps) + " below " +
                                                        num(kAbsTolVelocityMin_mps) + " m/s (the resolution of a double at orbital speed)");
  }
  if (!(s.time_limit_s > 0.0)) return key_error(m, "sim.time_limit_s", "value " + num(s.time_limit_s) + " must be positive");
  const Vehicle& v = m.vehicle;
  if (!(v.mass_kg > 0.0) || !(v.reference_area_m2 > 0.0) || !(v.nose_radius_m > 0.0)) {
    return key_error(m, "vehicle", "mass_kg " + num(v.mass_kg) + ", reference_area_m2 " + num(v.reference_area_m2) +
                                       " and nose_radius_m " + num(v.nose_radius_m) + " must be positive");
  }
  return {};
}

// Every named data file, whatever model a run selects: a mission names only files it can fly with.
std::string check_environment(const Mission& m) {
  GravityCoefficients g;
  std::string err = read_gravity_coefficients(m.environment.gravity_coefficients, kGravityFileDegree, g);
  if (!err.empty()) return key_error(m, "environment.gravity_coefficients", err);
  AtmosphereTable a;
  err = read_atmosphere_table(m.environment.us76_table, a);
  if (!err.empty()) return key_error(m, "environment.us76_table", err);
  WindProfile w;
  err = read_wind_profile(m.environment.wind_profile, w);
  if (!err.empty()) return key_error(m, "environment.wind_profile", err);
  double w_max = 0.0;
  for (std::size_t i = 0; i < w.h_m.size(); ++i)
    w_max = std::max({w_max, std::fabs(w.north_mps[i]), std::fabs(w.east_mps[i]), std::fabs(w.up_mps[i])});
  double scale = m.dispersions.wind_scale_max;
  if (m.has_stress_dispersions) scale = std::max(scale, m.stress_dispersions.wind_scale_max);
  scale = std::max(1.0, scale);  // nominal runs fly the profile as it is
  if (w_max * scale > kScaledWindMax_mps) {
    return key_error(m, "dispersions.wind_scale_max", "value " + num(scale) + " times the largest wind " + num(w_max) +
                                                          " m/s of " + m.environment.wind_profile + " exceeds " +
                                                          num(kScaledWindMax_mps) + " m/s");
  }
  return {};
}

}  // namespace

std::string check_mission(const Mission& m) {
  for (const auto& check : {&check_entry, &check_sim, &check_environment}) {
    const std::string err = check(m);
    if (!err.empty()) return err;
  }
  return {};
}

}  // namespace reentry::config
