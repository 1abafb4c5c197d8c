// Angle helpers shared by the flight software, the truth simulator and the tools.
#pragma once

#include <cmath>

namespace reentry::physics {

/// The angle brought into (-pi, pi].
inline double wrap_pi(double angle_rad) {
  const double two_pi = 2.0 * M_PI;
  double a = std::fmod(angle_rad, two_pi);
  if (a <= -M_PI) a += two_pi;
  if (a > M_PI) a -= two_pi;
  return a;
}

}  // namespace reentry::physics
