#include "app/guidance_node.hpp"

#include <lcm/lcm-cpp.hpp>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <vector>

#include "transport/lcm_codec.hpp"
#include "transport/monotonic_clock.hpp"

namespace reentry::fsw::app {
namespace {

using transport::decode_into;
using transport::encode_into;
using transport::mono_ns;
using transport::sleep_until_ns;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

}  // namespace

GuidanceNode::GuidanceNode(exec::Executive& exec, NavConvertFn convert, void* convert_ctx, double gnc_rate_hz)
    : exec_(exec), convert_(convert), convert_ctx_(convert_ctx), dt_s_(1.0 / gnc_rate_hz) {}

void GuidanceNode::on_nav(const lcm::ReceiveBuffer* rbuf, const std::string&, GuidanceNode* self) {
  if (!decode_into(self->nav_rx_, rbuf->data, static_cast<int>(rbuf->data_size), self->bad_messages_)) return;
  if (!self->nav_pending_ || self->nav_rx_.tick >= self->nav_newest_.tick) {
    self->nav_newest_ = self->nav_rx_;
    self->nav_pending_ = true;
  }
}

void GuidanceNode::on_run_control(const lcm::ReceiveBuffer* rbuf, const std::string&, GuidanceNode* self) {
  if (!decode_into(self->rc_rx_, rbuf->data, static_cast<int>(rbuf->data_size), self->bad_messages_)) return;
  if (self->rc_rx_.command == run_control_t::END_OF_RUN || self->rc_rx_.command == run_control_t::STOP) {
    self->end_of_run_ = true;
  }
}

bool GuidanceNode::cycle(const nav_state_t& nav, guidance_cmd_t& cmd, guidance_status_t& status,
                         bool& plan_adopted) {
  exec::NavInput in;
  in.tick = nav.tick;
  if (convert_(nav, in.state, convert_ctx_) != Status::kOk) {
    in.state = RelativeState{};
    in.state.t_s = nav.t_s;  // the tick/time windows still apply; the values are rejected: command held
    in.values_valid = false;
  }
  exec::CycleOutput out = exec_.step(in);
  while (out.awaiting_plan) {  // lockstep: the plan due now is late; wait for it
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    out = exec_.resume();
  }
  plan_adopted = out.plan_adopted;
  if (!out.emitted) return false;
  const exec::ExecCounters& c = exec_.counters();
  cmd.utime = nav.utime;
  cmd.tick = nav.tick;
  cmd.alpha_rad = out.alpha_rad;
  cmd.beta_rad = 0.0;
  cmd.sigma_rad = out.sigma_rad;
  cmd.mode = static_cast<std::int8_t>(out.phase);
  cmd.plan_seq = out.plan_seq;
  cmd.health_flags = out.health_flags;
  status.utime = nav.utime;
  status.tick = nav.tick;
  status.phase = static_cast<std::int8_t>(out.phase);
  status.mode = static_cast<std::int8_t>(mode_);
  status.health_flags = out.health_flags;
  status.cycle_us_last = c.cycle_us_last;
  status.cycle_us_max = c.cycle_us_max;
  status.jitter_us_last = jitter_us_last_;
  status.jitter_us_max = jitter_us_max_;
  status.cycle_overruns = cycle_overruns_;
  status.plan_overruns = c.plan_overruns;  // plans over their L / f budget (lockstep waits are not overruns)
  status.planner_runs = c.planner_runs;
  status.planner_ms_last = c.planner_ms_last;
  status.planner_ms_max = c.planner_ms_max;
  status.plan_age_s = c.plan_adopted_t_s >= 0.0 ? nav.t_s - c.plan_adopted_t_s : -1.0;
  status.plan_latency_ms = c.plan_latency_ms;
  status.plan_seq = out.plan_seq;
  status.bad_messages = bad_messages_;
  status.invalid_nav = c.invalid_nav;
  status.duplicate_ticks = c.duplicate_ticks;
  status.skipped_ticks = c.skipped_ticks;
  status.drag_err_mps2 = out.drag_err_mps2;
  status.heading_err_rad = out.heading_err_rad;
  return true;
}

void GuidanceNode::fill_plan(std::int64_t tick) {
  const ReferenceProfile& p = exec_.active_profile();
  const int n = std::min(p.n_points, static_cast<int>(plan_t::MAX_POINTS));
  plan_.utime = cmd_.utime;
  plan_.tick = tick;
  plan_.seq = p.seq;
  plan_.n_points = static_cast<std::int16_t>(n);
  for (int i = 0; i < plan_t::MAX_POINTS; ++i) {
    const bool in = i < n;
    plan_.e_norm[i] = in ? p.e_norm[i] : 0.0;
    plan_.drag_mps2[i] = in ? p.drag_mps2[i] : 0.0;
    plan_.radius_m[i] = in ? p.radius_m[i] : 0.0;
    plan_.gamma_rad[i] = in ? p.gamma_rad[i] : 0.0;
    plan_.sigma_rad[i] = in ? p.sigma_rad[i] : 0.0;
    plan_.alpha_rad[i] = in ? p.alpha_rad[i] : 0.0;
  }
  const double e0 = p.entry_energy_Jpkg != 0.0 ? p.entry_energy_Jpkg : 1.0;
  plan_.reversal_e_norm = p.reversal_energy_Jpkg / e0;
  plan_.dc_mps2 = p.dc_mps2;
  plan_.e1_norm = p.e1_Jpkg / e0;
  plan_.e2_norm = p.e2_Jpkg / e0;
  plan_.trajectory_length_m = p.trajectory_length_m;
  plan_.crossrange_err_m = p.crossrange_err_m;
  plan_.downrange_err_m = p.downrange_err_m;
  plan_.iterations = p.iterations;
  plan_.status = static_cast<std::int8_t>(p.status);
  plan_.converged = p.converged;
  plan_.compute_ms = exec_.counters().planner_ms_last;
}

void GuidanceNode::publish_cycle(lcm::LCM& lcm, bool plan_adopted) {
  int n = encode_into(cmd_, tx_, static_cast<int>(sizeof tx_));
  if (n > 0) lcm.publish("GUIDANCE_CMD", tx_, static_cast<unsigned>(n));
  n = encode_into(status_, tx_, static_cast<int>(sizeof tx_));
  if (n > 0) lcm.publish("GUIDANCE_STATUS", tx_, static_cast<unsigned>(n));
  if (plan_adopted) {
    fill_plan(cmd_.tick);
    n = encode_into(plan_, tx_, static_cast<int>(sizeof tx_));
    if (n > 0) lcm.publish("PLAN", tx_, static_cast<unsigned>(n));
  }
}

void GuidanceNode::publish_safe_status(lcm::LCM& lcm) {
  status_.phase = static_cast<std::int8_t>(Phase::kSafe);
  status_.health_flags |= exec::kHealthLinkLoss;
  status_.bad_messages = bad_messages_;
  const int n = encode_into(status_, tx_, static_cast<int>(sizeof tx_));
  if (n > 0) lcm.publish("GUIDANCE_STATUS", tx_, static_cast<unsigned>(n));
}

int GuidanceNode::run_live(lcm::LCM& lcm, RunMode mode, double lockstep_link_timeout_s,
                           double startup_timeout_s) {
  mode_ = mode;
  lcm.subscribeFunction("NAV_STATE", &GuidanceNode::on_nav, this);
  lcm.subscribeFunction("RUN_CONTROL", &GuidanceNode::on_run_control, this);
  bool started = false;
  std::int64_t last_nav_ns = mono_ns();
  const std::int64_t period_ns = static_cast<std::int64_t>(std::llround(dt_s_ * 1e9));
  const std::int64_t start_ns = mono_ns();
  std::int64_t last_tick = -1;
  bool adopted = false;

  if (mode == RunMode::kLockstep) {
    for (;;) {
      lcm.handleTimeout(50);
      if (nav_pending_) {
        nav_pending_ = false;
        started = true;
        last_nav_ns = mono_ns();
        if (cycle(nav_newest_, cmd_, status_, adopted)) {
          publish_cycle(lcm, adopted);
        } else if (nav_newest_.tick == cmd_.tick) {
          // The simulator repeats a nav message while it waits: answer again (same command).
          const int n = encode_into(cmd_, tx_, static_cast<int>(sizeof tx_));
          if (n > 0) lcm.publish("GUIDANCE_CMD", tx_, static_cast<unsigned>(n));
        }
      }
      if (end_of_run_) return kExitOk;
      const double silent_s = static_cast<double>(mono_ns() - last_nav_ns) * 1e-9;
      if (silent_s > (started ? lockstep_link_timeout_s : startup_timeout_s)) {
        publish_safe_status(lcm);
        std::fprintf(stderr, "reentry_fsw: link loss (no nav for %.2f s)\n", silent_s);
        return kExitLinkLoss;
      }
    }
  }
  // Realtime: absolute deadlines start + i*period, newest nav consumed each cycle.
  for (std::int64_t i = 1;; ++i) {
    const std::int64_t deadline = start_ns + i * period_ns;
    sleep_until_ns(deadline);
    const std::int64_t woke = mono_ns();
    jitter_us_last_ = static_cast<double>(woke - deadline) * 1e-3;
    jitter_us_max_ = std::max(jitter_us_max_, jitter_us_last_);
    while (lcm.handleTimeout(0) > 0) {
    }
    if (end_of_run_) return kExitOk;
    if (nav_pending_ && nav_newest_.tick != last_tick) {
      nav_pending_ = false;
      started = true;
      last_nav_ns = woke;
      last_tick = nav_newest_.tick;
      if (cycle(nav_newest_, cmd_, status_, adopted)) publish_cycle(lcm, adopted);
    }
    if (mono_ns() > deadline + period_ns) ++cycle_overruns_;
    const std::int64_t silent_ns = woke - last_nav_ns;
    if ((started && silent_ns > 3 * period_ns) ||
        (!started && static_cast<double>(silent_ns) * 1e-9 > startup_timeout_s)) {
      publish_safe_status(lcm);
      std::fprintf(stderr, "reentry_fsw: link loss (no nav for %.3f s)\n", static_cast<double>(silent_ns) * 1e-9);
      return kExitLinkLoss;
    }
  }
}

int GuidanceNode::run_replay(const std::string& log_path, bool compare) {
  mode_ = RunMode::kReplay;
  lcm::LogFile log(log_path, "r");
  if (!log.good()) {
    std::fprintf(stderr, "reentry_fsw: cannot read log %s\n", log_path.c_str());
    return kExitUsage;
  }
  // Ground-side replay: containers are fine here (not the flight loop).
  std::map<std::int64_t, nav_state_t> navs;
  std::map<std::int64_t, guidance_cmd_t> logged;
  nav_state_t nav{};
  guidance_cmd_t cmd{};
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev != nullptr; ev = log.readNextEvent()) {
    if (ev->channel == "NAV_STATE") {
      if (decode_into(nav, ev->data, ev->datalen, bad_messages_)) navs.emplace(nav.tick, nav);
    } else if (ev->channel == "GUIDANCE_CMD") {
      if (decode_into(cmd, ev->data, ev->datalen, bad_messages_)) logged.emplace(cmd.tick, cmd);
    }
  }
  if (navs.empty()) {
    std::fprintf(stderr, "reentry_fsw: no NAV_STATE messages in %s\n", log_path.c_str());
    return kExitUsage;
  }
  // Lockstep replay needs every tick: a log with holes (lcm-logger starved of CPU drops
  // datagrams) cannot reproduce the run, so say so instead of reporting a false difference.
  const std::int64_t first = navs.begin()->first, last = navs.rbegin()->first;
  const std::int64_t missing = (last - first + 1) - static_cast<std::int64_t>(navs.size());
  if (missing > 0) {
    std::int64_t gap = first;
    while (navs.count(gap) != 0) ++gap;
    std::printf("incomplete log: %lld of %lld NAV_STATE ticks missing (first at tick %lld); "
                "replay needs every tick\n",
                static_cast<long long>(missing), static_cast<long long>(last - first + 1), static_cast<long long>(gap));
    return kExitLogIncomplete;
  }
  std::int64_t compared = 0;
  bool adopted = false;
  for (const auto& [tick, n] : navs) {
    if (!cycle(n, cmd_, status_, adopted)) continue;
    if (!compare) continue;
    const auto it = logged.find(tick);
    if (it == logged.end()) continue;
    const guidance_cmd_t& r = it->second;
    const char* field = nullptr;
    if (!same_bits(cmd_.alpha_rad, r.alpha_rad)) field = "alpha_rad";
    else if (!same_bits(cmd_.sigma_rad, r.sigma_rad)) field = "sigma_rad";
    else if (!same_bits(cmd_.beta_rad, r.beta_rad)) field = "beta_rad";
    else if (cmd_.mode != r.mode) field = "mode";
    else if (cmd_.plan_seq != r.plan_seq) field = "plan_seq";
    if (field != nullptr) {
      std::printf("differs at tick %lld field %s (replayed %.17g, logged %.17g)\n", static_cast<long long>(tick),
                  field, std::strcmp(field, "alpha_rad") == 0 ? cmd_.alpha_rad : cmd_.sigma_rad,
                  std::strcmp(field, "alpha_rad") == 0 ? r.alpha_rad : r.sigma_rad);
      return kExitReplayDiffers;
    }
    ++compared;
  }
  if (compare) {
    if (compared == 0) {
      std::printf("no logged GUIDANCE_CMD to compare\n");
      return kExitReplayDiffers;
    }
    std::printf("identical (%lld commands)\n", static_cast<long long>(compared));
  }
  return kExitOk;
}

void GuidanceNode::write_status_json(const std::string& path) const {
  if (path.empty()) return;
  const exec::ExecCounters& c = exec_.counters();
  std::ofstream f(path);
  f << "{\n"
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
    << "  \"invalid_nav\": " << c.invalid_nav << ",\n"
    << "  \"duplicate_ticks\": " << c.duplicate_ticks << ",\n"
    << "  \"skipped_ticks\": " << c.skipped_ticks << ",\n"
    << "  \"bad_messages\": " << bad_messages_ << "\n"
    << "}\n";
}

}  // namespace reentry::fsw::app
