// Lateral logic of the tracker: the sign of the bank.
//   - planned phase: the plan's sign (one planned reversal, method 3 of §7.4);
//   - heading corridor: the sign keeps the heading within a corridor around the target
//     heading of a vector field onto the arrival great circle (the circle through the aim
//     point on the required TAEM heading), narrowing towards TAEM (Shuttle-style lateral
//     logic aimed along the arrival line); a capture guard turns away early when a turn
//     towards the line would carry the vehicle too far past it;
//   - final reversal: one last reversal timed so that the TAEM state is balanced between
//     heading error and cross-track offset, and at most one correction reversal after it.
// A sign change is flown by ReversalExecution.
#pragma once

#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

/// Where the vehicle stands relative to the aim point and the arrival line.
struct ArrivalLineTarget {
  double range_m = 0.0;           // great-circle distance to the aim point
  double bearing_rad = 0.0;       // line of sight to the aim point
  double heading_rad = 0.0;       // target heading of the vector field onto the arrival line
  double offset_rad = 0.0;        // eps: bearing aim->vehicle minus the reversed arrival heading
  double along_track_m = 0.0;     // range to go along the arrival line (< 0: aim point passed)
  double cross_track_m = 0.0;     // offset from the arrival line (> 0: the line is to the right)
  double line_heading_rad = 0.0;  // heading of the arrival line at the vehicle (not wrapped)
};

/// Heading and cross-track motion relative to a straight arrival line over the last seconds
/// before TAEM, for the final-reversal timing and the capture guard (how far past the line
/// a turn away started now carries the vehicle). The bank rolls from sigma_now to sigma_end at
/// sigma_rate after roll_lag; the heading error psi turns at L_h sin(sigma) / V (L_h: lift
/// over cos gamma), the cross-track offset y (> 0: the line is to the right) moves at
/// -V sin(psi), and V falls linearly from speed to taem_speed over t_go.
struct FinalTurnInput {
  double speed_mps = 0.0;
  double taem_speed_mps = 0.0;
  double t_go_s = 0.0;
  double lift_horizontal_mps2 = 0.0;
  double sigma_now_rad = 0.0;
  double sigma_end_rad = 0.0;
  double sigma_rate_radps = 0.0;
  double roll_lag_s = 0.0;
  double heading_err_rad = 0.0;  // heading minus the line's
  double cross_track_m = 0.0;
  int steps = TrackerParams{}.final_turn_steps;  // midpoint-rule steps (bounded)
};
struct FinalTurnState {
  double heading_err_rad = 0.0;
  double cross_track_m = 0.0;
  double overshoot_m = 0.0;  // farthest excursion past the line on the side opposite the start (>= 0)
};
FinalTurnState predict_final_turn(const FinalTurnInput& in);

/// What the lateral logic needs of the present cycle.
struct LateralInput {
  const RelativeState* state = nullptr;
  ArrivalLineTarget target;
  bool corridor_phase = false;    // heading corridor (or later) phase
  int plan_sign = 1;              // sign of the plan's bank at this energy
  double e_norm = 0.0;            // E / E_entry
  double sigma_d_rad = 0.0;       // bank magnitude of the drag loop this cycle
  double dt_s = 0.0;
  double t_go_s = 0.0;
  double taem_speed_mps = 0.0;
  double cos_gamma = 1.0;
  double sigma_flown_rad = 0.0;   // bank flown now (filter output, else the last command)
  bool attitude_given = false;    // the flown attitude is the rate filter's (not the last command)
  double filter_sigma_rad = 0.0;  // the rate filter's bank (when attitude_given)
  bool reversing = false;         // a reversal is being flown
};

struct LateralDecision {
  int sign = 1;
  bool final_reversal_started = false;  // the final (or the correction) reversal starts now
  bool heading_err_valid = false;       // heading_err_rad is the error to the target heading
  double heading_err_rad = 0.0;
  double corridor_half_width_rad = 0.0;
};

class LateralLogic {
 public:
  /// e_taem_norm, e_corridor_norm: TAEM and corridor-start energies over E_entry.
  void init(const TrackerParams& params, const TaemTarget& taem, double sigma_rate_max_radps, double e_taem_norm,
            double e_corridor_norm);
  /// Points at the parameters (init, and again after the owner is copied).
  void bind(const TrackerParams& params) { params_ = &params; }
  void reset();
  /// Arrival-line geometry and the vector-field target heading (turn radius at the mean bank).
  ArrivalLineTarget arrival_line_target(const RelativeState& s) const;
  /// Within the last final_reversal_window reversal durations before TAEM, at the mean bank.
  bool in_final_reversal_window(double t_go_s) const;
  /// Updates the mean bank with this cycle's, then decides the sign (not yet committed).
  LateralDecision decide(const LateralInput& in);
  void commit_sign(int sign) { last_sign_ = sign; }
  int last_sign() const { return last_sign_; }
  double mean_bank_rad() const { return mean_sigma_d_rad_; }
  bool final_reversal_done() const { return final_reversal_done_; }
  bool final_correction_done() const { return final_correction_done_; }

 private:
  FinalTurnState turn_until_taem(const LateralInput& in, int sign) const;
  int corridor_sign(const LateralInput& in, double err_to_target, double corridor_rad) const;

  const TrackerParams* params_ = nullptr;
  TaemTarget taem_{};
  double sigma_rate_max_radps_ = 0.0;
  double e_taem_norm_ = 0.0;
  double e_corridor_norm_ = 0.0;
  int last_sign_ = 0;
  double mean_sigma_d_rad_ = -1.0;  // bank magnitude averaged for the final reversal (< 0: unset)
  bool final_reversal_done_ = false;
  bool final_correction_done_ = false;  // the one reversal allowed after the final one
};

}  // namespace reentry::fsw
