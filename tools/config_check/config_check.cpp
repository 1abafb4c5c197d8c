// reentry_config_check: load one or more missions (names or paths) and build the guidance's
// start-up data from each (parameters, on-board tables, alpha profile), as reentry_fsw does;
// print one summary line each, or with --params every guidance tunable with its value, unit,
// documented range and meaning. Exit status 1 with the message naming file, key and value on
// the first failure, 2 on a usage error.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "guidance/alpha_profile_source.hpp"
#include "guidance/mission_adapter.hpp"
#include "reentry/config/mission.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Validate mission files as the guidance process takes them"};
  std::vector<std::string> missions;
  bool params = false;
  app.add_option("missions", missions, "mission names (x33, horus, orbiter, x38, ...) or .toml files")->required();
  app.add_flag("--params", params, "list the guidance tunables of each mission (key = value [range] meaning)");
  CLI11_PARSE(app, argc, argv);
  for (const std::string& name : missions) {
    reentry::config::LoadResult result = reentry::config::load_mission(name);
    if (!result.ok) {
      std::fprintf(stderr, "%s\n", result.error.c_str());
      return 1;
    }
    std::string error = reentry::fsw::resolve_alpha_profile(result.mission);
    auto setup = std::make_unique<reentry::fsw::GuidanceSetup>();
    if (error.empty()) error = reentry::fsw::make_guidance_setup(result.mission, *setup);
    if (!error.empty()) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    std::printf("%s\n", reentry::config::summary_line(result.mission).c_str());
    if (params) {
      std::printf("guidance.law = %s   {drag_tracking, predictor_corrector}   guidance law flown\n",
                  result.mission.guidance.law.c_str());
      std::printf("%s", reentry::fsw::describe_guidance_params(setup->params).c_str());
      std::printf("%s", reentry::fsw::describe_pc_params(setup->pc_params).c_str());
    }
  }
  return 0;
}
