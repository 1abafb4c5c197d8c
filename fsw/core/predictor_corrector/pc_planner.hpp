// The plan of the predictor-corrector law (planner thread): from the state the executive hands
// over, the state at adoption time (on-board equations, the flown bank held over the plan
// latency), the sensed density ratio K of that state and the in-flight L/D estimate, the final
// bank sigma_f of the TAEM glide, and the corrector's sigma_0 (corrector.hpp). The plan handed
// back is the best prediction sampled over energy (drag, altitude, speed, flight path, heading,
// signed bank, alpha), which the cycle flies: the bank magnitude as feed-forward, the altitude
// rate as the damping reference. Fixed capacity, no heap after init(), bounded loops.
#pragma once

#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "predictor_corrector/corrector.hpp"
#include "predictor_corrector/pc_guidance.hpp"
#include "predictor_corrector/pc_params.hpp"
#include "predictor_corrector/point_mass.hpp"
#include "predictor_corrector/predictor.hpp"

namespace reentry::fsw {

struct PcPlanDiagnostics {
  Status status = Status::kInvalidInput;
  bool converged = false;
  int predictions = 0;
  double sigma0_rad = 0.0;
  double sigmaf_rad = 0.0;
  double alpha_shift_rad = 0.0;  // ranging alpha within the band
  double control = 0.0;          // the corrector's free parameter (BankProfile::control)
  double density_ratio = 1.0;    // K of the plan's state
  double lift_scale = 1.0;       // L/D estimate used
  double miss_along_m = 0.0;     // predicted along-track to go at TAEM (> 0 short)
  double miss_cross_m = 0.0;
  double final_altitude_m = 0.0; // predicted, above the ellipsoid
  double final_heading_err_rad = 0.0;
  int reversals = 0;
  Prediction best;
};

/// Timing of the executive the plan must know: the state it receives was advanced over the
/// latency by the executive's first-order energy model (exec::predict_state).
struct PcPlanTiming {
  int latency_ticks = 0;
  double tick_s = 0.1;
};

class PredictorCorrectorPlanner {
 public:
  PredictorCorrectorPlanner() = default;
  // Its components point at its own models and parameters.
  PredictorCorrectorPlanner(const PredictorCorrectorPlanner&) = delete;
  PredictorCorrectorPlanner& operator=(const PredictorCorrectorPlanner&) = delete;
  /// The models and the alpha profile are copied; capture_drag_mps2 is the initial-descent
  /// threshold (the tracker's and the executive's, [guidance] initial_descent_drag_mps2).
  Status init(const OnboardModels& models, const AlphaProfile& alpha_profile, const GuidanceMission& mission,
              const PredictorCorrectorParams& params, double capture_drag_mps2, const PcPlanTiming& timing);
  /// Plan from the executive's state. No allocation. out.status mirrors the result.
  Status plan(const RelativeState& from, ReferenceProfile& out);
  const PcPlanDiagnostics& diagnostics() const { return diag_; }
  /// RelativeState at the mission entry interface (wings level, drag from the on-board models).
  RelativeState entry_state() const;
  double entry_energy_Jpkg() const { return entry_energy_; }
  double taem_energy_Jpkg() const { return taem_energy_; }
  double taem_target_altitude_m() const { return taem_altitude_; }
  const PredictorCorrectorParams& params() const { return params_; }
  /// Tests and tools: the prediction of one bank profile from a state at its own energy,
  /// K and L/D scale as given (no latency), profile sampled into `record` and the attitude into
  /// `trace` if given; sigmaf_rad >= 0: that final bank, else the plan's rule.
  Prediction predict(const RelativeState& s, double sigma0_rad, double density_ratio, ReferenceProfile* record,
                     double sigmaf_rad = -1.0, PredictionTrace* trace = nullptr);
  /// The same for any member of the plan's family (bank_family() with its control set), its
  /// terminal line aimed at bank.terminal_altitude_m (0: the target TAEM altitude).
  Prediction predict_profile(const RelativeState& s, BankProfile bank, double density_ratio, ReferenceProfile* record,
                             PredictionTrace* trace = nullptr);
  /// The plan's one-parameter family of bank and alpha profiles (BankProfile), control unset.
  BankProfile bank_family() const;
  /// The final bank of the TAEM glide at density ratio K (with the present L/D estimate).
  double final_bank_rad(double density_ratio) const;

 private:
  PredictionStart start_from(const RelativeState& from, double& density_ratio);
  double taem_altitude_target();  // also sets taem_aim_min_m_ and the range aim's span
  void fill(const CorrectorResult& r, const BankProfile& bank, ReferenceProfile& out) const;
  CorrectorResult solve(const PredictionStart& start, BankProfile& bank, ReferenceProfile& out);
  /// sigma_0 out of reach (r kRangeTooLong / kRangeTooShort): the terminal aim as the range
  /// control (params terminal_range_*); r, bank's aim and out take the best prediction.
  void range_by_terminal_aim(const PredictionStart& start, BankProfile& bank, CorrectorResult& r, ReferenceProfile& out);
  /// Still long after that: the bank's side held without corridor reversals down to an energy
  /// (params reversal_hold_predictions); r, bank's hold and out take the best prediction.
  void range_by_reversal_hold(const PredictionStart& start, BankProfile& bank, CorrectorResult& r, ReferenceProfile& out);

  OnboardModels models_;
  AlphaProfile alpha_profile_;
  GuidanceMission mission_;
  PredictorCorrectorParams params_;
  PcPlanTiming timing_;
  PointMassModel model_;
  PcLateral lateral_;
  Predictor predictor_;
  Corrector corrector_;
  ReferenceProfile scratch_;
  double capture_drag_mps2_ = 0.0;
  double entry_energy_ = 0.0;
  double taem_energy_ = 0.0;
  double taem_altitude_ = 0.0;
  PcLimits limits_;              // the mission's limits as the law plans them (pc_limits_from)
  PcLimits limits_unmargined_;   // the same without the planned margin (the reversal hold's check)
  double taem_aim_min_m_ = 0.0;  // lowest TAEM altitude of the band within q and q alpha
  double range_aim_lo_m_ = 0.0;  // span of the terminal aim as the range control (range_by_terminal_aim)
  double range_aim_hi_m_ = 0.0;
  // The last plan's bank profile: its magnitude at the new start energy is the first guess.
  bool have_last_ = false;
  BankProfile last_bank_;
  double last_hold_Jpkg_ = 0.0;     // the last plan's reversal hold (range_by_reversal_hold), 0: none
  double terminal_offset_m_ = 0.0;  // the terminal line's aim below the target, learnt from the TAEM altitude
  bool initialised_ = false;
  PcPlanDiagnostics diag_;
};

}  // namespace reentry::fsw
