// Executive cycle: lockstep adoption at k + L, plan-wait and overrun accounting with an
// injected slow planner, synchronous == lockstep, navigation plausibility windows (rejection
// without latch-up, 64-bit tick extremes), tick accounting.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <chrono>
#include <cstring>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

#include "exec/executive.hpp"

namespace {

using reentry::fsw::Phase;
using reentry::fsw::ReferenceProfile;
using reentry::fsw::RelativeState;
using reentry::fsw::Status;
using namespace reentry::fsw::exec;

// Planner double: a two-point profile whose values encode the planning state, so the test
// can see which state was planned from. Optionally blocks on a gate (slow planner).
class GatedPlanner : public PlanComputer {
 public:
  std::atomic<bool> gate_open{true};
  std::atomic<int> calls{0};
  std::atomic<double> last_from_t_s{0.0};
  std::atomic<double> last_from_energy{0.0};
  std::atomic<int> status{0};  // Status code every plan returns
  Status compute(const RelativeState& from, ReferenceProfile& out) override {
    for (long i = 0; i < 2000000000L && !gate_open.load(std::memory_order_acquire); ++i) {
      std::this_thread::yield();
    }
    calls.fetch_add(1);
    last_from_t_s.store(from.t_s);
    last_from_energy.store(from.energy_Jpkg);
    out.n_points = 2;
    out.energy_Jpkg[0] = from.energy_Jpkg;
    out.energy_Jpkg[1] = 0.0;
    out.drag_mps2[0] = 10.0 + 1e-6 * from.energy_Jpkg;
    out.sigma_rad[0] = 0.5 + 1e-3 * from.t_s;
    out.status = static_cast<Status>(status.load());
    if (out.status != Status::kOk && out.status != Status::kRangeTooLong) out.n_points = 0;
    return out.status;
  }
};

// Command-law double: holds alpha/sigma until a profile exists, then flies the profile's
// first bank angle; reports a tracking drag error relative to the profile.
class EchoLaw : public CommandLaw {
 public:
  ReferenceProfile profile;
  int profiles_set = 0;
  void set_profile(const ReferenceProfile& p) override {
    profile = p;
    ++profiles_set;
  }
  Status step(const RelativeState& s, double, bool has_profile, LawOutput& out) override {
    out.alpha_rad = 0.7;
    if (!has_profile) {
      out.sigma_rad = 0.0;
      out.phase = Phase::kInitialDescent;
      return Status::kOk;
    }
    out.sigma_rad = profile.sigma_rad[0] + 1e-9 * s.energy_Jpkg;
    out.phase = Phase::kTracking;
    out.tracker.drag_ref_mps2 = profile.drag_mps2[0];
    out.tracker.drag_err_mps2 = s.drag_mps2 - out.tracker.drag_ref_mps2;
    return Status::kOk;
  }
};

RelativeState state_at(std::int64_t tick, double dt) {
  RelativeState s;
  s.t_s = static_cast<double>(tick) * dt;
  s.radius_m = 6.45e6;
  s.altitude_m = 7.4e4;
  s.velocity_mps = 7000.0 - 10.0 * s.t_s;
  s.energy_Jpkg = 0.5 * s.velocity_mps * s.velocity_mps - 2.0e6;
  s.drag_mps2 = 10.0;
  s.flight_path_rad = -0.01;
  return s;
}

NavInput nav_at(std::int64_t tick, double dt) {
  NavInput n;
  n.tick = tick;
  n.state = state_at(tick, dt);
  return n;
}

// One lockstep cycle as the adapter runs it: step, then resume while the plan is late.
CycleOutput step_lockstep(Executive& exec, const NavInput& nav) {
  CycleOutput out = exec.step(nav);
  for (long i = 0; out.awaiting_plan && i < 200000000L; ++i) {
    std::this_thread::yield();
    out = exec.resume();
  }
  return out;
}

ExecConfig base_config(PlanMode mode, int latency) {
  ExecConfig c;
  c.gnc_rate_hz = 10.0;
  c.plan_latency_ticks = latency;
  c.replan_period_s = 2.0;
  c.replan_drag_error_frac = 10.0;  // never triggered by the doubles
  c.initial_descent_drag_mps2 = 0.0;
  c.mode = mode;
  return c;
}

TEST(Executive, LockstepAdoptsPlanExactlyAtTickKPlusL) {
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(base_config(PlanMode::kLockstep, 3), planner, law), Status::kOk);
  for (std::int64_t k = 0; k <= 6; ++k) {
    const CycleOutput out = step_lockstep(*exec, nav_at(k, 0.1));
    ASSERT_TRUE(out.emitted);
    EXPECT_EQ(out.plan_adopted, k == 3) << "tick " << k;
    EXPECT_EQ(out.plan_seq, k >= 3 ? 1 : 0) << "tick " << k;
    EXPECT_EQ(out.phase, k >= 3 ? Phase::kTracking : Phase::kInitialDescent);
  }
  // (Whether the worker finished before tick 3 is wall-clock luck: overruns are not asserted here.)
  EXPECT_EQ(exec->counters().plans_adopted, 1);
  // Requested at tick 0, planned from the state predicted to tick 3: t = 0.3 s.
  EXPECT_NEAR(planner.last_from_t_s.load(), 0.3, 1e-12);
}

TEST(Executive, PredictStateMatchesConstantDragKinematics) {
  // Constant drag D: V(t) = V0 - D t, E(t) = E0 - D (V0 t - D t^2 / 2) (dE/dt = -D V).
  RelativeState s = state_at(0, 0.1);
  const double dt = 0.1;
  const int n = 50;
  const RelativeState p = predict_state(s, n, dt);
  const double t = n * dt;
  EXPECT_NEAR(p.velocity_mps, s.velocity_mps - s.drag_mps2 * t, 1e-9);
  const double e_exact = s.energy_Jpkg - s.drag_mps2 * (s.velocity_mps * t - 0.5 * s.drag_mps2 * t * t);
  // Forward Euler error bound: D^2 dt t / 2.
  EXPECT_NEAR(p.energy_Jpkg, e_exact, 0.5 * s.drag_mps2 * s.drag_mps2 * dt * t + 1e-6);
  EXPECT_NEAR(p.t_s, t, 1e-12);
}

TEST(Executive, LatePlanIsAWaitNotAnOverrunAndStillAdoptsAtKPlusL) {
  GatedPlanner planner;
  planner.gate_open = false;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(base_config(PlanMode::kLockstep, 2), planner, law), Status::kOk);
  for (std::int64_t k = 0; k <= 4; ++k) {
    CycleOutput out = exec->step(nav_at(k, 0.1));
    if (k == 2) {
      // The plan requested at tick 0 is due and not ready: the cycle waits, nothing emitted.
      ASSERT_TRUE(out.awaiting_plan);
      EXPECT_FALSE(out.emitted);
      EXPECT_TRUE(exec->awaiting_plan());
      EXPECT_EQ(exec->awaiting_tick(), 2);
      // While it waits, a repeat of the sample is a duplicate, another tick is rejected.
      EXPECT_EQ(exec->step(nav_at(2, 0.1)).nav_verdict, NavVerdict::kDuplicate);
      EXPECT_EQ(exec->step(nav_at(3, 0.1)).nav_verdict, NavVerdict::kRejectedTick);
      for (int i = 0; i < 5; ++i) EXPECT_TRUE(exec->resume().awaiting_plan);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the wait (excluded from cycle time)
      planner.gate_open = true;
      for (long i = 0; out.awaiting_plan && i < 200000000L; ++i) {
        std::this_thread::yield();
        out = exec->resume();
      }
      EXPECT_TRUE(out.emitted);
      EXPECT_FALSE(exec->awaiting_plan());
    }
    EXPECT_EQ(out.plan_adopted, k == 2) << "tick " << k;
    EXPECT_EQ(out.plan_seq, k >= 2 ? 1 : 0) << "tick " << k;
    EXPECT_EQ(out.health_flags & kHealthPlanOverrun, 0) << "tick " << k;  // 20 ms < budget 200 ms
  }
  const ExecCounters& c = exec->counters();
  EXPECT_EQ(c.plan_waits, 1);
  EXPECT_EQ(c.plan_overruns, 0);
  EXPECT_EQ(c.plan_timeouts, 0);
  EXPECT_EQ(c.plans_adopted, 1);
  EXPECT_GE(c.plan_wait_ms_max, 20.0);
  EXPECT_GE(c.plan_wait_ms_total, c.plan_wait_ms_max);
  // The cycle's own time excludes the 20 ms wait (the doubles take microseconds).
  EXPECT_LT(c.cycle_us_max, 10000.0);
}

// A plan whose computation takes longer than its budget L / f is an overrun in every mode.
class SlowPlanner : public GatedPlanner {
 public:
  Status compute(const RelativeState& from, ReferenceProfile& out) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    return GatedPlanner::compute(from, out);
  }
};

TEST(Executive, PlanSlowerThanItsBudgetIsAnOverrunAndTheInlinePlanIsNotCycleTime) {
  SlowPlanner planner;
  EchoLaw law;
  ExecConfig cfg = base_config(PlanMode::kSynchronous, 1);
  cfg.gnc_rate_hz = 100.0;  // budget 1 tick = 10 ms < 30 ms
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(cfg, planner, law), Status::kOk);
  CycleOutput out;
  for (std::int64_t k = 0; k <= 1; ++k) out = exec->step(nav_at(k, 0.01));
  EXPECT_TRUE(out.plan_adopted);
  EXPECT_NE(out.health_flags & kHealthPlanOverrun, 0);
  EXPECT_EQ(exec->counters().plan_overruns, 1);
  EXPECT_EQ(exec->counters().plan_waits, 0);
  EXPECT_GE(exec->counters().planner_ms_max, 30.0);
  // Tick 0 computed the plan inline (30 ms): the cycle time excludes it.
  EXPECT_LT(exec->counters().cycle_us_max, 10000.0);
}

TEST(Executive, PlanWaitIsBoundedAndTimeoutIsFlagged) {
  GatedPlanner planner;
  planner.gate_open = false;
  EchoLaw law;
  ExecConfig cfg = base_config(PlanMode::kLockstep, 1);
  cfg.plan_wait_limit_s = 0.01;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(cfg, planner, law), Status::kOk);
  exec->step(nav_at(0, 0.1));
  const CycleOutput out = step_lockstep(*exec, nav_at(1, 0.1));
  EXPECT_TRUE(out.emitted);
  EXPECT_FALSE(out.plan_adopted);
  EXPECT_NE(out.health_flags & kHealthPlanTimeout, 0);
  EXPECT_EQ(exec->counters().plan_timeouts, 1);
  planner.gate_open = true;
  exec->shutdown();
}

std::vector<CycleOutput> fly(PlanMode mode, int n_ticks) {
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  std::vector<CycleOutput> outs;
  if (exec->init(base_config(mode, 4), planner, law) != Status::kOk) return outs;
  for (std::int64_t k = 0; k < n_ticks; ++k) {
    outs.push_back(mode == PlanMode::kLockstep ? step_lockstep(*exec, nav_at(k, 0.1)) : exec->step(nav_at(k, 0.1)));
  }
  return outs;
}

TEST(Executive, SynchronousModeReproducesLockstepBitForBit) {
  const auto a = fly(PlanMode::kLockstep, 200);
  const auto b = fly(PlanMode::kSynchronous, 200);
  ASSERT_EQ(a.size(), 200u);
  ASSERT_EQ(b.size(), 200u);
  int adoptions = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a[i].sigma_rad, &b[i].sigma_rad, sizeof(double)), 0) << "tick " << i;
    EXPECT_EQ(std::memcmp(&a[i].alpha_rad, &b[i].alpha_rad, sizeof(double)), 0) << "tick " << i;
    EXPECT_EQ(a[i].plan_seq, b[i].plan_seq) << "tick " << i;
    adoptions += a[i].plan_adopted ? 1 : 0;
  }
  // Replan every 2 s over 20 s with a request at tick 0 -> 10 plans, the last one adopted.
  EXPECT_EQ(adoptions, 10);
}

TEST(Executive, NonFiniteNavHoldsLastCommandFlagsAndRecovers) {
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
  CycleOutput last;
  for (std::int64_t k = 0; k < 5; ++k) last = exec->step(nav_at(k, 0.1));
  NavInput bad = nav_at(5, 0.1);
  bad.state.velocity_mps = std::numeric_limits<double>::quiet_NaN();
  const CycleOutput held = exec->step(bad);
  EXPECT_TRUE(held.emitted);
  EXPECT_EQ(held.sigma_rad, last.sigma_rad);
  EXPECT_EQ(held.alpha_rad, last.alpha_rad);
  EXPECT_NE(held.health_flags & kHealthNavInvalid, 0);
  NavInput inf = nav_at(6, 0.1);
  inf.state.drag_mps2 = std::numeric_limits<double>::infinity();
  EXPECT_NE(exec->step(inf).health_flags & kHealthNavInvalid, 0);
  EXPECT_EQ(exec->counters().invalid_nav, 2);
  const CycleOutput ok = exec->step(nav_at(7, 0.1));
  EXPECT_EQ(ok.health_flags & kHealthNavInvalid, 0);
  EXPECT_NE(ok.sigma_rad, last.sigma_rad);  // the law runs again on the new state
  EXPECT_EQ(exec->counters().skipped_ticks, 0);
}

TEST(Executive, TimeGoingBackwardsIsRejected) {
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
  exec->step(nav_at(0, 0.1));
  exec->step(nav_at(1, 0.1));
  // A time that does not match its tick (t_s = tick / f) means the tick or the time is
  // corrupted: rejected, and not answered (an answer would carry an untrusted tick).
  NavInput back = nav_at(2, 0.1);
  back.state.t_s = 0.05;  // earlier than tick 1
  const CycleOutput b = exec->step(back);
  EXPECT_FALSE(b.emitted);
  EXPECT_EQ(b.nav_verdict, NavVerdict::kRejectedTick);
  NavInput older_tick = nav_at(0, 0.1);
  older_tick.state.t_s = 0.3;
  EXPECT_EQ(exec->step(older_tick).nav_verdict, NavVerdict::kRejectedTick);
  EXPECT_EQ(exec->step(nav_at(0, 0.1)).nav_verdict, NavVerdict::kRejectedTick);  // consistent, but backwards
  EXPECT_EQ(exec->counters().invalid_nav, 3);
  EXPECT_EQ(exec->counters().nav_rejected_tick, 3);
  const CycleOutput ok = exec->step(nav_at(2, 0.1));
  EXPECT_TRUE(ok.emitted);
  EXPECT_EQ(ok.health_flags & kHealthNavInvalid, 0);
}

TEST(Executive, DuplicateAndSkippedTicksAreCounted) {
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
  EXPECT_TRUE(exec->step(nav_at(0, 0.1)).emitted);
  EXPECT_TRUE(exec->step(nav_at(1, 0.1)).emitted);
  EXPECT_FALSE(exec->step(nav_at(1, 0.1)).emitted);
  EXPECT_TRUE(exec->step(nav_at(2, 0.1)).emitted);
  EXPECT_TRUE(exec->step(nav_at(5, 0.1)).emitted);
  EXPECT_EQ(exec->counters().duplicate_ticks, 1);
  EXPECT_EQ(exec->counters().skipped_ticks, 2);
  EXPECT_EQ(exec->counters().invalid_nav, 0);
}

// Nominal sample stream for the window tests: a steady descent at 7 km/s.
TEST(Executive, OneImplausibleSampleIsRejectedAndTheStreamRecovers) {
  // The wire_fuzz reproductions: one valid-looking message with a far tick, INT64_MAX, a time
  // jump, a negative tick; then the real stream continues. Each is rejected without answer,
  // the next real sample is accepted (no latch-up), and no signed arithmetic overflows
  // (this test runs under UBSan in CI).
  const std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  const std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  struct Case {
    const char* name;
    std::int64_t tick;
    double t_s;
  };
  const Case cases[] = {{"tick_jump", 150 + 1000000, 15.0},   {"tick_jump_consistent", 150 + 1000000, 100015.0},
                        {"time_jump", 150, 1e9},              {"tick_max", kMax, 15.0},
                        {"tick_max_consistent", kMax, 9.2e17}, {"tick_min", kMin, 15.0},
                        {"tick_min_plus_1", kMin + 1, -9.2e17}, {"tick_negative", -(std::int64_t{1} << 62), 15.0},
                        {"time_nan", 150, std::numeric_limits<double>::quiet_NaN()}};
  for (const Case& c : cases) {
    GatedPlanner planner;
    EchoLaw law;
    auto exec = std::make_unique<Executive>();
    ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
    CycleOutput last;
    for (std::int64_t k = 0; k < 150; ++k) last = exec->step(nav_at(k, 0.1));
    NavInput bad = nav_at(150, 0.1);
    bad.tick = c.tick;
    bad.state.t_s = c.t_s;
    const CycleOutput r = exec->step(bad);
    EXPECT_FALSE(r.emitted) << c.name;
    EXPECT_EQ(r.nav_verdict, NavVerdict::kRejectedTick) << c.name;
    EXPECT_FALSE(exec->tick_in_window(c.tick) && c.tick != 150) << c.name;
    int answered = 0, flagged = 0;
    for (std::int64_t k = 150; k < 450; ++k) {
      const CycleOutput o = exec->step(nav_at(k, 0.1));
      answered += o.emitted ? 1 : 0;
      flagged += (o.health_flags & kHealthNavInvalid) ? 1 : 0;
    }
    EXPECT_EQ(answered, 300) << c.name;
    EXPECT_EQ(flagged, 0) << c.name;
    EXPECT_EQ(exec->counters().invalid_nav, 1) << c.name;
    EXPECT_EQ(exec->counters().skipped_ticks, 0) << c.name;
  }
  // INT64_MIN + 1 then INT64_MAX as the first two samples (wire_fuzz tick_overflow).
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
  NavInput a = nav_at(0, 0.1), b = nav_at(1, 0.1);
  a.tick = kMin + 1;
  b.tick = kMax;
  EXPECT_FALSE(exec->step(a).emitted);
  EXPECT_FALSE(exec->step(b).emitted);
  EXPECT_TRUE(exec->step(nav_at(0, 0.1)).emitted);
  EXPECT_EQ(exec->counters().nav_rejected_tick, 2);
}

TEST(Executive, AbsurdButFiniteValuesAndJumpsAreRejectedHeldAndFlagged) {
  // Absolute windows (radius 1 m, 1e6 m/s, drag 1e4 m/s^2) and rate windows (a 50 km altitude
  // step or a 500 m/s speed step within one tick): answered with the held command, flagged,
  // never adopted; the stream is accepted again at the next good sample.
  struct Case {
    const char* name;
    void (*apply)(RelativeState&);
  };
  const Case cases[] = {
      {"radius_1m", [](RelativeState& s) { s.radius_m = 1.0; s.altitude_m = 1.0 - 6378137.0; }},
      {"velocity_1e6", [](RelativeState& s) { s.velocity_mps = 1e6; }},
      {"drag_1e4", [](RelativeState& s) { s.drag_mps2 = 1e4; }},
      {"lift_minus_1e4", [](RelativeState& s) { s.lift_mps2 = -1e4; }},
      {"altitude_jump", [](RelativeState& s) { s.altitude_m += 5e4; }},
      {"speed_jump", [](RelativeState& s) { s.velocity_mps -= 500.0; }},
      {"negative_speed", [](RelativeState& s) { s.velocity_mps = -1.0; }},
      {"nan_heading", [](RelativeState& s) { s.heading_rad = std::numeric_limits<double>::quiet_NaN(); }},
  };
  for (const Case& c : cases) {
    GatedPlanner planner;
    EchoLaw law;
    auto exec = std::make_unique<Executive>();
    ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
    CycleOutput last;
    for (std::int64_t k = 0; k < 20; ++k) last = exec->step(nav_at(k, 0.1));
    NavInput bad = nav_at(20, 0.1);
    c.apply(bad.state);
    const CycleOutput held = exec->step(bad);
    EXPECT_TRUE(held.emitted) << c.name;
    EXPECT_EQ(held.nav_verdict, NavVerdict::kRejectedValues) << c.name;
    EXPECT_EQ(held.tick, 20) << c.name;
    EXPECT_EQ(std::memcmp(&held.sigma_rad, &last.sigma_rad, sizeof(double)), 0) << c.name;
    EXPECT_EQ(std::memcmp(&held.alpha_rad, &last.alpha_rad, sizeof(double)), 0) << c.name;
    EXPECT_NE(held.health_flags & kHealthNavInvalid, 0) << c.name;
    // The rejected sample did not consume its tick: the real sample 20 is used.
    const CycleOutput real = exec->step(nav_at(20, 0.1));
    EXPECT_EQ(real.nav_verdict, NavVerdict::kAccepted) << c.name;
    EXPECT_EQ(real.health_flags & kHealthNavInvalid, 0) << c.name;
    EXPECT_EQ(exec->counters().nav_rejected_values, 1) << c.name;
    EXPECT_EQ(exec->counters().skipped_ticks, 0) << c.name;
  }
}

TEST(Executive, RateWindowsWidenWithTheTicksSinceTheLastAcceptedSample) {
  // 30 ticks lost: a 30 km altitude change over 3 s is plausible (10 km/s), one tick is not.
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
  exec->step(nav_at(0, 0.1));
  NavInput one = nav_at(1, 0.1);
  one.state.altitude_m += 3e4;
  EXPECT_EQ(exec->step(one).nav_verdict, NavVerdict::kRejectedValues);
  NavInput later = nav_at(30, 0.1);
  later.state.altitude_m += 3e4;
  EXPECT_EQ(exec->step(later).nav_verdict, NavVerdict::kAccepted);
  EXPECT_EQ(exec->counters().skipped_ticks, 28);  // ticks 2..29 (tick 1 was received)
  // Beyond max_tick_gap nothing is accepted: the tick is implausible.
  EXPECT_EQ(exec->step(nav_at(30 + 101, 0.1)).nav_verdict, NavVerdict::kRejectedTick);
  EXPECT_EQ(exec->step(nav_at(30 + 100, 0.1)).nav_verdict, NavVerdict::kAccepted);
}

TEST(Executive, RejectsInvalidConfiguration) {
  GatedPlanner planner;
  EchoLaw law;
  auto exec = std::make_unique<Executive>();
  ExecConfig c = base_config(PlanMode::kSynchronous, 0);
  EXPECT_EQ(exec->init(c, planner, law), Status::kInvalidInput);
  c = base_config(PlanMode::kSynchronous, 1);
  c.gnc_rate_hz = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(exec->init(c, planner, law), Status::kInvalidInput);
  c = base_config(PlanMode::kSynchronous, 1);
  c.nav.max_tick_gap = 0;
  EXPECT_EQ(exec->init(c, planner, law), Status::kInvalidInput);
  c = base_config(PlanMode::kSynchronous, 1);
  c.nav.time_tolerance_ticks = 0.6;
  EXPECT_EQ(exec->init(c, planner, law), Status::kInvalidInput);
}

TEST(Executive, RangeTooLongPlanIsFlownFlaggedOtherFailuresAreNot) {
  // A range-too-long plan is the maximum-drag best effort: adopted and flagged. A plan that
  // failed otherwise (no profile) is counted and not adopted.
  for (Status st : {Status::kRangeTooLong, Status::kNotConverged}) {
    GatedPlanner planner;
    planner.status.store(static_cast<int>(st));
    EchoLaw law;
    auto exec = std::make_unique<Executive>();
    ASSERT_EQ(exec->init(base_config(PlanMode::kSynchronous, 1), planner, law), Status::kOk);
    CycleOutput out;
    for (std::int64_t k = 0; k <= 3; ++k) out = exec->step(nav_at(k, 0.1));
    const bool flown = st == Status::kRangeTooLong;
    EXPECT_EQ(exec->counters().plans_adopted, flown ? 1 : 0) << to_string(st);
    EXPECT_EQ(law.profiles_set, flown ? 1 : 0) << to_string(st);
    EXPECT_EQ((out.health_flags & kHealthRangeTooLong) != 0, flown) << to_string(st);
    EXPECT_EQ((out.health_flags & kHealthPlannerFailed) != 0, !flown) << to_string(st);
    EXPECT_EQ(out.phase, flown ? Phase::kTracking : Phase::kInitialDescent) << to_string(st);
  }
}

}  // namespace
