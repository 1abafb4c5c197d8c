#include "planner/mission_geometry.hpp"

#include <cmath>

namespace reentry::fsw {

namespace {

// (7.1) cos b = cos c cos a + sin c sin a cos B (co-latitudes c = 90 - lat1, a = 90 - lat2,
// B = lon2 - lon1, fig. 7.1), evaluated in the haversine form for accuracy.
double haversine_arc_rad(double lat1_rad, double lat2_rad, double d_lon_rad, double cos_lat1, double cos_lat2) {
  const double s_lat = std::sin(0.5 * (lat2_rad - lat1_rad));
  const double s_lon = std::sin(0.5 * d_lon_rad);
  double hav = s_lat * s_lat + cos_lat1 * cos_lat2 * s_lon * s_lon;
  hav = hav < 0.0 ? 0.0 : (hav > 1.0 ? 1.0 : hav);
  return 2.0 * std::asin(std::sqrt(hav));
}

// (7.2) cos A = (cos a - cos b cos c) / (sin b sin c), quadrant from sin A = sin B sin a / sin b:
// the azimuth at point 1 towards point 2, d_lon = lon2 - lon1.
double initial_azimuth_rad(double d_lon_rad, double sin_lat1, double cos_lat1, double sin_lat2, double cos_lat2) {
  return std::atan2(std::sin(d_lon_rad) * cos_lat2, cos_lat1 * sin_lat2 - sin_lat1 * cos_lat2 * std::cos(d_lon_rad));
}

}  // namespace

GreatCircle great_circle(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad) {
  const double d_lon = lon2_rad - lon1_rad;
  const double c1 = std::cos(lat1_rad), c2 = std::cos(lat2_rad);
  GreatCircle g;
  g.arc_rad = haversine_arc_rad(lat1_rad, lat2_rad, d_lon, c1, c2);
  g.azimuth_rad = initial_azimuth_rad(d_lon, std::sin(lat1_rad), c1, std::sin(lat2_rad), c2);
  return g;
}

GreatCircleBothWays great_circle_both_ways(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad) {
  const double s1 = std::sin(lat1_rad), c1 = std::cos(lat1_rad), s2 = std::sin(lat2_rad), c2 = std::cos(lat2_rad);
  const double d_lon = lon2_rad - lon1_rad;
  GreatCircleBothWays g;
  g.arc_rad = haversine_arc_rad(lat1_rad, lat2_rad, d_lon, c1, c2);
  g.azimuth_rad = initial_azimuth_rad(d_lon, s1, c1, s2, c2);
  g.back_azimuth_rad = initial_azimuth_rad(lon1_rad - lon2_rad, s2, c2, s1, c1);
  return g;
}

double great_circle_arc_rad(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad) {
  return haversine_arc_rad(lat1_rad, lat2_rad, lon2_rad - lon1_rad, std::cos(lat1_rad), std::cos(lat2_rad));
}

TrackPoint great_circle_point(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad, double fraction) {
  const GreatCircle whole = great_circle(lat1_rad, lon1_rad, lat2_rad, lon2_rad);
  TrackPoint p{lat1_rad, lon1_rad, whole.azimuth_rad};
  const double arc = whole.arc_rad;
  if (!(arc > 1e-9)) return p;
  const double f = fraction < 0.0 ? 0.0 : (fraction > 1.0 ? 1.0 : fraction);
  const double w0 = std::sin((1.0 - f) * arc) / std::sin(arc), w1 = std::sin(f * arc) / std::sin(arc);
  const double c1 = std::cos(lat1_rad), c2 = std::cos(lat2_rad);
  const double x = w0 * c1 * std::cos(lon1_rad) + w1 * c2 * std::cos(lon2_rad);
  const double y = w0 * c1 * std::sin(lon1_rad) + w1 * c2 * std::sin(lon2_rad);
  const double z = w0 * std::sin(lat1_rad) + w1 * std::sin(lat2_rad);
  p.lat_rad = std::atan2(z, std::hypot(x, y));
  p.lon_rad = std::atan2(y, x);
  if (f < 1.0 - 1e-9) {
    p.azimuth_rad = great_circle(p.lat_rad, p.lon_rad, lat2_rad, lon2_rad).azimuth_rad;
  } else {
    // At the end point: the arrival azimuth is the reverse of the departure azimuth from point 2, turned by pi.
    p.azimuth_rad = wrap_pi(great_circle(lat2_rad, lon2_rad, lat1_rad, lon1_rad).azimuth_rad + M_PI);
  }
  return p;
}

TrackErrors track_errors(double lat_entry_rad, double lon_entry_rad, double azimuth_mission_rad,
                         double lat_x_rad, double lon_x_rad) {
  // Steps 1-2: triangle 1 gives b1 and A1 (heading of X seen from the entry point).
  const GreatCircle t1 = great_circle(lat_entry_rad, lon_entry_rad, lat_x_rad, lon_x_rad);
  // Step 3: c2 = b1, A2 = A1 - A_mission (signed so that the side of the track is kept).
  const double c2 = t1.arc_rad;
  const double a2_angle = wrap_pi(t1.azimuth_rad - azimuth_mission_rad);
  // Step 4: right spherical triangle, sin a2 = sin c2 sin A2, tan b2 = tan c2 cos A2.
  TrackErrors e;
  double s = std::sin(c2) * std::sin(a2_angle);
  s = s < -1.0 ? -1.0 : (s > 1.0 ? 1.0 : s);
  e.crossrange_rad = std::asin(s);
  e.downrange_rad = std::atan2(std::sin(c2) * std::cos(a2_angle), std::cos(c2));
  return e;
}

int initial_bank_sign(double heading_rad, double azimuth_mission_rad) {
  return wrap_pi(heading_rad - azimuth_mission_rad) > 0.0 ? -1 : 1;
}

}  // namespace reentry::fsw
