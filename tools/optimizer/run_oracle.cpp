#include "run_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <utility>

namespace reentry::optimal {

using nlohmann::json;

const char* to_string(Feasibility f) {
  switch (f) {
    case Feasibility::kFlown: return "flown";
    case Feasibility::kProvenOpenLoop: return "proven_open_loop";
    case Feasibility::kInfeasible: return "infeasible";
    case Feasibility::kPulloutBound: return "infeasible_pullout_bound";
    case Feasibility::kUndecided: return "undecided";
  }
  return "unknown";
}

std::unique_ptr<truth::Simulator> make_run_simulator(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                                                     std::string* error) {
  truth::SimOverrides ov;
  if (dispersed) ov.dispersion = truth::draw_dispersions(mission.dispersions, seed);
  auto sim = truth::Simulator::create(mission, ov, error);
  if (!sim && error) *error = "simulator: " + *error;
  return sim;
}

namespace {

bool converged_with_margin(const OracleAttempt& a) {
  return converged(a.entry.solution.status) && std::isfinite(a.entry.figures.margin);
}

// Solves from `guess`, then flies the solution open loop in a fresh simulator of the run.
OracleAttempt attempt(const config::Mission& mission, std::uint64_t seed, bool dispersed, const truth::Simulator& sim,
                      const char* start, const Trajectory& guess, const OracleOptions& o, const EntrySolveOptions& so,
                      std::string* error) {
  OracleAttempt a;
  a.start = start;
  a.entry = solve_entry(sim, o.mode, guess, so);
  if (!a.entry.error.empty()) {
    *error = a.entry.error;
    return a;
  }
  if (!o.replay || a.entry.solution.trajectory.x.empty()) return a;
  auto replay_sim = make_run_simulator(mission, seed, dispersed, error);
  if (!replay_sim) return a;
  const EntryProblem pb(sim, o.mode, guess.p[0], 0.0, so.alpha_band_rad);
  a.replay = replay_open_loop(*replay_sim, pb, a.entry.solution.trajectory);
  a.replayed = true;
  return a;
}

bool proves(const OracleAttempt& a) { return a.replayed && a.replay.verdict.success; }

// A converged margin clearly below zero: below the threshold and below the solve's
// regularisation terms (which may have cost it that much).
bool negative_margin(const OracleAttempt& a, double threshold) {
  if (!converged_with_margin(a)) return false;
  const double reg = std::isfinite(a.entry.figures.regularisation) ? a.entry.figures.regularisation : 0.0;
  return a.entry.figures.margin < -std::max(threshold, reg);
}

std::string describe(const OracleAttempt& a) {
  char buf[256];
  const EntryFigures& f = a.entry.figures;
  std::string s = a.start + ": " + to_string(a.entry.solution.status);
  if (converged(a.entry.solution.status)) {
    std::snprintf(buf, sizeof buf, ", margin %+.4f (regularisation %.4f)", f.margin, f.regularisation);
    s += buf;
  }
  if (a.replayed) {
    s += std::string(", replay ") + (a.replay.verdict.success ? "success" : "failure");
    for (const auto& v : a.replay.verdict.violations) s += " " + v;
  }
  return s;
}

// The verdict from the attempts (the flight and the pull-out bound are judged by the caller).
void classify(OracleResult& r, bool flown_success, double threshold) {
  const OracleAttempt* decisive = nullptr;
  for (const auto& a : r.attempts)
    if (proves(a)) decisive = &a;
  const bool infeasible = r.attempts.size() >= 2 && std::all_of(r.attempts.begin(), r.attempts.end(), [&](const auto& a) {
    return a.start == "guidance_refined" || negative_margin(a, threshold);
  });
  if (!decisive) {  // the best converged margin stands for the run
    for (const auto& a : r.attempts)
      if (converged_with_margin(a) && (!decisive || a.entry.figures.margin > decisive->entry.figures.margin)) decisive = &a;
  }
  if (!decisive && !r.attempts.empty()) decisive = &r.attempts.front();
  if (decisive) {
    r.entry = decisive->entry;
    r.replayed = decisive->replayed;
    r.replay = decisive->replay;
    r.optimizer_feasible = converged(decisive->entry.solution.status) && decisive->entry.figures.all_satisfied;
  }
  if (flown_success) r.feasibility = Feasibility::kFlown;
  else if (decisive && proves(*decisive)) r.feasibility = Feasibility::kProvenOpenLoop;
  else if (infeasible) r.feasibility = Feasibility::kInfeasible;
  else r.feasibility = Feasibility::kUndecided;
  r.feasible = r.feasibility == Feasibility::kFlown || r.feasibility == Feasibility::kProvenOpenLoop;
  if (r.feasibility == Feasibility::kUndecided || r.feasibility == Feasibility::kInfeasible) {
    for (const auto& a : r.attempts) r.reason += (r.reason.empty() ? "" : "; ") + describe(a);
  }
}

}  // namespace

std::shared_ptr<const Trajectory> nominal_solution(const config::Mission& mission, const OracleOptions& options) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, double>, std::shared_ptr<const Trajectory>> cache;
  const auto key = std::make_pair(mission.name, options.solve.alpha_band_rad);
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  OracleOptions o = options;
  o.solve_decided = true;
  o.replay = false;
  o.neighbour = std::make_shared<const Trajectory>();  // no second start for the nominal itself
  const OracleResult r = run_oracle(mission, 0, false, o);
  std::shared_ptr<const Trajectory> out;
  if (r.error.empty() && converged(r.entry.solution.status)) out = std::make_shared<const Trajectory>(r.entry.solution.trajectory);
  std::lock_guard<std::mutex> lock(mutex);
  cache[key] = out;
  return out;
}

OracleResult solve_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                          const std::vector<FlownSample>& flown, bool flown_success, const OracleOptions& options) {
  OracleResult out;
  if (flown.size() < 2) {
    out.error = "no flown trajectory to start from";
    return out;
  }
  auto sim = make_run_simulator(mission, seed, dispersed, &out.error);
  if (!sim) return out;
  const EntrySolveOptions& so = options.solve;
  const Trajectory guess = guess_from_flown(flown, Mesh::uniform(so.segments));
  out.attempts.push_back(attempt(mission, seed, dispersed, *sim, "guidance", guess, options, so, &out.error));
  const OracleAttempt& first = out.attempts.front();
  const bool margin_mode = options.mode == EntryMode::kMaxMargin;
  if (out.error.empty() && margin_mode && !proves(first) && converged_with_margin(first) &&
      first.entry.figures.margin > 0.0 && first.replayed) {
    // A positive margin whose flight fails: the collocated trajectory and the flight part by
    // more than the margin; refine further from that solution.
    EntrySolveOptions fine = so;
    fine.refinement.end_error_target_m = 0.25 * so.refinement.end_error_target_m;
    fine.refinement.max_segments = 2 * so.refinement.max_segments;
    const Trajectory start = first.entry.solution.trajectory;
    out.attempts.push_back(attempt(mission, seed, dispersed, *sim, "guidance_refined", start, options, fine, &out.error));
  }
  const bool decided = std::any_of(out.attempts.begin(), out.attempts.end(), proves);
  if (out.error.empty() && margin_mode && !decided) {
    const std::shared_ptr<const Trajectory> neighbour = options.neighbour ? options.neighbour : nominal_solution(mission, options);
    if (neighbour && neighbour->points() >= 3)
      out.attempts.push_back(attempt(mission, seed, dispersed, *sim, "neighbour", *neighbour, options, so, &out.error));
  }
  for (const auto& a : out.attempts) out.solve_s += a.entry.wall_s;
  if (out.error.empty()) classify(out, flown_success, options.infeasible_margin);
  return out;
}

GuidanceFlight fly_guidance(const config::Mission& mission, std::uint64_t seed, bool dispersed) {
  GuidanceFlight f;
  auto record = [&](const truth::Simulator& sim, double alpha, double sigma) {
    FlownSample s;
    s.t_s = sim.time_s();
    for (size_t i = 0; i < 6; ++i) s.y[i] = sim.state()[i];
    s.alpha_rad = alpha;
    s.sigma_rad = sigma;
    if (!f.samples.empty() && s.t_s <= f.samples.back().t_s) f.samples.back() = s;  // the end sample repeats the last tick
    else f.samples.push_back(s);
  };
  f.result = tools::run_closed_loop(mission, seed, dispersed, {}, false, record);
  return f;
}

OracleResult run_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed, const OracleOptions& options) {
  GuidanceFlight flight = fly_guidance(mission, seed, dispersed);
  tools::ClosedLoopResult& cl = flight.result;
  const std::vector<FlownSample>& flown = flight.samples;
  tools::PulloutBound pullout = tools::wings_level_pullout_bound(mission, seed, dispersed);
  OracleResult out;
  const bool bound_exceeded = pullout.error.empty() && !pullout.exceeded.empty();
  if (!cl.error.empty() || !pullout.error.empty()) {
    out.error = !cl.error.empty() ? cl.error : "pull-out bound: " + pullout.error;
  } else if (options.solve_decided || !(cl.verdict.success || bound_exceeded)) {
    out = solve_oracle(mission, seed, dispersed, flown, cl.verdict.success, options);
    out.solved = out.error.empty();
  }
  // A flight is the proof of feasibility, the pull-out bound a proof of infeasibility that
  // stands over the optimizer's verdicts. A run both proven feasible and beyond the bound keeps
  // its proof: the campaign report names it as a bug to explain.
  if (out.error.empty() && cl.verdict.success) {
    out.feasibility = Feasibility::kFlown;
  } else if (out.error.empty() && bound_exceeded && out.feasibility != Feasibility::kProvenOpenLoop) {
    out.feasibility = Feasibility::kPulloutBound;
    out.reason.clear();
  }
  out.feasible = out.error.empty() && (out.feasibility == Feasibility::kFlown || out.feasibility == Feasibility::kProvenOpenLoop);
  out.flown = std::move(cl);
  out.pullout = std::move(pullout);
  return out;
}

json oracle_record(const OracleResult& o) {
  json j = {{"error", o.error}, {"feasible", o.feasible}, {"feasibility", to_string(o.feasibility)}, {"solved", o.solved}};
  if (!o.reason.empty()) j["reason"] = o.reason;
  if (!o.solved) return j;
  const auto& f = o.entry.figures;
  const auto& s = o.entry.solution;
  const std::pair<const char*, double> margins[] = {
      {"heat_flux", f.margin_heat_flux}, {"load_factor", f.margin_load},   {"dynamic_pressure", f.margin_q},
      {"q_alpha", f.margin_q_alpha},     {"taem_range", f.margin_range},   {"taem_altitude", f.margin_altitude},
      {"taem_mach", f.margin_mach},      {"taem_flight_path", f.margin_gamma}, {"taem_heading", f.margin_heading}};
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json m = json::object();
  json binding = json::array();  // the constraints that set the common margin
  for (const auto& [name, v] : margins) {
    m[name] = num(v);
    if (std::isfinite(v) && std::isfinite(f.margin) && v <= f.margin + 1e-3) binding.push_back(name);
  }
  json attempts = json::array();
  for (const auto& a : o.attempts) {
    attempts.push_back({{"start", a.start},
                        {"status", to_string(a.entry.solution.status)},
                        {"iterations", a.entry.solution.iterations},
                        {"solves", a.entry.passes.size()},
                        {"segments", a.entry.segments()},
                        {"wall_s", a.entry.wall_s},
                        {"margin", num(a.entry.figures.margin)},
                        {"replay_success", a.replayed && a.replay.verdict.success}});
  }
  j["optimizer_feasible"] = o.optimizer_feasible;
  j["status"] = to_string(s.status);
  j["ipopt_status"] = s.ipopt_status;
  j["iterations"] = s.iterations;
  j["solve_s"] = o.solve_s;
  j["margin"] = num(f.margin);
  j["regularisation"] = num(f.regularisation);
  j["binding"] = binding;
  j["margins"] = m;
  j["miss_km"] = f.miss_m * 1e-3;
  j["tf_s"] = f.tf_s;
  j["segments"] = o.entry.segments();
  j["attempts"] = attempts;
  if (o.replayed) {
    j["replay"] = {{"success", o.replay.verdict.success},
                   {"event", truth::to_string(o.replay.summary.event)},
                   {"miss_km", o.replay.verdict.taem_miss_m * 1e-3},
                   {"end_point_diff_m", o.replay.final_position_diff_m},
                   {"violations", o.replay.verdict.violations}};
  }
  return j;
}

}  // namespace reentry::optimal
