#include "transport/run_log.hpp"

#include "transport/lcm_codec.hpp"

namespace reentry::transport {

const char* end_event_name(std::int8_t event) {
  switch (event) {
    case run_control_t::EVENT_NONE: return "none";
    case run_control_t::EVENT_TAEM: return "taem";
    case run_control_t::EVENT_GROUND: return "ground";
    case run_control_t::EVENT_SKIP_OUT: return "skip_out";
    case run_control_t::EVENT_TIMEOUT: return "timeout";
    case run_control_t::EVENT_ABORT: return "abort";
    case run_control_t::EVENT_LINK_LOSS: return "link_loss";
    default: return "unknown";
  }
}

void RunLogCheck::add(const std::string& channel, const std::uint8_t* data, int size) {
  std::int32_t bad = 0;
  if (channel == "NAV_STATE") {
    ++r_.nav_events;
    nav_state_t nav{};
    if (!decode_into(nav, data, size, bad)) {
      ++r_.undecodable;
      return;
    }
    if (r_.end_of_run) ++r_.nav_after_end;
    std::vector<std::uint8_t> bytes(data, data + size);
    const auto it = nav_bytes_.find(nav.tick);
    if (it == nav_bytes_.end()) {
      nav_bytes_.emplace(nav.tick, std::move(bytes));
      navs_.emplace(nav.tick, nav);
    } else if (it->second != bytes && r_.conflicting_navs++ == 0) {
      r_.first_conflict = nav.tick;
    }
  } else if (channel == "GUIDANCE_CMD") {
    guidance_cmd_t cmd{};
    if (!decode_into(cmd, data, size, bad)) {
      ++r_.undecodable;
      return;
    }
    cmds_.emplace(cmd.tick, cmd);
  } else if (channel == "GUIDANCE_STATUS") {
    if (r_.guidance_mode >= 0) return;  // the first status names the run's mode
    guidance_status_t status{};
    if (decode_into(status, data, size, bad)) r_.guidance_mode = status.mode;
  } else if (channel == "RUN_CONTROL") {
    run_control_t rc{};
    if (!decode_into(rc, data, size, bad)) {
      ++r_.undecodable;
      return;
    }
    if (rc.command == run_control_t::END_OF_RUN && !r_.end_of_run) {
      r_.end_of_run = true;
      r_.end_tick = rc.tick;
      r_.end_event = rc.event;
      end_bytes_.assign(data, data + size);
    }
  }
}

RunCompleteness RunLogCheck::result(bool require_commands) const {
  RunCompleteness r = r_;
  r.nav_ticks = static_cast<std::int64_t>(navs_.size());
  if (!navs_.empty()) {
    r.first_tick = navs_.begin()->first;
    r.last_tick = navs_.rbegin()->first;
    r.missing_ticks = (r.last_tick - r.first_tick + 1) - r.nav_ticks;  // ticks are distinct: >= 0
    if (r.missing_ticks > 0) {
      std::int64_t expect = r.first_tick;
      for (const auto& kv : navs_) {
        if (kv.first != expect) break;
        ++expect;
      }
      r.first_missing = expect;
    }
    if (require_commands) {
      for (const auto& kv : navs_) {
        if (cmds_.count(kv.first) == 0 && r.unanswered_ticks++ == 0) r.first_unanswered = kv.first;
      }
    }
  }
  return r;
}

std::string RunCompleteness::problem() const {
  const auto s = [](std::int64_t v) { return std::to_string(v); };
  if (undecodable > 0) return s(undecodable) + " NAV_STATE / GUIDANCE_CMD / RUN_CONTROL events do not decode";
  if (conflicting_navs > 0) {
    return "NAV_STATE tick " + s(first_conflict) + " logged again with different content (" + s(conflicting_navs) + " times)";
  }
  if (nav_ticks == 0) return "no NAV_STATE message";
  if (first_tick != 0) return "the first NAV_STATE is tick " + s(first_tick) + ", not 0";
  if (missing_ticks > 0) {
    return s(missing_ticks) + " of " + s(last_tick - first_tick + 1) + " NAV_STATE ticks missing (first at tick " +
           s(first_missing) + ")";
  }
  if (unanswered_ticks > 0) {
    return s(unanswered_ticks) + " NAV_STATE ticks without a GUIDANCE_CMD (first at tick " + s(first_unanswered) + ")";
  }
  if (!end_of_run) return "no RUN_CONTROL END_OF_RUN after tick " + s(last_tick) + " (the run or the log was cut short)";
  if (nav_after_end > 0 || end_tick < last_tick) {
    return "END_OF_RUN at tick " + s(end_tick) + " but NAV_STATE up to tick " + s(last_tick);
  }
  if (end_tick > last_tick + 1) {
    return "END_OF_RUN at tick " + s(end_tick) + " but the NAV_STATE ticks end at " + s(last_tick) +
           ": the last samples are missing";
  }
  if (end_tick == last_tick && !link_loss_end()) {
    return "END_OF_RUN (event " + std::string(end_event_name(end_event)) + ") at the tick of the last NAV_STATE " +
           s(last_tick) + ": a normal end comes one tick after the last sample";
  }
  return {};
}

}  // namespace reentry::transport
