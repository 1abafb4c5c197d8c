// Stage 6 of the entry planner: the trajectory-length iteration (thesis §7.5, (7.22)) over
// stages 2-5, and the ranging-alpha step around it. Also the plan's data: the context every
// stage reads (PlanContext) and the fixed-capacity workspace the stages write (PlanWorkspace).
#pragma once

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"
#include "planner/drag_corridor.hpp"
#include "planner/planner_diagnostics.hpp"
#include "planner/planner_grid.hpp"
#include "planner/planner_params.hpp"
#include "planner/profile_fit.hpp"
#include "planner/reduced_order.hpp"
#include "planner/trajectory_extraction.hpp"

namespace reentry::fsw {

/// The planning point and what follows from it alone.
struct PlanSetup {
  RelativeState from{};               // planning state, energy filled in
  double r_mean_m = 0.0;              // mean of the planning and TAEM radii (7.22)
  double azimuth_mission_rad = 0.0;   // A (7.2) planning point -> TAEM
  double b_mission_rad = 0.0;         // b (7.1)
  double range_desired_m = 0.0;       // R_d = b r_mean, also the first length S0 (7.22)
  double d_actual_mps2 = 0.0;         // sensed drag (or the models' at the profile alpha)
  double ranging_blend_min = 0.0;     // blend of the last converged plan (never decreases in flight)
};

/// Everything a plan's stages read and none of them writes.
struct PlanContext {
  const OnboardModels& models;  // lift scale set for this plan
  const PlannerParams& params;
  const PlannerMission& mission;
  const PlanSetup& setup;
};

/// Stage outputs of one plan, written in place (fixed capacity, allocated with the planner).
struct PlanWorkspace {
  EnergyGrid grid;
  GridValues alpha_ld_rad{};    // alpha(L/D max) on the grid (ranging)
  GridValues radius_m{};        // r(E): equilibrium glide (stage 1), then extracted (stage 3)
  CorridorStage corridor;
  PlannedDrag drag;
  ExtractedTrajectory trajectory;
  RangeTable range;
  RopTrack base{};              // reduced-order run without reversal (stage 5)
  RopTrack track{};             // the reduced-order run of the plan handed out
  /// Zeroes the scalar reports of the stages (start of a plan).
  void reset_reports();
};

/// The bank reversal as the searches of one plan leave it.
struct ReversalState {
  double s_rev_m = 0.0;             // flown range of the reversal start of the last search
  int first_sign = 1;               // bank side flown first
  bool lateral_unreachable = false; // last search: not even a best-effort reversal
};

/// The reduced-order system over the workspace's planned trajectory.
ReducedOrderInput reduced_order_input(const PlanContext& ctx, const PlanWorkspace& ws);
/// Planning position and heading as the reduced-order start state.
RopState planning_start(const PlanSetup& setup);

/// Stage 1 on the workspace's grid (radius, corridor, breakpoints, Di, Df); reports into diag.
Status corridor_stage(const PlanContext& ctx, PlanWorkspace& ws, PlannerDiagnostics& diag);

/// (7.22): S_{i+1} = S_i + (R_d - R_i).
double next_trajectory_length_m(double length_m, double range_desired_m, double range_flown_m);

/// Stage 6: fit (2), extract (3), reversal search (4-5) and the length update (7.22) until the
/// downrange matches, from the length s_m. converged: both tolerances met. kRangeTooLong: even
/// the shortest-range profile flies past the aim point (that profile is kept).
Status length_iteration(const PlanContext& ctx, PlanWorkspace& ws, double& s_m, bool& converged, ReversalState& rev,
                        PlannerDiagnostics& diag);

/// The drag the range needs lies below the wings-level glide floor between the end of the
/// capture part of the profile and the terminal phase (judged on the last iteration).
bool below_glide_floor(const PlanContext& ctx, const PlanWorkspace& ws);
/// Early in the flight no single reversal turns the vehicle onto the target (judged on the
/// last iteration's report).
bool lateral_short(const PlanContext& ctx, const ReversalState& rev, const PlannerDiagnostics& diag);

/// Ranging alpha: the smallest blend (bisection) that makes the plan feasible, then the plan at
/// that blend. `first` is the status of the plan without it (reported if this one fails too).
Status ranging_alpha(const PlanContext& ctx, Status first, PlanWorkspace& ws, double& s_m, bool& converged,
                     ReversalState& rev, PlannerDiagnostics& diag);

}  // namespace reentry::fsw
