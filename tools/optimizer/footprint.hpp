// The reachable TAEM footprint of a mission from its nominal entry state: the downrange extremes
// on the arrival line, and the crossrange extremes at the aim point's downrange and at downrange
// stations on each side out to those extremes (continuation, each solve warm-started from its
// neighbour). Each extreme is reached by a homotopy: sought at most 300 km beyond the last
// solution's, step after step, until that limit no longer binds. The
// footprint is the one the mission's guidance can reach: alpha within kFootprintAlphaBand_rad
// of its profile, the flight-path angle at most kFootprintGlideMaxGamma_rad (no skip), every
// path limit backed off kFootprintPathBackoff at the collocation points (entry_problem.hpp).
// Each solve's control history is flown open loop in the truth simulator: a boundary point is
// the TAEM point that flight reaches within every path limit.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "entry_solver.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::optimal {

struct FootprintOptions {
  EntrySolveOptions solve;
  double step_m = 300e3;    // downrange spacing of the crossrange stations (at most the homotopy step, 300 km)
};

struct FootprintPoint {
  EntryMode mode = EntryMode::kMaxCrossrange;
  double downrange_target_m = 0.0;  // the crossrange modes' fixed downrange (0 for the downrange modes)
  EntryResult entry;
  bool replayed = false;
  ReplayResult replay;
  std::vector<std::string> path_violations;  // of the open-loop flight
  bool reached = false;  // the flight ended at the TAEM energy within every path limit
};

struct Footprint {
  std::string error;
  double guidance_nominal_miss_m = 0.0;
  Trajectory guidance_nominal;  // the warm start (the guidance's nominal flight)
  std::vector<FootprintPoint> points;
  double wall_s = 0.0;          // the whole footprint: every solve and flight
  int converged() const;        // solves with status optimal or acceptable
};

Footprint compute_footprint(const config::Mission& mission, const FootprintOptions& options);

/// footprint.json: the mission's aim and entry, every point (figures, status, its flight), times.
nlohmann::json footprint_json(const config::Mission& mission, const FootprintOptions& options, const Footprint& fp);

}  // namespace reentry::optimal
