#include "nav/relative_state.hpp"

#include <cmath>

#include "models/onboard_models.hpp"

namespace reentry::fsw {

Status relative_state_from_nav(double t_s, const double r_I_m[3], const double v_I_mps[3],
                               const double aero_accel_I_mps2[3], double earth_rotation_angle_rad,
                               RelativeState& out) {
  const double in[] = {t_s, r_I_m[0], r_I_m[1], r_I_m[2], v_I_mps[0], v_I_mps[1], v_I_mps[2],
                       aero_accel_I_mps2[0], aero_accel_I_mps2[1], aero_accel_I_mps2[2],
                       earth_rotation_angle_rad};
  for (double x : in) {
    if (!std::isfinite(x)) return Status::kNonFinite;
  }
  const double r = std::sqrt(r_I_m[0] * r_I_m[0] + r_I_m[1] * r_I_m[1] + r_I_m[2] * r_I_m[2]);
  if (!(r > 0.0)) return Status::kInvalidInput;

  // Earth-relative velocity in the inertial frame: v_I - omega x r_I (omega along +Z).
  const double w = kEarthRate_radps;
  const double vrel_I[3] = {v_I_mps[0] + w * r_I_m[1], v_I_mps[1] - w * r_I_m[0], v_I_mps[2]};
  const double speed = std::sqrt(vrel_I[0] * vrel_I[0] + vrel_I[1] * vrel_I[1] + vrel_I[2] * vrel_I[2]);
  if (!(speed > 0.0)) return Status::kInvalidInput;

  // Rotate to the Earth-fixed frame: rotation by -theta about Z.
  const double c = std::cos(earth_rotation_angle_rad), s = std::sin(earth_rotation_angle_rad);
  const double x = c * r_I_m[0] + s * r_I_m[1];
  const double y = -s * r_I_m[0] + c * r_I_m[1];
  const double z = r_I_m[2];
  const double vx = c * vrel_I[0] + s * vrel_I[1];
  const double vy = -s * vrel_I[0] + c * vrel_I[1];
  const double vz = vrel_I[2];

  const double lon = std::atan2(y, x);
  const double lat = std::asin(z / r);
  const double slon = std::sin(lon), clon = std::cos(lon), slat = std::sin(lat), clat = std::cos(lat);
  // Local north, east, up components of the Earth-relative velocity.
  const double v_up = clat * clon * vx + clat * slon * vy + slat * vz;
  const double v_east = -slon * vx + clon * vy;
  const double v_north = -slat * clon * vx - slat * slon * vy + clat * vz;

  // Sensed aerodynamic acceleration split along / across the Earth-relative velocity.
  const double a_along = (aero_accel_I_mps2[0] * vrel_I[0] + aero_accel_I_mps2[1] * vrel_I[1] +
                          aero_accel_I_mps2[2] * vrel_I[2]) / speed;
  const double a2 = aero_accel_I_mps2[0] * aero_accel_I_mps2[0] + aero_accel_I_mps2[1] * aero_accel_I_mps2[1] +
                    aero_accel_I_mps2[2] * aero_accel_I_mps2[2];
  const double a_perp2 = a2 - a_along * a_along;

  out.t_s = t_s;
  out.radius_m = r;
  out.altitude_m = r - kEarthRadius_m;
  out.longitude_rad = lon;
  out.latitude_rad = lat;
  out.velocity_mps = speed;
  out.flight_path_rad = std::asin(std::fmax(-1.0, std::fmin(1.0, v_up / speed)));
  out.heading_rad = std::atan2(v_east, v_north);
  out.energy_Jpkg = specific_energy_Jpkg(r, speed);  // (7.8)
  out.drag_mps2 = -a_along;
  out.lift_mps2 = a_perp2 > 0.0 ? std::sqrt(a_perp2) : 0.0;
  return Status::kOk;
}

}  // namespace reentry::fsw
