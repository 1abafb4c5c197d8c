// Alpha planner (thesis ch. 6) against independent truths: the closed-form corridor heights of
// appendix B.1 for the exponential atmosphere, the equilibrium-glide equation (6.6) itself, a
// brute-force scan of the aero tables, the corridor limits and the thesis' HORUS intersection
// velocity (about 4.5 km/s, section 6.1.1).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "guidance/mission_adapter.hpp"
#include "alpha_planner/alpha_planner.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::fsw {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kRho0 = 1.225;
constexpr double kBeta = 1.0 / 7050.0;
constexpr double kMu = 3.986004418e14;
constexpr double kRe = 6378137.0;

// Analytic test aero, identical at both Mach columns (so the exponential-atmosphere heights are
// exactly the closed forms): Newtonian-like CL = 2 sin^2 a cos a, CD = 0.06 + 2 sin^3 a.
double test_cl(double a) { return 2.0 * std::sin(a) * std::sin(a) * std::cos(a); }
double test_cd(double a) { return 0.06 + 2.0 * std::pow(std::sin(a), 3); }

// X-33 numbers of thesis table 3.3 with the analytic aero above.
config::Mission analytic_x33() {
  config::Mission m;
  m.name = "x33_analytic";
  m.vehicle.mass_kg = 37650.0;
  m.vehicle.reference_area_m2 = 149.4;
  m.vehicle.nose_radius_m = 0.8;
  for (int i = 0; i <= 50; ++i) m.vehicle.aero.cl.alpha_rad.push_back(i * kDeg);
  m.vehicle.aero.cl.mach = {0.5, 40.0};
  for (double a : m.vehicle.aero.cl.alpha_rad) {
    for (int k = 0; k < 2; ++k) {
      m.vehicle.aero.cl.values.push_back(test_cl(a));
      m.vehicle.aero.cd.values.push_back(test_cd(a));
    }
  }
  m.vehicle.aero.cd.alpha_rad = m.vehicle.aero.cl.alpha_rad;
  m.vehicle.aero.cd.mach = m.vehicle.aero.cl.mach;
  m.entry.altitude_m = 120100.0;
  m.entry.velocity_mps = 7627.0;
  m.taem.altitude_m = 29400.0;
  m.taem.velocity_mps = 918.8;
  m.constraints.heat_flux_max_Wpm2 = 851739.5;
  m.constraints.load_factor_max_g = 3.0;
  m.constraints.q_alpha_max_Pa_rad = 5849.68;
  m.constraints.dynamic_pressure_max_Pa = 14364.08;
  m.constraints.alpha_max_rad = 50.0 * kDeg;
  m.constraints.alpha_rate_max_radps = 5.0 * kDeg;
  m.guidance.onboard_atmosphere = "exponential";
  return m;
}

// Closed forms of appendix B.1 (exponential atmosphere). Heights below the search box clamp to 0.
double clamp0(double h) { return h < 0.0 ? 0.0 : h; }
double heat_constant(double nose_radius_m) {  // C of (3.6) from (3.5), c1 = 1.06584e8, c2 = 3
  const double vc = std::sqrt(kMu / kRe);
  return 1.06584e8 / (std::sqrt(nose_radius_m) * std::sqrt(kRho0) * vc * vc * vc);
}
double h_heat_b7(double q_max, double c, double v) {  // (B.7)
  return clamp0(-1.0 / kBeta * std::log(q_max * q_max / (kRho0 * c * c * std::pow(v, 6.0))));
}
double h_load_b9(double n_max, double m, double s, double cl, double cd, double v) {  // (B.9)
  return clamp0(-1.0 / kBeta * std::log(n_max * m * 9.80665 / (0.5 * kRho0 * v * v * s * std::sqrt(cl * cl + cd * cd))));
}
double h_qalpha_b10(double qa_max, double alpha, double v) {  // (B.10)
  return clamp0(-1.0 / kBeta * std::log(qa_max / (0.5 * v * v * alpha * kRho0)));
}
double h_q_b11(double q_max, double v) {  // (B.11)
  return clamp0(-1.0 / kBeta * std::log(q_max / (0.5 * v * v * kRho0)));
}
// (B.4) with g and Vc^2 = g r taken at the height itself (the closed form assumes them constant).
double h_glide_b4(double m, double s, double cl, double v, double h_at) {
  const double r = kRe + h_at;
  const double g = kMu / (r * r);
  const double vc2 = g * r;
  return -1.0 / kBeta * std::log(m * g * (1.0 / (v * v) - 1.0 / vc2) / (0.5 * kRho0 * cl * s));
}

std::unique_ptr<AlphaPlanner> make_planner(const config::Mission& m) {
  auto p = std::make_unique<AlphaPlanner>();
  EXPECT_EQ(init_from_mission(*p, m), Status::kOk);
  return p;
}

TEST(AlphaPlannerCorridor, RootFoundHeightsEqualAppendixB1ClosedForms) {
  const config::Mission m = analytic_x33();
  auto planner = make_planner(m);
  const double c = heat_constant(m.vehicle.nose_radius_m);
  const double alpha = 30.0 * kDeg;  // a table node: the interpolated CL, CD equal the analytic ones
  const AlphaPlanner::AlphaLaw fixed{0.0, alpha};
  for (double v : {7500.0, 6500.0, 5000.0, 3500.0, 2000.0, 1000.0}) {
    double h = 0.0;
    ASSERT_EQ(planner->heat_flux_height(v, fixed, h), Status::kOk);
    EXPECT_NEAR(h, h_heat_b7(m.constraints.heat_flux_max_Wpm2, c, v), 1.0) << "V " << v;
    ASSERT_EQ(planner->dynamic_pressure_height(v, h), Status::kOk);
    EXPECT_NEAR(h, h_q_b11(m.constraints.dynamic_pressure_max_Pa, v), 1.0) << "V " << v;
    ASSERT_EQ(planner->q_alpha_height(v, fixed, h), Status::kOk);
    EXPECT_NEAR(h, h_qalpha_b10(m.constraints.q_alpha_max_Pa_rad, alpha, v), 1.0) << "V " << v;
    ASSERT_EQ(planner->load_factor_height(v, fixed, h), Status::kOk);
    EXPECT_NEAR(h, h_load_b9(3.0, m.vehicle.mass_kg, m.vehicle.reference_area_m2, test_cl(alpha), test_cd(alpha), v), 1.0)
        << "V " << v;
    ASSERT_EQ(planner->glide_height(v, fixed, h), Status::kOk);
    EXPECT_GT(h, 10000.0);
    EXPECT_NEAR(h, h_glide_b4(m.vehicle.mass_kg, m.vehicle.reference_area_m2, test_cl(alpha), v, h), 1.0) << "V " << v;
  }
  // (6.1): higher CL gives a higher equilibrium glide
  double h20 = 0.0, h40 = 0.0;
  ASSERT_EQ(planner->glide_height(5000.0, AlphaPlanner::AlphaLaw{0.0, 20.0 * kDeg}, h20), Status::kOk);
  ASSERT_EQ(planner->glide_height(5000.0, AlphaPlanner::AlphaLaw{0.0, 40.0 * kDeg}, h40), Status::kOk);
  EXPECT_GT(h40, h20 + 1000.0);
}

TEST(AlphaPlannerCorridor, UnconstrainedLimitGivesGroundHeight) {
  config::Mission m = analytic_x33();
  m.constraints.heat_flux_max_Wpm2 = config::kNotConstrained;
  auto planner = make_planner(m);
  double h = -1.0;
  ASSERT_EQ(planner->heat_flux_height(7000.0, AlphaPlanner::AlphaLaw{}, h), Status::kOk);
  EXPECT_EQ(h, 0.0);
}

// Brute-force scan of g over [0, alpha_max] with a 1e-5 rad step.
template <class G>
double brute_max(G&& g, double alpha_max, double& arg) {
  double best = -1e300;
  const int n = static_cast<int>(alpha_max / 1e-5);
  for (int i = 0; i <= n + 1; ++i) {  // the last sample is alpha_max itself
    const double a = std::fmin(i * 1e-5, alpha_max);
    const double v = g(a);
    if (v > best) {
      best = v;
      arg = a;
    }
  }
  return best;
}

void check_searches_against_scan(const AlphaPlanner& planner, double alpha_max, double mach) {
  const OnboardAero& aero = planner.models().aero();
  auto ld = [&](double a) { return aero.cl(a, mach) / aero.cd(a, mach); };
  auto cl = [&](double a) { return aero.cl(a, mach); };
  double arg_ld = 0.0, arg_cl = 0.0;
  const double best_ld = brute_max(ld, alpha_max, arg_ld);
  const double best_cl = brute_max(cl, alpha_max, arg_cl);
  const double a_ld = planner.alpha_ld_max_rad(mach);
  const double a_cl = planner.alpha_cl_max_rad(mach);
  // The search is at least as good as the 1e-5 rad scan and can beat it only by what the scan
  // misses between its samples (slopes are O(1) per rad): 1e-5 relative.
  EXPECT_GE(ld(a_ld), best_ld * (1.0 - 1e-12)) << "Mach " << mach;
  EXPECT_LE(ld(a_ld), best_ld * (1.0 + 1e-5)) << "Mach " << mach;
  EXPECT_NEAR(a_ld, arg_ld, 2e-5) << "Mach " << mach;
  EXPECT_GE(cl(a_cl), best_cl * (1.0 - 1e-12)) << "Mach " << mach;
  EXPECT_LE(cl(a_cl), best_cl * (1.0 + 1e-5)) << "Mach " << mach;
  EXPECT_NEAR(a_cl, arg_cl, 2e-5) << "Mach " << mach;
}

TEST(AlphaPlannerSearch, LiftToDragAndLiftMaximaAgreeWithBruteForceScan) {
  const config::Mission m = analytic_x33();
  auto planner = make_planner(m);
  for (double mach : {1.0, 5.0, 25.0}) check_searches_against_scan(*planner, m.constraints.alpha_max_rad, mach);
  // Newtonian-like CL = 2 sin^2 a cos a peaks at 54.7 deg, beyond alpha_max: CL max at alpha_max
  EXPECT_NEAR(planner->alpha_cl_max_rad(10.0), 50.0 * kDeg, 1e-9);
}

void check_plan_invariants(const AlphaPlanner& planner, const AlphaPlanResult& r, double alpha_max) {
  ASSERT_EQ(r.n_corridor, AlphaPlanResult::kGridPoints);
  EXPECT_EQ(r.closed_points, 0);
  EXPECT_EQ(r.violation_points, 0);
  for (int i = 0; i < r.n_corridor; ++i) {
    const AlphaCorridorPoint& p = r.corridor[i];
    const double mach = planner.models().mach(p.h_path_m, p.velocity_mps);
    const double a_ld = planner.alpha_ld_max_rad(mach);
    const double a_cl = planner.alpha_cl_max_rad(mach);
    EXPECT_GE(p.alpha_rad, a_ld - 1e-9) << "i " << i;
    EXPECT_LE(p.alpha_rad, a_cl + 1e-9) << "i " << i;
    EXPECT_LE(p.alpha_rad, alpha_max + 1e-12);
    EXPECT_GE(p.h_path_m, p.h_lower_m - 1e-6) << "i " << i;
    EXPECT_LE(p.h_path_m, p.h_glide_cl_max_m + 1e-6) << "i " << i;
  }
  ASSERT_GE(r.n_profile, 2);
  ASSERT_LE(r.n_profile, AlphaPlanResult::kProfileCapacity);
  for (int k = 1; k < r.n_profile; ++k) EXPECT_GT(r.profile_energy_norm[k], r.profile_energy_norm[k - 1]);
  EXPECT_LE(r.profile_energy_norm[r.n_profile - 1], 1.0);
  EXPECT_GT(r.profile_energy_norm[0], 0.0);
}

TEST(AlphaPlannerExtraction, ExtractedAlphaGivesEquilibriumGlideLift) {
  const config::Mission m = analytic_x33();
  auto planner = make_planner(m);
  AlphaPlanResult r;
  ASSERT_EQ(planner->plan(AlphaPlanParams{}, r), Status::kOk);
  int checked = 0;
  for (int i = 0; i < r.n_corridor; i += 7) {
    const AlphaCorridorPoint& p = r.corridor[i];
    if (p.extraction_clamped) continue;
    const double rad = kRe + p.h_path_m;
    const double needed = kMu / (rad * rad) - p.velocity_mps * p.velocity_mps / rad;  // L/m = g - V^2/r (6.6)
    const double lift = planner->models().lift_mps2(p.alpha_extracted_rad, p.h_path_m, p.velocity_mps);
    EXPECT_NEAR(lift, needed, 1e-6 * needed) << "V " << p.velocity_mps;
    ++checked;
  }
  EXPECT_GE(checked, 10);
  check_plan_invariants(*planner, r, m.constraints.alpha_max_rad);
}

TEST(AlphaPlannerParams, PercentagesOutsideRangeAreRejected) {
  auto planner = make_planner(analytic_x33());
  AlphaPlanResult r;
  AlphaPlanParams p;
  p.heating_pct = -1.0;
  EXPECT_EQ(planner->plan(p, r), Status::kInvalidInput);
  p = AlphaPlanParams{};
  p.ranging_pct = 100.5;
  EXPECT_EQ(planner->plan(p, r), Status::kInvalidInput);
  p = AlphaPlanParams{};
  p.ranging_pct = std::nan("");
  EXPECT_EQ(planner->plan(p, r), Status::kInvalidInput);
  p = AlphaPlanParams{};
  p.heating_switch_pct = 80.0;
  p.taem_switch_pct = 20.0;  // switch to alpha(L/D max) before leaving the heating phase
  EXPECT_EQ(planner->plan(p, r), Status::kInvalidInput);
  AlphaPlanner uninitialised;
  EXPECT_EQ(uninitialised.plan(AlphaPlanParams{}, r), Status::kInvalidInput);
}

TEST(AlphaPlannerParams, RangingPercentageOrdersTheProfile) {
  // Higher ranging percentage -> higher alpha in the ranging phase (thesis 6.2/6.3.1).
  auto planner = make_planner(analytic_x33());
  AlphaPlanResult low, high;
  AlphaPlanParams p;
  p.ranging_pct = 10.0;
  ASSERT_EQ(planner->plan(p, low), Status::kOk);
  p.ranging_pct = 90.0;
  ASSERT_EQ(planner->plan(p, high), Status::kOk);
  const int mid = AlphaPlanResult::kGridPoints / 2;
  EXPECT_GT(high.corridor[mid].alpha_rad, low.corridor[mid].alpha_rad + 5.0 * kDeg);
  EXPECT_GT(high.corridor[mid].h_path_m, low.corridor[mid].h_path_m);
}

config::Mission load(const std::string& name) {
  const config::LoadResult r = config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

TEST(AlphaPlannerMissions, DefaultParametersGiveFlyableProfilesForAllMissions) {
  for (const char* name : {"x33", "horus", "orbiter", "x38"}) {
    SCOPED_TRACE(name);
    const config::Mission m = load(name);
    auto planner = make_planner(m);
    AlphaPlanResult r;
    ASSERT_EQ(planner->plan(AlphaPlanParams{}, r), Status::kOk);
    check_plan_invariants(*planner, r, m.constraints.alpha_max_rad);
    // TAEM interface: alpha(L/D max) (thesis 6.1.1, method 2)
    const AlphaCorridorPoint& last = r.corridor[r.n_corridor - 1];
    EXPECT_NEAR(last.alpha_rad, planner->alpha_ld_max_rad(planner->models().mach(last.h_path_m, last.velocity_mps)), 1e-6);
    // the profile is usable as mission.alpha_profile
    AlphaProfile profile;
    EXPECT_EQ(profile.init(r.profile_energy_norm, r.profile_alpha_rad, r.n_profile), Status::kOk);
  }
}

TEST(AlphaPlannerMissions, X33ProfileIsMonotoneInEnergyAndWithinLimits) {
  const config::Mission m = load("x33");
  auto planner = make_planner(m);
  AlphaPlanResult r;
  ASSERT_EQ(planner->plan(AlphaPlanParams{}, r), Status::kOk);
  for (int k = 1; k < r.n_profile; ++k) {
    EXPECT_GE(r.profile_alpha_rad[k], r.profile_alpha_rad[k - 1] - 1e-12) << "k " << k;
    EXPECT_GE(r.profile_alpha_rad[k], 0.0);
    EXPECT_LE(r.profile_alpha_rad[k], m.constraints.alpha_max_rad);
  }
  check_searches_against_scan(*planner, m.constraints.alpha_max_rad, 2.01);
  check_searches_against_scan(*planner, m.constraints.alpha_max_rad, 8.0);
  check_searches_against_scan(*planner, m.constraints.alpha_max_rad, 20.0);
}

TEST(AlphaPlannerMissions, TaemMatchingRampStaysWithinTheAlphaRate) {
  // The ranging -> alpha(L/D max) transition is a ramp the vehicle can fly: along the
  // equilibrium glide the velocity falls at dV/dt = -D, so the alpha rate of the profile is
  // |d alpha / dV| D, which must stay below alpha_rate_max (the least dV of (6.12) is the
  // whole step flown at the rate limit). The ramp ends at alpha(L/D max) at V_taem + dV.
  for (const char* name : {"x33", "horus"}) {
    SCOPED_TRACE(name);
    const config::Mission m = load(name);
    auto planner = make_planner(m);
    AlphaPlanResult r;
    ASSERT_EQ(planner->plan(AlphaPlanParams{}, r), Status::kOk);
    int ramp_points = 0;
    double alpha_drop = 0.0;
    for (int i = 1; i < r.n_corridor; ++i) {
      const AlphaCorridorPoint& a = r.corridor[i - 1];
      const AlphaCorridorPoint& b = r.corridor[i];
      if (b.phase != AlphaPhase::kTaem) continue;
      ++ramp_points;
      alpha_drop += a.alpha_rad - b.alpha_rad;
      const double drag = planner->models().drag_mps2(b.alpha_rad, b.h_path_m, b.velocity_mps);
      const double rate = std::fabs((a.alpha_rad - b.alpha_rad) / (a.velocity_mps - b.velocity_mps)) * drag;
      EXPECT_LT(rate, m.constraints.alpha_rate_max_radps) << "V " << b.velocity_mps;
    }
    EXPECT_GE(ramp_points, 3);
    EXPECT_GT(alpha_drop, 5.0 * kDeg);  // a real transition, not a hold
  }
}

TEST(AlphaPlannerMissions, HorusHeatFluxDominatesDownToAboutFourAndAHalfKmPerSecond) {
  // Thesis 6.1.1 / fig. 6.6: "until about 4.5 km/s, the lower boundary of the corridor is
  // constrained by the heat flux" (exponential atmosphere).
  const config::Mission m = load("horus");
  auto planner = make_planner(m);
  AlphaPlanResult r;
  ASSERT_EQ(planner->plan(AlphaPlanParams{}, r), Status::kOk);
  EXPECT_NEAR(r.v_intersection_mps, 4500.0, 300.0);
}

TEST(AlphaPlannerMissions, TableAtmosphereHeightsSatisfyTheConstraintEquations) {
  config::Mission m = load("x33");
  m.guidance.onboard_atmosphere = "table";
  auto planner = make_planner(m);
  ASSERT_EQ(planner->models().atmosphere().kind(), AtmosphereKind::kTable);
  const OnboardModels& mod = planner->models();
  for (double v : {7000.0, 5000.0, 3000.0}) {
    double h = 0.0;
    ASSERT_EQ(planner->heat_flux_height(v, AlphaPlanner::AlphaLaw{}, h), Status::kOk);
    if (h > 0.0) {
      const double rho = mod.atmosphere().density_kgpm3(h);  // (3.6) with the models' C
      EXPECT_NEAR(mod.heat_flux_coefficient(0.0) * std::sqrt(rho) * v * v * v / m.constraints.heat_flux_max_Wpm2, 1.0, 1e-6);
    }
    ASSERT_EQ(planner->dynamic_pressure_height(v, h), Status::kOk);
    EXPECT_NEAR(0.5 * mod.atmosphere().density_kgpm3(h) * v * v / m.constraints.dynamic_pressure_max_Pa, 1.0, 1e-6);
    const AlphaPlanner::AlphaLaw law{1.0, -1.0};
    ASSERT_EQ(planner->glide_height(v, law, h), Status::kOk);
    const double rad = kRe + h;
    const double alpha = planner->alpha_cl_max_rad(mod.mach(h, v));
    const double lift = 0.5 * mod.atmosphere().density_kgpm3(h) * v * v * mod.aero().cl(alpha, mod.mach(h, v)) * mod.area_over_mass();
    EXPECT_NEAR(lift + v * v / rad, kMu / (rad * rad), 1e-6 * kMu / (rad * rad));  // (6.6)
  }
  AlphaPlanResult r;
  ASSERT_EQ(planner->plan(AlphaPlanParams{}, r), Status::kOk);
  check_plan_invariants(*planner, r, m.constraints.alpha_max_rad);
}

}  // namespace
}  // namespace reentry::fsw
