// Navigation adapter of the flight software: inertial navigation output (position, velocity,
// sensed aerodynamic acceleration, Earth rotation angle) -> the Earth-relative state guidance
// works with. Independent of the truth simulator's frame code by design.
#pragma once

#include "guidance_types.hpp"

namespace reentry::fsw {

/// Converts one navigation sample. r_I, v_I in the inertial frame whose Z axis is the Earth's
/// rotation axis and which coincides with the Earth-fixed frame at zero rotation angle.
/// Drag is the component of the sensed aero acceleration opposite the Earth-relative
/// velocity, lift the magnitude of the part perpendicular to it (IMU-based, thesis §7).
/// kNonFinite for NaN/inf input, kInvalidInput for a non-positive radius or zero speed.
Status relative_state_from_nav(double t_s, const double r_I_m[3], const double v_I_mps[3],
                               const double aero_accel_I_mps2[3], double earth_rotation_angle_rad,
                               RelativeState& out);

}  // namespace reentry::fsw
