// reentry_optimal: optimal entry trajectories on the truth simulator's own models.
//   reentry_optimal --mission M [--seed S --dispersed] [--mode margin|miss] [--replay] [--out DIR]
//       one run's problem, warm-started from the guidance's flight of that run (the oracle's
//       solves: a second start from the nominal solution when the first does not prove it)
//   reentry_optimal --mission M --footprint --out DIR [--step KM]
//       the reachable TAEM footprint from the nominal entry state (footprint.hpp):
//       footprint.json, footprint_tracks.csv
//   reentry_optimal --betts [--heating-limit 70]
//       Betts's Space Shuttle maximum-crossrange benchmark
//   --repeat N solves the same problem N times and prints the median and maximum wall time.
// Solver settings are flags (--segments, --max-iter, --lbfgs, --ipopt-option name=value, ...).
// Exit: 0 solved (footprint: every solve converged), 1 a solve did not converge, 2 bad input.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "betts_shuttle.hpp"
#include "footprint.hpp"
#include "run_oracle.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace reentry;
using namespace reentry::optimal;

namespace {

constexpr double kDeg = 180.0 / M_PI;

struct Cli {
  std::string mission, mode = "margin", out;
  std::uint64_t seed = 7;
  bool dispersed = false, replay = true, footprint = false, betts = false, lbfgs = false;
  int repeat = 1;
  double step_km = 300.0, heating_limit = INFINITY, alpha_band_deg = 0.0;
  std::vector<std::string> ipopt_options;
  EntrySolveOptions solve;
};

void add_solver_options(CLI::App& app, Cli& c) {
  SolverOptions& s = c.solve.solver;
  RefinementOptions& r = c.solve.refinement;
  app.add_option("--segments", c.solve.segments, "Hermite-Simpson segments of the first mesh")->check(CLI::Range(4, 2000));
  app.add_option("--max-iter", s.max_iterations, "IPOPT iteration limit of one solve")->check(CLI::Range(0, 100000));
  app.add_option("--max-time", s.max_wall_s, "wall-clock limit of one solve [s]")->check(CLI::PositiveNumber);
  app.add_flag("--lbfgs", c.lbfgs, "IPOPT's limited-memory quasi-Newton Hessian instead of the exact (AD) one");
  app.add_option("--print-level", s.print_level, "IPOPT console output level (0-12)");
  app.add_option("--mu-init", s.mu_init, "IPOPT's initial barrier parameter")->check(CLI::PositiveNumber);
  app.add_option("--proximity", s.control_proximity, "weight of the control proximity term of the objective");
  app.add_option("--smoothing", s.control_smoothing, "weight of the control smoothing term of the objective");
  app.add_option("--ipopt-option", c.ipopt_options, "further IPOPT option name=value (repeatable)");
  app.add_option("--derivative-test", s.derivative_test, "IPOPT's derivative checker: first-order or second-order")
      ->check(CLI::IsMember({"first-order", "second-order"}));
  app.add_option("--refinement-passes", r.max_passes, "solves after the first (mesh refinement)")->check(CLI::Range(0, 20));
  app.add_option("--end-error-target", r.end_error_target_m, "estimated end-point error that stops refinement [m]")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-segments", r.max_segments, "segment limit of the refinement")->check(CLI::Range(4, 4000));
  app.add_flag("--model-correction,!--no-model-correction", r.model_correction,
               "correct the smooth models towards the truth's tables at the points (default)");
}

void add_options(CLI::App& app, Cli& c) {
  app.add_option("--mission", c.mission, "mission name or TOML file");
  app.add_option("--mode", c.mode, "margin (maximum common constraint margin) or miss (minimum TAEM miss)")
      ->check(CLI::IsMember({"margin", "miss"}));
  app.add_option("--seed", c.seed, "run seed (with --dispersed: the run's dispersion draw, as tools/mc run seed)");
  app.add_flag("--dispersed", c.dispersed, "the dispersed run of --seed (default: nominal)");
  app.add_flag("--replay,!--no-replay", c.replay, "fly the optimal control history open loop in the truth simulator (default)");
  app.add_flag("--footprint", c.footprint, "reachable TAEM footprint from the entry state (needs --out)");
  app.add_option("--step", c.step_km, "footprint: downrange spacing of the crossrange stations [km] (at most 300)")
      ->check(CLI::PositiveNumber);
  app.add_option("--out", c.out, "output directory (solution.json + solution.csv, or the footprint files)");
  app.add_option("--alpha-band", c.alpha_band_deg, "margin / miss: alpha within this band of the mission's alpha profile [deg] (0: free)")
      ->check(CLI::Range(0.0, 90.0));
  app.add_option("--repeat", c.repeat, "solve N times, print median and maximum wall time")->check(CLI::Range(1, 1000));
  app.add_flag("--betts", c.betts, "Betts's Space Shuttle maximum-crossrange benchmark");
  app.add_option("--heating-limit", c.heating_limit, "Betts: heating limit [BTU/ft^2/s] (70 in the constrained case)");
  add_solver_options(app, c);
}

// The flags into the solver settings; false (and a message) on a malformed --ipopt-option.
bool resolve(Cli& c) {
  c.solve.solver.exact_hessian = !c.lbfgs;
  c.solve.alpha_band_rad = c.alpha_band_deg / kDeg;
  for (const std::string& kv : c.ipopt_options) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::fprintf(stderr, "reentry_optimal: --ipopt-option needs name=value, got '%s'\n", kv.c_str());
      return false;
    }
    c.solve.solver.ipopt_options.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
  }
  return true;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

double largest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

void print_solution(const std::string& what, const EntryResult& r) {
  const Solution& s = r.solution;
  const EntryFigures& f = r.figures;
  std::printf("%s: %s (IPOPT %s), %.2f s in %zu solves, %d segments, max violation %.1e\n", what.c_str(), to_string(s.status),
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

void print_replay(const ReplayResult& p) {
  std::printf("open-loop replay in the truth simulator: %s, %s, miss %.3f km; end point %.1f m from the collocated one "
              "(dt %+.2f s, dh %+.1f m, dMach %+.4f, dheading %+.3f deg)",
              truth::to_string(p.summary.event), p.verdict.success ? "success" : "failure", p.verdict.taem_miss_m * 1e-3,
              p.final_position_diff_m, p.final_time_diff_s, p.final_altitude_diff_m, p.final_mach_diff,
              p.final_heading_diff_rad * kDeg);
  if (!p.verdict.violations.empty()) std::printf("; violations:");
  for (const auto& v : p.verdict.violations) std::printf(" %s", v.c_str());
  std::printf("\n");
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

int run_betts(const Cli& c) {
  BettsShuttle pb;
  pb.heating_limit_BTU = c.heating_limit;
  SolverOptions o;
  o.bound_push = 1e-2;
  o.mu_init = 0.1;
  const Mesh mesh = Mesh::uniform(100);
  std::vector<double> walls;
  Solution s;
  for (int k = 0; k < c.repeat; ++k) {
    s = solve(pb, mesh, pb.linear_guess(mesh), o);
    walls.push_back(s.wall_s);
  }
  const auto& tr = s.trajectory;
  std::printf("betts shuttle (%s): %s, %d iterations, theta_f %.4f deg, t_f %.2f s; wall median %.3f s, max %.3f s\n",
              std::isfinite(c.heating_limit) ? "q <= limit" : "unconstrained", to_string(s.status), s.iterations,
              tr.x[static_cast<size_t>((tr.points() - 1) * BettsShuttle::kStates + 2)] / BettsShuttle::kDeg, tr.p[0],
              median(walls), largest(walls));
  return converged(s.status) ? 0 : 1;
}

int run_footprint(const config::Mission& mission, const Cli& c) {
  FootprintOptions o;
  o.solve = c.solve;
  o.step_m = c.step_km * 1e3;
  const Footprint fp = compute_footprint(mission, o);
  if (!fp.error.empty()) {
    std::fprintf(stderr, "reentry_optimal: %s\n", fp.error.c_str());
    return 2;
  }
  fs::create_directories(c.out);
  std::ofstream(fs::path(c.out) / "footprint.json") << footprint_json(mission, o, fp).dump(2) << "\n";
  std::ofstream tracks(fs::path(c.out) / "footprint_tracks.csv");
  auto sim = make_run_simulator(mission, 0, false, nullptr);
  write_track_csv(tracks, "guidance_nominal", track(EntryProblem(*sim, EntryMode::kMinMiss, fp.guidance_nominal.p[0]), fp.guidance_nominal), true);
  for (const FootprintPoint& p : fp.points) {
    const EntryResult& r = p.entry;
    std::printf("%-15s %8.1f km -> %s: along %+9.1f km, across %+8.1f km, %d segments, %.1f s; open loop: %s, along %+9.1f, "
                "across %+8.1f km%s\n",
                to_string(p.mode), p.downrange_target_m * 1e-3, to_string(r.solution.status), r.figures.along_m * 1e-3,
                r.figures.cross_m * 1e-3, r.segments(), r.wall_s, p.reached ? "reached" : "not reached",
                p.replay.verdict.miss_along_m * 1e-3, p.replay.verdict.miss_cross_m * 1e-3,
                p.path_violations.empty() ? "" : " (path limit exceeded)");
    if (converged(r.solution.status) || p.reached)
      write_track_csv(tracks, to_string(p.mode), track(EntryProblem(*sim, p.mode, r.figures.tf_s, p.downrange_target_m), r.solution.trajectory), false);
  }
  std::printf("%s: footprint of %zu solves (%d converged) in %.1f s -> %s\n", mission.name.c_str(), fp.points.size(),
              fp.converged(), fp.wall_s, c.out.c_str());
  return fp.converged() == static_cast<int>(fp.points.size()) ? 0 : 1;
}

void write_solution(const config::Mission& mission, const Cli& c, const OracleResult& r) {
  fs::create_directories(c.out);
  json doc = result_json(r.entry);
  doc["mission"] = mission.name;
  doc["seed"] = c.seed;
  doc["dispersed"] = c.dispersed;
  doc["mode"] = to_string(r.entry.mode);
  doc["oracle"] = oracle_record(r);
  std::ofstream(fs::path(c.out) / "solution.json") << doc.dump(2) << "\n";
  auto sim = make_run_simulator(mission, c.seed, c.dispersed, nullptr);
  std::ofstream csv(fs::path(c.out) / "solution.csv");
  const EntryProblem pb(*sim, r.entry.mode, r.entry.figures.tf_s, 0.0, c.solve.alpha_band_rad);
  write_track_csv(csv, "optimal", track(pb, r.entry.solution.trajectory), true);
}

int run_single(const config::Mission& mission, const Cli& c) {
  OracleOptions o;
  o.mode = c.mode == "miss" ? EntryMode::kMinMiss : EntryMode::kMaxMargin;
  o.solve = c.solve;
  o.replay = c.replay;
  const GuidanceFlight flown = fly_guidance(mission, c.seed, c.dispersed);
  if (!flown.result.error.empty()) {
    std::fprintf(stderr, "reentry_optimal: %s\n", flown.result.error.c_str());
    return 2;
  }
  std::printf("guidance: %s, miss %.2f km%s\n", flown.result.verdict.success ? "success" : "failure",
              flown.result.verdict.taem_miss_m * 1e-3, c.dispersed ? " (dispersed run)" : " (nominal)");
  OracleResult r;
  std::vector<double> walls;
  for (int k = 0; k < c.repeat; ++k) {
    r = solve_oracle(mission, c.seed, c.dispersed, flown.samples, flown.result.verdict.success, o);
    if (!r.error.empty()) {
      std::fprintf(stderr, "reentry_optimal: %s\n", r.error.c_str());
      return 2;
    }
    walls.push_back(r.attempts.front().entry.wall_s);
  }
  for (const OracleAttempt& a : r.attempts) {
    print_solution(std::string(to_string(o.mode)) + " from " + a.start, a.entry);
    if (a.replayed) print_replay(a.replay);
  }
  std::printf("run: %s%s%s\n", to_string(r.feasibility), r.reason.empty() ? "" : ": ", r.reason.c_str());
  if (c.repeat > 1)
    std::printf("%d solves from the guidance's flight: wall median %.2f s, max %.2f s\n", c.repeat, median(walls), largest(walls));
  if (!c.out.empty()) write_solution(mission, c, r);
  return converged(r.attempts.front().entry.solution.status) ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"optimal entry trajectories on the truth models (direct collocation, IPOPT)"};
  Cli c;
  add_options(app, c);
  CLI11_PARSE(app, argc, argv);
  if (!resolve(c)) return 2;
  if (c.betts) return run_betts(c);
  if (c.mission.empty()) {
    std::fprintf(stderr, "reentry_optimal: --mission is required (or --betts)\n");
    return 2;
  }
  const auto loaded = config::load_mission(c.mission);
  if (!loaded.ok) {
    std::fprintf(stderr, "reentry_optimal: %s\n", loaded.error.c_str());
    return 2;
  }
  if (!c.footprint) return run_single(loaded.mission, c);
  if (c.out.empty()) {
    std::fprintf(stderr, "reentry_optimal: --footprint needs --out DIR\n");
    return 2;
  }
  return run_footprint(loaded.mission, c);
}
