// Aero ratio estimation (aero_ratio_estimator.hpp) against independent truths: the closed-form
// response of a first-order filter to a step in the sensed ratio, the documented bounds, the
// table's coefficient ratios for referring the sensed state to another alpha, and the planner's
// use of the L/D estimate (the planned L/D scaled point by point, ranging alpha found by an
// independent scan of the table).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "planner/entry_planner.hpp"
#include "tracker_fixtures.hpp"

namespace reentry::fsw {
namespace {

using namespace test;

TEST(AeroRatioEstimator, DragLoopSeesTheDensityNotTheAlphaChannel) {
  // The same air (same q) flown 10 deg below the reference alpha: the sensed drag and lift
  // are the table's C_D and C_L ratios times the reference-alpha ones (computed here from the
  // table). The drag loop must see the same drag error and command the same bank as at the
  // reference alpha: a drag change made by the alpha channel is not an altitude error.
  OnboardModels models;
  auto a = mid_profile_tracker(0.7);
  auto b = mid_profile_tracker(0.7);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  ASSERT_EQ(init_from_mission(models, a->mission), Status::kOk);
  RelativeState s = a->state;
  s.drag_mps2 *= 1.05;  // 5 % above the reference: a drag error to see
  s.lift_mps2 *= 1.05;
  TrackerOutput out_a, out_b;
  ASSERT_EQ(a->tracker.step(s, 0.1, out_a), Status::kOk);
  ASSERT_EQ(b->tracker.step(s, 0.1, out_b), Status::kOk);
  ASSERT_EQ(out_a.phase, Phase::kTracking);
  const double alpha_ref = out_a.alpha_rad;
  const double alpha_low = alpha_ref - 10.0 * M_PI / 180.0;
  const double mach = models.mach(s.altitude_m, s.velocity_mps);
  double cl_ref, cd_ref, cl_low, cd_low;
  models.aero().coefficients(alpha_ref, mach, cl_ref, cd_ref);
  models.aero().coefficients(alpha_low, mach, cl_low, cd_low);
  ASSERT_LT(cd_low, 0.9 * cd_ref);  // the modulation changes the drag by more than the error
  RelativeState s_low = s;
  s_low.t_s += 0.1;
  s_low.drag_mps2 = s.drag_mps2 * cd_low / cd_ref;
  s_low.lift_mps2 = s.lift_mps2 * cl_low / cl_ref;
  RelativeState s_ref = s;
  s_ref.t_s += 0.1;
  a->tracker.set_flown_attitude(alpha_ref, out_a.sigma_rad);
  b->tracker.set_flown_attitude(alpha_low, out_b.sigma_rad);
  ASSERT_EQ(a->tracker.step(s_ref, 0.1, out_a), Status::kOk);
  ASSERT_EQ(b->tracker.step(s_low, 0.1, out_b), Status::kOk);
  EXPECT_GT(out_a.drag_err_mps2, 0.0);
  EXPECT_NEAR(out_b.drag_err_mps2, out_a.drag_err_mps2, 1e-9 * s.drag_mps2);
  EXPECT_NEAR(out_b.drag_ref_mps2, out_a.drag_ref_mps2, 1e-9 * s.drag_mps2);
  // Same bank up to the energy-rate scaling of the gains (E' = -D V with the drag flown).
  EXPECT_NEAR(out_b.sigma_rad, out_a.sigma_rad, 2.0 * M_PI / 180.0);
  // Taken raw, the error would have the opposite sign (the vehicle would be told it is high).
  EXPECT_LT(s_low.drag_mps2 - out_a.drag_ref_mps2, -0.05 * out_a.drag_ref_mps2);
}

TEST(AeroRatioEstimator, LiftOverDragEstimateConvergesToTheSensedRatio) {
  // Sensed lift 12 % below the table's at the flown alpha: the filtered estimate (20 s time
  // constant) must settle at 0.88 after a few time constants.
  auto m = mid_profile_tracker(0.5);
  ASSERT_NE(m, nullptr);
  TrackerOutput out;
  ASSERT_EQ(m->tracker.step(m->state, 0.1, out), Status::kOk);
  OnboardModels models;
  ASSERT_EQ(init_from_mission(models, m->mission), Status::kOk);
  RelativeState s = m->state;
  for (int i = 0; i < 2000; ++i) {
    double cl, cd;
    models.aero().coefficients(out.alpha_rad, models.mach(s.altitude_m, s.velocity_mps), cl, cd);
    s.lift_mps2 = 0.88 * s.drag_mps2 * cl / cd;
    s.t_s += 0.1;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
  }
  EXPECT_NEAR(out.lift_over_drag_scale, 0.88, 0.002);
}

TEST(EntryPlanner, InFlightLiftOverDragEstimateScalesThePlannedLiftOverDrag) {
  // The planned L/D is the table's times the estimate, point by point, and the equilibrium
  // glide floor (7.7) rises accordingly: a plan with 0.85 of the lift is still feasible.
  const auto loaded = config::load_mission("x33");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  EntryPlanner planner;
  ASSERT_EQ(init_from_mission(planner, loaded.mission), Status::kOk);
  static ReferenceProfile nominal, scaled;
  RelativeState from = planner.entry_state();
  ASSERT_EQ(planner.plan(from, nominal), Status::kOk);
  from.lift_over_drag_scale = 0.85;
  ASSERT_EQ(planner.plan(from, scaled), Status::kOk);
  OnboardModels models;
  ASSERT_EQ(init_from_mission(models, loaded.mission), Status::kOk);
  for (int k = 0; k < scaled.n_points; k += 10) {
    const double h = scaled.radius_m[k] - kEarthRadius_m;
    double cl, cd;
    models.aero().coefficients(scaled.alpha_rad[k], models.mach(h, scaled.velocity_mps[k]), cl, cd);
    EXPECT_NEAR(scaled.lift_over_drag[k], 0.85 * cl / cd, 1e-9 * cl / cd) << k;
  }
  from.lift_over_drag_scale = 0.0;  // outside the accepted range
  EXPECT_EQ(planner.plan(from, scaled), Status::kInvalidInput);
}

TEST(EntryPlanner, RangingAlphaRestoresALowLiftOverDragPlan) {
  // With 65 % of the table L/D the X-33 range is beyond the wings-level glide at the profile
  // alpha (46 deg, L/D 0.72): the planner must move alpha towards alpha(L/D max), found here
  // by an independent brute-force scan of the table, never below it and never at TAEM, and
  // the plan must converge. The nominal vehicle needs no ranging.
  const auto loaded = config::load_mission("x33");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  auto planner = std::make_unique<EntryPlanner>();
  ASSERT_EQ(init_from_mission(*planner, loaded.mission), Status::kOk);
  static ReferenceProfile nominal, low;
  RelativeState from = planner->entry_state();
  ASSERT_EQ(planner->plan(from, nominal), Status::kOk);
  EXPECT_EQ(nominal.ranging_blend, 0.0);
  AlphaProfile profile_alpha;
  ASSERT_EQ(init_from_mission(profile_alpha, loaded.mission), Status::kOk);
  for (int k = 0; k < nominal.n_points; ++k) {
    EXPECT_DOUBLE_EQ(nominal.alpha_rad[k], profile_alpha.alpha_rad(nominal.e_norm[k])) << k;
  }
  from.lift_over_drag_scale = 0.65;
  ASSERT_EQ(planner->plan(from, low), Status::kOk);
  EXPECT_TRUE(low.converged);
  EXPECT_GT(low.ranging_blend, 0.0);
  OnboardModels models;
  ASSERT_EQ(init_from_mission(models, loaded.mission), Status::kOk);
  int lowered = 0;
  for (int k = 0; k < low.n_points; ++k) {
    const double a_profile = profile_alpha.alpha_rad(low.e_norm[k]);
    EXPECT_LE(low.alpha_rad[k], a_profile + 1e-12) << k;
    const double mach = models.mach(low.radius_m[k] - kEarthRadius_m, low.velocity_mps[k]);
    double best = -1.0, a_ld = 0.0;
    for (int i = 0; i <= 4000; ++i) {
      const double a = loaded.mission.constraints.alpha_max_rad * i / 4000.0;
      double cl, cd;
      models.aero().coefficients(a, mach, cl, cd);
      if (cl / cd > best) { best = cl / cd; a_ld = a; }
    }
    // Not below alpha(L/D max) (at the planned Mach; the planner scans at its glide Mach).
    EXPECT_GE(low.alpha_rad[k], std::fmin(a_ld, a_profile) - 2.0 * kDeg) << k;
    if (low.alpha_rad[k] < a_profile - 1.0 * kDeg) ++lowered;
  }
  EXPECT_GT(lowered, low.n_points / 4);
  EXPECT_DOUBLE_EQ(low.alpha_rad[low.n_points - 1], profile_alpha.alpha_rad(low.e_norm[low.n_points - 1]));
  // A later plan never lowers the blend again (continuous alpha reference in flight).
  static ReferenceProfile later;
  from.lift_over_drag_scale = 1.0;
  ASSERT_EQ(planner->plan(from, later), Status::kOk);
  EXPECT_GE(later.ranging_blend, low.ranging_blend);
}

// ------------------------------------------------------------------ first-order estimates
TEST(AeroRatioEstimator, DragRatioIsAFirstOrderFilterOfTheSensedRatioWithinItsBounds) {
  // The sensed drag K times the model's (at the height above the ellipsoid): from 1 the
  // estimate follows K - (K - 1) exp(-t / tau), tau = 20 s, to the 0.01 s step's discretisation;
  // a sensed ratio beyond [0.5, 2] is taken at the bound.
  auto c = x33_mid_plan();
  ASSERT_NE(c, nullptr);
  RelativeState s = c->state;
  const double h_ellipsoid_m = s.radius_m - surface_radius_m(s.latitude_rad);
  const double d_model = c->models.drag_mps2(c->alpha_rad, h_ellipsoid_m, s.velocity_mps);
  const double dt = 0.01, tau = c->params.ratio_time_constant_s;
  for (double K : {1.3, 0.8, 3.0, 0.2}) {
    AeroRatioEstimator est;
    est.init(c->models, c->params);
    s.drag_mps2 = K * d_model;
    const double K_seen = std::clamp(K, c->params.drag_ratio_min, c->params.drag_ratio_max);
    for (int i = 1; i <= static_cast<int>(3.0 * tau / dt); ++i) {
      est.update_drag_ratio(s, c->alpha_rad, dt);
      if (i % 1000 == 0) {
        const double expected = K_seen - (K_seen - 1.0) * std::exp(-i * dt / tau);
        EXPECT_NEAR(est.drag_ratio(), expected, 5e-4 * std::fabs(K_seen - 1.0)) << K << " " << i;
      }
    }
    EXPECT_DOUBLE_EQ(est.lift_over_drag_ratio(), 1.0);  // the drag update leaves L/D alone
  }
  // Drag not measurable: the estimate holds.
  AeroRatioEstimator est;
  est.init(c->models, c->params);
  s.drag_mps2 = 0.5 * c->params.min_drag_mps2;
  est.update_drag_ratio(s, c->alpha_rad, 1.0);
  EXPECT_EQ(est.drag_ratio(), 1.0);
}

TEST(AeroRatioEstimator, LiftOverDragRatioIsAFirstOrderFilterOfTheSensedOverTheTableRatio) {
  auto c = x33_mid_plan();
  ASSERT_NE(c, nullptr);
  RelativeState s = c->state;
  double cl, cd;
  c->models.aero().coefficients(c->alpha_rad, c->models.mach(s.altitude_m, s.velocity_mps), cl, cd);
  const double dt = 0.01, tau = c->params.ratio_time_constant_s;
  for (double r : {0.88, 1.2, 2.0}) {
    AeroRatioEstimator est;
    est.init(c->models, c->params);
    s.lift_mps2 = r * s.drag_mps2 * cl / cd;
    const double r_seen = std::clamp(r, c->params.lod_ratio_min, c->params.lod_ratio_max);
    for (int i = 0; i < static_cast<int>(tau / dt); ++i) est.update_lift_over_drag_ratio(s, c->alpha_rad, dt);
    EXPECT_NEAR(est.lift_over_drag_ratio(), r_seen - (r_seen - 1.0) * std::exp(-1.0), 5e-4 * std::fabs(r_seen - 1.0)) << r;
    EXPECT_DOUBLE_EQ(est.drag_ratio(), 1.0);
  }
  // Below the initial-descent drag the lift is not used.
  AeroRatioEstimator est;
  est.init(c->models, c->params);
  s.drag_mps2 = 0.5 * c->params.initial_descent_drag_mps2;
  s.lift_mps2 = 0.5 * s.drag_mps2 * cl / cd;
  est.update_lift_over_drag_ratio(s, c->alpha_rad, 1.0);
  EXPECT_EQ(est.lift_over_drag_ratio(), 1.0);
}

TEST(AeroRatioEstimator, ReferredStateScalesDragAndLiftByTheTablesCoefficientRatios) {
  auto c = x33_mid_plan();
  ASSERT_NE(c, nullptr);
  const RelativeState& s = c->state;
  const double mach = c->models.mach(s.altitude_m, s.velocity_mps);
  const double flown = c->alpha_rad - 8.0 * kDeg;
  const RelativeState r = referred_to_alpha(c->models, s, mach, flown, c->alpha_rad);
  const OnboardAero& aero = c->models.aero();
  EXPECT_NEAR(r.drag_mps2, s.drag_mps2 * aero.cd(c->alpha_rad, mach) / aero.cd(flown, mach), 1e-12 * s.drag_mps2);
  EXPECT_NEAR(r.lift_mps2, s.lift_mps2 * aero.cl(c->alpha_rad, mach) / aero.cl(flown, mach), 1e-12 * s.lift_mps2);
  EXPECT_EQ(r.velocity_mps, s.velocity_mps);
  const RelativeState same = referred_to_alpha(c->models, s, mach, c->alpha_rad, c->alpha_rad);
  EXPECT_DOUBLE_EQ(same.drag_mps2, s.drag_mps2);
  EXPECT_DOUBLE_EQ(same.lift_mps2, s.lift_mps2);
}

}  // namespace
}  // namespace reentry::fsw
