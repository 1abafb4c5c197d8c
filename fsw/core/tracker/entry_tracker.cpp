#include "tracker/entry_tracker.hpp"

#include <cmath>

#include "planner/mission_geometry.hpp"

namespace reentry::fsw {
namespace {

// Half-step of the central difference of C_D along the plan's (alpha(E), h) path (7.14), as a
// fraction of the entry energy.
constexpr double kCdSlopeEnergyStep = 1e-3;

bool finite_state(const RelativeState& s) {
  const double v[] = {s.t_s, s.radius_m, s.altitude_m, s.latitude_rad, s.velocity_mps, s.flight_path_rad,
                      s.heading_rad, s.energy_Jpkg, s.drag_mps2, s.lift_mps2};
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

}  // namespace

Status EntryTracker::init(const OnboardModels& models, const AlphaProfile& alpha_profile,
                          const GuidanceMission& mission, const GuidanceLawParams& params) {
  initialised_ = false;
  if (guidance_params_inconsistency(params) != nullptr) return Status::kInvalidInput;
  params_ = params.tracker;
  models_ = models;
  alpha_profile_ = alpha_profile;
  taem_ = mission.taem;
  entry_energy_Jpkg_ = specific_energy_Jpkg(kEarthRadius_m + mission.entry.altitude_m, mission.entry.velocity_mps);
  taem_energy_Jpkg_ =
      specific_energy_Jpkg(surface_radius_m(mission.taem.latitude_rad) + mission.taem.altitude_m, mission.taem.velocity_mps);
  const PathLimits& c = mission.limits;
  limits_.alpha_max_rad = c.alpha_max_rad;
  limits_.sigma_rate_max_radps = c.sigma_rate_max_radps;
  limits_.heat_flux_max_Wpm2 = c.heat_flux_max_Wpm2;
  limits_.q_alpha_max_Pa_rad = c.q_alpha_max_Pa_rad;
  limits_.q_max_Pa = c.dynamic_pressure_max_Pa;
  limits_.load_factor_max_mps2 = c.load_factor_max_g * kG0_mps2;
  limits_.constraint_margin = params.constraint_margin;
  const TrackerGains gains = derive_gains(params_);
  if (!(entry_energy_Jpkg_ > taem_energy_Jpkg_)) return Status::kInvalidInput;
  if (!(limits_.sigma_rate_max_radps > 0.0) || !(gains.omega0_radps > 0.0)) return Status::kInvalidInput;
  const double e_taem_norm = taem_energy_Jpkg_ / entry_energy_Jpkg_;
  const double e_terminal_norm = e_taem_norm + params.terminal_span_fraction * (1.0 - e_taem_norm);
  const double e_corridor_norm = e_taem_norm + params.lateral_corridor_span_fraction * (1.0 - e_taem_norm);
  const double rate = limits_.sigma_rate_max_radps;
  phases_.init(e_corridor_norm, e_terminal_norm);
  reference_.init(params_.q_ref_fraction);
  estimator_.init(models_, params_);
  drag_loop_.init(gains, params_);
  limiter_.init(models_, params_, limits_);
  terminal_.init(models_, params_, taem_, e_terminal_norm * entry_energy_Jpkg_, taem_energy_Jpkg_);
  lateral_.init(params_, taem_, rate, e_taem_norm, e_corridor_norm);
  reversal_.init(models_, params_, rate);
  last_alpha_cmd_rad_ = 0.0;
  last_sigma_d_rad_ = 0.0;
  flown_alpha_rad_ = -1.0;
  flown_sigma_rad_ = 0.0;
  initialised_ = true;
  return Status::kOk;
}

void EntryTracker::bind_components() {
  estimator_.bind(models_, params_);
  limiter_.bind(models_, params_);
  terminal_.bind(models_, params_);
  lateral_.bind(params_);
  reversal_.bind(models_, params_);
}

Status EntryTracker::check_input(const RelativeState& s, double dt_s) const {
  if (!initialised_) return Status::kInvalidInput;
  if (!finite_state(s) || !std::isfinite(dt_s)) return Status::kNonFinite;
  if (!(dt_s > 0.0) || !(s.velocity_mps > 0.0) || !(s.radius_m > 0.0)) return Status::kInvalidInput;
  // Physically impossible navigation (faster than escape, absurd sensed accelerations) is
  // rejected rather than pushed through the drag dynamics, where it would overflow.
  const double a_max = params_.max_accel_mps2;
  if (s.velocity_mps > params_.max_speed_mps || s.drag_mps2 < 0.0 || s.drag_mps2 > a_max || s.lift_mps2 < 0.0 ||
      s.lift_mps2 > a_max) {
    return Status::kInvalidInput;
  }
  return Status::kOk;
}

double EntryTracker::flown_alpha_rad(double alpha_profile_rad) const {
  // The rate filter's output when the stack provides it, else the alpha commanded last cycle,
  // else the profile's.
  if (flown_alpha_rad_ >= 0.0) return flown_alpha_rad_;
  return last_alpha_cmd_rad_ > 0.0 ? last_alpha_cmd_rad_ : alpha_profile_rad;
}

double EntryTracker::flown_bank_rad() const {
  // The rate filter's output when the stack provides it, else the tracker's own last command.
  return flown_alpha_rad_ >= 0.0 ? flown_sigma_rad_ : lateral_.last_sign() * last_sigma_d_rad_;
}

void EntryTracker::try_capture(const RelativeState& s) {
  // Capture once the drag is measurable and a wings-level pull-out would level off below the
  // reference (lift down is needed to reach it) or is essentially complete. Before that, the
  // reference can only be reached by the pull-out itself: lift down would deepen a dive the
  // drag loop cannot arrest. A shallow entry whose pull-out would level off below the
  // reference is captured from capture_drag_fraction of the threshold drag on: its drag may
  // never reach the threshold (skip-out).
  const double threshold = params_.initial_descent_drag_mps2;
  if (phases_.captured() || !reference_.has_profile() || !(s.drag_mps2 >= params_.capture_drag_fraction * threshold)) {
    return;
  }
  const double d_ref =
      reference_.at(s.energy_Jpkg - params_.capture_lookahead_energy_fraction * entry_energy_Jpkg_).drag;
  const double d_pullout = limiter_.pullout_drag_mps2(s, 0.0);
  if (d_pullout < d_ref || (s.drag_mps2 >= threshold && d_pullout < params_.pullout_complete_ratio * s.drag_mps2)) {
    phases_.capture();
  }
}

CycleContext EntryTracker::make_context(const RelativeState& s, double dt_s, const RefPoint& ref,
                                        double alpha_flown_rad, double alpha_ref_rad) {
  CycleContext c;
  c.state = &s;
  c.dt_s = dt_s;
  c.e_norm = s.energy_Jpkg / entry_energy_Jpkg_;
  c.mach = models_.mach(s.altitude_m, s.velocity_mps);
  c.alpha_flown_rad = alpha_flown_rad;
  c.alpha_ref_rad = alpha_ref_rad;
  c.referred = referred_to_alpha(models_, s, c.mach, alpha_flown_rad, alpha_ref_rad);
  const double D_ref_alpha = c.referred.drag_mps2;
  c.lift_over_drag_sensed = D_ref_alpha > params_.min_drag_mps2 ? c.referred.lift_mps2 / D_ref_alpha : 0.0;
  c.gravity_mps2 = gravity_mps2(s.radius_m);
  c.sin_gamma = std::sin(s.flight_path_rad);
  c.cos_gamma = std::cos(s.flight_path_rad);
  c.cd_ref = models_.drag_coefficient(alpha_ref_rad, s.energy_Jpkg, s.altitude_m);
  c.cd_flown = models_.drag_coefficient(alpha_flown_rad, s.energy_Jpkg, s.altitude_m);
  c.dynamic_pressure_Pa = c.cd_ref > 0.0 ? models_.sensed_dynamic_pressure_Pa(D_ref_alpha, c.cd_ref) : ref.q;
  // The limits hold at the flown alpha (true q, q alpha and load factor) and are referred to
  // the reference alpha.
  c.constraint_limit_mps2 = limiter_.sensed_drag_limit_mps2(s, alpha_flown_rad, c.cd_flown) * D_ref_alpha /
                            std::fmax(s.drag_mps2, params_.min_drag_mps2);
  // A density error does not move a q-type bound in drag space, a C_D / mass error does, and
  // the sensed ratio K cannot tell them apart (no air data): the bound is taken as planned.
  c.plan_bound_mps2 = ref.drag_max > 0.0 ? ref.drag_max : kUnconstrainedDrag_mps2;
  // Time to TAEM at the present drag with the speed falling linearly to the TAEM speed
  // (E' = -D V): with the present speed instead, t_go comes out 25-35 % short.
  const double V = s.velocity_mps;
  c.taem_speed_mps = std::fmin(taem_.velocity_mps, V);
  c.time_to_go_s =
      (s.energy_Jpkg - taem_energy_Jpkg_) / std::fmax(s.drag_mps2 * 0.5 * (V + c.taem_speed_mps), 1e-6);
  c.sigma_flown_rad = flown_bank_rad();
  phases_.advance(c.e_norm, lateral_.in_final_reversal_window(c.time_to_go_s));
  if (phases_.heading_corridor()) c.target = lateral_.arrival_line_target(s);
  return c;
}

void EntryTracker::shape_reference(const CycleContext& c, RefPoint& ref, TrackerOutput& out) {
  const RelativeState& s = *c.state;
  if (phases_.terminal()) {
    const double drag_raw = ref.drag, drag_max = ref.drag_max, sigma_plan = std::fabs(ref.sigma);
    // The final reversal is still to come: its alpha modulation lowers the drag for a reversal
    // time and so lengthens the range.
    auto extension_m = [&] {
      const bool modulated = !lateral_.final_reversal_done() &&
                             reversal_.modulation_allowed(drag_raw, drag_max, estimator_.drag_ratio());
      return modulated ? reversal_.range_extension_m(s, c.mach, c.alpha_ref_rad, sigma_plan) : 0.0;
    };
    out.telemetry.terminal_increment_mps2 =
        terminal_.shape_reference(ref, s.energy_Jpkg, c.target.along_track_m, estimator_.drag_ratio(), reference_,
                                  c.plan_bound_mps2, extension_m);
  }
  // The reference never asks for more drag than the sensed state allows within the planned
  // constraint fraction (the planner's bound is on the model atmosphere; tracking lag and
  // reversal transients must not eat the margin).
  ref.drag = std::fmin(ref.drag, c.constraint_limit_mps2);
}

double EntryTracker::available_lift_over_drag(const CycleContext& c, const RefPoint& ref) const {
  // Sensed L/D where it is measurable, else the planned one (a lift-less or drag-less
  // measurement must not turn into a 0/0 bank command).
  return c.lift_over_drag_sensed >= params_.min_lift_over_drag ? c.lift_over_drag_sensed : ref.lod;
}

DragLoopCommand EntryTracker::drag_command(const CycleContext& c, const RefPoint& ref, double lod,
                                           TrackerOutput& out) {
  const RelativeState& s = *c.state;
  const double V = s.velocity_mps, D = s.drag_mps2, V2 = V * V;
  // Actual D' from (7.14): density gradient and C_D' from the on-board models, alpha along the
  // plan (which may differ from the mission profile: ranging alpha).
  const double dlnrho_dr = models_.dlnrho_dr_fd(s.altitude_m, kTrackerDensityGradientStep_m);
  const double de = kCdSlopeEnergyStep * entry_energy_Jpkg_;
  const double cd_slope =
      models_.drag_coefficient_slope(ref.alpha + ref.alpha_prime * de, s.energy_Jpkg + de, s.altitude_m,
                                     ref.alpha - ref.alpha_prime * de, s.energy_Jpkg - de, s.altitude_m);
  const double cd_ratio = c.cd_ref > 0.0 ? cd_slope / c.cd_ref : 0.0;
  const double density_term = -dlnrho_dr + 2.0 * c.gravity_mps2 / V2;
  DragLoopInput in;
  in.ref = ref;
  in.drag_mps2 = c.referred.drag_mps2;
  in.drag_prime = c.referred.drag_mps2 * (2.0 / V2 + cd_ratio) + density_term * c.sin_gamma;  // (7.14)
  in.b = -density_term / V2;                                                                 // (7.20)
  if (!(std::fabs(in.b) > 0.0)) in.b = ref.b;
  in.lift_over_drag = lod;
  // Scheduled omega (3.13); in the terminal phase fast enough to remove the drag error
  // before TAEM, where the drag sets the altitude.
  const TrackerGains& g = drag_loop_.gains();
  in.omega_radps = scheduled_omega(g.omega0_radps, c.dynamic_pressure_Pa, reference_.q_ref_Pa());
  if (phases_.terminal()) {
    in.omega_radps = std::fmax(in.omega_radps, terminal_omega_floor_radps(g.omega0_radps, c.time_to_go_s,
                                                                          params_.terminal_settling,
                                                                          params_.terminal_omega_max_factor));
  }
  // Time -> energy conversion (3.14)-(3.18), E' = -D V.
  in.e_dot = -D * V;
  in.e_ddot = in.drag_prime * D * V2 + D * D + D * c.gravity_mps2 * c.sin_gamma;  // (3.18)
  DragLoopCommand cmd = drag_loop_.command(in);
  out.saturated = cmd.saturated;
  out.telemetry.omega_radps = in.omega_radps;
  // The pull-out guard, judged from the bank the vehicle flies (the rate filter's), not from
  // the last command (judged from its own command, the guard would release lift down on the
  // cycle after commanding wings level while the vehicle stays lift down).
  cmd.u_drag = limiter_.pullout_guard(s, c.sigma_flown_rad, cmd.u_drag, lod, phases_.terminal(),
                                      std::fmin(c.constraint_limit_mps2, c.plan_bound_mps2));
  // No lift down in the final-reversal window: a dive started there cannot be arrested before
  // TAEM, and a bank past 90 deg turns the vehicle on after the final reversal.
  cmd.u_drag = clamp(cmd.u_drag, phases_.final_reversal_window() ? 0.0 : -lod, lod);
  out.u_drag = cmd.u_drag;
  out.sigma_d_rad = std::acos(clamp(cmd.u_drag / lod, -1.0, 1.0));  // (3.20)
  drag_loop_.update_integral(cmd, reversal_.active(s.t_s), ref.drag, c.dt_s);
  return cmd;
}

int EntryTracker::bank_sign(const CycleContext& c, const RefPoint& ref, double sigma_d_rad, TrackerOutput& out) {
  const RelativeState& s = *c.state;
  const double rate = limits_.sigma_rate_max_radps;
  const double t_rev_s = 2.0 * sigma_d_rad / rate;
  LateralInput in;
  in.state = &s;
  in.target = c.target;
  in.corridor_phase = phases_.heading_corridor();
  in.plan_sign = ref.sigma >= 0.0 ? 1 : -1;
  in.e_norm = c.e_norm;
  in.sigma_d_rad = sigma_d_rad;
  in.dt_s = c.dt_s;
  in.t_go_s = c.time_to_go_s;
  in.taem_speed_mps = c.taem_speed_mps;
  in.cos_gamma = c.cos_gamma;
  in.sigma_flown_rad = c.sigma_flown_rad;
  in.attitude_given = flown_alpha_rad_ >= 0.0;
  in.filter_sigma_rad = flown_sigma_rad_;
  in.reversing = reversal_.active(s.t_s);
  const LateralDecision d = lateral_.decide(in);
  // The drag integral was built up on the range control's pre-reversal reference (it asks for
  // the drag the reversal's alpha modulation gives back); kept, it holds the bank above the
  // loop's demand after the roll.
  if (d.final_reversal_started) drag_loop_.reset();
  if (d.heading_err_valid) out.heading_err_rad = d.heading_err_rad;
  else if (!in.corridor_phase) out.heading_err_rad = wrap_pi(s.heading_rad - ref.heading);
  out.telemetry.corridor_half_width_rad = d.corridor_half_width_rad;
  if (lateral_.last_sign() != 0 && d.sign != lateral_.last_sign()) {
    reversal_.begin(s.t_s, t_rev_s, c.dt_s, sigma_d_rad,
                    lateral_.in_final_reversal_window(std::fmax(c.time_to_go_s - t_rev_s, 0.0)));
  }
  lateral_.commit_sign(d.sign);
  return d.sign;
}

Status EntryTracker::step(const RelativeState& s, double dt_s, TrackerOutput& out) {
  const Status input = check_input(s, dt_s);
  if (input != Status::kOk) return input;
  const double e_norm = s.energy_Jpkg / entry_energy_Jpkg_;
  out = TrackerOutput{};
  out.alpha_rad = clamp(alpha_profile_.alpha_rad(e_norm), 0.0, limits_.alpha_max_rad);
  const double alpha_flown = flown_alpha_rad(out.alpha_rad);
  estimator_.update_lift_over_drag_ratio(s, alpha_flown, dt_s);
  out.lift_over_drag_scale = estimator_.lift_over_drag_ratio();
  try_capture(s);
  if (!reference_.has_profile() || !phases_.captured()) {
    // Initial descent: profile alpha, wings level (maximum vertical lift) until captured.
    out.phase = Phase::kInitialDescent;
    last_alpha_cmd_rad_ = out.alpha_rad;
    finish_output(CycleContext{}, out);
    return Status::kOk;
  }
  RefPoint ref = reference_.at(s.energy_Jpkg);
  out.alpha_rad = clamp(ref.alpha, 0.0, limits_.alpha_max_rad);
  const double alpha_ref = out.alpha_rad;  // before any reversal modulation or load relief
  estimator_.update_drag_ratio(s, alpha_flown, dt_s);
  const CycleContext c = make_context(s, dt_s, ref, alpha_flown, alpha_ref);
  shape_reference(c, ref, out);
  const double lod = available_lift_over_drag(c, ref);
  if (!(lod >= params_.min_lift_over_drag)) return Status::kInvalidInput;
  const DragLoopCommand cmd = drag_command(c, ref, lod, out);
  const double sigma_d = out.sigma_d_rad;
  const int sign = bank_sign(c, ref, sigma_d, out);
  if (!lateral_.final_correction_done() &&
      reversal_.modulation_allowed(ref.drag, ref.drag_max, estimator_.drag_ratio())) {
    // Not in the correction reversal: seconds before TAEM, the drag a modulation removes can
    // no longer be made up.
    out.alpha_rad = reversal_.alpha_command(s.t_s, out.alpha_rad, c.mach, sign * sigma_d, flown_bank_rad(),
                                            cmd.u_drag / lod, lateral_.final_reversal_done());
  }
  // Load relief: the alpha command (a modulation ending at high dynamic pressure raises alpha
  // by up to 15 deg within seconds) never asks for more than the load-factor limit allows.
  if (alpha_flown > 0.0) {
    out.alpha_rad = limiter_.load_relief_alpha(out.alpha_rad, alpha_ref - params_.final_modulation_max_rad,
                                               alpha_flown, c.mach, std::hypot(s.drag_mps2, s.lift_mps2));
  }
  out.sigma_rad = sign * sigma_d;
  if (!std::isfinite(out.sigma_rad) || !std::isfinite(out.alpha_rad)) return Status::kNonFinite;
  last_sigma_d_rad_ = sigma_d;
  out.drag_ref_mps2 = ref.drag;
  out.drag_err_mps2 = cmd.error;
  finish_output(c, out);
  last_alpha_cmd_rad_ = out.alpha_rad;
  return Status::kOk;
}

void EntryTracker::finish_output(const CycleContext& c, TrackerOutput& out) {
  TrackerTelemetry& t = out.telemetry;
  t.drag_ref_mps2 = out.drag_ref_mps2;
  t.drag_err_mps2 = out.drag_err_mps2;
  t.heading_err_rad = out.heading_err_rad;
  t.saturated = out.saturated;
  if (phases_.captured() && c.state != nullptr) {
    out.phase = reversal_.active(c.state->t_s) ? Phase::kReversal : Phase::kTracking;
    t.reversing = reversal_.active(c.state->t_s);
    t.time_to_go_s = c.time_to_go_s;
    t.cross_track_m = c.target.cross_track_m;
    t.along_track_m = c.target.along_track_m;
  }
  t.phase = phases_.phase();
  t.drag_integral_mps = drag_loop_.integral();
  t.drag_ratio = estimator_.drag_ratio();
  t.lift_over_drag_ratio = estimator_.lift_over_drag_ratio();
  t.mean_bank_rad = lateral_.mean_bank_rad();
  t.final_reversal_done = lateral_.final_reversal_done();
  t.final_correction_done = lateral_.final_correction_done();
  t.pullout_arrested = limiter_.pullout_arrested();
}

}  // namespace reentry::fsw
