// Tunables of the drag/heading tracker (thesis §3.2.3 and the rules of docs/guidance_design.md).
//
// Every field is SI with its unit in the name. The defaults are the values the reference
// missions fly; a mission may set any field in its [guidance.tracker] table under the key that
// visit_tracker_params names (the key carries the unit of the file, e.g. `_deg`), and the value
// must lie in the documented range given there. docs/guidance_design.md has, for each, the rule
// it belongs to, its equation and the measurement behind the default.
#pragma once

#include <cmath>

#include "params/param_visitor.hpp"
#include "physics/earth_constants.hpp"

namespace reentry::fsw {

/// Half-step of the tracker's central difference of d(ln rho)/dr on the on-board atmosphere
/// ((7.14)-(7.16)) at the sensed altitude: the drag loop's D' and the pull-out's local scale
/// height (the planner takes its own step for its grid).
inline constexpr double kTrackerDensityGradientStep_m = 100.0;
/// Bisection steps of the alpha searches (load relief, reversal modulation): 2^-30 of the
/// searched alpha interval.
inline constexpr int kAlphaBisectionSteps = 30;

struct TrackerParams {
  // Drag loop (3.12)-(3.18). Zero omega0 / k_integral: derived by derive_gains.
  double zeta = 0.7071067811865476;          // damping ratio of the drag-error dynamics (3.12)
  double omega0_radps = 0.0;                 // natural frequency at q >= q_ref (3.13)
  double k_integral_ps3 = 0.0;               // integral gain of (3.12)
  double gain_frequency_factor = 2.0;        // derive_gains: omega0 = factor sqrt(g0 / H)
  double gain_integral_pole_ratio = 20.0;    // derive_gains: k_I = omega0^3 / ratio
  double q_ref_fraction = 0.3;               // (3.13): full bandwidth from this share of the plan's largest q
  double integral_bias_max_fraction = 0.2;   // anti-windup: the integral's drag bias at most this share of D_ref
  double terminal_settling = 1.5;            // terminal phase: omega >= settling / t_go ...
  double terminal_omega_max_factor = 3.0;    // ... and at most this many omega0
  // Initial descent and capture.
  double initial_descent_drag_mps2 = 0.05 * physics::kStandardGravity_mps2;  // from [guidance] initial_descent_drag_mps2 (executive too)
  double capture_drag_fraction = 0.1;        // shallow-entry capture from this share of the threshold drag
  double capture_lookahead_energy_fraction = 0.02;  // reference compared at E - fraction E_entry
  double pullout_complete_ratio = 1.05;      // pull-out complete when D would rise less than this factor
  double roll_lag_s = 1.0;                   // bank filter lag before a roll starts (pull-out, final turn)
  int pullout_guard_every_descent = 0;       // 1: the pull-out guard judges every descent, not only the entry's
  // Lateral logic: heading corridor, arrival-line field, capture guard, final reversal.
  double corridor_half_width_max_rad = 6.0 * M_PI / 180.0;  // at the corridor start ...
  double corridor_half_width_min_rad = 3.0 * M_PI / 180.0;  // ... narrowing linearly to TAEM
  double approach_angle_max_rad = 45.0 * M_PI / 180.0;      // vector field chi_inf
  double cross_track_scale_m = 30000.0;      // vector field y_s
  double approach_turn_factor = 1.5;         // approach angle <= sqrt(2 k |y| / R_turn)
  double aim_min_range_m = 1000.0;           // offset angle undefined closer than this
  double capture_overshoot_m = 15000.0;      // capture guard: largest accepted overshoot past the line
  double final_reversal_window = 2.0;        // final-reversal window, in reversal durations 2 sigma / rate
  double mean_bank_time_constant_s = 10.0;   // bank averaging for the final-reversal timing
  double bank_settled_rad = 5.0 * M_PI / 180.0;  // flown bank this close to the command: roll over
  int final_turn_steps = 50;                 // midpoint steps of the final-turn prediction
  // Reversal execution: alpha modulation.
  double final_modulation_max_rad = 15.0 * M_PI / 180.0;    // in the final reversal (and load-relief floor)
  double corridor_modulation_max_rad = 6.0 * M_PI / 180.0;  // in the corridor reversals before it
  double modulation_min_lift_ratio = 0.3;    // lift kept at no less than this share of the profile's
  double modulation_lead_s = 1.0;            // roll model led by the filter lag
  double modulation_bound_margin = 0.85;     // only while D_ref < margin D_max K
  // Terminal range control.
  double terminal_increment_max_fraction = 0.8;  // |c| <= fraction D_ref
  double terminal_min_range_m = 5000.0;      // closer than this to the aim point the increment is zero
  int final_factor_samples = 20;             // scan of the final-drag factor between 1 and K
  double final_altitude_band_depth = 0.5;    // predicted TAEM altitude inside this depth of its band
  // Estimation of the sensed drag and L/D ratios.
  double ratio_time_constant_s = 20.0;       // first-order filter of both ratios
  double drag_ratio_min = 0.5;
  double drag_ratio_max = 2.0;
  double lod_ratio_min = 0.5;
  double lod_ratio_max = 1.5;
  double min_drag_mps2 = 1e-3;               // below this the drag (and L/D) is not measurable
  double min_lift_over_drag = 1e-3;          // below this the sensed L/D is not used
  // Plausibility of the navigated state (beyond: rejected, never pushed through the loop).
  double max_speed_mps = 12000.0;
  double max_accel_mps2 = 100.0 * physics::kStandardGravity_mps2;
};

/// Visits every field a mission file may set, with its key, unit and documented range: the
/// loader's validation, `reentry_config_check --params` and the tests share this one list.
template <class Params, class Visitor>
void visit_tracker_params(Params& p, Visitor&& v) {
  using U = ParamUnit;
  v("zeta", p.zeta, U::kNone, 0.05, 5.0, "drag-loop damping ratio (3.12)");
  v("omega0_radps", p.omega0_radps, U::kNone, 0.0, 2.0, "drag-loop natural frequency (3.13); 0: derive_gains");
  v("k_integral_ps3", p.k_integral_ps3, U::kNone, 0.0, 1.0, "integral gain (3.12); 0: derive_gains");
  v("gain_frequency_factor", p.gain_frequency_factor, U::kNone, 0.5, 10.0, "derive_gains: omega0 / sqrt(g0/H)");
  v("gain_integral_pole_ratio", p.gain_integral_pole_ratio, U::kNone, 2.0, 1000.0, "derive_gains: omega0^3 / k_I");
  v("q_ref_fraction", p.q_ref_fraction, U::kNone, 0.01, 1.0, "(3.13) q_ref over the plan's largest q");
  v("integral_bias_max_fraction", p.integral_bias_max_fraction, U::kNone, 0.0, 1.0, "integral drag bias bound / D_ref");
  v("terminal_settling", p.terminal_settling, U::kNone, 0.0, 10.0, "terminal omega floor: settling / t_go");
  v("terminal_omega_max_factor", p.terminal_omega_max_factor, U::kNone, 1.0, 10.0, "terminal omega cap / omega0");
  v("capture_drag_fraction", p.capture_drag_fraction, U::kNone, 0.0, 1.0, "shallow capture from this share of the threshold drag");
  v("capture_lookahead_energy_fraction", p.capture_lookahead_energy_fraction, U::kNone, 0.0, 0.2, "capture reference lookahead / E_entry");
  v("pullout_complete_ratio", p.pullout_complete_ratio, U::kNone, 1.0, 2.0, "pull-out complete below this drag rise");
  v("roll_lag_s", p.roll_lag_s, U::kNone, 0.0, 10.0, "bank filter lag before a roll");
  v("pullout_guard_every_descent", p.pullout_guard_every_descent, U::kNone, 0, 1,
    "1: pull-out guard on every descent (0: until the entry pull-out is complete)");
  v("corridor_half_width_max_deg", p.corridor_half_width_max_rad, U::kDeg, 0.5, 45.0, "heading corridor at its start");
  v("corridor_half_width_min_deg", p.corridor_half_width_min_rad, U::kDeg, 0.5, 45.0, "heading corridor at TAEM");
  v("approach_angle_max_deg", p.approach_angle_max_rad, U::kDeg, 1.0, 90.0, "arrival-line field chi_inf");
  v("cross_track_scale_m", p.cross_track_scale_m, U::kNone, 100.0, 1e6, "arrival-line field y_s");
  v("approach_turn_factor", p.approach_turn_factor, U::kNone, 0.1, 10.0, "approach-angle turn bound k");
  v("aim_min_range_m", p.aim_min_range_m, U::kNone, 0.0, 1e5, "offset angle undefined closer than this");
  v("capture_overshoot_m", p.capture_overshoot_m, U::kNone, 0.0, 1e6, "capture guard overshoot limit");
  v("final_reversal_window", p.final_reversal_window, U::kNone, 0.5, 10.0, "final-reversal window / reversal time");
  v("mean_bank_time_constant_s", p.mean_bank_time_constant_s, U::kNone, 0.1, 100.0, "bank averaging time constant");
  v("bank_settled_deg", p.bank_settled_rad, U::kDeg, 0.1, 30.0, "bank settled on its command within this");
  v("final_turn_steps", p.final_turn_steps, U::kNone, 5, 500, "final-turn prediction steps");
  v("final_modulation_max_deg", p.final_modulation_max_rad, U::kDeg, 0.0, 30.0, "alpha modulation in the final reversal");
  v("corridor_modulation_max_deg", p.corridor_modulation_max_rad, U::kDeg, 0.0, 30.0, "alpha modulation in corridor reversals");
  v("modulation_min_lift_ratio", p.modulation_min_lift_ratio, U::kNone, 0.0, 1.0, "least lift kept by the modulation");
  v("modulation_lead_s", p.modulation_lead_s, U::kNone, 0.0, 10.0, "modulation roll-model lead");
  v("modulation_bound_margin", p.modulation_bound_margin, U::kNone, 0.0, 1.0, "modulation only below this share of D_max K");
  v("terminal_increment_max_fraction", p.terminal_increment_max_fraction, U::kNone, 0.0, 2.0, "terminal drag increment bound / D_ref");
  v("terminal_min_range_m", p.terminal_min_range_m, U::kNone, 0.0, 1e5, "terminal increment zero closer than this");
  v("final_factor_samples", p.final_factor_samples, U::kNone, 1, 1000, "final-drag factor scan samples");
  v("final_altitude_band_depth", p.final_altitude_band_depth, U::kNone, 0.0, 1.0, "TAEM altitude kept inside this band depth");
  v("ratio_time_constant_s", p.ratio_time_constant_s, U::kNone, 0.1, 1000.0, "drag and L/D ratio filter time constant");
  v("drag_ratio_min", p.drag_ratio_min, U::kNone, 0.1, 1.0, "lower bound of the sensed drag ratio K");
  v("drag_ratio_max", p.drag_ratio_max, U::kNone, 1.0, 10.0, "upper bound of the sensed drag ratio K");
  v("lod_ratio_min", p.lod_ratio_min, U::kNone, 0.1, 1.0, "lower bound of the sensed L/D ratio");
  v("lod_ratio_max", p.lod_ratio_max, U::kNone, 1.0, 10.0, "upper bound of the sensed L/D ratio");
  v("min_drag_mps2", p.min_drag_mps2, U::kNone, 1e-6, 1.0, "drag below this is not measured");
  v("min_lift_over_drag", p.min_lift_over_drag, U::kNone, 1e-6, 0.5, "sensed L/D below this is not used");
  v("max_speed_mps", p.max_speed_mps, U::kNone, 1000.0, 20000.0, "navigated speed beyond this is rejected");
  v("max_accel_mps2", p.max_accel_mps2, U::kNone, 10.0, 1e4, "sensed acceleration beyond this is rejected");
}

/// Relations between fields that single ranges cannot state: the key of the first field that
/// breaks one (nullptr when all hold).
inline const char* tracker_params_inconsistency(const TrackerParams& p) {
  if (!(p.corridor_half_width_min_rad <= p.corridor_half_width_max_rad)) return "corridor_half_width_min_deg";
  if (!(p.drag_ratio_min < p.drag_ratio_max)) return "drag_ratio_min";
  if (!(p.lod_ratio_min < p.lod_ratio_max)) return "lod_ratio_min";
  if (!(p.corridor_modulation_max_rad <= p.final_modulation_max_rad)) return "corridor_modulation_max_deg";
  if (!(p.initial_descent_drag_mps2 >= 0.0)) return "initial_descent_drag_mps2";
  return nullptr;
}

}  // namespace reentry::fsw
