#include "evaluation/mission_verdict.hpp"

#include <algorithm>
#include <cmath>

#include "environment/earth.hpp"

namespace reentry::truth {

namespace {
void check_max(std::vector<std::string>& v, const char* name, double value, double limit) {
  if (std::isfinite(limit) && value > limit * (1.0 + kConstraintSlack)) v.emplace_back(name);
}
}  // namespace

std::vector<std::string> path_constraint_violations(const config::PathConstraints& c, const RunMaxima& maxima) {
  std::vector<std::string> v;
  check_max(v, "heat_flux", maxima.qdot_Wpm2, c.heat_flux_max_Wpm2);
  check_max(v, "load_factor", maxima.n_g, c.load_factor_max_g);
  check_max(v, "dynamic_pressure", maxima.q_Pa, c.dynamic_pressure_max_Pa);
  check_max(v, "q_alpha", maxima.q_alpha_Pa_rad, c.q_alpha_max_Pa_rad);
  return v;
}

ArrivalLineOffset arrival_line_offset(double lat_rad, double lon_rad, double aim_lat_rad, double aim_lon_rad,
                                      double line_heading_rad) {
  // Right spherical triangle aim point - foot on the line - vehicle: hypotenuse delta (arc from
  // the aim point to the vehicle), angle theta at the aim point between the line and the
  // bearing to the vehicle. sin(xt) = sin(delta) sin(theta), tan(at) = tan(delta) cos(theta).
  const GreatCircleLeg from_aim = great_circle_leg(aim_lat_rad, aim_lon_rad, lat_rad, lon_rad);
  const double theta = from_aim.initial_bearing_rad - line_heading_rad;
  const double sin_delta = std::sin(from_aim.arc_rad), cos_delta = std::cos(from_aim.arc_rad);
  const double R = EarthConstants::kEquatorialRadius_m;
  ArrivalLineOffset o;
  o.cross_m = R * std::asin(std::clamp(sin_delta * std::sin(theta), -1.0, 1.0));
  o.along_m = R * std::atan2(sin_delta * std::cos(theta), cos_delta);
  return o;
}

MissionVerdict judge_mission(const config::Mission& mission, const RunSummary& summary,
                             const CommandRateMaxima& rates) {
  MissionVerdict v;
  const auto& f = summary.final_state;
  const auto& c = mission.constraints;
  const auto& taem = mission.taem;

  // Path constraints (thesis 3.1-3.7) and control constraints (alpha/sigma rates).
  v.violations = path_constraint_violations(c, summary.maxima);
  check_max(v.violations, "heat_load", f.Q_Jpm2, c.heat_load_max_Jpm2);
  check_max(v.violations, "alpha_rate", rates.alpha_rate_radps, c.alpha_rate_max_radps);
  check_max(v.violations, "sigma_rate", rates.sigma_rate_radps, c.sigma_rate_max_radps);

  // TAEM interface conditions (thesis 3.1.2).
  v.reached_taem = summary.event == SimEvent::kTaemEnergy;
  if (!v.reached_taem) v.violations.emplace_back(std::string("event_") + to_string(summary.event));
  v.taem_miss_m = f.range_to_taem_m;
  const ArrivalLineOffset split =
      arrival_line_offset(f.lat_rad, f.lon_rad, taem.latitude_rad, taem.longitude_rad, taem.heading_rad);
  v.miss_along_m = split.along_m;
  v.miss_cross_m = split.cross_m;
  v.altitude_err_m = f.h_m - taem.altitude_m;
  v.mach = f.mach;
  v.heading_err_rad = wrap_pi(f.chi_rad - taem.heading_rad);
  if (v.taem_miss_m > taem.range_tol_m) v.violations.emplace_back("taem_range");
  if (std::fabs(v.altitude_err_m) > taem.altitude_tol_m) v.violations.emplace_back("taem_altitude");
  if (std::fabs(v.heading_err_rad) > taem.heading_tol_rad) v.violations.emplace_back("taem_heading");
  if (taem.mach_target > 0.0) {
    v.mach_err = f.mach - taem.mach_target;
    if (std::fabs(v.mach_err) > taem.mach_tol) v.violations.emplace_back("taem_mach");
  }
  if (std::isfinite(taem.flight_path_tol_rad)) {
    v.flight_path_err_rad = f.gamma_rad - taem.flight_path_rad;
    if (std::fabs(v.flight_path_err_rad) > taem.flight_path_tol_rad) v.violations.emplace_back("taem_flight_path");
  }
  v.success = v.violations.empty();
  return v;
}

}  // namespace reentry::truth
