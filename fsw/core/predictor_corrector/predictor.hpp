// The predictor of the predictor-corrector law (Lu 2014): from a state, the on-board point-mass
// equations (point_mass.hpp) are integrated by fixed-step RK4 in time down to the TAEM energy
// with the law's own rules flown inside the prediction, each step as one guidance period:
//   - wings level until the sensed drag reaches the capture threshold (initial descent);
//   - bank magnitude |sigma|(E) linear from sigma_0 at the start to sigma_f at the TAEM energy,
//     with the altitude-rate damping toward the quasi-equilibrium glide, the constraint bound
//     and the pull-out guard (pc_guidance.hpp);
//   - the lateral logic (bank sign, reversals) and the mission's bank rate and acceleration
//     limits (the rate filter of the cycle, at the step), the bank linear over each step: a
//     reversal's roll time and range cost are in the prediction.
// The end state is located on the TAEM energy by a partial step. Along the way the predicted
// profile (drag, altitude, speed, flight path, heading, bank, alpha) is sampled on 201
// energies for the plan. No heap, no exceptions; at most params.max_steps steps.
#pragma once

#include "guidance_types.hpp"
#include "predictor_corrector/pc_guidance.hpp"
#include "predictor_corrector/pc_params.hpp"
#include "predictor_corrector/point_mass.hpp"

namespace reentry::fsw {

struct PredictionStart {
  PointMassState x;
  double sigma_flown_rad = 0.0;  // bank flown at the start (the rate filter's state)
  PcLateralState lateral;          // bank side being flown (sign 0: none yet, chosen at capture)
  bool captured = false;         // past the initial descent
};

enum class PredictionEnd : std::int8_t { kTaem, kGround, kSkipOut, kTimeOut, kNonFinite };

struct Prediction {
  PredictionEnd end = PredictionEnd::kNonFinite;
  PointMassState final_state;
  double energy_Jpkg = 0.0;
  double time_s = 0.0;           // flight time from the start
  double along_m = 0.0;          // along-track distance still to go to the aim point at the end (> 0: short)
  double cross_m = 0.0;          // off the arrival line at the end
  double heading_err_rad = 0.0;  // final heading minus the required TAEM heading
  double altitude_m = 0.0;       // final height above the ellipsoid
  double range_flown_m = 0.0;    // ground distance flown (R_eq sphere)
  double heat_flux_max_Wpm2 = 0.0, q_max_Pa = 0.0, q_alpha_max_Pa_rad = 0.0, aero_accel_max_mps2 = 0.0;
  int reversals = 0;
  double first_reversal_energy_Jpkg = 0.0;
  int first_sign = 0;            // bank sign chosen first (at capture, or the start's)
  int steps = 0;
  /// Reached the TAEM energy or the ground: along_m is a signed miss the corrector can use.
  bool usable() const { return end == PredictionEnd::kTaem || end == PredictionEnd::kGround; }
};

/// What one prediction flies, a one-parameter family in the corrector's control u (radians of
/// bank, monotonic in range: more u, a shorter flight):
///   - |sigma| linear in energy (Lu 2014) from sigma0 at e0 to sigma_f = share sigma0 + (1 - share)
///     sigma_glide at the TAEM energy ef (share 0: Lu's fixed sigma_f, the TAEM glide's bank;
///     1: a constant bank);
///   - alpha: the mission's profile shifted by alpha_shift within the band (ranging alpha: lower
///     alpha, more L/D, on the profiles of all our vehicles, which fly above the L/D-max alpha),
///     the shift ramped out over the terminal phase so the TAEM alpha is the profile's.
/// u in [0, s_lat]: sigma0 = u at the full shift -band (a range-short flight keeps the bank
/// s_lat it needs to turn and flies the band's L/D first); [s_lat, s_lat + w]: sigma0 = s_lat,
/// the shift from -band to 0; then sigma0 = u - w up to bank_max at no shift; last [0, w]
/// beyond: sigma0 = bank_max, the shift from 0 to +band (a range-long flight); farthest, at
/// +band, sigma0 from bank_max on to bank_far (lift down: a range-long flight that must shed
/// energy, e.g. after a shallow entry). w = band times alpha_control_scale (0 without a band).
struct BankProfile {
  double control = 0.0;            // u
  double lateral_bank_rad = 0.0;   // s_lat
  double bank_max_rad = 0.0;
  double bank_far_rad = 0.0;       // >= bank_max: the range-long end's bank (lift down)
  double alpha_band_rad = 0.0;
  double alpha_span = 0.0;         // w
  double sigma_glide_rad = 0.0;
  double final_share = 0.0;
  double e0_Jpkg = 0.0;
  double ef_Jpkg = 0.0;
  double terminal_altitude_m = 0.0;
  double reversal_hold_Jpkg = 0.0;  // side held (no corridor or capture-guard reversal) above it; 0: none
  double control_max() const { return bank_max_rad + 2.0 * alpha_span + (bank_far_rad - bank_max_rad); }
  double sigma0_rad() const;
  double alpha_shift_rad() const;
  double sigmaf_rad() const { return final_share * sigma0_rad() + (1.0 - final_share) * sigma_glide_rad; }
  double at(double energy_Jpkg) const;
  /// d|sigma|/dE of the profile.
  double slope_per_Jpkg() const { return e0_Jpkg > ef_Jpkg ? (sigma0_rad() - sigmaf_rad()) / (e0_Jpkg - ef_Jpkg) : 0.0; }
  /// The control that flies bank sigma0 without alpha shift (clamped to the family).
  double control_for_bank(double sigma0_rad) const;
};

/// The attitude flown at every step boundary of a prediction (the bank is linear between
/// them): what an open-loop flight of the same schedule needs (tests, tools).
struct PredictionTrace {
  static constexpr int kCapacity = PredictorCorrectorParams::kMaxSteps + 1;
  int n = 0;
  double t_s[kCapacity] = {};
  double sigma_rad[kCapacity] = {};
  double alpha_rad[kCapacity] = {};
};

struct PredictorConfig {
  PcLimits limits;
  double capture_drag_mps2 = 0.0;   // initial descent until the sensed drag reaches this
  double sigma_rate_max_radps = 0.0;
  double sigma_accel_max_radps2 = 0.0;
  double skip_out_altitude_m = 0.0;  // above this after capture: skip-out
  TerminalAltitude terminal;        // terminal phase (its target: the bank profile's)
};

class Predictor {
 public:
  /// The model, lateral logic and parameters are referenced (they outlive the predictor); the
  /// model's alpha shift is set by each prediction.
  Status init(PointMassModel* model, const PcLateral* lateral, const PredictorCorrectorParams* params,
              const PredictorConfig& config);
  /// Flies the prediction from `start` with `bank`; samples the profile into `record` and the
  /// attitude at the step boundaries into `trace` if given.
  Prediction run(const PredictionStart& start, const BankProfile& bank, ReferenceProfile* record,
                 PredictionTrace* trace = nullptr) const;
  const PredictorConfig& config() const { return config_; }

 private:
  /// The signed bank command of one guidance step (the lateral state is updated).
  double command(const PointMassState& x, const AeroSample& a, double energy, const BankProfile& bank,
                 double sigma_flown_rad, PcLateralState& lateral) const;
  /// Alpha of one step: the reversal's lift modulation with its heat relief, then load relief.
  double step_alpha_rad(const AeroSample& a, double v_mps, double e, double sigma_cmd_rad, double sigma_mid_rad,
                        bool reversing) const;
  void note_air(const AeroSample& a, double v_mps, Prediction& pr) const;
  /// One step from x (air_of_x: an AeroSample of x, whose air part the first RK4 stage uses).
  bool step(const PointMassState& x, const AeroSample& air_of_x, double e, double sigma_a, double sigma_b, double ef,
            PointMassState& xn, double& en, double& h) const;
  void finish(const PointMassState& x, double e, double t, double range_rad, Prediction& pr) const;

  PointMassModel* model_ = nullptr;  // its alpha shift is set per prediction
  const PcLateral* lateral_ = nullptr;
  const PredictorCorrectorParams* params_ = nullptr;
  PredictorConfig config_;
};

/// Local density scale height H = -1 / (d ln rho / dh) of the on-board atmosphere, bounded to
/// [3, 15] km (a table's thin layers).
double local_scale_height_m(const OnboardModels& models, double altitude_m);

}  // namespace reentry::fsw
