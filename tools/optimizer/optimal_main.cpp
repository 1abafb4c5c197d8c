// reentry_optimal: optimal entry trajectories on the truth simulator's own models.
//   reentry_optimal --mission M [--seed S --dispersed] [--mode margin|miss] [--replay] [--out DIR]
//       one run's problem, warm-started from the guidance's flight of that run
//   reentry_optimal --mission M --footprint --out DIR [--points K --step KM]
//       the reachable TAEM footprint from the (nominal) entry state: max / min crossrange at the
//       aim point's downrange, then at K downrange steps on each side (continuation; the edge
//       lies within a step beyond the last converged one) (footprint.json, footprint_tracks.csv)
//   reentry_optimal --betts [--heating-limit 70]
//       Betts's Space Shuttle maximum-crossrange benchmark
//   --repeat N solves the same problem N times and prints the median and maximum wall time.
// Exit: 0 solved (footprint: both solves at the aim's downrange), 1 a solve did not converge, 2 bad input.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "betts_shuttle.hpp"
#include "run_oracle.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace reentry;
using namespace reentry::optimal;

namespace {

constexpr double kDeg = 180.0 / M_PI;

json figures_json(const EntryFigures& f) {
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"tf_s", f.tf_s},
          {"margin", f.margin},
          {"miss_km", f.miss_m * 1e-3},
          {"along_km", f.along_m * 1e-3},
          {"cross_km", f.cross_m * 1e-3},
          {"altitude_err_km", f.altitude_err_m * 1e-3},
          {"mach", f.mach},
          {"gamma_deg", f.gamma_rad * kDeg},
          {"heading_err_deg", f.heading_err_rad * kDeg},
          {"final_lat_deg", f.final_lat_rad * kDeg},
          {"final_lon_deg", f.final_lon_rad * kDeg},
          {"max_heat_flux_kW_m2", f.max_heat_flux_Wpm2 * 1e-3},
          {"max_g", f.max_load_g},
          {"max_q_kPa", f.max_q_Pa * 1e-3},
          {"max_q_alpha_kPa_deg", f.max_q_alpha_Pa_rad * 1e-3 * kDeg},
          {"margins",
           {{"heat_flux", num(f.margin_heat_flux)},
            {"load_factor", num(f.margin_load)},
            {"dynamic_pressure", num(f.margin_q)},
            {"q_alpha", num(f.margin_q_alpha)},
            {"range", num(f.margin_range)},
            {"altitude", num(f.margin_altitude)},
            {"mach", num(f.margin_mach)},
            {"flight_path", num(f.margin_gamma)},
            {"heading", num(f.margin_heading)}}},
          {"all_satisfied", f.all_satisfied}};
}

void print_solution(const char* what, const EntryResult& r) {
  const Solution& s = r.solution;
  const EntryFigures& f = r.figures;
  std::printf("%s: %s (IPOPT %s), %.2f s in %zu solves, %d segments, max violation %.1e\n", what, to_string(s.status),
              s.ipopt_status.c_str(), r.wall_s, r.passes.size(), r.segments(), s.max_violation);
  for (size_t k = 0; k < r.passes.size(); ++k) {
    const MeshPass& p = r.passes[k];
    std::printf("  solve %zu: %d segments%s, %s, %d iterations, %.2f s; table-model flight ends %.0f m from it\n", k + 1,
                p.segments, p.corrected ? " (model corrected)" : "", to_string(p.status), p.iterations, p.wall_s, p.end_error_m);
  }
  std::printf("  t_f %.1f s, margin %+.4f, miss %.3f km (along %+.2f, across %+.2f), altitude %+.0f m, Mach %.2f, "
              "gamma %.2f deg, heading %+.2f deg\n",
              f.tf_s, f.margin, f.miss_m * 1e-3, f.along_m * 1e-3, f.cross_m * 1e-3, f.altitude_err_m, f.mach,
              f.gamma_rad * kDeg, f.heading_err_rad * kDeg);
  std::printf("  max heat flux %.1f kW/m2, g %.2f, q %.2f kPa, q*alpha %.1f kPa deg (margins %.3f %.3f %.3f %.3f)\n",
              f.max_heat_flux_Wpm2 * 1e-3, f.max_load_g, f.max_q_Pa * 1e-3, f.max_q_alpha_Pa_rad * 1e-3 * kDeg,
              f.margin_heat_flux, f.margin_load, f.margin_q, f.margin_q_alpha);
}

void write_track_csv(std::ostream& out, const std::string& label, const std::vector<TrackPoint>& tr, bool header) {
  if (header) out << "label,t_s,lat_deg,lon_deg,h_km,V_mps,gamma_deg,chi_deg,mach,qdot_kW_m2,n_g,q_kPa,alpha_deg,sigma_deg\n";
  char line[512];
  for (const TrackPoint& p : tr) {
    std::snprintf(line, sizeof line, "%s,%.3f,%.6f,%.6f,%.4f,%.3f,%.4f,%.4f,%.4f,%.3f,%.4f,%.4f,%.4f,%.4f\n", label.c_str(),
                  p.t_s, p.lat_rad * kDeg, p.lon_rad * kDeg, p.h_m * 1e-3, p.V_mps, p.gamma_rad * kDeg, p.chi_rad * kDeg,
                  p.mach, p.qdot_Wpm2 * 1e-3, p.n_g, p.q_Pa * 1e-3, p.alpha_rad * kDeg, p.sigma_rad * kDeg);
    out << line;
  }
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

int run_betts(double heating_limit, int segments, int repeat) {
  BettsShuttle pb;
  pb.heating_limit_BTU = heating_limit;
  SolverOptions o;
  o.bound_push = 1e-2;
  o.mu_init = 0.1;
  const Mesh mesh = Mesh::uniform(segments);
  std::vector<double> walls;
  Solution s;
  for (int k = 0; k < std::max(1, repeat); ++k) {
    s = solve(pb, mesh, pb.linear_guess(mesh), o);
    walls.push_back(s.wall_s);
  }
  const auto& tr = s.trajectory;
  std::printf("betts shuttle (%s): %s, %d iterations, theta_f %.4f deg, t_f %.2f s; wall median %.2f s, max %.2f s\n",
              std::isfinite(heating_limit) ? "q <= limit" : "unconstrained", to_string(s.status), s.iterations,
              tr.x[static_cast<size_t>((tr.points() - 1) * BettsShuttle::kStates + 2)] / BettsShuttle::kDeg, tr.p[0],
              median(walls), *std::max_element(walls.begin(), walls.end()));
  return converged(s.status) ? 0 : 1;
}

struct FlownRun {
  tools::ClosedLoopResult result;
  std::vector<FlownSample> samples;
};

FlownRun fly(const config::Mission& mission, std::uint64_t seed, bool dispersed) {
  FlownRun f;
  auto record = [&](const truth::Simulator& sim, double alpha, double sigma) {
    FlownSample s;
    s.t_s = sim.time_s();
    for (size_t i = 0; i < 6; ++i) s.y[i] = sim.state()[i];
    s.alpha_rad = alpha;
    s.sigma_rad = sigma;
    if (!f.samples.empty() && s.t_s <= f.samples.back().t_s) f.samples.back() = s;
    else f.samples.push_back(s);
  };
  f.result = tools::run_closed_loop(mission, seed, dispersed, {}, false, record);
  return f;
}

int run_footprint(const config::Mission& mission, const EntrySolveOptions& options, int points, double step_m,
                  const std::string& out) {
  const FlownRun flown = fly(mission, 0, false);
  if (!flown.result.error.empty() || flown.samples.size() < 2) {
    std::fprintf(stderr, "reentry_optimal: nominal flight failed: %s\n", flown.result.error.c_str());
    return 2;
  }
  std::string err;
  auto sim = make_run_simulator(mission, 0, false, &err);
  if (!sim) {
    std::fprintf(stderr, "reentry_optimal: %s\n", err.c_str());
    return 2;
  }
  const Mesh mesh = Mesh::uniform(options.segments);
  const Trajectory guess = guess_from_flown(flown.samples, mesh);
  json pts = json::array();
  fs::create_directories(out);
  std::ofstream tracks(fs::path(out) / "footprint_tracks.csv");
  write_track_csv(tracks, "guidance_nominal", track(EntryProblem(*sim, EntryMode::kMinMiss, guess.p[0]), guess), true);
  int failures = 0, aim_failures = 0;  // solves not converged / aim-downrange points not reached
  std::vector<double> walls;
  auto record = [&](const EntryResult& r, const char* label, double downrange_m) {
    const auto& f = r.figures;
    const bool ok = converged(r.solution.status);
    if (!ok) ++failures;
    walls.push_back(r.solution.wall_s);
    std::printf("%-15s %8.1f km  -> %s: along %+9.1f km, across %+8.1f km (lat %.3f, lon %.3f deg), %d it, %.1f s\n", label,
                downrange_m * 1e-3, to_string(r.solution.status), f.along_m * 1e-3, f.cross_m * 1e-3,
                f.final_lat_rad * kDeg, f.final_lon_rad * kDeg, r.solution.iterations, r.solution.wall_s);
    std::fflush(stdout);
    json p = figures_json(f);
    p["mode"] = label;
    p["status"] = to_string(r.solution.status);
    p["iterations"] = r.solution.iterations;
    p["wall_s"] = r.solution.wall_s;
    p["downrange_target_km"] = downrange_m * 1e-3;
    // The independent check: the solve's control history flown open loop in a fresh truth
    // simulator. Its end point, reached within every path limit, is a reachable TAEM point
    // whether or not the solver converged (a solve stopped at its iteration limit is then an
    // inner bound of the footprint, not its edge).
    const EntryProblem pb(*sim, r.mode, r.figures.tf_s, downrange_m);
    std::string err;
    auto replay_sim = make_run_simulator(mission, 0, false, &err);
    bool reached = false;
    if (replay_sim && !r.solution.trajectory.x.empty()) {
      const ReplayResult rp = replay_open_loop(*replay_sim, pb, r.solution.trajectory);
      const auto path = truth::path_constraint_violations(mission.constraints, rp.summary.maxima);
      reached = rp.summary.event == truth::SimEvent::kTaemEnergy && path.empty();
      p["replay"] = {{"event", truth::to_string(rp.summary.event)},
                     {"along_km", rp.verdict.miss_along_m * 1e-3},
                     {"cross_km", rp.verdict.miss_cross_m * 1e-3},
                     {"end_point_diff_km", rp.final_position_diff_m * 1e-3},
                     {"path_violations", path},
                     {"reached", reached}};
      std::printf("%-15s open-loop replay: %s, along %+9.1f km, across %+8.1f km, %.1f km from the solve's end%s\n", "",
                  truth::to_string(rp.summary.event), rp.verdict.miss_along_m * 1e-3, rp.verdict.miss_cross_m * 1e-3,
                  rp.final_position_diff_m * 1e-3, path.empty() ? "" : " (path limit exceeded)");
    }
    pts.push_back(p);
    if (ok || reached) write_track_csv(tracks, label, track(pb, r.solution.trajectory), false);
    return ok || reached;
  };
  // Continuation in downrange from the aim point: the crossrange extremes at the aim's downrange
  // (warm start: the guidance's nominal flight), then at downranges stepped outwards on each
  // side, each warm-started from its neighbour, until a solve fails (the footprint's edge lies
  // within a step beyond the last converged downrange). Maximising the downrange itself sends
  // the solver far from any converging path (X-33: 8700-16800 km, iteration limit at 3000).
  for (EntryMode mode : {EntryMode::kMaxCrossrange, EntryMode::kMinCrossrange}) {
    const EntryResult at_aim = solve_entry(*sim, mode, guess, options, 0.0);
    if (!record(at_aim, to_string(mode), 0.0)) {
      ++aim_failures;
      continue;
    }
    for (int side : {+1, -1}) {
      Trajectory start = at_aim.solution.trajectory;
      for (int k = 1; k <= points; ++k) {
        const double d = side * k * step_m;
        const EntryResult r = solve_entry(*sim, mode, start, options, d);
        if (!record(r, to_string(mode), d)) break;
        start = r.solution.trajectory;
      }
    }
  }
  const auto& tm = mission.taem;
  const auto& e = mission.entry;
  json doc = {{"mission", mission.name},
              {"aim_lat_deg", tm.latitude_rad * kDeg},
              {"aim_lon_deg", tm.longitude_rad * kDeg},
              {"aim_heading_deg", tm.heading_rad * kDeg},
              {"range_tol_km", tm.range_tol_m * 1e-3},
              {"entry_lat_deg", e.latitude_rad * kDeg},
              {"entry_lon_deg", e.longitude_rad * kDeg},
              {"segments", options.segments},
              {"guidance_nominal_miss_km", flown.result.verdict.taem_miss_m * 1e-3},
              {"solve_wall_s_median", median(walls)},
              {"solve_wall_s_max", walls.empty() ? 0.0 : *std::max_element(walls.begin(), walls.end())},
              {"points", pts}};
  std::ofstream(fs::path(out) / "footprint.json") << doc.dump(2) << "\n";
  std::printf("%s: footprint of %zu solves (%d not converged), solve wall median %.1f s, max %.1f s -> %s\n",
              mission.name.c_str(), walls.size(), failures, median(walls),
              walls.empty() ? 0.0 : *std::max_element(walls.begin(), walls.end()), out.c_str());
  return aim_failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"optimal entry trajectories on the truth models (direct collocation, IPOPT)"};
  std::string mission_arg, mode_arg = "margin", out;
  std::uint64_t seed = 7;
  bool dispersed = false, replay = true, footprint = false, betts = false, lbfgs = false;
  int segments = EntrySolveOptions{}.segments, max_iter = EntrySolveOptions{}.solver.max_iterations, points = 3, repeat = 1;
  int print_level = 0;
  double step_km = 500.0;
  double max_wall = EntrySolveOptions{}.solver.max_wall_s, heating_limit = INFINITY;
  double alpha_band_deg = 0.0;
  app.add_option("--mission", mission_arg, "mission name or TOML file");
  app.add_option("--mode", mode_arg, "margin (maximum common constraint margin) or miss (minimum TAEM miss)")
      ->check(CLI::IsMember({"margin", "miss"}));
  app.add_option("--seed", seed, "run seed (with --dispersed: the run's dispersion draw, as tools/mc run seed)");
  app.add_flag("--dispersed", dispersed, "the dispersed run of --seed (default: nominal)");
  app.add_flag("--replay,!--no-replay", replay, "fly the optimal control history open loop in the truth simulator (default)");
  app.add_flag("--footprint", footprint, "reachable TAEM footprint from the entry state (needs --out)");
  app.add_option("--points", points, "footprint: downrange steps on each side of the aim point")->check(CLI::Range(0, 40));
  app.add_option("--step", step_km, "footprint: downrange step [km]")->check(CLI::PositiveNumber);
  app.add_option("--out", out, "output directory (solution.json + solution.csv, or the footprint files)");
  app.add_option("--segments", segments, "Hermite-Simpson segments")->check(CLI::Range(4, 2000));
  app.add_option("--max-iter", max_iter, "IPOPT iteration limit")->check(CLI::Range(0, 100000));
  app.add_option("--max-time", max_wall, "wall-clock limit of one solve [s]")->check(CLI::PositiveNumber);
  app.add_option("--alpha-band", alpha_band_deg,
                 "margin / miss: alpha within this band of the mission's alpha profile [deg] (0: free)")
      ->check(CLI::Range(0.0, 90.0));
  app.add_flag("--lbfgs", lbfgs, "IPOPT's limited-memory quasi-Newton Hessian instead of the exact (AD) one");
  app.add_option("--print-level", print_level, "IPOPT console output level (0-12)");
  std::vector<std::string> ipopt_options;
  double smoothing = EntrySolveOptions{}.solver.control_smoothing;
  double proximity = EntrySolveOptions{}.solver.control_proximity;
  app.add_option("--proximity", proximity, "weight of the control proximity term of the objective");
  RefinementOptions ro;
  app.add_option("--a-priori-passes", ro.a_priori_passes, "refinements of the first mesh by the start's local errors");
  app.add_option("--a-priori-reduction", ro.a_priori_reduction, "their aimed reduction");
  app.add_option("--refinement-passes", ro.max_passes, "solves after the first (mesh refinement)");
  app.add_option("--end-error-target", ro.end_error_target_m, "estimated end-point error that stops refinement [m]");
  app.add_option("--smoothing", smoothing, "weight of the control smoothing term of the objective");
  std::string derivative_test;
  app.add_option("--ipopt-option", ipopt_options, "further IPOPT option name=value (repeatable)");
  app.add_option("--derivative-test", derivative_test, "IPOPT's derivative checker: first-order or second-order")
      ->check(CLI::IsMember({"first-order", "second-order"}));
  app.add_option("--repeat", repeat, "solve N times, print median and maximum wall time")->check(CLI::Range(1, 1000));
  app.add_flag("--betts", betts, "Betts's Space Shuttle maximum-crossrange benchmark");
  app.add_option("--heating-limit", heating_limit, "Betts: heating limit [BTU/ft^2/s] (70 in the constrained case)");
  CLI11_PARSE(app, argc, argv);

  if (betts) return run_betts(heating_limit, 100, repeat);
  if (mission_arg.empty()) {
    std::fprintf(stderr, "reentry_optimal: --mission is required (or --betts)\n");
    return 2;
  }
  const auto loaded = config::load_mission(mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "reentry_optimal: %s\n", loaded.error.c_str());
    return 2;
  }
  EntrySolveOptions so;
  so.segments = segments;
  so.solver.max_iterations = max_iter;
  so.solver.max_wall_s = max_wall;
  so.solver.exact_hessian = !lbfgs;
  so.solver.print_level = print_level;
  so.solver.derivative_test = derivative_test;
  so.solver.control_smoothing = smoothing;
  so.solver.control_proximity = proximity;
  so.refinement = ro;
  for (const std::string& kv : ipopt_options) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::fprintf(stderr, "reentry_optimal: --ipopt-option needs name=value, got '%s'\n", kv.c_str());
      return 2;
    }
    so.solver.ipopt_options.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
  }
  so.alpha_band_rad = alpha_band_deg / kDeg;
  if (footprint) {
    if (out.empty()) {
      std::fprintf(stderr, "reentry_optimal: --footprint needs --out DIR\n");
      return 2;
    }
    return run_footprint(loaded.mission, so, points, step_km * 1e3, out);
  }

  OracleOptions o;
  o.mode = mode_arg == "miss" ? EntryMode::kMinMiss : EntryMode::kMaxMargin;
  o.solve = so;
  o.replay = replay;
  const FlownRun flown = fly(loaded.mission, seed, dispersed);
  if (!flown.result.error.empty()) {
    std::fprintf(stderr, "reentry_optimal: %s\n", flown.result.error.c_str());
    return 2;
  }
  std::printf("guidance: %s, miss %.2f km%s\n", flown.result.verdict.success ? "success" : "failure",
              flown.result.verdict.taem_miss_m * 1e-3, dispersed ? " (dispersed run)" : " (nominal)");
  OracleResult r;
  std::vector<double> walls;
  for (int k = 0; k < repeat; ++k) {
    r = solve_oracle(loaded.mission, seed, dispersed, flown.samples, flown.result.verdict.success, o);
    if (!r.error.empty()) {
      std::fprintf(stderr, "reentry_optimal: %s\n", r.error.c_str());
      return 2;
    }
    walls.push_back(r.attempts.empty() ? 0.0 : r.attempts.front().entry.wall_s);
  }
  for (const OracleAttempt& a : r.attempts) print_solution((std::string(to_string(o.mode)) + " from " + a.start).c_str(), a.entry);
  std::printf("  optimizer: %s; run: %s%s%s\n", r.optimizer_feasible ? "every constraint met" : "not feasible",
              to_string(r.feasibility), r.reason.empty() ? "" : ": ", r.reason.c_str());
  if (repeat > 1)
    std::printf("  %d solves: wall median %.2f s, max %.2f s\n", repeat, median(walls),
                *std::max_element(walls.begin(), walls.end()));
  if (r.replayed) {
    const auto& p = r.replay;
    std::printf("open-loop replay in the truth simulator: %s, %s, miss %.3f km; end point %.1f m from the collocated one "
                "(dt %+.2f s, dh %+.1f m, dMach %+.4f, dheading %+.3f deg)",
                truth::to_string(p.summary.event), p.verdict.success ? "success" : "failure", p.verdict.taem_miss_m * 1e-3,
                p.final_position_diff_m, p.final_time_diff_s, p.final_altitude_diff_m, p.final_mach_diff,
                p.final_heading_diff_rad * kDeg);
    if (!p.verdict.violations.empty()) {
      std::printf("; violations:");
      for (const auto& v : p.verdict.violations) std::printf(" %s", v.c_str());
    }
    std::printf("\n");
  }
  if (!out.empty()) {
    fs::create_directories(out);
    json doc = figures_json(r.entry.figures);
    doc["mission"] = loaded.mission.name;
    doc["seed"] = seed;
    doc["dispersed"] = dispersed;
    doc["mode"] = to_string(o.mode);
    doc["status"] = to_string(r.entry.solution.status);
    doc["iterations"] = r.entry.solution.iterations;
    doc["wall_s"] = r.entry.solution.wall_s;
    doc["feasible"] = r.feasible;
    doc["feasibility"] = to_string(r.feasibility);
    doc["optimizer_feasible"] = r.optimizer_feasible;
    if (r.replayed) {
      doc["replay"] = {{"event", truth::to_string(r.replay.summary.event)},
                       {"success", r.replay.verdict.success},
                       {"miss_km", r.replay.verdict.taem_miss_m * 1e-3},
                       {"end_point_diff_m", r.replay.final_position_diff_m},
                       {"violations", r.replay.verdict.violations}};
    }
    std::ofstream(fs::path(out) / "solution.json") << doc.dump(2) << "\n";
    std::string err;
    auto sim = make_run_simulator(loaded.mission, seed, dispersed, &err);
    std::ofstream csv(fs::path(out) / "solution.csv");
    write_track_csv(csv, "optimal", track(EntryProblem(*sim, o.mode, r.entry.figures.tf_s, 0.0, so.alpha_band_rad), r.entry.solution.trajectory), true);
  }
  return converged(r.entry.solution.status) ? 0 : 1;
}
