// Planner benchmarks (DESIGN §8: full plan from the entry interface <= 20 ms median,
// <= 50 ms worst case; with trim <= 200 ms). Each case also runs as Iterations(1) x
// Repetitions(30) with a max statistic, so the worst single plan is reported. HORUS plans with
// its trimmed on-board tables (solved once at start-up: BM_OnboardTrimSolve_Horus) and, for
// comparison, with the basic ones.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <reentry/config/mission.hpp>

#include "guidance/mission_adapter.hpp"
#include "planner/entry_planner.hpp"

namespace {

using reentry::fsw::EntryPlanner;
using reentry::fsw::ReferenceProfile;
using reentry::fsw::RelativeState;
using reentry::fsw::Status;

// The mission file's mission; a failed load leaves an empty mission that init_from_mission
// rejects, and the case is skipped with an error.
reentry::config::Mission mission(const std::string& name, const char* profile, const char* initial_drag,
                                 bool onboard_trim = true) {
  reentry::config::Mission m = reentry::config::load_mission(name).mission;
  m.guidance.drag_profile = profile;
  m.guidance.initial_drag = initial_drag;
  m.guidance.onboard_trim = onboard_trim;
  return m;
}

double worst(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

// Planner and profile live on the heap of the benchmark harness (set up once, outside timing).
struct Fixture {
  std::unique_ptr<EntryPlanner> planner = std::make_unique<EntryPlanner>();
  std::unique_ptr<ReferenceProfile> profile = std::make_unique<ReferenceProfile>();
  RelativeState from{};
};

bool setup(Fixture& f, const std::string& name, const char* profile, const char* initial_drag, bool mid_flight,
           bool onboard_trim = true) {
  if (init_from_mission(*f.planner, mission(name, profile, initial_drag, onboard_trim)) != Status::kOk) return false;
  f.from = f.planner->entry_state();
  if (!mid_flight) return true;
  // A state at about half the entry energy on the entry plan.
  if (f.planner->plan(f.from, *f.profile) != Status::kOk) return false;
  const ReferenceProfile& p = *f.profile;
  int k = 0;
  while (k + 1 < p.n_points && p.e_norm[k] > 0.5) ++k;
  RelativeState s = f.from;
  s.radius_m = p.radius_m[k];
  s.altitude_m = s.radius_m - reentry::fsw::kEarthRadius_m;
  s.velocity_mps = p.velocity_mps[k];
  s.flight_path_rad = p.gamma_rad[k];
  s.heading_rad = p.heading_rad[k];
  s.energy_Jpkg = p.energy_Jpkg[k];
  s.drag_mps2 = p.drag_mps2[k];
  // Position: the plan's ground track up to point k ((2.42)-(2.43), exact range of each
  // linear-drag cell, heading linear in range within a cell).
  double lat = s.latitude_rad, lon = s.longitude_rad;
  for (int i = 0; i < k; ++i) {
    const double da = p.drag_mps2[i], db = p.drag_mps2[i + 1], de = p.energy_Jpkg[i] - p.energy_Jpkg[i + 1];
    const double len = std::abs(db - da) < 1e-12 * da ? de / da : de * std::log(db / da) / (db - da);
    const double ca = p.heading_rad[i], cb = p.heading_rad[i + 1];
    const bool flat = std::abs(cb - ca) < 1e-9;
    const double ic = flat ? len * std::cos(ca) : len * (std::sin(cb) - std::sin(ca)) / (cb - ca);
    const double is = flat ? len * std::sin(ca) : len * (std::cos(ca) - std::cos(cb)) / (cb - ca);
    const double r = 0.5 * (p.radius_m[i] + p.radius_m[i + 1]);
    const double cg = std::cos(0.5 * (p.gamma_rad[i] + p.gamma_rad[i + 1]));
    const double dlat = cg / r * ic;
    lon += cg / (r * std::cos(lat + 0.5 * dlat)) * is;
    lat += dlat;
  }
  s.latitude_rad = lat;
  s.longitude_rad = lon;
  f.from = s;
  return true;
}

void run(benchmark::State& state, const std::string& name, const char* profile, const char* initial_drag, bool mid,
         double lift_over_drag_scale = 1.0, bool onboard_trim = true) {
  Fixture f;
  if (!setup(f, name, profile, initial_drag, mid, onboard_trim)) {
    state.SkipWithError("planner setup failed");
    return;
  }
  f.from.lift_over_drag_scale = lift_over_drag_scale;
  int iterations = 0;
  Status last = Status::kOk;
  for (auto _ : state) {
    last = f.planner->plan(f.from, *f.profile);
    benchmark::DoNotOptimize(f.profile->drag_mps2[0]);
    iterations = f.planner->diagnostics().iterations;
  }
  state.counters["length_iterations"] = iterations;
  state.counters["converged"] = f.planner->diagnostics().converged ? 1 : 0;
  state.counters["status"] = static_cast<int>(last);
  state.counters["ranging_blend"] = f.profile->ranging_blend;
  state.counters["trimmed_aero"] = f.planner->models().aero_trimmed() ? 1 : 0;
}

// Start-up trim solve of the HORUS tables (51 alpha x 8 Mach nodes, body flap then elevons)
// from the loader's model: conversion into the fixed-capacity trim data and the solve.
void BM_OnboardTrimSolve_Horus(benchmark::State& state) {
  const reentry::config::Mission m = mission("horus", "smooth", "actual");
  if (m.vehicle.aero.cm.empty()) {
    state.SkipWithError("no HORUS moment data (mission file not loaded)");
    return;
  }
  auto aero = std::make_unique<reentry::fsw::OnboardAero>();
  auto data = std::make_unique<reentry::fsw::TrimAeroData>();
  for (auto _ : state) {
    Status s = reentry::fsw::trim_data_from_aero(m.vehicle.aero, *data);
    if (s == Status::kOk) s = aero->init_trimmed(*data);
    benchmark::DoNotOptimize(s);
  }
}

void BM_PlanFromEntry_X33(benchmark::State& s) { run(s, "x33", "three_segment", "actual", false); }
void BM_PlanFromEntry_X33_Smooth(benchmark::State& s) { run(s, "x33", "smooth", "actual", false); }
void BM_PlanFromEntry_Horus(benchmark::State& s) { run(s, "horus", "smooth", "actual", false); }  // mission defaults: trimmed
void BM_PlanFromEntry_Horus_Untrimmed(benchmark::State& s) { run(s, "horus", "smooth", "actual", false, 1.0, false); }
void BM_PlanUpdate_MidFlight_X33(benchmark::State& s) { run(s, "x33", "smooth", "actual", true); }
// Worst case: a first ranging plan (65 % of the table L/D: the alpha blend is searched by
// bisection, up to 7 extra length iterations); the repetitions start from a fresh planner.
void BM_PlanRanging_X33(benchmark::State& s) { run(s, "x33", "smooth", "actual", false, 0.65); }


}  // namespace

#define REENTRY_PLANNER_BENCH(fn)                                                        \
  BENCHMARK(fn)->Unit(benchmark::kMillisecond);                                          \
  BENCHMARK(fn)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(30)->         \
      ComputeStatistics("max", worst)->ReportAggregatesOnly(true)

REENTRY_PLANNER_BENCH(BM_PlanFromEntry_X33);
REENTRY_PLANNER_BENCH(BM_PlanFromEntry_X33_Smooth);
REENTRY_PLANNER_BENCH(BM_PlanFromEntry_Horus);
REENTRY_PLANNER_BENCH(BM_PlanFromEntry_Horus_Untrimmed);
BENCHMARK(BM_OnboardTrimSolve_Horus)->Unit(benchmark::kMillisecond);
REENTRY_PLANNER_BENCH(BM_PlanUpdate_MidFlight_X33);
REENTRY_PLANNER_BENCH(BM_PlanRanging_X33);

