#include "environment/earth.hpp"

#include <cmath>

namespace reentry::truth {

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

}  // namespace reentry::truth
