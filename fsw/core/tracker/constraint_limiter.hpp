// Constraint limiting: what the tracker does so that the flown state stays inside the path
// constraints whatever the plan and the drag loop ask for.
//   - the entry pull-out guard: from capture until the entry descent is arrested (optionally
//     on every later descent too), a descent whose wings-level pull-out would bottom out above
//     the constraint limit is stopped now with full lift (vertical energy balance of the
//     pull-out);
//   - the sensed-constraint drag limit: the largest drag at which q, q alpha, the load factor
//     and the heat flux (3.5) stay within the planned fraction of their limits at the sensed
//     state;
//   - load relief: the alpha command never asks for more than the load-factor limit allows.
#pragma once

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

/// Drag at the bottom of a wings-level pull-out from drag D sinking at h_dot < 0, speed held
/// and the air exponential with scale height H (vertical energy balance, see the .cpp);
/// D itself when not sinking, kNoPullOut_mps2 when the lift cannot arrest the sink.
inline constexpr double kNoPullOut_mps2 = 1e6;
/// The sensed-constraint drag limit where no constraint applies.
inline constexpr double kUnconstrainedDrag_mps2 = 1e300;
double wings_level_pullout_drag_mps2(double drag_mps2, double lift_over_drag, double h_dot_mps, double g_eff_mps2,
                                     double scale_height_m);
/// The same pull-out started after a roll from bank sigma0 to wings level lasting t_roll:
/// the roll is flown with the mean vertical lift L sin(sigma0) / sigma0 of a uniform roll at
/// the present lift and constant vertical acceleration (conservative: the lift growing with
/// the density over the roll is left out), then the wings-level pull-out.
double pullout_drag_after_roll_mps2(double drag_mps2, double lift_over_drag, double h_dot_mps, double g_eff_mps2,
                                    double scale_height_m, double sigma0_rad, double t_roll_s);

/// Path-constraint limits as the tracker applies them: the mission's, times the planned margin.
struct TrackerLimits {
  double alpha_max_rad = 0.0;
  double sigma_rate_max_radps = 0.0;
  double heat_flux_max_Wpm2 = 0.0;   // 0 or infinite: not constrained
  double q_alpha_max_Pa_rad = 0.0;
  double q_max_Pa = 0.0;
  double load_factor_max_mps2 = 0.0;
  double constraint_margin = 0.97;   // planned fraction of every limit (shared with the planner)
};

class ConstraintLimiter {
 public:
  void init(const OnboardModels& models, const TrackerParams& params, const TrackerLimits& limits);
  /// Points at the models and parameters (init, and again after the owner is copied).
  void bind(const OnboardModels& models, const TrackerParams& params) {
    models_ = &models;
    params_ = &params;
  }
  void reset() { pullout_arrested_ = false; }

  /// Drag at the bottom of a wings-level pull-out from the present state, started after the
  /// roll from sigma_now (plus the filter lag) to wings level; local scale height of the
  /// on-board atmosphere, sensed L/D.
  double pullout_drag_mps2(const RelativeState& s, double sigma_now_rad) const;
  /// The pull-out guard on the vertical L/D command u_drag: full lift (u = L/D) while the
  /// entry descent is not arrested and its pull-out would bottom out above `limit_mps2`.
  /// Judged from the bank the vehicle flies; off in the terminal phase; latched off once the
  /// pull-out is complete (later descents are the drag loop's own), unless
  /// pullout_guard_every_descent, which judges every descent until the terminal phase.
  double pullout_guard(const RelativeState& s, double sigma_flown_rad, double u_drag, double lod, bool terminal,
                       double limit_mps2);
  bool pullout_arrested() const { return pullout_arrested_; }

  /// Largest drag at which the sensed path-constraint values stay within the planned fraction
  /// of their limits, at alpha_rad with drag coefficient cd (kUnconstrainedDrag_mps2: none applies).
  double sensed_drag_limit_mps2(const RelativeState& s, double alpha_rad, double cd) const;
  /// The alpha command lowered (never below alpha_floor) until the sensed aerodynamic
  /// acceleration scaled to it stays within the planned fraction of the load-factor limit.
  double load_relief_alpha(double alpha_cmd_rad, double alpha_floor_rad, double alpha_flown_rad, double mach,
                           double aero_accel_mps2) const;

 private:
  const OnboardModels* models_ = nullptr;
  const TrackerParams* params_ = nullptr;
  TrackerLimits limits_;
  bool pullout_arrested_ = false;  // the descent of the capture has been arrested (guard off)
};

}  // namespace reentry::fsw
