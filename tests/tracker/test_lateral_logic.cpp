// Lateral logic (lateral_logic.hpp) against independent truths: circular-arc and integral
// closed forms for the final-turn prediction, spherical trigonometry for the arrival-line
// geometry and the vector field onto it, the heading corridor and the final-reversal window
// written out by hand, and flown scenarios for the final, correction and capture-guard reversals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tracker_fixtures.hpp"

namespace reentry::fsw {
namespace {

using namespace test;

TEST(FinalTurn, ConstantBankFollowsTheCircularArc) {
  // Independent truth: at constant speed and bank the heading error grows at
  // w = L_h sin(sigma) / V and the cross-track offset follows the arc
  // y(T) = y0 + (V / w) (cos(psi0 + w T) - cos(psi0)).
  FinalTurnInput in;
  in.speed_mps = in.taem_speed_mps = 1500.0;
  in.t_go_s = 40.0;
  in.lift_horizontal_mps2 = 15.0;
  in.sigma_now_rad = in.sigma_end_rad = 60.0 * M_PI / 180.0;
  in.sigma_rate_radps = 5.0 * M_PI / 180.0;
  in.heading_err_rad = -0.2;
  in.cross_track_m = 3000.0;
  const double w = in.lift_horizontal_mps2 * std::sin(in.sigma_now_rad) / in.speed_mps;
  const FinalTurnState f = predict_final_turn(in);
  EXPECT_NEAR(f.heading_err_rad, -0.2 + w * 40.0, 1e-12);
  EXPECT_NEAR(f.cross_track_m, 3000.0 + in.speed_mps / w * (std::cos(-0.2 + w * 40.0) - std::cos(-0.2)), 1.0);
}

TEST(FinalTurn, DeceleratingTurnAndSymmetricReversalMatchTheirIntegrals) {
  // Constant bank, speed falling linearly from V0 to V_f over T: the heading turned is
  // (L_h sin(sigma) / a) ln(V0 / V_f), a = (V0 - V_f) / T.
  FinalTurnInput in;
  in.speed_mps = 1500.0;
  in.taem_speed_mps = 900.0;
  in.t_go_s = 50.0;
  in.lift_horizontal_mps2 = 15.0;
  in.sigma_now_rad = in.sigma_end_rad = -70.0 * M_PI / 180.0;
  in.sigma_rate_radps = 5.0 * M_PI / 180.0;
  const double a = (1500.0 - 900.0) / 50.0;
  const double turned = 15.0 * std::sin(in.sigma_now_rad) / a * std::log(1500.0 / 900.0);
  EXPECT_NEAR(predict_final_turn(in).heading_err_rad, turned, 1e-4 * std::fabs(turned));
  // A reversal from sigma0 to -sigma0 at the rate limit, after the lag, lasting the whole
  // time at constant speed: the bank is antisymmetric about the middle of the roll, so the
  // heading turned during the lag is all that remains.
  in.taem_speed_mps = in.speed_mps;
  in.sigma_now_rad = 60.0 * M_PI / 180.0;
  in.sigma_end_rad = -in.sigma_now_rad;
  in.roll_lag_s = 1.0;
  in.t_go_s = in.roll_lag_s + 2.0 * in.sigma_now_rad / in.sigma_rate_radps;
  const double lag_turn = 15.0 * std::sin(in.sigma_now_rad) / in.speed_mps * in.roll_lag_s;
  EXPECT_NEAR(predict_final_turn(in).heading_err_rad, lag_turn, 2e-3 * lag_turn);
  // Degenerate input leaves the state as it is.
  in.t_go_s = 0.0;
  in.heading_err_rad = 0.1;
  EXPECT_EQ(predict_final_turn(in).heading_err_rad, 0.1);
}

TEST(FinalTurn, OvershootIsTheCircularArcPastTheLine) {
  // Independent truth: approaching the line at psi0 from y0 and turning away at constant speed
  // and bank on a circle of radius R = V^2 / (L_h sin|sigma|), the vehicle runs
  // R (1 - cos psi0) towards the line until it is parallel to it: past the line by
  // R (1 - cos psi0) - |y0| when that is positive, not at all otherwise. Mirrored sides agree.
  for (const double side : {1.0, -1.0}) {
    FinalTurnInput in;
    in.speed_mps = in.taem_speed_mps = 2000.0;
    in.t_go_s = 40.0;  // turned 10 deg after 17.5 s: the extremum lies inside the prediction
    in.lift_horizontal_mps2 = 20.0 / std::sin(60.0 * M_PI / 180.0);
    in.sigma_now_rad = in.sigma_end_rad = -side * 60.0 * M_PI / 180.0;
    in.sigma_rate_radps = 5.0 * M_PI / 180.0;
    in.heading_err_rad = side * 10.0 * M_PI / 180.0;
    const double radius_m = in.speed_mps * in.speed_mps / 20.0;  // 200 km
    const double run_in_m = radius_m * (1.0 - std::cos(10.0 * M_PI / 180.0));
    in.cross_track_m = side * 1000.0;
    EXPECT_NEAR(predict_final_turn(in).overshoot_m, run_in_m - 1000.0, 5.0) << side;
    in.cross_track_m = side * (run_in_m + 1000.0);
    EXPECT_EQ(predict_final_turn(in).overshoot_m, 0.0) << side;
  }
}

TEST(LateralLogic, OneCorrectionReversalStopsAFinalTurnThatOvershoots) {
  // X-33 near TAEM (about 40 s to go at the planned drag, inside the final-reversal window of
  // two reversals at 5 deg/s) on the planned flight-path angle, on the arrival line (placed by
  // the spherical destination formula) at the distance where the range control asks for the
  // planned drag (the plan's range to go (C.2) plus the final reversal's range extension),
  // the sensed drag trimmed to the reference before each test, the flown bank rolling at the
  // rate limit. Turned 8 deg past the line in the direction of the bank: the final reversal
  // starts, alpha modulated below the profile. After it, 10 deg past the line the other way
  // (over-turned): one correction reversal, at the alpha of a twin that does not reverse (no
  // modulation seconds before TAEM); the twin, still 3 deg short of the line, keeps its bank.
  // A second overshoot gets no further reversal.
  auto m = mid_profile_tracker(0.0);
  ASSERT_NE(m, nullptr);
  const ReferenceProfile& p = *m->profile;
  const int k = profile_index_at_time_to_go(p, 30.0);
  ASSERT_GT(k, 0);
  const double range_to_go_m = profile_range_to_go_m(p, k);
  const config::TaemInterface& taem = m->mission.taem;
  const RelativeState s0 = level_state_on_profile(p, k);
  double line = 0.0;  // heading of the line at the vehicle: the azimuth from it to the aim point
  auto place = [&](RelativeState& st, double distance_m) { line = place_from_aim_point(taem, distance_m, 0.0, st); };
  TrackerOutput out;
  // Captured level (the pull-out done), then on the planned flight path, heading 5 deg short
  // of the line on the side the bank turns from.
  auto start = [&](EntryTracker& t, RelativeState& st, double distance_m) {
    place(st, distance_m);
    st.heading_rad = line;
    if (t.step(st, 0.1, out) != Status::kOk) return 0.0;
    const double sign = out.sigma_rad >= 0.0 ? 1.0 : -1.0;
    st.t_s += 0.1;
    st.flight_path_rad = p.gamma_rad[k];
    st.heading_rad = line - sign * 5.0 * kDeg;
    return t.step(st, 0.1, out) == Status::kOk ? sign : 0.0;
  };
  double distance_m = range_to_go_m;
  for (int i = 0; i < 100; ++i, distance_m *= 1.01) {
    EntryTracker probe = m->tracker;
    RelativeState st = s0;
    if (start(probe, st, distance_m) != 0.0 && out.drag_ref_mps2 < 1.02 * st.drag_mps2) break;
  }
  RelativeState s = s0;
  const double sign = start(m->tracker, s, distance_m);
  ASSERT_NE(sign, 0.0);
  ASSERT_EQ(out.phase, Phase::kTracking);
  ASSERT_NEAR(out.drag_ref_mps2, s.drag_mps2, 0.03 * s.drag_mps2);
  // One cycle: the bank flown rolls towards the command at the maximum rate, alpha follows
  // the command, the sensed drag follows the reference.
  const double roll_step_rad = m->mission.constraints.sigma_rate_max_radps * 0.1;
  double sigma_flown = out.sigma_rad;
  auto fly = [&](EntryTracker& t, RelativeState& st) {
    st.t_s += 0.1;
    t.set_flown_attitude(out.alpha_rad, sigma_flown);
    const Status status = t.step(st, 0.1, out);
    sigma_flown += std::clamp(out.sigma_rad - sigma_flown, -roll_step_rad, roll_step_rad);
    return status;
  };
  // The sensed drag trimmed to the reference (the drag loop balanced).
  auto trim = [&](EntryTracker& t, RelativeState& st) {
    for (int i = 0; i < 5; ++i) {
      st.drag_mps2 = out.drag_ref_mps2;
      st.lift_mps2 = out.drag_ref_mps2 * p.lift_over_drag[k];
      if (fly(t, st) != Status::kOk) return false;
    }
    return true;
  };
  ASSERT_TRUE(trim(m->tracker, s));
  ASSERT_EQ(out.phase, Phase::kTracking);
  const double alpha_profile = out.alpha_rad;
  auto fly_until_tracking = [&](EntryTracker& t, RelativeState& st) {
    for (int i = 0; i < 1000 && out.phase == Phase::kReversal; ++i) ASSERT_EQ(fly(t, st), Status::kOk);
    ASSERT_EQ(out.phase, Phase::kTracking);
  };
  const EntryTracker before_final = m->tracker;
  const RelativeState s_before_final = s;
  const double sigma_flown_before_final = sigma_flown;
  // Final reversal, modulated.
  s.heading_rad = line + sign * 8.0 * kDeg;
  ASSERT_EQ(fly(m->tracker, s), Status::kOk);
  ASSERT_EQ(out.phase, Phase::kReversal);
  EXPECT_LT(out.sigma_rad * sign, 0.0);
  EXPECT_LT(out.alpha_rad, alpha_profile - 0.5 * kDeg);
  fly_until_tracking(m->tracker, s);
  EXPECT_LT(out.sigma_rad * sign, 0.0);
  ASSERT_TRUE(trim(m->tracker, s));
  // Twin short of the line: no correction.
  EntryTracker twin = m->tracker;
  RelativeState short_of_line = s;
  short_of_line.heading_rad = line + sign * 3.0 * kDeg;
  ASSERT_EQ(fly(twin, short_of_line), Status::kOk);
  EXPECT_EQ(out.phase, Phase::kTracking);
  EXPECT_LT(out.sigma_rad * sign, 0.0);
  const double alpha_unmodulated = out.alpha_rad;
  // Over-turned: the correction reversal, at the twin's (unmodulated) alpha.
  s.heading_rad = line - sign * 10.0 * kDeg;
  ASSERT_EQ(fly(m->tracker, s), Status::kOk);
  ASSERT_EQ(out.phase, Phase::kReversal);
  EXPECT_GT(out.sigma_rad * sign, 0.0);
  EXPECT_EQ(out.alpha_rad, alpha_unmodulated);
  fly_until_tracking(m->tracker, s);
  EXPECT_GT(out.sigma_rad * sign, 0.0);
  // Overshooting again (now on the first side): no third reversal.
  s.heading_rad = line + sign * 10.0 * kDeg;
  for (int i = 0; i < 50; ++i) {
    ASSERT_EQ(fly(m->tracker, s), Status::kOk);
    EXPECT_EQ(out.phase, Phase::kTracking);
    EXPECT_GT(out.sigma_rad * sign, 0.0);
  }
  // Final reversal from a 90 deg bank (the sensed drag 40 % short: the loop asks for lift
  // down, which the final-reversal window stops at 90 deg), 30 deg past the line; the drag then back
  // on the reference, so that the loop's bank on the other side is smaller: the roll from the
  // bank flown at its start is over before the nominal duration 2 sigma0 / sigma_rate. Far
  // over-turned (60 deg: the turn left is large at this bank and time to go) as soon as the
  // flown bank has settled within 2 deg of the command, still inside the nominal duration:
  // the correction starts then.
  EntryTracker& t = m->tracker;
  t = before_final;
  s = s_before_final;
  sigma_flown = sigma_flown_before_final;
  const double drag_trimmed = s.drag_mps2;
  s.drag_mps2 *= 0.6;
  for (int i = 0; i < 100 && std::fabs(sigma_flown) < 89.9 * kDeg; ++i) ASSERT_EQ(fly(t, s), Status::kOk);
  ASSERT_GT(std::fabs(sigma_flown), 89.9 * kDeg);
  ASSERT_LE(std::fabs(out.sigma_rad), 90.0 * kDeg + 1e-9);  // no lift down in the final window
  ASSERT_EQ(out.phase, Phase::kTracking);
  s.heading_rad = line + sign * 30.0 * kDeg;
  ASSERT_EQ(fly(t, s), Status::kOk);
  ASSERT_EQ(out.phase, Phase::kReversal);
  s.drag_mps2 = drag_trimmed;
  for (int i = 0; i < 1000 && std::fabs(sigma_flown - out.sigma_rad) > 2.0 * kDeg; ++i) ASSERT_EQ(fly(t, s), Status::kOk);
  ASSERT_LT(out.sigma_rad * sign, 0.0);
  ASSERT_LT(std::fabs(out.sigma_rad), 80.0 * kDeg);  // a roll shorter than 2 sigma0
  ASSERT_EQ(out.phase, Phase::kReversal);  // still within the nominal duration
  s.heading_rad = line - sign * 60.0 * kDeg;
  ASSERT_EQ(fly(t, s), Status::kOk);
  EXPECT_GT(out.sigma_rad * sign, 0.0);
}

TEST(LateralLogic, CaptureGuardTurnsAwayBeforeTheLineIsOvershot) {
  // X-33 in the lateral corridor, 200 s before TAEM, 40 km off the arrival line on the side
  // its bank turns towards, on the plan's drag and flight path, the bank settled on the loop's
  // 34 deg (3.1 km/s, lift 13.2 m/s^2: turn radius V^2 / (L sin sigma) = 1270 km, shrinking
  // with V^2 as the speed falls to 0.9 km/s at TAEM). Approaching the line at 3 deg (shallower
  // than the heading target: the corridor keeps the turn towards the line) a turn away would
  // run in a few km: the bank is kept. Approaching 2.5 deg steeper than the target (inside the
  // corridor, at least 3 deg wide) the turn away, started after a 15 s reversal, would carry
  // the vehicle more than the guard's 15 km past the line: the tracker reverses now (without
  // the guard it keeps the bank: checked). Not when the loop banks lift down.
  auto m = mid_profile_tracker(0.0);
  ASSERT_NE(m, nullptr);
  const ReferenceProfile& p = *m->profile;
  const int k = profile_index_at_time_to_go(p, 200.0);
  ASSERT_GT(k, 0);
  const RelativeState s0 = level_state_on_profile(p, k);
  ASSERT_LT(s0.energy_Jpkg, m->tracker.terminal_energy_Jpkg());  // the corridor starts before the terminal phase
  const config::TaemInterface& taem = m->mission.taem;
  const double distance_m = profile_range_to_go_m(p, k), cross_track_m = 40000.0;
  constexpr double kDeg = M_PI / 180.0;
  double sign = 0.0;  // > 0: banked right
  auto approach = [&](double approach_rad, double drag_ratio, TrackerOutput& out) {
    EntryTracker t = m->tracker;
    RelativeState s = s0;
    s.drag_mps2 *= drag_ratio;
    s.lift_mps2 *= drag_ratio;
    // First cycle level on the line (captured, the pull-out done), then 30 s on the planned
    // flight path: the 10 s bank average settles on the loop's bank, below 90 deg (the guard
    // acts on lift-up turns only).
    s.heading_rad = place_from_aim_point(taem, distance_m, 0.0, s);
    ASSERT_EQ(t.step(s, 0.1, out), Status::kOk);
    ASSERT_EQ(out.phase, Phase::kTracking);
    s.flight_path_rad = p.gamma_rad[k];
    for (int i = 0; i < 300; ++i) {
      s.t_s += 0.1;
      t.set_flown_attitude(out.alpha_rad, out.sigma_rad);
      ASSERT_EQ(t.step(s, 0.1, out), Status::kOk);
    }
    ASSERT_EQ(out.phase, Phase::kTracking);
    ASSERT_EQ(out.sigma_d_rad < 85.0 * kDeg, drag_ratio == 1.0);
    sign = out.sigma_rad >= 0.0 ? 1.0 : -1.0;
    // Then 40 km off the line on the side the bank turns towards (y = R sin(offset), > 0 with
    // the line to the right; the line's heading there is the bearing to the aim point less
    // the offset), approaching it.
    const double offset = std::asin(sign * cross_track_m / distance_m);
    const double line = place_from_aim_point(taem, distance_m, offset, s) - offset;
    s.heading_rad = line + sign * approach_rad;
    s.t_s += 0.1;
    t.set_flown_attitude(out.alpha_rad, out.sigma_rad);
    ASSERT_EQ(t.step(s, 0.1, out), Status::kOk);
  };
  // The shallow approach, then one 2.5 deg steeper than the heading target found from it
  // (heading error to the target: sign (approach - target approach)).
  auto shallow_and_steep = [&](double drag_ratio, TrackerOutput& shallow, TrackerOutput& steep) {
    approach(3.0 * kDeg, drag_ratio, shallow);
    ASSERT_NE(sign, 0.0);
    const double target_rad = 3.0 * kDeg - sign * shallow.heading_err_rad;
    ASSERT_GT(target_rad, 10.0 * kDeg);
    approach(target_rad + 2.5 * kDeg, drag_ratio, steep);
    ASSERT_NEAR(steep.heading_err_rad, sign * 2.5 * kDeg, 0.1 * kDeg);
  };
  TrackerOutput shallow, steep;
  shallow_and_steep(1.0, shallow, steep);
  EXPECT_EQ(shallow.phase, Phase::kTracking);
  EXPECT_GT(shallow.sigma_rad * sign, 0.0);
  EXPECT_EQ(steep.phase, Phase::kReversal);
  EXPECT_LT(steep.sigma_rad * sign, 0.0);
  // The sensed drag 20 % short: the loop banks past 90 deg (lift down, diving for drag) and
  // the guard leaves the steep approach alone (a reversal from there rolls through wings
  // level for most of a minute).
  shallow_and_steep(0.8, shallow, steep);
  EXPECT_EQ(steep.phase, Phase::kTracking);
  EXPECT_GT(steep.sigma_rad * sign, 0.0);
}

// ------------------------------------------------------------------ arrival line and corridor
// Aim point on the equator at longitude 0, arrival heading north: the arrival line is the
// meridian through it. A vehicle x south of the aim point along the meridian and y east of it
// along the great circle perpendicular to the meridian there is placed by the spherical
// destination formula.
constexpr double kRate = 5.0 * kDeg;

TaemTarget equator_aim() {
  TaemTarget taem;
  taem.heading_rad = 0.0;
  taem.range_tol_m = 5000.0;
  taem.heading_tol_rad = 5.0 * kDeg;
  return taem;
}

// x: distance to go along the line; y: offset east of it (the line then lies to the left).
RelativeState beside_the_meridian(double x_m, double y_m, double speed_mps, double lift_mps2) {
  const double a = x_m / kEarthRadius_m, b = y_m / kEarthRadius_m;
  // Point at arc b east of the meridian point at latitude -a: the perpendicular great circle
  // leaves heading east (90 deg); spherical destination formula.
  RelativeState s{};
  s.latitude_rad = std::asin(std::sin(-a) * std::cos(b));
  s.longitude_rad = std::atan2(std::sin(b) * std::cos(-a), std::cos(b) - std::sin(-a) * std::sin(s.latitude_rad));
  s.radius_m = kEarthRadius_m + 40000.0;
  s.altitude_m = 40000.0;
  s.velocity_mps = speed_mps;
  s.lift_mps2 = lift_mps2;
  s.drag_mps2 = lift_mps2;
  return s;
}

TEST(LateralLogic, ArrivalLineGeometryAndTheVectorFieldOntoIt) {
  const TrackerParams params;
  LateralLogic lateral;
  lateral.init(params, equator_aim(), kRate, 0.1, 0.4);
  for (double y : {-20000.0, 30000.0, 100000.0}) {
    const double x = 200000.0;
    const RelativeState s = beside_the_meridian(x, y, 3000.0, 10.0);
    const ArrivalLineTarget t = lateral.arrival_line_target(s);
    // Spherical truths: the perpendicular distance to the meridian, the distance along it.
    const double d_perp = kEarthRadius_m * std::asin(std::cos(s.latitude_rad) * std::sin(s.longitude_rad));
    const double along = -kEarthRadius_m * std::atan2(std::sin(s.latitude_rad), std::cos(s.latitude_rad) * std::cos(s.longitude_rad));
    EXPECT_NEAR(d_perp, y, 1e-6) << y;
    EXPECT_NEAR(along, x, 1e-6) << y;
    EXPECT_NEAR(t.cross_track_m, -y, 2e-3 * std::fabs(y)) << y;  // > 0: the line to the right
    EXPECT_NEAR(t.along_track_m, x, 2e-3 * x) << y;
    EXPECT_NEAR(t.range_m, kEarthRadius_m * std::acos(std::cos(s.latitude_rad) * std::cos(s.longitude_rad)), 1e-3) << y;
    EXPECT_NEAR(std::remainder(t.line_heading_rad, 2.0 * M_PI), 0.0, 0.05 * kDeg) << y;  // the meridian runs north
    // No bank flown yet: the field alone, 45 deg (2/pi) atan(|y| / 30 km) towards the line.
    const double approach = params.approach_angle_max_rad * (2.0 / M_PI) * std::atan(std::fabs(y) / params.cross_track_scale_m);
    EXPECT_NEAR(t.heading_rad, y > 0.0 ? -approach : approach, 0.05 * kDeg) << y;
  }
  // At y = y_s the field asks for half its largest angle.
  EXPECT_NEAR(lateral.arrival_line_target(beside_the_meridian(200000.0, 30000.0, 3000.0, 10.0)).heading_rad,
              -22.5 * kDeg, 0.05 * kDeg);
  // With a mean bank of 60 deg the approach is also bounded by the turn the vehicle can make,
  // sqrt(2 k |y| / R_turn), R_turn = V^2 / (L sin 60 deg) = 1039 km at 3 km/s and 10 m/s^2.
  LateralInput in;
  const RelativeState far = beside_the_meridian(200000.0, 100000.0, 3000.0, 10.0);
  in.state = &far;
  in.sigma_d_rad = 60.0 * kDeg;
  in.dt_s = 0.1;
  lateral.decide(in);
  ASSERT_NEAR(lateral.mean_bank_rad(), 60.0 * kDeg, 1e-12);
  const double r_turn = 3000.0 * 3000.0 / (10.0 * std::sin(60.0 * kDeg));
  const double bound = std::sqrt(2.0 * params.approach_turn_factor * 100000.0 / r_turn);
  ASSERT_LT(bound, params.approach_angle_max_rad * (2.0 / M_PI) * std::atan(100000.0 / params.cross_track_scale_m));
  EXPECT_NEAR(lateral.arrival_line_target(far).heading_rad, -bound, 0.05 * kDeg);
}

// One corridor-phase decision with the vehicle heading err_deg off a target heading of 0,
// on the line (no capture guard), far from TAEM (no final-reversal window).
int corridor_decision(int last_sign, double e_norm, double err_deg, bool reversing = false) {
  const TrackerParams params;
  LateralLogic lateral;
  lateral.init(params, equator_aim(), kRate, 0.1, 0.4);
  lateral.commit_sign(last_sign);
  RelativeState s = beside_the_meridian(500000.0, 0.0, 3000.0, 10.0);
  s.heading_rad = err_deg * kDeg;
  LateralInput in;
  in.state = &s;
  in.target.heading_rad = 0.0;
  in.corridor_phase = true;
  in.plan_sign = -last_sign;  // the plan's sign is not the corridor's
  in.e_norm = e_norm;
  in.sigma_d_rad = 50.0 * kDeg;
  in.dt_s = 0.1;
  in.t_go_s = 1000.0;
  in.reversing = reversing;
  const LateralDecision d = lateral.decide(in);
  EXPECT_TRUE(d.heading_err_valid);
  EXPECT_NEAR(d.heading_err_rad, err_deg * kDeg, 1e-12);
  return d.sign;
}

TEST(LateralLogic, HeadingCorridorReversesOnlyPastItsHalfWidthWhichNarrowsTowardsTaem) {
  // Corridor from E/E_entry = 0.4 (6 deg) narrowing linearly to 3 deg at TAEM (0.1): 4.5 deg
  // half-way. Banked right (+1), the vehicle turns right: past +half-width it reverses to the
  // left; banked left, past -half-width to the right; inside, the sign is kept.
  struct Case { double e_norm, half_width_deg; };
  for (const Case c : {Case{0.25, 4.5}, Case{0.4, 6.0}, Case{0.1, 3.0}, Case{0.05, 3.0}, Case{0.6, 6.0}}) {
    EXPECT_EQ(corridor_decision(1, c.e_norm, c.half_width_deg - 0.05), 1) << c.e_norm;
    EXPECT_EQ(corridor_decision(1, c.e_norm, c.half_width_deg + 0.05), -1) << c.e_norm;
    EXPECT_EQ(corridor_decision(-1, c.e_norm, -(c.half_width_deg - 0.05)), -1) << c.e_norm;
    EXPECT_EQ(corridor_decision(-1, c.e_norm, -(c.half_width_deg + 0.05)), 1) << c.e_norm;
    // Past the edge on the side the bank already turns away from: kept.
    EXPECT_EQ(corridor_decision(1, c.e_norm, -(c.half_width_deg + 5.0)), 1) << c.e_norm;
    EXPECT_EQ(corridor_decision(-1, c.e_norm, c.half_width_deg + 5.0), -1) << c.e_norm;
  }
  // No new reversal while one is flown.
  EXPECT_EQ(corridor_decision(1, 0.25, 20.0, true), 1);
}

TEST(LateralLogic, FinalReversalWindowIsTwoReversalTimesAtTheMeanBank) {
  // Window: the last final_reversal_window (2) reversal durations 2 sigma_mean / rate before
  // TAEM; sigma_mean 50 deg at 5 deg/s: 40 s.
  const TrackerParams params;
  LateralLogic lateral;
  lateral.init(params, equator_aim(), kRate, 0.1, 0.4);
  EXPECT_FALSE(lateral.in_final_reversal_window(1.0));  // no mean bank yet
  const RelativeState s = beside_the_meridian(500000.0, 0.0, 3000.0, 10.0);
  LateralInput in;
  in.state = &s;
  in.sigma_d_rad = 50.0 * kDeg;
  in.dt_s = 0.1;
  lateral.decide(in);
  EXPECT_TRUE(lateral.in_final_reversal_window(39.9));
  EXPECT_FALSE(lateral.in_final_reversal_window(40.1));
  // The mean bank follows the commanded magnitude with a 10 s time constant: after 10 s of
  // 30 deg, 30 + 20 exp(-1) deg (first order, to the discretisation of 0.1 s steps).
  in.sigma_d_rad = 30.0 * kDeg;
  for (int i = 0; i < 100; ++i) lateral.decide(in);
  EXPECT_NEAR(lateral.mean_bank_rad(), (30.0 + 20.0 * std::exp(-1.0)) * kDeg, 0.05 * kDeg);
}

}  // namespace
}  // namespace reentry::fsw
