// Terminal range control (terminal_range.hpp) against independent truths: the range
// S = -int dE / D (C.2) and its sensitivity to the drag increment in closed form for constant
// and linear drag profiles, the linearised range equation solved by hand, finite differences of
// the shaped reference, and the TAEM altitude band for the final-drag factor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tracker_fixtures.hpp"

namespace reentry::fsw {
namespace {

using namespace test;

TEST(TerminalRange, TerminalRangeControlRisesToThePlannedBoundWhateverTheSensedDragRatio) {
  // A q-type bound in drag space, q_max C_D S / m, does not move with the density; a low
  // sensed drag ratio K = 0.8 (here: the air 20 % thinner than the model) must not lower it.
  // X-33 a tenth into the terminal phase, level on the profile, on the arrival line at half
  // the plan's range to go (C.2): the range control asks for far more drag than the plan,
  // and is held at the plan's bound, lowered here to 1.1 times the planned drag (the
  // mission's limits removed, so that the sensed constraint limit does not act).
  auto m = mid_profile_tracker(0.0);
  ASSERT_NE(m, nullptr);
  static ReferenceProfile bounded;
  bounded = *m->profile;
  const ReferenceProfile& p = bounded;
  for (int j = 0; j < p.n_points; ++j) bounded.drag_max_mps2[j] = 1.1 * p.drag_mps2[j];
  config::Mission unconstrained = m->mission;  // the sensed limits out of the way
  unconstrained.constraints.heat_flux_max_Wpm2 = config::kNotConstrained;
  unconstrained.constraints.load_factor_max_g = config::kNotConstrained;
  unconstrained.constraints.q_alpha_max_Pa_rad = config::kNotConstrained;
  unconstrained.constraints.dynamic_pressure_max_Pa = config::kNotConstrained;
  ASSERT_EQ(init_from_mission(m->tracker, unconstrained), Status::kOk);
  m->tracker.set_profile(bounded);
  const int last = p.n_points - 1;
  const double e_early = p.energy_Jpkg[last] + 0.9 * GuidanceLawParams{}.terminal_span_fraction * (p.energy_Jpkg[0] - p.energy_Jpkg[last]);
  int k = last;
  while (k > 0 && p.energy_Jpkg[k - 1] <= e_early) --k;
  RelativeState s = level_state_on_profile(p, k);
  s.heading_rad = place_from_aim_point(m->mission.taem, 0.5 * profile_range_to_go_m(p, k), 0.0, s);
  OnboardModels models;
  ASSERT_EQ(init_from_mission(models, m->mission), Status::kOk);
  constexpr double kDragRatio = 0.8;
  TrackerOutput out;
  ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
  for (int i = 0; i < 3000; ++i) {  // 300 s: the 20 s drag-ratio filter has converged
    // The air is stratified over the ellipsoid: the model drag at the height above it.
    const double h_ellipsoid_m = s.radius_m - surface_radius_m(s.latitude_rad);
    s.drag_mps2 = kDragRatio * models.drag_mps2(out.alpha_rad, h_ellipsoid_m, s.velocity_mps);
    s.t_s += 0.1;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
  }
  ASSERT_EQ(out.phase, Phase::kTracking);
  const double planned_bound = 1.1 * p.drag_mps2[k];
  EXPECT_NEAR(out.drag_ref_mps2, planned_bound, 0.02 * planned_bound);
}

TEST(TerminalRange, FinalDragTakesOnlyThePartOfTheDragRatioTheInnerTaemBandNeeds) {
  // altitude band +-1.8 km, no Mach band. The sensed drag is K times the on-board
  // model's for 300 s (20 s filter). Flying k times the planned final drag meets the TAEM
  // energy H ln(K / k) above the planned altitude, so the inner half of the band (+-0.9 km,
  // the aim of the final factor) holds for k in [K exp(-hi / H), K exp(-lo / H)], lo/hi its
  // edges relative to the planned altitude; the factor is the value closest to 1 there
  // (closed form here), found by a 20-step scan.
  constexpr double kH_m = 7050.0;
  constexpr double kInnerBand = 0.5;
  for (double K : {1.1, 1.5, 0.7}) {
    auto m = mid_profile_tracker(0.7);
    ASSERT_NE(m, nullptr);
    OnboardModels models;
    ASSERT_EQ(init_from_mission(models, m->mission), Status::kOk);
    TrackerOutput out;
    RelativeState s = m->state;
    ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    for (int i = 0; i < 3000; ++i) {
      s.drag_mps2 = K * models.drag_mps2(out.alpha_rad, s.altitude_m, s.velocity_mps);
      s.t_s += 0.1;
      ASSERT_EQ(m->tracker.step(s, 0.1, out), Status::kOk);
    }
    const auto& p = *m->profile;
    const double h_plan = p.taem_altitude_m;  // above the ellipsoid, as the mission's TAEM altitude
    const double half_width_m = kInnerBand * m->mission.taem.altitude_tol_m;
    const double lo = m->mission.taem.altitude_m - half_width_m - h_plan;
    const double hi = m->mission.taem.altitude_m + half_width_m - h_plan;
    const double k_exact = std::clamp(1.0, K * std::exp(-hi / kH_m), K * std::exp(-lo / kH_m));
    const double k = m->tracker.final_drag_factor();
    if (kH_m * std::fabs(std::log(K)) < half_width_m) {  // fits in the inner band: k = 1
      EXPECT_DOUBLE_EQ(k, 1.0);
      EXPECT_DOUBLE_EQ(k_exact, 1.0);
      continue;
    }
    EXPECT_NE(k, 1.0);
    EXPECT_NEAR(k, k_exact, std::fabs(K - 1.0) / 20.0 + 1e-3);
    EXPECT_GE(std::fabs(k - 1.0), std::fabs(k_exact - 1.0) - 1e-3);  // never outside the band
  }
}

// ------------------------------------------------------------------ synthetic terminal phase
// A plan of 101 points from E_t = 3 MJ/kg (terminal phase start) to E_f = 1 MJ/kg (TAEM), no
// TAEM altitude band (the final-drag factor is the sensed ratio K itself).
constexpr double kEt = 3.0e6, kEf = 1.0e6, kSpan = kEt - kEf;

struct SyntheticTerminal {
  OnboardModels models;  // not read without an altitude band
  TrackerParams params;
  ReferenceProfile profile;
  ReferenceTrack track;
  TerminalRangeControl control;
  template <class Drag>
  explicit SyntheticTerminal(Drag drag) {
    synthetic_profile(profile, 101, kEt, kEf, drag);
    track.init(params.q_ref_fraction);
    track.adopt(profile);
    control.init(models, params, TaemTarget{}, kEt, kEf);
  }
};

// int_0^U w(u) du for w = 1 - (1 - u)^2.
double weight_integral(double U) { return U - (1.0 - std::pow(1.0 - U, 3)) / 3.0; }

// Simpson's rule of f over [a, b] with n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n = 20000) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
  return sum * h / 3.0;
}

TEST(TerminalRange, WeightRisesFromZeroAtTaemToOneWithZeroSlopeAtThePhaseStart) {
  EXPECT_DOUBLE_EQ(terminal_weight(0.0), 0.0);
  EXPECT_DOUBLE_EQ(terminal_weight(1.0), 1.0);
  EXPECT_DOUBLE_EQ(terminal_weight(0.5), 0.75);
  const double h = 1e-6;
  EXPECT_NEAR((terminal_weight(1.0) - terminal_weight(1.0 - h)) / h, 0.0, 1e-5);  // flat at the start
  EXPECT_NEAR((terminal_weight(h) - terminal_weight(0.0)) / h, 2.0, 1e-5);         // 2 at TAEM
}

TEST(TerminalRange, RangeToTheProfileEndIsTheIntegralOfOneOverDrag) {
  const double e = 2.345e6, u = (e - kEf) / kSpan;
  {
    // Constant drag: S = (E - E_f) / D, dS/dc = -(span / D^2) int_0^u w.
    SyntheticTerminal t([](double) { return 10.0; });
    t.track.at(e);
    const TerminalRange r = t.control.range_to_profile_end(t.track, e, 10.0, 1.0);
    EXPECT_NEAR(r.range_m, (e - kEf) / 10.0, 1e-9 * r.range_m);
    const double sens = -kSpan / 100.0 * weight_integral(u);
    EXPECT_NEAR(r.sensitivity, sens, 1e-4 * std::fabs(sens));
  }
  {
    // Drag linear in energy, D = 5 + 1e-6 (E_t - E): S = 1e6 ln(D(E_f) / D(E)).
    auto drag = [](double en) { return 5.0 + 1e-6 * (kEt - en); };
    SyntheticTerminal t(drag);
    t.track.at(e);
    const TerminalRange r = t.control.range_to_profile_end(t.track, e, drag(e), 1.0);
    EXPECT_NEAR(r.range_m, 1e6 * std::log(drag(kEf) / drag(e)), 1e-5 * r.range_m);
    // With a final-drag factor k = 1.2 blended in as 1 + (k - 1)(1 - w): Simpson's rule.
    const double k = 1.2;
    auto scaled = [&](double en) { return drag(en) * (1.0 + (k - 1.0) * (1.0 - terminal_weight((en - kEf) / kSpan))); };
    const TerminalRange rk = t.control.range_to_profile_end(t.track, e, drag(e), k);
    EXPECT_NEAR(rk.range_m, simpson([&](double en) { return 1.0 / scaled(en); }, kEf, e), 1e-4 * rk.range_m);
    const double sens = -simpson([&](double en) { return terminal_weight((en - kEf) / kSpan) / (scaled(en) * scaled(en)); },
                                 kEf, e);
    EXPECT_NEAR(rk.sensitivity, sens, 1e-4 * std::fabs(sens));
  }
}

TEST(TerminalRange, IncrementSolvesTheLinearisedRangeToGo) {
  // Constant drag D = 10: the increment c w(E) must make the plan fly the distance to go less
  // the range a final reversal still adds: to first order c = (S_target - S0) / (dS/dc) with
  // dS/dc = -(span / D^2) int_0^u w, and the range flown with D + c w (Simpson) lands on the
  // target within the linearisation's second-order error.
  SyntheticTerminal t([](double) { return 10.0; });
  const double e = 2.5e6, u = (e - kEf) / kSpan;
  const double s0 = (e - kEf) / 10.0, extension = 2000.0;
  for (double stretch : {1.04, 0.97}) {
    const double along = stretch * s0, target = along - extension;
    RefPoint ref = t.track.at(e);
    const double c = t.control.shape_reference(ref, e, along, 1.0, t.track, 1e300, [&] { return extension; });
    const double c_linear = (target - s0) / (-kSpan / 100.0 * weight_integral(u));
    EXPECT_NEAR(c, c_linear, 1e-3 * std::fabs(c_linear)) << stretch;
    EXPECT_EQ(c < 0.0, stretch > 1.0) << stretch;  // longer range: less drag
    const double flown = simpson([&](double en) { return 1.0 / (10.0 + c * terminal_weight((en - kEf) / kSpan)); }, kEf, e);
    EXPECT_NEAR(flown, target, 0.1 * std::fabs(target - s0)) << stretch;
    EXPECT_NEAR(ref.drag, 10.0 + c * terminal_weight(u), 1e-12) << stretch;
  }
  // Bounded to 0.8 D; zero within 5 km of the aim point; never above the plan's bound.
  RefPoint ref = t.track.at(e);
  EXPECT_NEAR(t.control.shape_reference(ref, e, 3.0 * s0, 1.0, t.track, 1e300, [] { return 0.0; }), -8.0, 1e-12);
  ref = t.track.at(e);
  EXPECT_EQ(t.control.shape_reference(ref, e, 4000.0, 1.0, t.track, 1e300, [] { return 0.0; }), 0.0);
  EXPECT_EQ(ref.drag, 10.0);
  ref = t.track.at(e);
  t.control.shape_reference(ref, e, 0.8 * s0, 1.0, t.track, 10.5, [] { return 0.0; });
  EXPECT_NEAR(ref.drag, 10.5, 1e-12);
}

TEST(TerminalRange, ShapedReferenceCarriesTheEnergyDerivativesOfTheShapedDrag) {
  // Linear plan, sensed ratio K = 1.3 (no altitude band: k = K), no increment (within 5 km of
  // the aim point): the shaped drag D k_f(E) and its derivatives against central differences
  // in energy. With an increment c (held), D + c w: its derivatives c w', c w'' likewise.
  auto drag = [](double en) { return 5.0 + 1e-6 * (kEt - en); };
  SyntheticTerminal t(drag);
  auto shaped = [&](double en, double along, double K) {
    RefPoint r = t.track.at(en);
    t.control.shape_reference(r, en, along, K, t.track, 1e300, [] { return 0.0; });
    return r;
  };
  const double e = 2.2e6, h = 2e3;
  const RefPoint r = shaped(e, 1000.0, 1.3);
  const double d_plus = shaped(e + h, 1000.0, 1.3).drag, d_minus = shaped(e - h, 1000.0, 1.3).drag;
  EXPECT_NEAR(r.drag, drag(e) * (1.0 + 0.3 * (1.0 - terminal_weight((e - kEf) / kSpan))), 1e-12);
  EXPECT_NEAR(r.drag_prime, (d_plus - d_minus) / (2.0 * h), 1e-6 * std::fabs(r.drag_prime));
  EXPECT_NEAR(r.drag_second, (d_plus - 2.0 * r.drag + d_minus) / (h * h), 1e-4 * std::fabs(r.drag_second));
  // An increment: the shaped point minus the plan's is c w(E) and its derivatives c w', c w''.
  const RefPoint plain = t.track.at(e);
  RefPoint with_c = plain;
  const double c = t.control.shape_reference(with_c, e, 1.1 * (1e6 * std::log(drag(kEf) / drag(e))), 1.0, t.track,
                                             1e300, [] { return 0.0; });
  ASSERT_NE(c, 0.0);
  auto w = [](double en) { return terminal_weight((en - kEf) / kSpan); };
  EXPECT_NEAR(with_c.drag - plain.drag, c * w(e), 1e-12);
  EXPECT_NEAR(with_c.drag_prime - plain.drag_prime, c * (w(e + h) - w(e - h)) / (2.0 * h), 1e-6 * std::fabs(c / kSpan));
  EXPECT_NEAR(with_c.drag_second - plain.drag_second, c * (w(e + h) - 2.0 * w(e) + w(e - h)) / (h * h),
              1e-4 * std::fabs(c / (kSpan * kSpan)));
}

}  // namespace
}  // namespace reentry::fsw
