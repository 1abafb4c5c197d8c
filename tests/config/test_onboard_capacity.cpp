// The limits a mission file meets are the on-board capacities: a mission accepted at the limit
// initialises the flight code, one step beyond is refused at load (tables: the loader; guidance
// tunables: the guidance adapter) with file, key and value, not later with a bare status.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "guidance/mission_adapter.hpp"
#include "models/onboard_models.hpp"
#include "planner/entry_planner.hpp"
#include "reentry/config/mission.hpp"
#include "temp_mission.hpp"

namespace {

// The X-33 mission with `from` replaced by `to`, loaded from a temporary copy (removed after).
reentry::config::LoadResult load_with(const std::string& from, const std::string& to) {
  reentry_test::TempMission t;
  reentry_test::replace_once(t.mission(), from, to);
  return t.load();
}

TEST(OnboardCapacity, Rk4StepsAtTheLimitFlyAndOneMoreIsRefusedAtLoad) {
  using reentry::fsw::EntryPlanner;
  const int cap = EntryPlanner::kMaxRkSteps;
  auto with_steps = [&](int n) { return load_with("\n[sim]\n", "\n[guidance.planner]\nrk4_steps = " + std::to_string(n) + "\n\n[sim]\n"); };
  auto ok = with_steps(cap);
  ASSERT_TRUE(ok.ok) << ok.error;
  auto planner = std::make_unique<EntryPlanner>();
  EXPECT_EQ(init_from_mission(*planner, ok.mission), reentry::fsw::Status::kOk);
  EXPECT_EQ(planner->params().rk4_steps, cap);
  auto over = with_steps(cap + 1);
  ASSERT_TRUE(over.ok) << over.error;  // the loader passes guidance tunables through
  auto setup = std::make_unique<reentry::fsw::GuidanceSetup>();
  const std::string error = reentry::fsw::make_guidance_setup(over.mission, *setup);
  EXPECT_NE(error.find("guidance.planner.rk4_steps"), std::string::npos) << error;
  EXPECT_NE(error.find(std::to_string(cap + 1)), std::string::npos) << error;
}

TEST(OnboardCapacity, TableCapacitiesAreTheLoadersLimits) {
  // The loader refuses 65 or more (tests/config/test_config.cpp, 70 rows); these are the
  // flight code's capacities it must equal.
  EXPECT_EQ(reentry::fsw::OnboardAero::kMaxAlpha, 64);
  EXPECT_EQ(reentry::fsw::OnboardAero::kMaxMach, 64);
  EXPECT_EQ(reentry::fsw::AlphaProfile::kCapacity, 64);
  std::string energies = "energy = [", alphas = "alpha_deg = [";
  for (int i = 0; i < reentry::fsw::AlphaProfile::kCapacity; ++i) {
    const bool last = i + 1 == reentry::fsw::AlphaProfile::kCapacity;
    energies += std::to_string(static_cast<double>(i) / (reentry::fsw::AlphaProfile::kCapacity - 1)) + (last ? "]" : ", ");
    alphas += std::string("30.0") + (last ? "]" : ", ");
  }
  auto at = load_with("energy = [0.000, 0.120, 0.414, 1.000]\nalpha_deg = [20.0, 20.0, 46.0, 46.0]", energies + "\n" + alphas);
  ASSERT_TRUE(at.ok) << at.error;
  reentry::fsw::AlphaProfile profile;
  EXPECT_EQ(init_from_mission(profile, at.mission), reentry::fsw::Status::kOk);
}

}  // namespace
