// A copy of the X-33 mission and vehicle files in a temporary directory, to be edited by a
// test and loaded (the loader's and the guidance adapter's bad-input tests). The mission's own
// tuning tables ([guidance.*]) are left out: the tests add theirs before [sim], in [guidance].
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

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

// A new folder of its own directly in the temporary directory (mkdtemp: unique across
// processes and concurrent builds, whatever the test's name), removed whole with everything in it.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "reentry_test") {
    std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "_XXXXXX")).string();
    if (::mkdtemp(tmpl.data()) == nullptr) ADD_FAILURE() << "mkdtemp " << tmpl << " failed";
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string str() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

class TempMission {
 public:
  TempMission() : tmp_("reentry_config_test") {
    mission_ = slurp(kConfigDir + "/missions/x33.toml");
    vehicle_ = slurp(kConfigDir + "/vehicles/x33.toml");
    size_t table;
    while ((table = mission_.find("\n[guidance.")) != std::string::npos) {
      const size_t next = mission_.find("\n[", table + 1);
      mission_.erase(table, next == std::string::npos ? std::string::npos : next - table);
    }
  }
  const std::filesystem::path& dir() const { return tmp_.path(); }
  std::string& mission() { return mission_; }
  std::string& vehicle() { return vehicle_; }
  std::string mission_path() const { return (dir() / "mission.toml").string(); }
  std::string vehicle_path() const { return (dir() / "vehicle.toml").string(); }
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
  TempDir tmp_;
  std::string mission_, vehicle_;
};

}  // namespace reentry_test
