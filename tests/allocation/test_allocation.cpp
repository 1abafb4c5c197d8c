// Zero heap allocation after start-up (DESIGN §8): counted with the C allocator interposed,
// during 10,000 tracker + filter cycles, complete plans for two missions, and executive
// cycles that request, compute and adopt plans; the same for the predictor-corrector law (its
// plans for the four missions, its cycles, executive cycles adopting its plans). Start-up
// (loading, create(), init) may allocate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <cstdlib>
#include <memory>
#include <vector>

#include "app/guidance_node.hpp"
#include "guidance/mission_adapter.hpp"
#include "guidance/guidance_stack.hpp"
#include "malloc_counter.hpp"
#include "planner/entry_planner.hpp"
#include "predictor_corrector/pc_planner.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::fsw {
namespace {

using test::MallocCounter;

#define SKIP_WITHOUT_COUNTER()                                                              \
  if (!test::malloc_counting_available()) GTEST_SKIP() << "allocator interposition is off under sanitizers"

config::Mission load(const char* name) {
  const auto r = config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

// A state on the profile (index k), with a drag offset so the tracker has work to do.
// A state on the planned profile at grid point k, placed at (lat, lon): the entry point by
// default, so that the first plan of a run, requested at the entry energy, is feasible.
RelativeState state_on(const ReferenceProfile& p, int k, double t_s, double drag_factor, double lat_rad = 0.3,
                       double lon_rad = -1.5) {
  RelativeState s;
  s.t_s = t_s;
  s.radius_m = p.radius_m[k];
  s.altitude_m = p.radius_m[k] - kEarthRadius_m;
  s.latitude_rad = lat_rad;
  s.longitude_rad = lon_rad;
  s.velocity_mps = p.velocity_mps[k];
  s.flight_path_rad = p.gamma_rad[k];
  s.heading_rad = p.heading_rad[k];
  s.energy_Jpkg = p.energy_Jpkg[k];
  s.drag_mps2 = drag_factor * p.drag_mps2[k];
  s.lift_mps2 = s.drag_mps2 * p.lift_over_drag[k];
  return s;
}

TEST(Allocation, CounterSeesNewVectorAndMalloc) {
  SKIP_WITHOUT_COUNTER();
  // The pointers escape through volatile sinks so the compiler cannot elide the allocations.
  static int* volatile int_sink = nullptr;
  static void* volatile raw_sink = nullptr;
  static double* volatile vec_sink = nullptr;
  std::int64_t after_new, after_vector, after_malloc;
  std::vector<double> v;
  {
    MallocCounter counter;
    int_sink = new int(3);
    after_new = counter.count();
    v.push_back(1.0);
    vec_sink = v.data();
    after_vector = counter.count();
    raw_sink = std::malloc(16);
    after_malloc = counter.count();
  }
  EXPECT_EQ(after_new, 1);
  EXPECT_EQ(after_vector, 2);
  EXPECT_EQ(after_malloc, 3);
  std::free(raw_sink);
  delete int_sink;
  (void)vec_sink;
}

TEST(Allocation, CompletePlansForTwoMissionsAllocateNothing) {
  SKIP_WITHOUT_COUNTER();
  for (const char* name : {"x33", "horus"}) {
    const config::Mission m = load(name);
    auto planner = std::make_unique<EntryPlanner>();
    auto profile = std::make_unique<ReferenceProfile>();
    ASSERT_EQ(init_from_mission(*planner, m), Status::kOk) << name;
    const RelativeState entry = planner->entry_state();
    Status st;
    std::int64_t allocations;
    {
      MallocCounter counter;
      st = planner->plan(entry, *profile);
      allocations = counter.count();
    }
    EXPECT_EQ(allocations, 0) << name << " plan status " << to_string(st);
    EXPECT_GT(planner->diagnostics().reversal_evaluations, 0) << name << ": the plan must have run its search";
  }
}

TEST(Allocation, TenThousandTrackerAndFilterCyclesAllocateNothing) {
  SKIP_WITHOUT_COUNTER();
  const config::Mission m = load("x33");
  GuidanceStack stack;
  ASSERT_EQ(stack.create(m, exec::PlanMode::kSynchronous), "");
  auto profile = std::make_unique<ReferenceProfile>();
  ASSERT_EQ(stack.planner->planner.plan(stack.planner->planner.entry_state(), *profile), Status::kOk);
  stack.law->set_profile(*profile);
  const int n = profile->n_points;
  exec::LawOutput out;
  int finite = 0;
  std::int64_t allocations;
  {
    MallocCounter counter;
    for (int i = 0; i < 10000; ++i) {
      const int k = 1 + (i * (n - 2)) / 10000;  // sweep the whole profile, entry to TAEM
      const double drag_factor = 1.0 + 0.1 * std::sin(0.01 * i);
      if (stack.law->step(state_on(*profile, k, 0.1 * i, drag_factor), 0.1, true, out) == Status::kOk &&
          std::isfinite(out.sigma_rad) && std::isfinite(out.alpha_rad)) {
        ++finite;
      }
    }
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(finite, 10000);
}

TEST(Allocation, ExecutiveCyclesWithPlanAdoptionAllocateNothing) {
  SKIP_WITHOUT_COUNTER();
  const config::Mission m = load("x33");
  GuidanceStack stack;
  ASSERT_EQ(stack.create(m, exec::PlanMode::kSynchronous), "");
  auto profile = std::make_unique<ReferenceProfile>();
  ASSERT_EQ(stack.planner->planner.plan(stack.planner->planner.entry_state(), *profile), Status::kOk);
  const int n = profile->n_points;
  std::int64_t allocations;
  {
    MallocCounter counter;
    for (int i = 0; i < 1000; ++i) {
      exec::NavInput nav;
      nav.tick = i;
      // From the entry point, so that the entry plan (tick 0) is feasible and is adopted.
      nav.state = state_on(*profile, 1 + (i * (n - 2)) / 1000, 0.1 * i, 1.0, m.entry.latitude_rad, m.entry.longitude_rad);
      stack.executive->step(nav);
    }
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_GE(stack.executive->counters().planner_runs, 2);  // entry plan and replans were computed
  EXPECT_GE(stack.executive->counters().plans_adopted, 1)
      << "last plan status: " << to_string(stack.executive->counters().last_plan_status);
}

// The mission with the predictor-corrector law selected.
config::Mission with_pc_law(const char* name) {
  config::Mission m = load(name);
  m.guidance.law = "predictor_corrector";
  return m;
}

TEST(Allocation, PredictorCorrectorPlansForFourMissionsAllocateNothing) {
  SKIP_WITHOUT_COUNTER();
  for (const char* name : {"x33", "horus", "orbiter", "x38"}) {
    const config::Mission m = with_pc_law(name);
    auto planner = std::make_unique<PredictorCorrectorPlanner>();
    auto profile = std::make_unique<ReferenceProfile>();
    ASSERT_EQ(init_from_mission(*planner, m), Status::kOk) << name;
    const RelativeState entry = planner->entry_state();
    Status st;
    std::int64_t allocations;
    {
      MallocCounter counter;
      st = planner->plan(entry, *profile);
      allocations = counter.count();
    }
    EXPECT_EQ(allocations, 0) << name << " plan status " << to_string(st);
    EXPECT_GE(planner->diagnostics().predictions, 2) << name << ": the corrector must have run";
  }
}

TEST(Allocation, TenThousandPredictorCorrectorCyclesAllocateNothing) {
  SKIP_WITHOUT_COUNTER();
  const config::Mission m = with_pc_law("x33");
  GuidanceStack stack;
  ASSERT_EQ(stack.create(m, exec::PlanMode::kSynchronous), "");
  ASSERT_TRUE(stack.pc_law && stack.pc_planner);
  auto profile = std::make_unique<ReferenceProfile>();
  auto& planner = stack.pc_planner->planner;
  ASSERT_EQ(planner.plan(planner.entry_state(), *profile), Status::kOk);
  stack.pc_law->set_profile(*profile);
  const int n = profile->n_points;
  exec::LawOutput out;
  int finite = 0;
  std::int64_t allocations;
  {
    MallocCounter counter;
    for (int i = 0; i < 10000; ++i) {
      const int k = 1 + (i * (n - 2)) / 10000;  // entry to TAEM, captured from the start
      const double drag_factor = 1.0 + 0.1 * std::sin(0.01 * i);
      const RelativeState s = state_on(*profile, k, 0.1 * i, drag_factor, m.entry.latitude_rad, m.entry.longitude_rad);
      if (stack.pc_law->step(s, 0.1, true, out) == Status::kOk && std::isfinite(out.sigma_rad) &&
          std::isfinite(out.alpha_rad)) {
        ++finite;
      }
    }
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(finite, 10000);
  EXPECT_TRUE(stack.pc_law->cycle.captured());
}

TEST(Allocation, ExecutiveCyclesWithPredictorCorrectorPlansAllocateNothing) {
  SKIP_WITHOUT_COUNTER();
  const config::Mission m = with_pc_law("x33");
  GuidanceStack stack;
  ASSERT_EQ(stack.create(m, exec::PlanMode::kSynchronous), "");
  auto profile = std::make_unique<ReferenceProfile>();
  auto& planner = stack.pc_planner->planner;
  ASSERT_EQ(planner.plan(planner.entry_state(), *profile), Status::kOk);
  const int n = profile->n_points;
  std::int64_t allocations;
  {
    MallocCounter counter;
    for (int i = 0; i < 1000; ++i) {
      exec::NavInput nav;
      nav.tick = i;
      nav.state = state_on(*profile, 1 + (i * (n - 2)) / 1000, 0.1 * i, 1.0, m.entry.latitude_rad, m.entry.longitude_rad);
      stack.executive->step(nav);
    }
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_GE(stack.executive->counters().planner_runs, 2);
  EXPECT_GE(stack.executive->counters().plans_adopted, 1)
      << "last plan status: " << to_string(stack.executive->counters().last_plan_status);
}

// The guidance process's per-message path (fsw/app): decode the datagram, record it in the
// process's own log, run the cycle, encode and record command, status and plan. The nav
// conversion is injected, here a look-up of the profile state for the message's tick.
struct ProfileNav {
  const ReferenceProfile* profile;
  double lat, lon;
};

Status profile_nav(const nav_state_t& nav, RelativeState& out, void* ctx) {
  const auto* p = static_cast<const ProfileNav*>(ctx);
  const int n = p->profile->n_points;
  out = state_on(*p->profile, 1 + static_cast<int>(nav.tick * (n - 2) / 1000), nav.t_s, 1.0, p->lat, p->lon);
  return Status::kOk;
}

TEST(Allocation, GuidanceProcessMessagePathAllocatesNothing) {
  SKIP_WITHOUT_COUNTER();
  const config::Mission m = load("x33");
  GuidanceStack stack;
  ASSERT_EQ(stack.create(m, exec::PlanMode::kSynchronous), "");
  auto profile = std::make_unique<ReferenceProfile>();
  ASSERT_EQ(stack.planner->planner.plan(stack.planner->planner.entry_state(), *profile), Status::kOk);
  ProfileNav ctx{profile.get(), m.entry.latitude_rad, m.entry.longitude_rad};
  auto node = std::make_unique<app::GuidanceNode>(*stack.executive, &profile_nav, &ctx, m.guidance.gnc_rate_hz);
  node->attach(nullptr, app::RunMode::kLockstep);
  const std::string log = ::testing::TempDir() + "/allocation_node.lcm";
  std::string err;
  ASSERT_TRUE(node->open_log(log, app::RunMode::kLockstep, err)) << err;
  std::vector<std::vector<std::uint8_t>> msgs;
  for (int i = 0; i < 1000; ++i) {
    nav_state_t nav{};
    nav.tick = i;
    nav.t_s = 0.1 * i;
    nav.utime = 100000LL * i;
    std::vector<std::uint8_t> b(static_cast<std::size_t>(nav.getEncodedSize()));
    nav.encode(b.data(), 0, static_cast<int>(b.size()));
    msgs.push_back(std::move(b));
  }
  std::int64_t allocations;
  {
    MallocCounter counter;
    for (const auto& b : msgs) node->on_datagram("NAV_STATE", b.data(), static_cast<int>(b.size()));
    allocations = counter.count();
  }
  node->close_log();
  std::remove(log.c_str());
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(node->commands_published(), 1000);
  EXPECT_GE(stack.executive->counters().plans_adopted, 1);
}

}  // namespace
}  // namespace reentry::fsw
