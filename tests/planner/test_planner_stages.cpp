// Planner stages, each against values computed here independently of the stage's own formula:
// constraint drags by their defining relations (7.3)-(7.7), breakpoints on a hand-built
// corridor, the fit clipped to a corridor maximum with known derivatives, r(E) and gamma(E)
// (7.13)-(7.14) on an exponential atmosphere, the reversal ramp and span of method 3 (§7.4),
// the reversal search against the root of the planar turn problem, the length update (7.22)
// on an affine range law, and the mission geometry against the thesis's HORUS numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <reentry/config/mission.hpp>

#include "guidance/mission_adapter.hpp"
#include "models/onboard_models.hpp"
#include "planner/drag_corridor.hpp"
#include "planner/entry_planner.hpp"
#include "planner/length_iteration.hpp"
#include "planner/profile_fit.hpp"
#include "planner/ranging_alpha.hpp"
#include "planner/reduced_order.hpp"
#include "planner/reversal_search.hpp"
#include "planner/trajectory_extraction.hpp"

using namespace reentry;
using namespace reentry::fsw;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr int kN = kPlannerGrid;

// A vehicle with constant CL, CD (any alpha, any Mach) in the exponential atmosphere (7.15).
struct SimpleVehicle {
  double mass_kg = 30000.0, area_m2 = 100.0, nose_m = 0.8, cl = 0.8, cd = 0.5;
  std::unique_ptr<OnboardModels> models = std::make_unique<OnboardModels>();
  SimpleVehicle() {
    EXPECT_EQ(models->init_vehicle(mass_kg, area_m2, nose_m, HeatFluxModel::kChapmanStagnation), Status::kOk);
    EXPECT_EQ(models->atmosphere().init_exponential(), Status::kOk);
    const double alpha[2] = {0.0, 1.0}, mach[2] = {0.0, 40.0};
    const double cls[4] = {cl, cl, cl, cl}, cds[4] = {cd, cd, cd, cd};
    EXPECT_EQ(models->aero().init(alpha, 2, mach, 2, cls, cds), Status::kOk);
  }
  double s_over_m() const { return area_m2 / mass_kg; }
};

// Energy grid, uniform from e0 down to ef, alpha constant.
std::unique_ptr<EnergyGrid> uniform_grid(double e0, double ef, double alpha_rad) {
  auto g = std::make_unique<EnergyGrid>();
  for (int k = 0; k < kN; ++k) {
    g->energy_Jpkg[k] = e0 + (ef - e0) * k / (kN - 1);
    g->alpha_rad[k] = alpha_rad;
    g->alpha_profile_rad[k] = alpha_rad;
  }
  return g;
}

}  // namespace

// ---------------------------------------------------------------- stage 1: corridor
TEST(DragCorridorStage, BoundsSatisfyTheirDefiningRelations) {
  // Each constraint drag, turned back into the quantity it bounds through D = rho V^2 CD S/(2m)
  // (D.1), gives the limit: heat flux (3.6) at the density of that drag, q alpha, the body-axis
  // load (L cos(alpha) + D sin(alpha)) / g, q; and Lmin CL/CD = g - V^2/r (7.7). The floor adds
  // the Earth-rate term of (2.45) on an eastbound equatorial track: -2 omega V.
  SimpleVehicle veh;
  const OnboardModels& models = *veh.models;
  auto grid = uniform_grid(3.0e7, 1.0e6, 30.0 * kDeg);
  auto radius = std::make_unique<GridValues>();
  for (int k = 0; k < kN; ++k) (*radius)[k] = kEarthRadius_m + 80000.0 - 50000.0 * k / (kN - 1);
  PlannerParams params;
  PlannerMission mission;
  mission.taem_energy_Jpkg = 1.0e6;
  mission.limits = CorridorLimits{500e3, 200e3 * kDeg, 2.5 * kG0_mps2, 15e3};
  const CorridorStageInput in{models, *grid, params, mission, TrackEnds{0.0, 0.0, 0.0, 60.0 * kDeg}, 3.0e7, 0.0};
  auto c = std::make_unique<DragCorridor>();
  corridor_bounds(in, *radius, *c);
  const double alpha = 30.0 * kDeg;
  int active[4] = {0, 0, 0, 0};
  for (int k = 0; k < kN; k += 25) {
    const double r = (*radius)[k], v = velocity_from_energy_mps(grid->energy_Jpkg[k], r);
    const double q_of = 1.0 / (veh.cd * veh.s_over_m());  // q = D / (CD S / m)
    const double d_heat = c->heat_flux_mps2[k];
    const double rho_heat = 2.0 * d_heat * q_of / (v * v);
    EXPECT_NEAR(models.heat_flux_Wpm2(rho_heat, v, alpha) / 500e3, 1.0, 1e-12) << k;
    EXPECT_NEAR(c->q_alpha_mps2[k] * q_of * alpha / (200e3 * kDeg), 1.0, 1e-12) << k;
    // Body-axis load at the drag of (7.5): lift from the same dynamic pressure, L = q CL S / m.
    const double d_load = load_factor_drag_mps2(2.5 * kG0_mps2, veh.cl, veh.cd, alpha);
    const double lift_at_load = d_load * q_of * veh.cl * veh.s_over_m();
    EXPECT_NEAR((lift_at_load * std::cos(alpha) + d_load * std::sin(alpha)) / (2.5 * kG0_mps2), 1.0, 1e-12);
    const double d_q = dynamic_pressure_drag_mps2(15e3, veh.cd, veh.s_over_m());
    EXPECT_NEAR(d_q * q_of / 15e3, 1.0, 1e-12);
    const double expected_max = std::fmin(std::fmin(d_heat, c->q_alpha_mps2[k]), std::fmin(d_load, d_q));
    EXPECT_DOUBLE_EQ(c->max_mps2[k], expected_max) << k;
    active[expected_max == d_heat ? 0 : expected_max == c->q_alpha_mps2[k] ? 1 : expected_max == d_load ? 2 : 3]++;
    const double lift_need = gravity_mps2(r) - v * v / r;
    EXPECT_NEAR(c->min_mps2[k] * veh.cl / veh.cd, lift_need, 1e-12 * std::fabs(lift_need) + 1e-15) << k;
    EXPECT_NEAR(c->floor_mps2[k] * veh.cl / veh.cd, lift_need - 2.0 * kEarthRate_radps * v, 1e-9) << k;
  }
  // The chosen points exercise more than one active constraint.
  EXPECT_GT((active[0] > 0) + (active[1] > 0) + (active[2] > 0) + (active[3] > 0), 1);
}

TEST(DragCorridorStage, ActiveLimitIgnoresANonPositiveLoadBound) {
  EXPECT_EQ(active_drag_limit_mps2({5.0, 7.0, 3.0, 9.0}), 3.0);
  EXPECT_EQ(active_drag_limit_mps2({5.0, 4.0, 6.0, 9.0}), 4.0);
  EXPECT_EQ(active_drag_limit_mps2({5.0, 7.0, -1.0, 9.0}), 5.0);  // lift and drag cancel in the body axis
  EXPECT_EQ(active_drag_limit_mps2({5.0, 7.0, 6.0, 2.0}), 2.0);
  EXPECT_EQ(q_alpha_drag_mps2(1e5, 0.5, 1e-3, 0.0), kUnconstrained);  // (7.4) does not bound at zero alpha
}

TEST(DragCorridorStage, BreakpointsFromACorridorBuiltByHand) {
  // D_heat - D_qalpha = (Ex - E) / 1e6 changes sign at Ex (falling energy: from - to +), and
  // Lmin peaks at Em below it: E1 = Ex, E2 = Em (on the grid). Without a crossing E1 is 30 % of
  // the span below E0, clamped; E2 stays at least 2 % of the span from E1 and TAEM.
  const double e0 = 3.0e7, ef = 1.0e6, span = e0 - ef;
  auto grid = uniform_grid(e0, ef, 0.5);
  auto c = std::make_unique<DragCorridor>();
  const double ex = 1.83e7;
  const int km = 150;
  const double em = grid->energy_Jpkg[km];
  for (int k = 0; k < kN; ++k) {
    const double e = grid->energy_Jpkg[k];
    c->q_alpha_mps2[k] = 10.0;
    c->heat_flux_mps2[k] = 10.0 - (e - ex) / 1e6;
    c->min_mps2[k] = 2.0 - std::fabs(e - em) / 1e7;
  }
  const PlannerParams p;
  Breakpoints b = profile_breakpoints(*grid, *c, e0, ef, p);
  EXPECT_NEAR(b.e1_Jpkg, ex, 1e-6 * ex);
  EXPECT_DOUBLE_EQ(b.e2_Jpkg, em);
  for (int k = 0; k < kN; ++k) c->heat_flux_mps2[k] = 1.0;  // heat flux everywhere below q alpha: no crossing
  b = profile_breakpoints(*grid, *c, e0, ef, p);
  EXPECT_DOUBLE_EQ(b.e1_Jpkg, e0 - 0.3 * span);
  for (int k = 0; k < kN; ++k) c->min_mps2[k] = 1.0 + grid->energy_Jpkg[k] / 1e9;  // Lmin rising to E1: E2 held off E1
  b = profile_breakpoints(*grid, *c, e0, ef, p);
  EXPECT_DOUBLE_EQ(b.e2_Jpkg, b.e1_Jpkg - 0.02 * span);
}

// ---------------------------------------------------------------- stage 2: profile fit
TEST(ProfileFitStage, FollowsAQuadraticCorridorMaximumWithItsDerivatives) {
  // Dmax(E) = c0 + c1 E + c2 E^2 on a uniform grid: where the three-segment profile lies above
  // it, D = Dmax, D' = c1 + 2 c2 E and D'' = 2 c2 (central differences are exact for a quadratic
  // on a uniform grid, up to rounding); elsewhere D is the fitted profile with D'' = 0.
  const double e0 = 3.0e7, ef = 1.0e6;
  auto grid = uniform_grid(e0, ef, 0.5);
  auto dmax = std::make_unique<GridValues>();
  const double c0 = 1.0, c1 = 4e-7, c2 = 1e-14;
  for (int k = 0; k < kN; ++k) {
    const double e = grid->energy_Jpkg[k];
    (*dmax)[k] = c0 + c1 * e + c2 * e * e;
  }
  const ProfileFitInput in{DragProfileKind::kThreeSegment, 5.0e6, e0, 2.0e7, 6.0e6, ef, 0.5, 8.0, grid->energy_Jpkg, *dmax};
  auto out = std::make_unique<PlannedDrag>();
  ASSERT_EQ(fit_drag_profile(in, *out), Status::kOk);
  ThreeSegmentProfile p{e0, 2.0e7, 6.0e6, ef, 0.5, out->level_mps2, 8.0};
  EXPECT_NEAR(p.length_m(), 5.0e6, 1.0);  // the level flies the length (7.11)
  int clipped = 0;
  for (int k = 0; k < kN; ++k) {
    const double e = grid->energy_Jpkg[k];
    if (p.drag(e) > (*dmax)[k]) {
      ++clipped;
      EXPECT_EQ(out->drag_mps2[k], (*dmax)[k]) << k;
      if (k == 0 || k + 1 == kN) continue;  // one-sided differences at the ends
      EXPECT_NEAR(out->drag_prime[k], c1 + 2.0 * c2 * e, 1e-9 * c1) << k;
      EXPECT_NEAR(out->drag_second[k], 2.0 * c2, 1e-4 * c2) << k;
    } else {
      EXPECT_EQ(out->drag_mps2[k], p.drag(e)) << k;
      EXPECT_EQ(out->drag_second[k], 0.0) << k;
    }
  }
  EXPECT_GT(clipped, 10);
  EXPECT_EQ(out->clipped_points, clipped);
  EXPECT_FALSE(out->level_at_max);
}

// ---------------------------------------------------------------- stage 3: extraction
TEST(TrajectoryExtractionStage, RadiusAndFlightPathOnAnExponentialAtmosphere) {
  // Drag profile of a trajectory whose altitude falls linearly with energy, h(E) = h0 + c (E - E0),
  // constant CD, exponential atmosphere: D = rho0 exp(-beta h) V^2 CD S / (2 m) with
  // V^2 = 2 (E + mu/r - mu/R), D' by hand. Extraction must give back h(E) (the closed form
  // h = ln(rho0 V^2 CD S / (2 m D)) / beta at the extracted V) and, by kinematics
  // (dr/dE = -sin(gamma) / D), sin(gamma) = -D c.
  SimpleVehicle veh;
  const double e0 = 2.5e7, ef = 2.0e6, h0 = 75000.0, hf = 30000.0;
  const double c = (hf - h0) / (ef - e0);
  auto grid = uniform_grid(e0, ef, 0.5);
  auto drag = std::make_unique<PlannedDrag>();
  const double beta = OnboardAtmosphere::kBeta_pm, rho0 = OnboardAtmosphere::kRho0_kgpm3;
  for (int k = 0; k < kN; ++k) {
    const double e = grid->energy_Jpkg[k], h = h0 + c * (e - e0), r = kEarthRadius_m + h;
    const double v2 = 2.0 * (e + kMuEarth_m3ps2 / r - kMuEarth_m3ps2 / kEarthRadius_m);
    const double d = 0.5 * rho0 * std::exp(-beta * h) * v2 * veh.cd * veh.s_over_m();
    const double dv2_de = 2.0 * (1.0 - kMuEarth_m3ps2 / (r * r) * c);
    drag->drag_mps2[k] = d;
    drag->drag_prime[k] = d * (-beta * c + dv2_de / v2);
  }
  auto radius = std::make_unique<GridValues>();
  auto out = std::make_unique<ExtractedTrajectory>();
  ASSERT_EQ(extract_trajectory(ExtractionInput{*veh.models, *grid, *drag}, *radius, *out), Status::kOk);
  for (int k = 0; k < kN; ++k) {
    const double e = grid->energy_Jpkg[k], h = (*radius)[k] - kEarthRadius_m, d = drag->drag_mps2[k];
    EXPECT_NEAR(h, h0 + c * (e - e0), 0.1) << k;
    const double v = out->velocity_mps[k];
    const double h_closed = std::log(rho0 * v * v * veh.cd * veh.s_over_m() / (2.0 * d)) / beta;
    EXPECT_NEAR(h, h_closed, 0.1) << k;
    EXPECT_NEAR(std::sin(out->gamma_rad[k]), -d * c, 1e-6 + 1e-4 * std::fabs(d * c)) << k;
    EXPECT_NEAR(out->lift_over_drag[k], veh.cl / veh.cd, 1e-12);
    // (7.20): b = -(beta + 2 g / V^2) / V^2 for the exponential atmosphere.
    const double g = gravity_mps2((*radius)[k]);
    EXPECT_NEAR(out->b[k], -(beta + 2.0 * g / (v * v)) / (v * v), 1e-6 * std::fabs(out->b[k])) << k;
  }
}

// ---------------------------------------------------------------- stage 4: reversal model
TEST(ReducedOrderStage, ReversalRampAndSpanOfMethod3) {
  // Method 3 of §7.4: dE = 2 sigma0 / sigma_dot_max D V; sigma from +s0 sigma0 at E_rev through
  // zero at the middle to -s0 sigma0 at E_rev - dE, linear in energy.
  EXPECT_DOUBLE_EQ(reversal_energy_span_Jpkg(0.5, 0.1, 10.0, 5000.0), 2.0 * 0.5 / 0.1 * 10.0 * 5000.0);
  EXPECT_GT(reversal_energy_span_Jpkg(0.0, 0.1, 10.0, 5000.0), 0.0);  // a span even for a zero bank
  const ReversalModel m{-1, 1.0e7, 4.0e5, 0.6};
  EXPECT_DOUBLE_EQ(reversal_ramp_bank_rad(m, 1.0e7), -0.6);
  EXPECT_NEAR(reversal_ramp_bank_rad(m, 1.0e7 - 1.0e5), -0.3, 1e-15);
  EXPECT_NEAR(reversal_ramp_bank_rad(m, 1.0e7 - 2.0e5), 0.0, 1e-15);
  EXPECT_NEAR(reversal_ramp_bank_rad(m, 1.0e7 - 4.0e5), 0.6, 1e-15);
  EXPECT_EQ(scheduled_bank_rad(m, 1.1e7, 0.7), -0.7);          // first side
  EXPECT_NEAR(scheduled_bank_rad(m, 1.0e7 - 3.0e5, 0.7), 0.3, 1e-15);  // ramp
  EXPECT_EQ(scheduled_bank_rad(m, 9.0e6, 0.7), 0.7);           // second side
  EXPECT_EQ(reversal_phase(m, 1.0e7), ReversalPhase::kReversing);
}

TEST(ReducedOrderStage, RangeTableOfALinearDragIsItsQuadrature) {
  // S = -int dE / D (7.10) for D linear in E: against Simpson's rule on 1/D.
  auto grid = uniform_grid(3.0e7, 1.0e6, 0.5);
  auto d = std::make_unique<GridValues>();
  for (int k = 0; k < kN; ++k) (*d)[k] = 0.2 + 12.0 * (3.0e7 - grid->energy_Jpkg[k]) / 2.9e7;
  auto table = std::make_unique<RangeTable>();
  build_range_table(grid->energy_Jpkg, *d, *table);
  const int m = 20000;
  double simpson = 0.0;
  const double a = 1.0e6, b = 3.0e7, hs = (b - a) / m;
  for (int i = 0; i <= m; ++i) {
    const double e = a + i * hs, w = (i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    simpson += w / (0.2 + 12.0 * (3.0e7 - e) / 2.9e7);
  }
  simpson *= hs / 3.0;
  EXPECT_NEAR(table->s_total_m / simpson, 1.0, 1e-9);
}

// ---------------------------------------------------------------- stage 5: reversal search
namespace {
// Root s_r of the planar crossrange after turning at rate kappa per metre, reversing at s_r:
// y(S) = (1 - 2 cos(kappa s_r) + cos(kappa (2 s_r - S))) / kappa, by bisection.
double planar_reversal_root(double kappa, double s_total) {
  auto y = [&](double sr) { return 1.0 - 2.0 * std::cos(kappa * sr) + std::cos(kappa * (2.0 * sr - s_total)); };
  double lo = 0.0, hi = 0.5 * s_total;  // y(0) < 0 < y(S/2)
  for (int i = 0; i < 200; ++i) (y(0.5 * (lo + hi)) > 0.0 ? hi : lo) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}
}  // namespace

TEST(ReversalSearchStage, FindsTheRootOfThePlanarTurnProblem) {
  // Constant drag D, speed V, L/D with the whole lift horizontal (D'' = a = 0 -> cos(sigma) = 0),
  // gamma = 0, heading east on the equator towards a target on it: the heading turns at
  // kappa = D (L/D) / V^2 per metre flown, one way then the other. The Earth-rate and
  // spherical terms are below 1e-3 of kappa here, the ramp is 20 m (fast roll), so the search
  // must find the planar root (and, for small angles, S (1 - 1/sqrt(2))).
  const double drag = 5.0, v = 7000.0, lod = 1.0, r0 = kEarthRadius_m + 60000.0;
  const double e0 = 2.0e7, s_total = 5.0e5, ef = e0 - drag * s_total;
  auto grid = uniform_grid(e0, ef, 0.5);
  auto radius = std::make_unique<GridValues>();
  auto pd = std::make_unique<PlannedDrag>();
  auto traj = std::make_unique<ExtractedTrajectory>();
  for (int k = 0; k < kN; ++k) {
    (*radius)[k] = r0;
    pd->drag_mps2[k] = drag;
    traj->velocity_mps[k] = v;
    traj->lift_over_drag[k] = lod;
    traj->b[k] = -1.0;  // a = D'' = 0: cos(sigma) = 0
  }
  auto range = std::make_unique<RangeTable>();
  build_range_table(grid->energy_Jpkg, pd->drag_mps2, *range);
  ASSERT_NEAR(range->s_total_m, s_total, 1e-6 * s_total);
  const ReducedOrderInput sys{grid->energy_Jpkg, *radius, *pd, *traj, *range, -1e30, ef, 1000.0, 2000};
  const ReversalSearchInput in{sys, RopState{0.0, 0.0, 90.0 * kDeg}, 90.0 * kDeg, s_total / r0, r0, e0, 1.0, 0.05};
  auto base = std::make_unique<RopTrack>();
  int sign = 1;
  double s_rev = 0.0;
  ReversalSearchResult res;
  ASSERT_EQ(bank_reversal_search(in, sign, s_rev, *base, res), Status::kOk);
  EXPECT_EQ(sign, 1);
  EXPECT_FALSE(res.best_effort);
  const double kappa = drag * lod / (v * v);
  EXPECT_NEAR(s_rev / planar_reversal_root(kappa, s_total), 1.0, 1e-3);
  EXPECT_NEAR(s_rev / (s_total * (1.0 - 1.0 / std::sqrt(2.0))), 1.0, 2e-3);
  EXPECT_LT(std::fabs(res.crossrange_rad * r0), 1.0);
  EXPECT_NEAR(res.downrange_rad * r0 / s_total, 1.0, 1e-3);  // the detour is short
}

// ---------------------------------------------------------------- stage 6: length update
TEST(LengthIterationStage, UpdateConvergesOnAnAffineRangeLaw) {
  // R(S) = c S + d (the downrange a length flies; c < 1: a lateral detour): (7.22) has the fixed
  // point S* = (R_d - d) / c and the error shrinks by exactly (1 - c) per step.
  const double c = 0.8, d = 2.0e4, r_d = 6.5e6, s_star = (r_d - d) / c;
  double s = r_d, err = s - s_star;
  for (int i = 0; i < 12; ++i) {
    s = next_trajectory_length_m(s, r_d, c * s + d);
    EXPECT_NEAR(s - s_star, (1.0 - c) * err, 1e-6) << i;
    err = s - s_star;
  }
  EXPECT_LT(std::fabs(s - s_star), 1.0);
}

// ---------------------------------------------------------------- stage 6: ranging alpha
TEST(RangingAlphaStage, AlphaOfMaximumLiftOverDragAndTheBlendRamps) {
  // CD constant, CL peaking at the 0.4 rad node of a piecewise-linear table: L/D is largest
  // there at every Mach. The blend moves alpha by blend w (alpha_LD - alpha) where alpha_LD is
  // lower, w rising over the ramp span below the planning energy and falling over the
  // next-to-last ramp span above TAEM (0 over the last one).
  SimpleVehicle veh;
  const double alpha_nodes[5] = {0.0, 0.2, 0.4, 0.6, 0.8}, mach[2] = {0.0, 40.0};
  const double cl[10] = {0.1, 0.1, 0.5, 0.5, 0.9, 0.9, 0.7, 0.7, 0.6, 0.6}, cd[10] = {0.5, 0.5, 0.5, 0.5, 0.5,
                                                                                       0.5, 0.5, 0.5, 0.5, 0.5};
  ASSERT_EQ(veh.models->aero().init(alpha_nodes, 5, mach, 2, cl, cd), Status::kOk);
  const double e_entry = 3.0e7, ef = 1.0e6, e0 = 2.5e7;
  auto grid = uniform_grid(e0, ef, 0.6);
  auto radius = std::make_unique<GridValues>();
  for (int k = 0; k < kN; ++k) (*radius)[k] = kEarthRadius_m + 50000.0;
  auto alpha_ld = std::make_unique<GridValues>();
  alpha_of_max_lift_over_drag(*veh.models, *grid, *radius, 0.8, 200, *alpha_ld);
  for (int k = 0; k < kN; k += 20) EXPECT_EQ((*alpha_ld)[k], 0.4) << k;
  RangingBlendInput in;
  in.blend = 0.5;
  in.planning_energy_Jpkg = e0;
  in.entry_energy_Jpkg = e_entry;
  in.taem_energy_Jpkg = ef;
  in.ramp_fraction = 0.05;
  const double ramp = 0.05 * (e_entry - ef);  // 1.45e6 J/kg
  EXPECT_EQ(ranging_weight(in, ramp, e0), 0.0);
  EXPECT_NEAR(ranging_weight(in, ramp, e0 - 0.5 * ramp), 0.5, 1e-12);
  EXPECT_EQ(ranging_weight(in, ramp, 1.0e7), 1.0);
  EXPECT_NEAR(ranging_weight(in, ramp, ef + 1.5 * ramp), 0.5, 1e-12);
  EXPECT_EQ(ranging_weight(in, ramp, ef + 0.5 * ramp), 0.0);
  in.continuing = true;
  EXPECT_EQ(ranging_weight(in, ramp, e0), 1.0);  // a flown blend continues at the planning energy
  in.continuing = false;
  apply_ranging_blend(in, *alpha_ld, *grid);
  for (int k = 0; k < kN; ++k) {
    const double e = grid->energy_Jpkg[k];
    const double w = std::fmin(std::fmax((e0 - e) / ramp, 0.0), 1.0) * std::fmin(std::fmax((e - ef - ramp) / ramp, 0.0), 1.0);
    EXPECT_NEAR(grid->alpha_rad[k], 0.6 + 0.5 * w * (0.4 - 0.6), 1e-12) << k;
  }
  // Where alpha(L/D max) lies above the profile alpha nothing moves.
  for (int k = 0; k < kN; ++k) grid->alpha_profile_rad[k] = 0.3;
  apply_ranging_blend(in, *alpha_ld, *grid);
  for (int k = 0; k < kN; ++k) EXPECT_EQ(grid->alpha_rad[k], 0.3) << k;
}

TEST(PlannerParamsRelations, BreakpointClampsLeaveAnInterval) {
  // E1 in [TAEM + e1_min, E0 - gap] and E2 in [TAEM + gap, E1 - gap] (shares of the span):
  // both intervals are non-empty only for e1_min + gap <= 1 and 2 gap <= e1_min.
  PlannerParams p;
  EXPECT_EQ(planner_params_inconsistency(p), nullptr);
  p.segment_min_span_fraction = 0.06;
  EXPECT_STREQ(planner_params_inconsistency(p), "planner.segment_min_span_fraction");
  p = PlannerParams{};
  p.e1_min_span_fraction = 0.99;
  EXPECT_STREQ(planner_params_inconsistency(p), "planner.e1_min_span_fraction");
}

// ---------------------------------------------------------------- geometry (§7.4, DESIGN §7)
TEST(PlannerGeometry, HorusPlanStartsFromThePublishedMissionGeometry) {
  // The planner's planning-point geometry for the HORUS entry: b = 57.79 deg, A = 68.57 deg,
  // chi_e - A = 1.87 deg, S0 = 6506 km (thesis §7.1 and §7.6, read as in DESIGN §7).
  const config::LoadResult loaded = config::load_mission("horus");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  auto planner = std::make_unique<EntryPlanner>();
  auto out = std::make_unique<ReferenceProfile>();
  ASSERT_EQ(init_from_mission(*planner, loaded.mission), Status::kOk);
  planner->plan(planner->entry_state(), *out);
  const PlannerDiagnostics& d = planner->diagnostics();
  EXPECT_NEAR(d.b_mission_rad / kDeg, 57.79, 0.005);
  EXPECT_NEAR(d.a_mission_rad / kDeg, 68.57, 0.005);
  EXPECT_NEAR(d.chi_minus_a_rad / kDeg, 1.87, 0.005);
  EXPECT_NEAR(d.s_initial_m / 1e3, 6506.0, 0.5);
  EXPECT_EQ(d.initial_bank_sign, -1);  // heading right of the target: bank left first (fig. 7.20)
}
