#include "predictor_corrector/pc_cycle.hpp"

#include <cmath>

#include "planner/mission_geometry.hpp"
#include "predictor_corrector/point_mass.hpp"
#include "predictor_corrector/predictor.hpp"

namespace reentry::fsw {
namespace {

// Least bank magnitude commanded after capture: a zero magnitude out of the rate filter would
// lose the bank side the law flies, which the planner takes from the flown bank.
constexpr double kMinBankMagnitude_rad = 1e-4;

bool usable_state(const RelativeState& s, double dt_s) {
  const double v[] = {s.t_s, s.radius_m, s.latitude_rad, s.longitude_rad, s.velocity_mps, s.flight_path_rad,
                      s.heading_rad, s.energy_Jpkg, s.drag_mps2, s.lift_mps2, dt_s};
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return dt_s > 0.0 && s.velocity_mps > 0.0 && s.radius_m > 0.0 && s.drag_mps2 >= 0.0 && s.lift_mps2 >= 0.0;
}

}  // namespace

Status PredictorCorrectorCycle::init(const OnboardModels& models, const AlphaProfile& alpha_profile,
                                     const GuidanceMission& mission, const PredictorCorrectorParams& params,
                                     const TrackerParams& estimator_params, double capture_drag_mps2) {
  initialised_ = false;
  if (pc_params_inconsistency(params) != nullptr || !(mission.limits.sigma_rate_max_radps > 0.0)) {
    return Status::kInvalidInput;
  }
  models_ = models;
  alpha_profile_ = alpha_profile;
  params_ = params;
  estimator_params_ = estimator_params;
  taem_ = mission.taem;
  limits_ = pc_limits_from(mission.limits, params.constraint_margin, params.drag_model_uncertainty);
  alpha_max_rad_ = mission.limits.alpha_max_rad;
  sigma_rate_max_radps_ = mission.limits.sigma_rate_max_radps;
  capture_drag_mps2_ = capture_drag_mps2;
  entry_energy_Jpkg_ = specific_energy_Jpkg(kEarthRadius_m + mission.entry.altitude_m, mission.entry.velocity_mps);
  taem_energy_Jpkg_ =
      specific_energy_Jpkg(surface_radius_m(taem_.latitude_rad) + taem_.altitude_m, taem_.velocity_mps);
  if (!(entry_energy_Jpkg_ > taem_energy_Jpkg_)) return Status::kInvalidInput;
  lateral_.init(params_, taem_, sigma_rate_max_radps_, entry_energy_Jpkg_, taem_energy_Jpkg_);
  estimator_.init(models_, estimator_params_);
  has_profile_ = captured_ = attitude_given_ = false;
  lateral_state_ = PcLateralState{};
  initialised_ = true;
  return Status::kOk;
}

double PredictorCorrectorCycle::replan_floor_energy_Jpkg() const {
  return taem_energy_Jpkg_ + params_.replan_floor_span_fraction * (entry_energy_Jpkg_ - taem_energy_Jpkg_);
}

void PredictorCorrectorCycle::set_profile(const ReferenceProfile& profile) {
  if (profile.n_points < 2 || !(profile.energy_Jpkg[0] > profile.energy_Jpkg[profile.n_points - 1])) return;
  profile_ = profile;
  has_profile_ = true;
}

PredictorCorrectorCycle::PlanPoint PredictorCorrectorCycle::plan_at(double energy_Jpkg) const {
  // The plan's points are uniform in energy (the predictor's sampling), index 0 at its start.
  const ReferenceProfile& p = profile_;
  const int n = p.n_points;
  const double e0 = p.energy_Jpkg[0], ef = p.energy_Jpkg[n - 1];
  const double u = clamp((e0 - energy_Jpkg) / (e0 - ef), 0.0, 1.0) * (n - 1);
  const int k = static_cast<int>(std::fmin(std::floor(u), n - 2));
  const double w = u - k;
  auto lerp = [&](const double* a) { return a[k] + w * (a[k + 1] - a[k]); };
  PlanPoint pt;
  pt.sigma_rad = lerp(p.sigma_rad);
  pt.alpha_rad = lerp(p.alpha_rad);
  pt.radius_m = lerp(p.radius_m);
  pt.hdot_mps = lerp(p.velocity_mps) * std::sin(lerp(p.gamma_rad));
  pt.drag_mps2 = lerp(p.drag_mps2);
  return pt;
}

void PredictorCorrectorCycle::bank_command(const RelativeState& s, double alpha_rad, double alpha_profile_rad,
                                           PcCycleOutput& out) {
  const PlanPoint plan = plan_at(s.energy_Jpkg);
  const double h = s.radius_m - surface_radius_m(s.latitude_rad);
  const double mach = models_.mach(h, s.velocity_mps);
  // The limits hold at the alpha flown (the sensed drag's): its coefficients give the drag limit.
  const double alpha_flown = attitude_given_ ? flown_alpha_rad_ : alpha_rad;
  double cl = 0.0, cd = 0.0;
  models_.aero().coefficients(alpha_flown, mach, cl, cd);
  cl *= estimator_.lift_over_drag_ratio();
  BankLawInput in;
  in.sigma_base_rad = std::fabs(plan.sigma_rad);
  in.scale_height_m = local_scale_height_m(models_, h);
  in.sigma_flown_rad = attitude_given_ ? flown_sigma_rad_ : 0.0;
  in.velocity_mps = s.velocity_mps;
  in.radius_m = s.radius_m;
  in.latitude_rad = s.latitude_rad;
  in.heading_rad = s.heading_rad;
  in.flight_path_rad = s.flight_path_rad;
  // The plan's altitude rate; in the terminal phase the line onto the plan's TAEM altitude from
  // the navigated state, as the prediction flies it.
  const double need = level_flight_lift_need_mps2(s.radius_m, s.velocity_mps * std::cos(s.flight_path_rad),
                                                  s.latitude_rad, s.heading_rad);
  const double to_plan_m = plan.radius_m - s.radius_m;
  in.hdot_ref_mps = plan.hdot_mps + position_gain_ps(need, in.scale_height_m, params_) * to_plan_m;
  const TerminalAltitude terminal{taem_energy_Jpkg_, entry_energy_Jpkg_ - taem_energy_Jpkg_, profile_.taem_altitude_m};
  in.terminal = terminal.at(s.energy_Jpkg, h, s.velocity_mps, s.drag_mps2, params_);
  in.drag_mps2 = s.drag_mps2;
  in.lift_mps2 = s.lift_mps2;
  in.drag_limit_mps2 = constraint_drag_limit_mps2(models_, limits_, s.velocity_mps, alpha_flown, cl, cd);
  in.drag_limit_rate_ps =
      constraint_drag_limit_rate_ps(models_, limits_, s.velocity_mps, s.drag_mps2, alpha_flown, cl, cd);
  in.sigma_rate_radps = sigma_rate_max_radps_;
  in.skip_phase = s.drag_mps2 < capture_drag_mps2_;
  PcLateralInput li;
  li.energy_Jpkg = s.energy_Jpkg;
  li.velocity_mps = s.velocity_mps;
  li.heading_rad = s.heading_rad;
  li.flight_path_rad = s.flight_path_rad;
  li.drag_mps2 = s.drag_mps2;
  li.lift_mps2 = s.lift_mps2;
  li.sigma_flown_rad = in.sigma_flown_rad;
  li.hold_side = profile_.reversal_hold_energy_Jpkg > 0.0 && s.energy_Jpkg > profile_.reversal_hold_energy_Jpkg;
  const BankLawOutput law = bank_magnitude(in, params_);
  const ArrivalGeometry g =
      lateral_.geometry(s.latitude_rad, s.longitude_rad, s.velocity_mps, s.flight_path_rad, s.lift_mps2, law.sigma_rad);
  // Outside the terminal phase (its reversals are the end game's) the capture guard waits for the
  // plan's first reversal.
  li.capture_waits = !terminal.in_phase(s.energy_Jpkg, params_) &&
                     lateral_.capture_waits_for_plan(s.energy_Jpkg, profile_.reversal_energy_Jpkg);
  li.sigma_mag_rad = law.sigma_rad;
  lateral_.decide(lateral_state_, li, g);
  const int sign = lateral_state_.sign;
  out.sigma_rad = sign * std::fmax(law.sigma_rad, kMinBankMagnitude_rad);
  // While a reversal rolls the bank through wings level, alpha sheds the vertical lift in excess
  // of the command's within the band, as far as the heat flux allows (density from the sensed
  // drag).
  const double alpha_min = std::fmax(alpha_profile_rad - params_.alpha_band_rad, 0.0);
  if (lateral_state_.reversing && terminal.modulates(s.energy_Jpkg, params_)) {
    const double density = models_.sensed_density_kgpm3(s.drag_mps2, s.velocity_mps, cd);
    out.alpha_rad = reversal_alpha_rad(models_, alpha_rad, mach, law.sigma_rad, in.sigma_flown_rad, sigma_rate_max_radps_,
                                       alpha_min, density, s.velocity_mps, limits_, params_);
  } else {
    out.alpha_rad = alpha_rad;
  }
  // Load relief at the present q (sensed drag over the model's C_D at the alpha flown).
  if (cd > 0.0) out.alpha_rad = load_relief_alpha_rad(models_.aero(), out.alpha_rad, mach, s.drag_mps2 / cd, limits_, alpha_min);
  out.phase = sign * in.sigma_flown_rad < 0.0 ? Phase::kReversal : Phase::kTracking;
  out.drag_ref_mps2 = plan.drag_mps2;
  out.drag_err_mps2 = s.drag_mps2 - plan.drag_mps2;
  out.heading_err_rad = wrap_pi(s.heading_rad - g.target_heading_rad);
  write_telemetry(s, in, law, g, li, out);
}

void PredictorCorrectorCycle::write_telemetry(const RelativeState& s, const BankLawInput& in, const BankLawOutput& law,
                                              const ArrivalGeometry& g, const PcLateralInput& li,
                                              PcCycleOutput& out) const {
  // Telemetry in the tracker's fields where the meaning fits: the plan's bank magnitude as the
  // base bank, the damping gain as the loop frequency, the bound and the guard as flags.
  TrackerTelemetry& t = out.telemetry;
  t.phase = TrackerPhase::kPlanned;
  t.drag_ref_mps2 = out.drag_ref_mps2;
  t.drag_err_mps2 = out.drag_err_mps2;
  t.heading_err_rad = out.heading_err_rad;
  t.corridor_half_width_rad = lateral_.half_width_rad(s.energy_Jpkg);
  t.omega_radps = law.damping_gain_ps;
  t.mean_bank_rad = in.sigma_base_rad;
  t.cross_track_m = g.cross_m;
  t.along_track_m = g.along_m;
  t.reversing = lateral_state_.reversing;
  t.saturated = law.bounded;
  t.pullout_arrested = law.pullout_guard;
  t.time_to_go_s = lateral_.time_to_go_s(li);
  t.final_reversal_done = lateral_state_.final_done;
  t.final_correction_done = lateral_state_.correction_done;
}

Status PredictorCorrectorCycle::step(const RelativeState& s, double dt_s, PcCycleOutput& out) {
  if (!initialised_) return Status::kInvalidInput;
  if (!usable_state(s, dt_s)) return Status::kNonFinite;
  out = PcCycleOutput{};
  const double alpha = clamp(alpha_profile_.alpha_rad(s.energy_Jpkg / entry_energy_Jpkg_), 0.0, alpha_max_rad_);
  const double alpha_flown = attitude_given_ ? flown_alpha_rad_ : alpha;
  estimator_.update_lift_over_drag_ratio(s, alpha_flown, dt_s);
  out.alpha_rad = alpha;
  out.lift_over_drag_scale = estimator_.lift_over_drag_ratio();
  if (!captured_ && has_profile_) {
    const double h = s.radius_m - surface_radius_m(s.latitude_rad);
    const double need = level_flight_lift_need_mps2(s.radius_m, s.velocity_mps * std::cos(s.flight_path_rad),
                                                    s.latitude_rad, s.heading_rad);
    captured_ = capture_due(s.drag_mps2, s.lift_mps2, s.velocity_mps * std::sin(s.flight_path_rad), need,
                            local_scale_height_m(models_, h), capture_drag_mps2_, params_);
  }
  if (!captured_) {
    out.sigma_rad = 0.0;  // initial descent: wings level
    out.phase = Phase::kInitialDescent;
    out.telemetry.phase = TrackerPhase::kInitialDescent;
  } else {
    // The plan's alpha (its ranging shift), never outside the band about the profile.
    out.alpha_rad = clamp(plan_at(s.energy_Jpkg).alpha_rad, std::fmax(alpha - params_.alpha_band_rad, 0.0),
                          std::fmin(alpha + params_.alpha_band_rad, alpha_max_rad_));
    estimator_.update_drag_ratio(s, alpha_flown, dt_s);
    bank_command(s, out.alpha_rad, alpha, out);
  }
  out.telemetry.drag_ratio = estimator_.drag_ratio();
  out.telemetry.lift_over_drag_ratio = estimator_.lift_over_drag_ratio();
  if (!std::isfinite(out.sigma_rad) || !std::isfinite(out.alpha_rad)) return Status::kNonFinite;
  return Status::kOk;
}

}  // namespace reentry::fsw
