// Timings of the trajectory optimizer (tools/optimizer), not pass/fail tests:
// - BM_MaxMarginSolve/<mission>: one maximum-margin solve of the mission's nominal run from the
//   guidance's flight (the first mesh, its model correction and refinement: everything
//   solve_entry does; the guidance's flight and the open-loop replay excluded), 5 repetitions,
//   median and max reported;
// - BM_BettsShuttle/{unconstrained,heating_limit}: Betts's Space Shuttle maximum-crossrange
//   benchmark (100 segments, as tests/optimal/test_betts_shuttle.cpp), 5 repetitions;
// - BM_Point{Double,Ad1,Ad2}: one evaluation of the entry problem's point functions.
// Run: build/tools/bench_optimal/bench_optimal (quote the machine's load with the figures).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "ad.hpp"
#include "betts_shuttle.hpp"
#include "run_oracle.hpp"

namespace {

using namespace reentry;
using namespace reentry::optimal;

double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

// The nominal run of a mission: its simulator and the guidance's flight as the start.
struct NominalCase {
  config::Mission mission;
  std::unique_ptr<truth::Simulator> sim;
  Trajectory start;
  explicit NominalCase(const std::string& name) {
    mission = config::load_mission(name).mission;
    sim = make_run_simulator(mission, 0, false, nullptr);
    const GuidanceFlight flown = fly_guidance(mission, 0, false);
    start = guess_from_flown(flown.samples, Mesh::uniform(EntrySolveOptions{}.segments));
  }
};

const NominalCase& nominal(const std::string& name) {
  static std::map<std::string, std::unique_ptr<NominalCase>> cases;
  auto& c = cases[name];
  if (!c) c = std::make_unique<NominalCase>(name);
  return *c;
}

void BM_MaxMarginSolve(benchmark::State& state, const char* mission) {
  const NominalCase& c = nominal(mission);
  EntryResult r;
  for (auto _ : state) r = solve_entry(*c.sim, EntryMode::kMaxMargin, c.start, EntrySolveOptions{});
  if (r.solution.status != SolveStatus::kOptimal) state.SkipWithError("not optimal");
  state.counters["segments"] = r.segments();
  state.counters["solves"] = static_cast<double>(r.passes.size());
  int iterations = 0;
  for (const MeshPass& p : r.passes) iterations += p.iterations;
  state.counters["iterations"] = iterations;
  state.counters["margin"] = r.figures.margin;
}

void BM_BettsShuttle(benchmark::State& state, double heating_limit) {
  BettsShuttle pb;
  pb.heating_limit_BTU = heating_limit;
  SolverOptions o;
  o.bound_push = 1e-2;
  o.mu_init = 0.1;
  const Mesh mesh = Mesh::uniform(100);
  Solution s;
  for (auto _ : state) s = solve(pb, mesh, pb.linear_guess(mesh), o);
  if (s.status != SolveStatus::kOptimal) state.SkipWithError("not optimal");
  const Trajectory& tr = s.trajectory;
  state.counters["theta_f_deg"] = tr.x[static_cast<size_t>((tr.points() - 1) * BettsShuttle::kStates + 2)] / BettsShuttle::kDeg;
  state.counters["iterations"] = s.iterations;
}

// One solve per repetition, five repetitions: median and max (wall time, and CPU time).
#define REPEATED \
  ->Iterations(1)->Repetitions(5)->ReportAggregatesOnly(true)->UseRealTime()->ComputeStatistics("max", max_of)->Unit(benchmark::kMillisecond)
BENCHMARK_CAPTURE(BM_MaxMarginSolve, horus, "horus") REPEATED;
BENCHMARK_CAPTURE(BM_MaxMarginSolve, x33, "x33") REPEATED;
BENCHMARK_CAPTURE(BM_MaxMarginSolve, orbiter, "orbiter") REPEATED;
BENCHMARK_CAPTURE(BM_MaxMarginSolve, x38, "x38") REPEATED;
BENCHMARK_CAPTURE(BM_BettsShuttle, unconstrained, std::numeric_limits<double>::infinity()) REPEATED;
BENCHMARK_CAPTURE(BM_BettsShuttle, heating_limit, 70.0) REPEATED;

// A mid-flight point of the nominal run of `mission` (400 s at the profile's entry alpha, 57 deg bank).
struct PointCase {
  config::Mission mission;
  std::unique_ptr<truth::Simulator> sim;
  std::unique_ptr<EntryProblem> problem;
  double w[9] = {};
  explicit PointCase(const std::string& name) {
    mission = config::load_mission(name).mission;
    auto flown = make_run_simulator(mission, 0, false, nullptr);
    flown->set_command(mission.alpha_profile.y.back(), 1.0);
    flown->advance_to(400.0);
    sim = make_run_simulator(mission, 0, false, nullptr);
    problem = std::make_unique<EntryProblem>(*sim, EntryMode::kMaxMargin, 1500.0);
    w[0] = flown->time_s();
    for (int i = 0; i < 6; ++i) w[1 + i] = flown->state()[static_cast<size_t>(i)];
    w[7] = mission.alpha_profile.y.back();
    w[8] = 1.0;
  }
};

template <class T>
void BM_PointEvaluation(benchmark::State& state, const char* mission) {
  static std::map<std::string, std::unique_ptr<PointCase>> cases;
  auto& c = cases[mission];
  if (!c) c = std::make_unique<PointCase>(mission);
  constexpr int kZ = 8;
  std::vector<T> g(static_cast<size_t>(c->problem->n_path()));
  for (auto _ : state) {
    T z[kZ];
    if constexpr (std::is_same_v<T, double>) {
      for (int i = 0; i < kZ; ++i) z[i] = c->w[1 + i];
    } else {
      seed<kZ>(c->w + 1, z);
    }
    T f[6];
    c->problem->point(T(c->w[0]), z, z + 6, f, g.data());
    benchmark::DoNotOptimize(f[3]);
  }
}
void BM_PointDouble(benchmark::State& s, const char* m) { BM_PointEvaluation<double>(s, m); }
void BM_PointAd1(benchmark::State& s, const char* m) { BM_PointEvaluation<Ad1<8>>(s, m); }
void BM_PointAd2(benchmark::State& s, const char* m) { BM_PointEvaluation<Ad2<8>>(s, m); }
BENCHMARK_CAPTURE(BM_PointDouble, horus, "horus");
BENCHMARK_CAPTURE(BM_PointAd1, horus, "horus");
BENCHMARK_CAPTURE(BM_PointAd2, horus, "horus");

}  // namespace
