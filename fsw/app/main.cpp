// reentry_fsw: the guidance process.
//   reentry_fsw --mission <name|file> [--mode lockstep|realtime] [--log fsw.lcm] [--status-json F]
//               [--link-timeout-ticks N] [--replay run.lcm [--compare] [--replay-log out.lcm]
//               [--mission-digest D]]
// Exit statuses: the table of transport/exit_status.hpp (tools/README.md); SIGINT/SIGTERM/SIGHUP
// end a live run with the log sealed (128 + signal).
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
#include "transport/command_line.hpp"
#include "transport/monotonic_clock.hpp"
#include "transport/udpm.hpp"

namespace {

using namespace reentry::fsw;

Status convert_nav(const reentry::nav_state_t& nav, RelativeState& out, void*) {
  return relative_state_from_nav(nav.t_s, nav.position_I_m, nav.velocity_I_mps, nav.aero_accel_I_mps2,
                                 nav.earth_rotation_angle_rad, out);
}

struct Options {
  std::string mission_arg, mode = "lockstep", replay, replay_log, status_json, log_path, mission_digest;
  bool compare = false, unsealed = false;
  app::LiveOptions live;
};

int parse_options(int argc, char** argv, Options& o) {
  CLI::App cli{"reentry guidance process", "reentry_fsw"};
  cli.add_option("--mission", o.mission_arg, "mission name or TOML file")->required();
  cli.add_option("--mode", o.mode, "lockstep or realtime")->check(CLI::IsMember({"lockstep", "realtime"}));
  cli.add_option("--replay", o.replay, "replay the NAV_STATE messages of an LCM log");
  cli.add_flag("--compare", o.compare, "with --replay: compare with the logged GUIDANCE_CMD");
  cli.add_flag("--unsealed", o.unsealed, "with --replay: accept a log without a seal (not written by our tools)");
  cli.add_option("--replay-log", o.replay_log, "with --replay: write the re-run (navs, commands, status) to this log");
  cli.add_option("--mission-digest", o.mission_digest,
                 "with --replay: the digest of the mission the run was flown with (its summary.json)");
  cli.add_option("--status-json", o.status_json, "write the executive counters and the exit status here at exit");
  cli.add_option("--log", o.log_path, "record every message received and sent in this LCM log");
  cli.add_option("--link-timeout-ticks", o.live.link_timeout_ticks,
                 "GNC periods without a usable NAV_STATE that are a link loss")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--startup-timeout", o.live.startup_timeout_s, "seconds to wait for the first NAV_STATE")
      ->check(CLI::Range(0.1, 3600.0));
  return reentry::transport::parse_command_line(cli, argc, argv, "reentry_fsw");
}

// The live run on the network (lockstep or realtime) with its own log.
int fly_live(app::GuidanceNode& node, reentry::transport::UdpmSocket& net, const Options& o) {
  const app::RunMode run_mode = o.mode == "realtime" ? app::RunMode::kRealtime : app::RunMode::kLockstep;
  reentry::transport::UdpmUrl url;
  std::string net_err;
  if (!reentry::transport::parse_udpm_url(reentry::transport::default_udpm_url(), url, net_err) ||
      !net.open(url, net_err)) {
    std::fprintf(stderr, "reentry_fsw: network: %s\n", net_err.c_str());
    return app::kExitTransport;
  }
  if (!node.open_log(o.log_path, run_mode, net_err)) {
    std::fprintf(stderr, "reentry_fsw: write failed: %s\n", net_err.c_str());
    return app::kExitWriteFailed;
  }
  reentry::transport::install_stop_handlers();
  const int rc = node.run_live(net, run_mode, o.live);
  return node.close_log() ? rc : app::kExitWriteFailed;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const int parsed = parse_options(argc, argv, o);
  if (parsed >= 0) return parsed;
  const auto loaded = reentry::config::load_mission(o.mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "reentry_fsw: mission refused: %s\n", loaded.error.c_str());
    return app::kExitUsage;
  }
  const auto& m = loaded.mission;
  if (!o.replay.empty() && !o.mission_digest.empty() && o.mission_digest != m.digest) {
    std::printf("not replayable: %s was flown with mission %s of digest %s; %s now has digest %s (its files changed "
                "since the run)\n", o.replay.c_str(), m.name.c_str(), o.mission_digest.c_str(), m.source_file.c_str(),
                m.digest.c_str());
    return app::kExitNotReplayable;
  }
  const exec::PlanMode plan_mode = !o.replay.empty()       ? exec::PlanMode::kSynchronous
                                   : o.mode == "realtime" ? exec::PlanMode::kRealtime
                                                          : exec::PlanMode::kLockstep;
  GuidanceStack stack;
  const std::string err = stack.create(m, plan_mode);
  if (!err.empty()) {
    std::fprintf(stderr, "reentry_fsw: mission refused: %s: %s\n", m.name.c_str(), err.c_str());
    return app::kExitUsage;
  }
  auto& executive = stack.executive;
  executive->set_cycle_clock(&reentry::transport::thread_cpu_ns);  // cycle_us: the cycle's own compute time
  auto node = std::make_unique<app::GuidanceNode>(*executive, &convert_nav, nullptr, stack.config.gnc_rate_hz);
  node->set_mission_name("mission " + m.name + " (" + m.source_file + ")");
  auto net = std::make_unique<reentry::transport::UdpmSocket>();  // outlives the node's use of it
  int rc = o.replay.empty() ? fly_live(*node, *net, o) : node->run_replay(o.replay, o.compare, o.replay_log, o.unsealed);
  if (!node->write_status_json(o.status_json, rc)) rc = app::kExitWriteFailed;
  executive->shutdown();
  return rc;
}
