// Earth constants, shape and reference frames of the truth simulator (thesis 2.1-2.3).
#pragma once

#include <Eigen/Dense>

namespace reentry::truth {

struct EarthConstants {
  static constexpr double kMu_m3ps2 = 3.986004418e14;        // WGS84 / EGM96
  static constexpr double kOmega_radps = 7.292115e-5;        // Earth rotation rate
  static constexpr double kEquatorialRadius_m = 6378137.0;   // WGS84
  static constexpr double kFlattening = 1.0 / 298.257223563; // WGS84
};

enum class ShapeModel { kSphere, kOblate };

/// Altitude above the reference surface. Sphere: r - Re. Oblate: (2.12)-(2.13),
/// h = r - Re (1 - f sin^2(delta)), delta the geocentric latitude.
double altitude_m(const Eigen::Vector3d& r_R, ShapeModel shape);

/// Radius of the point at altitude h above the reference surface at geocentric latitude
/// delta: the inverse of altitude_m, r = h + Re (1 - f sin^2(delta)) for the oblate shape.
double radius_at_altitude_m(double geocentric_latitude_rad, double altitude_m, ShapeModel shape);

/// Great circle from point 1 to point 2 on a sphere (geocentric latitudes): the central
/// angle between them and the initial bearing at point 1 (from north, clockwise).
struct GreatCircleLeg {
  double arc_rad = 0.0;
  double initial_bearing_rad = 0.0;
};
GreatCircleLeg great_circle_leg(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad);

/// Geocentric latitude delta of a position in the rotating frame R.
double geocentric_latitude_rad(const Eigen::Vector3d& r_R);

/// Longitude tau (east positive) of a position in the rotating frame R.
double longitude_rad(const Eigen::Vector3d& r_R);

/// Rotation from the inertial frame I to the Earth-fixed frame R: R rotates about Z
/// at kOmega_radps and is aligned with I at t = 0. v_R = rotation_I_to_R(t) * v_I.
Eigen::Matrix3d rotation_I_to_R(double t_s);

/// DCM from the rotating frame R to the vertical frame V (thesis 2.1: X north,
/// Y east, Z down) at longitude lon and geocentric latitude lat. v_V = dcm * v_R.
Eigen::Matrix3d dcm_R_to_V(double longitude_rad, double latitude_rad);

}  // namespace reentry::truth
