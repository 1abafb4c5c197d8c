// Loader and simulator agree on what is valid (issue 38 item 5): every mission the loader
// refuses, the simulator refuses with the same rule (and message) when handed the same values
// directly; the stock missions pass both.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "dynamics/simulator.hpp"
#include "reentry/config/mission.hpp"
#include "temp_mission.hpp"

namespace {

using reentry_test::TempMission;
using reentry_test::replace_once;

std::string sim_error(const reentry::config::Mission& m) {
  std::string err;
  auto sim = reentry::truth::Simulator::create(m, reentry::truth::SimOverrides{}, &err);
  return sim ? std::string() : err;
}

// A copy of the stock wind profile with one value replaced (row 3, EWmean).
std::string wind_file_with(const std::string& dir, const std::string& value) {
  std::ifstream in(reentry_test::kConfigDir + "/environment/earthgram_nominal_wind.txt");
  std::string line, text;
  for (int row = 0; std::getline(in, line); ++row) {
    if (row == 3) {
      std::istringstream ls(line);
      std::string tok, out;
      for (int col = 0; ls >> tok; ++col) out += (col ? " " : "") + (col == 7 ? value : tok);
      line = out;
    }
    text += line + "\n";
  }
  const std::string path = dir + "/wind_" + std::to_string(std::hash<std::string>{}(value)) + ".txt";
  std::ofstream(path) << text;
  return path;
}

struct Case {
  const char* name;
  std::function<void(TempMission&, const std::string& dir)> edit_file;        // the mission file
  std::function<void(reentry::config::Mission&, const std::string& dir)> edit;  // the same, in memory
  const char* key;                                                              // named by both
};

TEST(MissionRules, LoaderAndSimulatorRefuseTheSameMissions) {
  const reentry_test::TempDir tmp("reentry_mission_rules");
  const std::string dir = tmp.str();
  const std::string garbage = dir + "/garbage_gravity.txt";
  std::ofstream(garbage) << "this is not a gravity field\n";
  const Case cases[] = {
      {"entry latitude 90", [](TempMission& t, const std::string&) { replace_once(t.mission(), "latitude_deg = -23.75", "latitude_deg = 90.0"); },
       [](reentry::config::Mission& m, const std::string&) { m.entry.latitude_rad = M_PI / 2.0; }, "entry.latitude_deg"},
      {"rel_tol 1e-300", [](TempMission& t, const std::string&) { replace_once(t.mission(), "rel_tol = 1e-10", "rel_tol = 1e-300"); },
       [](reentry::config::Mission& m, const std::string&) { m.sim.rel_tol = 1e-300; }, "sim.rel_tol"},
      {"wind nan", [](TempMission& t, const std::string& d) {
         replace_once(t.mission(), "\"../environment/earthgram_nominal_wind.txt\"", "\"" + wind_file_with(d, "nan") + "\""); },
       [](reentry::config::Mission& m, const std::string& d) { m.environment.wind_profile = wind_file_with(d, "nan"); },
       "environment.wind_profile"},
      {"wind 1e300", [](TempMission& t, const std::string& d) {
         replace_once(t.mission(), "\"../environment/earthgram_nominal_wind.txt\"", "\"" + wind_file_with(d, "1e300") + "\""); },
       [](reentry::config::Mission& m, const std::string& d) { m.environment.wind_profile = wind_file_with(d, "1e300"); },
       "environment.wind_profile"},
      {"garbage gravity file with j2j4", [&](TempMission& t, const std::string&) {
         replace_once(t.mission(), "\"../environment/egm96_deg20.txt\"", "\"" + garbage + "\""); },
       [&](reentry::config::Mission& m, const std::string&) { m.environment.gravity_coefficients = garbage; },
       "environment.gravity_coefficients"},
  };
  const auto good = reentry::config::load_mission("x33");
  ASSERT_TRUE(good.ok) << good.error;
  for (const Case& c : cases) {
    TempMission t;
    c.edit_file(t, dir);
    const auto loaded = t.load();
    EXPECT_FALSE(loaded.ok) << c.name;
    EXPECT_NE(loaded.error.find(c.key), std::string::npos) << c.name << ": " << loaded.error;
    reentry::config::Mission m = good.mission;
    c.edit(m, dir);
    const std::string err = sim_error(m);
    EXPECT_NE(err.find(c.key), std::string::npos) << c.name << ": the simulator said '" << err << "'";
  }
}

TEST(MissionRules, StockMissionsPassBoth) {
  for (const char* name : {"x33", "horus", "orbiter", "x38", "x33_planned_alpha"}) {
    const auto r = reentry::config::load_mission(name);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(reentry::config::check_mission(r.mission), "") << name;
    EXPECT_EQ(sim_error(r.mission), "") << name;
    EXPECT_EQ(r.mission.digest.size(), 16u) << name;
  }
}

TEST(MissionRules, DigestChangesWithAnyFileOfTheMission) {
  TempMission a;
  const auto la = a.load();
  ASSERT_TRUE(la.ok) << la.error;
  TempMission c;
  c.mission() += "\n# a comment changes the file\n";
  const auto lc = c.load();
  ASSERT_TRUE(lc.ok) << lc.error;
  EXPECT_NE(la.mission.digest, lc.mission.digest);
  TempMission d;
  const auto ld = d.load();
  EXPECT_EQ(la.mission.digest, ld.mission.digest);
}

}  // namespace
