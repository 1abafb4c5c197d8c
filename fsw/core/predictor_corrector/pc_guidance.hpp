// The guidance rules of the predictor-corrector law, shared by the prediction (planner thread)
// and the cycle (GNC thread) so that what is predicted is what is flown:
//   - the path-constraint drag limit: the largest drag at which heat flux, load factor, q and
//     q alpha stay within the planned fraction of their limits at the present speed and alpha;
//   - the bank magnitude: the base bank with altitude-rate damping (Lu 2014),
//     L cos(sigma) = L cos(sigma_base) - k (hdot - hdot_ref), bounded above by the constraint
//     bound (Lu 2014: a least altitude rate from the drag limit over a horizon tau, held by an
//     altitude-rate law) and by a predictive pull-out guard (a wings-level pull-out started after
//     the roll from the bank flown would bottom out above the drag limit: full lift);
//   - the lateral logic: the bank sign is reversed when the heading leaves a corridor about the
//     target heading of a vector field onto the arrival line (the great circle through the aim
//     point on the required TAEM heading), the corridor narrowing linearly in energy.
// No heap, no exceptions, bounded loops.
#pragma once

#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "predictor_corrector/pc_params.hpp"

namespace reentry::fsw {

/// Path limits as the law applies them (infinite or zero: not constrained).
struct PcLimits {
  double heat_flux_max_Wpm2 = 0.0;
  double q_max_Pa = 0.0;
  double q_alpha_max_Pa_rad = 0.0;
  double load_factor_max_mps2 = 0.0;
  double margin = 0.97;
};
/// The mission's limits times `margin`; the drag-form limits (q, q alpha, heat flux: the sensed
/// drag turned into q or density through the on-board C_D S/m) also lowered so that their drag
/// limit falls by the share `drag_uncertainty` the on-board C_D S/m may overstate the vehicle's
/// (q-type limits times 1 - u, heat flux times sqrt(1 - u): q ~ sqrt(rho)). Load factor, sensed
/// directly, keeps the margin alone.
PcLimits pc_limits_from(const PathLimits& limits, double margin, double drag_uncertainty);

/// Largest drag acceleration at which every limit holds within its margin at speed v, alpha and
/// coefficients (cl, cd) of the present Mach; load factor as hypot(L, D) (>= the body-normal one).
/// 1e300 when nothing is constrained.
double constraint_drag_limit_mps2(const OnboardModels& models, const PcLimits& limits, double v_mps, double alpha_rad,
                                  double cl, double cd);
/// d ln(D_lim)/dt at speed v falling at drag D (coefficients held), over one second.
double constraint_drag_limit_rate_ps(const OnboardModels& models, const PcLimits& limits, double v_mps, double drag_mps2,
                                     double alpha_rad, double cl, double cd);

/// The terminal phase: over the last terminal_span_fraction of the energy span the bank is blended
/// (weight ramping in) into an altitude-rate law onto the straight line in (E, h) from the
/// present state to the TAEM target, hdot_line = -(h - h_f) D V / (E - E_f) (flight-path angle
/// bounded): L cos(sigma) = need + k_t (hdot_line - hdot).
struct TerminalCommand {
  double weight = 0.0;     // 0 before the phase, 1 after its ramp
  double hdot_mps = 0.0;   // the line's altitude rate
};
struct TerminalAltitude {
  double taem_energy_Jpkg = 0.0;
  double span_Jpkg = 0.0;       // entry-to-TAEM energy span
  double target_altitude_m = 0.0;
  TerminalCommand at(double energy_Jpkg, double altitude_m, double velocity_mps, double drag_mps2,
                     const PredictorCorrectorParams& p) const;
  /// The terminal phase: the last terminal_span_fraction of the span above the TAEM energy
  /// (none when the fraction is 0).
  bool in_phase(double energy_Jpkg, const PredictorCorrectorParams& p) const {
    const double phase = p.terminal_span_fraction * span_Jpkg;
    return phase > 0.0 && energy_Jpkg - taem_energy_Jpkg < phase;
  }
  /// A reversal's lift modulation is flown at this energy (modulation_in_terminal).
  bool modulates(double energy_Jpkg, const PredictorCorrectorParams& p) const {
    return p.modulation_in_terminal != 0 || !in_phase(energy_Jpkg, p);
  }
};

/// What the bank law needs of the present (navigated or predicted) state.
struct BankLawInput {
  double sigma_base_rad = 0.0;   // magnitude of the profile (plan) at this energy
  double sigma_flown_rad = 0.0;  // bank flown now, signed (the pull-out guard rolls out of it)
  double velocity_mps = 0.0;
  double radius_m = 0.0;
  double latitude_rad = 0.0;
  double heading_rad = 0.0;
  double flight_path_rad = 0.0;
  double hdot_ref_mps = 0.0;     // reference altitude rate
  double drag_mps2 = 0.0;
  double lift_mps2 = 0.0;
  double drag_limit_mps2 = 1e300;
  double drag_limit_rate_ps = 0.0;  // d ln(D_lim)/dt along V' = -D (the heat limit rises as V falls)
  double scale_height_m = 7050.0;  // local density scale height -1 / (d ln rho / dh)
  double sigma_rate_radps = 0.0;   // the mission's bank rate limit
  TerminalCommand terminal;        // terminal altitude law (weight 0: none)
  bool skip_phase = false;         // captured below the threshold drag (a shallow entry): lift down allowed
};
struct BankLawOutput {
  double sigma_rad = 0.0;        // magnitude commanded
  double damping_gain_ps = 0.0;  // k
  double hdot_min_mps = -1e300;  // the constraint bound's least altitude rate
  bool bounded = false;          // the constraint bound lowered the bank
  bool pullout_guard = false;    // full lift: the pull-out guard holds
};
BankLawOutput bank_magnitude(const BankLawInput& in, const PredictorCorrectorParams& p);

/// Reversal lift modulation (the tracker's rule, docs/guidance_design.md 6.1, within the band):
/// while the bank flown gives more vertical lift than the command, alpha is lowered so that
/// C_L(alpha') = r C_L(alpha), r = cos|sigma_cmd| / cos(sigma_flown) bounded below by
/// modulation_min_lift_ratio, alpha' in [alpha_min, alpha] (bisection, C_L rising with alpha);
/// only for a roll lasting at least modulation_min_roll_s (2 |sigma| / rate).
double modulated_alpha_rad(const OnboardAero& aero, double alpha_rad, double mach, double sigma_cmd_mag_rad,
                           double sigma_flown_rad, double sigma_rate_radps, double alpha_min_rad,
                           const PredictorCorrectorParams& p);

/// Capture (end of the initial descent, wings level): at the threshold drag, or earlier, from
/// capture_drag_fraction of it, when a wings-level pull-out from here would level off below the
/// threshold (a shallow entry that would skip out: the tracker's rule, docs/guidance_design.md 1.2).
bool capture_due(double drag_mps2, double lift_mps2, double hdot_mps, double need_mps2, double scale_height_m,
                 double threshold_mps2, const PredictorCorrectorParams& p);

/// Load relief (the tracker's rule, docs/guidance_design.md 3.3): alpha lowered, never below
/// alpha_min, until the aerodynamic acceleration q S/m hypot(C_L, C_D)(alpha) stays within the
/// planned load-factor limit (bisection); alpha itself when it already does or nothing is limited.
double load_relief_alpha_rad(const OnboardAero& aero, double alpha_rad, double mach, double q_s_over_m,
                             const PcLimits& limits, double alpha_min_rad);

/// Heat relief of a modulated alpha: with a heat flux that rises as alpha falls (Betts's leading
/// edge, q = C(alpha) sqrt(rho) V^c2), the lowest alpha' in [alpha_mod, alpha] whose heat flux
/// stays within the planned limit, or within the unmodulated alpha's where that is already
/// above it (bisection, C falling with alpha). An alpha-free model (Chapman, 3.5) returns alpha_mod.
double heat_relief_alpha_rad(const OnboardModels& models, double alpha_mod_rad, double alpha_rad, double density_kgpm3,
                             double velocity_mps, const PcLimits& limits);

/// Alpha while a reversal rolls: the lift modulation with its heat relief, one rule for the cycle
/// (density from the sensed drag; 0 when unknown: no relief) and the prediction (its own density).
double reversal_alpha_rad(const OnboardModels& models, double alpha_rad, double mach, double sigma_cmd_mag_rad,
                          double sigma_flown_rad, double sigma_rate_radps, double alpha_min_rad, double density_kgpm3,
                          double velocity_mps, const PcLimits& limits, const PredictorCorrectorParams& p);

/// The altitude-rate damping gain k = 2 zeta sqrt(g_eff / H) at a lift need (g_eff at least a
/// tenth of g0), and the gain k / glide_position_factor of the altitude term that pulls the
/// vehicle onto its reference height (0 without).
double damping_gain_ps(double need_mps2, double scale_height_m, const PredictorCorrectorParams& p);
double position_gain_ps(double need_mps2, double scale_height_m, const PredictorCorrectorParams& p);

/// Altitude rate of the quasi-equilibrium glide at the present speed and heading: the glide's
/// height h from L(h, V) cos(sigma) = need(V) differentiated along V' = -D (Earth-rate term of
/// (2.45)) and the bank's own rate sigma_dot.
double qeg_altitude_rate_mps(double velocity_mps, double radius_m, double latitude_rad, double heading_rad,
                             double drag_mps2, double scale_height_m, double sigma_rad = 0.0,
                             double sigma_dot_radps = 0.0);

/// Where the vehicle stands relative to the aim point and the arrival line (spherical, R_eq).
struct ArrivalGeometry {
  double range_m = 0.0;           // great-circle distance to the aim point
  double along_m = 0.0;           // along the arrival line to the aim point (> 0: still to go)
  double cross_m = 0.0;           // from the line (> 0: the line is to the right)
  double line_heading_rad = 0.0;  // heading of the arrival line at the vehicle
  double target_heading_rad = 0.0;  // vector field onto the line
};

/// The lateral logic's state (carried by the cycle and by each prediction).
struct PcLateralState {
  int sign = 0;                  // bank side (0: none chosen yet)
  bool final_done = false;       // the final reversal has started
  bool correction_done = false;  // the one correction reversal after it has started
  bool reversing = false;        // a reversal's roll is under way (until the bank settles)
};

/// What the lateral logic needs of the present state.
struct PcLateralInput {
  double energy_Jpkg = 0.0;
  double velocity_mps = 0.0;
  double heading_rad = 0.0;
  double flight_path_rad = 0.0;
  double drag_mps2 = 0.0;
  double lift_mps2 = 0.0;
  double sigma_mag_rad = 0.0;    // bank magnitude commanded now
  double sigma_flown_rad = 0.0;  // bank flown now (signed)
  bool hold_side = false;        // the plan's reversal hold: no corridor or capture-guard reversal now
  bool capture_waits = false;    // the capture guard waits for the plan's reversal (the corridor does not)
};

class PcLateral {
 public:
  void init(const PredictorCorrectorParams& params, const TaemTarget& taem, double sigma_rate_max_radps,
            double entry_energy_Jpkg, double taem_energy_Jpkg);
  void bind(const PredictorCorrectorParams& params) { params_ = &params; }
  /// Geometry and the target heading; the approach angle is bounded by the turn the vehicle
  /// can make at its lift and bank magnitude (0: unbounded).
  ArrivalGeometry geometry(double latitude_rad, double longitude_rad, double velocity_mps, double flight_path_rad,
                           double lift_mps2, double sigma_mag_rad) const;
  /// Corridor half-width at an energy (linear from entry to TAEM, held outside).
  double half_width_rad(double energy_Jpkg) const;
  /// The capture guard's overshoot limit: capture_overshoot_m, or capture_overshoot_range_fraction
  /// of the distance to go along the line when that is more.
  double capture_limit_m(const ArrivalGeometry& g) const;
  /// Capture guard timed by the plan (capture_waits_for_plan): while the plan's first reversal lies
  /// below the present energy, the capture guard's reversal waits for it.
  bool capture_waits_for_plan(double energy_Jpkg, double plan_reversal_energy_Jpkg) const;
  /// The bank side (st.sign): none yet -> towards the target heading; in the final window the
  /// final and correction reversals; else reversed when the heading leaves the corridor on the
  /// side the bank turns to. Never while a roll is still under way.
  void decide(PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g) const;
  /// Time to the TAEM energy at the present drag, the speed falling linearly to the TAEM speed.
  double time_to_go_s(const PcLateralInput& in) const;
  const TaemTarget& taem() const { return taem_; }

 private:
  void decide_sign(PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g) const;
  /// Overshoot past the line of a turn away started now; 0 within limit_m of the line.
  double capture_overshoot_m(const PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g,
                             double limit_m) const;
  bool final_balance_passed(const PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g,
                            double t_go_s) const;

  const PredictorCorrectorParams* params_ = nullptr;
  double sigma_rate_max_radps_ = 0.0;
  TaemTarget taem_{};
  double entry_energy_Jpkg_ = 0.0;
  double taem_energy_Jpkg_ = 0.0;
};

}  // namespace reentry::fsw
