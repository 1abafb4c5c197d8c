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
// Each records file has its campaign identity beside it (campaign.json, or
// campaign_shard_i_of_K.json: mission and its digest, runs, seed, shard, dispersion set and the
// flags that change a record); a merge proves from them that its inputs are the shards of one
// campaign, each exactly once, every run index and seed in place, and refuses anything else with
// the reason. Exit statuses: the table in tools/README.md (0 done, 2 usage or an input refused,
// 8 an output not written whole, 11 runs that could not be flown, 128 + signal interrupted).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "campaign_stats.hpp"
#include "closed_loop.hpp"
#include "run_oracle.hpp"
#include "transport/command_line.hpp"
#include "transport/exit_status.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using reentry::tools::ClosedLoopResult;

namespace {

namespace tx = reentry::transport;
constexpr double kDeg = 180.0 / M_PI;
constexpr const char* kTool = "reentry_mc";
constexpr int kRunsMax = 1000000;  // a campaign's records are held in memory

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
  // A numerical failure of the truth simulation is a run that could not be flown, not a result.
  for (const double v : {f.lat_rad, f.lon_rad, f.gamma_rad, m.qdot_Wpm2, m.n_g, m.q_Pa, r.verdict.taem_miss_m}) {
    if (!std::isfinite(v) && r.error.empty()) {
      j["error"] = "non-finite result of the truth simulation (event " + j["event"].get<std::string>() + ")";
      j["success"] = false;
      break;
    }
  }
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

json pullout_record(const reentry::tools::PulloutBound& b) {
  const auto& m = b.maxima;
  return {{"error", b.error},
          {"heat_flux_kW_m2", m.qdot_Wpm2 * 1e-3},
          {"q_kPa", m.q_Pa * 1e-3},
          {"q_alpha_kPa_deg", m.q_alpha_Pa_rad * 1e-3 * kDeg},
          {"g", m.n_g},
          {"exceeded", b.exceeded}};
}

// Progress on stderr: on a terminal one updating line; into a file (Slurm's job output, CI) one
// plain line every 10 % of the runs or every minute, never a carriage-return frame.
class Progress {
 public:
  explicit Progress(int total) : total_(total), tty_(isatty(STDERR_FILENO) != 0), t0_(std::chrono::steady_clock::now()) {}
  void update(int done) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const int pct = total_ > 0 ? 100 * done / total_ : 100;
    const bool last = done >= total_;
    if (!tty_) {
      if (done == last_done_ && !(elapsed - last_line_s_ >= 60.0)) return;
      if (!last && pct < next_pct_ && elapsed - last_line_s_ < 60.0) return;
      next_pct_ = (pct / 10 + 1) * 10;
      last_line_s_ = elapsed;
    }
    if (last && printed_last_) return;
    printed_last_ = last;
    last_done_ = done;
    const double eta = done > 0 ? elapsed / done * (total_ - done) : 0.0;
    const int width = 30;
    const int filled = total_ > 0 ? width * std::min(done, total_) / total_ : width;
    std::fprintf(stderr, "%s[%s%s] %d/%d runs, %.0f s elapsed, ETA %.0f s%s", tty_ ? "\r" : "",
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done, total_, elapsed, eta,
                 tty_ ? (last ? "\n" : "") : "\n");
    std::fflush(stderr);
  }

 private:
  int total_;
  bool tty_;
  std::chrono::steady_clock::time_point t0_;
  int next_pct_ = 0;
  int last_done_ = -1;
  double last_line_s_ = -1e9;
  bool printed_last_ = false;
};

// ----------------------------------------------------------------------------------------------
// Campaign identity: what must be equal for records to belong to one campaign.

struct Campaign {
  std::string mission, mission_digest, dispersions;
  std::int64_t runs = 0, seed = 0;
  int shard_i = 0, shard_k = 1;
  json flags = json::object();  // options that change a record (nominal, pull-out bound, oracle, ...)

  std::string records_name() const {
    return shard_k == 1 ? "runs.jsonl"
                        : "runs_shard_" + std::to_string(shard_i) + "_of_" + std::to_string(shard_k) + ".jsonl";
  }
  std::string identity_name() const {
    return shard_k == 1 ? "campaign.json"
                        : "campaign_shard_" + std::to_string(shard_i) + "_of_" + std::to_string(shard_k) + ".json";
  }
  json to_json() const {
    return {{"mission", mission}, {"mission_digest", mission_digest}, {"dispersions", dispersions}, {"runs", runs},
            {"seed", seed},       {"shard", std::to_string(shard_i) + "/" + std::to_string(shard_k)},
            {"flags", flags}};
  }
  /// Runs of this shard: r % K == i, 0 <= r < N.
  std::int64_t shard_runs() const { return runs > shard_i ? (runs - shard_i + shard_k - 1) / shard_k : 0; }
};

// "i/K" with 0 <= i < K, nothing else.
bool parse_shard(const std::string& s, int& i, int& k) {
  const auto slash = s.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 >= s.size() || s.size() > 19) return false;
  for (std::size_t c = 0; c < s.size(); ++c)
    if (c != slash && (s[c] < '0' || s[c] > '9')) return false;
  const long long a = std::stoll(s.substr(0, slash)), b = std::stoll(s.substr(slash + 1));
  if (b < 1 || b > kRunsMax || a < 0 || a >= b) return false;
  i = static_cast<int>(a);
  k = static_cast<int>(b);
  return true;
}

std::string campaign_from_json(const json& j, const std::string& where, Campaign& c) {
  const bool shape = j.is_object() && j.contains("mission") && j["mission"].is_string() && j.contains("mission_digest") &&
                     j["mission_digest"].is_string() && j.contains("dispersions") && j["dispersions"].is_string() &&
                     j.contains("runs") && j["runs"].is_number_integer() && j.contains("seed") &&
                     j["seed"].is_number_integer() && j.contains("shard") && j["shard"].is_string() &&
                     j.contains("flags") && j["flags"].is_object();
  if (!shape) return where + ": not a campaign identity (mission, mission_digest, dispersions, runs, seed, shard, flags)";
  c.mission = j["mission"];
  c.mission_digest = j["mission_digest"];
  c.dispersions = j["dispersions"];
  c.runs = j["runs"];
  c.seed = j["seed"];
  c.flags = j["flags"];
  if (c.runs < 1 || c.runs > kRunsMax) return where + ": field runs: value " + std::to_string(c.runs) + " outside [1, " + std::to_string(kRunsMax) + "]";
  if (c.seed < 0) return where + ": field seed: value " + std::to_string(c.seed) + " is negative";
  if (!parse_shard(j["shard"], c.shard_i, c.shard_k)) return where + ": field shard: value " + j["shard"].dump() + " is not i/K";
  return {};
}

// ----------------------------------------------------------------------------------------------
// Writing: every output checked; a failure is named with the file and the reason.

bool write_file(const fs::path& path, const std::string& content) {
  errno = 0;
  std::ofstream f(path);
  f << content;
  f.close();
  if (f) return true;
  std::fprintf(stderr, "%s: write failed: %s: %s\n", kTool, path.string().c_str(),
               std::strerror(errno != 0 ? errno : EIO));
  return false;
}

bool write_records(const fs::path& dir, const Campaign& c, const std::vector<json>& records) {
  std::string text;
  for (const auto& rec : records) text += rec.dump() + "\n";
  return write_file(dir / c.records_name(), text) && write_file(dir / c.identity_name(), c.to_json().dump(2) + "\n");
}

// The output folder exists and takes a file before anything is flown.
bool prepare_output(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec)) {
    std::fprintf(stderr, "%s: write failed: --out %s: %s\n", kTool, dir.string().c_str(),
                 ec ? ec.message().c_str() : "not a directory");
    return false;
  }
  return write_file(dir / ".reentry_mc_probe", "probe\n") && fs::remove(dir / ".reentry_mc_probe", ec);
}

// ----------------------------------------------------------------------------------------------
// Reading: every record checked field by field before anything is computed from it.

std::string check_record(const json& r) {
  if (!r.is_object()) return "not a JSON object";
  auto bad = [&](const char* key, const char* want) {
    return std::string("field ") + key + ": " + (r.contains(key) ? r[key].dump() : "missing") + " is not " + want;
  };
  for (const char* key : {"run", "seed"})
    if (!r.contains(key) || !r[key].is_number_integer() || r[key].get<std::int64_t>() < 0) return bad(key, "an integer >= 0");
  if (!r.contains("success") || !r["success"].is_boolean()) return bad("success", "true or false");
  for (const char* key : {"event", "mission", "dispersions", "error"})
    if (!r.contains(key) || !r[key].is_string()) return bad(key, "a string");
  if (!r.contains("violations") || !r["violations"].is_array()) return bad("violations", "an array");
  for (const auto& v : r["violations"])
    if (!v.is_string()) return bad("violations", "an array of strings");
  const bool flown = r["error"].get<std::string>().empty();  // a run not flown may carry nulls
  for (const char* key : {"miss_km", "alt_err_km", "mach", "heading_err_deg", "max_heat_flux_kW_m2", "max_g", "max_q_kPa",
                          "max_q_alpha_kPa_deg", "planner_ms_max", "wall_s"}) {
    if (!r.contains(key) || !(r[key].is_number() || (!flown && r[key].is_null()))) return bad(key, "a number");
  }
  for (const char* key : {"miss_along_km", "miss_cross_km"})
    if (r.contains(key) && !(r[key].is_number() || (!flown && r[key].is_null()))) return bad(key, "a number");
  if (r.contains("pullout_bound") && !(r["pullout_bound"].is_object() && r["pullout_bound"].contains("exceeded") &&
                                       r["pullout_bound"]["exceeded"].is_array())) {
    return bad("pullout_bound", "an object with an array 'exceeded'");
  }
  if (r.contains("oracle")) {
    const json& o = r["oracle"];
    const bool ok = o.is_object() && o.contains("feasible") && o["feasible"].is_boolean() && o.contains("feasibility") &&
                    o["feasibility"].is_string() && o.contains("solved") && o["solved"].is_boolean() &&
                    (!o["solved"].get<bool>() || (o.contains("solve_s") && o["solve_s"].is_number() &&
                                                  o.contains("optimizer_feasible") && o["optimizer_feasible"].is_boolean() &&
                                                  o.contains("binding") && o["binding"].is_array())) &&
                    r.contains("pullout_bound");
    if (!ok) return bad("oracle", "an oracle verdict (feasible, feasibility, solved, solve_s, binding) with a pull-out bound");
  }
  return {};
}

struct RecordsFile {
  fs::path path;
  Campaign campaign;
  std::vector<json> runs;
};

std::string read_records_file(const fs::path& path, RecordsFile& out) {
  out.path = path;
  const std::string name = path.filename().string();
  const std::string id_name = name == "runs.jsonl" ? "campaign.json" : "campaign" + name.substr(4, name.size() - 10) + ".json";
  const fs::path id_path = path.parent_path() / id_name;
  std::ifstream id(id_path);
  if (!id) return id_path.string() + ": missing (the campaign identity of " + path.string() + "; without it a merge cannot prove the campaign whole)";
  const json j = json::parse(id, nullptr, false);
  std::string err = campaign_from_json(j, id_path.string(), out.campaign);
  if (!err.empty()) return err;
  if (out.campaign.records_name() != name) return id_path.string() + ": field shard: " + j["shard"].dump() + " does not match " + name;
  std::ifstream in(path);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    json r = json::parse(line, nullptr, false);
    err = r.is_discarded() ? "not JSON" : check_record(r);
    if (!err.empty()) return path.string() + ":" + std::to_string(line_no) + ": " + err;
    out.runs.push_back(std::move(r));
  }
  if (in.bad()) return path.string() + ": read error";
  return {};
}

// The records files of the directories (runs.jsonl, runs_shard_i_of_K.jsonl).
std::string read_dirs(const std::vector<std::string>& dirs, std::vector<RecordsFile>& files) {
  for (const auto& d : dirs) {
    std::error_code ec;
    if (!fs::is_directory(d, ec)) return "--merge " + d + ": not a directory";
    std::vector<fs::path> names;
    for (const auto& entry : fs::directory_iterator(d, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("runs", 0) == 0 && entry.path().extension() == ".jsonl") names.push_back(entry.path());
    }
    if (names.empty()) return "--merge " + d + ": no run records (runs.jsonl or runs_shard_i_of_K.jsonl)";
    std::sort(names.begin(), names.end());
    for (const auto& n : names) {
      RecordsFile f;
      const std::string err = read_records_file(n, f);
      if (!err.empty()) return err;
      files.push_back(std::move(f));
    }
  }
  return {};
}

// One campaign: equal identities but for the shard index, every shard 0..K-1 exactly once,
// each holding exactly its runs (r % K == i, r < N) with seed S + r. "" or the reason.
std::string check_campaign(const std::vector<RecordsFile>& files, Campaign& merged) {
  const Campaign& c0 = files.front().campaign;
  std::map<int, std::string> shards;
  for (const auto& f : files) {
    const Campaign& c = f.campaign;
    const std::pair<const char*, bool> same[] = {
        {"mission", c.mission == c0.mission}, {"mission_digest", c.mission_digest == c0.mission_digest},
        {"dispersions", c.dispersions == c0.dispersions}, {"runs", c.runs == c0.runs}, {"seed", c.seed == c0.seed},
        {"shard count", c.shard_k == c0.shard_k}, {"flags", c.flags == c0.flags}};
    for (const auto& [what, equal] : same) {
      if (!equal) {
        return "inconsistent campaigns: " + std::string(what) + " of " + f.path.string() + " (" + c.to_json().dump() +
               ") differs from " + files.front().path.string() + " (" + c0.to_json().dump() + ")";
      }
    }
    if (!shards.emplace(c.shard_i, f.path.string()).second) {
      return "shard " + std::to_string(c.shard_i) + "/" + std::to_string(c.shard_k) + " appears twice (" +
             shards[c.shard_i] + " and " + f.path.string() + ")";
    }
    std::set<std::int64_t> runs;
    for (const auto& r : f.runs) {
      const std::int64_t run = r["run"], seed = r["seed"];
      const std::string at = f.path.string() + ": run " + std::to_string(run);
      if (run >= c.runs || run % c.shard_k != c.shard_i) return at + ": not a run of shard " + std::to_string(c.shard_i) + "/" + std::to_string(c.shard_k) + " of " + std::to_string(c.runs);
      if (seed != c.seed + run) return at + ": field seed: value " + std::to_string(seed) + ", the campaign's is " + std::to_string(c.seed + run);
      if (r["mission"] != c.mission || r["dispersions"] != c.dispersions) return at + ": mission or dispersions differ from the campaign's";
      if (!runs.insert(run).second) return at + ": appears twice";
    }
    if (static_cast<std::int64_t>(runs.size()) != c.shard_runs()) {
      return f.path.string() + ": " + std::to_string(runs.size()) + " of the " + std::to_string(c.shard_runs()) + " runs of its shard";
    }
  }
  for (int i = 0; i < c0.shard_k; ++i) {
    if (shards.count(i) == 0) return "shard " + std::to_string(i) + "/" + std::to_string(c0.shard_k) + " missing: the campaign has gaps";
  }
  merged = c0;
  merged.shard_i = 0;
  merged.shard_k = 1;
  return {};
}

// ----------------------------------------------------------------------------------------------
// Summary of a campaign.

// Finite values of a numeric field over the runs (runs not flown carry nulls).
std::vector<double> field(const std::vector<json>& runs, const char* key, bool absolute = false) {
  std::vector<double> v;
  for (const auto& r : runs) {
    if (!r.contains(key) || !r[key].is_number()) continue;
    const double x = r[key].get<double>();
    if (std::isfinite(x)) v.push_back(absolute ? std::fabs(x) : x);
  }
  return v;
}

json dist(const std::vector<double>& v) {
  using reentry::tools::percentile;
  return json{{"p50", percentile(v, 50)}, {"p95", percentile(v, 95)}, {"max", percentile(v, 100)}};
}

json spread(const std::vector<double>& v) {
  using reentry::tools::percentile;
  return json{{"p5", percentile(v, 5)}, {"p50", percentile(v, 50)}, {"p95", percentile(v, 95)}};
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

json summarise_core(const std::vector<json>& runs, const std::string& mission) {
  json failed = json::array(), errors = json::array();
  int successes = 0;
  for (const auto& r : runs) {
    if (r["success"].get<bool>()) ++successes;
    else failed.push_back(r["seed"]);
    if (!r["error"].get<std::string>().empty()) errors.push_back({{"seed", r["seed"]}, {"error", r["error"]}});
  }
  const int n = static_cast<int>(runs.size());
  const auto ci = reentry::tools::wilson_interval(successes, n);
  json rep;
  rep["mission"] = mission;
  // The dispersion set(s) of the records ("reference", "stress", "nominal").
  std::map<std::string, int> sets;
  for (const auto& r : runs) ++sets[r["dispersions"].get<std::string>()];
  rep["dispersions"] = json::object();
  for (const auto& [set, count] : sets) rep["dispersions"][set] = count;
  rep["runs"] = n;
  rep["successes"] = successes;
  rep["success_rate"] = n > 0 ? static_cast<double>(successes) / n : 0.0;
  rep["ci95_low"] = ci.low;
  rep["ci95_high"] = ci.high;
  const std::vector<double> miss = field(runs, "miss_km");
  rep["miss_km_p50"] = reentry::tools::percentile(miss, 50);
  rep["miss_km_p95"] = reentry::tools::percentile(miss, 95);
  rep["miss_km_max"] = reentry::tools::percentile(miss, 100);
  // Bias and spread of the miss split along the arrival line (> 0: long / right of it), only
  // over the whole campaign.
  const std::vector<double> along = field(runs, "miss_along_km"), cross = field(runs, "miss_cross_km");
  if (along.size() == runs.size() && cross.size() == runs.size() && !runs.empty()) {
    rep["miss_along_km"] = spread(along);
    rep["miss_cross_km"] = spread(cross);
  }
  rep["failed_seeds"] = failed;
  if (!errors.empty()) rep["run_errors"] = errors;  // runs that could not be flown, with the reason
  rep["altitude_err_km_abs"] = dist(field(runs, "alt_err_km", true));
  rep["mach"] = spread(field(runs, "mach"));
  rep["heading_err_deg_abs"] = dist(field(runs, "heading_err_deg", true));
  rep["max_heat_flux_kW_m2"] = dist(field(runs, "max_heat_flux_kW_m2"));
  rep["max_g"] = dist(field(runs, "max_g"));
  rep["max_q_kPa"] = dist(field(runs, "max_q_kPa"));
  rep["max_q_alpha_kPa_deg"] = dist(field(runs, "max_q_alpha_kPa_deg"));
  rep["planner_ms_max"] = dist(field(runs, "planner_ms_max"));
  rep["wall_s_per_run"] = dist(field(runs, "wall_s"));
  return rep;
}

void add_worst_and_modes(json& rep, const std::vector<json>& runs) {
  std::vector<json> sorted = runs;
  auto miss = [](const json& r) { return r["miss_km"].is_number() ? r["miss_km"].get<double>() : -HUGE_VAL; };
  std::sort(sorted.begin(), sorted.end(), [&](const json& a, const json& b) { return miss(a) > miss(b); });
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
}

void add_pullout_bound(json& rep, const std::vector<json>& runs) {
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
}

void add_oracle(json& rep, const std::vector<json>& runs) {
  using reentry::tools::percentile;
  // Feasibility oracle (--oracle): which runs any guidance could fly, and how ours does on them.
  int with_oracle = 0, solved = 0, feasible = 0, feasible_successes = 0;
  std::map<std::string, int> by_class;
  std::map<std::string, int> binding_infeasible;
  json feasible_but_pullout = json::array(), successes_not_found = json::array();
  json optimizer_feasible_beyond_bound = json::array(), undecided_seeds = json::array();
  json undecided_reasons = json::object();
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
    if (o["feasibility"] == "undecided") {
      undecided_seeds.push_back(r["seed"]);
      undecided_reasons[std::to_string(r["seed"].get<std::uint64_t>())] = o.value("reason", "");
    }
    if (o["feasibility"] == "infeasible")
      for (const auto& b : o["binding"]) ++binding_infeasible[b.get<std::string>()];
  }
  if (with_oracle == 0) return;
  {
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
        {"undecided_reasons", undecided_reasons},
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
}

json summarise(const std::vector<json>& runs, const std::string& mission) {
  json rep = summarise_core(runs, mission);
  add_worst_and_modes(rep, runs);
  add_pullout_bound(rep, runs);
  add_oracle(rep, runs);
  return rep;
}

void print_modes(const std::string& name, const char* what, const json& modes) {
  if (modes.empty()) return;
  std::printf("%s: %s:", name.c_str(), what);
  for (std::size_t i = 0; i < modes.size() && i < 6; ++i) {
    std::printf("%s %s %d", i == 0 ? "" : ",", modes[i]["mode"].get<std::string>().c_str(), modes[i]["runs"].get<int>());
  }
  std::printf("%s\n", modes.size() > 6 ? ", ..." : "");
}

void print_oracle(const std::string& name, const json& o) {
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
  print_modes(name, "failure modes of the feasible runs (the guidance's gap)", o["failure_modes_feasible"]);
  if (!o["feasible_but_pullout_bound_exceeded"].empty())
    std::printf("%s: BUG: %zu runs proven feasible exceed a limit at the wings-level pull-out\n", name.c_str(),
                o["feasible_but_pullout_bound_exceeded"].size());
}

void print_report(const json& rep, const std::string& name) {
  std::string sets;
  for (const auto& [set, count] : rep["dispersions"].items()) sets += (sets.empty() ? "" : "+") + set;
  std::printf("%s (%s): %d/%d successful (%.1f %%, 95 %% CI %.1f-%.1f %%), miss p50 %.2f km, p95 %.2f km, max %.2f km\n",
              name.c_str(), sets.c_str(), rep["successes"].get<int>(), rep["runs"].get<int>(),
              100.0 * rep["success_rate"].get<double>(), 100.0 * rep["ci95_low"].get<double>(),
              100.0 * rep["ci95_high"].get<double>(), rep["miss_km_p50"].get<double>(), rep["miss_km_p95"].get<double>(),
              rep["miss_km_max"].get<double>());
  if (rep.contains("miss_along_km") && rep.contains("miss_cross_km")) {
    const json& a = rep["miss_along_km"];
    const json& c = rep["miss_cross_km"];
    std::printf("%s: miss along the arrival line p50 %+.2f km (p5 %+.2f, p95 %+.2f; > 0 long), across it p50 %+.2f km "
                "(p5 %+.2f, p95 %+.2f; > 0 right)\n",
                name.c_str(), a["p50"].get<double>(), a["p5"].get<double>(), a["p95"].get<double>(),
                c["p50"].get<double>(), c["p5"].get<double>(), c["p95"].get<double>());
  }
  print_modes(name, "failure modes (runs)", rep["failure_modes"]);
  if (rep.contains("guidance_knows_vehicle_runs")) {
    std::printf("%s: diagnosis: the guidance knew the drawn C_L, C_D and mass in %d runs\n", name.c_str(),
                rep["guidance_knows_vehicle_runs"].get<int>());
  }
  if (rep.contains("pullout_bound")) {
    const json& b = rep["pullout_bound"];
    std::printf("%s: wings-level pull-out at alpha_max exceeds a path constraint in %d/%d runs: success rate <= %.1f %%\n",
                name.c_str(), b["runs_exceeding"].get<int>(), b["runs"].get<int>(),
                100.0 * b["success_rate_upper_bound"].get<double>());
    print_modes(name, "failure modes of the runs feasible at the pull-out", b["failure_modes_feasible"]);
  }
  if (rep.contains("oracle")) print_oracle(name, rep["oracle"]);
}

// report.json of the campaign's own records (`records`: the file that holds them, for the
// plots); prints the summary. The exit status: 0, 8 (not written) or 11 (runs not flown).
int write_report(const std::vector<json>& runs, const fs::path& out, const Campaign& c) {
  json rep = summarise(runs, c.mission);
  rep["records"] = c.records_name();
  rep["campaign"] = c.to_json();
  if (!write_file(out / "report.json", rep.dump(2) + "\n")) return tx::kExitWriteFailed;
  print_report(rep, c.mission);
  if (!rep.contains("run_errors")) return tx::kExitOk;
  for (const auto& e : rep["run_errors"]) {
    std::fprintf(stderr, "%s: run not flown: seed %lld: %s\n", kTool, e["seed"].get<long long>(),
                 e["error"].get<std::string>().c_str());
  }
  std::fprintf(stderr, "%s: %zu of %d runs could not be flown (counted as failures in the report); exit %d (%s)\n", kTool,
               rep["run_errors"].size(), rep["runs"].get<int>(), tx::kExitRunError, tx::exit_name(tx::kExitRunError));
  return tx::kExitRunError;
}

// ----------------------------------------------------------------------------------------------
// Flying a campaign.

struct Options {
  std::string mission_arg, out, shard, dispersion_set = "reference";
  int runs = 0, jobs = 0;
  std::int64_t seed = 1;
  bool nominal = false, trace = false, pullout_bound = false, knows_vehicle = false, oracle = false, oracle_all = false;
  int oracle_segments = reentry::optimal::EntrySolveOptions{}.segments;
  double oracle_max_s = reentry::optimal::EntrySolveOptions{}.solver.max_wall_s;
  double oracle_alpha_band_deg = 0.0;
  std::vector<std::string> merge;
};

int parse_options(int argc, char** argv, Options& o) {
  CLI::App app{"reentry Monte Carlo campaign (closed loop, in process)", kTool};
  app.add_option("--mission", o.mission_arg, "mission name or TOML file");
  app.add_option("--runs", o.runs, "number of runs of the whole campaign")->check(CLI::Range(1, kRunsMax));
  app.add_option("--seed", o.seed, "seed of run 0 (run r uses seed + r; 0 is a dispersed draw like any other)")
      ->check(tx::non_negative_integer());
  app.add_option("--out", o.out, "output directory")->required()->check([](const std::string& v) {
    return v.empty() ? std::string("an empty --out names no directory") : std::string();
  });
  app.add_option("--jobs", o.jobs, "parallel runs (default: all cores)")->check(CLI::Range(0, 4096));
  app.add_option("--shard", o.shard, "i/K: fly only the runs r with r % K == i")->check([](const std::string& v) {
    int i = 0, k = 0;
    return parse_shard(v, i, k) ? std::string() : "--shard must be i/K with 0 <= i < K, got '" + v + "'";
  });
  app.add_flag("--nominal", o.nominal, "no dispersions (every run nominal)");
  app.add_option("--dispersions", o.dispersion_set,
                 "dispersion set: reference ([dispersions], Gaussian 3 sigma) or stress ([stress_dispersions])")
      ->check(CLI::IsMember({"reference", "stress"}));
  app.add_flag("--trace", o.trace, "record each run (1 Hz, the SIL's channels) in --out/traces/run_<seed>.lcm");
  app.add_flag("--pullout-bound", o.pullout_bound,
               "also fly each run's entry descent wings level at alpha_max (the physics bound of the first pull-out)");
  app.add_flag("--guidance-knows-vehicle", o.knows_vehicle,
               "diagnosis: give the guidance each run's drawn C_L, C_D and mass (what their ignorance costs)");
  app.add_flag("--oracle", o.oracle,
               "also solve each run's maximum-margin problem on its own truth models (feasible runs, margins)");
  app.add_flag("--oracle-all", o.oracle_all,
               "oracle: solve every run, also those a guidance success or the pull-out bound decides (checks both)");
  app.add_option("--oracle-segments", o.oracle_segments, "oracle: Hermite-Simpson segments")->check(CLI::Range(10, 1000));
  app.add_option("--oracle-max-time", o.oracle_max_s, "oracle: wall-clock limit of one solve [s]")->check(CLI::PositiveNumber);
  app.add_option("--oracle-alpha-band", o.oracle_alpha_band_deg,
                 "oracle: keep alpha within this band of the mission's alpha profile [deg] (0: alpha free; "
                 "> 0: feasibility for a guidance that flies its profile)")
      ->check(CLI::Range(0.0, 90.0));
  app.add_option("--merge", o.merge, "combine the run files of these directories into --out (runs.jsonl, report.json)");
  return tx::parse_command_line(app, argc, argv, kTool);
}

// The checks that need more than one option; "" or the reason (usage).
std::string check_options(const Options& o) {
  if (!o.merge.empty()) return {};
  if (o.mission_arg.empty() || o.runs <= 0) return "--mission and --runs N (1 <= N <= 1000000) are required (or --merge)";
  if (o.oracle && (o.trace || o.knows_vehicle))
    return "--oracle flies the guidance as in flight: not with --trace or --guidance-knows-vehicle";
  if (o.seed > std::numeric_limits<std::int64_t>::max() - o.runs) return "--seed " + std::to_string(o.seed) + " + --runs overflows";
  int i = 0, k = 1;
  if (!o.shard.empty() && parse_shard(o.shard, i, k) && k > o.runs)
    return "--shard " + o.shard + ": more shards than the " + std::to_string(o.runs) + " runs (empty shards)";
  return {};
}

Campaign campaign_of(const Options& o, const reentry::config::Mission& m) {
  Campaign c;
  c.mission = m.name;
  c.mission_digest = m.digest;
  c.dispersions = o.nominal ? "nominal" : o.dispersion_set;
  c.runs = o.runs;
  c.seed = o.seed;
  if (!o.shard.empty()) parse_shard(o.shard, c.shard_i, c.shard_k);
  c.flags = {{"nominal", o.nominal}, {"pullout_bound", o.pullout_bound || o.oracle},
             {"guidance_knows_vehicle", o.knows_vehicle}, {"oracle", o.oracle}};
  if (o.oracle) {
    c.flags["oracle_all"] = o.oracle_all;
    c.flags["oracle_segments"] = o.oracle_segments;
    c.flags["oracle_max_time_s"] = o.oracle_max_s;
    c.flags["oracle_alpha_band_deg"] = o.oracle_alpha_band_deg;
  }
  return c;
}

/// Flies one run of the campaign into its record.
class RunFlier {
 public:
  RunFlier(const Options& o, const reentry::config::Mission& m) : o_(o), m_(m) {}
  json operator()(int r) const {
    const std::uint64_t seed = static_cast<std::uint64_t>(o_.seed) + static_cast<std::uint64_t>(r);
    const std::string set_name = o_.nominal ? "nominal" : o_.dispersion_set;
    const std::string trace_log =
        o_.trace ? (fs::path(o_.out) / "traces" / ("run_" + std::to_string(seed) + ".lcm")).string() : std::string();
    json rec;
    if (o_.oracle) {
      reentry::optimal::OracleOptions oo;
      oo.solve.segments = o_.oracle_segments;
      oo.solve.solver.max_wall_s = o_.oracle_max_s;
      oo.solve.alpha_band_rad = o_.oracle_alpha_band_deg / kDeg;
      oo.solve_decided = o_.oracle_all;
      const reentry::optimal::OracleResult o = reentry::optimal::run_oracle(m_, seed, !o_.nominal, oo);
      rec = run_record(r, o.flown);
      rec["oracle"] = reentry::optimal::oracle_record(o);
      rec["oracle"]["alpha_band_deg"] = o_.oracle_alpha_band_deg;
      rec["feasible"] = o.feasible;
      rec["pullout_bound"] = pullout_record(o.pullout);
    } else {
      const ClosedLoopResult res = reentry::tools::run_closed_loop(m_, seed, !o_.nominal, trace_log, o_.knows_vehicle);
      rec = run_record(r, res);
      if (!res.trace_error.empty()) rec["trace_error"] = res.trace_error;  // the flight itself is whole
    }
    rec["mission"] = m_.name;
    rec["dispersions"] = set_name;
    if (o_.knows_vehicle) rec["guidance_knows_vehicle"] = true;
    if (o_.pullout_bound && !o_.oracle)
      rec["pullout_bound"] = pullout_record(reentry::tools::wings_level_pullout_bound(m_, seed, !o_.nominal));
    return rec;
  }

 private:
  const Options& o_;
  const reentry::config::Mission& m_;
};

// Threads: each takes the next run; the calling thread reports progress. False when interrupted.
bool fly_threads(const RunFlier& fly, const std::vector<int>& mine, int workers, std::vector<json>& records) {
  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < mine.size() && tx::g_stop_signal == 0; i = next++) {
      records[i] = fly(mine[i]);
      ++done;
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < workers; ++j) pool.emplace_back(worker);
  Progress progress(static_cast<int>(mine.size()));
  while (done.load() < static_cast<int>(mine.size()) && tx::g_stop_signal == 0) {
    progress.update(done.load());
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (auto& t : pool) t.join();
  progress.update(done.load());
  return tx::g_stop_signal == 0;
}

// Lines written so far into the oracle processes' part files (their progress).
int part_lines(const fs::path& out, int workers) {
  int n = 0;
  for (int k = 0; k < workers; ++k) {
    std::ifstream in(out / (".oracle_part_" + std::to_string(k) + ".jsonl"));
    n += static_cast<int>(std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n'));
  }
  return n;
}

// IPOPT's linear solver (MUMPS 5.5, sequential build) is not thread-safe: two solves in one
// process crash in DMUMPS_LOAD_INIT. Oracle campaigns run their jobs as processes (forked before
// any thread exists), each on every workers-th run, writing its records to a part file that this
// process collects. The exit status (0, 8 a part not written, 11 a worker failed, 128 + signal).
int fly_processes(const RunFlier& fly, const std::vector<int>& mine, int workers, const fs::path& out,
                  std::vector<json>& records) {
  std::vector<pid_t> children;
  for (int k = 0; k < workers; ++k) {
    const pid_t pid = fork();
    if (pid < 0) {
      std::fprintf(stderr, "%s: fork failed: %s\n", kTool, std::strerror(errno));
      for (pid_t c : children) kill(c, SIGTERM);
      return tx::kExitRunError;
    }
    if (pid == 0) {
      std::ofstream part(out / (".oracle_part_" + std::to_string(k) + ".jsonl"));
      for (std::size_t i = static_cast<std::size_t>(k); i < mine.size() && tx::g_stop_signal == 0;
           i += static_cast<std::size_t>(workers)) {
        part << json{{"index", i}, {"record", fly(mine[i])}}.dump() << "\n" << std::flush;
      }
      part.close();
      std::_Exit(!part ? tx::kExitWriteFailed : tx::g_stop_signal != 0 ? tx::kExitSignalBase + tx::g_stop_signal : 0);
    }
    children.push_back(pid);
  }
  Progress progress(static_cast<int>(mine.size()));
  int rc = tx::kExitOk;
  for (std::size_t waited = 0; waited < children.size();) {
    progress.update(part_lines(out, workers));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    for (pid_t& pid : children) {
      int status = 0;
      if (pid <= 0 || waitpid(pid, &status, WNOHANG) != pid) continue;
      pid = -1;
      ++waited;
      const int code = WIFEXITED(status) ? WEXITSTATUS(status) : tx::kExitRunError;
      if (code != 0 && rc == tx::kExitOk) rc = code;
    }
  }
  progress.update(part_lines(out, workers));
  for (int k = 0; k < workers; ++k) {
    const fs::path part = out / (".oracle_part_" + std::to_string(k) + ".jsonl");
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
  if (rc == tx::kExitOk && tx::g_stop_signal != 0) rc = tx::kExitSignalBase + tx::g_stop_signal;
  if (rc == tx::kExitOk && std::any_of(records.begin(), records.end(), [](const json& r) { return r.is_null(); })) rc = tx::kExitRunError;
  if (rc != tx::kExitOk) std::fprintf(stderr, "%s: an oracle worker process failed (records missing); exit %d (%s)\n", kTool, rc, tx::exit_name(rc));
  return rc;
}

// A --trace campaign starts from an empty traces/ folder (no trace of another campaign stays).
bool prepare_traces(const fs::path& out) {
  std::error_code ec;
  const fs::path traces = out / "traces";
  for (const auto& entry : fs::directory_iterator(traces, ec)) {
    const std::string name = entry.path().filename().string();
    const bool trace = entry.path().extension() == ".lcm" || entry.path().extension() == ".csv";
    if (name.rfind("run_", 0) == 0 && trace) fs::remove(entry.path(), ec);
  }
  fs::create_directories(traces, ec);
  if (!ec && fs::is_directory(traces, ec)) return true;
  std::fprintf(stderr, "%s: write failed: %s: %s\n", kTool, traces.string().c_str(), ec.message().c_str());
  return false;
}

int run_campaign(const Options& o) {
  auto loaded = reentry::config::load_mission(o.mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "%s: mission refused: %s\n", kTool, loaded.error.c_str());
    return tx::kExitUsage;
  }
  if (o.dispersion_set == "stress") {
    if (!loaded.mission.has_stress_dispersions) {
      std::fprintf(stderr, "%s: --dispersions stress: %s has no [stress_dispersions] section\n", kTool,
                   loaded.mission.source_file.c_str());
      return tx::kExitUsage;
    }
    loaded.mission.dispersions = loaded.mission.stress_dispersions;  // every draw below uses this set
  }
  const fs::path out(o.out);
  if (!prepare_output(out) || (o.trace && !prepare_traces(out))) return tx::kExitWriteFailed;
  const Campaign c = campaign_of(o, loaded.mission);
  std::vector<int> mine;
  for (int r = 0; r < o.runs; ++r)
    if (r % c.shard_k == c.shard_i) mine.push_back(r);
  const int jobs = o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int workers = std::min<int>(jobs, static_cast<int>(mine.size()));
  std::vector<json> records(mine.size());
  const RunFlier fly(o, loaded.mission);
  const auto t0 = std::chrono::steady_clock::now();
  if (o.oracle && workers > 1) {
    const int rc = fly_processes(fly, mine, workers, out, records);
    if (rc != tx::kExitOk) return rc;
  } else if (!fly_threads(fly, mine, workers, records)) {
    std::fprintf(stderr, "%s: interrupted by signal %d: no records written\n", kTool, static_cast<int>(tx::g_stop_signal));
    return tx::kExitSignalBase + tx::g_stop_signal;
  }
  if (!write_records(out, c, records)) return tx::kExitWriteFailed;
  int traces_lost = 0;
  for (const auto& rec : records) {
    if (!rec.contains("trace_error")) continue;
    if (traces_lost++ == 0) std::fprintf(stderr, "%s: %s\n", kTool, rec["trace_error"].get<std::string>().c_str());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s: campaign wall time %.0f s (%zu runs, %d jobs)\n", c.mission.c_str(), wall, mine.size(), jobs);
  const int rc = write_report(records, out, c);
  if (traces_lost == 0) return rc;
  std::fprintf(stderr, "%s: write failed: %d run trace(s) not written whole in %s; exit %d (%s)\n", kTool, traces_lost,
               (out / "traces").string().c_str(), tx::kExitWriteFailed, tx::exit_name(tx::kExitWriteFailed));
  return tx::kExitWriteFailed;
}

int run_merge(const Options& o) {
  // The merged records go to --out/runs.jsonl: a directory merged into itself would hold its
  // runs twice.
  std::error_code ec;
  for (const auto& d : o.merge) {
    if (fs::exists(o.out) && fs::equivalent(fs::path(d), fs::path(o.out), ec)) {
      std::fprintf(stderr, "%s: --out %s is one of the merged directories\n", kTool, o.out.c_str());
      return tx::kExitUsage;
    }
  }
  std::vector<RecordsFile> files;
  Campaign merged;
  std::string err = read_dirs(o.merge, files);
  if (err.empty()) err = check_campaign(files, merged);
  if (!err.empty()) {
    std::fprintf(stderr, "%s: merge refused: %s\n", kTool, err.c_str());
    return tx::kExitUsage;
  }
  std::vector<json> runs;
  for (auto& f : files)
    for (auto& r : f.runs) runs.push_back(std::move(r));
  std::sort(runs.begin(), runs.end(), [](const json& a, const json& b) { return a["run"] < b["run"]; });
  // A merge leaves a complete campaign directory: the combined records (in run order) next to
  // the report, so that the plots and a later merge read it like a whole campaign.
  const fs::path out(o.out);
  if (!prepare_output(out) || !write_records(out, merged, runs)) return tx::kExitWriteFailed;
  return write_report(runs, out, merged);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const int parsed = parse_options(argc, argv, o);
  if (parsed >= 0) return parsed;
  const std::string err = check_options(o);
  if (!err.empty()) {
    std::fprintf(stderr, "%s: bad argument: %s\n", kTool, err.c_str());
    return tx::kExitUsage;
  }
  tx::install_stop_handlers();
  return o.merge.empty() ? run_campaign(o) : run_merge(o);
}
