// Drag and heading tracker after EAGLE (thesis §3.2.3, Saraf et al. 2003, Tu et al. 2000).
//
//   drag loop    (3.12)  e'' + c_E e' + k_E e + k_I int e dt = 0, e = D - D_ref, in energy
//                        with the time-domain zeta/omega converted by (3.14)-(3.18) and the
//                        natural frequency scheduled on dynamic pressure (3.13);
//                        D'' = a + b u_D (3.10) gives u_D = (L/D) cos(sigma), sigma_D (3.20);
//   heading loop (3.19)  chi' error dynamics through (3.11) gives u_chi, sigma_chi (3.21);
//   bank sign    (3.22) with w = 1: sigma = s sigma_D; the heading loop's sigma_chi is reported
//                        only. The sign s is the plan's (one reversal, §7.4) until the lateral
//                        corridor phase (last 30 % of the energy span), then a heading corridor
//                        around a vector field onto the arrival great circle (the circle through
//                        the aim point on the required TAEM heading), 6 -> 3 deg, with one last
//                        reversal timed so that the heading at TAEM is the target heading
//                        and, if the turn it leaves overshoots, one correction reversal;
//                        farther than 15 km from the line and banked lift up, a capture
//                        guard turns away as soon as a turn away started later would carry
//                        the vehicle more than 15 km past the line;
//   reversal             sign changes are flown open loop at the maximum bank rate (the rate
//                        filter after the tracker limits the rate), drag integrator frozen;
//                        alpha is lowered meanwhile so that C_L cos(sigma(t)) stays C_L cos(sigma0)
//                        (the roll through wings level would otherwise leave a climb that the
//                        drag loop cannot remove before TAEM; at most 15 deg in the final
//                        reversal, 6 deg in the corridor reversals before it, whose drag deficit
//                        the range control can correct only late), and the range control allows
//                        for the drag this costs in the final reversal;
//   terminal range       over the last 25 % of the energy span the drag reference gets a
//                        range-to-go increment (quadratic in energy) vanishing at TAEM, and the
//                        final drag takes as much of the sensed drag-to-model ratio as keeps
//                        the TAEM state inside the inner half of its altitude band and inside
//                        its Mach band (the rest of the ratio moves the TAEM altitude); the
//                        increment stays within the plan's path-constraint bound; the drag
//                        loop's frequency is at least 1.5 / t_go (at most 3 omega0) and, in
//                        the final-reversal window, the bank stays within 90 deg (no lift
//                        down), so that the drag error is removed before TAEM.
// Before the first plan, and until the sensed drag passes the initial-descent threshold,
// the tracker holds the profile alpha and wings level (flight practice, DESIGN §6).
// Gains are derived from vehicle-independent physics (see derive_gains) unless the mission
// overrides them. No heap, no exceptions, bounded loops.
#pragma once

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::fsw {

struct TrackerGains {
  double zeta = 0.7071067811865476;     // time-domain damping ratio of the drag loop
  double omega0_radps = 0.0;            // time-domain natural frequency at q = q_ref
  double k_integral = 0.0;              // time-domain integral gain [1/s^3]
  double k_heading = 0.0;               // heading loop gain factor k2 of (3.19)
  double k_heading_integral = 0.0;      // k3 of (3.19)
};

struct TrackerOutput {
  double alpha_rad = 0.0;
  double sigma_rad = 0.0;
  Phase phase = Phase::kInitialDescent;
  double drag_ref_mps2 = 0.0;
  double drag_err_mps2 = 0.0;      // D - D_ref
  double heading_err_rad = 0.0;    // chi - chi_ref
  double sigma_d_rad = 0.0;        // drag-loop bank magnitude (3.20)
  double sigma_chi_rad = 0.0;      // heading-loop bank (3.21)
  double u_drag = 0.0;             // commanded vertical L/D
  bool saturated = false;          // |u| exceeded the available L/D
  double lift_over_drag_scale = 1.0;  // sensed L/D over the model's at the commanded alpha, filtered
};

/// Drag at the bottom of a wings-level pull-out from drag D sinking at h_dot < 0, speed held
/// and the air exponential with scale height H (vertical energy balance, see the .cpp);
/// D itself when not sinking, kNoPullOut_mps2 when the lift cannot arrest the sink.
inline constexpr double kNoPullOut_mps2 = 1e6;
double wings_level_pullout_drag_mps2(double drag_mps2, double lift_over_drag, double h_dot_mps, double g_eff_mps2,
                                     double scale_height_m);
/// The same pull-out started after a roll from bank sigma0 to wings level lasting t_roll:
/// the roll is flown with the mean vertical lift L sin(sigma0) / sigma0 of a uniform roll at
/// the present lift and constant vertical acceleration (conservative: the lift growing with
/// the density over the roll is left out), then the wings-level pull-out.
double pullout_drag_after_roll_mps2(double drag_mps2, double lift_over_drag, double h_dot_mps, double g_eff_mps2,
                                    double scale_height_m, double sigma0_rad, double t_roll_s);

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
};
struct FinalTurnState {
  double heading_err_rad = 0.0;
  double cross_track_m = 0.0;
  double overshoot_m = 0.0;  // farthest excursion past the line on the side opposite the start (>= 0)
};
FinalTurnState predict_final_turn(const FinalTurnInput& in);

/// Lower bound on the drag loop's natural frequency in the terminal phase: 1.5 / t_go, so
/// that the loop's time constant 1 / (zeta omega) stays within the time to go, at most three
/// times omega0 (the bank-rate limit bounds what a faster loop can fly).
double terminal_omega_floor_radps(double omega0_radps, double t_go_s);

/// The documented gain rule (no per-vehicle tuning):
///  - omega0 = 2 sqrt(g0 / H), twice the natural frequency sqrt(g/H) of the altitude mode of a
///    glide in an atmosphere of scale height H = 7050 m (about 0.075 rad/s, period 85 s): fast
///    enough to reject density errors, slow against the GNC rate and the bank-rate limit;
///  - zeta = 1/sqrt(2) (no resonance peak, thesis §8.3);
///  - integral gain omega0^3 / 20 (integral pole a decade below the loop);
///  - heading loop k2 = 1 with the scheduled omega, k3 = 0;
///  - drag-loop bandwidth scheduled (3.13) with q_ref = 0.3 of the plan's largest q.
/// Non-zero mission values (guidance.zeta, omega0_radps, ...) override the rule.
TrackerGains derive_gains(const config::Mission& mission);

class EntryTracker {
 public:
  Status init(const config::Mission& mission);
  /// Copies the profile (no allocation); resets the integrators when the sequence changes.
  void set_profile(const ReferenceProfile& profile);
  /// alpha and bank out of the command rate filters last cycle (what the vehicle flies, up to
  /// the attitude lag): the sensed accelerations are referred to the reference alpha with
  /// them, and the reversal modulation and the load relief act on them. Not given: the
  /// tracker's own last commands.
  void set_flown_attitude(double alpha_rad, double sigma_rad) {
    flown_alpha_rad_ = alpha_rad;
    flown_sigma_rad_ = sigma_rad;
  }
  bool has_profile() const { return has_profile_; }
  /// Factor on the planned final drag in the terminal phase: the part of the sensed
  /// drag-to-model ratio K that keeps the TAEM state inside its altitude and Mach bands.
  double final_drag_factor() const;
  Status step(const RelativeState& s, double dt_s, TrackerOutput& out);

  const TrackerGains& gains() const { return gains_; }
  const ReferenceProfile& profile() const { return profile_; }
  /// Start of the terminal phase (range control in the tracker).
  double terminal_energy_Jpkg() const { return terminal_e_norm_ * entry_energy_Jpkg_; }

  /// omega(q) of (3.13): omega0 [2 (q/q_ref) - (q/q_ref)^2] below q_ref, omega0 above.
  static double scheduled_omega(double omega0, double q_Pa, double q_ref_Pa);

 private:
  struct RefPoint {
    double drag = 0, drag_prime = 0, drag_second = 0, a = 0, b = 0, gamma = 0, alpha = 0, alpha_prime = 0;
    double lod = 0, sigma = 0, heading = 0, heading_prime = 0, q = 0, velocity = 0, radius = 0, drag_max = 0;
  };
  RefPoint reference_at(double energy_Jpkg);
  struct TerminalRange {
    double range_m = -1.0;     // range to the end of the profile (C.2); < 0: undefined
    double sensitivity = 0.0;  // d range / d c of the terminal drag increment [m per m/s^2]
  };
  TerminalRange terminal_range(double energy, double drag_here, double e_t, double final_factor) const;

  struct LateralTarget {
    double range_m = 0.0;       // great-circle distance to the aim point
    double bearing_rad = 0.0;   // line of sight to the aim point
    double heading_rad = 0.0;   // heading of the arc that arrives on the required heading
    double offset_rad = 0.0;    // eps: bearing aim->vehicle minus the reversed arrival heading
    double along_track_m = 0.0; // range to go along the arrival line (< 0: aim point passed)
    double cross_track_m = 0.0; // offset from the arrival line (> 0: the line is to the right)
    double line_heading_rad = 0.0;  // heading of the arrival line at the vehicle (not wrapped)
  };
  LateralTarget lateral_target(const RelativeState& s) const;
  double flown_bank_rad() const;
  /// Within the last kFinalReversalWindow reversal durations before TAEM (mean bank).
  bool in_final_reversal_window(double t_go_s) const;
  bool modulation_allowed(double drag_ref, double drag_max) const;
  double modulated_alpha(double alpha_rad, double mach, double lift_ratio, double max_rad) const;
  double load_relief_alpha(double alpha_cmd_rad, double alpha_floor_rad, double alpha_flown_rad, double mach,
                           double aero_accel_mps2) const;
  double reversal_lift_ratio(double sigma0_rad, double t_rel_s) const;
  double reversal_range_extension_m(const RelativeState& s, double alpha_rad, double sigma0_rad) const;
  void update_drag_scale(const RelativeState& s, double alpha_rad, double dt_s);
  void update_lod_scale(const RelativeState& s, double alpha_rad, double dt_s);
  double lift_up_pullout_drag_mps2(const RelativeState& s, double sigma_now_rad = 0.0) const;
  double constraint_drag_limit_mps2(const RelativeState& s, double alpha_rad, double cd) const;
  /// The sensed drag and lift as they would be at alpha_rad (table C_D, C_L ratios to the flown alpha).
  RelativeState referred_to_alpha(const RelativeState& s, double alpha_flown_rad, double alpha_rad) const;

  OnboardModels models_;
  AlphaProfile alpha_profile_;
  TrackerGains gains_;
  double entry_energy_Jpkg_ = 0.0;
  double taem_energy_Jpkg_ = 0.0;
  double initial_descent_drag_mps2_ = 0.0;
  double sigma_rate_max_radps_ = 0.0;
  double alpha_max_rad_ = 0.0;
  double heat_flux_max_Wpm2_ = 0.0;  // path-constraint limits (0: none)
  double q_alpha_max_Pa_rad_ = 0.0;
  double q_max_Pa_ = 0.0;
  double load_factor_max_mps2_ = 0.0;
  double q_ref_Pa_ = 1.0;
  double terminal_e_norm_ = 0.0;    // terminal phase below this normalised energy
  double lateral_e_norm_ = 0.0;     // lateral heading corridor below this normalised energy
  bool initialised_ = false;

  ReferenceProfile profile_;
  bool has_profile_ = false;
  int hint_ = 0;
  bool captured_ = false;           // initial descent over
  bool first_pullout_done_ = false; // the descent of the capture has been arrested (guard off)
  double drag_integral_ = 0.0;      // int (D - D_ref) dt
  double heading_integral_ = 0.0;   // int (chi_ref - chi) dE
  double drag_scale_ = 1.0;         // sensed drag / model drag, filtered
  double lod_scale_ = 1.0;          // sensed L/D / model L/D, filtered
  double last_alpha_cmd_rad_ = 0.0; // alpha commanded in the previous cycle
  double last_sigma_d_rad_ = 0.0;   // bank magnitude commanded in the previous cycle
  double flown_alpha_rad_ = -1.0;   // alpha out of the rate filter (< 0: attitude not given)
  double flown_sigma_rad_ = 0.0;    // bank out of the rate filter (given with the alpha)
  double mean_sigma_d_rad_ = -1.0;  // bank magnitude averaged for the final reversal (< 0: unset)
  config::TaemInterface taem_{};    // TAEM aim point, arrival heading, speed and bands (mission)
  bool final_reversal_done_ = false;
  bool final_correction_done_ = false;  // the one reversal allowed after the final one
  int last_sign_ = 0;
  double reversal_until_t_s_ = -1.0;
  double reversal_start_t_s_ = -1.0;  // start of the last reversal
  double reversal_sigma0_rad_ = 0.0;  // bank magnitude at its start
  bool reversal_ends_in_final_window_ = false;  // judged at its start on the time to go
};

}  // namespace reentry::fsw
