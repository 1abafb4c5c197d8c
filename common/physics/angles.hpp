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

/// The angle moved by whole turns to within pi of `reference` (unchanged when it already is),
/// so that a path from the reference to it is continuous through +-pi.
inline double unwrap_near(double angle_rad, double reference_rad) {
  const double d = angle_rad - reference_rad;
  return std::fabs(d) > M_PI ? reference_rad + wrap_pi(d) : angle_rad;
}

}  // namespace reentry::physics
