// Rate and acceleration limiter for one command channel (bank angle or angle of attack):
// the output follows the guidance command as fast as the vehicle may rotate (thesis §3.1.3
// control constraints: |rate| <= rate_max, |acceleration| <= accel_max) and brakes in time
// so it reaches a constant target without overshoot (v_allowed = sqrt(2 a |e|)).
// Known limitation: the output lands exactly on the target at a GNC tick, so when a short
// move (shorter than rate_max^2 / accel_max) does not end on a tick, the landing step brakes
// up to about 11 % harder than accel_max (tests/filter); long moves respect it exactly.
#pragma once

#include "guidance_types.hpp"

namespace reentry::fsw {

class RateFilter {
 public:
  /// Limits must be positive and finite; dt is the GNC period. Output starts at 0.
  Status init(double rate_max, double accel_max, double dt_s);
  /// Optional output bounds (e.g. alpha in [0, alpha_max]).
  void set_bounds(double lower, double upper);
  /// Sets the output (and zero rate), e.g. to the first command.
  void reset(double value);
  /// One GNC period towards `target`; returns the limited output. NaN targets hold the output.
  double step(double target);

  double value() const { return x_; }
  double rate() const { return v_; }

 private:
  double rate_max_ = 0.0;
  double accel_max_ = 0.0;
  double dt_s_ = 0.0;
  double lower_ = -1e300;
  double upper_ = 1e300;
  double x_ = 0.0;
  double v_ = 0.0;
};

}  // namespace reentry::fsw
