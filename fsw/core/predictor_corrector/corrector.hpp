// The corrector of the predictor-corrector law (Lu 2014): solves for the one free parameter
// (sigma_0, BankProfile's control u) of the bank profile so that the predicted along-track distance still to go at the
// TAEM energy, z(sigma_0), is zero. z rises with sigma_0 (more bank, more drag, a shorter
// flight). Safeguarded secant: the secant step is bounded (first_step .. 45 deg), a step that
// does not reduce |z| is halved back towards the best point, and once z has changed sign the
// root is kept bracketed (Illinois regula falsi); at most max_predictions predictions.
// When the target is out of reach the minimum-miss answer is the bound of the control that flies
// closest (0: longest flight, its maximum: shortest), or the least miss found when the
// predictions run out without crossing the root, and the status says which way it misses.
// A prediction that skips out or times out counts as far too long; one that is not finite is
// stepped back from. No heap, no exceptions.
#pragma once

#include "guidance_types.hpp"
#include "predictor_corrector/predictor.hpp"

namespace reentry::fsw {

struct CorrectorResult {
  /// kOk: |z| <= miss_tol; kRangeTooShort / kRangeTooLong: out of reach, the bound that
  /// misses least; kNotConverged: predictions used up (best kept); kNonFinite: nothing usable.
  Status status = Status::kNonFinite;
  double control = 0.0;     // the free parameter u of the best prediction (BankProfile)
  double sigma0_rad = 0.0;  // its sigma_0 ...
  double alpha_shift_rad = 0.0;  // ... and alpha shift
  Prediction best;
  int predictions = 0;
  bool converged = false;
};

class Corrector {
 public:
  /// `bank` carries sigma_f and the energies; its sigma0 is the first guess. The best
  /// prediction's profile is sampled into *best_profile (scratch: work space).
  CorrectorResult solve(const Predictor& predictor, const PredictionStart& start, BankProfile bank,
                        const PredictorCorrectorParams& params, int max_predictions, ReferenceProfile* best_profile,
                        ReferenceProfile* scratch);

 private:
  struct Point {
    double x = 0.0;  // control u
    double z = 0.0;  // along-track to go at TAEM (far too long: -1e7)
    bool valid = false;
  };
  Point evaluate(double x);
  double next_guess(const Point& prev, const Point& cur) const;

  const Predictor* predictor_ = nullptr;
  const PredictionStart* start_ = nullptr;
  const PredictorCorrectorParams* params_ = nullptr;
  BankProfile bank_;
  ReferenceProfile* best_profile_ = nullptr;
  ReferenceProfile* scratch_ = nullptr;
  CorrectorResult result_;
  bool have_best_ = false;
  Point neg_, pos_;            // bracket ends: z < 0 (long), z > 0 (short)
  bool have_neg_ = false, have_pos_ = false;
  int illinois_side_ = 0;      // end kept twice in a row (Illinois halving of its z)
};

}  // namespace reentry::fsw
