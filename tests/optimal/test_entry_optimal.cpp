// The optimizer on the truth models, judged by the truth simulator: the optimal control
// history of a run flown open loop must reach the end point the collocation predicts, and be
// judged by the referee as the optimizer judged it.
#include <gtest/gtest.h>

#include "run_oracle.hpp"

namespace reentry::optimal {
namespace {

config::Mission load(const std::string& name) {
  const config::LoadResult r = config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

TEST(EntryOptimal, X33NominalMaximumMarginFlownOpenLoopReachesTheCollocatedEndPoint) {
  OracleOptions o;
  o.mode = EntryMode::kMaxMargin;
  o.replay = true;
  const OracleResult r = run_oracle(load("x33"), 0, false, o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_TRUE(converged(r.entry.solution.status)) << r.entry.solution.ipopt_status;
  EXPECT_TRUE(r.optimizer_feasible);
  EXPECT_EQ(r.feasibility, Feasibility::kFlown);
  // The guidance's own flight is feasible, so the best common margin is at least its own.
  EXPECT_GT(r.entry.figures.margin, 0.1);
  ASSERT_TRUE(r.replayed);
  EXPECT_EQ(r.replay.summary.event, truth::SimEvent::kTaemEnergy);
  EXPECT_LT(r.replay.final_position_diff_m, 1000.0);
  EXPECT_LT(std::fabs(r.replay.final_time_diff_s), 1.0);
  EXPECT_TRUE(r.replay.verdict.success);
  for (const auto& v : r.replay.verdict.violations) ADD_FAILURE() << "replay violation " << v;
}

TEST(EntryOptimal, HorusDispersedMinimumMissIsAtLeastAsGoodAsTheGuidance) {
  // Seed 9: a guidance success 2.48 km from the aim point (tolerance 3 km).
  OracleOptions o;
  o.mode = EntryMode::kMinMiss;
  const OracleResult r = run_oracle(load("horus"), 9, true, o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_TRUE(r.flown.verdict.success);
  ASSERT_TRUE(converged(r.entry.solution.status)) << r.entry.solution.ipopt_status;
  EXPECT_TRUE(r.optimizer_feasible);
  EXPECT_EQ(r.feasibility, Feasibility::kFlown);
  EXPECT_LE(r.entry.figures.miss_m, r.flown.verdict.taem_miss_m);
  EXPECT_LT(r.replay.final_position_diff_m, 5000.0);
}

TEST(EntryOptimal, HorusRunTheGuidanceLosesIsProvenFeasibleByAnOpenLoopFlight) {
  // Seed 8: the guidance ends 3.33 km from the aim point (tolerance 3 km), no path limit exceeded.
  const OracleResult r = run_oracle(load("horus"), 8, true, OracleOptions{});
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_FALSE(r.flown.verdict.success);
  ASSERT_TRUE(converged(r.entry.solution.status)) << r.entry.solution.ipopt_status;
  EXPECT_GT(r.entry.figures.margin, 0.0);
  ASSERT_TRUE(r.replayed);
  EXPECT_TRUE(r.replay.verdict.success);
  EXPECT_EQ(r.feasibility, Feasibility::kProvenOpenLoop);
  EXPECT_TRUE(r.feasible);
}

}  // namespace
}  // namespace reentry::optimal
