// Closed-loop missions flown in process (truth simulator + guidance stack), judged by the
// truth-side verdict (thesis 3.1.2 tolerances in the mission files), and the planned angle-of-
// attack profile of a mission without a hand-made one.
#include <gtest/gtest.h>

#include <cmath>

#include "guidance/mission_adapter.hpp"
#include "closed_loop.hpp"
#include "guidance/alpha_profile_source.hpp"
#include "models/onboard_models.hpp"
#include "planner/entry_planner.hpp"
#include "reentry/config/mission.hpp"

namespace reentry {
namespace {

config::Mission load(const std::string& name) {
  const config::LoadResult r = config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

// The mission with its uniform stress set ([stress_dispersions]): the draws of the seeds the
// tests below name (draws of the uniform set that once failed).
config::Mission load_stress(const std::string& name) {
  config::Mission m = load(name);
  EXPECT_TRUE(m.has_stress_dispersions) << name;
  m.dispersions = m.stress_dispersions;
  return m;
}

// Closed loop judged on every TAEM tolerance (range, altitude, Mach, heading, flight path) and
// path constraint; returns the result for mission-specific checks.
tools::ClosedLoopResult fly_within_tolerances(const config::Mission& m, std::uint64_t seed, bool dispersed) {
  const tools::ClosedLoopResult r = tools::run_closed_loop(m, seed, dispersed);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.summary.event, truth::SimEvent::kTaemEnergy);
  for (const auto& v : r.verdict.violations) ADD_FAILURE() << "seed " << seed << " violation: " << v;
  EXPECT_TRUE(r.verdict.success) << "seed " << seed;
  EXPECT_LT(std::fabs(r.verdict.heading_err_rad), m.taem.heading_tol_rad) << "seed " << seed;
  EXPECT_LT(std::fabs(r.verdict.altitude_err_m), m.taem.altitude_tol_m) << "seed " << seed;
  return r;
}

tools::ClosedLoopResult fly_nominal_within_tolerances(const config::Mission& m) {
  return fly_within_tolerances(m, 1, false);
}

TEST(ClosedLoop, GuidanceAndTruthAgreeOnTheTaemEnergy) {
  // Both end the flight at the energy of the mission's TAEM state (its altitude above the
  // oblate Earth over the aim point, its speed): the truth simulator from its shape model,
  // the planner from the WGS-84 surface radius. Before, both took R_eq + h: at the X-38's
  // 33 deg the state with zero altitude error then flew 80 m/s faster than the mission's.
  for (const char* name : {"x33", "horus", "x38", "orbiter", "x33_planned_alpha"}) {
    config::Mission m = load(name);
    ASSERT_EQ(fsw::resolve_alpha_profile(m), "") << name;
    std::string err;
    auto sim = truth::Simulator::create(m, truth::SimOverrides{}, &err);
    ASSERT_NE(sim, nullptr) << err;
    fsw::EntryPlanner planner;
    static fsw::ReferenceProfile profile;
    ASSERT_EQ(init_from_mission(planner, m), fsw::Status::kOk) << name;
    const fsw::Status st = planner.plan(planner.entry_state(), profile);
    ASSERT_TRUE(st == fsw::Status::kOk || st == fsw::Status::kRangeTooLong) << name;
    EXPECT_NEAR(profile.taem_energy_Jpkg, sim->taem_energy_Jpkg(), 1e-9 * sim->taem_energy_Jpkg()) << name;
    const double lat_deg = m.taem.latitude_rad * 180.0 / M_PI;
    if (std::fabs(lat_deg) > 20.0) {  // the old definition differs by g (R_eq - R(lat))
      const double old = fsw::specific_energy_Jpkg(fsw::kEarthRadius_m + m.taem.altitude_m, m.taem.velocity_mps);
      EXPECT_GT(std::fabs(old - sim->taem_energy_Jpkg()), 1e4) << name;
    }
  }
}

TEST(ClosedLoop, X33NominalReachesTaemWithinEveryTolerance) {
  const tools::ClosedLoopResult r = fly_nominal_within_tolerances(load("x33"));
  // In-flight replans may fail (the executive keeps the active plan); most must succeed.
  EXPECT_GT(r.counters.plans_adopted, 3 * r.counters.planner_failures);
}

// The mission with its guidance law replaced (both laws fly every mission file).
config::Mission with_law(config::Mission m, const char* law) {
  m.guidance.law = law;
  return m;
}

TEST(ClosedLoop, HorusNominalReachesTaemWithinEveryTolerance) {
  // HORUS rides its heat-flux limit and, in the terminal phase, its q*alpha limit; with the
  // mission's alpha profile (30 deg on the q*alpha bound, where more alpha gives more drag)
  // both laws reach the aim point within the 2 km goal and every constraint.
  for (const char* law : {"predictor_corrector", "drag_tracking"}) {
    SCOPED_TRACE(law);
    const tools::ClosedLoopResult r = fly_nominal_within_tolerances(with_law(load("horus"), law));
    EXPECT_LT(r.verdict.taem_miss_m, 2000.0);
  }
}

TEST(ClosedLoop, OrbiterNominalWithThePredictorCorrectorReachesTaemWithinEveryTolerance) {
  // The predictor flies the 2 deg/s reversals it commands (10.1), so their range cost is in
  // the bank parameter the corrector solves for: the Orbiter reaches the TAEM interface within
  // every tolerance and path limit (the drag-tracking law, below, does not).
  const config::Mission m = load("orbiter");
  ASSERT_EQ(m.guidance.law, "predictor_corrector");
  fly_nominal_within_tolerances(m);
}

TEST(ClosedLoop, X38NominalReachesTaemWithinEveryTolerance) {
  // The X-38 is 120 km off the arrival line when the heading corridor starts and turns at
  // about 0.1 deg/s: the corridor's approach angle is bounded by the turn it can make
  // (without the bound it crossed the line 16 deg off and missed by 12.9 km, 12 deg off).
  fly_nominal_within_tolerances(load("x38"));
}

TEST(ClosedLoop, OrbiterKeepsItsHeatAndLoadLimitsThroughThePlannedReversal) {
  // The drag-tracking law on the Orbiter. Table 3.3's 2 deg/s bank rate: the planned reversal on the heat-flux bound rolls through
  // wings level for about a minute and leaves a climb; the drag loop answers with lift down
  // 150-170 deg, and with the pull-out guard latched off after the entry pull-out the dive it
  // starts cannot be rolled out of in time (truth: 3218 kW/m2 and 7.3 g against 795 kW/m2 and
  // 2.5 g). The mission file sets tracker.pullout_guard_every_descent, so the guard judges that
  // descent too: the flight reaches the TAEM energy within both limits. This law does not
  // meet the Orbiter's TAEM tolerances (docs/status.md): this test holds what it achieves.
  const config::Mission m = with_law(load("orbiter"), "drag_tracking");
  const tools::ClosedLoopResult guarded = tools::run_closed_loop(m, 1, false);
  ASSERT_TRUE(guarded.error.empty()) << guarded.error;
  EXPECT_EQ(guarded.summary.event, truth::SimEvent::kTaemEnergy);
  EXPECT_LT(guarded.summary.maxima.qdot_Wpm2, m.constraints.heat_flux_max_Wpm2);
  EXPECT_LT(guarded.summary.maxima.n_g, m.constraints.load_factor_max_g);
  config::Mission latched = m;
  int set = 0;
  for (auto& t : latched.guidance.tuning) {
    if (t.key == "tracker.pullout_guard_every_descent") {
      t.value = 0.0;
      ++set;
    }
  }
  ASSERT_EQ(set, 1);
  const tools::ClosedLoopResult unguarded = tools::run_closed_loop(latched, 1, false);
  ASSERT_TRUE(unguarded.error.empty()) << unguarded.error;
  EXPECT_GT(unguarded.summary.maxima.qdot_Wpm2, 2.0 * m.constraints.heat_flux_max_Wpm2);
  EXPECT_GT(unguarded.summary.maxima.n_g, 2.0 * m.constraints.load_factor_max_g);
}

TEST(ClosedLoop, DispersedX33RunsThatTurnedPastTheArrivalLineNowArriveOnIt) {
  // Dispersed entries (seeds of the uniform 500-run campaign) that reached TAEM 12-18 km out
  // and up to 10.5 deg off heading with the final reversal timed on a constant turn at the
  // present speed: the turn after it was under-predicted by 5-15 deg.
  const config::Mission m = load_stress("x33");
  for (std::uint64_t seed : {408u, 426u, 506u}) fly_within_tolerances(m, seed, true);
}

TEST(ClosedLoop, GuidanceThatKnowsTheDrawnVehicleKeepsTheTrueHeatLimit) {
  // HORUS seed 282 (uniform set) draws C_D -9 % and mass +4 %: at a given drag the true dynamic pressure,
  // hence the heat flux (3.5), is higher than the on-board model says (by sqrt(m / C_D), 7 %),
  // and the guidance, flying at 97 % of the limit it believes in, exceeds 530 kW/m2 (truth).
  // Given the drawn vehicle (the diagnosis mode of tools/mc), it places the drag under the
  // true limit.
  const config::Mission m = load_stress("horus");
  const tools::ClosedLoopResult blind = tools::run_closed_loop(m, 282, true);
  const tools::ClosedLoopResult informed = tools::run_closed_loop(m, 282, true, {}, true);
  ASSERT_TRUE(blind.error.empty() && informed.error.empty()) << blind.error << informed.error;
  ASSERT_LT(informed.dispersion.cd_scale / informed.dispersion.mass_scale, 0.9);
  EXPECT_LT(informed.summary.maxima.qdot_Wpm2, m.constraints.heat_flux_max_Wpm2);
  EXPECT_LT(informed.summary.maxima.qdot_Wpm2, blind.summary.maxima.qdot_Wpm2 - 10e3);
}

TEST(PlannedAlpha, ProfileCoversTheEnergyRangeMonotoneWithinAlphaMax) {
  config::Mission m = load("x33_planned_alpha");
  ASSERT_TRUE(m.alpha_profile_planned);
  ASSERT_EQ(fsw::resolve_alpha_profile(m), "");
  const auto& t = m.alpha_profile;
  ASSERT_GE(t.x.size(), 2u);
  ASSERT_EQ(t.x.size(), t.y.size());
  EXPECT_EQ(t.x.front(), 0.0);
  EXPECT_EQ(t.x.back(), 1.0);
  for (size_t i = 1; i < t.x.size(); ++i) {
    EXPECT_GT(t.x[i], t.x[i - 1]) << i;
    EXPECT_GE(t.y[i], t.y[i - 1] - 1e-12) << i;  // alpha does not grow as energy falls (ch. 6)
  }
  for (double a : t.y) {
    EXPECT_GT(a, 0.0);
    EXPECT_LE(a, m.constraints.alpha_max_rad);
  }
  // A table mission is left alone.
  config::Mission table = load("x33");
  const auto before = table.alpha_profile.y;
  EXPECT_EQ(fsw::resolve_alpha_profile(table), "");
  EXPECT_EQ(table.alpha_profile.y, before);
}

TEST(PlannedAlpha, X33NominalReachesTaemWithinEveryToleranceWithThePlannedProfile) {
  // The guidance plans the profile at start-up (thesis ch. 6, with the TAEM-matching ramp);
  // the mission is judged like the hand-profile X-33: every constraint and TAEM tolerance,
  // the altitude included (the step of the profile before the ramp left it 2.6 km high).
  const tools::ClosedLoopResult r = fly_nominal_within_tolerances(load("x33_planned_alpha"));
  EXPECT_GE(r.counters.plans_adopted, 2);
}

}  // namespace
}  // namespace reentry
