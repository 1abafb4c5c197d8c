// The referee's verdict on one flown mission: did the vehicle reach the TAEM interface
// within the mission's tolerances without exceeding a path or control constraint?
// One definition, used by the LCM simulator process (tools/sil) and the in-process
// Monte Carlo runner (tools/mc), so both judge a run the same way.
#pragma once

#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "physics/angles.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::truth {

/// Command-rate maxima seen by the runner (from successive applied commands).
struct CommandRateMaxima {
  double alpha_rate_radps = 0.0;
  double sigma_rate_radps = 0.0;
};

struct MissionVerdict {
  bool success = false;
  bool reached_taem = false;        // the TAEM energy event ended the run
  double taem_miss_m = 0.0;         // great-circle distance to the aim point at the event
  // The miss split along the arrival line (the great circle through the aim point on the
  // required TAEM heading), on the same R_eq sphere as taem_miss_m:
  double miss_along_m = 0.0;        // along the line, > 0 past the aim point (long)
  double miss_cross_m = 0.0;        // across it, > 0 right of the line (looking along the heading)
  double altitude_err_m = 0.0;      // final altitude - TAEM altitude
  double mach = 0.0;
  double mach_err = 0.0;            // final Mach - target (0 when no target)
  double flight_path_err_rad = 0.0; // final gamma - TAEM gamma (0 when not constrained)
  double heading_err_rad = 0.0;     // final heading - required TAEM heading, wrapped to (-pi, pi]
  std::vector<std::string> violations;  // names of violated constraints / tolerances
};

/// Relative tolerance on path-constraint maxima (a limit met exactly is not a violation).
inline constexpr double kConstraintSlack = 1e-9;

/// Names of the path constraints (heat flux, load factor, q, q alpha) whose maxima exceed the
/// mission's limits, in the order and with the slack of judge_mission.
std::vector<std::string> path_constraint_violations(const config::PathConstraints& c, const RunMaxima& maxima);

MissionVerdict judge_mission(const config::Mission& mission, const RunSummary& summary,
                             const CommandRateMaxima& rates);

/// Along- and cross-track distance of a point from the great circle through an aim point on
/// a given heading, on the R_eq sphere (geocentric latitudes): along > 0 ahead of the aim
/// point, cross > 0 to the right of the line.
struct ArrivalLineOffset {
  double along_m = 0.0;
  double cross_m = 0.0;
};
ArrivalLineOffset arrival_line_offset(double lat_rad, double lon_rad, double aim_lat_rad, double aim_lon_rad,
                                      double line_heading_rad);

using physics::wrap_pi;  // angle to (-pi, pi]

}  // namespace reentry::truth
