// Wire fuzzer for the two running processes (CTest, inside a private network namespace only).
//   wire_fuzz guidance --mission M --ticks N --junk-per-tick J --seed S --commands OUT --expect OUT.json
//     Acts as the simulator of a running guidance process: flies the truth simulator in
//     lockstep with it and, every tick, sends J malformed datagrams (broken LCM framing, LC03
//     fragments incl. the liblcm 1.3.1 fragment_offset wrap, and malformed messages of every
//     type on NAV_STATE / RUN_CONTROL from tests/exec/junk_messages.hpp); every 20th tick a
//     sample with implausible values comes first and its answer must be the held command,
//     flagged. Writes the commands flown (bit patterns) and the counts the guidance process
//     must report; with J = 0 it is the clean reference run.
//   wire_fuzz simulator --expect OUT.json   (the simulator ends the run: --stop-after)
//     Acts as the guidance process of a running simulator: answers every sample, and at tick 50
//     first sends NaN/inf/out-of-range/future-tick/negative-tick commands and undecodable ones;
//     from tick 51 on it banks 1.0 rad. The simulator must count each, hold, and fly the bank.
//   wire_fuzz repro --scenario frag_wrap|tick_jump|time_jump|tick_max|tick_overflow|tick_negative_start|
//                              first_absurd|first_wrong|radial_velocity
//     The reproductions of ../shared/repro/ (frag_targets.sh, wire_fuzz.py) against a fresh
//     guidance process: after the one bad datagram the real stream must be answered as before
//     (nothing crashes, nothing latches: no answer flagged nav-invalid, commands not frozen).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "junk_messages.hpp"
#include "reentry/config/mission.hpp"
#include "transport/lcm_codec.hpp"
#include "transport/monotonic_clock.hpp"
#include "transport/udpm.hpp"

namespace {

using reentry::transport::decode_into;
using reentry::transport::mono_ns;
namespace tr = reentry::transport;

// Raw datagrams to the group: what no LCM library would send.
class RawSender {
 public:
  explicit RawSender(const tr::UdpmUrl& url) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    const unsigned char ttl = 0, loop = 1;
    ::setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
    ::setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
    dest_.sin_family = AF_INET;
    dest_.sin_port = htons(url.port);
    dest_.sin_addr.s_addr = htonl(url.group);
  }
  ~RawSender() { ::close(fd_); }
  void send(const std::vector<std::uint8_t>& d) {
    ::sendto(fd_, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&dest_), sizeof dest_);
  }

 private:
  int fd_ = -1;
  sockaddr_in dest_{};
};

void put32(std::vector<std::uint8_t>& d, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) d.push_back(static_cast<std::uint8_t>(v >> s));
}

// A datagram that parse_datagram must refuse (LC03 wrap first: the liblcm crash).
std::vector<std::uint8_t> bad_framing(std::mt19937_64& rng, int variant) {
  std::vector<std::uint8_t> d;
  const std::string ch = "NAV_STATE";
  switch (variant % 8) {
    case 0:  // LC03 with fragment_offset + size wrapping 2^32 (../shared/repro/frag_wrap_one.py)
      put32(d, tr::kMagicFragment), put32(d, static_cast<std::uint32_t>(rng())), put32(d, 1000), put32(d, 0xFFFFFF00u);
      d.insert(d.end(), {0, 0, 0, 2});
      d.insert(d.end(), ch.begin(), ch.end());
      d.push_back(0);
      d.resize(d.size() + 300, 0x55);
      break;
    case 1:  // LC03 claiming 4 GB, zero fragments, offset past the end, orphan fragment
      put32(d, tr::kMagicFragment), put32(d, static_cast<std::uint32_t>(rng()));
      put32(d, static_cast<std::uint32_t>(rng() % 2 ? 0xFFFFFFF0u : 1000)), put32(d, static_cast<std::uint32_t>(rng() % 6000));
      d.insert(d.end(), {0, static_cast<std::uint8_t>(rng() % 10), 0, static_cast<std::uint8_t>(rng() % 3)});
      d.resize(d.size() + rng() % 300, static_cast<std::uint8_t>(rng()));
      break;
    case 2: d.assign({0x4c, 0x43, 0x30}); d.resize(1 + rng() % 7, 0x32); break;  // shorter than a header
    case 3: put32(d, 0x58585858u), put32(d, 7), d.insert(d.end(), ch.begin(), ch.end()), d.push_back(0), d.resize(60, 1); break;
    case 4:  // channel without its NUL
      put32(d, tr::kMagicShort), put32(d, 7);
      for (int i = 0; i < 10; ++i) d.insert(d.end(), ch.begin(), ch.end());
      break;
    case 5: put32(d, tr::kMagicShort), put32(d, 8), d.push_back(0), d.resize(50, 'x'); break;  // empty channel
    case 6: put32(d, tr::kMagicShort), put32(d, 9), d.insert(d.end(), {'N', 'A', 'V', ' ', 'S', 0, 1, 2}); break;
    default: d.resize(1 + rng() % 2000); for (auto& b : d) b = static_cast<std::uint8_t>(rng()); d[0] = 0xAB; break;
  }
  return d;
}

reentry::nav_state_t nav_of(const reentry::truth::NavSample& ns, std::int64_t k) {
  reentry::nav_state_t nav{};
  nav.utime = std::llround(ns.t_s * 1e6);
  nav.tick = k;
  nav.t_s = ns.t_s;
  for (int i = 0; i < 3; ++i) {
    nav.position_I_m[i] = ns.r_I_m[i];
    nav.velocity_I_mps[i] = ns.v_I_mps[i];
    nav.aero_accel_I_mps2[i] = ns.aero_accel_I_mps2[i];
  }
  nav.earth_rotation_angle_rad = ns.earth_rotation_angle_rad;
  return nav;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

constexpr std::int32_t kHealthNavInvalidBit = 1;  // guidance_cmd_t.health_flags bit 0: nav rejected, command held

struct Net {
  std::unique_ptr<tr::UdpmSocket> sock = std::make_unique<tr::UdpmSocket>();
  tr::UdpmUrl url;
  bool open() {
    std::string err;
    if (!tr::parse_udpm_url(tr::default_udpm_url(), url, err) || !sock->open(url, err)) {
      std::fprintf(stderr, "wire_fuzz: network: %s\n", err.c_str());
      return false;
    }
    return true;
  }
  template <class Msg>
  void publish(const char* ch, const Msg& m) {
    const auto b = reentry::testing::encoded(m);
    sock->publish(ch, b.data(), static_cast<int>(b.size()));
  }
};

std::int64_t g_flagged_answers = 0;  // GUIDANCE_CMD seen with the nav-invalid flag

// Waits for a GUIDANCE_CMD of `tick` (flagged nav-invalid or not); republishes `nav` each second.
bool wait_cmd(Net& net, std::int64_t tick, bool flagged, const std::vector<std::uint8_t>& nav,
              reentry::guidance_cmd_t& out, std::int64_t& republished, double timeout_s = 30.0, bool either = false) {
  const std::int64_t t0 = mono_ns();
  std::int64_t next = t0 + 1000000000LL;
  tr::Datagram d;
  std::int32_t bad = 0;
  while (static_cast<double>(mono_ns() - t0) * 1e-9 < timeout_s) {
    if (net.sock->receive(d, 10000000) == 1 && std::strcmp(d.channel, "GUIDANCE_CMD") == 0 &&
        decode_into(out, d.payload, d.payload_len, bad)) {
      const bool is_flagged = (out.health_flags & kHealthNavInvalidBit) != 0;
      if (is_flagged) ++g_flagged_answers;
      if (out.tick == tick && (is_flagged == flagged || either)) return true;
    }
    if (mono_ns() > next) {
      net.sock->publish("NAV_STATE", nav.data(), static_cast<int>(nav.size()));
      ++republished;
      next += 1000000000LL;
    }
  }
  return false;
}

// One command as the comparison reads it: tick, the bits of alpha and sigma, mode, plan.
void write_command(std::ofstream& out, const reentry::guidance_cmd_t& cmd) {
  std::uint64_t a = 0, s = 0;
  std::memcpy(&a, &cmd.alpha_rad, 8);
  std::memcpy(&s, &cmd.sigma_rad, 8);
  out << cmd.tick << ' ' << a << ' ' << s << ' ' << static_cast<int>(cmd.mode) << ' ' << cmd.plan_seq << '\n';
}

int fuzz_guidance(const std::string& mission_arg, int ticks, int junk_per_tick, std::uint64_t seed,
                  const std::string& commands_path, const std::string& expect_path) {
  const auto loaded = reentry::config::load_mission(mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "wire_fuzz: %s\n", loaded.error.c_str());
    return 2;
  }
  std::string error;
  auto sim = reentry::truth::Simulator::create(loaded.mission, reentry::truth::SimOverrides{}, &error);
  if (!sim) {
    std::fprintf(stderr, "wire_fuzz: %s\n", error.c_str());
    return 2;
  }
  Net net;
  if (!net.open()) return 2;
  RawSender raw(net.url);
  reentry::testing::JunkGenerator junk(seed);
  const double dt = 1.0 / loaded.mission.guidance.gnc_rate_hz;
  std::ofstream cmds(commands_path);
  std::int64_t undecodable = 0, duplicates = 0, bad_ticks = 0, bad_controls = 0, held = 0, framing = 0, sent = 0;
  std::int64_t republished = 0, held_wrong = 0;
  reentry::guidance_cmd_t cmd{}, prev{};
  bool have_prev = false;
  std::int64_t k = 0;
  for (; k < ticks && !sim->finished(); ++k) {
    const reentry::nav_state_t nav = nav_of(sim->nav_sample(), k);
    const auto bytes = reentry::testing::encoded(nav);
    if (junk_per_tick > 0 && k % 20 == 10 && have_prev) {
      const auto bad = junk.bad_values(nav);
      net.sock->publish("NAV_STATE", bad.data(), static_cast<int>(bad.size()));
      if (!wait_cmd(net, k, true, bad, cmd, republished)) {
        std::fprintf(stderr, "wire_fuzz: no held answer to an implausible sample at tick %lld\n", static_cast<long long>(k));
        return 1;
      }
      ++held;
      if (!same_bits(cmd.alpha_rad, prev.alpha_rad) || !same_bits(cmd.sigma_rad, prev.sigma_rad)) ++held_wrong;
    }
    net.sock->publish("NAV_STATE", bytes.data(), static_cast<int>(bytes.size()));
    if (!wait_cmd(net, k, false, bytes, cmd, republished)) {
      std::fprintf(stderr, "wire_fuzz: no command for tick %lld (guidance dead or stuck)\n", static_cast<long long>(k));
      return 1;
    }
    write_command(cmds, cmd);
    prev = cmd;
    have_prev = true;
    for (int j = 0; j < junk_per_tick; ++j, ++sent) {
      if (j % 10 == 0) {
        raw.send(bad_framing(junk.rng(), static_cast<int>(k + j / 10)));
        ++framing;
        continue;
      }
      const reentry::testing::Junk m = junk.next(nav);
      net.sock->publish(m.channel, m.bytes.data(), static_cast<int>(m.bytes.size()));
      switch (m.effect) {
        case reentry::testing::JunkEffect::kUndecodable: ++undecodable; break;
        case reentry::testing::JunkEffect::kDuplicate: ++duplicates; break;
        case reentry::testing::JunkEffect::kBadTick: ++bad_ticks; break;
        case reentry::testing::JunkEffect::kBadControl: ++bad_controls; break;
      }
    }
    sim->set_command(cmd.alpha_rad, cmd.sigma_rad);
    sim->advance_to(static_cast<double>(k + 1) * dt);
  }
  reentry::run_control_t rc{};
  rc.tick = k;
  rc.command = reentry::run_control_t::END_OF_RUN;
  rc.event = reentry::run_control_t::EVENT_TIMEOUT;
  for (int i = 0; i < 3; ++i) net.publish("RUN_CONTROL", rc);
  std::ofstream(expect_path) << "{\"ticks\": " << k << ", \"sent\": " << sent << ", \"bad_datagrams\": " << framing
                             << ", \"bad_messages\": " << undecodable + bad_controls
                             << ", \"duplicate_ticks\": " << duplicates + republished
                             << ", \"nav_rejected_tick\": " << bad_ticks << ", \"nav_rejected_values\": " << held
                             << ", \"invalid_nav\": " << bad_ticks + held << ", \"held_wrong\": " << held_wrong
                             << ", \"republished\": " << republished << "}\n";
  std::printf("wire_fuzz guidance: %lld ticks, %lld malformed datagrams (%lld framing, %lld undecodable, %lld "
              "duplicates, %lld bad ticks, %lld bad controls), %lld implausible samples held (%lld wrongly)\n",
              static_cast<long long>(k), static_cast<long long>(sent), static_cast<long long>(framing),
              static_cast<long long>(undecodable), static_cast<long long>(duplicates), static_cast<long long>(bad_ticks),
              static_cast<long long>(bad_controls), static_cast<long long>(held), static_cast<long long>(held_wrong));
  return held_wrong == 0 ? 0 : 1;
}

int fuzz_simulator(const std::string& expect_path) {
  Net net;
  if (!net.open()) return 2;
  std::int64_t bad_commands = 0, undecodable = 0, answered = 0;
  double last_truth_sigma = std::numeric_limits<double>::quiet_NaN();
  std::int64_t last_truth_tick = -1, last_nav = -1;
  bool ended = false;
  tr::Datagram d;
  std::int32_t bad = 0;
  reentry::nav_state_t nav{};
  reentry::truth_telemetry_t tel{};
  reentry::run_control_t rc{};
  const std::int64_t t0 = mono_ns();
  while (!ended && mono_ns() - t0 < 120000000000LL) {
    if (net.sock->receive(d, 20000000) != 1) continue;
    if (std::strcmp(d.channel, "TRUTH") == 0 && decode_into(tel, d.payload, d.payload_len, bad)) {
      last_truth_sigma = tel.sigma_rad;
      last_truth_tick = tel.tick;
    } else if (std::strcmp(d.channel, "RUN_CONTROL") == 0 && decode_into(rc, d.payload, d.payload_len, bad)) {
      ended = rc.command == reentry::run_control_t::END_OF_RUN;
    } else if (std::strcmp(d.channel, "NAV_STATE") == 0 && decode_into(nav, d.payload, d.payload_len, bad) &&
               nav.tick > last_nav) {
      last_nav = nav.tick;
      reentry::guidance_cmd_t c{};
      c.utime = nav.utime;
      c.tick = nav.tick;
      c.alpha_rad = 0.80285;
      c.sigma_rad = nav.tick > 50 ? 1.0 : 0.0;
      if (nav.tick == 50) {
        // Decodable but implausible: each must be counted and ignored, none adopted. Each banks
        // -2.5 rad: had one been flown, the bank rate to the 1.0 rad from tick 51 on would be
        // 2000 deg/s instead of the 573 deg/s of the step 0 -> 1.0 rad.
        const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
        reentry::guidance_cmd_t base = c;
        base.sigma_rad = -2.5;
        std::vector<reentry::guidance_cmd_t> bads(8, base);
        bads[0].alpha_rad = nan;
        bads[1].sigma_rad = inf;
        bads[2].beta_rad = -inf;
        bads[3].tick = 1000000000000LL;  // used to latch the simulator: every later command ignored
        bads[4].tick = -1;
        bads[5].tick = nav.tick + 1;     // from the future
        bads[6].alpha_rad = 100.0;
        bads[7].sigma_rad = 1e300;
        for (const auto& b : bads) net.publish("GUIDANCE_CMD", b), ++bad_commands;
        const auto good = reentry::testing::encoded(c);
        std::vector<std::vector<std::uint8_t>> junk = {{}, {1, 2, 3}, std::vector<std::uint8_t>(good.begin(), good.end() - 3)};
        junk.push_back(good);
        junk.back()[3] ^= 0x10;  // fingerprint
        reentry::nav_state_t foreign = nav;
        junk.push_back(reentry::testing::encoded(foreign));
        for (const auto& j : junk) net.sock->publish("GUIDANCE_CMD", j.data(), static_cast<int>(j.size())), ++undecodable;
      }
      net.publish("GUIDANCE_CMD", c);
      ++answered;
    }
  }
  std::ofstream(expect_path) << "{\"bad_commands\": " << bad_commands << ", \"bad_messages\": " << undecodable
                             << ", \"answered\": " << answered << ", \"last_nav_tick\": " << last_nav
                             << ", \"last_truth_tick\": " << last_truth_tick << ", \"last_truth_sigma_rad\": "
                             << (std::isfinite(last_truth_sigma) ? last_truth_sigma : -999.0)
                             << ", \"ended\": " << (ended ? "true" : "false") << "}\n";
  std::printf("wire_fuzz simulator: answered %lld samples (last tick %lld), sent %lld implausible and %lld undecodable "
              "commands at tick 50; flown bank at tick %lld: %.3f rad; run ended: %s\n",
              static_cast<long long>(answered), static_cast<long long>(last_nav), static_cast<long long>(bad_commands),
              static_cast<long long>(undecodable), static_cast<long long>(last_truth_tick), last_truth_sigma,
              ended ? "yes" : "no");
  return ended ? 0 : 1;
}

// The issue-38 samples: plausible for every absolute window, absurd for the mission.
reentry::nav_state_t absurd_nav(reentry::nav_state_t n, const std::string& scenario) {
  double r = 0.0, v = 0.0;
  for (int i = 0; i < 3; ++i) r += n.position_I_m[i] * n.position_I_m[i], v += n.velocity_I_mps[i] * n.velocity_I_mps[i];
  r = std::sqrt(r), v = std::sqrt(v);
  if (scenario == "first_absurd") {  // 999 km, 14.9 km/s, 489 m/s^2 sensed
    for (int i = 0; i < 3; ++i) {
      n.position_I_m[i] *= (6378137.0 + 999e3) / r;
      n.velocity_I_mps[i] *= 14900.0 / v;
      n.aero_accel_I_mps2[i] = -489.0 * n.velocity_I_mps[i] / 14900.0;
    }
  } else if (scenario == "first_wrong") {  // plausible for the mission, 5 km too high
    for (int i = 0; i < 3; ++i) n.position_I_m[i] *= (r + 5e3) / r;
  } else if (scenario == "radial_velocity") {  // 7.6 km/s straight up
    for (int i = 0; i < 3; ++i) n.velocity_I_mps[i] = 7600.0 * n.position_I_m[i] / r;
  }
  return n;
}

int repro(const std::string& mission_arg, const std::string& scenario) {
  const auto loaded = reentry::config::load_mission(mission_arg);
  if (!loaded.ok) return 2;
  std::string error;
  auto sim = reentry::truth::Simulator::create(loaded.mission, reentry::truth::SimOverrides{}, &error);
  if (!sim) return 2;
  Net net;
  if (!net.open()) return 2;
  RawSender raw(net.url);
  std::mt19937_64 rng(7);
  const double dt = 1.0 / loaded.mission.guidance.gnc_rate_hz;
  const std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  const bool first = scenario == "first_absurd" || scenario == "first_wrong";
  const std::int64_t bad_at = scenario == "frag_wrap" ? 50 : first ? 0 : 150;
  const std::int64_t end = scenario == "frag_wrap" ? 100 : 450;
  std::int64_t answered = 0, flagged = 0, republished = 0;
  reentry::guidance_cmd_t cmd{};
  auto send_nav = [&](reentry::nav_state_t n) {
    const auto b = reentry::testing::encoded(n);
    net.sock->publish("NAV_STATE", b.data(), static_cast<int>(b.size()));
  };
  if (scenario == "tick_overflow" || scenario == "tick_negative_start") {
    reentry::nav_state_t first = nav_of(sim->nav_sample(), 0);
    first.tick = scenario == "tick_overflow" ? std::numeric_limits<std::int64_t>::min() + 1 : -(std::int64_t{1} << 62);
    send_nav(first);
    if (scenario == "tick_overflow") {
      first.tick = kMax;  // INT64_MIN + 1 then INT64_MAX: was a signed overflow (UBSan abort)
      send_nav(first);
    }
  }
  std::int64_t k = 0;
  for (; k < end && !sim->finished(); ++k) {
    reentry::nav_state_t nav = nav_of(sim->nav_sample(), k);
    if (k == bad_at) {
      reentry::nav_state_t bad = nav;
      if (scenario == "frag_wrap") {
        for (int i = 0; i < 5; ++i) raw.send(bad_framing(rng, 0));
      } else if (scenario == "tick_jump") {
        bad.tick = k + 1000000, send_nav(bad);
      } else if (scenario == "time_jump") {
        bad.t_s = 1e9, send_nav(bad);
      } else if (scenario == "tick_max") {
        bad.tick = kMax, send_nav(bad);
      } else {
        send_nav(absurd_nav(bad, scenario));
      }
    }
    const auto bytes = reentry::testing::encoded(nav);
    net.sock->publish("NAV_STATE", bytes.data(), static_cast<int>(bytes.size()));
    // A plausible-but-wrong first sample is accepted and the first real samples answered flagged
    // until they replace it (the simulator takes any answer of its tick).
    const bool any_answer = scenario == "first_wrong" && k < 5;
    if (!wait_cmd(net, k, false, bytes, cmd, republished, 5.0, any_answer)) {
      std::printf("wire_fuzz repro %s: no answer at tick %lld: the guidance process died or latched\n", scenario.c_str(),
                  static_cast<long long>(k));
      return 1;
    }
    ++answered;
    sim->set_command(cmd.alpha_rad, cmd.sigma_rad);
    sim->advance_to(static_cast<double>(k + 1) * dt);
  }
  // A flagged answer to the real stream would be the latch-up of the reproduction.
  flagged = g_flagged_answers;
  reentry::run_control_t rc{};
  rc.tick = k;
  rc.command = reentry::run_control_t::END_OF_RUN;
  for (int i = 0; i < 3; ++i) net.publish("RUN_CONTROL", rc);
  // The latch-up looked like every later real sample answered with the held command, flagged
  // (300 of 300): here every tick must get its own unflagged answer.
  std::printf("wire_fuzz repro %s: %lld of %lld ticks answered, %lld answers flagged nav-invalid\n", scenario.c_str(),
              static_cast<long long>(answered), static_cast<long long>(end), static_cast<long long>(flagged));
  // The injected sample itself is answered flagged (values refused) when it carries a tick the
  // guidance has not answered yet; the plausible wrong one is accepted, then 2 real samples are
  // refused until 3 consistent ones replace it.
  const std::int64_t want_flagged = scenario == "first_absurd" || scenario == "radial_velocity" ? 1
                                    : scenario == "first_wrong"                                 ? 2
                                                                                                : 0;
  return answered == end && flagged == want_flagged ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"wire fuzzer of the SIL processes (private network namespace only)"};
  std::string role, mission = "x33", commands = "/dev/null", expect = "/dev/null", scenario;
  int ticks = 2000, junk_per_tick = 0;
  std::uint64_t seed = 20261203;
  cli.add_option("role", role)->required()->check(CLI::IsMember({"guidance", "simulator", "repro"}));
  cli.add_option("--scenario", scenario);
  cli.add_option("--mission", mission);
  cli.add_option("--ticks", ticks);
  cli.add_option("--junk-per-tick", junk_per_tick);
  cli.add_option("--seed", seed);
  cli.add_option("--commands", commands);
  cli.add_option("--expect", expect);
  CLI11_PARSE(cli, argc, argv);
  if (role == "repro") return repro(mission, scenario);
  return role == "guidance" ? fuzz_guidance(mission, ticks, junk_per_tick, seed, commands, expect)
                            : fuzz_simulator(expect);
}
