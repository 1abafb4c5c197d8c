// The tracker's cycle (entry_tracker.hpp) as a whole: statuses and never a NaN command for
// adversarial input, the initial descent, the bank magnitude of (3.20) from the commanded
// vertical L/D, and the lift-down limit of the final-reversal window.
#include <gtest/gtest.h>

#include <cmath>

#include "planner/entry_planner.hpp"
#include "tracker_fixtures.hpp"

namespace reentry::fsw {
namespace {

using namespace test;

TEST(EntryTracker, AdversarialInputsInTrackingNeverGiveANaNCommand) {
  // Found by a review: lift 0 with normal drag gave 0/0 -> NaN bank with status ok.
  const auto loaded = config::load_mission("x33");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  EntryPlanner planner;  // static-size object; the test body is not flight code
  ASSERT_EQ(init_from_mission(planner, loaded.mission), Status::kOk);
  static ReferenceProfile profile;
  ASSERT_EQ(planner.plan(planner.entry_state(), profile), Status::kOk);
  EntryTracker t;
  ASSERT_EQ(init_from_mission(t, loaded.mission), Status::kOk);
  t.set_profile(profile);
  const int k = profile.n_points / 2;
  RelativeState s;
  s.radius_m = profile.radius_m[k];
  s.altitude_m = profile.radius_m[k] - kEarthRadius_m;
  s.velocity_mps = profile.velocity_mps[k];
  s.flight_path_rad = 0.0;  // level: the pull-out is complete, so the drag is captured
  s.heading_rad = profile.heading_rad[k];
  s.energy_Jpkg = profile.energy_Jpkg[k];
  s.drag_mps2 = profile.drag_mps2[k];
  s.lift_mps2 = profile.drag_mps2[k] * profile.lift_over_drag[k];
  TrackerOutput out;
  ASSERT_EQ(t.step(s, 0.1, out), Status::kOk);  // captured: tracking
  EXPECT_EQ(out.phase, Phase::kTracking);
  const struct { double drag, lift, speed; } cases[] = {
      {s.drag_mps2, 0.0, s.velocity_mps},         // no sensed lift
      {0.0, 0.0, s.velocity_mps},                 // nothing sensed
      {1e300, 1e300, s.velocity_mps},             // absurd accelerations
      {s.drag_mps2, s.lift_mps2, 1e300},          // absurd speed
      {s.drag_mps2, -1.0, s.velocity_mps},        // negative lift magnitude
  };
  for (const auto& c : cases) {
    RelativeState a = s;
    a.drag_mps2 = c.drag;
    a.lift_mps2 = c.lift;
    a.velocity_mps = c.speed;
    const Status st = t.step(a, 0.1, out);
    if (st == Status::kOk) {
      EXPECT_TRUE(std::isfinite(out.sigma_rad) && std::isfinite(out.alpha_rad))
          << "drag " << c.drag << " lift " << c.lift << " V " << c.speed;
    } else {
      EXPECT_TRUE(st == Status::kInvalidInput || st == Status::kNonFinite) << to_string(st);
    }
  }
}

TEST(EntryTracker, InitialDescentHoldsProfileAlphaWingsLevelAndNeverEmitsNaN) {
  const auto loaded = config::load_mission("x33");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  EntryTracker t;
  ASSERT_EQ(init_from_mission(t, loaded.mission), Status::kOk);
  AlphaProfile alpha;
  ASSERT_EQ(init_from_mission(alpha, loaded.mission), Status::kOk);
  const double r = kEarthRadius_m + 110000.0, V = 7500.0;
  RelativeState s;
  s.radius_m = r;
  s.altitude_m = 110000.0;
  s.velocity_mps = V;
  s.flight_path_rad = -0.02;
  s.energy_Jpkg = specific_energy_Jpkg(r, V);
  s.drag_mps2 = 0.01;  // below the 0.05 g threshold
  s.lift_mps2 = 0.008;
  TrackerOutput out;
  ASSERT_EQ(t.step(s, 0.1, out), Status::kOk);
  EXPECT_EQ(out.phase, Phase::kInitialDescent);
  EXPECT_DOUBLE_EQ(out.sigma_rad, 0.0);
  const double e_entry = specific_energy_Jpkg(kEarthRadius_m + loaded.mission.entry.altitude_m,
                                              loaded.mission.entry.velocity_mps);
  EXPECT_NEAR(out.alpha_rad, alpha.alpha_rad(s.energy_Jpkg / e_entry), 1e-12);
  // Adversarial inputs: statuses, never NaN commands.
  s.drag_mps2 = 0.0;
  s.lift_mps2 = 0.0;
  EXPECT_EQ(t.step(s, 0.1, out), Status::kOk);
  EXPECT_TRUE(std::isfinite(out.sigma_rad) && std::isfinite(out.alpha_rad));
  s.velocity_mps = NAN;
  EXPECT_EQ(t.step(s, 0.1, out), Status::kNonFinite);
  s.velocity_mps = V;
  EXPECT_EQ(t.step(s, 0.0, out), Status::kInvalidInput);
}

TEST(EntryTracker, NoLiftDownInTheFinalReversalWindow) {
  // Sensed drag at half the reference: the drag loop asks for lift down. 10 s before TAEM
  // (inside the final-reversal window, twice the reversal time 2 sigma / sigma_rate at about
  // 50 deg and 5 deg/s) the bank stops at 90 deg (zero vertical lift): a dive started there
  // cannot be arrested before TAEM. 150 s before TAEM (terminal phase, outside the window)
  // and mid-flight the bank goes past 90 deg.
  auto probe = mid_profile_tracker(0.0);
  ASSERT_NE(probe, nullptr);
  const ReferenceProfile& p = *probe->profile;
  const int last = p.n_points - 1;
  auto index_at = [&](double t_go_s) { return profile_index_at_time_to_go(p, t_go_s); };
  int k_mid = last;  // above the terminal phase
  while (k_mid > 0 && p.energy_Jpkg[k_mid] < 1.1 * probe->tracker.terminal_energy_Jpkg()) --k_mid;
  struct Case { int k; bool barred; };
  for (const Case c : {Case{index_at(10.0), true}, Case{index_at(150.0), false}, Case{k_mid, false}}) {
    auto m = mid_profile_tracker(static_cast<double>(c.k) / last);
    ASSERT_NE(m, nullptr);
    RelativeState s = m->state;
    TrackerOutput out;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);  // level: captured, the mean bank set
    ASSERT_EQ(out.phase, Phase::kTracking);
    s.t_s += 0.1;
    s.flight_path_rad = p.gamma_rad[c.k];  // then on the planned flight path and drag
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    ASSERT_LT(std::fabs(out.sigma_rad), 0.5 * M_PI);
    s.t_s += 0.1;
    s.drag_mps2 *= 0.5;
    s.lift_mps2 *= 0.5;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    ASSERT_NE(out.phase, Phase::kInitialDescent);  // a reversal may start: the magnitude counts
    EXPECT_EQ(s.energy_Jpkg < m->tracker.terminal_energy_Jpkg(), c.k != k_mid) << c.k;
    if (c.barred) {
      EXPECT_NEAR(std::fabs(out.sigma_rad), 0.5 * M_PI, 1e-9) << c.k;
      EXPECT_NEAR(out.u_drag, 0.0, 1e-12);
    } else {
      EXPECT_GT(std::fabs(out.sigma_rad), 0.5 * M_PI + 0.1) << c.k;
    }
  }
}

TEST(EntryTracker, BankMagnitudeIsTheArccosOfTheCommandedVerticalLiftOverDrag) {
  // (3.20): sigma_d = acos(u / (L/D)), L/D the sensed one (flown at the reference alpha), for
  // drag errors either way; u within [-L/D, L/D].
  for (double drag_scale : {0.9, 1.0, 1.1, 1.3}) {
    auto m = mid_profile_tracker(0.5);
    ASSERT_NE(m, nullptr);
    RelativeState s = m->state;
    s.drag_mps2 *= drag_scale;
    s.lift_mps2 *= drag_scale;
    const double lod = s.lift_mps2 / s.drag_mps2;
    TrackerOutput out;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    ASSERT_EQ(out.phase, Phase::kTracking);
    EXPECT_NEAR(std::cos(out.sigma_d_rad) * lod, out.u_drag, 1e-12) << drag_scale;
    EXPECT_NEAR(std::fabs(out.sigma_rad), out.sigma_d_rad, 1e-12) << drag_scale;
    EXPECT_LE(std::fabs(out.u_drag), lod + 1e-12) << drag_scale;
    EXPECT_NEAR(out.drag_err_mps2, s.drag_mps2 - out.drag_ref_mps2, 1e-12) << drag_scale;
  }
}

}  // namespace
}  // namespace reentry::fsw
