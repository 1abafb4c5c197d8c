// Earth constants, shape and reference frames of the truth simulator (thesis 2.1-2.3).
#pragma once

#include <Eigen/Dense>

#include <cmath>

#include "environment/scalar.hpp"
#include "physics/earth_constants.hpp"

namespace reentry::truth {

struct EarthConstants {
  static constexpr double kMu_m3ps2 = physics::kMuEarth_m3ps2;
  static constexpr double kOmega_radps = physics::kEarthRate_radps;
  static constexpr double kEquatorialRadius_m = physics::kEarthEquatorialRadius_m;
  static constexpr double kFlattening = physics::kEarthFlattening;
};

enum class ShapeModel { kSphere, kOblate };

/// Altitude above the reference surface. Sphere: r - Re. Oblate: (2.12)-(2.13),
/// h = r - Re (1 - f sin^2(delta)), delta the geocentric latitude. Scalar-generic
/// (environment/scalar.hpp), like the frame functions below.
template <class T>
T altitude_m(const Eigen::Matrix<T, 3, 1>& r_R, ShapeModel shape);
inline double altitude_m(const Eigen::Vector3d& r_R, ShapeModel shape) { return altitude_m<double>(r_R, shape); }

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
template <class T>
T geocentric_latitude_rad(const Eigen::Matrix<T, 3, 1>& r_R) {
  using std::atan2;
  return atan2(r_R.z(), scalar::hypot(r_R.x(), r_R.y()));
}
inline double geocentric_latitude_rad(const Eigen::Vector3d& r_R) { return geocentric_latitude_rad<double>(r_R); }

/// Longitude tau (east positive) of a position in the rotating frame R.
template <class T>
T longitude_rad(const Eigen::Matrix<T, 3, 1>& r_R) {
  using std::atan2;
  return atan2(r_R.y(), r_R.x());
}
inline double longitude_rad(const Eigen::Vector3d& r_R) { return longitude_rad<double>(r_R); }

/// Rotation from the inertial frame I to the Earth-fixed frame R: R rotates about Z
/// at kOmega_radps and is aligned with I at t = 0. v_R = rotation_I_to_R(t) * v_I.
template <class T>
Eigen::Matrix<T, 3, 3> rotation_I_to_R(const T& t_s) {
  using std::cos;
  using std::sin;
  const T a = EarthConstants::kOmega_radps * t_s;
  const T c = cos(a), s = sin(a);
  Eigen::Matrix<T, 3, 3> m;
  m << c, s, T(0.0),
      -s, c, T(0.0),
      T(0.0), T(0.0), T(1.0);
  return m;
}
inline Eigen::Matrix3d rotation_I_to_R(double t_s) { return rotation_I_to_R<double>(t_s); }

/// DCM from the rotating frame R to the vertical frame V (thesis 2.1: X north,
/// Y east, Z down) at longitude lon and geocentric latitude lat. v_V = dcm * v_R.
template <class T>
Eigen::Matrix<T, 3, 3> dcm_R_to_V(const T& lon, const T& lat) {
  using std::cos;
  using std::sin;
  const T cl = cos(lon), sl = sin(lon);
  const T cd = cos(lat), sd = sin(lat);
  Eigen::Matrix<T, 3, 3> m;
  m << -sd * cl, -sd * sl, cd,   // north
      -sl, cl, T(0.0),           // east
      -cd * cl, -cd * sl, -sd;   // down
  return m;
}
inline Eigen::Matrix3d dcm_R_to_V(double longitude_rad, double latitude_rad) {
  return dcm_R_to_V<double>(longitude_rad, latitude_rad);
}

template <class T>
T altitude_m(const Eigen::Matrix<T, 3, 1>& r_R, ShapeModel shape) {
  const T r = r_R.norm();
  const double re = EarthConstants::kEquatorialRadius_m;
  if (shape == ShapeModel::kSphere) return r - re;
  // (2.12) e = (Re - Rp) / Re = flattening; (2.13) h = r - Re (1 - e sin^2 delta)
  const T s = scalar::value(r) > 0.0 ? T(r_R.z() / r) : T(0.0);
  return r - re * (1.0 - EarthConstants::kFlattening * s * s);
}

}  // namespace reentry::truth
