// The guidance process's adapter (DESIGN §11): datagrams from our validated UDP-multicast
// transport (common/transport/udpm.hpp) decoded into preallocated messages, commands/status
// encoded into a preallocated buffer. Runs the executive one cycle per navigation message
// (lockstep), on absolute deadlines (realtime), or from a log (replay, driven by the ticks
// inside the messages). Every message received and sent is recorded in the process's own log.
#pragma once

#include <cstdint>
#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/tracker_status_t.hpp>
#include <reentry/run_control_t.hpp>
#include <string>

#include "exec/executive.hpp"
#include "transport/event_log.hpp"
#include "transport/exit_status.hpp"
#include "transport/run_log.hpp"
#include "transport/udpm.hpp"

namespace reentry::fsw::app {

/// Exit statuses of reentry_fsw (named in its last stderr line and in --status-json): the
/// table shared by every process and tool (transport/exit_status.hpp, tools/README.md).
using transport::exit_name;
using transport::kExitLinkLoss;        // no usable NAV_STATE for link_timeout_ticks periods
using transport::kExitLogDamaged;      // framing damaged (truncated, garbage, jumps) or inconsistent
using transport::kExitLogIncomplete;   // ticks, commands or END_OF_RUN missing
using transport::kExitNotReplayable;   // a whole log of another mission or of a realtime run
using transport::kExitOk;
using transport::kExitReplayDiffers;
using transport::kExitTransport;       // socket error
using transport::kExitUsage;
using transport::kExitWriteFailed;     // a log or the status JSON could not be written whole

/// Converts a navigation message into the Earth-relative state guidance works with.
using NavConvertFn = Status (*)(const nav_state_t& nav, RelativeState& out, void* ctx);

enum class RunMode : std::int8_t { kLockstep = 0, kRealtime = 1, kReplay = 2 };

/// The guidance process's own fields of guidance_status_t (the executive's come from its cycle
/// output and counters): named as in guidance_status_t.lcm, copied by the generated fill.
struct AdapterStatus {
  RunMode mode = RunMode::kLockstep;
  double jitter_us_last = 0.0;     // realtime: start-time deviation from the deadline
  double jitter_us_max = 0.0;
  std::int32_t cycle_overruns = 0;
  double plan_age_s = -1.0;        // since the plan in use was adopted (-1: none)
  std::int32_t bad_messages = 0;
  std::int32_t bad_datagrams = 0;
  std::int32_t rx_kernel_drops = 0;
  std::int32_t log_dropped = 0;
  double link_silent_ms = 0.0;
};

struct LiveOptions {
  int link_timeout_ticks = 3;       // simulator silent this many GNC periods: link loss
  double startup_timeout_s = 30.0;  // wait for the first navigation message
};

class GuidanceNode {
 public:
  GuidanceNode(exec::Executive& exec, NavConvertFn convert, void* convert_ctx, double gnc_rate_hz);

  /// Records everything received and sent into `path` (start-up; realtime drops rather than waits).
  bool open_log(const std::string& path, RunMode mode, std::string& error);
  /// Drains and closes the log (end of run, before the status JSON); false when it could not
  /// be written whole (the reason printed).
  bool close_log();

  /// Live run on the network until END_OF_RUN / STOP (kExitOk) or link loss (kExitLinkLoss):
  /// the safe command is then held and published with the link-loss flag before returning.
  int run_live(transport::UdpmSocket& net, RunMode mode, const LiveOptions& options);

  /// Replay a log: checks its seal (unless allow_unsealed), framing and completeness (every
  /// tick from 0, a GUIDANCE_CMD for each, END_OF_RUN right after the last sample), then runs
  /// every NAV_STATE through the executive and compares each command with the logged one.
  /// Prints `identical`, the first differing tick and field, or why the log cannot be
  /// replayed. out_log: the re-run's log (navs, commands, status, plans, END_OF_RUN).
  int run_replay(const std::string& log_path, bool compare, const std::string& out_log, bool allow_unsealed = false);
  /// The mission's name for the replay's messages (a log of another mission is named as such).
  void set_mission_name(const std::string& name) { mission_name_ = name; }

  /// One received datagram (the live loop, and the in-process fuzz test). May publish.
  void on_datagram(const char* channel, const std::uint8_t* payload, int len);

  /// Write the counters as JSON (end of run, ground tool output); false when it could not be
  /// written (the reason printed).
  bool write_status_json(const std::string& path, int exit_code) const;

  std::int32_t bad_messages() const { return bad_messages_; }
  const guidance_cmd_t& last_cmd() const { return cmd_; }
  const guidance_status_t& last_status() const { return status_; }
  std::int64_t commands_published() const { return commands_published_; }
  bool end_of_run() const { return end_of_run_; }
  /// Test hook: publish into this socket without a live loop (nullptr: publish nothing).
  void attach(transport::UdpmSocket* net, RunMode mode) {
    net_ = net;
    mode_ = mode;
  }

 private:
  void handle_nav(const nav_state_t& nav);
  void handle_run_control(const run_control_t& rc);
  exec::CycleOutput cycle(const nav_state_t& nav);
  void on_cycle(const exec::CycleOutput& out);
  void fill_cmd(const exec::CycleOutput& out);
  void fill_status(const exec::CycleOutput& out);
  void fill_tracker_status(const exec::CycleOutput& out);
  void fill_plan(std::int64_t tick);
  template <class Msg>
  void publish(const char* channel, const Msg& msg);
  void publish_heartbeat();
  void publish_safe(double silent_s);
  void note_nav_alive() { last_alive_ns_ = now_ns_; }
  int run_lockstep(transport::UdpmSocket& net, const LiveOptions& options);
  int run_realtime(transport::UdpmSocket& net, const LiveOptions& options);
  bool link_lost(std::int64_t now, std::int64_t since, const LiveOptions& options);
  int interrupted() const;
  int replay_commands(const transport::RunLogCheck& check, bool compare, bool keep_going);

  exec::Executive& exec_;
  NavConvertFn convert_;
  void* convert_ctx_;
  double dt_s_;
  RunMode mode_ = RunMode::kLockstep;
  transport::UdpmSocket* net_ = nullptr;
  transport::EventLogWriter log_;

  nav_state_t nav_rx_{};
  nav_state_t nav_newest_{};   // realtime: newest plausible sample of the period
  bool nav_pending_ = false;
  nav_state_t awaiting_nav_{};  // lockstep: the sample whose cycle waits for its plan
  run_control_t rc_rx_{};
  bool end_of_run_ = false;
  bool have_cmd_ = false;
  guidance_cmd_t cmd_{};
  guidance_status_t status_{};
  plan_t plan_{};
  tracker_status_t tracker_{};
  std::uint8_t tx_[65000] = {};
  std::int32_t bad_messages_ = 0;
  std::int32_t cycle_overruns_ = 0;
  std::int64_t commands_published_ = 0;
  double jitter_us_last_ = 0.0;
  double jitter_us_max_ = 0.0;
  std::int64_t now_ns_ = 0;         // time of the datagram / deadline being handled
  std::int64_t last_alive_ns_ = 0;  // last usable nav message
  std::int64_t last_heartbeat_ns_ = 0;
  std::int64_t last_tick_answered_ = -1;
  double link_silent_s_ = 0.0;
  std::string mission_name_ = "the mission";
  std::int64_t replayed_ = 0;  // commands compared by the replay
};

}  // namespace reentry::fsw::app
