#include "environment/earth.hpp"

#include <cmath>

namespace reentry::truth {

double geocentric_latitude_rad(const Eigen::Vector3d& r_R) {
  return std::atan2(r_R.z(), std::hypot(r_R.x(), r_R.y()));
}

double longitude_rad(const Eigen::Vector3d& r_R) { return std::atan2(r_R.y(), r_R.x()); }

double altitude_m(const Eigen::Vector3d& r_R, ShapeModel shape) {
  const double r = r_R.norm();
  const double re = EarthConstants::kEquatorialRadius_m;
  if (shape == ShapeModel::kSphere) return r - re;
  // (2.12) e = (Re - Rp) / Re = flattening; (2.13) h = r - Re (1 - e sin^2 delta)
  const double s = r > 0.0 ? r_R.z() / r : 0.0;
  return r - re * (1.0 - EarthConstants::kFlattening * s * s);
}

GreatCircleLeg great_circle_leg(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad) {
  const Eigen::Vector3d n1(std::cos(lat1_rad) * std::cos(lon1_rad), std::cos(lat1_rad) * std::sin(lon1_rad),
                           std::sin(lat1_rad));
  const Eigen::Vector3d n2(std::cos(lat2_rad) * std::cos(lon2_rad), std::cos(lat2_rad) * std::sin(lon2_rad),
                           std::sin(lat2_rad));
  const double dlon = lon2_rad - lon1_rad;
  GreatCircleLeg leg;
  leg.arc_rad = std::atan2(n1.cross(n2).norm(), n1.dot(n2));
  leg.initial_bearing_rad = std::atan2(std::sin(dlon) * std::cos(lat2_rad), std::cos(lat1_rad) * std::sin(lat2_rad) -
                                                                               std::sin(lat1_rad) * std::cos(lat2_rad) * std::cos(dlon));
  return leg;
}

double radius_at_altitude_m(double geocentric_latitude_rad, double altitude_m, ShapeModel shape) {
  const double re = EarthConstants::kEquatorialRadius_m;
  if (shape == ShapeModel::kSphere) return re + altitude_m;
  const double s = std::sin(geocentric_latitude_rad);
  return altitude_m + re * (1.0 - EarthConstants::kFlattening * s * s);  // (2.13)
}

Eigen::Matrix3d rotation_I_to_R(double t_s) {
  const double a = EarthConstants::kOmega_radps * t_s;
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d m;
  m << c, s, 0.0,
      -s, c, 0.0,
      0.0, 0.0, 1.0;
  return m;
}

Eigen::Matrix3d dcm_R_to_V(double lon, double lat) {
  const double cl = std::cos(lon), sl = std::sin(lon);
  const double cd = std::cos(lat), sd = std::sin(lat);
  Eigen::Matrix3d m;
  m << -sd * cl, -sd * sl, cd,   // north
      -sl, cl, 0.0,              // east
      -cd * cl, -cd * sl, -sd;   // down
  return m;
}

}  // namespace reentry::truth
