// Tunables of the numerical predictor-corrector law (FNPEG class: P. Lu, "Entry Guidance: A
// Unified Method", JGCD 37(3), 2014). Every field is SI with its unit in the name; the defaults
// are one set for all vehicles. A mission sets any of them in its [guidance.predictor_corrector]
// table under the key visit_pc_params names (the key carries the unit of the file, `_deg`), within
// the documented range; docs/guidance_design.md section 10 has the rule each belongs to.
#pragma once

#include <cmath>

#include "params/param_visitor.hpp"

namespace reentry::fsw {

struct PredictorCorrectorParams {
  static constexpr int kMaxSteps = 8000;  // capacity bound of one prediction [steps]

  // Predictor: fixed-step RK4 in time on the point-mass equations over the rotating Earth.
  double step_s = 2.0;             // integration step (also the predicted guidance period)
  int max_steps = 4000;            // one prediction ends (time-out) after this many steps
  // Corrector: safeguarded secant on sigma_0 (Lu 2014), step halving, bounded predictions.
  int max_predictions = 12;        // predictions per plan
  double miss_tol_m = 500.0;       // |along-track miss at TAEM| below this: converged
  double control_tol_rad = 0.02 * M_PI / 180.0;  // a bracket narrower than this ends the search
  int altitude_predictions = 4;    // of max_predictions, kept for the TAEM-altitude iterations
  double accept_miss_m = 5000.0;   // a plan out of predictions is still adopted below this miss
  double first_step_rad = 5.0 * M_PI / 180.0;  // secant's second sigma_0 from the first
  double bank_max_rad = 85.0 * M_PI / 180.0;   // largest |sigma| of the profile and of a command
  double bank_min_rad = 0.0;       // least |sigma| commanded after capture
  double bank_damped_max_rad = 150.0 * M_PI / 180.0;  // the damping's largest bank (lift down against a skip)
  // Alpha band: alpha stays within alpha_band of the mission's profile (the oracle judges with the
  // same band, tools/mc --oracle-alpha-band). The corrector's one free parameter also moves alpha
  // inside it (BankProfile): a range-short flight keeps lateral_bank and flies the band's L/D
  // first; a range-long one at bank_max raises alpha. alpha_control_scale: radians of the
  // control per radian of alpha.
  double alpha_band_rad = 3.0 * M_PI / 180.0;
  double lateral_bank_rad = 45.0 * M_PI / 180.0;
  double alpha_control_scale = 3.0;
  // Reversal lift modulation inside the band (modulated_alpha_rad): lift kept at no less than this
  // share of the profile's.
  double modulation_min_lift_ratio = 0.3;
  double modulation_min_roll_s = 20.0;  // only reversals lasting this long are modulated
  // 0: not in the terminal phase (terminal_span_fraction, below), where no plan comes in the last
  // replan_floor_span_fraction of the span and a modulated roll's lower C_D (ds/dE = -1/D)
  // lengthens the flight at energies the last plan put elsewhere; the terminal altitude law then
  // takes the unmodulated roll's climb, which needs the authority to sink back onto the TAEM
  // altitude (a mission that has it sets 0).
  int modulation_in_terminal = 1;
  // Final bank sigma_f of the linear profile: the quasi-equilibrium glide bank at the TAEM state
  // of the target altitude (bounded), or a share of sigma_0.
  double final_bank_max_rad = 80.0 * M_PI / 180.0;
  double final_bank_share = 0.0;   // sigma_f = share sigma_0 + (1 - share) sigma_glide
  int taem_altitude_samples = 60;  // scan of the TAEM altitude band for the target altitude
  // TAEM altitude: while the predicted TAEM altitude misses the target by more than
  // altitude_tol_fraction of the TAEM altitude tolerance, the terminal line's aim is moved by the
  // miss (within the band) and sigma_0 solved again, at most altitude_iterations times per plan;
  // the aim's offset is kept for the next plan.
  int altitude_iterations = 2;
  double altitude_tol_fraction = 0.2;
  // Range by the terminal aim: when sigma_0 is out of reach (the bank bound still long or short,
  // as late in the flight, where the terminal altitude law flies the bank), the terminal line's aim
  // is the range control within the altitudes whose depth in the TAEM altitude and Mach bands is
  // at least 1 - terminal_range_aim_fraction of the target's (a lower line flies denser air: more
  // drag per unit energy, ds/dE = -1/D, a shorter range); secant on the aim, at most
  // terminal_range_predictions more predictions per plan (after capture). 0: the aim stays on the
  // target.
  double terminal_range_aim_fraction = 0.6;
  int terminal_range_predictions = 4;
  // Range by the reversal hold: still long after that (the constraint bound holds the vehicle
  // up), the bank's side is held without corridor reversals down to an energy between the TAEM
  // energy and now, so the turn carries the heading off the line of sight (a longer ground
  // track); a march and regula falsi on that energy, at most reversal_hold_predictions more
  // predictions per plan (after capture). 0: no hold.
  int reversal_hold_predictions = 6;
  // Terminal altitude: over the last terminal_span_fraction of the entry-to-TAEM energy span the
  // bank blends (weight ramping in over terminal_ramp_fraction of that span) into the altitude-
  // rate law L cos(sigma) = need + k_t (hdot_line - hdot) onto the straight line in (E, h) from
  // the present state to the target TAEM altitude, hdot_line = -(h - h_TAEM) D V / (E - E_TAEM),
  // its flight-path angle within [terminal_gamma_min, terminal_gamma_max].
  double terminal_span_fraction = 0.15;
  double terminal_ramp_fraction = 0.3;
  double terminal_gamma_min_rad = -20.0 * M_PI / 180.0;
  double terminal_gamma_max_rad = 0.0;
  double terminal_rate_gain_ps = 0.2;  // k_t of the terminal altitude-rate law [1/s]
  // Altitude-rate damping: L cos(sigma) = L cos(sigma_base) - k (hdot - hdot_ref),
  // k = 2 zeta sqrt(g_eff / H) (the glide's altitude mode, g_eff >= a tenth of g0).
  double damping_ratio = 0.7;
  // The reference altitude rate also pulls the vehicle onto its reference height with gain
  // k / glide_position_factor (prediction: the glide's height h + H ln(L cos(sigma) / need); cycle:
  // the plan's height at the energy); 0: rate damping only (the glide's lag persists).
  double glide_position_factor = 2.0;
  // Path constraints: planned fraction of every limit (heat flux, load factor, q, q alpha).
  double constraint_margin = 0.97;
  // Share by which the on-board C_D S/m may overstate the vehicle's (aero and mass knowledge):
  // the q, q alpha and heat-flux limits, met through the sensed drag, lowered so that their drag
  // limits fall by it (pc_limits_from).
  double drag_model_uncertainty = 0.06;
  double capture_drag_fraction = 0.1;  // a shallow entry is captured from this share of the threshold drag
  double roll_lag_s = 1.0;         // pull-out guard: bank filter lag before the roll to wings level
  double pullout_glide_need = 0.5; // pull-out guard: the glide's sink is discounted fully from this need / g0
  // Constraint bound: the drag approaches its limit no faster than ln(D_lim / D) / tau
  // (pc_guidance.cpp), held by an altitude-rate law of gain k_c.
  double constraint_time_s = 30.0;
  double constraint_gain_ps = 0.1;
  // Lateral logic: bank sign reversed when the heading leaves a corridor about the target
  // heading of a vector field onto the arrival line, narrowing linearly in energy.
  double corridor_entry_rad = 12.0 * M_PI / 180.0;  // half-width at the entry energy
  double corridor_taem_rad = 4.0 * M_PI / 180.0;    // half-width at the TAEM energy
  double approach_angle_max_rad = 45.0 * M_PI / 180.0;  // vector field chi_inf
  double cross_track_scale_m = 30000.0;  // vector field y_s
  double approach_turn_factor = 1.5;     // approach angle <= sqrt(2 k |y| / R_turn)
  double sight_line_factor = 2.0;        // approach angle <= n |eps| (eps: line of sight off the line)
  double aim_min_range_m = 1000.0;       // offset angle undefined closer than this
  // Capture guard: farther than capture_overshoot_m from the line, a bank towards it is flown only
  // while a turn away started now (roll, then the circular arc of the present turn) would stop
  // within capture_overshoot_m past it.
  double capture_overshoot_m = 15000.0;
  // The guard's limit grows with the distance still to fly along the line: at least
  // capture_overshoot_range_fraction of it (0: the fixed limit alone).
  double capture_overshoot_range_fraction = 0.0;
  // Capture guard timed by the plan (cycle, outside the terminal phase; 1: on): while the plan's
  // first reversal lies below the present energy, the capture guard does not reverse (the corridor
  // still does). The prediction flies the cycle's capture guard, so the plan's first reversal is
  // where its test fires on the predicted state; the flown state (above the plan, banking more)
  // can fire it earlier, at another drag, where the roll's lift-up pulse lofts the vehicle
  // differently from the prediction.
  int capture_waits_for_plan = 0;
  // Final reversal (the tracker's rule, docs/guidance_design.md 5.4): within the last
  // final_reversal_window reversal durations 2 |sigma| / rate before TAEM no corridor reversal;
  // the last one starts when the TAEM state it leads to balances heading error and cross-track
  // offset (tolerances as weights), and one correction reversal may follow once the bank is settled.
  double final_reversal_window = 2.0;
  int final_turn_steps = 50;             // midpoint steps of the final-turn prediction
  double bank_settled_rad = 5.0 * M_PI / 180.0;
  double final_keep_fraction = 0.3;  // no final reversal while the present turn ends within this share of the tolerances
  // Plan schedule (the executive's): period, and no plans in the last fraction of the span.
  double replan_period_s = 10.0;
  double replan_floor_span_fraction = 0.03;
  // Sensed drag ratio K (density) of a plan's state, bounded.
  double drag_ratio_min = 0.5;
  double drag_ratio_max = 2.0;
  double lod_ratio_min = 0.5;      // accepted in-flight L/D estimate
  double lod_ratio_max = 1.5;
};

/// Visits every field a mission may set, with its key, unit and documented range.
template <class Params, class Visitor>
void visit_pc_params(Params& p, Visitor&& v) {
  using U = ParamUnit;
  v("step_s", p.step_s, U::kNone, 0.1, 10.0, "predictor RK4 step [s]");
  v("max_steps", p.max_steps, U::kNone, 100, PredictorCorrectorParams::kMaxSteps, "predictor steps per prediction");
  v("max_predictions", p.max_predictions, U::kNone, 3, 60, "corrector: predictions per plan");
  v("miss_tol_m", p.miss_tol_m, U::kNone, 1.0, 1e5, "corrector: converged below this along-track miss [m]");
  v("control_tol_deg", p.control_tol_rad, U::kDeg, 1e-6, 1.0, "corrector: bracket width that ends the search");
  v("altitude_predictions", p.altitude_predictions, U::kNone, 0, 30, "predictions kept for the TAEM-altitude iterations");
  v("accept_miss_m", p.accept_miss_m, U::kNone, 1.0, 1e6, "corrector: best effort adopted below this miss [m]");
  v("first_step_deg", p.first_step_rad, U::kDeg, 0.1, 45.0, "corrector: second sigma_0 from the first");
  v("bank_max_deg", p.bank_max_rad, U::kDeg, 10.0, 150.0, "largest bank magnitude (profile and command)");
  v("bank_min_deg", p.bank_min_rad, U::kDeg, 0.0, 60.0, "least bank magnitude after capture");
  v("bank_damped_max_deg", p.bank_damped_max_rad, U::kDeg, 10.0, 180.0, "largest bank of the damping (lift down)");
  v("alpha_band_deg", p.alpha_band_rad, U::kDeg, 0.0, 20.0, "alpha within this of the mission's profile");
  v("lateral_bank_deg", p.lateral_bank_rad, U::kDeg, 0.0, 90.0, "bank kept while alpha gives range");
  v("alpha_control_scale", p.alpha_control_scale, U::kNone, 0.1, 100.0, "corrector control per alpha shift");
  v("modulation_min_lift_ratio", p.modulation_min_lift_ratio, U::kNone, 0.0, 1.0, "reversal modulation: least lift kept");
  v("modulation_min_roll_s", p.modulation_min_roll_s, U::kNone, 0.0, 1000.0, "reversal modulation: rolls lasting this long [s]");
  v("final_bank_max_deg", p.final_bank_max_rad, U::kDeg, 0.0, 89.0, "largest derived final bank sigma_f");
  v("final_bank_share", p.final_bank_share, U::kNone, 0.0, 1.0, "sigma_f = share sigma_0 + (1 - share) sigma_glide");
  v("taem_altitude_samples", p.taem_altitude_samples, U::kNone, 1, 10000, "TAEM altitude-band scan samples");
  v("altitude_iterations", p.altitude_iterations, U::kNone, 0, 10, "terminal-aim corrections per plan");
  v("altitude_tol_fraction", p.altitude_tol_fraction, U::kNone, 0.0, 1.0, "terminal aim corrected beyond this share of the altitude tolerance");
  v("terminal_range_aim_fraction", p.terminal_range_aim_fraction, U::kNone, 0.0, 1.0, "range by the terminal aim: share of the TAEM band depth it may give up (0: none)");
  v("terminal_range_predictions", p.terminal_range_predictions, U::kNone, 0, 20, "range by the terminal aim: predictions per plan");
  v("reversal_hold_predictions", p.reversal_hold_predictions, U::kNone, 0, 20, "range by the reversal hold: predictions per plan");
  v("terminal_span_fraction", p.terminal_span_fraction, U::kNone, 0.0, 1.0, "terminal altitude line: last share of the span");
  v("terminal_ramp_fraction", p.terminal_ramp_fraction, U::kNone, 0.01, 1.0, "terminal altitude line: ramp-in share of its span");
  v("terminal_gamma_min_deg", p.terminal_gamma_min_rad, U::kDeg, -45.0, 0.0, "terminal altitude line: steepest flight path");
  v("terminal_gamma_max_deg", p.terminal_gamma_max_rad, U::kDeg, -45.0, 10.0, "terminal altitude line: shallowest flight path");
  v("terminal_rate_gain_ps", p.terminal_rate_gain_ps, U::kNone, 0.0, 10.0, "terminal altitude-rate gain k_t [1/s]");
  v("damping_ratio", p.damping_ratio, U::kNone, 0.0, 5.0, "altitude-rate damping ratio zeta");
  v("glide_position_factor", p.glide_position_factor, U::kNone, 0.0, 100.0, "height term gain: k / factor (0: none)");
  v("constraint_margin", p.constraint_margin, U::kNone, 0.5, 1.0, "planned fraction of every path limit");
  v("drag_model_uncertainty", p.drag_model_uncertainty, U::kNone, 0.0, 0.5, "share the on-board C_D S/m may overstate: drag-form limits lowered by it");
  v("capture_drag_fraction", p.capture_drag_fraction, U::kNone, 0.0, 1.0, "shallow-entry capture from this share of the threshold drag");
  v("roll_lag_s", p.roll_lag_s, U::kNone, 0.0, 10.0, "pull-out guard: lag before the roll to wings level [s]");
  v("pullout_glide_need", p.pullout_glide_need, U::kNone, 0.01, 1.0, "pull-out guard: glide sink discounted fully from this need / g0");
  v("constraint_time_s", p.constraint_time_s, U::kNone, 1.0, 1000.0, "constraint bound: horizon tau of the drag's approach [s]");
  v("constraint_gain_ps", p.constraint_gain_ps, U::kNone, 0.001, 10.0, "constraint bound: altitude-rate gain k_c [1/s]");
  v("corridor_entry_deg", p.corridor_entry_rad, U::kDeg, 0.5, 60.0, "heading corridor half-width at entry");
  v("corridor_taem_deg", p.corridor_taem_rad, U::kDeg, 0.5, 60.0, "heading corridor half-width at TAEM");
  v("approach_angle_max_deg", p.approach_angle_max_rad, U::kDeg, 1.0, 90.0, "arrival-line field chi_inf");
  v("cross_track_scale_m", p.cross_track_scale_m, U::kNone, 100.0, 1e6, "arrival-line field y_s [m]");
  v("approach_turn_factor", p.approach_turn_factor, U::kNone, 0.1, 10.0, "approach-angle turn bound k");
  v("sight_line_factor", p.sight_line_factor, U::kNone, 1.0, 100.0, "approach angle <= n x the line of sight's angle off the line");
  v("aim_min_range_m", p.aim_min_range_m, U::kNone, 0.0, 1e5, "offset angle undefined closer than this [m]");
  v("capture_overshoot_m", p.capture_overshoot_m, U::kNone, 0.0, 1e6, "capture guard: largest overshoot past the line [m]");
  v("capture_overshoot_range_fraction", p.capture_overshoot_range_fraction, U::kNone, 0.0, 0.2, "capture guard: limit at least this share of the distance to go along the line");
  v("capture_waits_for_plan", p.capture_waits_for_plan, U::kNone, 0, 1, "capture guard waits for the plan's first reversal (0: never)");
  v("final_reversal_window", p.final_reversal_window, U::kNone, 0.0, 10.0, "final-reversal window / reversal time");
  v("final_turn_steps", p.final_turn_steps, U::kNone, 5, 500, "final-turn prediction steps");
  v("bank_settled_deg", p.bank_settled_rad, U::kDeg, 0.1, 30.0, "bank settled on its command within this");
  v("modulation_in_terminal", p.modulation_in_terminal, U::kNone, 0, 1, "reversal modulation also in the terminal phase (0: not there)");
  v("final_keep_fraction", p.final_keep_fraction, U::kNone, 0.0, 1.0, "final reversal only beyond this share of the TAEM tolerances");
  v("replan_period_s", p.replan_period_s, U::kNone, 0.5, 1000.0, "plan period [s]");
  v("replan_floor_span_fraction", p.replan_floor_span_fraction, U::kNone, 0.0, 1.0, "no plans in this last share of the span");
  v("drag_ratio_min", p.drag_ratio_min, U::kNone, 0.1, 1.0, "least sensed drag ratio K");
  v("drag_ratio_max", p.drag_ratio_max, U::kNone, 1.0, 10.0, "largest sensed drag ratio K");
  v("lod_ratio_min", p.lod_ratio_min, U::kNone, 0.1, 1.0, "least accepted L/D estimate");
  v("lod_ratio_max", p.lod_ratio_max, U::kNone, 1.0, 10.0, "largest accepted L/D estimate");
}

/// The key of the first field that breaks a relation between fields (nullptr: consistent).
inline const char* pc_params_inconsistency(const PredictorCorrectorParams& p) {
  if (!(p.bank_min_rad < p.bank_max_rad)) return "bank_min_deg";
  if (!(p.lateral_bank_rad <= p.bank_max_rad)) return "lateral_bank_deg";
  if (!(p.bank_max_rad <= p.bank_damped_max_rad)) return "bank_damped_max_deg";
  if (!(p.final_bank_max_rad <= p.bank_max_rad)) return "final_bank_max_deg";
  if (!(p.corridor_taem_rad <= p.corridor_entry_rad)) return "corridor_taem_deg";
  if (!(p.drag_ratio_min < p.drag_ratio_max)) return "drag_ratio_min";
  if (!(p.lod_ratio_min < p.lod_ratio_max)) return "lod_ratio_min";
  if (!(p.miss_tol_m <= p.accept_miss_m)) return "miss_tol_m";
  if (!(p.altitude_predictions < p.max_predictions)) return "altitude_predictions";
  if (!(p.terminal_gamma_min_rad <= p.terminal_gamma_max_rad)) return "terminal_gamma_min_deg";
  return nullptr;
}

}  // namespace reentry::fsw
