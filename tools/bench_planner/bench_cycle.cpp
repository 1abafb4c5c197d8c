// One guidance cycle: tracker + alpha/sigma rate filters (TrackerLaw::step) on a real X-33
// plan, at the profile's states in flight order. Target (DESIGN §8): <= 10 us per tracker +
// filter cycle.
//
// The tracker's phases are one way (after capture the energy only falls), so every pass over
// the profile flies from a fresh law, restored outside the timed region. A sweep that wrapped
// around with the same law would fly the entry states in the terminal phase, with the range
// control and its range-extension quadrature (20 modulated-alpha bisections on the aero
// table), which no flight does. Two mixes are timed: the whole flight (the mean cycle) and the
// terminal phase alone (the costliest phase), its passes starting from the law as the flight
// left it at the terminal-phase energy.
#include <benchmark/benchmark.h>

#include <memory>

#include "guidance/guidance_stack.hpp"
#include "reentry/config/mission.hpp"

namespace {

using namespace reentry::fsw;

struct CycleFixture {
  GuidanceStack stack;
  std::unique_ptr<ReferenceProfile> profile = std::make_unique<ReferenceProfile>();
  std::unique_ptr<TrackerLaw> fresh = std::make_unique<TrackerLaw>();  // plan adopted, no cycle flown
  std::unique_ptr<TrackerLaw> at_terminal = std::make_unique<TrackerLaw>();  // flown to the terminal phase
  int terminal_first_k = 1;  // first profile point below the terminal-phase energy
  bool ok = false;
  CycleFixture() {
    const auto loaded = reentry::config::load_mission("x33");
    if (!loaded.ok || !stack.create(loaded.mission, exec::PlanMode::kSynchronous).empty()) return;
    auto& planner = stack.planner->planner;
    ok = planner.plan(planner.entry_state(), *profile) == Status::kOk;
    if (!ok) return;
    stack.law->set_profile(*profile);
    *fresh = *stack.law;
    const double e_terminal = stack.law->tracker.terminal_energy_Jpkg();
    while (terminal_first_k < profile->n_points - 2 && profile->energy_Jpkg[terminal_first_k] >= e_terminal) {
      ++terminal_first_k;
    }
    *at_terminal = *fresh;
    exec::LawOutput out;
    for (int k = 1; k < terminal_first_k; ++k) ok = ok && at_terminal->step(state(k, k - 1), 0.1, true, out) == Status::kOk;
  }
  /// Profile point k, 5 % above the planned drag, at cycle i.
  RelativeState state(int k, int i) const {
    const ReferenceProfile& p = *profile;
    RelativeState s;
    s.t_s = 0.1 * i;
    s.radius_m = p.radius_m[k];
    s.altitude_m = p.radius_m[k] - kEarthRadius_m;
    s.latitude_rad = 0.3;
    s.longitude_rad = -1.5;
    s.velocity_mps = p.velocity_mps[k];
    s.flight_path_rad = p.gamma_rad[k];
    s.heading_rad = p.heading_rad[k];
    s.energy_Jpkg = p.energy_Jpkg[k];
    s.drag_mps2 = 1.05 * p.drag_mps2[k];
    s.lift_mps2 = s.drag_mps2 * p.lift_over_drag[k];
    return s;
  }
};

CycleFixture& fixture() {
  static CycleFixture f;
  return f;
}

/// Passes over profile points k_first .. n_points - 2, each from the law `start`.
void fly_passes(benchmark::State& st, const TrackerLaw& start, int k_first) {
  CycleFixture& f = fixture();
  if (!f.ok) {
    st.SkipWithError("X-33 plan failed");
    return;
  }
  const int k_end = f.profile->n_points - 1;
  exec::LawOutput out;
  int k = k_first, i = k_first - 1;
  *f.stack.law = start;
  for (auto _ : st) {
    if (k == k_end) {
      st.PauseTiming();
      *f.stack.law = start;
      st.ResumeTiming();
      k = k_first;
      i = k_first - 1;  // every pass flies the same times as the first
    }
    const RelativeState s = f.state(k++, i++);
    benchmark::DoNotOptimize(f.stack.law->step(s, 0.1, true, out));
    benchmark::DoNotOptimize(out);
  }
}

void BM_TrackerFilterCycle(benchmark::State& st) { fly_passes(st, *fixture().fresh, 1); }
BENCHMARK(BM_TrackerFilterCycle)->Unit(benchmark::kMicrosecond);

void BM_TrackerFilterCycleTerminal(benchmark::State& st) {
  fly_passes(st, *fixture().at_terminal, fixture().terminal_first_k);
}
BENCHMARK(BM_TrackerFilterCycleTerminal)->Unit(benchmark::kMicrosecond);

}  // namespace
