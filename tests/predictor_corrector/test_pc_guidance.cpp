// The predictor-corrector's path-constraint drag limit against the truth simulator's own
// constraint models: at the drag the law allows, the density it implies (D = rho V^2 C_D S / 2m)
// gives, through sim_truth's heat-flux model (Chapman (3.5) for the X-33, Betts's leading edge
// for the Orbiter), q = rho V^2 / 2, q alpha and the aerodynamic load hypot(L, D), values within
// the planned fraction of every limit, and one of them on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "guidance/mission_adapter.hpp"
#include "predictor_corrector/pc_guidance.hpp"
#include "reentry/config/mission.hpp"
#include "vehicle/heating.hpp"

namespace reentry::fsw {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Largest ratio of a constrained quantity to its planned limit at the drag the law allows.
double largest_limit_ratio(const config::Mission& m, const OnboardModels& models, const PcLimits& lim, double v_mps,
                           double alpha_rad) {
  const double mach = v_mps / 300.0;
  double cl = 0.0, cd = 0.0;
  models.aero().coefficients(alpha_rad, mach, cl, cd);
  const double d = constraint_drag_limit_mps2(models, lim, v_mps, alpha_rad, cl, cd);
  const double rho = 2.0 * d / (v_mps * v_mps * cd * models.area_over_mass());
  const double q = 0.5 * rho * v_mps * v_mps;
  double ratio = 0.0;
  if (lim.heat_flux_max_Wpm2 > 0.0) {
    const double qdot = truth::heat_flux_Wpm2(m.vehicle.heating_model, rho, v_mps, alpha_rad, m.vehicle.nose_radius_m);
    ratio = std::max(ratio, qdot / lim.heat_flux_max_Wpm2);
  }
  if (lim.q_max_Pa > 0.0) ratio = std::max(ratio, q / lim.q_max_Pa);
  if (lim.q_alpha_max_Pa_rad > 0.0) ratio = std::max(ratio, q * alpha_rad / lim.q_alpha_max_Pa_rad);
  if (lim.load_factor_max_mps2 > 0.0) {
    ratio = std::max(ratio, q * models.area_over_mass() * std::hypot(cl, cd) / lim.load_factor_max_mps2);
  }
  return ratio;
}

void expect_on_the_tightest_limit(const char* name) {
  const auto r = config::load_mission(name);
  ASSERT_TRUE(r.ok) << r.error;
  auto models = std::make_unique<OnboardModels>();
  ASSERT_EQ(init_from_mission(*models, r.mission), Status::kOk);
  const PcLimits lim = pc_limits_from(to_guidance_mission(r.mission).limits, 0.97, 0.0);
  for (double v : {7200.0, 6000.0, 4500.0, 3000.0, 1500.0}) {
    for (double alpha_deg : {15.0, 30.0, 40.0}) {
      EXPECT_NEAR(largest_limit_ratio(r.mission, *models, lim, v, alpha_deg * kDeg), 1.0, 1e-3)
          << name << " V " << v << " m/s alpha " << alpha_deg << " deg";
    }
  }
}

TEST(PcConstraintDragLimit, X33SitsOnItsTightestLimitByTheTruthModels) { expect_on_the_tightest_limit("x33"); }
TEST(PcConstraintDragLimit, OrbiterSitsOnItsTightestLimitByTheTruthModels) { expect_on_the_tightest_limit("orbiter"); }

// A lower margin lowers the allowed drag in proportion for the q-type limits and by the square
// of the margin for heat flux (q ~ sqrt(rho)).
TEST(PcConstraintDragLimit, HeatFluxLimitScalesWithTheSquareOfTheMargin) {
  const auto r = config::load_mission("x33");
  ASSERT_TRUE(r.ok) << r.error;
  auto models = std::make_unique<OnboardModels>();
  ASSERT_EQ(init_from_mission(*models, r.mission), Status::kOk);
  PathLimits heat_only;
  heat_only.heat_flux_max_Wpm2 = to_guidance_mission(r.mission).limits.heat_flux_max_Wpm2;
  double cl = 0.0, cd = 0.0;
  models->aero().coefficients(40.0 * kDeg, 20.0, cl, cd);
  const double d1 = constraint_drag_limit_mps2(*models, pc_limits_from(heat_only, 1.0, 0.0), 6000.0, 40.0 * kDeg, cl, cd);
  const double d2 = constraint_drag_limit_mps2(*models, pc_limits_from(heat_only, 0.8, 0.0), 6000.0, 40.0 * kDeg, cl, cd);
  EXPECT_NEAR(d2 / d1, 0.64, 1e-9);
}

// The C_D S/m knowledge: every drag-form limit (q, q alpha, heat flux) lowers its drag limit by
// the share u, so that a vehicle whose C_D S/m is u below the model's meets it at the drag sensed;
// the load factor, sensed directly, does not move.
TEST(PcConstraintDragLimit, DragUncertaintyLowersEveryDragFormLimitByItsShare) {
  const auto r = config::load_mission("x38");
  ASSERT_TRUE(r.ok) << r.error;
  auto models = std::make_unique<OnboardModels>();
  ASSERT_EQ(init_from_mission(*models, r.mission), Status::kOk);
  const PathLimits all = to_guidance_mission(r.mission).limits;
  double cl = 0.0, cd = 0.0;
  models->aero().coefficients(30.0 * kDeg, 8.0, cl, cd);
  auto only = [&](int which) {
    PathLimits l;
    if (which == 0) l.heat_flux_max_Wpm2 = all.heat_flux_max_Wpm2;
    if (which == 1) l.dynamic_pressure_max_Pa = all.dynamic_pressure_max_Pa;
    if (which == 2) l.q_alpha_max_Pa_rad = 300e3 / kDeg;
    if (which == 3) l.load_factor_max_g = all.load_factor_max_g;
    return l;
  };
  for (int which = 0; which < 4; ++which) {
    const double d0 = constraint_drag_limit_mps2(*models, pc_limits_from(only(which), 0.97, 0.0), 2500.0, 30.0 * kDeg, cl, cd);
    const double d1 = constraint_drag_limit_mps2(*models, pc_limits_from(only(which), 0.97, 0.1), 2500.0, 30.0 * kDeg, cl, cd);
    ASSERT_TRUE(d0 > 0.0 && d0 < 1e299) << which;
    EXPECT_NEAR(d1 / d0, which == 3 ? 1.0 : 0.9, 1e-12) << "limit " << which;
  }
}

// The constraint bound's least altitude rate holds the drag on its limit: with the drag at the
// limit, a descent at hdot_min through an exponential atmosphere (D ~ exp(-h / H) V^2) with the
// point-mass speed equation V' = -D - g sin(gamma) leaves the drag constant (d ln D / dt = 0 by
// the chain rule; without gravity's share the dive's drag grows by 2 g |hdot| / V^2 per second).
TEST(PcConstraintBound, LeastAltitudeRateHoldsTheDragOnItsLimitInADive) {
  PredictorCorrectorParams p;
  for (double v : {1200.0, 2500.0, 6000.0}) {
    BankLawInput in;
    in.velocity_mps = v;
    in.radius_m = kEarthRadius_m + 30e3;
    in.flight_path_rad = -5.0 * kDeg;
    in.drag_mps2 = 15.0;
    in.lift_mps2 = 13.0;
    in.drag_limit_mps2 = 15.0;
    in.drag_limit_rate_ps = 0.0;
    in.scale_height_m = 6500.0;
    in.sigma_base_rad = 60.0 * kDeg;
    const BankLawOutput out = bank_magnitude(in, p);
    const double hdot = out.hdot_min_mps;
    ASSERT_LT(hdot, 0.0) << v;
    const double g = gravity_mps2(in.radius_m);
    const double dt = 1e-4;
    const double h1 = hdot * dt;
    const double v1 = v + (-in.drag_mps2 - g * hdot / v) * dt;
    const double d1 = in.drag_mps2 * std::exp(-h1 / in.scale_height_m) * (v1 / v) * (v1 / v);
    EXPECT_NEAR(std::log(d1 / in.drag_mps2) / dt, 0.0, 1e-6) << "V " << v << " m/s, hdot_min " << hdot << " m/s";
  }
}

// Heat relief of a reversal's lowered alpha, against the truth simulator's heat-flux models: on
// the Orbiter (Betts's leading edge, heat flux rising as alpha falls) the alpha returned is the
// lowest whose heat flux stays within the limit, or within the unmodulated alpha's where that
// is above it; with the X-33's stagnation point (alpha-free, 3.5) the modulation is kept.
class PcHeatRelief : public ::testing::Test {
 protected:
  void load_models(const char* name) {
    const auto r = config::load_mission(name);
    ASSERT_TRUE(r.ok) << r.error;
    mission = r.mission;
    models = std::make_unique<OnboardModels>();
    ASSERT_EQ(init_from_mission(*models, mission), Status::kOk);
    lim = pc_limits_from(to_guidance_mission(mission).limits, 0.97, 0.0);
  }
  double truth_heat(double rho, double alpha_rad) const {
    return truth::heat_flux_Wpm2(mission.vehicle.heating_model, rho, kV_mps, alpha_rad, mission.vehicle.nose_radius_m);
  }
  // Density at which the truth's heat flux at alpha is `fraction` of the planned limit.
  double density_for(double fraction, double alpha_rad) const {
    const double per_sqrt_rho = truth_heat(1.0, alpha_rad);
    return std::pow(fraction * lim.heat_flux_max_Wpm2 / per_sqrt_rho, 2);
  }
  static constexpr double kV_mps = 6200.0;
  config::Mission mission;
  std::unique_ptr<OnboardModels> models;
  PcLimits lim;
};

TEST_F(PcHeatRelief, LowestAlphaWithinTheLimitOnTheLeadingEdge) {
  load_models("orbiter");
  const double alpha = 40.0 * kDeg, alpha_mod = 37.0 * kDeg;
  const double rho = density_for(0.99, alpha);
  ASSERT_GT(truth_heat(rho, alpha_mod), 1.01 * lim.heat_flux_max_Wpm2);  // the modulation alone exceeds it
  const double a = heat_relief_alpha_rad(*models, alpha_mod, alpha, rho, kV_mps, lim);
  EXPECT_GT(a, alpha_mod);
  EXPECT_LT(a, alpha);
  EXPECT_NEAR(truth_heat(rho, a) / lim.heat_flux_max_Wpm2, 1.0, 1e-3);
}

TEST_F(PcHeatRelief, AboveTheLimitAlreadyTheModulationAddsNoHeat) {
  load_models("orbiter");
  const double alpha = 40.0 * kDeg, alpha_mod = 37.0 * kDeg;
  const double rho = density_for(1.02, alpha);
  const double a = heat_relief_alpha_rad(*models, alpha_mod, alpha, rho, kV_mps, lim);
  EXPECT_NEAR(a, alpha, 0.01 * kDeg);
  EXPECT_LE(truth_heat(rho, a), truth_heat(rho, alpha) * (1.0 + 1e-4));
}

TEST_F(PcHeatRelief, WellBelowTheLimitTheModulationIsKept) {
  load_models("orbiter");
  const double rho = density_for(0.8, 40.0 * kDeg);
  EXPECT_EQ(heat_relief_alpha_rad(*models, 37.0 * kDeg, 40.0 * kDeg, rho, kV_mps, lim), 37.0 * kDeg);
}

TEST_F(PcHeatRelief, AnAlphaFreeHeatFluxKeepsTheModulation) {
  load_models("x33");
  const double rho = density_for(1.05, 40.0 * kDeg);
  EXPECT_DOUBLE_EQ(truth_heat(rho, 37.0 * kDeg), truth_heat(rho, 40.0 * kDeg));
  EXPECT_EQ(heat_relief_alpha_rad(*models, 37.0 * kDeg, 40.0 * kDeg, rho, kV_mps, lim), 37.0 * kDeg);
}

// The terminal phase flies its reversals unmodulated (modulation_in_terminal = 0): the phase is the
// terminal altitude law's own (modulation stops exactly where that law's weight starts to rise),
// and with the setting on, a reversal is modulated at every energy.
TEST(PcTerminalPhase, ReversalsAreModulatedExactlyOutsideTheTerminalAltitudeLaw) {
  PredictorCorrectorParams p;
  const TerminalAltitude terminal{4.0e5, 3.0e7, 25000.0};
  const double start = terminal.taem_energy_Jpkg + p.terminal_span_fraction * terminal.span_Jpkg;
  for (double e : {start + 1.0e4, start + 1.0, start - 1.0, start - 1.0e5, terminal.taem_energy_Jpkg + 1.0}) {
    p.modulation_in_terminal = 0;
    const bool in_terminal = terminal.at(e, 30000.0, 1200.0, 6.0, p).weight > 0.0;
    EXPECT_EQ(terminal.modulates(e, p), !in_terminal) << e - start;
    EXPECT_EQ(terminal.modulates(e, p), e > start) << e - start;
    p.modulation_in_terminal = 1;
    EXPECT_TRUE(terminal.modulates(e, p)) << e - start;
  }
  // No terminal phase (fraction 0): no terminal altitude law, so every reversal is modulated.
  p.modulation_in_terminal = 0;
  p.terminal_span_fraction = 0.0;
  for (double e : {terminal.taem_energy_Jpkg + 1.0, terminal.taem_energy_Jpkg + 1.0e6}) {
    EXPECT_FALSE(terminal.in_phase(e, p));
    EXPECT_EQ(terminal.at(e, 30000.0, 1200.0, 6.0, p).weight, 0.0);
    EXPECT_TRUE(terminal.modulates(e, p));
  }
}

// Capture guard timed by the plan: it waits while the plan's first reversal lies below the
// present energy, and not once that reversal is due, when the plan has none, or when it is off.
TEST(PcReversalTiming, TheCaptureGuardWaitsForThePlansReversal) {
  PredictorCorrectorParams p;
  p.capture_waits_for_plan = 1;
  PcLateral lateral;
  const double e_entry = 3.0e7, e_taem = 1.0e6, e = 0.5 * (e_entry + e_taem);
  lateral.init(p, TaemTarget{}, 2.0 * M_PI / 180.0, e_entry, e_taem);
  EXPECT_TRUE(lateral.capture_waits_for_plan(e, e - 1.0e6));
  EXPECT_FALSE(lateral.capture_waits_for_plan(e, e + 1.0e5)) << "the plan's reversal is due";
  EXPECT_FALSE(lateral.capture_waits_for_plan(e, 0.0)) << "the plan has no reversal";
  p.capture_waits_for_plan = 0;
  EXPECT_FALSE(lateral.capture_waits_for_plan(e, e - 1.0e6)) << "off";
}

// The wait holds the capture guard only. Out of the corridor on the side the bank turns to, the
// corridor reverses whether or not the guard waits. Farther than the guard's limit from the line
// and turning towards it (heading 10 deg into the line, 20 km off, V 5000 m/s, L 10 m/s2,
// |sigma| 60 deg: R = V^2 / (L sin 60) = 2887 km; a turn away started now stops
// R (1 - cos 10) + V (120 deg / (2 deg/s) + 1 s) sin 10 - 20 km = 76.8 km past the line, above the
// 15 km limit), the guard reverses unless it waits.
TEST(PcReversalTiming, TheWaitHoldsTheCaptureGuardNotTheCorridor) {
  const double deg = M_PI / 180.0;
  PredictorCorrectorParams p;
  PcLateral lateral;
  TaemTarget taem;
  taem.velocity_mps = 900.0;
  const double e_entry = 3.0e7, e_taem = 1.0e6;
  lateral.init(p, taem, 2.0 * deg, e_entry, e_taem);
  PcLateralInput in;
  in.energy_Jpkg = 0.5 * (e_entry + e_taem);  // corridor half-width 8 deg
  in.velocity_mps = 5000.0;
  in.drag_mps2 = 10.0;
  in.lift_mps2 = 10.0;
  in.sigma_mag_rad = 60.0 * deg;
  in.sigma_flown_rad = 60.0 * deg;
  ASSERT_GT(lateral.time_to_go_s(in), p.final_reversal_window * 2.0 * in.sigma_mag_rad / (2.0 * deg))
      << "outside the final window";
  // The side chosen from a right turn (sign +1), the guard waiting or not.
  const auto side_after = [&](const ArrivalGeometry& g, bool waits) {
    PcLateralState st;
    st.sign = 1;
    in.capture_waits = waits;
    lateral.decide(st, in, g);
    return st.sign;
  };
  // Corridor: turning right (sign +1), heading 20 deg right of the target heading, the line 5 km
  // to the left (inside the guard's limit).
  ArrivalGeometry corridor;
  corridor.cross_m = -5000.0;
  in.heading_rad = 20.0 * deg;
  for (bool waits : {false, true}) EXPECT_EQ(side_after(corridor, waits), -1) << "corridor, guard waits " << waits;
  // Capture guard: the line 20 km to the right, heading 10 deg into it on the target heading,
  // turning right.
  ArrivalGeometry capture;
  capture.cross_m = 20000.0;
  capture.target_heading_rad = 10.0 * deg;
  in.heading_rad = 10.0 * deg;
  for (bool waits : {false, true}) EXPECT_EQ(side_after(capture, waits), waits ? 1 : -1) << "guard, waits " << waits;
}

// The guard's limit grows with the distance to go along the line (capture_overshoot_range_fraction
// 0.01): 20 km off the line and turning into it (a 76.8 km overshoot, as above), the guard reverses
// 1000 km before the aim (limit 15 km) but not 3600 km before it (limit 36 km: 20 km off the line
// is not yet past it).
TEST(PcReversalTiming, TheCaptureGuardsLimitGrowsWithTheDistanceToGo) {
  const double deg = M_PI / 180.0;
  PredictorCorrectorParams p;
  p.capture_overshoot_range_fraction = 0.01;
  PcLateral lateral;
  TaemTarget taem;
  taem.velocity_mps = 900.0;
  lateral.init(p, taem, 2.0 * deg, 3.0e7, 1.0e6);
  PcLateralInput in;
  in.energy_Jpkg = 1.55e7;
  in.velocity_mps = 5000.0;
  in.drag_mps2 = 10.0;
  in.lift_mps2 = 10.0;
  in.sigma_mag_rad = 60.0 * deg;
  in.sigma_flown_rad = 60.0 * deg;
  in.heading_rad = 10.0 * deg;
  ArrivalGeometry g;
  g.cross_m = 20000.0;
  g.target_heading_rad = 10.0 * deg;
  for (double along_km : {1000.0, 3600.0}) {
    g.along_m = along_km * 1000.0;
    EXPECT_NEAR(lateral.capture_limit_m(g), std::fmax(15000.0, 10.0 * along_km), 1e-6) << along_km;
    PcLateralState st;
    st.sign = 1;
    lateral.decide(st, in, g);
    EXPECT_EQ(st.sign, along_km < 2000.0 ? -1 : 1) << along_km;
  }
}

}  // namespace
}  // namespace reentry::fsw
