#include "tracker/lateral_logic.hpp"

#include <cmath>

#include "models/onboard_models.hpp"
#include "planner/mission_geometry.hpp"

namespace reentry::fsw {

FinalTurnState predict_final_turn(const FinalTurnInput& in) {
  // Midpoint rule over in.steps steps (bounded).
  FinalTurnState out{in.heading_err_rad, in.cross_track_m, 0.0};
  if (!(in.t_go_s > 0.0) || !(in.speed_mps > 0.0) || in.steps < 1) return out;
  const double side = in.cross_track_m >= 0.0 ? 1.0 : -1.0;
  const double h = in.t_go_s / in.steps;
  const double v_f = std::fmin(in.taem_speed_mps, in.speed_mps);
  for (int i = 0; i < in.steps; ++i) {
    const double t = (i + 0.5) * h;
    const double speed = in.speed_mps - (in.speed_mps - v_f) * t / in.t_go_s;
    const double roll = in.sigma_rate_radps * std::fmax(t - in.roll_lag_s, 0.0);
    const double sigma = in.sigma_now_rad + clamp(in.sigma_end_rad - in.sigma_now_rad, -roll, roll);
    const double turn = in.lift_horizontal_mps2 * std::sin(sigma) / speed * h;
    out.cross_track_m -= speed * std::sin(out.heading_err_rad + 0.5 * turn) * h;
    out.heading_err_rad += turn;
    out.overshoot_m = std::fmax(out.overshoot_m, -side * out.cross_track_m);
  }
  return out;
}

void LateralLogic::init(const TrackerParams& params, const TaemTarget& taem, double sigma_rate_max_radps,
                        double e_taem_norm, double e_corridor_norm) {
  bind(params);
  taem_ = taem;
  sigma_rate_max_radps_ = sigma_rate_max_radps;
  e_taem_norm_ = e_taem_norm;
  e_corridor_norm_ = e_corridor_norm;
  reset();
}

void LateralLogic::reset() {
  last_sign_ = 0;
  mean_sigma_d_rad_ = -1.0;
  final_reversal_done_ = false;
  final_correction_done_ = false;
}

ArrivalLineTarget LateralLogic::arrival_line_target(const RelativeState& s) const {
  // Arrival line: the great circle through the aim point on the required TAEM heading chi_f.
  // The offset eps (bearing from the aim point to the vehicle minus the reversed arrival
  // heading) gives, in the local plane, the cross-track distance y = R sin(eps) and the line's
  // heading at the vehicle chi_line = lambda - eps (lambda: line of sight to the aim point);
  // measuring eps at the aim point keeps this valid over thousands of kilometres. The target
  // heading is a vector field onto the line (Nelson et al. 2007), bounded by the turn the
  // vehicle can make (approach_turn_factor k):
  //   chi_d = chi_line + sign(y) min(chi_inf (2/pi) atan(|y| / y_s), sqrt(2 k |y| / R_turn)),
  // R_turn = V^2 cos(gamma) / (L sin|sigma|) at the mean bank, so the vehicle converges on the
  // line and arrives along it, on chi_f.
  const TrackerParams& p = *params_;
  ArrivalLineTarget t;
  const double aim_lat = taem_.latitude_rad, aim_lon = taem_.longitude_rad;
  const GreatCircleBothWays to_aim =
      great_circle_both_ways(s.latitude_rad, s.longitude_rad, aim_lat, aim_lon);  // (7.1)-(7.2)
  t.range_m = kEarthRadius_m * to_aim.arc_rad;
  t.bearing_rad = to_aim.azimuth_rad;
  if (t.range_m > p.aim_min_range_m) t.offset_rad = wrap_pi(to_aim.back_azimuth_rad - (taem_.heading_rad + M_PI));
  t.cross_track_m = t.range_m * std::sin(t.offset_rad);
  t.line_heading_rad = t.bearing_rad - t.offset_rad;
  double approach_rad =
      p.approach_angle_max_rad * (2.0 / M_PI) * std::atan(std::fabs(t.cross_track_m) / p.cross_track_scale_m);
  const double turn_accel_mps2 = s.lift_mps2 * std::sin(std::fmax(mean_sigma_d_rad_, 0.0));
  if (turn_accel_mps2 > 0.0) {
    const double turn_radius_m = s.velocity_mps * s.velocity_mps * std::cos(s.flight_path_rad) / turn_accel_mps2;
    approach_rad =
        std::fmin(approach_rad, std::sqrt(2.0 * p.approach_turn_factor * std::fabs(t.cross_track_m) / turn_radius_m));
  }
  t.heading_rad = wrap_pi(t.line_heading_rad + std::copysign(approach_rad, t.cross_track_m));
  t.along_track_m = t.range_m * std::cos(t.offset_rad);
  return t;
}

bool LateralLogic::in_final_reversal_window(double t_go_s) const {
  return mean_sigma_d_rad_ > 0.0 &&
         t_go_s < params_->final_reversal_window * 2.0 * mean_sigma_d_rad_ / sigma_rate_max_radps_;
}

FinalTurnState LateralLogic::turn_until_taem(const LateralInput& in, int sign) const {
  // Heading and cross-track from now to TAEM with the bank rolled from the one flown to the
  // mean bank magnitude on the side `sign`.
  const RelativeState& s = *in.state;
  FinalTurnInput f;
  f.speed_mps = s.velocity_mps;
  f.taem_speed_mps = in.taem_speed_mps;
  f.t_go_s = in.t_go_s;
  f.lift_horizontal_mps2 = s.lift_mps2 / in.cos_gamma;
  f.sigma_now_rad = in.sigma_flown_rad;
  f.sigma_end_rad = sign * mean_sigma_d_rad_;
  f.sigma_rate_radps = sigma_rate_max_radps_;
  f.roll_lag_s = params_->roll_lag_s;
  f.heading_err_rad = wrap_pi(s.heading_rad - in.target.line_heading_rad);
  f.cross_track_m = in.target.cross_track_m;
  f.steps = params_->final_turn_steps;
  return predict_final_turn(f);
}

int LateralLogic::corridor_sign(const LateralInput& in, double err_to_target, double corridor_rad) const {
  int sign = last_sign_;
  if (last_sign_ > 0 && err_to_target > corridor_rad) sign = -1;        // right of the target: bank left
  else if (last_sign_ < 0 && err_to_target < -corridor_rad) sign = 1;   // left of it: bank right
  // Capture guard: farther than capture_overshoot_m from the arrival line, a bank towards it
  // is flown only while a turn away started now (roll to the mean bank on the other side,
  // speed falling to TAEM) would still stop the vehicle within capture_overshoot_m past the
  // line; otherwise the vehicle reverses (or does not reverse) to turn away. The field's
  // approach-angle bound assumes the turn away starts at once, but the corridor lets the
  // heading run up to its half-width past the target and the reversal takes 2 sigma / rate.
  // Not while the mean bank is past 90 deg: the drag loop is diving, and a reversal from there
  // rolls through wings level for up to a minute (the climb it leaves costs more range).
  const double overshoot_m = params_->capture_overshoot_m;
  const int toward_line = in.target.cross_track_m >= 0.0 ? 1 : -1;
  if (sign == toward_line && mean_sigma_d_rad_ < 0.5 * M_PI && std::fabs(in.target.cross_track_m) > overshoot_m &&
      turn_until_taem(in, -toward_line).overshoot_m > overshoot_m) {
    sign = -toward_line;
  }
  return sign;
}

LateralDecision LateralLogic::decide(const LateralInput& in) {
  const TrackerParams& p = *params_;
  LateralDecision d;
  d.sign = in.plan_sign;
  // Bank magnitude averaged over mean_bank_time_constant_s: the final-reversal window and the
  // heading turned until TAEM depend on the bank flown over the remaining flight, not on the
  // present command, which swings by tens of degrees after a reversal.
  mean_sigma_d_rad_ = mean_sigma_d_rad_ < 0.0 ? in.sigma_d_rad
                                              : mean_sigma_d_rad_ + clamp(in.dt_s / p.mean_bank_time_constant_s, 0.0, 1.0) *
                                                                        (in.sigma_d_rad - mean_sigma_d_rad_);
  if (!in.corridor_phase || last_sign_ == 0) return d;
  const double err_to_target = wrap_pi(in.state->heading_rad - in.target.heading_rad);
  const double x = clamp((in.e_norm - e_taem_norm_) / (e_corridor_norm_ - e_taem_norm_), 0.0, 1.0);
  const double corridor = p.corridor_half_width_min_rad + (p.corridor_half_width_max_rad - p.corridor_half_width_min_rad) * x;
  d.sign = last_sign_;
  d.heading_err_valid = true;
  d.heading_err_rad = err_to_target;
  d.corridor_half_width_rad = corridor;
  if (in_final_reversal_window(in.t_go_s)) {
    // The one last reversal starts when the TAEM state it leads to is balanced between
    // heading error and cross-track offset, weighted by the mission's tolerances (a corridor
    // reversal this late would leave the vehicle mid-swing); waiting moves both towards the
    // present turn. The same test after the final reversal is the correction reversal: the
    // turn it left would carry the heading past the balance even if the vehicle rolled back
    // now, so it rolls back once. The correction starts once the final reversal's roll has
    // settled on the bank the loop asks for (a roll from a lift-down bank outlasts the
    // nominal reversal time).
    const FinalTurnState turn = turn_until_taem(in, -last_sign_);
    const double cross_weight =
        taem_.range_tol_m > 0.0 && taem_.heading_tol_rad > 0.0 ? taem_.heading_tol_rad / taem_.range_tol_m : 0.0;
    const bool balance_passed = last_sign_ * (turn.heading_err_rad - cross_weight * turn.cross_track_m) >= 0.0;
    const bool bank_settled = in.attitude_given && in.filter_sigma_rad * last_sign_ > 0.0 &&
                              std::fabs(in.filter_sigma_rad - last_sign_ * in.sigma_d_rad) < p.bank_settled_rad;
    const bool roll_over = !in.reversing || (final_reversal_done_ && bank_settled);
    if (roll_over && balance_passed && !final_correction_done_) {
      d.sign = -last_sign_;
      if (final_reversal_done_) final_correction_done_ = true;
      final_reversal_done_ = true;
      d.final_reversal_started = true;
    }
  } else if (!in.reversing) {
    d.sign = corridor_sign(in, err_to_target, corridor);
  }
  return d;
}

}  // namespace reentry::fsw
