// The guidance process's LCM adapter (DESIGN §11): raw subscriptions decoded into
// preallocated messages, commands/status encoded into a preallocated buffer and published
// as raw bytes. Runs the executive one cycle per navigation message (lockstep), on absolute
// deadlines (realtime), or from a log (replay, driven by the ticks inside the messages).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/tracker_status_t.hpp>
#include <reentry/run_control_t.hpp>
#include <string>

#include "exec/executive.hpp"

namespace reentry::fsw::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitLinkLoss = 3;
inline constexpr int kExitReplayDiffers = 4;
inline constexpr int kExitLogIncomplete = 5;

/// Converts a navigation message into the Earth-relative state guidance works with.
using NavConvertFn = Status (*)(const nav_state_t& nav, RelativeState& out, void* ctx);

enum class RunMode : std::int8_t { kLockstep = 0, kRealtime = 1, kReplay = 2 };

class GuidanceNode {
 public:
  GuidanceNode(exec::Executive& exec, NavConvertFn convert, void* convert_ctx, double gnc_rate_hz);

  /// Live run on the network. lockstep: a cycle per nav message, link loss after
  /// `lockstep_link_timeout_s` without nav; realtime: link loss after 3 periods without nav.
  int run_live(lcm::LCM& lcm, RunMode mode, double lockstep_link_timeout_s, double startup_timeout_s);

  /// Replay a log: every logged NAV_STATE (ordered by tick) through the executive, compare
  /// the computed commands with the logged GUIDANCE_CMD of the same tick. Prints `identical`
  /// or the first differing tick and field.
  int run_replay(const std::string& log_path, bool compare);

  /// One cycle: nav message -> command + status. False when nothing is to be published.
  bool cycle(const nav_state_t& nav, guidance_cmd_t& cmd, guidance_status_t& status, bool& plan_adopted);

  /// Write the counters as JSON (end of run, ground tool output).
  void write_status_json(const std::string& path) const;

  std::int32_t bad_messages() const { return bad_messages_; }

 private:
  static void on_nav(const lcm::ReceiveBuffer* rbuf, const std::string& channel, GuidanceNode* self);
  static void on_run_control(const lcm::ReceiveBuffer* rbuf, const std::string& channel, GuidanceNode* self);
  void publish_cycle(lcm::LCM& lcm, bool plan_adopted);
  void fill_tracker_status(const nav_state_t& nav, const TrackerTelemetry& t);
  void publish_safe_status(lcm::LCM& lcm);
  void fill_plan(std::int64_t tick);

  exec::Executive& exec_;
  NavConvertFn convert_;
  void* convert_ctx_;
  double dt_s_;
  RunMode mode_ = RunMode::kLockstep;

  nav_state_t nav_rx_{};
  nav_state_t nav_newest_{};
  bool nav_pending_ = false;
  run_control_t rc_rx_{};
  bool end_of_run_ = false;
  guidance_cmd_t cmd_{};
  guidance_status_t status_{};
  plan_t plan_{};
  tracker_status_t tracker_{};
  std::uint8_t tx_[65000] = {};
  std::int32_t bad_messages_ = 0;
  std::int32_t cycle_overruns_ = 0;
  double jitter_us_last_ = 0.0;
  double jitter_us_max_ = 0.0;
};

}  // namespace reentry::fsw::app
