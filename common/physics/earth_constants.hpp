// Physical constants of the Earth and unit conversions: the one home of these numbers.
//
// Constants only: the flight models (fsw/core/models) and the truth models (sim_truth/) each
// build their own gravity, shape and atmosphere from these values and nothing else here, so a
// modelling error cannot hide in both (DESIGN §1).
#pragma once

#include <cmath>

namespace reentry::physics {

// WGS-84 ellipsoid and EGM96 gravitational parameter (NIMA TR8350.2, 3rd ed., tables 3.1-3.4).
inline constexpr double kMuEarth_m3ps2 = 3.986004418e14;
inline constexpr double kEarthEquatorialRadius_m = 6378137.0;
inline constexpr double kEarthFlattening = 1.0 / 298.257223563;
inline constexpr double kEarthRate_radps = 7.292115e-5;

// Standard acceleration of gravity g0 (CGPM 1901; US Standard Atmosphere 1976).
inline constexpr double kStandardGravity_mps2 = 9.80665;

// Angle units: SI (radians) inside, degrees at the edges.
inline constexpr double kRadPerDeg = M_PI / 180.0;
inline constexpr double kDegPerRad = 180.0 / M_PI;

}  // namespace reentry::physics
