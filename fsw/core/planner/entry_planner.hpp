// Entry planner after thesis ch. 7 (Mease et al. 2002 / Saraf et al. 2003), as explicit stages
// with input and output structs (each in its own header):
//   0. energy grid and alpha on it                               planner_grid.hpp
//   1. drag-energy corridor (7.3)-(7.7), breakpoints, Di, Df     drag_corridor.hpp
//   2. drag profile fitting a trajectory length S (7.11)-(7.12)  profile_fit.hpp
//   3. extraction of r(E) (7.13), gamma(E) (7.14), D'' terms     trajectory_extraction.hpp
//   4. reduced-order system (2.42)-(2.45), reversal method 3     reduced_order.hpp
//   5. bank-reversal search (§7.4)                               reversal_search.hpp
//   6. length update (7.22) until the downrange matches, and     length_iteration.hpp
//      ranging alpha (ch. 6 ranging phase): when the range needs less drag than the
//      wings-level glide floor (L/D too low for the distance), alpha is moved towards
//      alpha(L/D max) by the smallest blend that restores feasibility, never decreasing in
//      flight (ranging_alpha.hpp).
// EntryPlanner holds the mission constants, the memory of the plan being flown and the
// fixed-capacity workspace, runs the stages and writes the reference profile (bank sign and
// magnitude (7.17) along the reduced-order track).
// Replans take the in-flight L/D estimate (RelativeState::lift_over_drag_scale) as a C_L scale.
// Fixed capacity, no heap after init(), bounded loops, every failure returned as a Status.
#pragma once

#include "guidance_params.hpp"
#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "planner/length_iteration.hpp"
#include "planner/planner_diagnostics.hpp"
#include "planner/planner_grid.hpp"
#include "planner/planner_params.hpp"

namespace reentry::fsw {

class EntryPlanner {
 public:
  static constexpr int kGrid = kPlannerGrid;  // energy grid points
  static constexpr int kMaxRkSteps = PlannerParams::kMaxRkSteps;

  /// The models and the alpha profile are copied; the planner's tunables are params.planner.
  Status init(const OnboardModels& models, const AlphaProfile& alpha_profile, const GuidanceMission& mission,
              const GuidanceLawParams& params);
  /// Plan from a state (entry or in flight). No allocation. out.status mirrors the result.
  Status plan(const RelativeState& from, ReferenceProfile& out);
  const PlannerDiagnostics& diagnostics() const { return diag_; }
  const OnboardModels& models() const { return models_; }
  const PlannerParams& params() const { return params_; }
  double entry_energy_Jpkg() const { return mission_.entry_energy_Jpkg; }
  double taem_energy_Jpkg() const { return mission_.taem_energy_Jpkg; }
  /// RelativeState at the mission entry interface, drag from the on-board models.
  RelativeState entry_state() const { return mission_.entry; }
  /// Active maximum-drag and minimum-drag (Lmin (7.7), rotation-free) corridor of the last plan, on the grid.
  double corridor_max(int k) const { return ws_.corridor.corridor.max_mps2[k]; }
  double corridor_min(int k) const { return ws_.corridor.corridor.min_mps2[k]; }
  /// Lmin with the Earth-rate term of (2.33): the floor the closure test uses.
  double corridor_floor(int k) const { return ws_.corridor.corridor.floor_mps2[k]; }
  double grid_energy(int k) const { return ws_.grid.energy_Jpkg[k]; }

 private:
  /// Bank side of the last plan handed out (first sign and reversal energy): a replan keeps the
  /// side being flown (see planning_setup).
  struct FlownSide {
    bool known = false;
    int first_sign = 1;
    double reversal_energy_Jpkg = 0.0;
  };

  Status planning_setup(const RelativeState& from, PlanSetup& setup, int& first_sign, PlannerDiagnostics& diag);
  void fill_output(const PlanContext& ctx, const ReversalModel& reversal, ReferenceProfile& out, PlannerDiagnostics& diag) const;

  OnboardModels models_;
  AlphaProfile alpha_profile_;
  PlannerParams params_;
  PlannerMission mission_{};
  bool initialised_ = false;
  double ranging_blend_min_ = 0.0;  // blend of the last converged plan (never decreases in flight)
  FlownSide flown_{};
  PlanWorkspace ws_;                // per-plan stage outputs
  PlannerDiagnostics diag_{};
};

}  // namespace reentry::fsw
