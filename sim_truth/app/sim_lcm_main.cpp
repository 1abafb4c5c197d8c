// reentry_sim_lcm: the truth simulator as an LCM process (sim_truth/app).
//   publishes NAV_STATE (tick 0 at the entry interface) and TRUTH every GNC tick,
//   lockstep: waits for the GUIDANCE_CMD of tick k before advancing to tick k+1,
//   realtime: paces itself with absolute deadlines and applies the newest command (its own
//   missed deadlines are counted), applies commands after --transport-delay-ticks ticks, ends
//   at an event with a RUN_CONTROL END_OF_RUN summary and (optionally) a JSON summary file.
// Commands are accepted only when they decode, are finite and inside plausibility windows,
// and answer a tick the simulator has published (never one from the future); the last
// accepted command is held otherwise. A guidance process silent for --link-timeout-ticks GNC
// periods ends the run (event link_loss, exit 3). SIGINT, SIGTERM or SIGHUP end the run at the
// next tick (END_OF_RUN, log sealed, summary event "interrupted", exit 128 + signal). A log or
// summary that cannot be written whole is named, exit 8. Network: our validated
// UDP-multicast transport on $LCM_DEFAULT_URL; --log records every message sent and received.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/run_control_t.hpp>
#include <reentry/truth_telemetry_t.hpp>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "evaluation/mission_verdict.hpp"
#include "reentry/config/mission.hpp"
#include "sim_messages.hpp"
#include "transport/command_line.hpp"
#include "transport/event_log.hpp"
#include "transport/exit_status.hpp"
#include "transport/lcm_codec.hpp"
#include "transport/monotonic_clock.hpp"
#include "transport/udpm.hpp"

namespace {

namespace tx = reentry::transport;
using tx::decode_into;
using tx::encode_into;
using tx::mono_ns;
using tx::sleep_until_ns;
constexpr const char* kTool = "reentry_sim_lcm";

// Plausibility windows of a command: finite, attitude angles physically meaningful. (Guidance
// limits are judged by the verdict, not enforced here: the referee must see what was flown.)
constexpr double kAlphaLimit_rad = M_PI / 2.0;
constexpr double kBetaLimit_rad = M_PI / 2.0;
constexpr double kSigmaLimit_rad = 2.0 * M_PI;

struct Options {
  std::string mission_arg, mode = "lockstep", summary_path, log_path;
  int truth_every = 10;  // truth telemetry every N ticks (1 Hz at 10 Hz GNC): enough for the plots
  int link_timeout_ticks = 3;
  bool dispersed = false;  // --seed given: the dispersion draw of that seed (0 included)
  std::int64_t seed = 0;
  int transport_delay = -1;
  double cmd_timeout_s = 10.0;
  double progress_period_s = 10.0;
  double stop_after_s = -1.0;
};

int parse_options(int argc, char** argv, Options& o) {
  CLI::App cli{"Truth simulator LCM process (SIL)", kTool};
  cli.add_option("--mission", o.mission_arg, "mission name or TOML file")->required();
  auto* seed = cli.add_option("--seed", o.seed, "dispersion seed (absent: the nominal run)")->check(tx::non_negative_integer());
  cli.add_option("--mode", o.mode, "lockstep or realtime")->check(CLI::IsMember({"lockstep", "realtime"}));
  cli.add_option("--transport-delay-ticks", o.transport_delay, "command transport delay (default: mission)")
      ->check(CLI::Range(0, 1000));
  cli.add_option("--cmd-timeout", o.cmd_timeout_s, "seconds to wait for the first message of the guidance process")
      ->check(CLI::PositiveNumber);
  cli.add_option("--link-timeout-ticks", o.link_timeout_ticks,
                 "GNC periods without a message from the guidance process that are a link loss")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--log", o.log_path, "record every message sent and received in this LCM log");
  cli.add_option("--truth-every", o.truth_every, "publish TRUTH every N ticks (and at the end)")->check(CLI::PositiveNumber);
  cli.add_option("--summary-json", o.summary_path, "write the end-of-run summary here");
  cli.add_option("--progress-period", o.progress_period_s, "simulated seconds between progress lines")
      ->check(CLI::PositiveNumber);
  cli.add_option("--stop-after", o.stop_after_s, "end the run (time-out event) after this simulated time");
  const int rc = tx::parse_command_line(cli, argc, argv, kTool);
  o.dispersed = seed->count() > 0;
  return rc;
}

struct CmdState {
  reentry::guidance_cmd_t msg{};
  reentry::guidance_cmd_t latest{};
  bool have_latest = false;
  std::int64_t sim_tick = 0;        // the tick the simulator has published last
  std::int32_t bad = 0;             // undecodable messages on the guidance channels
  std::int32_t bad_commands = 0;    // decodable commands outside the windows (NaN/inf, tick, range)
  std::int64_t last_heard_ns = -1;  // last usable message from the guidance process
  reentry::guidance_status_t status{};
  reentry::plan_t plan{};
};

bool command_plausible(const reentry::guidance_cmd_t& c, const CmdState& st) {
  if (!std::isfinite(c.alpha_rad) || !std::isfinite(c.beta_rad) || !std::isfinite(c.sigma_rad)) return false;
  if (std::fabs(c.alpha_rad) > kAlphaLimit_rad || std::fabs(c.beta_rad) > kBetaLimit_rad ||
      std::fabs(c.sigma_rad) > kSigmaLimit_rad) {
    return false;
  }
  // It must answer a published tick (not the future) and not go back behind the latest one.
  if (c.tick < 0 || c.tick > st.sim_tick) return false;
  return !st.have_latest || c.tick >= st.latest.tick;
}

void on_datagram(const tx::Datagram& d, CmdState& st, tx::EventLogWriter& log) {
  const bool cmd = std::strcmp(d.channel, "GUIDANCE_CMD") == 0;
  const bool status = std::strcmp(d.channel, "GUIDANCE_STATUS") == 0;
  const bool plan = std::strcmp(d.channel, "PLAN") == 0;
  if (!cmd && !status && !plan) return;  // our own output looped back, or not ours
  log.record(d.channel, d.payload, d.payload_len);
  if (status) {
    if (decode_into(st.status, d.payload, d.payload_len, st.bad)) st.last_heard_ns = mono_ns();
    return;
  }
  if (plan) {
    if (decode_into(st.plan, d.payload, d.payload_len, st.bad)) st.last_heard_ns = mono_ns();
    return;
  }
  if (!decode_into(st.msg, d.payload, d.payload_len, st.bad)) return;
  if (!command_plausible(st.msg, st)) {
    ++st.bad_commands;
    return;
  }
  st.last_heard_ns = mono_ns();
  st.latest = st.msg;
  st.have_latest = true;
}

/// One simulator run: set-up, the ticks, the end of the run.
class SimProcess {
 public:
  /// Loads the mission, creates the simulator, opens the network and the log (kExitOk or the
  /// exit status, its reason printed).
  int setup(const Options& o);
  /// Flies tick by tick until an event, a link loss or a stop signal.
  void fly();
  /// END_OF_RUN, the log sealed, the summary written; returns the exit status.
  int finish();

 private:
  void publish(const char* channel, const std::uint8_t* data, int len) {
    net_->publish(channel, data, len);
    log_.record(channel, data, len);
  }
  int drain(std::int64_t timeout_ns);
  bool publish_tick();
  bool await_lockstep(std::int64_t nav_sent_ns, int nav_bytes);
  bool await_realtime();
  bool link_lost(std::int64_t now, std::int64_t since, bool heard);
  void apply_command();
  void progress_line(const reentry::truth::TruthSample& ts);
  bool write_summary(const reentry::truth::RunSummary& summary, const char* event_name) const;
  const char* event_name(const reentry::truth::RunSummary& summary) const;

  Options o_;
  reentry::config::Mission mission_;
  std::unique_ptr<reentry::truth::Simulator> sim_;
  std::unique_ptr<tx::UdpmSocket> net_;
  tx::EventLogWriter log_;
  CmdState cmds_;
  tx::Datagram dgram_;
  std::vector<std::uint8_t> buf_ = std::vector<std::uint8_t>(65000);
  reentry::nav_state_t nav_{};
  reentry::truth_telemetry_t tel_{};
  // Commands waiting for the transport delay: cmd_fifo[k % n] is applied at tick k + delay.
  std::vector<reentry::guidance_cmd_t> cmd_fifo_;
  std::vector<bool> cmd_valid_;
  reentry::truth::CommandRateMaxima rates_;
  double applied_alpha_ = 0.0, applied_sigma_ = 0.0;
  bool have_applied_ = false;
  int delay_ = 0;
  double dt_ = 0.1;
  bool lockstep_ = true;
  std::int64_t link_ns_ = 0, startup_ns_ = 0, start_ns_ = 0, period_ns_ = 0;
  double link_silent_s_ = 0.0;
  std::int64_t link_lost_tick_ = -1;
  std::int64_t deadline_misses_ = 0;  // realtime: ticks whose work ended after their deadline
  double deadline_late_ms_max_ = 0.0;
  int exit_code_ = tx::kExitOk;
  int stop_signal_ = 0;
  reentry::truth::SimEvent event_ = reentry::truth::SimEvent::kNone;
  double next_progress_s_ = 0.0;
  std::int64_t k_ = 0;
};

int SimProcess::setup(const Options& o) {
  o_ = o;
  const auto loaded = reentry::config::load_mission(o.mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "%s: mission refused: %s\n", kTool, loaded.error.c_str());
    return tx::kExitUsage;
  }
  mission_ = loaded.mission;
  reentry::truth::SimOverrides ov;
  if (o.stop_after_s > 0.0) ov.time_limit_s = o.stop_after_s;
  if (o.dispersed) ov.dispersion = reentry::truth::draw_dispersions(mission_.dispersions, static_cast<std::uint64_t>(o.seed));
  std::string error;
  sim_ = reentry::truth::Simulator::create(mission_, ov, &error);
  if (!sim_) {
    std::fprintf(stderr, "%s: mission refused by the simulator: %s\n", kTool, error.c_str());
    return tx::kExitUsage;
  }
  delay_ = o.transport_delay >= 0 ? o.transport_delay : mission_.sim.transport_delay_ticks;
  dt_ = 1.0 / mission_.guidance.gnc_rate_hz;
  lockstep_ = o.mode == "lockstep";
  tx::UdpmUrl url;
  std::string net_err;
  net_ = std::make_unique<tx::UdpmSocket>();
  if (!tx::parse_udpm_url(tx::default_udpm_url(), url, net_err) || !net_->open(url, net_err)) {
    std::fprintf(stderr, "%s: network: %s\n", kTool, net_err.c_str());
    return tx::kExitTransport;
  }
  const auto policy = lockstep_ ? tx::EventLogWriter::WhenFull::kWait : tx::EventLogWriter::WhenFull::kDrop;
  if (!o.log_path.empty() && !log_.open(o.log_path, 16u << 20, policy, net_err)) {
    std::fprintf(stderr, "%s: write failed: %s\n", kTool, net_err.c_str());
    return tx::kExitWriteFailed;
  }
  cmd_fifo_.assign(static_cast<std::size_t>(delay_) + 1, reentry::guidance_cmd_t{});
  cmd_valid_.assign(static_cast<std::size_t>(delay_) + 1, false);
  period_ns_ = static_cast<std::int64_t>(std::llround(dt_ * 1e9));
  link_ns_ = static_cast<std::int64_t>(o.link_timeout_ticks) * period_ns_;
  startup_ns_ = static_cast<std::int64_t>(o.cmd_timeout_s * 1e9);
  start_ns_ = mono_ns();
  return tx::kExitOk;
}

int SimProcess::drain(std::int64_t timeout_ns) {  // handles at most one datagram after waiting
  const int r = net_->receive(dgram_, timeout_ns);
  if (r == 1) on_datagram(dgram_, cmds_, log_);
  return r;
}

void SimProcess::progress_line(const reentry::truth::TruthSample& ts) {
  // Progress in energy from the entry interface to TAEM (the run's natural clock).
  const double e0 = sim_->entry_energy_Jpkg(), e1 = sim_->taem_energy_Jpkg();
  const double pct = e0 > e1 ? std::clamp(100.0 * (e0 - ts.E_Jpkg) / (e0 - e1), 0.0, 100.0) : 0.0;
  std::printf("progress pct=%.0f t_s=%.1f alt_km=%.2f mach=%.2f dtg_km=%.1f\n", pct, ts.t_s, ts.h_m * 1e-3, ts.mach,
              ts.range_to_taem_m * 1e-3);
  std::fflush(stdout);
}

// TRUTH (every truth_every ticks and at the end) and the progress line; false once the run has
// ended (the event's state was published), else NAV_STATE of tick k follows.
bool SimProcess::publish_tick() {
  const auto ts = sim_->sample();
  reentry::truth::fill_nav(sim_->nav_sample(), k_, nav_);
  reentry::truth::fill_truth(ts, nav_.utime, k_, tel_);
  const int n = encode_into(tel_, buf_.data(), static_cast<int>(buf_.size()));
  if (n > 0 && (k_ % o_.truth_every == 0 || sim_->finished())) publish("TRUTH", buf_.data(), n);
  if (ts.t_s >= next_progress_s_) {
    progress_line(ts);
    next_progress_s_ += o_.progress_period_s;
  }
  return event_ == reentry::truth::SimEvent::kNone;
}

bool SimProcess::link_lost(std::int64_t now, std::int64_t since, bool heard) {
  if (now - since <= (heard ? link_ns_ : startup_ns_)) return false;
  link_silent_s_ = static_cast<double>(now - since) * 1e-9;
  return true;
}

// Lockstep: the command answering tick k (republishing the sample every period); false on a
// link loss, a receive failure or a stop signal.
bool SimProcess::await_lockstep(std::int64_t nav_sent_ns, int nav_bytes) {
  std::int64_t republish_ns = nav_sent_ns + period_ns_;
  while (!(cmds_.have_latest && cmds_.latest.tick >= k_)) {
    if (tx::g_stop_signal != 0) return false;
    const std::int64_t now = mono_ns();
    // Silence is counted from our sample or the guidance's last word (its status heartbeats
    // while a plan is late), whichever is later; before its first word, the start-up time.
    const bool heard = cmds_.last_heard_ns >= 0;
    if (link_lost(now, heard ? std::max(cmds_.last_heard_ns, nav_sent_ns) : start_ns_, heard)) return false;
    if (drain(std::min<std::int64_t>(republish_ns - now, 20000000)) < 0) {
      std::fprintf(stderr, "%s: receive failed\n", kTool);
      return false;
    }
    if (mono_ns() >= republish_ns) {  // a late subscriber or a lost datagram: repeat
      if (nav_bytes > 0) publish("NAV_STATE", buf_.data(), nav_bytes);
      republish_ns += period_ns_;
    }
  }
  return true;
}

// Realtime: the tick's deadline (a miss when its work already ran past it), then every
// command that arrived; false on a link loss.
bool SimProcess::await_realtime() {
  const std::int64_t deadline = start_ns_ + (k_ + 1) * period_ns_;
  const std::int64_t late = mono_ns() - deadline;
  if (late > 0) {
    ++deadline_misses_;
    deadline_late_ms_max_ = std::max(deadline_late_ms_max_, static_cast<double>(late) * 1e-6);
  }
  sleep_until_ns(deadline);
  while (drain(0) == 1) {
  }
  const bool heard = cmds_.last_heard_ns >= 0;
  return !link_lost(mono_ns(), heard ? cmds_.last_heard_ns : start_ns_, heard);
}

void SimProcess::apply_command() {
  const std::size_t slot = static_cast<std::size_t>(k_ % (delay_ + 1));
  cmd_fifo_[slot] = cmds_.latest;
  cmd_valid_[slot] = cmds_.have_latest;
  const std::size_t apply = static_cast<std::size_t>((k_ + 1) % (delay_ + 1));  // = tick k - delay
  const std::size_t use = delay_ == 0 ? slot : apply;
  if (!cmd_valid_[use]) return;
  const auto& c = cmd_fifo_[use];
  if (have_applied_) {  // control-constraint check on the applied command rates
    rates_.alpha_rate_radps = std::max(rates_.alpha_rate_radps, std::fabs(c.alpha_rad - applied_alpha_) / dt_);
    rates_.sigma_rate_radps = std::max(rates_.sigma_rate_radps, std::fabs(reentry::physics::wrap_pi(c.sigma_rad - applied_sigma_)) / dt_);
  }
  applied_alpha_ = c.alpha_rad;
  applied_sigma_ = c.sigma_rad;
  have_applied_ = true;
  sim_->set_command(c.alpha_rad, c.sigma_rad);
}

void SimProcess::fly() {
  for (;; ++k_) {
    if (tx::g_stop_signal != 0) break;
    if (!publish_tick()) break;
    const int n = encode_into(nav_, buf_.data(), static_cast<int>(buf_.size()));
    cmds_.sim_tick = k_;
    if (n > 0) publish("NAV_STATE", buf_.data(), n);
    const bool answered = lockstep_ ? await_lockstep(mono_ns(), n) : await_realtime();
    if (tx::g_stop_signal != 0) break;
    if (!answered) {
      link_lost_tick_ = k_;
      std::fprintf(stderr,
                   "%s: link loss: no message from the guidance process for %.3f s (%d ticks of %.3f s) at tick %lld; "
                   "last command held, run ended; exit %d (link_loss)\n",
                   kTool, link_silent_s_, cmds_.last_heard_ns >= 0 ? o_.link_timeout_ticks : 0, dt_,
                   static_cast<long long>(k_), tx::kExitLinkLoss);
      exit_code_ = tx::kExitLinkLoss;
      event_ = reentry::truth::SimEvent::kFailure;
      break;
    }
    apply_command();
    event_ = sim_->advance_to(static_cast<double>(k_ + 1) * dt_);
  }
  if (tx::g_stop_signal != 0) {
    stop_signal_ = tx::g_stop_signal;
    exit_code_ = tx::kExitSignalBase + stop_signal_;
    std::fprintf(stderr, "%s: interrupted by signal %d at tick %lld: run ended, log sealed; exit %d\n", kTool,
                 stop_signal_, static_cast<long long>(k_), exit_code_);
  }
}

const char* SimProcess::event_name(const reentry::truth::RunSummary& summary) const {
  if (stop_signal_ != 0) return "interrupted";
  return exit_code_ == tx::kExitOk ? reentry::truth::to_string(summary.event) : "link_loss";
}

int SimProcess::finish() {
  const auto summary = sim_->summary();
  const auto& f = summary.final_state;
  reentry::run_control_t rc{};
  const std::int8_t event = exit_code_ == tx::kExitOk ? reentry::truth::end_event_code(summary.event)
                            : stop_signal_ != 0      ? reentry::run_control_t::EVENT_ABORT
                                                     : reentry::run_control_t::EVENT_LINK_LOSS;
  reentry::truth::fill_end_of_run(summary, k_, event, mission_.taem.heading_rad, rc);
  const int n = encode_into(rc, buf_.data(), static_cast<int>(buf_.size()));
  for (int i = 0; i < 3 && n > 0; ++i) publish("RUN_CONTROL", buf_.data(), n);
  bool written = log_.close();
  if (!written) std::fprintf(stderr, "%s: write failed: %s\n", kTool, log_.error().c_str());
  written = write_summary(summary, event_name(summary)) && written;
  std::printf("end event=%s t_s=%.1f alt_km=%.2f mach=%.2f dtg_km=%.1f\n", event_name(summary), f.t_s, f.h_m * 1e-3,
              f.mach, f.range_to_taem_m * 1e-3);
  std::fflush(stdout);
  if (!written) {
    std::fprintf(stderr, "%s: the run's outputs are not whole (run status %d, %s); exit %d (%s)\n", kTool, exit_code_,
                 tx::exit_name(exit_code_), tx::kExitWriteFailed, tx::exit_name(tx::kExitWriteFailed));
    return tx::kExitWriteFailed;
  }
  return exit_code_;
}

bool SimProcess::write_summary(const reentry::truth::RunSummary& summary, const char* event_name) const {
  if (o_.summary_path.empty()) return true;
  const auto& f = summary.final_state;
  nlohmann::json j;
  const reentry::truth::MissionVerdict verdict = reentry::truth::judge_mission(mission_, summary, rates_);
  j["mission"] = mission_.name;
  j["mission_file"] = mission_.source_file;
  j["mission_digest"] = mission_.digest;
  j["mode"] = o_.mode;
  j["seed"] = o_.dispersed ? nlohmann::json(o_.seed) : nlohmann::json(nullptr);  // null: the nominal run
  j["event"] = event_name;
  j["success"] = exit_code_ == tx::kExitOk && verdict.success;
  j["taem_miss_km"] = f.range_to_taem_m * 1e-3;
  j["miss_along_km"] = verdict.miss_along_m * 1e-3;  // > 0: past the aim point
  j["miss_cross_km"] = verdict.miss_cross_m * 1e-3;  // > 0: right of the arrival line
  j["final_alt_km"] = f.h_m * 1e-3;
  j["final_mach"] = f.mach;
  j["final_gamma_deg"] = f.gamma_rad * 180.0 / M_PI;
  j["heading_err_deg"] = verdict.heading_err_rad * 180.0 / M_PI;
  j["max_alpha_rate_deg_s"] = rates_.alpha_rate_radps * 180.0 / M_PI;
  j["max_sigma_rate_deg_s"] = rates_.sigma_rate_radps * 180.0 / M_PI;
  j["max_heat_flux_kW_m2"] = summary.maxima.qdot_Wpm2 * 1e-3;
  j["heat_load_MJ_m2"] = f.Q_Jpm2 * 1e-6;
  j["max_g"] = summary.maxima.n_g;
  j["max_q_kPa"] = summary.maxima.q_Pa * 1e-3;
  j["max_q_alpha_kPa_deg"] = summary.maxima.q_alpha_Pa_rad * 1e-3 * 180.0 / M_PI;
  j["violations"] = verdict.violations;
  j["flight_time_s"] = f.t_s;
  j["ticks"] = k_;
  j["bad_messages"] = cmds_.bad;
  j["bad_commands"] = cmds_.bad_commands;
  j["bad_datagrams"] = net_->counters().bad_datagrams;
  j["rx_kernel_drops"] = net_->counters().kernel_drops;
  j["log_recorded"] = log_.recorded();
  j["log_dropped"] = log_.dropped();
  j["log_error"] = log_.error();
  j["link_timeout_ticks"] = o_.link_timeout_ticks;
  j["deadline_misses"] = deadline_misses_;  // realtime only: ticks whose work ran past their deadline
  j["deadline_late_ms_max"] = deadline_late_ms_max_;
  j["exit_code"] = exit_code_;
  j["exit"] = tx::exit_name(exit_code_);
  if (exit_code_ == tx::kExitLinkLoss) {
    j["link_loss"] = {{"tick", link_lost_tick_}, {"silent_ms", link_silent_s_ * 1e3},
                      {"guidance_ever_heard", cmds_.last_heard_ns >= 0}};
  }
  // Context for the plots (tools/plot): aim point, heading-alignment circle, limits.
  j["taem_lat_deg"] = mission_.taem.latitude_rad * 180.0 / M_PI;
  j["taem_lon_deg"] = mission_.taem.longitude_rad * 180.0 / M_PI;
  j["taem_heading_deg"] = mission_.taem.heading_rad * 180.0 / M_PI;
  j["hac_radius_km"] = mission_.taem.hac_radius_m * 1e-3;
  j["entry_energy_Jpkg"] = sim_->entry_energy_Jpkg();
  j["taem_energy_Jpkg"] = sim_->taem_energy_Jpkg();
  const auto& lim = mission_.constraints;
  if (std::isfinite(lim.heat_flux_max_Wpm2)) j["limit_heat_flux_kW_m2"] = lim.heat_flux_max_Wpm2 * 1e-3;
  if (std::isfinite(lim.load_factor_max_g)) j["limit_g"] = lim.load_factor_max_g;
  if (std::isfinite(lim.dynamic_pressure_max_Pa)) j["limit_q_kPa"] = lim.dynamic_pressure_max_Pa * 1e-3;
  std::ofstream out(o_.summary_path);
  out << j.dump(2) << "\n";
  out.close();
  if (!out) {
    std::fprintf(stderr, "%s: write failed: %s: %s\n", kTool, o_.summary_path.c_str(), std::strerror(errno));
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  const int parsed = parse_options(argc, argv, options);
  if (parsed >= 0) return parsed;
  tx::install_stop_handlers();
  auto process = std::make_unique<SimProcess>();
  const int rc = process->setup(options);
  if (rc != tx::kExitOk) return rc;
  process->fly();
  return process->finish();
}
