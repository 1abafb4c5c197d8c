// Reversal execution (reversal_execution.hpp) against independent truths: the kinematics of
// the rate-limited roll sigma(t) = sigma0 - rate t (its duration 2 sigma0 / rate and the
// vertical lift C_L cos(sigma(t)) the modulation holds), scans and bisections of the aero table
// written here, and an independent fine quadrature of the range a modulated reversal adds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "tracker_fixtures.hpp"

namespace reentry::fsw {
namespace {

using namespace test;

TEST(ReversalExecution, ReversalModulationNeverRemovesLiftTheDragLoopAsksFor) {
  // A corridor reversal forced by a heading error past the corridor edge, the drag loop asking
  // for a bank of about 60 deg. The flown bank lags at 85 deg (its vertical lift is below the
  // loop's demand): alpha stays at the reference. The flown bank is at 20 deg (more vertical
  // lift than asked for): alpha is lowered so that C_L(alpha) / C_L(alpha_ref) =
  // cos(sigma0) / cos(sigma0 - sigma_rate 1 s), the roll led by 1 s, within the corridor
  // modulation depth of 6 deg (both checked on the table here).
  OnboardModels models;
  for (double flown_deg : {85.0, 20.0}) {
    auto m = mid_profile_tracker(0.9);
    ASSERT_NE(m, nullptr);
    ASSERT_EQ(init_from_mission(models, m->mission), Status::kOk);
    RelativeState s = m->state;
    s.drag_mps2 *= 1.3;  // below the reference: banked less than 90 deg
    s.lift_mps2 *= 1.3;
    TrackerOutput out;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    ASSERT_EQ(out.phase, Phase::kTracking);
    ASSERT_LT(std::fabs(out.sigma_rad), 80.0 * M_PI / 180.0);
    const double alpha_ref = out.alpha_rad;
    const double sign = out.sigma_rad >= 0.0 ? 1.0 : -1.0;
    // Heading past the corridor edge on the side the present bank turns towards.
    s.heading_rad += sign * 20.0 * M_PI / 180.0;
    s.t_s += 0.1;
    m->tracker.set_flown_attitude(alpha_ref, sign * flown_deg * M_PI / 180.0);
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    ASSERT_EQ(out.phase, Phase::kReversal);
    ASSERT_LT(out.sigma_rad * sign, 0.0);
    if (flown_deg > 80.0) {
      EXPECT_NEAR(out.alpha_rad, alpha_ref, 1e-12);
      continue;
    }
    const double mach = models.mach(s.altitude_m, s.velocity_mps);
    const double sigma0 = out.sigma_d_rad;
    const double sigma_lead = std::fabs(sigma0 - m->mission.constraints.sigma_rate_max_radps * 1.0);
    const double ratio = std::max(0.3, std::cos(sigma0) / std::cos(sigma_lead));
    const double floor = alpha_ref - 6.0 * M_PI / 180.0;
    double expected = alpha_ref;  // independent: finest table scan down from the reference
    while (expected > floor && models.aero().cl(expected, mach) > ratio * models.aero().cl(alpha_ref, mach)) expected -= 1e-5;
    EXPECT_LT(out.alpha_rad, alpha_ref - 0.5 * M_PI / 180.0);
    EXPECT_NEAR(out.alpha_rad, std::max(expected, floor), 2e-4);
  }
}

TEST(ReversalExecution, ACorridorReversalEndingInTheFinalWindowGetsTheFullModulation) {
  // Terminal phase, drag at 60 % of the reference (the loop asks for lift down, far past 90
  // deg: the lift ratio of the roll falls to its floor 0.3), heading past the corridor edge: a
  // corridor reversal starts. Started 150 s before TAEM it ends long before the
  // final-reversal window and its modulation is limited to the corridor depth (6 deg), which
  // cannot reach that ratio; started so that it ends inside the window (but begins outside
  // it), it gets the final reversal's depth (15 deg). The window 2 x 2 sigma_mean / sigma_rate and the roll 2 sigma0 / sigma_rate are
  // computed here from the commanded banks and the tracker's time-to-go estimate.
  auto probe = mid_profile_tracker(0.0);
  ASSERT_NE(probe, nullptr);
  const ReferenceProfile& p = *probe->profile;
  const int last = p.n_points - 1;
  const double rate = probe->mission.constraints.sigma_rate_max_radps;
  constexpr double kDeg = M_PI / 180.0;
  OnboardModels models;
  ASSERT_EQ(init_from_mission(models, probe->mission), Status::kOk);
  for (const double t_go_target : {150.0, 65.0}) {
    auto m = mid_profile_tracker(static_cast<double>(profile_index_at_time_to_go(p, t_go_target)) / last);
    ASSERT_NE(m, nullptr);
    RelativeState s = m->state;
    ASSERT_LT(s.energy_Jpkg, m->tracker.terminal_energy_Jpkg());
    TrackerOutput out;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    ASSERT_EQ(out.phase, Phase::kTracking);
    const double sigma1 = out.sigma_d_rad, alpha_ref = out.alpha_rad;
    const double sign = out.sigma_rad >= 0.0 ? 1.0 : -1.0;
    s.t_s += 0.1;
    s.heading_rad += sign * 20.0 * kDeg;
    s.drag_mps2 *= 0.6;
    s.lift_mps2 *= 0.6;
    m->tracker.set_flown_attitude(alpha_ref, sign * 20.0 * kDeg);
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    ASSERT_EQ(out.phase, Phase::kReversal);
    ASSERT_LT(out.sigma_rad * sign, 0.0);
    const double sigma0 = out.sigma_d_rad;
    ASSERT_GT(sigma0, 85.0 * kDeg);
    const double mean = sigma1 + 0.01 * (sigma0 - sigma1);  // 0.1 s of the 10 s bank average
    const double window_s = 2.0 * 2.0 * mean / rate, roll_s = 2.0 * sigma0 / rate;
    const double v_f = std::fmin(m->mission.taem.velocity_mps, s.velocity_mps);
    const double t_go = (s.energy_Jpkg - p.taem_energy_Jpkg) / (s.drag_mps2 * 0.5 * (s.velocity_mps + v_f));
    ASSERT_GT(t_go, window_s + 1.0);  // a corridor reversal, not the final one
    const bool ends_in_window = t_go - roll_s < window_s - 1.0;
    ASSERT_EQ(ends_in_window, t_go_target < 100.0) << t_go << " " << roll_s << " " << window_s;
    if (ends_in_window) {
      EXPECT_LT(out.alpha_rad, alpha_ref - 7.0 * kDeg);
      EXPECT_GE(out.alpha_rad, alpha_ref - 15.0 * kDeg - 1e-9);
    } else {
      // The lift ratio 0.3 is out of reach within the corridor depth: alpha stays (a
      // modulation held at the depth only costs drag).
      const double mach = models.mach(s.altitude_m, s.velocity_mps);
      ASSERT_GT(models.aero().cl(alpha_ref - 6.0 * kDeg, mach), 0.3 * models.aero().cl(alpha_ref, mach));
      EXPECT_NEAR(out.alpha_rad, alpha_ref, 1e-12);
    }
  }
}

// ------------------------------------------------------------------ the rate-limited roll
constexpr double kRate = 5.0 * kDeg;

TEST(ReversalExecution, LiftRatioHoldsTheVerticalLiftOfTheRateLimitedRoll) {
  // sigma(t) = sigma0 - rate t: the modulation keeps C_L cos(sigma(t)) at C_L0 cos(sigma0), so
  // the lift ratio is cos(sigma0) / cos(sigma(t)), within [0.3, 1]; 1 once the roll is past
  // wings level by sigma0 (the roll is over) or at 90 deg and beyond.
  static OnboardModels models;
  const TrackerParams params;
  ReversalExecution rev;
  rev.init(models, params, kRate);
  const double sigma0 = 60.0 * kDeg;
  for (double t : {0.0, 2.0, 6.0, 10.0, 12.0, 14.0, 18.0, 22.0}) {
    const double sigma_t = sigma0 - kRate * t;
    const double ratio = rev.lift_ratio(sigma0, t);
    EXPECT_NEAR(ratio * std::cos(sigma_t), std::cos(sigma0), 1e-12) << t;
    EXPECT_NEAR(rev.lift_ratio(sigma0, 24.0 - t), ratio, 1e-12) << t;  // symmetric about wings level
  }
  EXPECT_NEAR(rev.lift_ratio(sigma0, 12.0), 0.5, 1e-12);      // wings level: cos 60 deg
  EXPECT_NEAR(rev.lift_ratio(sigma0, 24.0), 1.0, 1e-12);      // the roll is over
  EXPECT_NEAR(rev.lift_ratio(sigma0, 30.0), 1.0, 1e-12);      // -90 deg: no modulation
  EXPECT_NEAR(rev.lift_ratio(80.0 * kDeg, 16.0), 0.3, 1e-12);  // cos 80 deg = 0.17: the floor
}

TEST(ReversalExecution, ModulationIsAllowedOnlyBelowTheBoundMargin) {
  static OnboardModels models;
  const TrackerParams params;
  ReversalExecution rev;
  rev.init(models, params, kRate);
  EXPECT_TRUE(rev.modulation_allowed(8.4, 10.0, 1.0));   // below 0.85 D_max K
  EXPECT_FALSE(rev.modulation_allowed(8.6, 10.0, 1.0));
  EXPECT_TRUE(rev.modulation_allowed(8.6, 10.0, 1.2));   // K = 1.2: 10.2
  EXPECT_TRUE(rev.modulation_allowed(50.0, 0.0, 1.0));   // no bound
}

// The X-33 at a terminal-phase point of the plan, 120 s before TAEM.
std::unique_ptr<X33Point> x33_terminal_aero() {
  const X33Plan* plan = x33_plan();
  return plan == nullptr ? nullptr : x33_point(profile_index_at_time_to_go(plan->profile, 120.0));
}

// Independent modulated alpha: bisection (60 steps) of C_L(alpha) = ratio C_L(alpha_ref) in
// [alpha_ref - max, alpha_ref], only where C_L falls below alpha_ref and the ratio is reachable.
double modulated_alpha_truth(const OnboardAero& aero, double alpha, double mach, double ratio, double max_rad) {
  const double cl_ref = aero.cl(alpha, mach), lo0 = std::max(0.0, alpha - max_rad);
  if (!(ratio < 1.0) || !(aero.cl(alpha - 1.0 * kDeg, mach) < cl_ref) || !(aero.cl(lo0, mach) < ratio * cl_ref)) {
    return alpha;
  }
  double lo = lo0, hi = alpha;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (aero.cl(mid, mach) > ratio * cl_ref ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(ReversalExecution, ModulatedAlphaMeetsTheLiftRatioOnTheTable) {
  auto a = x33_terminal_aero();
  ASSERT_NE(a, nullptr);
  const TrackerParams params;
  ReversalExecution rev;
  rev.init(a->models, params, kRate);
  const OnboardAero& aero = a->models.aero();
  const double cl_ref = aero.cl(a->alpha_rad, a->mach);
  for (double ratio : {0.95, 0.8, 0.6}) {
    const double alpha = rev.modulated_alpha(a->alpha_rad, a->mach, ratio, 15.0 * kDeg);
    EXPECT_NEAR(alpha, modulated_alpha_truth(aero, a->alpha_rad, a->mach, ratio, 15.0 * kDeg), 1e-8) << ratio;
    if (alpha > a->alpha_rad - 15.0 * kDeg + 1e-9 && alpha < a->alpha_rad) {
      EXPECT_NEAR(aero.cl(alpha, a->mach), ratio * cl_ref, 1e-6 * cl_ref) << ratio;
    }
  }
  EXPECT_EQ(rev.modulated_alpha(a->alpha_rad, a->mach, 1.0, 15.0 * kDeg), a->alpha_rad);
  EXPECT_EQ(rev.modulated_alpha(a->alpha_rad, a->mach, 0.8, 0.0), a->alpha_rad);  // no depth: nothing reachable
}

TEST(ReversalExecution, RangeExtensionIsTheDragSavedOverTheModulatedRoll) {
  // Over the roll T = 2 sigma0 / rate the vehicle dissipates int D_mod V dt instead of D V T;
  // the energy saved is flown off at D afterwards: dS = V int_0^T (1 - C_D(alpha_mod(t)) /
  // C_D(alpha)) dt, alpha_mod(t) holding C_L cos(sigma(t)) at the final reversal's depth.
  // Truth: 4000-point midpoint rule with the independent modulated alpha.
  auto a = x33_terminal_aero();
  ASSERT_NE(a, nullptr);
  const TrackerParams params;
  ReversalExecution rev;
  rev.init(a->models, params, kRate);
  const OnboardAero& aero = a->models.aero();
  for (double sigma0_deg : {40.0, 60.0, 75.0}) {
    const double sigma0 = sigma0_deg * kDeg, T = 2.0 * sigma0 / kRate;
    const int n = 4000;
    double truth = 0.0;
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) * T / n;
      const double sigma_t = std::fabs(sigma0 - kRate * t);
      const double ratio = std::clamp(std::cos(sigma0) / std::cos(sigma_t), params.modulation_min_lift_ratio, 1.0);
      const double alpha_mod = modulated_alpha_truth(aero, a->alpha_rad, a->mach, ratio, params.final_modulation_max_rad);
      truth += (1.0 - aero.cd(alpha_mod, a->mach) / aero.cd(a->alpha_rad, a->mach)) * a->state.velocity_mps * T / n;
    }
    const double ext = rev.range_extension_m(a->state, a->mach, a->alpha_rad, sigma0);
    EXPECT_GT(truth, 1000.0) << sigma0_deg;
    EXPECT_NEAR(ext, truth, 0.02 * truth) << sigma0_deg;
  }
  EXPECT_EQ(rev.range_extension_m(a->state, a->mach, a->alpha_rad, 0.0), 0.0);
}

// ------------------------------------------------------------------ bit-for-bit equivalence
// The modulation's bisections run on the table at one Mach (OnboardAero::MachSlice), side by
// side, sharing look-ups. Their results must be those of one 30-step bisection at a time through
// the general look-up OnboardAero::cl(alpha, mach), bit for bit (commands are compared run by
// run with the baseline campaigns): that is the reference written here.
double one_bisection_at_a_time(const OnboardAero& aero, double alpha, double mach, double ratio, double max_rad) {
  const double cl_ref = aero.cl(alpha, mach);
  if (!(ratio < 1.0) || !(cl_ref > 0.0)) return alpha;
  double lo = std::fmax(0.0, alpha - max_rad), hi = alpha;
  if (!(aero.cl(alpha - M_PI / 180.0, mach) < cl_ref) || !(aero.cl(lo, mach) < ratio * cl_ref)) return alpha;
  for (int i = 0; i < kAlphaBisectionSteps; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (aero.cl(mid, mach) > ratio * cl_ref) hi = mid; else lo = mid;
  }
  return 0.5 * (lo + hi);
}

double extension_one_sample_at_a_time(const ReversalExecution& rev, const OnboardAero& aero, const TrackerParams& p,
                                      double v, double mach, double alpha, double sigma0) {
  const double cd_ref = aero.cd(alpha, mach), t_rev = 2.0 * sigma0 / kRate;
  double extension = 0.0;
  for (int i = 0; i < 20; ++i) {
    const double t = (i + 0.5) * t_rev / 20;
    const double a = one_bisection_at_a_time(aero, alpha, mach, rev.lift_ratio(sigma0, t), p.final_modulation_max_rad);
    if (cd_ref > 0.0) extension += (1.0 - aero.cd(a, mach) / cd_ref) * v * t_rev / 20;
  }
  return extension;
}

TEST(ReversalExecution, BatchedModulationEqualsOneBisectionAtATimeBitForBit) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const TrackerParams params;
  int modulated = 0;
  for (const char* name : {"x33", "horus", "x38"}) {
    const config::LoadResult loaded = config::load_mission(name);
    ASSERT_TRUE(loaded.ok) << loaded.error;
    OnboardModels models;
    ASSERT_EQ(init_from_mission(models, loaded.mission), Status::kOk);
    const OnboardAero& aero = models.aero();
    ReversalExecution rev;
    rev.init(models, params, kRate);
    const auto& grid = loaded.mission.vehicle.aero.cl;
    for (int n = 0; n < 300; ++n) {
      // alpha_ref and Mach over the table (and a little past its edges), banks 0-89 deg: ratios
      // from 1 down to the floor, depths from nothing to past the table's first alpha.
      const double alpha = grid.alpha_rad.front() - 0.05 + (grid.alpha_rad.back() - grid.alpha_rad.front() + 0.1) * u(rng);
      const double mach = grid.mach.front() * 0.9 + (grid.mach.back() * 1.1 - grid.mach.front() * 0.9) * u(rng);
      const double sigma0 = 89.0 * kDeg * u(rng), v = 1000.0 + 6000.0 * u(rng);
      const double ratio = 0.2 + 0.85 * u(rng), depth = 20.0 * kDeg * u(rng);
      const double a = rev.modulated_alpha(alpha, mach, ratio, depth);
      ASSERT_EQ(a, one_bisection_at_a_time(aero, alpha, mach, ratio, depth)) << name << " " << n;
      modulated += a != alpha ? 1 : 0;
      RelativeState s;
      s.velocity_mps = v;
      ASSERT_EQ(rev.range_extension_m(s, mach, alpha, sigma0),
                extension_one_sample_at_a_time(rev, aero, params, v, mach, alpha, sigma0))
          << name << " " << n;
    }
  }
  EXPECT_GT(modulated, 200);  // most cases bisect (not an early return)
}

TEST(ReversalExecution, AReversalLastsTheRollAtTheRateLimitWithTheIntegralFrozen) {
  // A corridor reversal forced by a heading 20 deg past the corridor edge, from the drag
  // loop's bank sigma_d: the roll from sigma_d to -sigma_d at the bank-rate limit takes
  // 2 sigma_d / rate (the tracker holds the reversal one cycle more). The drag integral is
  // frozen throughout and runs again after it.
  auto m = mid_profile_tracker(0.9);
  ASSERT_NE(m, nullptr);
  const double rate = m->mission.constraints.sigma_rate_max_radps, dt = 0.1;
  RelativeState s = m->state;
  s.drag_mps2 *= 1.3;
  s.lift_mps2 *= 1.3;
  TrackerOutput out;
  ASSERT_EQ(m->tracker.step(s, dt, out), Status::kOk);
  ASSERT_EQ(out.phase, Phase::kTracking);
  const double sign = out.sigma_rad >= 0.0 ? 1.0 : -1.0;
  s.heading_rad += sign * 20.0 * kDeg;
  s.t_s += dt;
  ASSERT_EQ(m->tracker.step(s, dt, out), Status::kOk);
  ASSERT_EQ(out.phase, Phase::kReversal);
  const double sigma_d = out.sigma_d_rad, t_roll = 2.0 * sigma_d / rate;
  ASSERT_GT(t_roll, 10.0);
  const double integral = out.telemetry.drag_integral_mps;
  int cycles = 1;
  for (int i = 0; i < 1000; ++i) {
    s.t_s += dt;
    ASSERT_EQ(m->tracker.step(s, dt, out), Status::kOk);
    if (out.phase != Phase::kReversal) break;
    ++cycles;
    EXPECT_EQ(out.telemetry.drag_integral_mps, integral) << i;
  }
  EXPECT_GE(cycles * dt, t_roll - 1e-9);
  EXPECT_LE(cycles * dt, t_roll + 2.0 * dt + 1e-9);
  EXPECT_EQ(out.phase, Phase::kTracking);
  EXPECT_LT(out.sigma_rad * sign, 0.0);
  s.t_s += dt;
  ASSERT_EQ(m->tracker.step(s, dt, out), Status::kOk);
  EXPECT_NE(out.telemetry.drag_integral_mps, integral);
}

}  // namespace
}  // namespace reentry::fsw
