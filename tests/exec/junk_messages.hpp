// Seeded generator of malformed input for the guidance process's channels (shared by the
// in-process fuzz test and the wire fuzzer of the running process). Every junk message comes
// with what the guidance process must make of it, known by construction:
//   kUndecodable: does not decode as the channel's type (random bytes, truncated or extended
//                 encodings, a flipped fingerprint bit, another type) -> bad_messages + 1;
//   kDuplicate:   a decodable NAV_STATE of the tick just accepted (one bit flipped outside the
//                 fingerprint and the tick) -> duplicate_ticks + 1, nothing adopted;
//   kBadTick:     a decodable NAV_STATE whose tick or time is implausible -> invalid_nav + 1,
//                 not answered;
//   kBadControl:  a decodable RUN_CONTROL that must not end the run -> bad_messages + 1.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/run_control_t.hpp>
#include <reentry/truth_telemetry_t.hpp>

namespace reentry::testing {

enum class JunkEffect { kUndecodable, kDuplicate, kBadTick, kBadControl };

struct Junk {
  const char* channel;
  std::vector<std::uint8_t> bytes;
  JunkEffect effect;
  const char* kind;
};

template <class Msg>
std::vector<std::uint8_t> encoded(const Msg& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

class JunkGenerator {
 public:
  explicit JunkGenerator(std::uint64_t seed) : rng_(seed) {}

  /// One malformed message for the tick that has just been accepted (`nav` is its sample).
  Junk next(const nav_state_t& nav) {
    const auto good = encoded(nav);
    switch (rng_() % 14) {
      case 0: return {"NAV_STATE", random_bytes(1 + rng_() % 300), JunkEffect::kUndecodable, "random"};
      case 1: return {"NAV_STATE", {}, JunkEffect::kUndecodable, "empty"};
      case 2: return {"NAV_STATE", truncated(good), JunkEffect::kUndecodable, "truncated"};
      case 3: return {"NAV_STATE", extended(good), JunkEffect::kUndecodable, "trailing_bytes"};
      case 4: return {"NAV_STATE", flipped(good, 0, 8), JunkEffect::kUndecodable, "fingerprint_flip"};
      case 5: return {"NAV_STATE", foreign(nav, true), JunkEffect::kUndecodable, "foreign_type"};
      case 6: return {"NAV_STATE", mangled_foreign(nav), JunkEffect::kUndecodable, "foreign_type_damaged"};
      case 7: return {"NAV_STATE", flipped_outside_tick(good), JunkEffect::kDuplicate, "payload_flip_same_tick"};
      case 8: return {"NAV_STATE", flipped(good, 16, 24), JunkEffect::kBadTick, "tick_flip"};
      case 9: return {"NAV_STATE", tick_variant(nav), JunkEffect::kBadTick, "tick_or_time_jump"};
      case 10: return {"RUN_CONTROL", random_bytes(1 + rng_() % 200), JunkEffect::kUndecodable, "rc_random"};
      case 11: {
        const auto rc = encoded(control(nav));
        return {"RUN_CONTROL", rng_() % 2 ? truncated(rc) : flipped(rc, 0, 8), JunkEffect::kUndecodable,
                "rc_truncated_or_fingerprint"};
      }
      case 12: return {"RUN_CONTROL", foreign(nav, false), JunkEffect::kUndecodable, "rc_foreign_type"};
      default: return {"RUN_CONTROL", encoded(control(nav)), JunkEffect::kBadControl, "rc_implausible"};
    }
  }

  /// A sample of this tick with implausible values (radius 1 m, 1e6 m/s, drag 1e4 m/s^2, NaN),
  /// sent in place of the real one: answered with the held command, flagged.
  std::vector<std::uint8_t> bad_values(const nav_state_t& nav) {
    nav_state_t b = nav;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    switch (rng_() % 6) {
      case 0: b.position_I_m[0] = 1.0, b.position_I_m[1] = 0.0, b.position_I_m[2] = 0.0; break;
      case 1: b.velocity_I_mps[0] = 1e6; break;
      case 2: b.aero_accel_I_mps2[0] = 1e4; break;
      case 3: b.position_I_m[2] = nan; break;
      case 4: b.velocity_I_mps[1] = std::numeric_limits<double>::infinity(); break;
      default: b.position_I_m[0] *= 1.2; break;  // a 1300 km altitude jump in one tick
    }
    return encoded(b);
  }

  std::mt19937_64& rng() { return rng_; }

 private:
  std::vector<std::uint8_t> random_bytes(std::size_t n) {
    std::vector<std::uint8_t> b(n);
    for (auto& x : b) x = static_cast<std::uint8_t>(rng_());
    return b;
  }
  std::vector<std::uint8_t> truncated(const std::vector<std::uint8_t>& g) {
    return std::vector<std::uint8_t>(g.begin(), g.begin() + static_cast<long>(rng_() % g.size()));
  }
  std::vector<std::uint8_t> extended(std::vector<std::uint8_t> g) {
    const std::size_t n = 1 + rng_() % 64;
    for (std::size_t i = 0; i < n; ++i) g.push_back(static_cast<std::uint8_t>(rng_()));
    return g;
  }
  // One bit flipped in bytes [from, to).
  std::vector<std::uint8_t> flipped(std::vector<std::uint8_t> g, std::size_t from, std::size_t to) {
    g[from + rng_() % (to - from)] ^= static_cast<std::uint8_t>(1u << (rng_() % 8));
    return g;
  }
  // nav_state_t: fingerprint [0,8), utime [8,16), tick [16,24), t_s [24,32), then values.
  // Any flip outside the fingerprint and the tick keeps the tick: a duplicate (checked first).
  std::vector<std::uint8_t> flipped_outside_tick(std::vector<std::uint8_t> g) {
    std::size_t pos = 8 + rng_() % (g.size() - 16);
    if (pos >= 16) pos += 8;  // skip the tick
    g[pos] ^= static_cast<std::uint8_t>(1u << (rng_() % 8));
    return g;
  }
  std::vector<std::uint8_t> tick_variant(const nav_state_t& nav) {
    nav_state_t b = nav;
    const std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
    switch (rng_() % 7) {
      case 0: b.tick = nav.tick + 1000000; break;                          // tick_jump
      case 1: b.tick = nav.tick + 1; b.t_s = 1e9; break;                    // time_jump
      case 2: b.tick = kMax; break;                                         // tick_max
      case 3: b.tick = std::numeric_limits<std::int64_t>::min() + 1; break; // tick_overflow
      case 4: b.tick = nav.tick - 5; b.t_s = static_cast<double>(b.tick) * 0.1; break;  // replayed old tick
      case 5: b.tick = nav.tick + 1000; b.t_s = static_cast<double>(b.tick) * 0.1; break;  // consistent far jump
      default: b.tick = nav.tick + 1; b.t_s = nav.t_s - 1.0; break;        // time going back
    }
    return encoded(b);
  }
  // Another of our types on this channel (on NAV_STATE a RUN_CONTROL and vice versa).
  std::vector<std::uint8_t> foreign(const nav_state_t& nav, bool on_nav_channel) {
    switch (rng_() % 5) {
      case 0: { guidance_cmd_t m{}; m.tick = nav.tick; return encoded(m); }
      case 1: { guidance_status_t m{}; m.tick = nav.tick; return encoded(m); }
      case 2: { plan_t m{}; m.tick = nav.tick; return encoded(m); }
      case 3: { truth_telemetry_t m{}; m.tick = nav.tick; return encoded(m); }
      default: return on_nav_channel ? encoded(control(nav)) : encoded(nav);
    }
  }
  std::vector<std::uint8_t> mangled_foreign(const nav_state_t& nav) {
    auto b = foreign(nav, true);
    return rng_() % 2 ? truncated(b) : extended(b);
  }
  // A RUN_CONTROL that must never end the run: an unknown command, or an end far from the run.
  run_control_t control(const nav_state_t& nav) {
    run_control_t rc{};
    if (rng_() % 2) {
      rc.command = 99;  // one bit flip away from neither STOP (2) nor END_OF_RUN (3)
      rc.tick = nav.tick;
    } else {
      rc.command = run_control_t::END_OF_RUN;
      rc.tick = rng_() % 2 ? -5 : nav.tick + 100000;
    }
    return rc;
  }

  std::mt19937_64 rng_;
};

}  // namespace reentry::testing
