// Tunables of the entry planner (thesis ch. 7 and the rules of docs/guidance_design.md).
// Every field is SI with its unit in the name; defaults are the values the reference missions
// fly. A mission sets the numeric ones in [guidance.planner] (visit_planner_params gives key,
// unit and documented range); the profile shape and the initial drag are the [guidance]
// choices `drag_profile` and `initial_drag`.
#pragma once

#include "params/param_visitor.hpp"

namespace reentry::fsw {

enum class DragProfileKind { kThreeSegment, kSmooth };
enum class InitialDrag { kActual, kLmin };

struct PlannerParams {
  static constexpr int kMaxRkSteps = 4000;  // capacity of the reduced-order state arrays

  DragProfileKind drag_profile = DragProfileKind::kSmooth;  // three segments (7.11) or smooth
  InitialDrag initial_drag = InitialDrag::kActual;          // profile start: sensed drag or Lmin (7.6)
  // Trajectory-length iteration (7.22) and the reduced-order system (2.42)-(2.45).
  int rk4_steps = 600;                       // RK4 steps in flown range
  int max_length_iterations = 20;
  double downrange_tol_m = 1500.0;
  double crossrange_tol_m = 1000.0;
  // Energy grid and corridor.
  double graded_grid_drag_mps2 = 0.1;        // below this initial drag the energy grid is graded
  double max_closed_fraction = 0.1;          // of the grid: a longer corridor closure is a failure
  double capture_span_fraction = 0.1;        // profile start (capture) exempt from the floor check
  double drag_floor_mps2 = 1e-4;             // least initial drag of a profile
  // Breakpoints of the three-segment profile (7.11), as shares of the planning-to-TAEM energy
  // span (§7.2: E1 at the heat-flux / q-alpha crossing, E2 at the highest Lmin below E1).
  double e1_default_span_fraction = 0.3;     // E1 below the planning energy when the limits do not cross
  double e1_min_span_fraction = 0.1;         // E1 at least this far above TAEM
  double e2_default_span_fraction = 0.05;    // E2 above TAEM when Lmin has no maximum below E1
  double segment_min_span_fraction = 0.02;   // least span of each of the three segments
  int taem_box_samples = 60;                 // altitude samples of the TAEM band (start-up)
  // Reversal search: no reversal nulls the crossrange -> smallest one, if below this share of
  // the mission angle b.
  double best_effort_crossrange_fraction = 0.05;
  // Ranging alpha (ch. 6 ranging phase).
  double lateral_move_span_fraction = 0.9;   // ranging alpha for lateral reach: above this energy only
  double ranging_ramp_fraction = 0.05;       // alpha blend ramps over this share of the span
  int ranging_bisections = 6;                // blend resolution 1/64
  double ranging_blend_tol = 1.0 / 64.0;
  int alpha_scan_steps = 200;                // alpha(L/D max) scan over [0, alpha_max]
  // Accepted range of the in-flight L/D estimate (replans scale the lift with it).
  double lift_scale_min = 0.5;
  double lift_scale_max = 1.5;
};

template <class Params, class Visitor>
void visit_planner_params(Params& p, Visitor&& v) {
  using U = ParamUnit;
  v("rk4_steps", p.rk4_steps, U::kNone, 10, PlannerParams::kMaxRkSteps, "reduced-order RK4 steps (capacity)");
  v("max_length_iterations", p.max_length_iterations, U::kNone, 1, 1000, "trajectory-length iterations (7.22)");
  v("downrange_tol_m", p.downrange_tol_m, U::kNone, 1.0, 1e6, "length iteration: downrange tolerance");
  v("crossrange_tol_m", p.crossrange_tol_m, U::kNone, 1.0, 1e6, "reversal search: crossrange tolerance");
  v("graded_grid_drag_mps2", p.graded_grid_drag_mps2, U::kNone, 0.0, 10.0, "graded energy grid below this drag");
  v("max_closed_fraction", p.max_closed_fraction, U::kNone, 0.0, 1.0, "corridor closure accepted over this grid share");
  v("capture_span_fraction", p.capture_span_fraction, U::kNone, 0.0, 1.0, "profile start exempt from the floor check");
  v("drag_floor_mps2", p.drag_floor_mps2, U::kNone, 1e-8, 1.0, "least initial drag");
  v("taem_box_samples", p.taem_box_samples, U::kNone, 1, 10000, "TAEM altitude-band samples");
  v("e1_default_span_fraction", p.e1_default_span_fraction, U::kNone, 0.0, 1.0,
    "E1 below the planning energy without a heat-flux / q-alpha crossing (share of the span)");
  v("e1_min_span_fraction", p.e1_min_span_fraction, U::kNone, 0.0, 1.0, "E1 at least this share of the span above TAEM");
  v("e2_default_span_fraction", p.e2_default_span_fraction, U::kNone, 0.0, 1.0,
    "E2 above TAEM without an Lmin maximum below E1 (share of the span)");
  v("segment_min_span_fraction", p.segment_min_span_fraction, U::kNone, 0.0, 0.3,
    "least span of each three-segment piece (share of the span; 2x it <= e1_min_span_fraction)");
  v("best_effort_crossrange_fraction", p.best_effort_crossrange_fraction, U::kNone, 0.0, 1.0,
    "best-effort reversal accepted below this share of b");
  v("lateral_move_span_fraction", p.lateral_move_span_fraction, U::kNone, 0.0, 1.0, "lateral ranging alpha above this span");
  v("ranging_ramp_fraction", p.ranging_ramp_fraction, U::kNone, 1e-4, 1.0, "ranging alpha ramp / span");
  v("ranging_bisections", p.ranging_bisections, U::kNone, 1, 30, "ranging blend bisections");
  v("ranging_blend_tol", p.ranging_blend_tol, U::kNone, 1e-9, 1.0, "ranging blend resolution");
  v("alpha_scan_steps", p.alpha_scan_steps, U::kNone, 10, 100000, "alpha(L/D max) scan steps");
  v("lift_scale_min", p.lift_scale_min, U::kNone, 0.01, 1.0, "least accepted in-flight L/D estimate");
  v("lift_scale_max", p.lift_scale_max, U::kNone, 1.0, 100.0, "largest accepted in-flight L/D estimate");
}

/// The first key whose value breaks a relation between planner fields (nullptr: consistent):
/// the breakpoint clamps must leave E1 and E2 an interval, E1 in
/// [TAEM + e1_min, E0 - gap] and E2 in [TAEM + gap, E1 - gap], gap = segment_min_span_fraction.
inline const char* planner_params_inconsistency(const PlannerParams& p) {
  if (!(p.e1_min_span_fraction + p.segment_min_span_fraction <= 1.0)) return "planner.e1_min_span_fraction";
  if (!(2.0 * p.segment_min_span_fraction <= p.e1_min_span_fraction)) return "planner.segment_min_span_fraction";
  return nullptr;
}

}  // namespace reentry::fsw
