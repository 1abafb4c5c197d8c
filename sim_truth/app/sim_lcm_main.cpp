// reentry_sim_lcm: the truth simulator as an LCM process (sim_truth/app).
//   publishes NAV_STATE (tick 0 at the entry interface) and TRUTH every GNC tick,
//   lockstep: waits for the GUIDANCE_CMD of tick k before advancing to tick k+1,
//   realtime: paces itself with absolute deadlines and applies the newest command,
//   applies commands after --transport-delay-ticks ticks, ends at an event with a
//   RUN_CONTROL END_OF_RUN summary and (optionally) a JSON summary file.
// Commands are accepted only when they decode, are finite and inside plausibility windows,
// and answer a tick the simulator has published (never one from the future); the last
// accepted command is held otherwise. A guidance process silent for --link-timeout-ticks GNC
// periods ends the run (event link_loss, exit 3). Network: our validated UDP-multicast
// transport on $LCM_DEFAULT_URL; --log records every message sent and received.
#include <time.h>

#include <CLI/CLI.hpp>
#include <cstring>
#include <memory>
#include <algorithm>
#include <chrono>
#include <thread>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/run_control_t.hpp>
#include <reentry/truth_telemetry_t.hpp>
#include <string>
#include <vector>

#include "transport/event_log.hpp"
#include "transport/lcm_codec.hpp"
#include "transport/monotonic_clock.hpp"
#include "transport/udpm.hpp"
#include "dynamics/simulator.hpp"
#include "evaluation/mission_verdict.hpp"
#include "reentry/config/mission.hpp"
#include "sim_messages.hpp"

namespace {

using reentry::transport::decode_into;
using reentry::transport::encode_into;
using reentry::transport::mono_ns;
using reentry::transport::sleep_until_ns;

constexpr int kExitOk = 0;
constexpr int kExitUsage = 2;
constexpr int kExitLinkLoss = 3;
constexpr int kExitTransport = 7;

// Plausibility windows of a command: finite, attitude angles physically meaningful. (Guidance
// limits are judged by the verdict, not enforced here: the referee must see what was flown.)
constexpr double kAlphaLimit_rad = M_PI / 2.0;
constexpr double kBetaLimit_rad = M_PI / 2.0;
constexpr double kSigmaLimit_rad = 2.0 * M_PI;

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

void on_datagram(const reentry::transport::Datagram& d, CmdState& st, reentry::transport::EventLogWriter& log) {
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"Truth simulator LCM process (SIL)"};
  std::string mission_arg, mode = "lockstep", summary_path, log_path;
  // Truth telemetry every N ticks (default 1 Hz at 10 Hz GNC): enough for the plots.
  int truth_every = 10;
  int link_timeout_ticks = 3;
  std::uint64_t seed = 0;
  int transport_delay = -1;
  double cmd_timeout_s = 10.0;
  double progress_period_s = 10.0;
  double stop_after_s = -1.0;
  cli.add_option("--mission", mission_arg, "mission name or TOML file")->required();
  cli.add_option("--seed", seed, "dispersion seed (0: nominal)");
  cli.add_option("--mode", mode, "lockstep or realtime")->check(CLI::IsMember({"lockstep", "realtime"}));
  cli.add_option("--transport-delay-ticks", transport_delay, "command transport delay (default: mission)");
  cli.add_option("--cmd-timeout", cmd_timeout_s, "seconds to wait for the first message of the guidance process");
  cli.add_option("--link-timeout-ticks", link_timeout_ticks,
                 "GNC periods without a message from the guidance process that are a link loss")
      ->check(CLI::Range(1, 1000));
  cli.add_option("--log", log_path, "record every message sent and received in this LCM log");
  cli.add_option("--truth-every", truth_every, "publish TRUTH every N ticks (and at the end)")->check(CLI::PositiveNumber);
  cli.add_option("--summary-json", summary_path, "write the end-of-run summary here");
  cli.add_option("--progress-period", progress_period_s, "simulated seconds between progress lines");
  cli.add_option("--stop-after", stop_after_s, "end the run (time-out event) after this simulated time");
  CLI11_PARSE(cli, argc, argv);

  const auto loaded = reentry::config::load_mission(mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "reentry_sim_lcm: %s\n", loaded.error.c_str());
    return kExitUsage;
  }
  const auto& mission = loaded.mission;
  reentry::truth::SimOverrides ov;
  if (stop_after_s > 0.0) ov.time_limit_s = stop_after_s;
  if (seed != 0) ov.dispersion = reentry::truth::draw_dispersions(mission.dispersions, seed);
  std::string error;
  auto sim = reentry::truth::Simulator::create(mission, ov, &error);
  if (!sim) {
    std::fprintf(stderr, "reentry_sim_lcm: %s\n", error.c_str());
    return kExitUsage;
  }
  const int delay = transport_delay >= 0 ? transport_delay : mission.sim.transport_delay_ticks;
  const double dt = 1.0 / mission.guidance.gnc_rate_hz;
  const bool lockstep = mode == "lockstep";

  reentry::transport::UdpmUrl url;
  std::string net_err;
  auto net = std::make_unique<reentry::transport::UdpmSocket>();
  if (!reentry::transport::parse_udpm_url(reentry::transport::default_udpm_url(), url, net_err) ||
      !net->open(url, net_err)) {
    std::fprintf(stderr, "reentry_sim_lcm: network: %s\n", net_err.c_str());
    return kExitTransport;
  }
  reentry::transport::EventLogWriter log;
  if (!log_path.empty() &&
      !log.open(log_path, 16u << 20,
                lockstep ? reentry::transport::EventLogWriter::WhenFull::kWait
                         : reentry::transport::EventLogWriter::WhenFull::kDrop,
                net_err)) {
    std::fprintf(stderr, "reentry_sim_lcm: %s\n", net_err.c_str());
    return kExitTransport;
  }
  CmdState cmds;
  auto publish = [&](const char* channel, const std::uint8_t* data, int len) {
    net->publish(channel, data, len);
    log.record(channel, data, len);
  };
  reentry::transport::Datagram dgram;
  auto drain = [&](std::int64_t timeout_ns) {  // handles at most one datagram after waiting
    const int r = net->receive(dgram, timeout_ns);
    if (r == 1) on_datagram(dgram, cmds, log);
    return r;
  };
  const std::int64_t link_ns = static_cast<std::int64_t>(link_timeout_ticks) *
                               static_cast<std::int64_t>(std::llround(dt * 1e9));
  const std::int64_t startup_ns = static_cast<std::int64_t>(cmd_timeout_s * 1e9);
  double link_silent_s = 0.0;
  std::int64_t link_lost_tick = -1;

  std::vector<std::uint8_t> buf(65000);
  reentry::nav_state_t nav{};
  reentry::truth_telemetry_t tel{};
  // Commands waiting for the transport delay: cmd_fifo[k % n] is applied at tick k + delay.
  std::vector<reentry::guidance_cmd_t> cmd_fifo(static_cast<std::size_t>(delay) + 1);
  reentry::truth::CommandRateMaxima rates;
  double applied_alpha = 0.0, applied_sigma = 0.0;
  bool have_applied = false;
  std::vector<bool> cmd_valid(static_cast<std::size_t>(delay) + 1, false);

  const std::int64_t start_ns = mono_ns();
  const std::int64_t period_ns = static_cast<std::int64_t>(std::llround(dt * 1e9));
  int exit_code = kExitOk;
  reentry::truth::SimEvent event = reentry::truth::SimEvent::kNone;
  double next_progress_s = 0.0;
  std::int64_t k = 0;
  for (;; ++k) {
    const auto ns = sim->nav_sample();
    const auto ts = sim->sample();
    reentry::truth::fill_nav(ns, k, nav);
    reentry::truth::fill_truth(ts, nav.utime, k, tel);
    int n = encode_into(tel, buf.data(), static_cast<int>(buf.size()));
    const bool last_tick = sim->finished();
    if (n > 0 && (k % truth_every == 0 || last_tick)) publish("TRUTH", buf.data(), n);
    if (ts.t_s >= next_progress_s) {
      std::printf("progress t_s=%.1f alt_km=%.2f mach=%.2f dtg_km=%.1f\n", ts.t_s, ts.h_m * 1e-3, ts.mach,
                  ts.range_to_taem_m * 1e-3);
      std::fflush(stdout);
      next_progress_s += progress_period_s;
    }
    if (event != reentry::truth::SimEvent::kNone) break;
    n = encode_into(nav, buf.data(), static_cast<int>(buf.size()));
    cmds.sim_tick = k;
    if (n > 0) publish("NAV_STATE", buf.data(), n);
    const std::int64_t nav_sent_ns = mono_ns();

    // Collect the command answering tick k.
    bool lost = false;
    if (lockstep) {
      std::int64_t republish_ns = nav_sent_ns + period_ns;
      while (!(cmds.have_latest && cmds.latest.tick >= k)) {
        const std::int64_t now = mono_ns();
        // Silence is counted from our sample or the guidance's last word (its status heartbeats
        // while a plan is late), whichever is later; before its first word, the start-up time.
        const bool heard = cmds.last_heard_ns >= 0;
        const std::int64_t since = heard ? std::max(cmds.last_heard_ns, nav_sent_ns) : start_ns;
        if (now - since > (heard ? link_ns : startup_ns)) {
          lost = true;
          link_silent_s = static_cast<double>(now - since) * 1e-9;
          break;
        }
        if (drain(std::min<std::int64_t>(republish_ns - now, 20000000)) < 0) {
          std::fprintf(stderr, "reentry_sim_lcm: receive failed\n");
          lost = true;
          break;
        }
        if (mono_ns() >= republish_ns) {  // a late subscriber or a lost datagram: repeat
          if (n > 0) publish("NAV_STATE", buf.data(), n);
          republish_ns += period_ns;
        }
      }
    } else {
      sleep_until_ns(start_ns + (k + 1) * period_ns);
      while (drain(0) == 1) {
      }
      const std::int64_t now = mono_ns();
      const bool heard = cmds.last_heard_ns >= 0;
      const std::int64_t since = heard ? cmds.last_heard_ns : start_ns;
      if (now - since > (heard ? link_ns : startup_ns)) {
        lost = true;
        link_silent_s = static_cast<double>(now - since) * 1e-9;
      }
    }
    if (lost) {
      link_lost_tick = k;
      std::fprintf(stderr,
                   "reentry_sim_lcm: link loss: no message from the guidance process for %.3f s (%d ticks of "
                   "%.3f s) at tick %lld; last command held, run ended; exit %d (link_loss)\n",
                   link_silent_s, cmds.last_heard_ns >= 0 ? link_timeout_ticks : 0, dt, static_cast<long long>(k),
                   kExitLinkLoss);
      exit_code = kExitLinkLoss;
      event = reentry::truth::SimEvent::kFailure;
      break;
    }
    const std::size_t slot = static_cast<std::size_t>(k % (delay + 1));
    cmd_fifo[slot] = cmds.latest;
    cmd_valid[slot] = cmds.have_latest;
    const std::size_t apply = static_cast<std::size_t>((k + 1) % (delay + 1));  // = tick k - delay
    const std::size_t use = delay == 0 ? slot : apply;
    if (cmd_valid[use]) {
      const auto& c = cmd_fifo[use];
      if (have_applied) {  // control-constraint check on the applied command rates
        rates.alpha_rate_radps = std::max(rates.alpha_rate_radps, std::fabs(c.alpha_rad - applied_alpha) / dt);
        rates.sigma_rate_radps = std::max(rates.sigma_rate_radps, std::fabs(c.sigma_rad - applied_sigma) / dt);
      }
      applied_alpha = c.alpha_rad;
      applied_sigma = c.sigma_rad;
      have_applied = true;
      sim->set_command(c.alpha_rad, c.sigma_rad);
    }
    event = sim->advance_to(static_cast<double>(k + 1) * dt);
  }

  const auto summary = sim->summary();
  const auto& f = summary.final_state;
  reentry::run_control_t rc{};
  reentry::truth::fill_end_of_run(
      summary, k, exit_code == kExitOk ? reentry::truth::end_event_code(summary.event) : reentry::run_control_t::EVENT_LINK_LOSS,
      mission.taem.heading_rad, rc);
  const int n = encode_into(rc, buf.data(), static_cast<int>(buf.size()));
  for (int i = 0; i < 3 && n > 0; ++i) publish("RUN_CONTROL", buf.data(), n);
  log.close();

  if (!summary_path.empty()) {
    nlohmann::json j;
    const reentry::truth::MissionVerdict verdict = reentry::truth::judge_mission(mission, summary, rates);
    nlohmann::json violations = verdict.violations;
    j["mission"] = mission.name;
    j["event"] = exit_code == kExitOk ? reentry::truth::to_string(summary.event) : "link_loss";
    j["success"] = exit_code == kExitOk && verdict.success;
    j["taem_miss_km"] = f.range_to_taem_m * 1e-3;
    j["miss_along_km"] = verdict.miss_along_m * 1e-3;  // > 0: past the aim point
    j["miss_cross_km"] = verdict.miss_cross_m * 1e-3;  // > 0: right of the arrival line
    j["final_alt_km"] = f.h_m * 1e-3;
    j["final_mach"] = f.mach;
    j["final_gamma_deg"] = f.gamma_rad * 180.0 / M_PI;
    j["heading_err_deg"] = verdict.heading_err_rad * 180.0 / M_PI;
    j["max_alpha_rate_deg_s"] = rates.alpha_rate_radps * 180.0 / M_PI;
    j["max_sigma_rate_deg_s"] = rates.sigma_rate_radps * 180.0 / M_PI;
    j["max_heat_flux_kW_m2"] = summary.maxima.qdot_Wpm2 * 1e-3;
    j["heat_load_MJ_m2"] = f.Q_Jpm2 * 1e-6;
    j["max_g"] = summary.maxima.n_g;
    j["max_q_kPa"] = summary.maxima.q_Pa * 1e-3;
    j["max_q_alpha_kPa_deg"] = summary.maxima.q_alpha_Pa_rad * 1e-3 * 180.0 / M_PI;
    j["violations"] = violations;
    j["flight_time_s"] = f.t_s;
    j["ticks"] = k;
    j["bad_messages"] = cmds.bad;
    j["bad_commands"] = cmds.bad_commands;
    j["bad_datagrams"] = net->counters().bad_datagrams;
    j["rx_kernel_drops"] = net->counters().kernel_drops;
    j["log_recorded"] = log.recorded();
    j["log_dropped"] = log.dropped();
    j["link_timeout_ticks"] = link_timeout_ticks;
    if (exit_code == kExitLinkLoss) {
      j["link_loss"] = {{"tick", link_lost_tick}, {"silent_ms", link_silent_s * 1e3},
                        {"guidance_ever_heard", cmds.last_heard_ns >= 0}};
    }
    // Context for the plots (tools/plot): aim point, heading-alignment circle, limits.
    j["taem_lat_deg"] = mission.taem.latitude_rad * 180.0 / M_PI;
    j["taem_lon_deg"] = mission.taem.longitude_rad * 180.0 / M_PI;
    j["taem_heading_deg"] = mission.taem.heading_rad * 180.0 / M_PI;
    j["hac_radius_km"] = mission.taem.hac_radius_m * 1e-3;
    j["entry_energy_Jpkg"] = sim->entry_energy_Jpkg();
    j["taem_energy_Jpkg"] = sim->taem_energy_Jpkg();
    const auto& lim = mission.constraints;
    if (std::isfinite(lim.heat_flux_max_Wpm2)) j["limit_heat_flux_kW_m2"] = lim.heat_flux_max_Wpm2 * 1e-3;
    if (std::isfinite(lim.load_factor_max_g)) j["limit_g"] = lim.load_factor_max_g;
    if (std::isfinite(lim.dynamic_pressure_max_Pa)) j["limit_q_kPa"] = lim.dynamic_pressure_max_Pa * 1e-3;
    std::ofstream(summary_path) << j.dump(2) << "\n";
  }
  std::printf("end event=%s t_s=%.1f alt_km=%.2f mach=%.2f dtg_km=%.1f\n",
              exit_code == kExitOk ? reentry::truth::to_string(summary.event) : "link_loss", f.t_s,
              f.h_m * 1e-3, f.mach, f.range_to_taem_m * 1e-3);
  return exit_code;
}
