// One guidance cycle: tracker + alpha/sigma rate filters (TrackerLaw::step) on a real X-33
// plan, at states swept along the profile; and one executive cycle in synchronous mode
// between plan requests. Target (DESIGN §8): <= 10 us per tracker + filter cycle.
#include <benchmark/benchmark.h>

#include <memory>

#include "guidance/guidance_stack.hpp"
#include "reentry/config/mission.hpp"

namespace {

using namespace reentry::fsw;

struct CycleFixture {
  GuidanceStack stack;
  std::unique_ptr<ReferenceProfile> profile = std::make_unique<ReferenceProfile>();
  bool ok = false;
  CycleFixture() {
    const auto loaded = reentry::config::load_mission("x33");
    if (!loaded.ok || !stack.create(loaded.mission, exec::PlanMode::kSynchronous).empty()) return;
    auto& planner = stack.planner->planner;
    ok = planner.plan(planner.entry_state(), *profile) == Status::kOk;
    if (ok) stack.law->set_profile(*profile);
  }
  RelativeState state(int i) const {
    const ReferenceProfile& p = *profile;
    const int k = 1 + (i % (p.n_points - 2));
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

void BM_TrackerFilterCycle(benchmark::State& st) {
  static CycleFixture f;
  if (!f.ok) {
    st.SkipWithError("X-33 plan failed");
    return;
  }
  exec::LawOutput out;
  int i = 0;
  for (auto _ : st) {
    const RelativeState s = f.state(i++);
    benchmark::DoNotOptimize(f.stack.law->step(s, 0.1, true, out));
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_TrackerFilterCycle)->Unit(benchmark::kMicrosecond);

}  // namespace
