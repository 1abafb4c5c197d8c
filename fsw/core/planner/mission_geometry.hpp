// Spherical geometry of the mission (thesis §7.4, fig. 7.1, 7.17-7.19).
#pragma once

#include "physics/angles.hpp"

namespace reentry::fsw {

/// Great-circle arc b (7.1) and initial azimuth A (7.2) from point 1 to point 2, radians.
/// The azimuth quadrant is resolved as the thesis's acos2 does (atan2 form).
struct GreatCircle {
  double arc_rad = 0.0;
  double azimuth_rad = 0.0;
};
GreatCircle great_circle(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad);

/// great_circle(1 -> 2) and the azimuth back at point 2 towards point 1
/// (great_circle(2 -> 1).azimuth_rad), bit for bit, from one set of the latitudes' sines and
/// cosines.
struct GreatCircleBothWays {
  double arc_rad = 0.0;
  double azimuth_rad = 0.0;
  double back_azimuth_rad = 0.0;
};
GreatCircleBothWays great_circle_both_ways(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad);

/// great_circle(...).arc_rad alone (bit for bit).
double great_circle_arc_rad(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad);

/// Point at fraction f in [0, 1] of the great circle from point 1 to point 2 (spherical
/// linear interpolation) and the azimuth of the circle there, radians.
struct TrackPoint {
  double lat_rad = 0.0;
  double lon_rad = 0.0;
  double azimuth_rad = 0.0;
};
TrackPoint great_circle_point(double lat1_rad, double lon1_rad, double lat2_rad, double lon2_rad, double fraction);

/// Triangle steps 1-4 of §7.4: cross-range error a2 (signed, + right of the entry->TAEM
/// great circle) and downrange b2 projected on that circle, for the end point X.
struct TrackErrors {
  double crossrange_rad = 0.0;
  double downrange_rad = 0.0;
};
TrackErrors track_errors(double lat_entry_rad, double lon_entry_rad, double azimuth_mission_rad,
                         double lat_x_rad, double lon_x_rad);

using physics::wrap_pi;  // angle to (-pi, pi]

/// Initial bank sign from the quadrant rule (fig. 7.20): steer towards the TAEM point.
/// chi - A > 0 (heading right of the target) -> bank left (-1), otherwise +1.
int initial_bank_sign(double heading_rad, double azimuth_mission_rad);

}  // namespace reentry::fsw
