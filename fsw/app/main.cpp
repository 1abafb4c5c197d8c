// reentry_fsw: the guidance process.
//   reentry_fsw --mission <name|file> [--mode lockstep|realtime] [--log fsw.lcm] [--status-json F]
//               [--link-timeout-ticks N] [--replay run.lcm [--compare] [--replay-log out.lcm]]
// Wires the core components (nav conversion, entry planner, tracker, rate filters) into the
// executive and runs the process adapter. All allocation happens here, before the loop starts.
// The network is our validated UDP-multicast transport on $LCM_DEFAULT_URL (LCM's wire format).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "app/guidance_node.hpp"
#include "guidance/guidance_stack.hpp"
#include "nav/relative_state.hpp"
#include "reentry/config/mission.hpp"
#include "transport/monotonic_clock.hpp"
#include "transport/udpm.hpp"

namespace {

using namespace reentry::fsw;

Status convert_nav(const reentry::nav_state_t& nav, RelativeState& out, void*) {
  return relative_state_from_nav(nav.t_s, nav.position_I_m, nav.velocity_I_mps, nav.aero_accel_I_mps2,
                                 nav.earth_rotation_angle_rad, out);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"reentry guidance process"};
  std::string mission_arg, mode = "lockstep", replay, replay_log, status_json, log_path;
  bool compare = false, unsealed = false;
  app::LiveOptions live;
  cli.add_option("--mission", mission_arg, "mission name or TOML file")->required();
  cli.add_option("--mode", mode, "lockstep or realtime")->check(CLI::IsMember({"lockstep", "realtime"}));
  cli.add_option("--replay", replay, "replay the NAV_STATE messages of an LCM log");
  cli.add_flag("--compare", compare, "with --replay: compare with the logged GUIDANCE_CMD");
  cli.add_flag("--unsealed", unsealed, "with --replay: accept a log without a seal (not written by our tools)");
  cli.add_option("--replay-log", replay_log, "with --replay: write the re-run (navs, commands, status) to this log");
  cli.add_option("--status-json", status_json, "write the executive counters and the exit status here at exit");
  cli.add_option("--log", log_path, "record every message received and sent in this LCM log");
  cli.add_option("--link-timeout-ticks", live.link_timeout_ticks,
                 "GNC periods without a usable NAV_STATE that are a link loss")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--startup-timeout", live.startup_timeout_s, "seconds to wait for the first NAV_STATE")
      ->check(CLI::Range(0.1, 3600.0));
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
  executive->set_cycle_clock(&reentry::transport::thread_cpu_ns);  // cycle_us: the cycle's own compute time
  const auto& cfg = stack.config;
  auto node = std::make_unique<app::GuidanceNode>(*executive, &convert_nav, nullptr, cfg.gnc_rate_hz);
  int rc = app::kExitOk;
  auto net = std::make_unique<reentry::transport::UdpmSocket>();  // outlives the node's use of it
  if (!replay.empty()) {
    rc = node->run_replay(replay, compare, replay_log, unsealed);
  } else {
    const app::RunMode run_mode = mode == "realtime" ? app::RunMode::kRealtime : app::RunMode::kLockstep;
    reentry::transport::UdpmUrl url;
    std::string net_err;
    if (!reentry::transport::parse_udpm_url(reentry::transport::default_udpm_url(), url, net_err) ||
        !net->open(url, net_err)) {
      std::fprintf(stderr, "reentry_fsw: network: %s\n", net_err.c_str());
      return app::kExitTransport;
    }
    if (!node->open_log(log_path, run_mode, net_err)) {
      std::fprintf(stderr, "reentry_fsw: %s\n", net_err.c_str());
      return app::kExitTransport;
    }
    rc = node->run_live(*net, run_mode, live);
    node->close_log();
  }
  node->write_status_json(status_json, rc);
  executive->shutdown();
  return rc;
}
