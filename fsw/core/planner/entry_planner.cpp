#include "planner/entry_planner.hpp"

#include <cmath>

#include "planner/drag_derivatives.hpp"
#include "planner/mission_geometry.hpp"

namespace reentry::fsw {
namespace {

// A planning energy must exceed the TAEM energy by this factor (a shorter span is no plan).
constexpr double kMinPlanningEnergyRatio = 1.001;
// Largest trajectory-length iterations accepted by init (bounds the plan's time).
constexpr int kMaxLengthIterations = 1000;
// Least RK4 step count accepted by init.
constexpr int kMinRkSteps = 10;

bool finite_state(const RelativeState& s) {
  return std::isfinite(s.radius_m) && std::isfinite(s.latitude_rad) && std::isfinite(s.longitude_rad) &&
         std::isfinite(s.velocity_mps) && std::isfinite(s.heading_rad) && std::isfinite(s.energy_Jpkg) &&
         std::isfinite(s.drag_mps2);
}

// Final drag of the profile: the vehicle meets the TAEM energy where the drag equals it, so
// that drag sets the TAEM altitude (and, the energy being fixed, the speed and Mach). Rule:
// of the altitudes in the TAEM altitude band, take the one whose state at the TAEM energy
// lies deepest inside both bands, min over {altitude, Mach} of the normalised distance to
// the band edge, among the altitudes where q and q*alpha at the TAEM alpha are within their
// limits (the mission altitude itself when no Mach band is given).
double taem_drag_altitude_m(const OnboardModels& models, const AlphaProfile& alpha_profile, const TaemTarget& t,
                            const PlannerMission& m, int samples) {
  if (!has_mach_band(t) || !(t.altitude_tol_m > 0.0)) return t.altitude_m;
  double best_h = t.altitude_m, best_depth = -1e300;
  const double alpha_taem = alpha_profile.alpha_rad(m.taem_energy_Jpkg / m.entry_energy_Jpkg);
  for (int i = 0; i <= samples; ++i) {
    const double h = t.altitude_m + t.altitude_tol_m * (2.0 * i / samples - 1.0);
    const double v = OnboardModels::taem_speed_mps(t.latitude_rad, m.taem_energy_Jpkg, h);
    if (!(v > 0.0)) continue;
    // The TAEM state must itself satisfy the dynamic-pressure constraints at the TAEM alpha.
    const double q = 0.5 * models.atmosphere().density_kgpm3(h) * v * v;
    if (q * alpha_taem > m.limits.q_alpha_Pa_rad || q > m.limits.dynamic_pressure_Pa) continue;
    const double depth = models.taem_band_depth(t, m.taem_energy_Jpkg, h);
    if (depth > best_depth) {
      best_depth = depth;
      best_h = h;
    }
  }
  return best_h;
}

bool params_valid(const PlannerParams& p) {
  return p.rk4_steps >= kMinRkSteps && p.rk4_steps <= PlannerParams::kMaxRkSteps && p.max_length_iterations >= 1 &&
         p.max_length_iterations <= kMaxLengthIterations && p.downrange_tol_m > 0.0 && p.crossrange_tol_m > 0.0 &&
         planner_params_inconsistency(p) == nullptr;
}

RelativeState entry_interface_state(const EntryInterface& e, const OnboardModels& models, const AlphaProfile& alpha) {
  RelativeState s{};
  s.radius_m = kEarthRadius_m + e.altitude_m;
  s.altitude_m = e.altitude_m;
  s.longitude_rad = e.longitude_rad;
  s.latitude_rad = e.latitude_rad;
  s.velocity_mps = e.velocity_mps;
  s.flight_path_rad = e.flight_path_rad;
  s.heading_rad = e.heading_rad;
  s.energy_Jpkg = specific_energy_Jpkg(s.radius_m, e.velocity_mps);  // (7.8)
  const double alpha_entry = alpha.alpha_rad(1.0);
  s.drag_mps2 = models.drag_mps2(alpha_entry, e.altitude_m, e.velocity_mps);
  s.lift_mps2 = models.lift_mps2(alpha_entry, e.altitude_m, e.velocity_mps);
  return s;
}

}  // namespace

Status EntryPlanner::init(const OnboardModels& models, const AlphaProfile& alpha_profile,
                          const GuidanceMission& mission, const GuidanceLawParams& params) {
  initialised_ = false;
  models_ = models;
  alpha_profile_ = alpha_profile;
  params_ = params.planner;
  if (!params_valid(params_)) return Status::kInvalidInput;
  PlannerMission& m = mission_;
  m.terminal_span_fraction = params.terminal_span_fraction;
  // The corridor is planned with a design margin on every path constraint: the tracker's
  // transients at drag capture and the on-board/true aerodynamics differences (trim) must fit.
  const PathLimits& c = mission.limits;
  const double margin = params.constraint_margin;
  m.limits.heat_flux_Wpm2 = margin * c.heat_flux_max_Wpm2;
  m.limits.q_alpha_Pa_rad = margin * c.q_alpha_max_Pa_rad;
  m.alpha_max_rad = c.alpha_max_rad;
  m.limits.load_mps2 = margin * c.load_factor_max_g * kG0_mps2;
  m.limits.dynamic_pressure_Pa = margin * c.dynamic_pressure_max_Pa;
  m.sigma_rate_max_radps = c.sigma_rate_max_radps;
  if (!(m.sigma_rate_max_radps > 0.0)) return Status::kInvalidInput;

  m.entry = entry_interface_state(mission.entry, models_, alpha_profile_);
  m.entry_energy_Jpkg = m.entry.energy_Jpkg;
  const TaemTarget& t = mission.taem;
  m.taem_radius_m = surface_radius_m(t.latitude_rad) + t.altitude_m;
  m.taem_lat_rad = t.latitude_rad;
  m.taem_lon_rad = t.longitude_rad;
  m.taem_energy_Jpkg = specific_energy_Jpkg(m.taem_radius_m, t.velocity_mps);
  m.taem_drag_altitude_m = taem_drag_altitude_m(models_, alpha_profile_, t, m, params_.taem_box_samples);
  m.corridor_energy_Jpkg = m.taem_energy_Jpkg + params.lateral_corridor_span_fraction * (m.entry_energy_Jpkg - m.taem_energy_Jpkg);
  if (!(m.entry_energy_Jpkg > m.taem_energy_Jpkg) || !(m.taem_energy_Jpkg > 0.0) || !std::isfinite(m.entry.drag_mps2)) {
    return Status::kInvalidInput;
  }
  ranging_blend_min_ = 0.0;
  flown_ = FlownSide{};
  initialised_ = true;
  return Status::kOk;
}

Status EntryPlanner::planning_setup(const RelativeState& from, PlanSetup& setup, int& first_sign,
                                    PlannerDiagnostics& diag) {
  setup.from = from;
  RelativeState& f = setup.from;
  if (!(f.energy_Jpkg > 0.0)) f.energy_Jpkg = specific_energy_Jpkg(f.radius_m, f.velocity_mps);
  if (!finite_state(f)) return Status::kNonFinite;
  // In-flight L/D estimate (1 before the drag is measurable): the corridor floor (7.7), the
  // equilibrium-glide radius and the bank extraction then use the vehicle's sensed L/D.
  const double lod_scale = f.lift_over_drag_scale;
  if (!(lod_scale >= params_.lift_scale_min && lod_scale <= params_.lift_scale_max)) return Status::kInvalidInput;
  models_.aero().set_lift_scale(lod_scale);
  if (!(f.energy_Jpkg > mission_.taem_energy_Jpkg * kMinPlanningEnergyRatio) || !(f.radius_m > kEarthRadius_m)) {
    return Status::kInvalidInput;
  }
  // Mission geometry (7.1), (7.2) from the planning position to the TAEM point.
  const GreatCircle gc = great_circle(f.latitude_rad, f.longitude_rad, mission_.taem_lat_rad, mission_.taem_lon_rad);
  setup.azimuth_mission_rad = gc.azimuth_rad;
  setup.b_mission_rad = gc.arc_rad;
  diag.b_mission_rad = gc.arc_rad;
  diag.a_mission_rad = gc.azimuth_rad;
  diag.chi_minus_a_rad = wrap_pi(f.heading_rad - gc.azimuth_rad);
  // First bank side: the quadrant rule (fig. 7.20) at the first plan. A replan keeps the side
  // the last plan flies at the planning energy (reversal search tries the other side only
  // when no single reversal nulls the crossrange with it): the heading offset crosses zero
  // while the first bank turns the vehicle towards the target, and re-applying the rule there
  // reverses the bank for nothing (with a slow roll at high speed, a roll through wings level
  // of a minute or more and a phugoid).
  first_sign = initial_bank_sign(f.heading_rad, gc.azimuth_rad);
  if (flown_.known && f.energy_Jpkg > mission_.corridor_energy_Jpkg) {
    first_sign = f.energy_Jpkg > flown_.reversal_energy_Jpkg ? flown_.first_sign : -flown_.first_sign;
  }
  diag.initial_bank_sign = first_sign;
  setup.r_mean_m = 0.5 * (f.radius_m + mission_.taem_radius_m);
  setup.range_desired_m = gc.arc_rad * setup.r_mean_m;  // R_d, the first length S0 (7.22)
  diag.s_initial_m = setup.range_desired_m;
  setup.d_actual_mps2 =
      f.drag_mps2 > 0.0
          ? f.drag_mps2
          : models_.drag_mps2(alpha_profile_.alpha_rad(f.energy_Jpkg / mission_.entry_energy_Jpkg), f.radius_m - kEarthRadius_m,
                              f.velocity_mps);
  setup.ranging_blend_min = ranging_blend_min_;
  return Status::kOk;
}

Status EntryPlanner::plan(const RelativeState& from, ReferenceProfile& out) {
  diag_ = PlannerDiagnostics{};
  ws_.reset_reports();
  out.status = Status::kInvalidInput;
  out.converged = false;
  if (!initialised_) {
    out.n_points = 0;
    return Status::kInvalidInput;
  }
  auto fail = [&](Status s) {  // no partial profile is handed out on failure
    diag_.status = s;
    out.status = s;
    out.converged = false;
    out.n_points = 0;
    return s;
  };
  PlanSetup setup;
  ReversalState rev;
  Status s = planning_setup(from, setup, rev.first_sign, diag_);
  if (s != Status::kOk) return fail(s);
  const PlanContext ctx{models_, params_, mission_, setup};
  const bool graded = params_.initial_drag == InitialDrag::kActual && setup.d_actual_mps2 < params_.graded_grid_drag_mps2;
  build_energy_grid({setup.from.energy_Jpkg, mission_.taem_energy_Jpkg, mission_.entry_energy_Jpkg, graded}, alpha_profile_,
                    ws_.grid);
  s = corridor_stage(ctx, ws_, diag_);
  if (s != Status::kOk) return fail(s);
  double s_m = setup.range_desired_m;  // S0
  bool converged = false;
  s = length_iteration(ctx, ws_, s_m, converged, rev, diag_);
  const Status first = s;
  const bool lateral = lateral_short(ctx, rev, diag_);
  if ((s == Status::kOk || lateral) && (setup.ranging_blend_min > 0.0 || lateral || below_glide_floor(ctx, ws_))) {
    s = ranging_alpha(ctx, first, ws_, s_m, converged, rev, diag_);
  }
  const bool too_long = s == Status::kRangeTooLong;
  if (s != Status::kOk && !too_long) return fail(s);
  RopFlight flight;
  s = fly_reduced_order(reduced_order_input(ctx, ws_), planning_start(setup), rev.first_sign, rev.s_rev_m, ws_.base,
                        &ws_.track, flight);
  if (s != Status::kOk) return fail(s);
  diag_.reversal_energy_Jpkg = flight.reversal.energy_Jpkg;
  diag_.converged = converged && !too_long;
  diag_.status = too_long ? Status::kRangeTooLong : (converged ? Status::kOk : Status::kNotConverged);
  fill_output(ctx, flight.reversal, out, diag_);
  if (converged) ranging_blend_min_ = diag_.ranging_blend;
  if (diag_.status == Status::kOk || too_long) {  // the plans the tracker flies
    flown_ = FlownSide{true, rev.first_sign, flight.reversal.energy_Jpkg};
  }
  return diag_.status;
}

void EntryPlanner::fill_output(const PlanContext& ctx, const ReversalModel& reversal, ReferenceProfile& out,
                               PlannerDiagnostics& diag) const {
  const ReducedOrderInput sys = reduced_order_input(ctx, ws_);
  const ExtractedTrajectory& t = ws_.trajectory;
  const PlannedDrag& d = ws_.drag;
  const int n = params_.rk4_steps;
  const double h = ws_.range.s_total_m / n;
  int saturated = 0;
  out.n_points = kGrid;
  for (int k = 0; k < kGrid; ++k) {
    const double energy = ws_.grid.energy_Jpkg[k];
    // Latitude and heading of the reduced-order track at the point's flown range.
    const double u = ws_.range.s_cum_m[k] / h;
    int i = static_cast<int>(u);
    i = i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
    const double w = clamp(u - i, 0.0, 1.0);
    const RopState& a = ws_.track[i];
    const RopState& b = ws_.track[i + 1];
    const double lat = a.lat + w * (b.lat - a.lat);
    const double chi = a.chi + w * (b.chi - a.chi);
    const int kk = k < kGrid - 1 ? k : kGrid - 2;
    const double wk = k < kGrid - 1 ? 0.0 : 1.0;
    double lod;
    const double lod_cos = vertical_lift_over_drag(sys, kk, wk, lat, chi, lod);
    if (std::fabs(lod_cos) > lod) ++saturated;
    out.energy_Jpkg[k] = energy;
    out.e_norm[k] = energy / mission_.entry_energy_Jpkg;
    out.drag_mps2[k] = d.drag_mps2[k];
    out.drag_prime[k] = d.drag_prime[k];
    out.drag_second[k] = d.drag_second[k];
    out.a_coef[k] = t.a_no_coriolis[k] + t.density_gravity[k] * coriolis_gamma(kEarthRate_radps, lat, chi, d.drag_mps2[k], t.velocity_mps[k]);
    out.b_coef[k] = t.b[k];
    out.radius_m[k] = ws_.radius_m[k];
    out.velocity_mps[k] = t.velocity_mps[k];
    out.gamma_rad[k] = t.gamma_rad[k];
    out.alpha_rad[k] = ws_.grid.alpha_rad[k];
    out.lift_over_drag[k] = t.lift_over_drag[k];
    out.sigma_rad[k] = scheduled_bank_rad(reversal, energy, bank_magnitude_rad(lod_cos, lod));
    out.heading_rad[k] = chi;
    out.dynamic_pressure_Pa[k] = t.dynamic_pressure_Pa[k];
    out.drag_max_mps2[k] = ws_.corridor.corridor.max_mps2[k];
  }
  diag.bank_saturated_points = saturated;
  out.reversal_energy_Jpkg = diag.reversal_energy_Jpkg;
  out.initial_bank_sign = reversal.first_sign;
  out.entry_energy_Jpkg = mission_.entry_energy_Jpkg;
  out.taem_energy_Jpkg = mission_.taem_energy_Jpkg;
  out.taem_altitude_m = mission_.taem_drag_altitude_m;
  out.dc_mps2 = diag.dc_mps2;
  out.e1_Jpkg = diag.e1_Jpkg;
  out.e2_Jpkg = diag.e2_Jpkg;
  out.trajectory_length_m = diag.s_final_m;
  out.ranging_blend = diag.ranging_blend;
  out.crossrange_err_m = diag.crossrange_err_m;
  out.downrange_err_m = diag.downrange_err_m;
  out.iterations = diag.iterations;
  out.status = diag.status;
  out.converged = diag.converged;
}

}  // namespace reentry::fsw
