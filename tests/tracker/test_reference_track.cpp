// Reference track (reference_track.hpp) against independent truths: linear interpolation of a
// synthetic plan written out by hand, the short way round the heading wrap, (3.13)'s q_ref, and
// the X-33 plan's bank reversal read back as the rate-limited roll of method 3 (§7.4): the bank
// the tracker reads through the planned reversal changes at the bank-rate limit in time
// (dt = -dE / (D V)) from the bank flown before it to its mirror image.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tracker_fixtures.hpp"

namespace reentry::fsw {
namespace {

using namespace test;

// 11 points from 10 MJ/kg down to 0, each array a different linear function of the index.
void indexed_profile(ReferenceProfile& p) {
  synthetic_profile(p, 11, 1.0e7, 0.0, [](double e) { return 2.0 + 1e-6 * (1.0e7 - e); });
  for (int k = 0; k < p.n_points; ++k) {
    p.alpha_rad[k] = 0.7 - 0.02 * k;
    p.lift_over_drag[k] = 1.0 + 0.01 * k;
    p.sigma_rad[k] = 0.1 * k - 0.5;
    p.b_coef[k] = -1e-12 * (k + 1);
    p.dynamic_pressure_Pa[k] = k == 7 ? 16000.0 : 1000.0 * k;
    p.drag_max_mps2[k] = 30.0 + k;
    p.heading_rad[k] = 0.2 * k;
  }
}

TEST(ReferenceTrack, InterpolatesThePlanLinearlyInEnergy) {
  static ReferenceProfile p;
  indexed_profile(p);
  ReferenceTrack track;
  track.init(0.3);
  ASSERT_TRUE(track.adopt(p));
  // At E = 6.5 MJ/kg, between points 3 (7 MJ/kg) and 4 (6 MJ/kg), weight 0.5.
  const RefPoint r = track.at(6.5e6);
  EXPECT_NEAR(r.drag, 2.0 + 3.5, 1e-12);
  EXPECT_NEAR(r.drag_prime, -1e-6, 1e-12);
  EXPECT_NEAR(r.alpha, 0.7 - 0.02 * 3.5, 1e-12);
  EXPECT_NEAR(r.alpha_prime, -0.02 / -1.0e6, 1e-18);  // the cell's slope d alpha / dE
  EXPECT_NEAR(r.lod, 1.035, 1e-12);
  EXPECT_NEAR(r.sigma, -0.15, 1e-12);
  EXPECT_NEAR(r.b, -4.5e-12, 1e-24);
  EXPECT_NEAR(r.q, 3500.0, 1e-9);
  EXPECT_NEAR(r.drag_max, 33.5, 1e-12);
  EXPECT_NEAR(r.heading, 0.7, 1e-12);
  EXPECT_EQ(track.cell(), 3);
  // At the points themselves, the arrays; outside the plan, its end values.
  EXPECT_NEAR(track.at(1.0e7).drag, 2.0, 1e-12);
  EXPECT_NEAR(track.at(3.0e6).alpha, 0.7 - 0.14, 1e-12);
  EXPECT_NEAR(track.at(-5.0e5).drag, 12.0, 1e-12);
  EXPECT_NEAR(track.at(2.0e7).drag, 2.0, 1e-12);
  // (3.13): q_ref is 0.3 of the plan's largest dynamic pressure (16 kPa at point 7).
  EXPECT_DOUBLE_EQ(track.q_ref_Pa(), 0.3 * 16000.0);
}

TEST(ReferenceTrack, FindsTheSameCellWhateverTheLastOne) {
  // The search starts from the last cell (a hint): any order of queries gives what a fresh
  // track gives.
  static ReferenceProfile p;
  indexed_profile(p);
  ReferenceTrack walked;
  walked.init(0.3);
  ASSERT_TRUE(walked.adopt(p));
  for (double e : {9.9e6, 0.3e6, 5.5e6, 5.5e6, 1.0e7, 0.0, 7.2e6, 1.5e6, 8.8e6}) {
    ReferenceTrack fresh;
    fresh.init(0.3);
    ASSERT_TRUE(fresh.adopt(p));
    const RefPoint a = walked.at(e), b = fresh.at(e);
    EXPECT_EQ(a.drag, b.drag) << e;
    EXPECT_EQ(a.alpha_prime, b.alpha_prime) << e;
    EXPECT_EQ(walked.cell(), fresh.cell()) << e;
    EXPECT_NEAR(a.drag, 2.0 + 1e-6 * (1.0e7 - e), 1e-12) << e;
  }
}

TEST(ReferenceTrack, HeadingIsInterpolatedTheShortWayRoundTheWrap) {
  static ReferenceProfile p;
  indexed_profile(p);
  p.heading_rad[3] = 179.0 * kDeg;
  p.heading_rad[4] = -179.0 * kDeg;
  ReferenceTrack track;
  track.init(0.3);
  ASSERT_TRUE(track.adopt(p));
  EXPECT_NEAR(std::fabs(track.at(6.5e6).heading), 180.0 * kDeg, 1e-12);
  EXPECT_NEAR(track.at(6.75e6).heading, 179.5 * kDeg, 1e-12);
}

TEST(ReferenceTrack, AdoptsOnlyTrackablePlansAndKeepsTheOldOneOtherwise) {
  static ReferenceProfile good, failed, best_effort;
  indexed_profile(good);
  ReferenceTrack track;
  track.init(0.3);
  EXPECT_FALSE(track.has_profile());
  failed = good;
  failed.status = Status::kNotConverged;
  EXPECT_FALSE(track.adopt(failed));
  EXPECT_FALSE(track.has_profile());
  ASSERT_TRUE(track.adopt(good));
  failed.drag_mps2[0] = 99.0;
  EXPECT_FALSE(track.adopt(failed));
  EXPECT_EQ(track.profile().drag_mps2[0], 2.0);
  failed.status = Status::kOk;
  failed.n_points = 1;
  EXPECT_FALSE(track.adopt(failed));
  best_effort = good;
  best_effort.status = Status::kRangeTooLong;  // the maximum-drag best effort is flown
  best_effort.drag_mps2[0] = 3.0;
  EXPECT_TRUE(track.adopt(best_effort));
  EXPECT_EQ(track.at(1.0e7).drag, 3.0);
}

TEST(ReferenceTrack, PlannedReversalIsTheRateLimitedRollInTime) {
  // The X-33 plan reverses once. Through the reversal the bank is linear in energy; in time
  // (dE/dt = -D V, D V at the reversal start) it rolls at the bank-rate limit, from the bank
  // flown before it (s0 sigma_rev0) through zero to -s0 sigma_rev0, where the bank of the other
  // side takes over.
  const X33Plan* plan = x33_plan();
  ASSERT_NE(plan, nullptr);
  const ReferenceProfile& p = plan->profile;
  const double rate = plan->mission.constraints.sigma_rate_max_radps;
  const double e_rev = p.reversal_energy_Jpkg;
  const int s0 = p.initial_bank_sign;
  ReferenceTrack track;
  track.init(0.3);
  ASSERT_TRUE(track.adopt(p));
  ASSERT_LT(e_rev, p.energy_Jpkg[0]);
  ASSERT_GT(e_rev, p.taem_energy_Jpkg);
  // D V at the reversal start, interpolated in the plan like the tracker's reference.
  int j = 0;
  while (p.energy_Jpkg[j + 1] > e_rev) ++j;
  const double w = (p.energy_Jpkg[j] - e_rev) / (p.energy_Jpkg[j] - p.energy_Jpkg[j + 1]);
  const double dv = (p.drag_mps2[j] + w * (p.drag_mps2[j + 1] - p.drag_mps2[j])) *
                    (p.velocity_mps[j] + w * (p.velocity_mps[j + 1] - p.velocity_mps[j]));
  // The bank just above the reversal energy: s0 sigma_rev0 (the bank magnitude varies little
  // over a cell); the ramp then spans dE = 2 sigma_rev0 D V / rate.
  const double sigma_rev0 = s0 * p.sigma_rad[j];
  ASSERT_GT(sigma_rev0, 10.0 * kDeg);
  const double de = 2.0 * sigma_rev0 * dv / rate;
  std::vector<int> ramp;
  for (int k = 0; k < p.n_points; ++k) {
    if (p.energy_Jpkg[k] < e_rev && p.energy_Jpkg[k] > e_rev - de) ramp.push_back(k);
  }
  ASSERT_GE(ramp.size(), 3u) << "grid points inside the reversal";
  for (int k : ramp) {
    // sigma(E) = s0 sigma_rev0 - s0 rate (E_rev - E) / (D V): the roll at the rate limit.
    const double expected = s0 * (sigma_rev0 - rate * (e_rev - p.energy_Jpkg[k]) / dv);
    EXPECT_NEAR(p.sigma_rad[k], expected, 0.5 * kDeg) << k;
    EXPECT_NEAR(track.at(p.energy_Jpkg[k]).sigma, p.sigma_rad[k], 1e-12) << k;
  }
  // Between ramp points the bank rate in time is the limit itself (slope in energy times D V).
  for (size_t i = 0; i + 1 < ramp.size(); ++i) {
    const int a = ramp[i], b = ramp[i + 1];
    const double slope = (p.sigma_rad[a] - p.sigma_rad[b]) / (p.energy_Jpkg[a] - p.energy_Jpkg[b]);
    EXPECT_NEAR(slope * dv, s0 * rate, 0.01 * rate) << a;
  }
  // Past the ramp: the other side, at the drag loop's magnitude (no jump of more than a cell's
  // change of the bank magnitude).
  const int after = ramp.back() + 1;
  EXPECT_LT(s0 * p.sigma_rad[after], 0.0);
  EXPECT_NEAR(std::fabs(p.sigma_rad[after]), sigma_rev0, 10.0 * kDeg);
}

}  // namespace
}  // namespace reentry::fsw
