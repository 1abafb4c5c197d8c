#include "tracker/aero_ratio_estimator.hpp"

#include <cmath>

namespace reentry::fsw {

void AeroRatioEstimator::init(const OnboardModels& models, const TrackerParams& params) {
  bind(models, params);
  reset();
}

void AeroRatioEstimator::update_drag_ratio(const RelativeState& s, double alpha_rad, double dt_s) {
  // The on-board altitude is above the R_eq sphere while the air is stratified over the
  // ellipsoid, so the model is evaluated at the height above the ellipsoid (first order in f).
  const TrackerParams& p = *params_;
  const double h_ellipsoid_m = s.radius_m - surface_radius_m(s.latitude_rad);
  const double d_model = models_->drag_mps2(alpha_rad, h_ellipsoid_m, s.velocity_mps);
  if (!(d_model > p.min_drag_mps2) || !(s.drag_mps2 > p.min_drag_mps2)) return;
  const double ratio = clamp(s.drag_mps2 / d_model, p.drag_ratio_min, p.drag_ratio_max);
  drag_ratio_ += clamp(dt_s / p.ratio_time_constant_s, 0.0, 1.0) * (ratio - drag_ratio_);
}

void AeroRatioEstimator::update_lift_over_drag_ratio(const RelativeState& s, double alpha_rad, double dt_s) {
  const TrackerParams& p = *params_;
  if (!(s.drag_mps2 >= p.initial_descent_drag_mps2) || !(s.lift_mps2 > 0.0)) return;
  double cl, cd;
  models_->aero().coefficients(alpha_rad, models_->mach(s.altitude_m, s.velocity_mps), cl, cd);
  if (!(cl > 0.0) || !(cd > 0.0)) return;
  const double ratio = clamp((s.lift_mps2 / s.drag_mps2) / (cl / cd), p.lod_ratio_min, p.lod_ratio_max);
  lod_ratio_ += clamp(dt_s / p.ratio_time_constant_s, 0.0, 1.0) * (ratio - lod_ratio_);
}

RelativeState referred_to_alpha(const OnboardModels& models, const RelativeState& s, double mach, double alpha_flown_rad,
                                double alpha_rad) {
  RelativeState out = s;
  double cl, cd, cl_flown, cd_flown;
  models.aero().coefficients(alpha_rad, mach, cl, cd);
  models.aero().coefficients(alpha_flown_rad, mach, cl_flown, cd_flown);
  if (cd > 0.0 && cd_flown > 0.0) out.drag_mps2 = s.drag_mps2 * cd / cd_flown;
  if (cl > 0.0 && cl_flown > 0.0) out.lift_mps2 = s.lift_mps2 * cl / cl_flown;
  return out;
}

}  // namespace reentry::fsw
