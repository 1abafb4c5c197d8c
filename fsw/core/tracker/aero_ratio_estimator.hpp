// Estimation of the vehicle's sensed aerodynamics against the on-board models: the drag ratio
// K = D_sensed / D_model at the navigated height and speed (the product of the density, C_D and
// mass errors, and wind) and the L/D ratio (sensed L/D over the model's at the flown alpha).
// Both are first-order filtered and bounded. No air data: nothing here tells a density error
// from a C_D error.
#pragma once

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

class AeroRatioEstimator {
 public:
  void init(const OnboardModels& models, const TrackerParams& params);
  /// Points at the models and parameters (init, and again after the owner is copied).
  void bind(const OnboardModels& models, const TrackerParams& params) {
    models_ = &models;
    params_ = &params;
  }
  void reset() {
    drag_ratio_ = 1.0;
    lod_ratio_ = 1.0;
  }
  /// K update from the sensed drag at the flown alpha (tracking phases).
  void update_drag_ratio(const RelativeState& s, double alpha_flown_rad, double dt_s);
  /// L/D ratio update, where both accelerations are measurable (drag past the initial-descent
  /// threshold): the planner scales its lift with it, so that replans see the vehicle's true
  /// manoeuvrability (the equilibrium-glide floor (7.7) and the bank extraction depend on L/D).
  void update_lift_over_drag_ratio(const RelativeState& s, double alpha_flown_rad, double dt_s);
  double drag_ratio() const { return drag_ratio_; }
  double lift_over_drag_ratio() const { return lod_ratio_; }

 private:
  const OnboardModels* models_ = nullptr;
  const TrackerParams* params_ = nullptr;
  double drag_ratio_ = 1.0;
  double lod_ratio_ = 1.0;
};

/// The sensed drag and lift as they would be at alpha_rad: scaled by the table's C_D and C_L
/// ratios between alpha_rad and the flown alpha. The drag loop controls the density (altitude);
/// a drag change made by the alpha channel (reversal modulation, load relief) is not an
/// altitude error.
RelativeState referred_to_alpha(const OnboardModels& models, const RelativeState& s, double mach, double alpha_flown_rad,
                                double alpha_rad);

}  // namespace reentry::fsw
