// reentry_fsw: the guidance process.
//   reentry_fsw --mission <name|file> [--mode lockstep|realtime] [--replay run.lcm] [--compare]
// Wires the core components (nav conversion, entry planner, tracker, rate filters) into the
// executive and runs the LCM adapter. All allocation happens here, before the loop starts.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "app/guidance_node.hpp"
#include "guidance/guidance_stack.hpp"
#include "nav/relative_state.hpp"
#include "reentry/config/mission.hpp"

namespace {

using namespace reentry::fsw;

Status convert_nav(const reentry::nav_state_t& nav, RelativeState& out, void*) {
  return relative_state_from_nav(nav.t_s, nav.position_I_m, nav.velocity_I_mps, nav.aero_accel_I_mps2,
                                 nav.earth_rotation_angle_rad, out);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"reentry guidance process"};
  std::string mission_arg, mode = "lockstep", replay, status_json;
  bool compare = false;
  double link_timeout_s = 2.0;
  cli.add_option("--mission", mission_arg, "mission name or TOML file")->required();
  cli.add_option("--mode", mode, "lockstep or realtime")->check(CLI::IsMember({"lockstep", "realtime"}));
  cli.add_option("--replay", replay, "replay the NAV_STATE messages of an LCM log");
  cli.add_flag("--compare", compare, "with --replay: compare with the logged GUIDANCE_CMD");
  cli.add_option("--status-json", status_json, "write the executive counters here at exit");
  cli.add_option("--link-timeout", link_timeout_s, "lockstep: seconds without nav before link loss");
  CLI11_PARSE(cli, argc, argv);

  const auto loaded = reentry::config::load_mission(mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "reentry_fsw: %s\n", loaded.error.c_str());
    return app::kExitUsage;
  }
  const auto& m = loaded.mission;
  const exec::PlanMode plan_mode = !replay.empty()       ? exec::PlanMode::kSynchronous
                                   : mode == "realtime" ? exec::PlanMode::kRealtime
                                                        : exec::PlanMode::kLockstep;
  GuidanceStack stack;
  const std::string err = stack.create(m, plan_mode);
  if (!err.empty()) {
    std::fprintf(stderr, "reentry_fsw: mission %s: %s\n", m.name.c_str(), err.c_str());
    return app::kExitUsage;
  }
  auto& executive = stack.executive;
  const auto& cfg = stack.config;
  auto node = std::make_unique<app::GuidanceNode>(*executive, &convert_nav, nullptr, cfg.gnc_rate_hz);
  int rc = app::kExitOk;
  if (!replay.empty()) {
    rc = node->run_replay(replay, compare);
  } else {
    lcm::LCM lcm;
    if (!lcm.good()) {
      std::fprintf(stderr, "reentry_fsw: LCM initialisation failed\n");
      return app::kExitUsage;
    }
    rc = node->run_live(lcm, mode == "realtime" ? app::RunMode::kRealtime : app::RunMode::kLockstep,
                        link_timeout_s, 30.0);
  }
  node->write_status_json(status_json);
  executive->shutdown();
  return rc;
}
