#include "footprint.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "evaluation/mission_verdict.hpp"
#include "run_oracle.hpp"

namespace reentry::optimal {

using nlohmann::json;

int Footprint::converged() const {
  int n = 0;
  for (const FootprintPoint& p : points) n += optimal::converged(p.entry.solution.status) ? 1 : 0;
  return n;
}

namespace {

// The homotopy's step: the extreme is sought at most this far beyond the last solution's (a
// solve that had to carry the X-38's end point 1700 km sideways in one go diverged), and the
// downrange continuation moves the fixed downrange at most this far per solve.
constexpr double kHomotopyStep_m = 300e3;
constexpr int kMaxHomotopySteps = 40;
constexpr int kMaxStations = 40;  // crossrange stations on each side of the aim point

double extent_of(EntryMode mode, const EntryFigures& f) {
  switch (mode) {
    case EntryMode::kMaxDownrange: return f.along_m;
    case EntryMode::kMinDownrange: return -f.along_m;
    case EntryMode::kMaxCrossrange: return f.cross_m;
    case EntryMode::kMinCrossrange: return -f.cross_m;
    default: return 0.0;
  }
}

// Flies the point's control history open loop in a fresh truth simulator of the nominal run.
void replay(const config::Mission& mission, const truth::Simulator& sim, FootprintPoint* p) {
  std::string err;
  auto replay_sim = make_run_simulator(mission, 0, false, &err);
  if (!replay_sim || p->entry.solution.trajectory.x.empty()) return;
  const EntryProblem pb(sim, p->mode, p->entry.figures.tf_s, p->downrange_target_m);
  p->replay = replay_open_loop(*replay_sim, pb, p->entry.solution.trajectory);
  p->replayed = true;
  p->path_violations = truth::path_constraint_violations(mission.constraints, p->replay.summary.maxima);
  p->reached = p->replay.summary.event == truth::SimEvent::kTaemEnergy && p->path_violations.empty();
}

// The extreme of `mode` at downrange d from `start`: the extreme sought at most a homotopy step
// beyond the last solution's, step after step (without mesh refinement), until that limit is no
// longer active; then the extreme itself, refined, and its flight.
FootprintPoint boundary_point(const config::Mission& mission, const truth::Simulator& sim, EntryMode mode, double d,
                              const Trajectory& start, const EntrySolveOptions& so) {
  FootprintPoint p;
  p.mode = mode;
  p.downrange_target_m = d;
  EntrySolveOptions step = so;
  step.refinement.max_passes = 0;
  Trajectory from = start;
  double wall = 0.0;
  for (int k = 0; k < kMaxHomotopySteps; ++k) {
    step.extent_limit_m = extent_of(mode, evaluate_figures(EntryProblem(sim, mode, from.p[0], d), from)) + kHomotopyStep_m;
    p.entry = solve_entry(sim, mode, from, step, d);
    wall += p.entry.wall_s;
    if (!converged(p.entry.solution.status)) break;
    from = p.entry.solution.trajectory;
    if (extent_of(mode, p.entry.figures) < step.extent_limit_m - 1e3) {  // the limit is inactive
      p.entry = solve_entry(sim, mode, from, so, d);
      wall += p.entry.wall_s;
      break;
    }
  }
  p.entry.wall_s = wall;
  replay(mission, sim, &p);
  return p;
}

bool usable(const FootprintPoint& p) { return converged(p.entry.solution.status) && p.reached; }

// The crossrange extreme `mode` at the aim's downrange, then at downranges stepped outwards on
// each side, each warm-started from its neighbour, up to the downrange extreme of that side
// (less a quarter step; `far` and `near`: the extents reached, or +-inf), or until a solve fails
// (the edge then lies within a step beyond the last converged downrange).
void crossrange_side(const config::Mission& mission, const truth::Simulator& sim, EntryMode mode, const Trajectory& guess,
                     const FootprintOptions& o, double far_m, double near_m, std::vector<FootprintPoint>* out) {
  out->push_back(boundary_point(mission, sim, mode, 0.0, guess, o.solve));
  if (!usable(out->back())) return;
  const Trajectory at_aim = out->back().entry.solution.trajectory;
  const double step = std::min(o.step_m, kHomotopyStep_m);
  for (int side : {+1, -1}) {
    const double end = side > 0 ? far_m : near_m;
    Trajectory start = at_aim;
    for (int k = 1; k <= kMaxStations && k * step < end - 0.25 * step; ++k) {
      out->push_back(boundary_point(mission, sim, mode, side * k * step, start, o.solve));
      if (!usable(out->back())) break;
      start = out->back().entry.solution.trajectory;
    }
  }
}

}  // namespace

Footprint compute_footprint(const config::Mission& mission, const FootprintOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  Footprint fp;
  const GuidanceFlight flown = fly_guidance(mission, 0, false);
  if (!flown.result.error.empty() || flown.samples.size() < 2) {
    fp.error = "nominal flight failed: " + flown.result.error;
    return fp;
  }
  fp.guidance_nominal_miss_m = flown.result.verdict.taem_miss_m;
  auto sim = make_run_simulator(mission, 0, false, &fp.error);
  if (!sim) return fp;
  fp.guidance_nominal = guess_from_flown(flown.samples, Mesh::uniform(options.solve.segments));
  double extent[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (EntryMode mode : {EntryMode::kMaxDownrange, EntryMode::kMinDownrange}) {
    fp.points.push_back(boundary_point(mission, *sim, mode, 0.0, fp.guidance_nominal, options.solve));
    if (usable(fp.points.back())) extent[mode == EntryMode::kMaxDownrange ? 0 : 1] = extent_of(mode, fp.points.back().entry.figures);
  }
  for (EntryMode mode : {EntryMode::kMaxCrossrange, EntryMode::kMinCrossrange})
    crossrange_side(mission, *sim, mode, fp.guidance_nominal, options, extent[0], extent[1], &fp.points);
  fp.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return fp;
}

json footprint_json(const config::Mission& mission, const FootprintOptions& options, const Footprint& fp) {
  constexpr double kDeg = 180.0 / M_PI;
  json pts = json::array();
  std::vector<double> walls;
  for (const FootprintPoint& p : fp.points) {
    json j = result_json(p.entry);
    j["mode"] = to_string(p.mode);
    j["downrange_target_km"] = p.downrange_target_m * 1e-3;
    if (p.replayed) {
      j["replay"] = {{"event", truth::to_string(p.replay.summary.event)},
                     {"along_km", p.replay.verdict.miss_along_m * 1e-3},
                     {"cross_km", p.replay.verdict.miss_cross_m * 1e-3},
                     {"final_lat_deg", p.replay.summary.final_state.lat_rad * kDeg},
                     {"final_lon_deg", p.replay.summary.final_state.lon_rad * kDeg},
                     {"end_point_diff_km", p.replay.final_position_diff_m * 1e-3},
                     {"path_violations", p.path_violations},
                     {"reached", p.reached}};
    }
    pts.push_back(j);
    walls.push_back(p.entry.wall_s);
  }
  const auto& tm = mission.taem;
  const auto& e = mission.entry;
  return {{"mission", mission.name},
          {"aim_lat_deg", tm.latitude_rad * kDeg},
          {"aim_lon_deg", tm.longitude_rad * kDeg},
          {"aim_heading_deg", tm.heading_rad * kDeg},
          {"range_tol_km", tm.range_tol_m * 1e-3},
          {"entry_lat_deg", e.latitude_rad * kDeg},
          {"entry_lon_deg", e.longitude_rad * kDeg},
          {"first_mesh_segments", options.solve.segments},
          {"downrange_step_km", std::min(options.step_m, kHomotopyStep_m) * 1e-3},
          {"guidance_nominal_miss_km", fp.guidance_nominal_miss_m * 1e-3},
          {"solves", fp.points.size()},
          {"converged", fp.converged()},
          {"footprint_wall_s", fp.wall_s},
          {"points", pts}};
}

}  // namespace reentry::optimal
