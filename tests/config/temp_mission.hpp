// A copy of the X-33 mission and vehicle files in a temporary directory, to be edited by a
// test and loaded (the loader's and the guidance adapter's bad-input tests).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "reentry/config/mission.hpp"

namespace reentry_test {

inline const std::string kConfigDir = REENTRY_TEST_CONFIG_DIR;

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void replace_once(std::string& text, const std::string& from, const std::string& to) {
  const size_t pos = text.find(from);
  ASSERT_NE(pos, std::string::npos) << "fixture text not found: " << from;
  text.replace(pos, from.size(), to);
}

class TempMission {
 public:
  TempMission() {
    dir_ = std::filesystem::temp_directory_path() /
           ("reentry_config_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    mission_ = slurp(kConfigDir + "/missions/x33.toml");
    vehicle_ = slurp(kConfigDir + "/vehicles/x33.toml");
  }
  ~TempMission() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string& mission() { return mission_; }
  std::string& vehicle() { return vehicle_; }
  std::string mission_path() const { return (dir_ / "mission.toml").string(); }
  std::string vehicle_path() const { return (dir_ / "vehicle.toml").string(); }
  reentry::config::LoadResult load() {
    std::string m = mission_;
    replace_once(m, "\"../vehicles/x33.toml\"", "\"vehicle.toml\"");
    size_t pos;
    while ((pos = m.find("\"../environment/")) != std::string::npos) m.replace(pos, 16, "\"" + kConfigDir + "/environment/");
    std::ofstream(mission_path()) << m;
    std::ofstream(vehicle_path()) << vehicle_;
    return reentry::config::load_mission(mission_path());
  }

 private:
  std::filesystem::path dir_;
  std::string mission_, vehicle_;
};

}  // namespace reentry_test
