// Timings of the trajectory optimizer (tools/optimizer): the point functions of the entry
// problem in double, first- and second-order AD.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "ad.hpp"
#include "run_oracle.hpp"

namespace {

using namespace reentry;
using namespace reentry::optimal;

// A mid-flight point of the nominal run of `mission` (400 s at the profile's entry alpha, 60 deg bank).
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
  static PointCase c(mission);
  constexpr int kZ = 8;
  std::vector<T> g(static_cast<size_t>(c.problem->n_path()));
  for (auto _ : state) {
    T z[kZ];
    if constexpr (std::is_same_v<T, double>) {
      for (int i = 0; i < kZ; ++i) z[i] = c.w[1 + i];
    } else {
      seed<kZ>(c.w + 1, z);
    }
    T f[6];
    c.problem->point(T(c.w[0]), z, z + 6, f, g.data());
    benchmark::DoNotOptimize(f[3]);
  }
}
void BM_PointDouble(benchmark::State& s, const char* m) { BM_PointEvaluation<double>(s, m); }
void BM_PointAd1(benchmark::State& s, const char* m) { BM_PointEvaluation<Ad1<8>>(s, m); }
void BM_PointAd2(benchmark::State& s, const char* m) { BM_PointEvaluation<Ad2<8>>(s, m); }
BENCHMARK_CAPTURE(BM_PointDouble, horus, "horus");
BENCHMARK_CAPTURE(BM_PointAd1, horus, "horus");
BENCHMARK_CAPTURE(BM_PointAd2, horus, "horus");
BENCHMARK_CAPTURE(BM_PointAd2, x33, "x33");

}  // namespace
