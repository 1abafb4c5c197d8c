// The mission's interface types, shared by the mission loader (config/), the truth simulator
// and the flight software: the entry interface state, the TAEM target with its tolerances, the
// path and control limits. Plain data, SI, no behaviour: the one definition that the loader
// fills and both sides read (a model never lives here).
#pragma once

#include <limits>

namespace reentry::mission {

/// A limit that is not imposed.
inline constexpr double kUnconstrained = std::numeric_limits<double>::infinity();

/// Entry interface state relative to the rotating Earth (spherical coordinates).
struct EntryInterface {
  double altitude_m = 0.0;
  double longitude_rad = 0.0;
  double latitude_rad = 0.0;
  double velocity_mps = 0.0;      // Earth-relative speed
  double flight_path_rad = 0.0;   // gamma (negative: descending)
  double heading_rad = 0.0;       // chi, from North, clockwise
};

/// TAEM interface: aim point, required heading, and the tolerances of the mission.
struct TaemTarget {
  double altitude_m = 0.0;        // height above the ellipsoid
  double velocity_mps = 0.0;
  double longitude_rad = 0.0;     // aim point
  double latitude_rad = 0.0;
  double heading_rad = 0.0;       // required heading at TAEM (towards the HAC)
  double range_tol_m = 0.0;       // distance to the aim point
  double altitude_tol_m = 0.0;
  double mach_target = 0.0;       // 0: not specified
  double mach_tol = kUnconstrained;
  double flight_path_rad = 0.0;
  double flight_path_tol_rad = kUnconstrained;
  double heading_tol_rad = 0.0;
  double hac_radius_m = 0.0;      // heading-alignment circle radius
};

/// Path and control limits (kUnconstrained where the mission sets none).
struct PathLimits {
  double heat_flux_max_Wpm2 = kUnconstrained;
  double heat_load_max_Jpm2 = kUnconstrained;
  double load_factor_max_g = kUnconstrained;      // body-normal, thesis 3.7
  double q_alpha_max_Pa_rad = kUnconstrained;
  double dynamic_pressure_max_Pa = kUnconstrained;
  double alpha_max_rad = 0.0;
  double alpha_rate_max_radps = 0.0;
  double sigma_rate_max_radps = 0.0;
  double alpha_accel_max_radps2 = 0.0;
  double sigma_accel_max_radps2 = 0.0;
};

}  // namespace reentry::mission
