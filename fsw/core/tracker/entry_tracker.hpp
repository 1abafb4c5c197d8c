// Drag and heading tracker after EAGLE (thesis §3.2.3, Saraf et al. 2003, Tu et al. 2000): the
// per-cycle command law that flies the adopted plan. EntryTracker::step runs, once per cycle:
//   1. the cycle context (cycle_context.hpp): everything the components need of the sensed
//      state, computed once (Mach, q, C_D, time to go, arrival-line target);
//   2. the phase machine (tracker_phase.hpp): initial descent and capture, planned, heading
//      corridor, terminal range control, final-reversal window;
//   3. the drag reference: the plan at the vehicle's energy (reference_track.hpp), shaped by the
//      terminal range control (terminal_range.hpp) and capped by the sensed constraint limit
//      (constraint_limiter.hpp);
//   4. the drag loop (drag_loop.hpp, 3.10-3.18): bank magnitude, with the pull-out guard and
//      the lift-down limit of the final-reversal window;
//   5. the lateral logic (lateral_logic.hpp): the bank sign; a sign change is flown by the
//      reversal execution with its alpha modulation (reversal_execution.hpp);
//   6. load relief of the alpha command (constraint_limiter.hpp).
// The sensed drag and L/D ratios against the on-board models are estimated alongside
// (aero_ratio_estimator.hpp). Every tunable is in TrackerParams. No heap, no exceptions,
// bounded loops.
#pragma once

#include "guidance_params.hpp"
#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "tracker/aero_ratio_estimator.hpp"
#include "tracker/constraint_limiter.hpp"
#include "tracker/cycle_context.hpp"
#include "tracker/drag_loop.hpp"
#include "tracker/lateral_logic.hpp"
#include "tracker/reference_track.hpp"
#include "tracker/reversal_execution.hpp"
#include "tracker/terminal_range.hpp"
#include "tracker/tracker_params.hpp"
#include "tracker/tracker_phase.hpp"

namespace reentry::fsw {

struct TrackerOutput {
  double alpha_rad = 0.0;
  double sigma_rad = 0.0;
  Phase phase = Phase::kInitialDescent;  // executive-level phase (tracking / reversal)
  double drag_ref_mps2 = 0.0;
  double drag_err_mps2 = 0.0;      // D - D_ref
  double heading_err_rad = 0.0;    // chi - chi_target (corridor phase), chi - chi_plan before
  double sigma_d_rad = 0.0;        // drag-loop bank magnitude (3.20)
  double u_drag = 0.0;             // commanded vertical L/D
  bool saturated = false;          // |u| exceeded the available L/D
  double lift_over_drag_scale = 1.0;  // sensed L/D over the model's at the commanded alpha, filtered
  TrackerTelemetry telemetry;
};

/// The tracker's data: its parameters, models and components (copyable as values; the
/// components' pointers to the models and parameters are re-bound by EntryTracker's copies).
struct EntryTrackerData {
  TrackerParams params_;
  OnboardModels models_;
  AlphaProfile alpha_profile_;
  TaemTarget taem_{};               // aim point, arrival heading, speed and bands
  TrackerLimits limits_;            // path and control limits, planned margin
  double entry_energy_Jpkg_ = 0.0;  // E at the entry interface (normalisation)
  double taem_energy_Jpkg_ = 0.0;   // E at the TAEM interface
  bool initialised_ = false;

  TrackerPhaseMachine phases_;
  ReferenceTrack reference_;
  AeroRatioEstimator estimator_;
  DragLoop drag_loop_;
  ConstraintLimiter limiter_;
  TerminalRangeControl terminal_;
  LateralLogic lateral_;
  ReversalExecution reversal_;

  double last_alpha_cmd_rad_ = 0.0; // alpha commanded in the previous cycle
  double last_sigma_d_rad_ = 0.0;   // bank magnitude commanded in the previous cycle
  double flown_alpha_rad_ = -1.0;   // alpha out of the rate filter (< 0: attitude not given)
  double flown_sigma_rad_ = 0.0;    // bank out of the rate filter (given with the alpha)
};

class EntryTracker : private EntryTrackerData {
 public:
  EntryTracker() = default;
  EntryTracker(const EntryTracker& other) : EntryTrackerData(other) { bind_components(); }
  EntryTracker& operator=(const EntryTracker& other) {
    EntryTrackerData::operator=(other);
    bind_components();
    return *this;
  }

  /// The models, the alpha profile and params.tracker are copied; the gains follow
  /// derive_gains unless params.tracker sets them.
  Status init(const OnboardModels& models, const AlphaProfile& alpha_profile, const GuidanceMission& mission,
              const GuidanceLawParams& params);
  /// Copies the profile (no allocation); a plan that cannot be tracked is ignored.
  void set_profile(const ReferenceProfile& profile) { reference_.adopt(profile); }
  /// alpha and bank out of the command rate filters last cycle (what the vehicle flies, up to
  /// the attitude lag): the sensed accelerations are referred to the reference alpha with
  /// them, and the reversal modulation and the load relief act on them. Not given: the
  /// tracker's own last commands.
  void set_flown_attitude(double alpha_rad, double sigma_rad) {
    flown_alpha_rad_ = alpha_rad;
    flown_sigma_rad_ = sigma_rad;
  }
  bool has_profile() const { return reference_.has_profile(); }
  /// Factor on the planned final drag in the terminal phase (see TerminalRangeControl).
  double final_drag_factor() const { return terminal_.final_drag_factor(estimator_.drag_ratio(), reference_); }
  Status step(const RelativeState& s, double dt_s, TrackerOutput& out);

  const TrackerGains& gains() const { return drag_loop_.gains(); }
  const TrackerParams& params() const { return params_; }
  const ReferenceProfile& profile() const { return reference_.profile(); }
  TrackerPhase phase() const { return phases_.phase(); }
  /// Start of the terminal phase (range control in the tracker; no replans below it).
  double terminal_energy_Jpkg() const { return terminal_.terminal_energy_Jpkg(); }

 private:
  void bind_components();
  Status check_input(const RelativeState& s, double dt_s) const;
  double flown_alpha_rad(double alpha_profile_rad) const;
  double flown_bank_rad() const;
  void try_capture(const RelativeState& s);
  CycleContext make_context(const RelativeState& s, double dt_s, const RefPoint& ref, double alpha_flown_rad,
                            double alpha_ref_rad);
  void shape_reference(const CycleContext& c, RefPoint& ref, TrackerOutput& out);
  double available_lift_over_drag(const CycleContext& c, const RefPoint& ref) const;
  DragLoopCommand drag_command(const CycleContext& c, const RefPoint& ref, double lod, TrackerOutput& out);
  int bank_sign(const CycleContext& c, const RefPoint& ref, double sigma_d_rad, TrackerOutput& out);
  void finish_output(const CycleContext& c, TrackerOutput& out);
};

}  // namespace reentry::fsw
