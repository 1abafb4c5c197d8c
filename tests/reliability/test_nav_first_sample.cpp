// The executive's navigation validation against the mission (issue 38 items 1 and 7): a first
// sample is judged against the mission's entry state and the physics, one bad message never
// latches a run (a wrong reference is replaced by a consistent run of samples), and the
// flight-path angle cannot jump faster than lift and gravity turn it (2.45). The samples are the
// truth simulator's own (an independent model of the flight), converted by the flight software's
// navigation adapter.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "closed_loop.hpp"
#include "dynamics/simulator.hpp"
#include "guidance/guidance_stack.hpp"
#include "nav/relative_state.hpp"
#include "reentry/config/mission.hpp"

namespace {

using reentry::fsw::RelativeState;
using reentry::fsw::Status;
namespace exec = reentry::fsw::exec;

class NullPlanner : public exec::PlanComputer {
 public:
  Status compute(const RelativeState&, reentry::fsw::ReferenceProfile& out) override {
    out.n_points = 0;
    return Status::kNotConverged;
  }
};

class NullLaw : public exec::CommandLaw {
 public:
  void set_profile(const reentry::fsw::ReferenceProfile&) override {}
  Status step(const RelativeState&, double, bool, exec::LawOutput& out) override {
    out.alpha_rad = 0.6;
    return Status::kOk;
  }
};

reentry::config::Mission load(const std::string& name) {
  const auto r = reentry::config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

// The navigation windows of the guidance stack of `m` (entry envelope included).
exec::NavWindows stack_windows(const reentry::config::Mission& m) {
  reentry::fsw::GuidanceStack stack;
  EXPECT_EQ(stack.create(m, exec::PlanMode::kSynchronous), "");
  stack.executive->shutdown();
  return stack.config.nav;
}

// An executive with the given windows around doubles (its verdicts are the subject).
struct Harness {
  NullPlanner planner;
  NullLaw law;
  std::unique_ptr<exec::Executive> executive = std::make_unique<exec::Executive>();
  explicit Harness(const exec::NavWindows& windows) {
    exec::ExecConfig c;
    c.mode = exec::PlanMode::kSynchronous;
    c.nav = windows;
    EXPECT_EQ(executive->init(c, planner, law), Status::kOk);
  }
  exec::NavVerdict step(std::int64_t tick, const RelativeState& s) {
    exec::NavInput in;
    in.tick = tick;
    in.state = s;
    return executive->step(in).nav_verdict;
  }
};

RelativeState relative(const reentry::truth::NavSample& n) {
  const double r[3] = {n.r_I_m.x(), n.r_I_m.y(), n.r_I_m.z()};
  const double v[3] = {n.v_I_mps.x(), n.v_I_mps.y(), n.v_I_mps.z()};
  const double a[3] = {n.aero_accel_I_mps2.x(), n.aero_accel_I_mps2.y(), n.aero_accel_I_mps2.z()};
  RelativeState s;
  EXPECT_EQ(reentry::fsw::relative_state_from_nav(n.t_s, r, v, a, n.earth_rotation_angle_rad, s), Status::kOk);
  return s;
}

// The truth simulator of mission m (nominal or the draw of `seed`), flown wings level.
std::unique_ptr<reentry::truth::Simulator> truth(const reentry::config::Mission& m, std::uint64_t seed = 0) {
  reentry::truth::SimOverrides ov;
  if (seed != 0) ov.dispersion = reentry::truth::draw_dispersions(m.dispersions, seed);
  std::string err;
  auto sim = reentry::truth::Simulator::create(m, ov, &err);
  EXPECT_TRUE(sim) << err;
  return sim;
}

// The sample: inside every absolute window, 999 km, 14.9 km/s, 489 m/s^2 sensed.
RelativeState absurd_first_sample(const RelativeState& real) {
  RelativeState s = real;
  s.altitude_m = 999e3;
  s.radius_m = 6378137.0 + 999e3;
  s.velocity_mps = 14900.0;
  s.energy_Jpkg = 0.5 * 14900.0 * 14900.0 - 3.986004418e14 / s.radius_m + 3.986004418e14 / 6378137.0;
  s.drag_mps2 = 489.0;
  return s;
}

TEST(NavFirstSample, AbsurdFirstSampleIsRejectedAndTheRealStreamFlies) {
  const auto m = load("x33");
  Harness h(stack_windows(m));
  auto sim = truth(m);
  const RelativeState real0 = relative(sim->nav_sample());
  EXPECT_EQ(h.step(0, absurd_first_sample(real0)), exec::NavVerdict::kRejectedValues);
  EXPECT_EQ(h.step(0, real0), exec::NavVerdict::kAccepted);
  for (std::int64_t k = 1; k <= 50; ++k) {
    sim->advance_to(0.1 * static_cast<double>(k));
    ASSERT_EQ(h.step(k, relative(sim->nav_sample())), exec::NavVerdict::kAccepted) << "tick " << k;
  }
  EXPECT_EQ(h.executive->counters().invalid_nav, 1);
}

TEST(NavFirstSample, EachQuantityOfTheEntryStateIsJudged) {
  // Not one special value: every quantity the entry state fixes, and the physics bounds.
  const auto m = load("x33");
  const exec::NavWindows w = stack_windows(m);
  auto sim = truth(m);
  const RelativeState real0 = relative(sim->nav_sample());
  struct Case {
    const char* name;
    void (*apply)(RelativeState&);
  };
  const Case cases[] = {
      {"radius 30 km high", [](RelativeState& s) { s.radius_m += 30e3, s.altitude_m += 30e3; }},
      {"radius 30 km low", [](RelativeState& s) { s.radius_m -= 30e3, s.altitude_m -= 30e3; }},
      {"speed 400 m/s high", [](RelativeState& s) { s.velocity_mps += 400.0; }},
      {"speed 400 m/s low", [](RelativeState& s) { s.velocity_mps -= 400.0; }},
      {"climbing at 10 deg", [](RelativeState& s) { s.flight_path_rad = 10.0 * M_PI / 180.0; }},
      {"5 deg from the entry point", [](RelativeState& s) { s.latitude_rad += 5.0 * M_PI / 180.0; }},
      {"energy of 8.5 km/s", [](RelativeState& s) { s.energy_Jpkg += 0.5 * (8500.0 * 8500.0 - s.velocity_mps * s.velocity_mps); }},
      {"20 m/s^2 of drag in thin air", [](RelativeState& s) { s.drag_mps2 = 20.0; }},
      {"5 g of lift in thin air", [](RelativeState& s) { s.lift_mps2 = 49.0; }},
  };
  for (const Case& c : cases) {
    Harness h(w);
    RelativeState s = real0;
    c.apply(s);
    EXPECT_EQ(h.step(0, s), exec::NavVerdict::kRejectedValues) << c.name;
    EXPECT_EQ(h.step(0, real0), exec::NavVerdict::kAccepted) << c.name;
  }
  // A later first sample (the guidance started late) is judged by what the time since the entry
  // allows: 60 s after the entry interface the vehicle may be 30 km lower; 300 km higher at the
  // same speed it would hold more energy than it entered with.
  Harness late(w);
  RelativeState s = real0;
  s.t_s = 60.0;
  s.radius_m -= 30e3, s.altitude_m -= 30e3;
  EXPECT_EQ(late.step(600, s), exec::NavVerdict::kAccepted);
  Harness late_high(w);
  s = real0;
  s.t_s = 60.0;
  s.radius_m += 300e3, s.altitude_m += 300e3;
  s.energy_Jpkg += 3.986004418e14 / real0.radius_m - 3.986004418e14 / s.radius_m;
  EXPECT_EQ(late_high.step(600, s), exec::NavVerdict::kRejectedValues);
}

TEST(NavFirstSample, RealEntryStatesOfEveryMissionAndDispersionPass) {
  // The envelope never refuses a real entry: all missions, both dispersion sets, 40 draws each.
  for (const char* name : {"x33", "horus", "orbiter", "x38"}) {
    auto m = load(name);
    for (int set = 0; set < 2; ++set) {
      if (set == 1) {
        if (!m.has_stress_dispersions) continue;
        m.dispersions = m.stress_dispersions;
      }
      const exec::NavWindows w = stack_windows(m);
      for (std::uint64_t seed = 0; seed < 40; ++seed) {
        Harness h(w);
        auto sim = truth(m, seed);
        EXPECT_EQ(h.step(0, relative(sim->nav_sample())), exec::NavVerdict::kAccepted)
            << name << (set ? " stress" : " reference") << " seed " << seed;
      }
    }
  }
}

TEST(NavFirstSample, OneBadMessageNeverLatchesEvenWithoutAnEntryEnvelope) {
  // The root of the latch-up: a wrong reference refusing every real sample. With no entry
  // envelope at all the absurd first sample is accepted; the real stream replaces it after
  // reacquire_samples consistent samples and is flown from then on.
  const auto m = load("x33");
  exec::NavWindows w = stack_windows(m);
  w.entry.known = false;
  Harness h(w);
  auto sim = truth(m);
  EXPECT_EQ(h.step(0, absurd_first_sample(relative(sim->nav_sample()))), exec::NavVerdict::kAccepted);
  int refused = 0;
  for (std::int64_t k = 1; k <= 200; ++k) {
    sim->advance_to(0.1 * static_cast<double>(k));
    const auto v = h.step(k, relative(sim->nav_sample()));
    if (v != exec::NavVerdict::kAccepted) ++refused;
    if (k > w.reacquire_samples) {
      ASSERT_EQ(v, exec::NavVerdict::kAccepted) << "latched at tick " << k;
    }
  }
  EXPECT_EQ(refused, w.reacquire_samples - 1);
  EXPECT_EQ(h.executive->counters().nav_reacquired, 1);
}

TEST(NavFirstSample, PlausibleButWrongFirstSampleIsReplacedByTheRealStream) {
  const auto m = load("x33");
  const exec::NavWindows w = stack_windows(m);
  Harness h(w);
  auto sim = truth(m);
  RelativeState wrong = relative(sim->nav_sample());
  wrong.radius_m += 5e3, wrong.altitude_m += 5e3;  // inside the envelope, 5 km off
  EXPECT_EQ(h.step(0, wrong), exec::NavVerdict::kAccepted);
  for (std::int64_t k = 1; k <= 30; ++k) {
    sim->advance_to(0.1 * static_cast<double>(k));
    const RelativeState s = relative(sim->nav_sample());
    const auto v = h.step(k, s);
    if (k >= w.reacquire_samples) {
      EXPECT_EQ(v, exec::NavVerdict::kAccepted) << "tick " << k;
    }
    if (k == 2) {
      EXPECT_EQ(h.step(k, s), exec::NavVerdict::kRejectedValues);  // a republished sample is no new evidence
    }
  }
  EXPECT_EQ(h.executive->counters().nav_reacquired, 1);
}

TEST(NavFirstSample, RadialVelocityFailsTheFlightPathAngleRate) {
  // 7.6 km/s straight up one tick after a shallow entry: gamma would turn by 90 deg in 0.1 s,
  // (L + g + V^2/r) / V allows a few thousandths of a radian.
  const auto m = load("x33");
  Harness h(stack_windows(m));
  auto sim = truth(m);
  for (std::int64_t k = 0; k <= 20; ++k) {
    if (k > 0) sim->advance_to(0.1 * static_cast<double>(k));
    const RelativeState real = relative(sim->nav_sample());
    if (k == 10) {
      RelativeState radial = real;
      radial.flight_path_rad = 0.5 * M_PI;
      radial.velocity_mps = 7600.0;
      EXPECT_EQ(h.step(k, radial), exec::NavVerdict::kRejectedValues);
    }
    ASSERT_EQ(h.step(k, real), exec::NavVerdict::kAccepted) << "tick " << k;
  }
  EXPECT_EQ(h.executive->counters().nav_rejected_values, 1);
}

TEST(NavFirstSample, WholeFlightsNeverTripTheWindows) {
  // Closed-loop flights (the Monte Carlo path: truth simulator + the guidance stack): nominal
  // X-33 and Orbiter, and HORUS stress draws (steep pull-outs, large lift): no sample refused.
  struct Run {
    const char* mission;
    bool stress;
    std::uint64_t seed;
  };
  for (const Run& run : {Run{"x33", false, 0}, Run{"orbiter", false, 0}, Run{"horus", true, 7}, Run{"horus", true, 8}}) {
    auto m = load(run.mission);
    if (run.stress) m.dispersions = m.stress_dispersions;
    const auto r = reentry::tools::run_closed_loop(m, run.seed, run.seed != 0);
    ASSERT_EQ(r.error, "") << run.mission;
    EXPECT_EQ(r.counters.invalid_nav, 0) << run.mission << " seed " << run.seed;
  }
}

}  // namespace
