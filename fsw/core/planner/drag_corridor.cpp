#include "planner/drag_corridor.hpp"

#include <cmath>

#include "mission_data.hpp"
#include "numerics/root_finding.hpp"
#include "planner/mission_geometry.hpp"

namespace reentry::fsw {
namespace {

// Altitude bracket of the equilibrium-glide root: from the surface to where the energy would
// leave only this speed ((7.8) solved for r); a bracket lower than kGlideMinBracket_m means
// the energy is too low for any glide above the surface.
constexpr double kGlideBracketSpeed_mps = 50.0;
constexpr double kGlideMinBracket_m = 1000.0;
constexpr double kGlideAltitudeTol_m = 1.0;
// (7.4) divides by alpha: at (near) zero alpha q alpha does not bound the drag.
constexpr double kQAlphaMinAlpha_rad = 1e-6;

Status glide_radius_at(const OnboardModels& models, double energy, double alpha, double& radius_m) {
  const double r_top = radius_for_speed_m(energy, kGlideBracketSpeed_mps);
  const double h_top = clamp(r_top - kEarthRadius_m, 0.0, kPlannerMaxAltitude_m);
  if (!(h_top > kGlideMinBracket_m)) return Status::kExtractionFailed;
  auto residual = [&](double h) {  // (2.50): L - (g - V^2 / r)
    const double r = kEarthRadius_m + h;
    const double v = velocity_from_energy_mps(energy, r);
    return models.lift_mps2(alpha, h, v) - (gravity_mps2(r) - v * v / r);
  };
  const numerics::RootResult root = numerics::brent(residual, 0.0, h_top, kGlideAltitudeTol_m, kPlannerRootIterations);
  const Status st = to_status(root.status);
  if (st == Status::kOk || st == Status::kMaxIterations) {
    radius_m = kEarthRadius_m + root.x;
  } else if (st == Status::kNoBracket && residual(h_top) > 0.0) {
    radius_m = kEarthRadius_m + h_top;  // lift exceeds the need everywhere: highest admissible point
  } else {
    return st == Status::kNoBracket ? Status::kExtractionFailed : st;
  }
  return Status::kOk;
}

}  // namespace

double heat_flux_drag_mps2(double heat_flux_max_Wpm2, double cd, double area_over_mass_m2pkg, double heat_coefficient,
                           double velocity_mps, double velocity_exponent) {
  const double q = heat_flux_max_Wpm2, c = heat_coefficient;
  return (q * q * cd * area_over_mass_m2pkg) / (2.0 * c * c * std::pow(velocity_mps, 2.0 * (velocity_exponent - 1.0)));  // (7.3)
}

double q_alpha_drag_mps2(double q_alpha_max_Pa_rad, double cd, double area_over_mass_m2pkg, double alpha_rad) {
  return alpha_rad > kQAlphaMinAlpha_rad ? q_alpha_max_Pa_rad * cd * area_over_mass_m2pkg / alpha_rad : kUnconstrained;  // (7.4)
}

double load_factor_drag_mps2(double load_max_mps2, double cl, double cd, double alpha_rad) {
  return load_max_mps2 / (cl / cd * std::cos(alpha_rad) + std::sin(alpha_rad));  // (7.5)
}

double dynamic_pressure_drag_mps2(double dynamic_pressure_max_Pa, double cd, double area_over_mass_m2pkg) {
  return dynamic_pressure_max_Pa * cd * area_over_mass_m2pkg;  // (7.6)
}

double lift_need_drag_mps2(double lift_need_mps2, double cl, double cd) { return lift_need_mps2 * cd / cl; }  // (7.7)

double active_drag_limit_mps2(const ConstraintDrags& c) {
  double d = c.heat_flux_mps2;
  if (c.q_alpha_mps2 < d) d = c.q_alpha_mps2;
  if (c.load_mps2 > 0.0 && c.load_mps2 < d) d = c.load_mps2;
  if (c.dynamic_pressure_mps2 < d) d = c.dynamic_pressure_mps2;
  return d;
}

Status equilibrium_glide_radius(const OnboardModels& models, const EnergyGrid& grid, GridValues& radius_m) {
  for (int k = 0; k < kPlannerGrid; ++k) {
    const Status s = glide_radius_at(models, grid.energy_Jpkg[k], grid.alpha_rad[k], radius_m[k]);
    if (s != Status::kOk) return s;
  }
  return Status::kOk;
}

void corridor_bounds(const CorridorStageInput& in, const GridValues& radius_m, DragCorridor& out) {
  const OnboardModels& models = in.models;
  const CorridorLimits& lim = in.mission.limits;
  const double s_over_m = models.area_over_mass();
  const double c2 = models.heat_flux_velocity_exponent();
  const double e0 = in.planning_energy_Jpkg;
  const double span = e0 - in.mission.taem_energy_Jpkg;
  for (int k = 0; k < kPlannerGrid; ++k) {
    const double r = radius_m[k];
    const double h = r - kEarthRadius_m;
    const double v = velocity_from_energy_mps(in.grid.energy_Jpkg[k], r);
    const double g = gravity_mps2(r);
    const double alpha = in.grid.alpha_rad[k];
    double cl, cd;
    models.aero().coefficients(alpha, models.mach(h, v), cl, cd);
    ConstraintDrags c;
    c.heat_flux_mps2 = heat_flux_drag_mps2(lim.heat_flux_Wpm2, cd, s_over_m, models.heat_flux_coefficient(alpha), v, c2);
    c.q_alpha_mps2 = q_alpha_drag_mps2(lim.q_alpha_Pa_rad, cd, s_over_m, alpha);
    c.load_mps2 = load_factor_drag_mps2(lim.load_mps2, cl, cd, alpha);
    c.dynamic_pressure_mps2 = dynamic_pressure_drag_mps2(lim.dynamic_pressure_Pa, cd, s_over_m);
    out.heat_flux_mps2[k] = c.heat_flux_mps2;
    out.q_alpha_mps2[k] = c.q_alpha_mps2;
    out.max_mps2[k] = active_drag_limit_mps2(c);
    out.min_mps2[k] = lift_need_drag_mps2(g - v * v / r, cl, cd);
    // Feasibility floor: (7.7) with the Earth-rate term of (2.33) (level_flight_lift_need_mps2),
    // lat and chi on the planning-point -> TAEM great circle at the energy fraction (the range
    // fraction is not known before the fit). (7.7) itself stays the thesis's Lmin for the
    // initial drag and the E2 breakpoint; the closure test needs the floor the vehicle really
    // has: for the eastbound Orbiter at 40 deg alpha the rotation-free Lmin lies above the
    // heat-flux limit between 7.2 and 5.5 km/s, the true floor below it.
    const double f = span > 0.0 ? (e0 - in.grid.energy_Jpkg[k]) / span : 0.0;
    const TrackPoint p = great_circle_point(in.track.lat1_rad, in.track.lon1_rad, in.track.lat2_rad, in.track.lon2_rad, f);
    out.floor_mps2[k] = lift_need_drag_mps2(level_flight_lift_need_mps2(r, v, p.lat_rad, p.azimuth_rad), cl, cd);
  }
}

Status corridor_closure(const DragCorridor& c, double max_closed_fraction, int& closed_points) {
  int closed = 0;
  for (int k = 0; k < kPlannerGrid; ++k) {
    if (!std::isfinite(c.floor_mps2[k]) || !(c.max_mps2[k] > 0.0)) return Status::kCorridorClosed;
    if (c.max_mps2[k] <= c.floor_mps2[k]) ++closed;
  }
  closed_points = closed;
  return closed > max_closed_fraction * kPlannerGrid ? Status::kCorridorClosed : Status::kOk;
}

Breakpoints profile_breakpoints(const EnergyGrid& grid, const DragCorridor& c, double planning_energy_Jpkg,
                                double taem_energy_Jpkg, const PlannerParams& params) {
  const GridValues& e = grid.energy_Jpkg;
  const double e0 = planning_energy_Jpkg;
  const double span = e0 - taem_energy_Jpkg;
  const double gap = params.segment_min_span_fraction * span;
  Breakpoints b;
  // E1: first sign change of D_heat - D_qalpha from the planning energy down, linear in the cell.
  double e1 = e0 - params.e1_default_span_fraction * span;
  bool found = false;
  for (int k = 0; k + 1 < kPlannerGrid && !found; ++k) {
    const double f0 = c.heat_flux_mps2[k] - c.q_alpha_mps2[k];
    const double f1 = c.heat_flux_mps2[k + 1] - c.q_alpha_mps2[k + 1];
    if (std::isfinite(f0) && std::isfinite(f1) && f0 < 0.0 && f1 >= 0.0) {
      e1 = e[k] + (e[k + 1] - e[k]) * (f0 / (f0 - f1));
      found = true;
    }
  }
  b.e1_Jpkg = clamp(e1, taem_energy_Jpkg + params.e1_min_span_fraction * span, e0 - gap);
  // E2: energy of the (highest) maximum of Lmin below E1.
  double best = -1.0;
  double e2 = taem_energy_Jpkg + params.e2_default_span_fraction * span;
  for (int k = 0; k < kPlannerGrid; ++k) {
    if (e[k] < b.e1_Jpkg && c.min_mps2[k] > best) {
      best = c.min_mps2[k];
      e2 = e[k];
    }
  }
  b.e2_Jpkg = clamp(e2, taem_energy_Jpkg + gap, b.e1_Jpkg - gap);
  return b;
}

Status drag_energy_corridor(const CorridorStageInput& in, GridValues& radius_m, CorridorStage& out) {
  Status s = equilibrium_glide_radius(in.models, in.grid, radius_m);
  if (s != Status::kOk) return s;
  corridor_bounds(in, radius_m, out.corridor);
  s = corridor_closure(out.corridor, in.params.max_closed_fraction, out.closed_points);
  if (s != Status::kOk) return s;
  out.breakpoints = profile_breakpoints(in.grid, out.corridor, in.planning_energy_Jpkg, in.mission.taem_energy_Jpkg, in.params);
  // Di (§7.6): the sensed drag or Lmin at the planning energy, at least the drag floor; Df from
  // the TAEM conditions at the TAEM alpha.
  out.d_initial_mps2 = in.params.initial_drag == InitialDrag::kActual ? in.d_actual_mps2 : out.corridor.min_mps2[0];
  if (out.d_initial_mps2 < in.params.drag_floor_mps2) out.d_initial_mps2 = in.params.drag_floor_mps2;
  const PlannerMission& m = in.mission;
  out.d_final_mps2 = in.models.drag_mps2(in.grid.alpha_rad[kPlannerGrid - 1], m.taem_drag_altitude_m,
                                         OnboardModels::taem_speed_mps(m.taem_lat_rad, m.taem_energy_Jpkg, m.taem_drag_altitude_m));
  return Status::kOk;
}

}  // namespace reentry::fsw
