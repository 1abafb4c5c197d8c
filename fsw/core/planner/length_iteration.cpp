#include "planner/length_iteration.hpp"

#include <cmath>

#include "planner/mission_geometry.hpp"
#include "planner/ranging_alpha.hpp"
#include "planner/reversal_search.hpp"

namespace reentry::fsw {
namespace {

// Stages 4-5 on the fitted and extracted profile: flown-range table, reversal search.
Status reversal_stage(const PlanContext& ctx, PlanWorkspace& ws, ReversalState& rev, double& crossrange_rad,
                      double& downrange_rad, PlannerDiagnostics& diag) {
  build_range_table(ws.grid.energy_Jpkg, ws.drag.drag_mps2, ws.range);
  const PlanSetup& setup = ctx.setup;
  const ReducedOrderInput sys = reduced_order_input(ctx, ws);
  const ReversalSearchInput in{sys,
                               planning_start(setup),
                               setup.azimuth_mission_rad,
                               setup.b_mission_rad,
                               setup.r_mean_m,
                               setup.from.energy_Jpkg,
                               ctx.params.crossrange_tol_m,
                               ctx.params.best_effort_crossrange_fraction};
  ReversalSearchResult r;
  const Status s = bank_reversal_search(in, rev.first_sign, rev.s_rev_m, ws.base, r);
  diag.reversal_best_effort = r.best_effort;
  diag.reversal_evaluations += r.evaluations;
  diag.initial_bank_sign = rev.first_sign;
  rev.lateral_unreachable = r.lateral_unreachable;
  if (s == Status::kOk) {
    crossrange_rad = r.crossrange_rad;
    downrange_rad = r.downrange_rad;
  }
  return s;
}

void set_ranging_blend(const PlanContext& ctx, double blend, PlanWorkspace& ws, PlannerDiagnostics& diag) {
  RangingBlendInput in;
  in.blend = blend;
  in.continuing = ctx.setup.ranging_blend_min > 0.0;
  in.planning_energy_Jpkg = ctx.setup.from.energy_Jpkg;
  in.entry_energy_Jpkg = ctx.mission.entry_energy_Jpkg;
  in.taem_energy_Jpkg = ctx.mission.taem_energy_Jpkg;
  in.ramp_fraction = ctx.params.ranging_ramp_fraction;
  apply_ranging_blend(in, ws.alpha_ld_rad, ws.grid);
  diag.ranging_blend = blend;
}

}  // namespace

void PlanWorkspace::reset_reports() {
  corridor.closed_points = 0;
  corridor.breakpoints = Breakpoints{};
  corridor.d_initial_mps2 = 0.0;
  corridor.d_final_mps2 = 0.0;
  drag.level_mps2 = 0.0;
  drag.clipped_points = 0;
}

ReducedOrderInput reduced_order_input(const PlanContext& ctx, const PlanWorkspace& ws) {
  return ReducedOrderInput{ws.grid.energy_Jpkg,
                           ws.radius_m,
                           ws.drag,
                           ws.trajectory,
                           ws.range,
                           ctx.mission.corridor_energy_Jpkg,
                           ctx.mission.taem_energy_Jpkg,
                           ctx.mission.sigma_rate_max_radps,
                           ctx.params.rk4_steps};
}

RopState planning_start(const PlanSetup& setup) {
  return RopState{setup.from.longitude_rad, setup.from.latitude_rad, setup.from.heading_rad};
}

Status corridor_stage(const PlanContext& ctx, PlanWorkspace& ws, PlannerDiagnostics& diag) {
  const RelativeState& f = ctx.setup.from;
  const TrackEnds track{f.latitude_rad, f.longitude_rad, ctx.mission.taem_lat_rad, ctx.mission.taem_lon_rad};
  const CorridorStageInput in{ctx.models, ws.grid, ctx.params, ctx.mission, track, f.energy_Jpkg, ctx.setup.d_actual_mps2};
  const Status s = drag_energy_corridor(in, ws.radius_m, ws.corridor);
  diag.corridor_closed_points = ws.corridor.closed_points;
  diag.e1_Jpkg = ws.corridor.breakpoints.e1_Jpkg;
  diag.e2_Jpkg = ws.corridor.breakpoints.e2_Jpkg;
  diag.di_mps2 = ws.corridor.d_initial_mps2;
  diag.df_mps2 = ws.corridor.d_final_mps2;
  return s;
}

double next_trajectory_length_m(double length_m, double range_desired_m, double range_flown_m) {
  return length_m + (range_desired_m - range_flown_m);  // (7.22)
}

Status length_iteration(const PlanContext& ctx, PlanWorkspace& ws, double& s_m, bool& converged, ReversalState& rev,
                        PlannerDiagnostics& diag) {
  const PlannerParams& p = ctx.params;
  const double range_desired = ctx.setup.range_desired_m;  // R_d
  const Breakpoints& bp = ws.corridor.breakpoints;
  double cross = 0.0, down = 0.0;
  converged = false;
  rev.lateral_unreachable = false;
  for (int it = 0; it < p.max_length_iterations; ++it) {
    diag.iterations = it + 1;
    const ProfileFitInput fit{p.drag_profile, s_m, ctx.setup.from.energy_Jpkg, bp.e1_Jpkg, bp.e2_Jpkg,
                              ctx.mission.taem_energy_Jpkg, ws.corridor.d_initial_mps2, ws.corridor.d_final_mps2,
                              ws.grid.energy_Jpkg, ws.corridor.corridor.max_mps2};
    Status s = fit_drag_profile(fit, ws.drag);
    diag.dc_mps2 = ws.drag.level_mps2;
    diag.clipped_points = ws.drag.clipped_points;
    if (s != Status::kOk) return s;
    s = extract_trajectory(ExtractionInput{ctx.models, ws.grid, ws.drag}, ws.radius_m, ws.trajectory);
    if (s != Status::kOk) return s;
    s = reversal_stage(ctx, ws, rev, cross, down, diag);
    if (s != Status::kOk) return s;
    const double range_flown = down * ctx.setup.r_mean_m;  // R_i
    diag.s_final_m = s_m;
    diag.crossrange_err_m = cross * ctx.setup.r_mean_m;
    diag.downrange_err_m = range_desired - range_flown;
    // The shortest-range (maximum-drag) profile still flies past the aim point: no length
    // fits. Reported, with this profile kept as the best effort.
    if (ws.drag.level_at_max && range_desired - range_flown < -p.downrange_tol_m) return Status::kRangeTooLong;
    if (std::fabs(range_desired - range_flown) < p.downrange_tol_m) {
      converged = diag.reversal_best_effort || std::fabs(diag.crossrange_err_m) < p.crossrange_tol_m;
      break;
    }
    s_m = next_trajectory_length_m(s_m, range_desired, range_flown);
    if (!(s_m > 0.0)) return Status::kNotConverged;
  }
  return Status::kOk;
}

bool lateral_short(const PlanContext& ctx, const ReversalState& rev, const PlannerDiagnostics& diag) {
  // No single reversal nulls the crossrange and the best effort leaves more than the
  // tolerance: the bank needed for the range is too small to turn (low L/D, long range).
  // Judged only in the first tenth of the energy span, before the heat pulse: later, a
  // best-effort plan just after a flown reversal is normal (the lateral corridor steers the
  // rest out), and moving alpha then swaps a profile on the heat-flux limit for one the
  // vehicle cannot reach without exceeding it.
  const PlannerMission& m = ctx.mission;
  const double early = m.taem_energy_Jpkg + ctx.params.lateral_move_span_fraction * (m.entry_energy_Jpkg - m.taem_energy_Jpkg);
  return ctx.setup.from.energy_Jpkg > early &&
         (rev.lateral_unreachable ||
          (diag.reversal_best_effort && std::fabs(diag.crossrange_err_m) > ctx.params.crossrange_tol_m));
}

bool below_glide_floor(const PlanContext& ctx, const PlanWorkspace& ws) {
  // Floor: L = g - V^2/r - 2 omega V cos(lat) sin(chi) ((2.33) with gamma' = 0 and sigma = 0;
  // the Earth-rate term is a sixth of the need for the eastbound X-33 at Mach 20, so the
  // rotation-free Lmin (7.7) would call its nominal plan infeasible), lat and chi on the
  // planning-point -> TAEM great circle at the planned range fraction. Checked from where the
  // profile first reaches the floor (or after capture_span_fraction of the span) down to the
  // terminal phase (where the tracker's range control takes over).
  const PlannerMission& m = ctx.mission;
  const RelativeState& from = ctx.setup.from;
  const GridValues& e = ws.grid.energy_Jpkg;
  const GridValues& d = ws.drag.drag_mps2;
  const double e0 = from.energy_Jpkg;
  const double span = e0 - m.taem_energy_Jpkg;
  const double e_terminal = m.taem_energy_Jpkg + m.terminal_span_fraction * (m.entry_energy_Jpkg - m.taem_energy_Jpkg);
  const double s_end = ws.range.s_cum_m[kPlannerGrid - 1];
  bool entered = false;
  for (int k = 0; k < kPlannerGrid && e[k] > e_terminal; ++k) {
    const double f = s_end > 0.0 ? ws.range.s_cum_m[k] / s_end : 0.0;  // planned range fraction
    const TrackPoint p = great_circle_point(from.latitude_rad, from.longitude_rad, m.taem_lat_rad, m.taem_lon_rad, f);
    const double floor = level_flight_lift_need_mps2(ws.radius_m[k], ws.trajectory.velocity_mps[k], p.lat_rad, p.azimuth_rad) /
                         ws.trajectory.lift_over_drag[k];
    if (!entered) entered = d[k] >= floor || e[k] < e0 - ctx.params.capture_span_fraction * span;
    if (entered && d[k] < floor) return true;
  }
  return false;
}

Status ranging_alpha(const PlanContext& ctx, Status first, PlanWorkspace& ws, double& s_m, bool& converged,
                     ReversalState& rev, PlannerDiagnostics& diag) {
  // alpha moves towards alpha(L/D max) from the planning point to near TAEM; the smallest move
  // that lifts the floor below the needed drag (and lets a reversal turn the vehicle) is found
  // by bisection on the blend (the full move when even that is not enough: the longest range
  // the vehicle can fly). Once used, the blend never decreases in later plans, so the alpha
  // reference stays continuous from plan to plan.
  const PlannerParams& p = ctx.params;
  const double range_desired = ctx.setup.range_desired_m;
  alpha_of_max_lift_over_drag(ctx.models, ws.grid, ws.radius_m, ctx.mission.alpha_max_rad, p.alpha_scan_steps, ws.alpha_ld_rad);
  auto feasible = [&](double blend) {
    set_ranging_blend(ctx, blend, ws, diag);
    double s_trial = range_desired;
    bool conv_trial = false;
    if (corridor_stage(ctx, ws, diag) != Status::kOk) return false;
    return length_iteration(ctx, ws, s_trial, conv_trial, rev, diag) == Status::kOk && !below_glide_floor(ctx, ws) &&
           !lateral_short(ctx, rev, diag);
  };
  const double blend_min = ctx.setup.ranging_blend_min;
  double lo = blend_min, hi = 1.0;
  if (blend_min > 0.0 && feasible(blend_min)) hi = lo;
  for (int i = 0; i < p.ranging_bisections && hi - lo > p.ranging_blend_tol; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (feasible(mid)) hi = mid;
    else lo = mid;
  }
  set_ranging_blend(ctx, hi, ws, diag);
  s_m = range_desired;
  Status s = corridor_stage(ctx, ws, diag);
  if (s == Status::kOk) s = length_iteration(ctx, ws, s_m, converged, rev, diag);
  if (s != Status::kOk && first != Status::kOk) s = first;  // report the original failure
  return s;
}

}  // namespace reentry::fsw
