// Is a run log complete? One rule for the replay, tools/loginfo and tools/sil: a lockstep run
// log holds every NAV_STATE tick from 0 (the entry interface) to the last, a GUIDANCE_CMD
// answering each, and RUN_CONTROL END_OF_RUN right after the last sample (the simulator ends
// at tick k without publishing sample k; a link-loss end is at the unanswered last sample);
// every event of those channels decodes, and a tick logged twice carries the same bytes (a
// republished sample). (Byte integrity is the seal's business: event_log.hpp.)
// Ground-side code (containers allowed).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/run_control_t.hpp>

namespace reentry::transport {

struct RunCompleteness {
  std::int64_t nav_events = 0;
  std::int64_t nav_ticks = 0;           // distinct ticks
  std::int64_t first_tick = -1, last_tick = -1;
  std::int64_t missing_ticks = 0, first_missing = -1;
  std::int64_t unanswered_ticks = 0, first_unanswered = -1;
  std::int64_t undecodable = 0;         // NAV_STATE / GUIDANCE_CMD / RUN_CONTROL events that do not decode
  std::int64_t conflicting_navs = 0, first_conflict = -1;
  bool end_of_run = false;
  std::int64_t end_tick = -1;
  std::int8_t end_event = 0;
  std::int64_t nav_after_end = 0;
  std::int8_t guidance_mode = -1;       // GUIDANCE_STATUS mode of the run (0 lockstep, 1 realtime), -1: none logged
  /// Content damage (undecodable, conflicting, samples after the end): the log is inconsistent.
  bool damaged() const { return undecodable > 0 || conflicting_navs > 0 || nav_after_end > 0 || (end_of_run && end_tick < last_tick); }
  /// Something missing (ticks, answers, the end).
  bool incomplete() const {
    return nav_ticks == 0 || first_tick != 0 || missing_ticks > 0 || unanswered_ticks > 0 || !end_of_run ||
           end_tick > last_tick + 1 || (end_tick == last_tick && !link_loss_end());
  }
  bool link_loss_end() const {
    return end_event == run_control_t::EVENT_LINK_LOSS || end_event == run_control_t::EVENT_ABORT;
  }
  bool complete() const { return !damaged() && !incomplete(); }
  /// The first reason the log is not complete (empty when it is).
  std::string problem() const;
};

const char* end_event_name(std::int8_t event);

class RunLogCheck {
 public:
  /// Feed every event of the log in order.
  void add(const std::string& channel, const std::uint8_t* data, int size);
  RunCompleteness result(bool require_commands = true) const;

  /// The decoded samples by tick (first of each) and commands by tick (the first answer of a
  /// tick is the one flown), and the raw END_OF_RUN message.
  const std::map<std::int64_t, std::vector<std::uint8_t>>& nav_bytes() const { return nav_bytes_; }
  const std::map<std::int64_t, nav_state_t>& navs() const { return navs_; }
  const std::map<std::int64_t, guidance_cmd_t>& commands() const { return cmds_; }
  const std::vector<std::uint8_t>& end_bytes() const { return end_bytes_; }

 private:
  std::map<std::int64_t, std::vector<std::uint8_t>> nav_bytes_;
  std::map<std::int64_t, nav_state_t> navs_;
  std::map<std::int64_t, guidance_cmd_t> cmds_;
  std::vector<std::uint8_t> end_bytes_;
  RunCompleteness r_;
};

}  // namespace reentry::transport
