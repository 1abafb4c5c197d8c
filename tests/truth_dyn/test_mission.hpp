// X-33 reference mission (thesis table 3.3) built in code, with a synthetic aerodynamic model
// linear in alpha and independent of Mach, so tests can evaluate CL and CD exactly themselves.
#pragma once

#include "reentry/config/mission.hpp"

namespace truth_test {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
// CL = kCl1 * alpha, CD = kCd0 + kCd1 * alpha (alpha in rad); bilinear interpolation is exact.
constexpr double kCl1 = 0.86;
constexpr double kCd0 = 0.05;
constexpr double kCd1 = 0.8;
inline double cl_of(double alpha_rad) { return kCl1 * alpha_rad; }
inline double cd_of(double alpha_rad) { return kCd0 + kCd1 * alpha_rad; }

reentry::config::Mission x33_test_mission();

}  // namespace truth_test
