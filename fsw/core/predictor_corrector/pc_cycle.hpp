// The guidance cycle of the predictor-corrector law (GNC thread), once per tick:
//   1. initial descent: the profile's alpha, wings level, until a plan is adopted and the sensed
//      drag reaches the capture threshold (as the prediction assumes);
//   2. bank magnitude: the latest plan's at the present energy (feed-forward), with the
//      altitude-rate damping toward the plan's predicted altitude rate, the constraint bound and
//      the pull-out guard re-applied on the navigated state (pc_guidance.hpp);
//   3. bank sign: the lateral logic of the prediction (corridor about the arrival-line field);
//   4. alpha: the plan's (the mission's profile, shifted within the band by the corrector).
// The rate filters follow (the guidance stack). Sensed drag and L/D ratios against the on-board
// models are estimated with the tracker's estimator (K for telemetry, the L/D ratio for the
// planner). No heap, no exceptions, bounded work.
#pragma once

#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "predictor_corrector/pc_guidance.hpp"
#include "predictor_corrector/pc_params.hpp"
#include "tracker/aero_ratio_estimator.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

struct PcCycleOutput {
  double alpha_rad = 0.0;
  double sigma_rad = 0.0;
  Phase phase = Phase::kInitialDescent;
  double drag_ref_mps2 = 0.0;    // the plan's predicted drag at this energy
  double drag_err_mps2 = 0.0;    // sensed minus predicted
  double heading_err_rad = 0.0;  // heading minus the lateral target heading
  double lift_over_drag_scale = 1.0;
  TrackerTelemetry telemetry;    // the fields whose meaning fits (see pc_cycle.cpp)
};

class PredictorCorrectorCycle {
 public:
  PredictorCorrectorCycle() = default;
  PredictorCorrectorCycle(const PredictorCorrectorCycle&) = delete;  // components point at its members
  PredictorCorrectorCycle& operator=(const PredictorCorrectorCycle&) = delete;

  /// Models and profile are copied; estimator_params: the tracker's ratio filter settings.
  Status init(const OnboardModels& models, const AlphaProfile& alpha_profile, const GuidanceMission& mission,
              const PredictorCorrectorParams& params, const TrackerParams& estimator_params, double capture_drag_mps2);
  /// Copies the plan (no allocation); a plan with fewer than two points is ignored.
  void set_profile(const ReferenceProfile& profile);
  /// alpha and bank out of the rate filters last cycle (what the vehicle flies).
  void set_flown_attitude(double alpha_rad, double sigma_rad) {
    flown_alpha_rad_ = alpha_rad;
    flown_sigma_rad_ = sigma_rad;
    attitude_given_ = true;
  }
  Status step(const RelativeState& s, double dt_s, PcCycleOutput& out);
  bool has_profile() const { return has_profile_; }
  bool captured() const { return captured_; }
  /// The energy below which no plan is requested (the last replan_floor_span_fraction).
  double replan_floor_energy_Jpkg() const;

 private:
  struct PlanPoint {
    double sigma_rad = 0.0, alpha_rad = 0.0, hdot_mps = 0.0, drag_mps2 = 0.0, radius_m = 0.0;
  };
  PlanPoint plan_at(double energy_Jpkg) const;
  void bank_command(const RelativeState& s, double alpha_rad, double alpha_profile_rad, PcCycleOutput& out);
  void write_telemetry(const RelativeState& s, const BankLawInput& in, const BankLawOutput& law,
                       const ArrivalGeometry& g, const PcLateralInput& li, PcCycleOutput& out) const;

  OnboardModels models_;
  AlphaProfile alpha_profile_;
  PredictorCorrectorParams params_;
  TrackerParams estimator_params_;
  TaemTarget taem_{};
  PcLimits limits_;
  PcLateral lateral_;
  AeroRatioEstimator estimator_;
  double alpha_max_rad_ = 0.0;
  double sigma_rate_max_radps_ = 0.0;
  double capture_drag_mps2_ = 0.0;
  double entry_energy_Jpkg_ = 0.0;
  double taem_energy_Jpkg_ = 0.0;
  ReferenceProfile profile_;
  bool has_profile_ = false;
  bool captured_ = false;
  PcLateralState lateral_state_;
  bool attitude_given_ = false;
  double flown_alpha_rad_ = 0.0;
  double flown_sigma_rad_ = 0.0;
  bool initialised_ = false;
};

}  // namespace reentry::fsw
