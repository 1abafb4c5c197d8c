#include "planner/mission_geometry.hpp"

#include <cmath>

namespace reentry::fsw {

GreatCircle great_circle(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad) {
  // Co-latitudes c = 90 - lat1, a = 90 - lat2, B = lon2 - lon1 (fig. 7.1).
  const double d_lon = lon2_rad - lon1_rad;
  // (7.1) cos b = cos c cos a + sin c sin a cos B, evaluated in the haversine form for accuracy.
  const double s_lat = std::sin(0.5 * (lat2_rad - lat1_rad));
  const double s_lon = std::sin(0.5 * d_lon);
  double hav = s_lat * s_lat + std::cos(lat1_rad) * std::cos(lat2_rad) * s_lon * s_lon;
  hav = hav < 0.0 ? 0.0 : (hav > 1.0 ? 1.0 : hav);
  GreatCircle g;
  g.arc_rad = 2.0 * std::asin(std::sqrt(hav));
  // (7.2) cos A = (cos a - cos b cos c) / (sin b sin c), quadrant from sin A = sin B sin a / sin b.
  g.azimuth_rad = std::atan2(std::sin(d_lon) * std::cos(lat2_rad),
                             std::cos(lat1_rad) * std::sin(lat2_rad) - std::sin(lat1_rad) * std::cos(lat2_rad) * std::cos(d_lon));
  return g;
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
