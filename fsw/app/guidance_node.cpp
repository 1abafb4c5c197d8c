#include "app/guidance_node.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

#include "app/guidance_messages.hpp"
#include "transport/lcm_codec.hpp"
#include "transport/monotonic_clock.hpp"
#include "transport/run_log.hpp"

namespace reentry::fsw::app {
namespace {

using transport::decode_into;
using transport::encode_into;
using transport::mono_ns;
using transport::sleep_until_ns;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

bool is_channel(const char* a, const char* b) { return std::strcmp(a, b) == 0; }

constexpr std::int64_t kAwaitPollNs = 100000;    // lockstep: poll the plan every 100 us while it is late
constexpr std::int64_t kIdlePollNs = 20000000;   // otherwise wake at least every 20 ms
constexpr std::size_t kLogRingBytes = 16u << 20;  // ~60 s of lockstep traffic at full speed

std::int32_t clamp_i32(std::int64_t v) {
  return static_cast<std::int32_t>(std::min<std::int64_t>(v, 2147483647));
}

}  // namespace

GuidanceNode::GuidanceNode(exec::Executive& exec, NavConvertFn convert, void* convert_ctx, double gnc_rate_hz)
    : exec_(exec), convert_(convert), convert_ctx_(convert_ctx), dt_s_(1.0 / gnc_rate_hz) {}

bool GuidanceNode::open_log(const std::string& path, RunMode mode, std::string& error) {
  if (path.empty()) return true;
  const auto policy = mode == RunMode::kRealtime ? transport::EventLogWriter::WhenFull::kDrop
                                                 : transport::EventLogWriter::WhenFull::kWait;
  return log_.open(path, kLogRingBytes, policy, error);
}

bool GuidanceNode::close_log() {
  if (log_.close()) return true;
  std::fprintf(stderr, "reentry_fsw: write failed: %s\n", log_.error().c_str());
  return false;
}

template <class Msg>
void GuidanceNode::publish(const char* channel, const Msg& msg) {
  const int n = encode_into(msg, tx_, static_cast<int>(sizeof tx_));
  if (n <= 0) return;
  if (net_ != nullptr) net_->publish(channel, tx_, n);
  log_.record(channel, tx_, n);
}

void GuidanceNode::on_datagram(const char* channel, const std::uint8_t* payload, int len) {
  now_ns_ = mono_ns();
  if (is_channel(channel, "NAV_STATE")) {
    log_.record(channel, payload, len);
    if (!decode_into(nav_rx_, payload, len, bad_messages_)) return;
    handle_nav(nav_rx_);
  } else if (is_channel(channel, "RUN_CONTROL")) {
    log_.record(channel, payload, len);
    if (!decode_into(rc_rx_, payload, len, bad_messages_)) return;
    handle_run_control(rc_rx_);
  }
  // Other channels (our own output looped back, truth telemetry) are not ours to read.
}

void GuidanceNode::handle_run_control(const run_control_t& rc) {
  const bool ends = rc.command == run_control_t::END_OF_RUN || rc.command == run_control_t::STOP;
  if (!ends) {
    if (rc.command != run_control_t::START) ++bad_messages_;  // unknown command
    return;
  }
  // Only an end that belongs to this run: at the last answered tick or just ahead of it.
  const bool plausible = rc.tick >= 0 && (rc.tick == last_tick_answered_ || exec_.tick_in_window(rc.tick));
  if (!plausible) {
    ++bad_messages_;
    return;
  }
  end_of_run_ = true;
}

exec::CycleOutput GuidanceNode::cycle(const nav_state_t& nav) {
  exec::NavInput in;
  in.tick = nav.tick;
  if (convert_(nav, in.state, convert_ctx_) != Status::kOk) {
    in.state = RelativeState{};
    in.state.t_s = nav.t_s;  // the tick/time windows still apply; the values are rejected: command held
    in.values_valid = false;
  }
  return exec_.step(in);
}

void GuidanceNode::handle_nav(const nav_state_t& nav) {
  if (mode_ == RunMode::kRealtime) {
    // The newest plausible sample of the period is flown at the next deadline; anything the
    // executive would refuse anyway goes to it now, to be counted.
    if (exec_.tick_in_window(nav.tick)) {
      note_nav_alive();  // a plausible tick, stamped at its arrival (its values are judged at the deadline)
      if (!nav_pending_ || nav.tick > nav_newest_.tick) {
        nav_newest_ = nav;
        nav_pending_ = true;
      }
      return;
    }
    const exec::CycleOutput out = cycle(nav);
    if (out.nav_verdict == exec::NavVerdict::kDuplicate) note_nav_alive();
    return;
  }
  const bool was_awaiting = exec_.awaiting_plan();
  const exec::CycleOutput out = cycle(nav);
  if (out.nav_verdict != exec::NavVerdict::kRejectedTick) note_nav_alive();
  if (out.awaiting_plan) {
    if (!was_awaiting) {
      awaiting_nav_ = nav;
      last_heartbeat_ns_ = now_ns_;
    }
    return;
  }
  if (out.emitted) {
    on_cycle(out);
  } else if (out.nav_verdict == exec::NavVerdict::kDuplicate && have_cmd_ && nav.tick == cmd_.tick) {
    // The simulator repeats a nav message while it waits: answer again (same command).
    publish("GUIDANCE_CMD", cmd_);
  }
}

void GuidanceNode::fill_cmd(const exec::CycleOutput& out) { fill_command(out, cmd_); }

void GuidanceNode::fill_status(const exec::CycleOutput& out) {
  // The process's own fields; the executive's come from its cycle output and counters, each by
  // its name in guidance_status_t.lcm (generated fill: a field without a source does not build).
  const exec::ExecCounters& c = exec_.counters();
  AdapterStatus a;
  a.mode = mode_;
  a.jitter_us_last = jitter_us_last_;
  a.jitter_us_max = jitter_us_max_;
  a.cycle_overruns = cycle_overruns_;
  a.plan_age_s = c.plan_adopted_t_s >= 0.0 ? out.t_s - c.plan_adopted_t_s : -1.0;
  a.bad_messages = bad_messages_;
  if (net_ != nullptr) {
    a.bad_datagrams = clamp_i32(net_->counters().bad_datagrams);
    a.rx_kernel_drops = clamp_i32(net_->counters().kernel_drops);
  } else {  // no socket (replay, tests): the last figures stand
    a.bad_datagrams = status_.bad_datagrams;
    a.rx_kernel_drops = status_.rx_kernel_drops;
  }
  a.log_dropped = clamp_i32(log_.dropped());
  a.link_silent_ms = link_silent_s_ * 1e3;
  reentry::stamp(status_, out.t_s, out.tick);
  reentry::fill(status_, out, c, a);
}

void GuidanceNode::on_cycle(const exec::CycleOutput& out) {
  fill_cmd(out);
  fill_status(out);
  have_cmd_ = true;
  last_tick_answered_ = out.tick;
  publish("GUIDANCE_CMD", cmd_);
  ++commands_published_;
  publish("GUIDANCE_STATUS", status_);
  fill_tracker_status(out);
  publish("TRACKER_STATUS", tracker_);
  if (out.plan_adopted) {
    fill_plan(out.tick);
    publish("PLAN", plan_);
  }
}

void GuidanceNode::fill_tracker_status(const exec::CycleOutput& out) { app::fill_tracker_status(out, tracker_); }

void GuidanceNode::fill_plan(std::int64_t tick) {
  app::fill_plan(exec_.active_profile(), cmd_.utime, tick, exec_.counters().planner_ms_last, plan_);
}

void GuidanceNode::publish_heartbeat() {
  // A lockstep cycle waits for its plan: tell the simulator we are alive and why it waits.
  exec::CycleOutput o = exec_.last_valid_output();
  o.tick = exec_.awaiting_tick();
  o.t_s = awaiting_nav_.t_s;
  fill_status(o);
  status_.health_flags |= exec::kHealthPlanWait;
  publish("GUIDANCE_STATUS", status_);
}

void GuidanceNode::publish_safe(double silent_s) {
  // Link loss: the last valid attitude is held, in the safe phase, flagged.
  exec::CycleOutput o = exec_.last_valid_output();
  o.tick = last_tick_answered_ >= 0 ? last_tick_answered_ : 0;
  o.phase = Phase::kSafe;
  o.health_flags |= exec::kHealthLinkLoss;
  link_silent_s_ = silent_s;
  fill_cmd(o);
  fill_status(o);
  publish("GUIDANCE_CMD", cmd_);
  publish("GUIDANCE_STATUS", status_);
}

bool GuidanceNode::link_lost(std::int64_t now, std::int64_t since, const LiveOptions& options) {
  const bool started = last_tick_answered_ >= 0;
  const std::int64_t period_ns = static_cast<std::int64_t>(std::llround(dt_s_ * 1e9));
  const std::int64_t silent = now - since;
  link_silent_s_ = static_cast<double>(silent) * 1e-9;
  const std::int64_t limit = started ? static_cast<std::int64_t>(options.link_timeout_ticks) * period_ns
                                     : static_cast<std::int64_t>(options.startup_timeout_s * 1e9);
  if (silent <= limit) return false;
  publish_safe(link_silent_s_);
  std::fprintf(stderr,
               "reentry_fsw: link loss: no NAV_STATE for %.3f s (%d ticks of %.3f s) after tick %lld; "
               "safe command held (alpha %.2f deg, sigma %.2f deg), health flag link_loss; exit %d (%s)\n",
               link_silent_s_, options.link_timeout_ticks, dt_s_, static_cast<long long>(last_tick_answered_),
               cmd_.alpha_rad * 180.0 / M_PI, cmd_.sigma_rad * 180.0 / M_PI, kExitLinkLoss, exit_name(kExitLinkLoss));
  return true;
}

int GuidanceNode::interrupted() const {
  const int sig = transport::g_stop_signal;
  std::fprintf(stderr, "reentry_fsw: interrupted by signal %d after tick %lld: log sealed; exit %d\n", sig,
               static_cast<long long>(last_tick_answered_), transport::kExitSignalBase + sig);
  return transport::kExitSignalBase + sig;
}

int GuidanceNode::run_live(transport::UdpmSocket& net, RunMode mode, const LiveOptions& options) {
  mode_ = mode;
  net_ = &net;
  last_alive_ns_ = mono_ns();
  return mode == RunMode::kLockstep ? run_lockstep(net, options) : run_realtime(net, options);
}

int GuidanceNode::run_lockstep(transport::UdpmSocket& net, const LiveOptions& options) {
  const std::int64_t period_ns = static_cast<std::int64_t>(std::llround(dt_s_ * 1e9));
  transport::Datagram d;
  std::int64_t last_answer_ns = last_alive_ns_;
  for (;;) {
    if (transport::g_stop_signal != 0) return interrupted();
    const int r = net.receive(d, exec_.awaiting_plan() ? kAwaitPollNs : kIdlePollNs);
    if (r < 0) {
      if (transport::g_stop_signal != 0) return interrupted();
      std::fprintf(stderr, "reentry_fsw: receive failed; exit %d (%s)\n", kExitTransport, exit_name(kExitTransport));
      return kExitTransport;
    }
    const std::int64_t answered_before = commands_published_;
    if (r == 1) on_datagram(d.channel, d.payload, d.payload_len);
    const std::int64_t now = mono_ns();
    if (end_of_run_) return kExitOk;
    if (exec_.awaiting_plan()) {
      now_ns_ = now;
      const exec::CycleOutput out = exec_.resume();
      if (!out.awaiting_plan) {
        on_cycle(out);
      } else if (now - last_heartbeat_ns_ >= period_ns) {
        last_heartbeat_ns_ = now;
        publish_heartbeat();
      }
    }
    if (commands_published_ != answered_before) last_answer_ns = now;
    // The simulator owes the next sample from our last answer on; while our cycle waits for
    // its plan we owe the answer (the heartbeats tell the simulator so).
    if (!exec_.awaiting_plan() && link_lost(now, std::max(last_alive_ns_, last_answer_ns), options)) return kExitLinkLoss;
  }
}

int GuidanceNode::run_realtime(transport::UdpmSocket& net, const LiveOptions& options) {
  // Absolute deadlines start + i*period, newest plausible nav consumed each cycle.
  const std::int64_t period_ns = static_cast<std::int64_t>(std::llround(dt_s_ * 1e9));
  const std::int64_t start_ns = last_alive_ns_;
  transport::Datagram d;
  for (std::int64_t i = 1;; ++i) {
    const std::int64_t deadline = start_ns + i * period_ns;
    sleep_until_ns(deadline);
    if (transport::g_stop_signal != 0) return interrupted();
    const std::int64_t woke = mono_ns();
    jitter_us_last_ = static_cast<double>(woke - deadline) * 1e-3;
    jitter_us_max_ = std::max(jitter_us_max_, jitter_us_last_);
    for (;;) {
      const int r = net.receive(d, 0);
      if (r < 0) {
        std::fprintf(stderr, "reentry_fsw: receive failed; exit %d (%s)\n", kExitTransport, exit_name(kExitTransport));
        return kExitTransport;
      }
      if (r == 0) break;
      on_datagram(d.channel, d.payload, d.payload_len);
    }
    if (end_of_run_) return kExitOk;
    now_ns_ = woke;
    if (nav_pending_) {
      nav_pending_ = false;
      const exec::CycleOutput out = cycle(nav_newest_);
      if (out.emitted) on_cycle(out);
    }
    if (mono_ns() > deadline + period_ns) ++cycle_overruns_;
    if (link_lost(mono_ns(), last_alive_ns_, options)) return kExitLinkLoss;
  }
}

namespace {

/// Reads and judges a log for replay (ground side: containers are fine here). kExitOk when it
/// can be replayed, else the exit status, with the reason printed.
int check_replay_log(const std::string& log_path, bool compare, bool allow_unsealed, transport::RunLogCheck& check,
                     transport::RunCompleteness& run) {
  std::string channel;
  const transport::LogFraming fr = transport::read_event_log(log_path, [&](const transport::LogEventView& ev) {
    channel.assign(ev.channel, static_cast<std::size_t>(ev.channel_len));
    check.add(channel, ev.data, ev.size);
    return true;
  });
  if (!fr.error.empty()) {
    std::printf("damaged log: %s\n", fr.error.c_str());
    return kExitLogDamaged;
  }
  if (fr.malformed()) {
    std::printf("damaged log: %s; a damaged log is never replayed\n", fr.describe().c_str());
    return kExitLogDamaged;
  }
  // Lockstep replay needs every tick from the entry interface on, an answer to each, and the
  // end of the run: a log without them cannot reproduce the run and is named, never compared.
  run = check.result(compare);
  if (run.guidance_mode == static_cast<std::int8_t>(RunMode::kRealtime)) {
    std::printf("not replayable: %s is the log of a realtime run (plans adopted when ready, ticks skipped): only a "
                "lockstep run is reproduced bit for bit\n", log_path.c_str());
    return kExitNotReplayable;
  }
  if (run.damaged()) {
    std::printf("damaged log: %s\n", run.problem().c_str());
    return kExitLogDamaged;
  }
  if (run.incomplete()) {
    std::printf("incomplete log: %s; replay needs every tick, its command and END_OF_RUN\n", run.problem().c_str());
    return kExitLogIncomplete;
  }
  if (!fr.sealed && !allow_unsealed) {
    std::printf("incomplete log: no seal at the end (its writer did not close it, or it was cut at an event "
                "boundary, or another tool wrote it): nothing proves it whole; --unsealed replays it anyway\n");
    return kExitLogIncomplete;
  }
  if (fr.seal_dropped > 0) {
    std::printf("incomplete log: its writer dropped %lld records\n", static_cast<long long>(fr.seal_dropped));
    return kExitLogIncomplete;
  }
  return kExitOk;
}

/// The first command field that differs between the replayed and the logged command (bit for
/// bit for the doubles), or nullptr.
const char* first_differing_field(const guidance_cmd_t& c, const guidance_cmd_t& r, double& a, double& b) {
  const struct {
    const char* name;
    double replayed, logged;
    bool differs;
  } fields[] = {
      {"alpha_rad", c.alpha_rad, r.alpha_rad, !same_bits(c.alpha_rad, r.alpha_rad)},
      {"sigma_rad", c.sigma_rad, r.sigma_rad, !same_bits(c.sigma_rad, r.sigma_rad)},
      {"beta_rad", c.beta_rad, r.beta_rad, !same_bits(c.beta_rad, r.beta_rad)},
      {"mode", static_cast<double>(c.mode), static_cast<double>(r.mode), c.mode != r.mode},
      {"plan_seq", static_cast<double>(c.plan_seq), static_cast<double>(r.plan_seq), c.plan_seq != r.plan_seq},
  };
  for (const auto& f : fields) {
    if (!f.differs) continue;
    a = f.replayed;
    b = f.logged;
    return f.name;
  }
  return nullptr;
}

}  // namespace

int GuidanceNode::run_replay(const std::string& log_path, bool compare, const std::string& out_log,
                             bool allow_unsealed) {
  mode_ = RunMode::kReplay;
  net_ = nullptr;
  transport::RunLogCheck check;
  transport::RunCompleteness run;
  const int verdict = check_replay_log(log_path, compare, allow_unsealed, check, run);
  if (verdict != kExitOk) return verdict;
  std::string err;
  if (!out_log.empty() && !open_log(out_log, RunMode::kReplay, err)) {
    std::fprintf(stderr, "reentry_fsw: write failed: %s\n", err.c_str());
    return kExitWriteFailed;
  }
  const int rc = replay_commands(check, compare, !out_log.empty());
  const std::vector<std::uint8_t>& end = check.end_bytes();
  log_.record("RUN_CONTROL", end.data(), static_cast<int>(end.size()));
  if (!close_log()) return kExitWriteFailed;  // a re-run log that is not whole is never "identical"
  if (compare && rc == kExitOk) {
    std::printf("identical (%lld commands, ticks 0..%lld, END_OF_RUN at tick %lld, event %s)\n",
                static_cast<long long>(replayed_), static_cast<long long>(run.last_tick),
                static_cast<long long>(run.end_tick), transport::end_event_name(run.end_event));
  }
  return rc;
}

int GuidanceNode::replay_commands(const transport::RunLogCheck& check, bool compare, bool keep_going) {
  replayed_ = 0;
  int rc_code = kExitOk;
  const auto& logged = check.commands();
  for (const auto& [tick, n] : check.navs()) {
    const std::vector<std::uint8_t>& bytes = check.nav_bytes().at(tick);
    log_.record("NAV_STATE", bytes.data(), static_cast<int>(bytes.size()));
    const exec::CycleOutput out = cycle(n);
    if (tick == 0 && out.nav_verdict == exec::NavVerdict::kRejectedValues) {
      // The entry interface of the log is not this mission's: the log is of another mission.
      std::printf("not replayable: the log's tick-0 sample is not at the entry interface of %s (its position, "
                  "speed or flight-path angle lies outside the entry dispersions): the log is of another mission\n",
                  mission_name_.c_str());
      return kExitNotReplayable;
    }
    if (!out.emitted) continue;
    on_cycle(out);
    if (!compare || rc_code != kExitOk) continue;
    double a = 0.0, b = 0.0;
    const char* field = first_differing_field(cmd_, logged.at(tick), a, b);
    if (field != nullptr) {
      std::printf("differs at tick %lld field %s (replayed %.17g, logged %.17g)\n", static_cast<long long>(tick), field,
                  a, b);
      rc_code = kExitReplayDiffers;
      if (!keep_going) break;
    }
    ++replayed_;
  }
  return rc_code;
}

bool GuidanceNode::write_status_json(const std::string& path, int exit_code) const {
  if (path.empty()) return true;
  const exec::ExecCounters& c = exec_.counters();
  std::ofstream f(path);
  f << "{\n"
    << "  \"exit\": \"" << exit_name(exit_code) << "\",\n"
    << "  \"exit_code\": " << exit_code << ",\n"
    << "  \"planner_runs\": " << c.planner_runs << ",\n"
    << "  \"planner_failures\": " << c.planner_failures << ",\n"
    << "  \"last_plan_status\": \"" << to_string(c.last_plan_status) << "\",\n"
    << "  \"planner_ms_max\": " << c.planner_ms_max << ",\n"
    << "  \"plan_overruns\": " << c.plan_overruns << ",\n"
    << "  \"plan_waits\": " << c.plan_waits << ",\n"
    << "  \"plan_wait_ms_max\": " << c.plan_wait_ms_max << ",\n"
    << "  \"plan_wait_ms_total\": " << c.plan_wait_ms_total << ",\n"
    << "  \"plan_timeouts\": " << c.plan_timeouts << ",\n"
    << "  \"plans_adopted\": " << c.plans_adopted << ",\n"
    << "  \"cycle_us_max\": " << c.cycle_us_max << ",\n"
    << "  \"cycle_overruns\": " << cycle_overruns_ << ",\n"
    << "  \"jitter_us_max\": " << jitter_us_max_ << ",\n"
    << "  \"commands\": " << commands_published_ << ",\n"
    << "  \"last_tick\": " << last_tick_answered_ << ",\n"
    << "  \"invalid_nav\": " << c.invalid_nav << ",\n"
    << "  \"nav_rejected_values\": " << c.nav_rejected_values << ",\n"
    << "  \"nav_rejected_tick\": " << c.nav_rejected_tick << ",\n"
    << "  \"nav_reacquired\": " << c.nav_reacquired << ",\n"
    << "  \"duplicate_ticks\": " << c.duplicate_ticks << ",\n"
    << "  \"skipped_ticks\": " << c.skipped_ticks << ",\n"
    << "  \"bad_messages\": " << bad_messages_ << ",\n"
    << "  \"bad_datagrams\": " << (net_ != nullptr ? net_->counters().bad_datagrams : 0) << ",\n"
    << "  \"rx_kernel_drops\": " << (net_ != nullptr ? net_->counters().kernel_drops : 0) << ",\n"
    << "  \"log_recorded\": " << log_.recorded() << ",\n"
    << "  \"log_dropped\": " << log_.dropped() << ",\n"
    << "  \"link_silent_ms\": " << link_silent_s_ * 1e3 << "\n"
    << "}\n";
  f.close();
  if (!f) {
    std::fprintf(stderr, "reentry_fsw: write failed: %s: %s\n", path.c_str(), std::strerror(errno));
    return false;
  }
  return true;
}

}  // namespace reentry::fsw::app
