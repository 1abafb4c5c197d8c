// reentry_mc: Monte Carlo dispersion campaigns of closed-loop missions flown in process.
//   reentry_mc --mission M --runs N --seed S --out DIR [--jobs J] [--shard i/K] [--nominal]
//              [--dispersions reference|stress]
// --dispersions picks the mission's dispersion set: [dispersions] (reference, default) or
// [stress_dispersions] (stress); every record and the report name it.
//   reentry_mc --merge DIR1 [DIR2 ...] --out DIR
// --guidance-knows-vehicle gives the guidance each run's drawn C_L, C_D and mass (diagnosis of
// what the unobservable aerodynamic and mass errors cost; every record is marked).
// --pullout-bound adds, per run, the maxima of the entry descent flown wings level at
// alpha_max with the run's dispersions, and to the report the runs that exceed a path
// constraint there (an upper bound on the success rate that no guidance can beat).
// --oracle judges every run's feasibility: a guidance success is feasible by its own flight, a
// run whose wings-level pull-out already exceeds a limit is infeasible (the cheap bound); the
// optimizer (tools/optimizer: maximum common constraint margin on the run's own truth models,
// warm-started from the run's flight, the optimal control history flown open loop in the truth
// simulator) judges the rest (--oracle-all: every run, which checks both cheap verdicts). Each
// record gets `feasible` (a truth flight proves it: the guidance's or the open-loop one) and the
// margins; the report `success_rate_feasible` (successes among feasible runs, Wilson interval)
// and the failure modes of the feasible runs the guidance loses.
// Run r (0 <= r < N) uses seed S + r, so any run is reproduced alone with the same seed
// (e.g. tools/sil --seed S+r). A shard i/K flies the runs with r % K == i and writes
// DIR/runs_shard_i_of_K.jsonl; a whole campaign writes DIR/runs.jsonl; --merge combines the
// run files of several directories into DIR/runs.jsonl. Every mode ends by writing
// DIR/report.json.
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "campaign_stats.hpp"
#include "closed_loop.hpp"
#include "run_oracle.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using reentry::tools::ClosedLoopResult;

namespace {

constexpr double kDeg = 180.0 / M_PI;

json run_record(int run, const ClosedLoopResult& r) {
  const auto& f = r.summary.final_state;
  const auto& m = r.summary.maxima;
  const auto& d = r.dispersion;
  json j;
  j["run"] = run;
  j["seed"] = r.seed;
  j["success"] = r.error.empty() && r.verdict.success;
  j["error"] = r.error;
  j["event"] = reentry::truth::to_string(r.summary.event);
  j["miss_km"] = r.verdict.taem_miss_m * 1e-3;
  j["miss_along_km"] = r.verdict.miss_along_m * 1e-3;
  j["miss_cross_km"] = r.verdict.miss_cross_m * 1e-3;
  j["alt_err_km"] = r.verdict.altitude_err_m * 1e-3;
  j["mach"] = r.verdict.mach;
  j["heading_err_deg"] = r.verdict.heading_err_rad * kDeg;
  j["gamma_deg"] = f.gamma_rad * kDeg;
  j["final_lat_deg"] = f.lat_rad * kDeg;
  j["final_lon_deg"] = f.lon_rad * kDeg;
  j["max_heat_flux_kW_m2"] = m.qdot_Wpm2 * 1e-3;
  j["max_g"] = m.n_g;
  j["max_q_kPa"] = m.q_Pa * 1e-3;
  j["max_q_alpha_kPa_deg"] = m.q_alpha_Pa_rad * 1e-3 * kDeg;
  j["heat_load_MJ_m2"] = f.Q_Jpm2 * 1e-6;
  j["violations"] = r.verdict.violations;
  j["planner_runs"] = r.counters.planner_runs;
  j["plans_adopted"] = r.counters.plans_adopted;
  j["planner_ms_max"] = r.counters.planner_ms_max;
  j["wall_s"] = r.wall_s;
  j["dispersion"] = {{"entry_gamma_deg", d.entry_flight_path_rad * kDeg},
                     {"entry_heading_deg", d.entry_heading_rad * kDeg},
                     {"entry_velocity_mps", d.entry_velocity_mps},
                     {"density_scale", d.density_scale},
                     {"cl_scale", d.cl_scale},
                     {"cd_scale", d.cd_scale},
                     {"mass_scale", d.mass_scale},
                     {"wind_scale", d.wind_scale}};
  return j;
}

json num_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The oracle's part of a run record: its verdict, and the solve when the optimizer judged.
json oracle_record(const reentry::optimal::OracleResult& o) {
  using reentry::optimal::to_string;
  json j = {{"error", o.error}, {"feasible", o.feasible}, {"feasibility", to_string(o.feasibility)}, {"solved", o.solved}};
  if (!o.solved) return j;
  const auto& f = o.entry.figures;
  const auto& s = o.entry.solution;
  const std::pair<const char*, double> margins[] = {
      {"heat_flux", f.margin_heat_flux}, {"load_factor", f.margin_load},   {"dynamic_pressure", f.margin_q},
      {"q_alpha", f.margin_q_alpha},     {"taem_range", f.margin_range},   {"taem_altitude", f.margin_altitude},
      {"taem_mach", f.margin_mach},      {"taem_flight_path", f.margin_gamma}, {"taem_heading", f.margin_heading}};
  json m = json::object();
  json binding = json::array();  // the constraints that set the common margin
  for (const auto& [name, v] : margins) {
    m[name] = num_or_null(v);
    if (std::isfinite(v) && std::isfinite(f.margin) && v <= f.margin + 1e-3) binding.push_back(name);
  }
  j["optimizer_feasible"] = o.optimizer_feasible;
  j["status"] = to_string(s.status);
  j["ipopt_status"] = s.ipopt_status;
  j["iterations"] = s.iterations;
  j["solve_s"] = s.wall_s;
  j["margin"] = num_or_null(f.margin);
  j["binding"] = binding;
  j["margins"] = m;
  j["miss_km"] = f.miss_m * 1e-3;
  j["tf_s"] = f.tf_s;
  if (o.replayed) {
    j["replay"] = {{"success", o.replay.verdict.success},
                   {"event", reentry::truth::to_string(o.replay.summary.event)},
                   {"miss_km", o.replay.verdict.taem_miss_m * 1e-3},
                   {"end_point_diff_m", o.replay.final_position_diff_m},
                   {"violations", o.replay.verdict.violations}};
  }
  return j;
}

json pullout_record(const reentry::tools::PulloutBound& b) {
  const auto& m = b.maxima;
  return {{"error", b.error},
          {"heat_flux_kW_m2", m.qdot_Wpm2 * 1e-3},
          {"q_kPa", m.q_Pa * 1e-3},
          {"q_alpha_kPa_deg", m.q_alpha_Pa_rad * 1e-3 * kDeg},
          {"g", m.n_g},
          {"exceeded", b.exceeded}};
}

void progress(int done, int total, double elapsed_s) {
  const bool tty = isatty(STDERR_FILENO) != 0;
  const int step = std::max(1, total / 10);
  if (!tty && done != total && done % step != 0) return;
  const double eta = done > 0 ? elapsed_s / done * (total - done) : 0.0;
  const int width = 30;
  const int filled = total > 0 ? width * done / total : width;
  std::fprintf(stderr, "%s[%s%s] %d/%d runs, %.0f s elapsed, ETA %.0f s%s", tty ? "\r" : "",
               std::string(static_cast<std::size_t>(filled), '#').c_str(),
               std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done, total, elapsed_s, eta,
               tty ? (done == total ? "\n" : "") : "\n");
  std::fflush(stderr);
}

std::vector<json> read_runs(const std::vector<std::string>& dirs, std::string* error) {
  std::vector<json> runs;
  std::map<int, std::string> seen;
  for (const auto& d : dirs) {
    if (!fs::is_directory(d)) {
      *error = "not a directory: " + d;
      return {};
    }
    for (const auto& entry : fs::directory_iterator(d)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("runs", 0) != 0 || entry.path().extension() != ".jsonl") continue;
      std::ifstream in(entry.path());
      std::string line;
      int line_no = 0;
      while (std::getline(in, line)) {
        ++line_no;
        if (line.empty()) continue;
        json j = json::parse(line, nullptr, false);
        if (j.is_discarded() || !j.contains("run")) {
          *error = entry.path().string() + ":" + std::to_string(line_no) + ": not a run record";
          return {};
        }
        const int run = j["run"].get<int>();
        if (seen.count(run) != 0) {
          *error = "run " + std::to_string(run) + " appears twice (" + seen[run] + " and " + entry.path().string() + ")";
          return {};
        }
        seen[run] = entry.path().string();
        runs.push_back(std::move(j));
      }
    }
  }
  std::sort(runs.begin(), runs.end(), [](const json& a, const json& b) { return a["run"] < b["run"]; });
  return runs;
}

// A failed run's mode: its violations in the order recorded, "taem_range" split into
// "taem_range_long" / "taem_range_short" by the side of the aim point it ended on.
std::string failure_mode(const json& r) {
  std::string mode;
  for (const auto& v : r["violations"]) {
    std::string name = v.get<std::string>();
    if (name == "taem_range" && r.contains("miss_along_km"))
      name += r["miss_along_km"].get<double>() < 0.0 ? "_short" : "_long";
    mode += (mode.empty() ? "" : " + ") + name;
  }
  return mode.empty() ? (r.contains("event") ? r["event"].get<std::string>() : std::string("unknown")) : mode;
}

template <class Select>
json failure_modes(const std::vector<json>& runs, Select select) {
  std::map<std::string, std::vector<json>> seeds;
  for (const auto& r : runs) {
    if (!r["success"].get<bool>() && select(r)) seeds[failure_mode(r)].push_back(r["seed"]);
  }
  std::vector<std::pair<std::string, std::vector<json>>> sorted(seeds.begin(), seeds.end());
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second.size() > b.second.size(); });
  json out = json::array();
  for (const auto& [mode, s] : sorted) out.push_back({{"mode", mode}, {"runs", s.size()}, {"seeds", s}});
  return out;
}

json violation_counts(const std::vector<json>& runs) {
  std::map<std::string, int> count;
  for (const auto& r : runs) {
    for (const auto& v : r["violations"]) ++count[v.get<std::string>()];
  }
  json out = json::object();
  for (const auto& [name, n] : count) out[name] = n;
  return out;
}

json summarise(const std::vector<json>& runs, const std::string& mission) {
  using reentry::tools::percentile;
  std::vector<double> miss, along, cross, alt, mach, heading, qdot, g, q, qa, plan_ms, wall;
  json failed = json::array();
  int successes = 0;
  for (const auto& r : runs) {
    if (r["success"].get<bool>()) ++successes;
    else failed.push_back(r["seed"]);
    miss.push_back(r["miss_km"]);
    if (r.contains("miss_along_km")) along.push_back(r["miss_along_km"]);
    if (r.contains("miss_cross_km")) cross.push_back(r["miss_cross_km"]);
    alt.push_back(std::fabs(r["alt_err_km"].get<double>()));
    mach.push_back(r["mach"]);
    heading.push_back(std::fabs(r["heading_err_deg"].get<double>()));
    qdot.push_back(r["max_heat_flux_kW_m2"]);
    g.push_back(r["max_g"]);
    q.push_back(r["max_q_kPa"]);
    qa.push_back(r["max_q_alpha_kPa_deg"]);
    plan_ms.push_back(r["planner_ms_max"]);
    wall.push_back(r["wall_s"]);
  }
  const int n = static_cast<int>(runs.size());
  const auto ci = reentry::tools::wilson_interval(successes, n);
  auto dist = [&](const std::vector<double>& v) {
    return json{{"p50", percentile(v, 50)}, {"p95", percentile(v, 95)}, {"max", percentile(v, 100)}};
  };
  json rep;
  rep["mission"] = mission;
  // The dispersion set(s) of the records ("reference", "stress", "nominal"; older records: none).
  std::map<std::string, int> sets;
  for (const auto& r : runs) ++sets[r.contains("dispersions") ? r["dispersions"].get<std::string>() : "unrecorded"];
  rep["dispersions"] = json::object();
  for (const auto& [set, count] : sets) rep["dispersions"][set] = count;
  rep["runs"] = n;
  rep["successes"] = successes;
  rep["success_rate"] = n > 0 ? static_cast<double>(successes) / n : 0.0;
  rep["ci95_low"] = ci.low;
  rep["ci95_high"] = ci.high;
  rep["miss_km_p50"] = percentile(miss, 50);
  rep["miss_km_p95"] = percentile(miss, 95);
  rep["miss_km_max"] = percentile(miss, 100);
  // Bias and spread of the miss split along the arrival line (> 0: long / right of it).
  auto spread = [&](const std::vector<double>& v) {
    return json{{"p5", percentile(v, 5)}, {"p50", percentile(v, 50)}, {"p95", percentile(v, 95)}};
  };
  // Only over the whole campaign: a merge with run files written before the split has none.
  if (along.size() == runs.size() && cross.size() == runs.size() && !runs.empty()) {
    rep["miss_along_km"] = spread(along);
    rep["miss_cross_km"] = spread(cross);
  }
  rep["failed_seeds"] = failed;
  rep["altitude_err_km_abs"] = dist(alt);
  rep["mach"] = {{"p5", percentile(mach, 5)}, {"p50", percentile(mach, 50)}, {"p95", percentile(mach, 95)}};
  rep["heading_err_deg_abs"] = dist(heading);
  rep["max_heat_flux_kW_m2"] = dist(qdot);
  rep["max_g"] = dist(g);
  rep["max_q_kPa"] = dist(q);
  rep["max_q_alpha_kPa_deg"] = dist(qa);
  rep["planner_ms_max"] = dist(plan_ms);
  rep["wall_s_per_run"] = dist(wall);
  std::vector<json> sorted = runs;
  std::sort(sorted.begin(), sorted.end(),
            [](const json& a, const json& b) { return a["miss_km"].get<double>() > b["miss_km"].get<double>(); });
  json worst = json::array();
  for (std::size_t i = 0; i < sorted.size() && i < 5; ++i) {
    worst.push_back({{"seed", sorted[i]["seed"]}, {"miss_km", sorted[i]["miss_km"]}, {"event", sorted[i]["event"]},
                     {"violations", sorted[i]["violations"]}});
  }
  rep["worst_cases"] = worst;
  // Failure modes: the set of violations of each failed run, the range miss split by side
  // (long or short of the aim point), counted per set and sorted by count, plus the runs per
  // violation. What fails, and with what else, is the first question of a campaign review.
  rep["violation_runs"] = violation_counts(runs);
  rep["failure_modes"] = failure_modes(runs, [](const json&) { return true; });
  // A diagnosis campaign (--guidance-knows-vehicle) must never pass for a flight campaign.
  const auto knows = std::count_if(runs.begin(), runs.end(), [](const json& r) { return r.contains("guidance_knows_vehicle"); });
  if (knows > 0) rep["guidance_knows_vehicle_runs"] = knows;
  // Physics bound (--pullout-bound): runs whose wings-level pull-out at alpha_max already
  // exceeds a path constraint fail whatever the guidance does.
  int bounded = 0;
  json exceeding = json::array();
  for (const auto& r : runs) {
    if (!r.contains("pullout_bound")) continue;
    ++bounded;
    if (!r["pullout_bound"]["exceeded"].empty()) exceeding.push_back(r["seed"]);
  }
  if (bounded > 0) {
    rep["pullout_bound"] = {{"runs", bounded},
                            {"runs_exceeding", exceeding.size()},
                            {"success_rate_upper_bound", static_cast<double>(bounded - static_cast<int>(exceeding.size())) / bounded},
                            {"seeds_exceeding", exceeding}};
    // What the guidance loses among the runs the pull-out leaves feasible.
    rep["pullout_bound"]["failure_modes_feasible"] = failure_modes(
        runs, [](const json& r) { return r.contains("pullout_bound") && r["pullout_bound"]["exceeded"].empty(); });
  }
  // Feasibility oracle (--oracle): which runs any guidance could fly, and how ours does on them.
  int with_oracle = 0, solved = 0, feasible = 0, feasible_successes = 0;
  std::map<std::string, int> by_class;
  std::map<std::string, int> binding_infeasible;
  json feasible_but_pullout = json::array(), successes_not_found = json::array();
  json optimizer_feasible_beyond_bound = json::array(), undecided_seeds = json::array();
  std::vector<double> solve_times, margins;
  double alpha_band_deg = 0.0;
  for (const auto& r : runs) {
    if (!r.contains("oracle")) continue;
    const json& o = r["oracle"];
    ++with_oracle;
    if (o.contains("alpha_band_deg")) alpha_band_deg = std::max(alpha_band_deg, o["alpha_band_deg"].get<double>());
    ++by_class[o["feasibility"].get<std::string>()];
    if (o["solved"].get<bool>()) {
      ++solved;
      solve_times.push_back(o["solve_s"].get<double>());
      if (o["margin"].is_number()) margins.push_back(o["margin"].get<double>());
      if (r["success"].get<bool>() && !o["optimizer_feasible"].get<bool>()) successes_not_found.push_back(r["seed"]);
      if (!r["pullout_bound"]["exceeded"].empty() && o["optimizer_feasible"].get<bool>())
        optimizer_feasible_beyond_bound.push_back(r["seed"]);
    }
    if (o["feasible"].get<bool>()) {
      ++feasible;
      if (r["success"].get<bool>()) ++feasible_successes;
      if (r.contains("pullout_bound") && !r["pullout_bound"]["exceeded"].empty()) feasible_but_pullout.push_back(r["seed"]);
    }
    if (o["feasibility"] == "undecided" || o["feasibility"] == "optimizer_only") undecided_seeds.push_back(r["seed"]);
    if (o["feasibility"] == "infeasible")
      for (const auto& b : o["binding"]) ++binding_infeasible[b.get<std::string>()];
  }
  if (with_oracle > 0) {
    const auto fci = reentry::tools::wilson_interval(feasible_successes, feasible);
    json classes = json::object();
    for (const auto& [k, v] : by_class) classes[k] = v;
    json binding = json::object();
    for (const auto& [k, v] : binding_infeasible) binding[k] = v;
    rep["success_rate_feasible"] = feasible > 0 ? static_cast<double>(feasible_successes) / feasible : 0.0;
    rep["oracle"] = {
        {"runs", with_oracle},
        // 0: alpha free in its bounds (any guidance); > 0: within this band of the mission's
        // alpha profile (a guidance that flies its profile).
        {"alpha_band_deg", alpha_band_deg},
        {"solved", solved},
        {"feasible", feasible},
        {"feasible_successes", feasible_successes},
        {"success_rate_feasible", feasible > 0 ? static_cast<double>(feasible_successes) / feasible : 0.0},
        {"ci95_low", fci.low},
        {"ci95_high", fci.high},
        // Runs nothing decided (the solve stopped at its limits, or its open-loop flight fails
        // while the collocated one has a margin): counted as feasible losses, the rate's floor.
        {"undecided_seeds", undecided_seeds},
        {"success_rate_feasible_undecided_as_feasible",
         feasible + static_cast<int>(undecided_seeds.size()) > 0
             ? static_cast<double>(feasible_successes) / (feasible + static_cast<double>(undecided_seeds.size()))
             : 0.0},
        {"feasibility", classes},
        {"binding_constraints_of_infeasible_runs", binding},
        {"margin", {{"p5", percentile(margins, 5)}, {"p50", percentile(margins, 50)}, {"p95", percentile(margins, 95)}}},
        {"solve_s", {{"p50", percentile(solve_times, 50)}, {"p95", percentile(solve_times, 95)}, {"max", percentile(solve_times, 100)}}},
        {"successes_the_optimizer_did_not_find_feasible", successes_not_found},
        {"feasible_but_pullout_bound_exceeded", feasible_but_pullout},
        {"optimizer_feasible_but_pullout_bound_exceeded", optimizer_feasible_beyond_bound},
        // The guidance's real gap: the feasible runs it loses, by failure mode.
        {"failure_modes_feasible", failure_modes(runs, [](const json& r) {
           return r.contains("oracle") && r["oracle"]["feasible"].get<bool>();
         })}};
  }
  return rep;
}

int write_report(const std::vector<std::string>& dirs, const std::string& out, const std::string& mission,
                 bool write_runs = false) {
  std::string error;
  const auto runs = read_runs(dirs, &error);
  if (!error.empty()) {
    std::fprintf(stderr, "reentry_mc: %s\n", error.c_str());
    return 2;
  }
  if (write_runs) {
    // A merge leaves a complete campaign directory: the combined records (in run order) next
    // to the report, so that the plots and a later merge read it like a whole campaign.
    fs::create_directories(out);
    std::ofstream records(fs::path(out) / "runs.jsonl");
    for (const auto& r : runs) records << r.dump() << "\n";
  }
  std::string name = mission;
  if (name.empty() && !runs.empty() && runs.front().contains("mission")) name = runs.front()["mission"];
  const json rep = summarise(runs, name);
  fs::create_directories(out);
  std::ofstream(fs::path(out) / "report.json") << rep.dump(2) << "\n";
  std::string sets;
  for (const auto& [set, count] : rep["dispersions"].items()) sets += (sets.empty() ? "" : "+") + set;
  std::printf("%s (%s): %d/%d successful (%.1f %%, 95 %% CI %.1f-%.1f %%), miss p50 %.2f km, p95 %.2f km, max %.2f km\n",
              name.c_str(), sets.c_str(), rep["successes"].get<int>(), rep["runs"].get<int>(), 100.0 * rep["success_rate"].get<double>(),
              100.0 * rep["ci95_low"].get<double>(), 100.0 * rep["ci95_high"].get<double>(),
              rep["miss_km_p50"].get<double>(), rep["miss_km_p95"].get<double>(), rep["miss_km_max"].get<double>());
  if (rep.contains("miss_along_km") && rep.contains("miss_cross_km")) {
    const json& a = rep["miss_along_km"];
    const json& c = rep["miss_cross_km"];
    std::printf("%s: miss along the arrival line p50 %+.2f km (p5 %+.2f, p95 %+.2f; > 0 long), across it p50 %+.2f km "
                "(p5 %+.2f, p95 %+.2f; > 0 right)\n",
                name.c_str(), a["p50"].get<double>(), a["p5"].get<double>(), a["p95"].get<double>(),
                c["p50"].get<double>(), c["p5"].get<double>(), c["p95"].get<double>());
  }
  auto print_modes = [&](const char* what, const json& modes) {
    if (modes.empty()) return;
    std::printf("%s: %s:", name.c_str(), what);
    for (std::size_t i = 0; i < modes.size() && i < 6; ++i) {
      std::printf("%s %s %d", i == 0 ? "" : ",", modes[i]["mode"].get<std::string>().c_str(), modes[i]["runs"].get<int>());
    }
    std::printf("%s\n", modes.size() > 6 ? ", ..." : "");
  };
  print_modes("failure modes (runs)", rep["failure_modes"]);
  if (rep.contains("guidance_knows_vehicle_runs")) {
    std::printf("%s: diagnosis: the guidance knew the drawn C_L, C_D and mass in %d runs\n", name.c_str(),
                rep["guidance_knows_vehicle_runs"].get<int>());
  }
  if (rep.contains("pullout_bound")) {
    const json& b = rep["pullout_bound"];
    std::printf("%s: wings-level pull-out at alpha_max exceeds a path constraint in %d/%d runs: success rate <= %.1f %%\n",
                name.c_str(), b["runs_exceeding"].get<int>(), b["runs"].get<int>(),
                100.0 * b["success_rate_upper_bound"].get<double>());
    print_modes("failure modes of the runs feasible at the pull-out", b["failure_modes_feasible"]);
  }
  if (rep.contains("oracle")) {
    const json& o = rep["oracle"];
    std::printf("%s: oracle: %d/%d runs feasible (proven by a truth flight), %d successes among them: "
                "success_rate_feasible %.1f %% (95 %% CI %.1f-%.1f %%)\n",
                name.c_str(), o["feasible"].get<int>(), o["runs"].get<int>(), o["feasible_successes"].get<int>(),
                100.0 * o["success_rate_feasible"].get<double>(), 100.0 * o["ci95_low"].get<double>(),
                100.0 * o["ci95_high"].get<double>());
    if (!o["undecided_seeds"].empty())
      std::printf("%s: %zu runs undecided; counted as feasible losses, success_rate_feasible %.1f %%\n", name.c_str(),
                  o["undecided_seeds"].size(), 100.0 * o["success_rate_feasible_undecided_as_feasible"].get<double>());
    if (o.value("alpha_band_deg", 0.0) > 0.0)
      std::printf("%s: oracle: alpha kept within %.1f deg of the mission's alpha profile (feasible for a guidance "
                  "that flies its profile)\n",
                  name.c_str(), o["alpha_band_deg"].get<double>());
    std::printf("%s: oracle classes:", name.c_str());
    for (const auto& [k, v] : o["feasibility"].items()) std::printf(" %s %d", k.c_str(), v.get<int>());
    if (o["solved"].get<int>() > 0)
      std::printf("; %d solved, solve p50 %.1f s, max %.1f s", o["solved"].get<int>(), o["solve_s"]["p50"].get<double>(),
                  o["solve_s"]["max"].get<double>());
    std::printf("\n");
    print_modes("failure modes of the feasible runs (the guidance's gap)", o["failure_modes_feasible"]);
    if (!o["feasible_but_pullout_bound_exceeded"].empty())
      std::printf("%s: BUG: %zu runs proven feasible exceed a limit at the wings-level pull-out\n", name.c_str(),
                  o["feasible_but_pullout_bound_exceeded"].size());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"reentry Monte Carlo campaign (closed loop, in process)"};
  std::string mission_arg, out, shard, dispersion_set = "reference";
  int runs = 0, jobs = 0;
  std::uint64_t seed = 1;
  bool nominal = false, trace = false, pullout_bound = false, knows_vehicle = false, oracle = false,
       oracle_all = false;
  int oracle_segments = reentry::optimal::EntrySolveOptions{}.segments;
  double oracle_max_s = reentry::optimal::EntrySolveOptions{}.solver.max_wall_s;
  double oracle_alpha_band_deg = 0.0;
  std::vector<std::string> merge;
  app.add_option("--mission", mission_arg, "mission name or TOML file");
  app.add_option("--runs", runs, "number of runs of the whole campaign");
  app.add_option("--seed", seed, "seed of run 0 (run r uses seed + r)");
  app.add_option("--out", out, "output directory")->required();
  app.add_option("--jobs", jobs, "parallel runs (default: all cores)");
  app.add_option("--shard", shard, "i/K: fly only the runs r with r % K == i");
  app.add_flag("--nominal", nominal, "no dispersions (every run nominal)");
  app.add_option("--dispersions", dispersion_set,
                 "dispersion set: reference ([dispersions], Gaussian 3 sigma) or stress ([stress_dispersions])")
      ->check(CLI::IsMember({"reference", "stress"}));
  app.add_flag("--trace", trace, "record each run (1 Hz, the SIL's channels) in --out/traces/run_<seed>.lcm");
  app.add_flag("--pullout-bound", pullout_bound,
               "also fly each run's entry descent wings level at alpha_max (the physics bound of the first pull-out)");
  app.add_flag("--guidance-knows-vehicle", knows_vehicle,
               "diagnosis: give the guidance each run's drawn C_L, C_D and mass (what their ignorance costs)");
  app.add_flag("--oracle", oracle,
               "also solve each run's maximum-margin problem on its own truth models (feasible runs, margins)");
  app.add_flag("--oracle-all", oracle_all,
               "oracle: solve every run, also those a guidance success or the pull-out bound decides (checks both)");
  app.add_option("--oracle-segments", oracle_segments, "oracle: Hermite-Simpson segments")->check(CLI::Range(10, 1000));
  app.add_option("--oracle-max-time", oracle_max_s, "oracle: wall-clock limit of one solve [s]")->check(CLI::PositiveNumber);
  app.add_option("--oracle-alpha-band", oracle_alpha_band_deg,
                 "oracle: keep alpha within this band of the mission's alpha profile [deg] (0: alpha free; "
                 "> 0: feasibility for a guidance that flies its profile)")
      ->check(CLI::Range(0.0, 90.0));
  app.add_option("--merge", merge, "combine the run files of these directories into --out (runs.jsonl, report.json)");
  CLI11_PARSE(app, argc, argv);

  if (!merge.empty()) {
    // The merged records go to --out/runs.jsonl: a directory merged into itself would hold its
    // runs twice.
    std::error_code ec;
    for (const auto& d : merge) {
      if (fs::exists(out) && fs::equivalent(fs::path(d), fs::path(out), ec)) {
        std::fprintf(stderr, "reentry_mc: --out %s is one of the merged directories\n", out.c_str());
        return 2;
      }
    }
    return write_report(merge, out, "", true);
  }
  if (mission_arg.empty() || runs <= 0) {
    std::fprintf(stderr, "reentry_mc: --mission and --runs N (N >= 1) are required (or --merge)\n");
    return 2;
  }
  if (oracle && (trace || knows_vehicle)) {
    std::fprintf(stderr, "reentry_mc: --oracle flies the guidance as in flight: not with --trace or --guidance-knows-vehicle\n");
    return 2;
  }
  int shard_i = 0, shard_k = 1;
  if (!shard.empty()) {
    if (std::sscanf(shard.c_str(), "%d/%d", &shard_i, &shard_k) != 2 || shard_k < 1 || shard_i < 0 || shard_i >= shard_k) {
      std::fprintf(stderr, "reentry_mc: --shard must be i/K with 0 <= i < K, got '%s'\n", shard.c_str());
      return 2;
    }
  }
  auto loaded = reentry::config::load_mission(mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "reentry_mc: %s\n", loaded.error.c_str());
    return 2;
  }
  if (dispersion_set == "stress") {
    if (!loaded.mission.has_stress_dispersions) {
      std::fprintf(stderr, "reentry_mc: --dispersions stress: %s has no [stress_dispersions] section\n",
                   loaded.mission.source_file.c_str());
      return 2;
    }
    loaded.mission.dispersions = loaded.mission.stress_dispersions;  // every draw below uses this set
  }
  const std::string set_name = nominal ? "nominal" : dispersion_set;
  std::vector<int> mine;
  for (int r = 0; r < runs; ++r) {
    if (r % shard_k == shard_i) mine.push_back(r);
  }
  if (jobs <= 0) jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (trace) fs::create_directories(fs::path(out) / "traces");
  std::vector<json> records(mine.size());
  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  const auto t0 = std::chrono::steady_clock::now();
  // One run's record.
  auto compute = [&](std::size_t i) {
    const int r = mine[i];
    const std::string trace_log =
        trace ? (fs::path(out) / "traces" / ("run_" + std::to_string(seed + r) + ".lcm")).string() : std::string();
    json rec;
    if (oracle) {
      reentry::optimal::OracleOptions oo;
      oo.solve.segments = oracle_segments;
      oo.solve.solver.max_wall_s = oracle_max_s;
      oo.solve.alpha_band_rad = oracle_alpha_band_deg / kDeg;
      oo.solve_decided = oracle_all;
      const reentry::optimal::OracleResult o = reentry::optimal::run_oracle(loaded.mission, seed + r, !nominal, oo);
      rec = run_record(r, o.flown);
      rec["oracle"] = oracle_record(o);
      rec["oracle"]["alpha_band_deg"] = oracle_alpha_band_deg;
      rec["feasible"] = o.feasible;
      rec["pullout_bound"] = pullout_record(o.pullout);
    } else {
      const ClosedLoopResult res = reentry::tools::run_closed_loop(loaded.mission, seed + r, !nominal, trace_log, knows_vehicle);
      rec = run_record(r, res);
    }
    rec["mission"] = loaded.mission.name;
    rec["dispersions"] = set_name;
    if (knows_vehicle) rec["guidance_knows_vehicle"] = true;
    if (pullout_bound && !oracle) rec["pullout_bound"] = pullout_record(
        reentry::tools::wings_level_pullout_bound(loaded.mission, seed + r, !nominal));
    return rec;
  };
  auto worker = [&] {
    for (std::size_t i = next++; i < mine.size(); i = next++) {
      records[i] = compute(i);
      const int d = ++done;
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(d, static_cast<int>(mine.size()),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
  };
  const int workers = std::min<int>(jobs, static_cast<int>(mine.size()));
  if (oracle && workers > 1) {
    // IPOPT's linear solver (MUMPS 5.5, sequential build) is not thread-safe: two solves in
    // one process crash in DMUMPS_LOAD_INIT. Oracle campaigns run their jobs as processes
    // (forked before any thread exists), each on every workers-th run, writing its records
    // to a part file that this process collects.
    fs::create_directories(out);
    std::vector<pid_t> children;
    for (int k = 0; k < workers; ++k) {
      const pid_t pid = fork();
      if (pid < 0) {
        std::perror("reentry_mc: fork");
        return 2;
      }
      if (pid == 0) {
        std::ofstream part(fs::path(out) / (".oracle_part_" + std::to_string(k) + ".jsonl"));
        int mine_done = 0;
        for (std::size_t i = static_cast<std::size_t>(k); i < mine.size(); i += static_cast<std::size_t>(workers)) {
          part << json{{"index", i}, {"record", compute(i)}}.dump() << "\n" << std::flush;
          ++mine_done;
          if (k == 0)  // the first process reports for all (they share the runs evenly)
            progress(std::min<int>(mine_done * workers, static_cast<int>(mine.size())), static_cast<int>(mine.size()),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        part.close();
        std::_Exit(part ? 0 : 3);
      }
      children.push_back(pid);
    }
    bool ok = true;
    for (pid_t pid : children) {
      int status = 0;
      if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) ok = false;
    }
    for (int k = 0; k < workers; ++k) {
      const fs::path part = fs::path(out) / (".oracle_part_" + std::to_string(k) + ".jsonl");
      std::ifstream in(part);
      std::string line;
      while (std::getline(in, line)) {
        const json j = json::parse(line, nullptr, false);
        if (j.is_discarded() || !j.contains("index")) continue;
        records[j["index"].get<std::size_t>()] = j["record"];
      }
      std::error_code ec;
      fs::remove(part, ec);
    }
    for (const auto& rec : records) ok = ok && !rec.is_null();
    if (!ok) {
      std::fprintf(stderr, "reentry_mc: an oracle worker process failed (records missing)\n");
      return 3;
    }
  } else {
    std::vector<std::thread> pool;
    for (int j = 0; j < workers; ++j) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }

  fs::create_directories(out);
  const std::string file = shard.empty() ? "runs.jsonl"
                                         : "runs_shard_" + std::to_string(shard_i) + "_of_" + std::to_string(shard_k) + ".jsonl";
  std::ofstream f(fs::path(out) / file);
  for (const auto& rec : records) f << rec.dump() << "\n";
  f.close();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s: campaign wall time %.0f s (%zu runs, %d jobs)\n", loaded.mission.name.c_str(), wall, mine.size(), jobs);
  return write_report({out}, out, loaded.mission.name);
}
