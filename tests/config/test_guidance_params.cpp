// The guidance tunables as a mission file sets them ([guidance], [guidance.planner],
// [guidance.tracker]): defaults inside their documented ranges, values converted from the
// file's units, and every bad value rejected with the file, the key and the value named.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "guidance/mission_adapter.hpp"
#include "temp_mission.hpp"

namespace {

using reentry::fsw::GuidanceLawParams;
using reentry::fsw::GuidanceSetup;
using reentry::fsw::ParamUnit;
using reentry_test::replace_once;
using reentry_test::TempMission;

/// Checks that every default lies inside its documented range (in the file's unit).
struct RangeCheck {
  int checked = 0;
  template <class T>
  void operator()(const char* key, const T& field, ParamUnit unit, double lo, double hi, const char*) {
    const double v = reentry::fsw::param_from_si(static_cast<double>(field), unit);
    EXPECT_GE(v, lo) << key;
    EXPECT_LE(v, hi) << key;
    ++checked;
  }
};

std::string setup_error(TempMission& t, std::unique_ptr<GuidanceSetup>& setup) {
  const reentry::config::LoadResult r = t.load();
  if (!r.ok) return r.error;
  setup = std::make_unique<GuidanceSetup>();
  return reentry::fsw::make_guidance_setup(r.mission, *setup);
}

void add_tuning(TempMission& t, const std::string& tables) { replace_once(t.mission(), "\n[sim]\n", "\n" + tables + "\n[sim]\n"); }

TEST(GuidanceParams, DefaultsLieInTheirDocumentedRangesAndAreConsistent) {
  const GuidanceLawParams p;
  RangeCheck shared, planner, tracker;
  reentry::fsw::visit_shared_guidance_params(p, shared);
  reentry::fsw::visit_planner_params(p.planner, planner);
  reentry::fsw::visit_tracker_params(p.tracker, tracker);
  EXPECT_EQ(shared.checked, 3);
  EXPECT_GT(planner.checked, 15);
  EXPECT_GT(tracker.checked, 40);
  EXPECT_EQ(reentry::fsw::guidance_params_inconsistency(p), nullptr);
}

TEST(GuidanceParams, TheReferenceMissionsFlyTheDefaultsExceptTheirStatedExceptions) {
  // The tunables set away from their defaults, each with its reason in the mission file: the
  // Orbiter's pull-out guard on every descent for its 2 deg/s bank rate (drag tracking,
  // docs/guidance_design.md 3.1) and, for the same rate, its wider heading corridor and its
  // reversal modulation on the long rolls only and not in the terminal phase, and its
  // capture guard timed by the plan and its limit growing with the distance to go
  // (predictor-corrector, 10.4-10.5); HORUS plans on
  // the model's C_D S/m (its heat-flux limit leaves no room); the X-38's alpha band down to its
  // L/D-max alpha and the bank it keeps to turn (predictor-corrector, docs/guidance_design.md
  // 10.2-10.3), its 3-sigma C_D S/m knowledge (its q limit in the terminal dive) and its least bank
  // after capture (its lateral authority against the Coriolis drift); HORUS and the
  // X-38 keep the terminal aim on its target (their terminal limits and TAEM altitude leave no
  // room), and HORUS holds no bank side for range; the X-33's predictor-corrector banks at most
  // 75 deg (its terminal descent's turn). Nothing else.
  const std::map<std::string, std::set<std::string>> exceptions = {
      {"orbiter", {"tracker.pullout_guard_every_descent", "predictor_corrector.corridor_entry_deg",
                   "predictor_corrector.corridor_taem_deg", "predictor_corrector.modulation_min_roll_s",
                   "predictor_corrector.modulation_in_terminal", "predictor_corrector.capture_waits_for_plan",
                   "predictor_corrector.capture_overshoot_range_fraction"}},
      {"horus", {"predictor_corrector.drag_model_uncertainty", "predictor_corrector.terminal_range_aim_fraction",
                 "predictor_corrector.reversal_hold_predictions"}},
      {"x38", {"predictor_corrector.alpha_band_deg", "predictor_corrector.lateral_bank_deg",
               "predictor_corrector.terminal_range_aim_fraction", "predictor_corrector.drag_model_uncertainty",
               "predictor_corrector.bank_min_deg"}},
      {"x33", {"predictor_corrector.bank_max_deg", "predictor_corrector.final_bank_max_deg"}}};
  for (const auto& [name, keys] : exceptions) {
    const auto r = reentry::config::load_mission(name.c_str());
    ASSERT_TRUE(r.ok) << r.error;
    std::set<std::string> set;
    for (const auto& t : r.mission.guidance.tuning) set.insert(t.key);
    EXPECT_EQ(set, keys) << name;
    auto setup = std::make_unique<GuidanceSetup>();
    ASSERT_EQ(reentry::fsw::make_guidance_setup(r.mission, *setup), "") << name;
    EXPECT_EQ(setup->params.tracker.initial_descent_drag_mps2, 0.05 * 9.80665) << name;
    EXPECT_EQ(setup->params.tracker.pullout_guard_every_descent, name == "orbiter" ? 1 : 0) << name;
    const reentry::fsw::PredictorCorrectorParams defaults;
    EXPECT_EQ(setup->pc_params.drag_model_uncertainty,
              name == "horus" ? 0.0 : (name == "x38" ? 0.11 : defaults.drag_model_uncertainty)) << name;
    EXPECT_NEAR(setup->pc_params.alpha_band_rad, (name == "x38" ? 15.0 : 3.0) * M_PI / 180.0, 1e-15) << name;
    EXPECT_NEAR(setup->pc_params.lateral_bank_rad, (name == "x38" ? 65.0 : 45.0) * M_PI / 180.0, 1e-15) << name;
    EXPECT_EQ(setup->pc_params.terminal_range_aim_fraction,
              name == "horus" || name == "x38" ? 0.0 : defaults.terminal_range_aim_fraction) << name;
    EXPECT_EQ(setup->pc_params.reversal_hold_predictions, name == "horus" ? 0 : defaults.reversal_hold_predictions) << name;
    EXPECT_NEAR(setup->pc_params.corridor_entry_rad, name == "orbiter" ? 18.0 * M_PI / 180.0 : defaults.corridor_entry_rad,
                1e-15) << name;
    EXPECT_NEAR(setup->pc_params.corridor_taem_rad, name == "orbiter" ? 5.0 * M_PI / 180.0 : defaults.corridor_taem_rad,
                1e-15) << name;
    EXPECT_EQ(setup->pc_params.modulation_min_roll_s, name == "orbiter" ? 50.0 : defaults.modulation_min_roll_s) << name;
    EXPECT_EQ(setup->pc_params.modulation_in_terminal, name == "orbiter" ? 0 : defaults.modulation_in_terminal) << name;
    EXPECT_EQ(setup->pc_params.capture_waits_for_plan, name == "orbiter" ? 1 : defaults.capture_waits_for_plan) << name;
    EXPECT_EQ(setup->pc_params.capture_overshoot_range_fraction,
              name == "orbiter" ? 0.01 : defaults.capture_overshoot_range_fraction) << name;
    EXPECT_NEAR(setup->pc_params.bank_min_rad, name == "x38" ? 20.0 * M_PI / 180.0 : defaults.bank_min_rad, 1e-15) << name;
    EXPECT_NEAR(setup->pc_params.bank_max_rad, name == "x33" ? 75.0 * M_PI / 180.0 : defaults.bank_max_rad, 1e-15) << name;
    EXPECT_NEAR(setup->pc_params.final_bank_max_rad, name == "x33" ? 75.0 * M_PI / 180.0 : defaults.final_bank_max_rad,
                1e-15) << name;
  }
}

TEST(GuidanceParams, FileValuesAreConvertedToSI) {
  TempMission t;
  add_tuning(t,
             "constraint_margin = 0.95\n"
             "[guidance.planner]\nrk4_steps = 800\ndownrange_tol_m = 1000\n"
             "[guidance.tracker]\ncorridor_half_width_min_deg = 2.5\ncorridor_half_width_max_deg = 6.0\nzeta = 0.8\n");
  std::unique_ptr<GuidanceSetup> s;
  ASSERT_EQ(setup_error(t, s), "");
  EXPECT_EQ(s->params.constraint_margin, 0.95);
  EXPECT_EQ(s->params.planner.rk4_steps, 800);
  EXPECT_EQ(s->params.planner.downrange_tol_m, 1000.0);
  EXPECT_NEAR(s->params.tracker.corridor_half_width_min_rad, 2.5 * 3.14159265358979323846 / 180.0, 1e-16);
  EXPECT_EQ(s->params.tracker.zeta, 0.8);
  // A key set to its default gives the default bit for bit (the defaults are written in the
  // order the conversion computes).
  EXPECT_EQ(s->params.tracker.corridor_half_width_max_rad, GuidanceLawParams{}.tracker.corridor_half_width_max_rad);
}

struct BadTuning {
  const char* label;
  const char* tables;
  const char* key;    // expected in the message
  const char* what;   // expected in the message (the value or the reason)
};

class BadGuidanceParam : public ::testing::TestWithParam<BadTuning> {};

TEST_P(BadGuidanceParam, IsRejectedNamingFileKeyAndValue) {
  const BadTuning& c = GetParam();
  TempMission t;
  add_tuning(t, c.tables);
  std::unique_ptr<GuidanceSetup> s;
  const std::string error = setup_error(t, s);
  ASSERT_NE(error, "") << c.label;
  EXPECT_NE(error.find(t.mission_path()), std::string::npos) << error;
  EXPECT_NE(error.find(c.key), std::string::npos) << error;
  EXPECT_NE(error.find(c.what), std::string::npos) << error;
}

INSTANTIATE_TEST_SUITE_P(
    Tunables, BadGuidanceParam,
    ::testing::Values(
        BadTuning{"unknown", "[guidance.tracker]\ncorridor_width_deg = 3.0\n", "guidance.tracker.corridor_width_deg", "unknown"},
        BadTuning{"wrong_unit", "[guidance.tracker]\ncorridor_half_width_min_rad = 0.05\n",
                  "guidance.tracker.corridor_half_width_min_rad", "unknown"},
        BadTuning{"unknown_top", "constraint_margn = 0.9\n", "guidance.constraint_margn", "0.9"},
        BadTuning{"range", "[guidance.tracker]\nzeta = 12.0\n", "guidance.tracker.zeta", "12"},
        BadTuning{"capacity", "[guidance.planner]\nrk4_steps = 5000\n", "guidance.planner.rk4_steps", "5000"},
        BadTuning{"integer", "[guidance.planner]\nrk4_steps = 600.5\n", "guidance.planner.rk4_steps", "600.5"},
        BadTuning{"text", "[guidance.tracker]\nzeta = \"0.7\"\n", "guidance.tracker.zeta", "\"0.7\""},
        BadTuning{"nan", "[guidance.tracker]\nzeta = nan\n", "guidance.tracker.zeta", "nan"},
        BadTuning{"inconsistent", "[guidance.tracker]\ncorridor_half_width_min_deg = 8.0\n",
                  "guidance.tracker.corridor_half_width_min_deg", "inconsistent"},
        BadTuning{"phases", "terminal_span_fraction = 0.4\n", "guidance.terminal_span_fraction", "inconsistent"},
        BadTuning{"not_a_table", "planner = 3\n", "guidance.planner", "table"}),
    [](const ::testing::TestParamInfo<BadTuning>& info) { return std::string(info.param.label); });

}  // namespace
