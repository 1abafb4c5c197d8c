#include "filter/rate_filter.hpp"

#include <cmath>

namespace reentry::fsw {

Status RateFilter::init(double rate_max, double accel_max, double dt_s) {
  if (!(rate_max > 0.0) || !(accel_max > 0.0) || !(dt_s > 0.0) || !std::isfinite(rate_max) ||
      !std::isfinite(accel_max) || !std::isfinite(dt_s)) {
    return Status::kInvalidInput;
  }
  rate_max_ = rate_max;
  accel_max_ = accel_max;
  dt_s_ = dt_s;
  x_ = 0.0;
  v_ = 0.0;
  return Status::kOk;
}

void RateFilter::set_bounds(double lower, double upper) {
  if (lower <= upper) {
    lower_ = lower;
    upper_ = upper;
    x_ = clamp(x_, lower_, upper_);
  }
}

void RateFilter::reset(double value) {
  if (std::isfinite(value)) x_ = clamp(value, lower_, upper_);
  v_ = 0.0;
}

double RateFilter::step(double target) {
  if (dt_s_ <= 0.0 || !std::isfinite(target)) return x_;
  target = clamp(target, lower_, upper_);
  const double e = target - x_;
  const double dv_max = accel_max_ * dt_s_;
  // Largest speed from which the vehicle can still stop at the target (discrete braking
  // curve: after this step the remaining error must be coverable while decelerating).
  const double brake = std::sqrt(2.0 * accel_max_ * std::fabs(e) + 0.25 * dv_max * dv_max) - 0.5 * dv_max;
  double v_des = std::copysign(std::fmin(rate_max_, std::fmin(brake, std::fabs(e) / dt_s_)), e);
  const double v_new = v_ + clamp(v_des - v_, -dv_max, dv_max);
  double x_new = x_ + v_new * dt_s_;
  // Never pass the target from this side (no overshoot); the rate is what was flown.
  if ((e >= 0.0 && x_new > target) || (e <= 0.0 && x_new < target)) x_new = target;
  v_ = (x_new - x_) / dt_s_;
  x_ = clamp(x_new, lower_, upper_);
  return x_;
}

}  // namespace reentry::fsw
