// Decoder fuzz: random bytes into every message decode never crash and are counted as
// malformed; valid encodings round-trip.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/run_control_t.hpp>
#include <reentry/truth_telemetry_t.hpp>

#include "transport/lcm_codec.hpp"

namespace {

using reentry::transport::decode_into;
using reentry::transport::encode_into;

template <class Msg>
void fuzz_type() {
  std::mt19937_64 rng(12345);
  Msg msg{};
  std::int32_t bad = 0;
  int accepted = 0;
  const int n = 20000;
  std::vector<std::uint8_t> buf(70000);
  for (int i = 0; i < n; ++i) {
    const int len = static_cast<int>(rng() % 4096);
    for (int j = 0; j < len; ++j) buf[j] = static_cast<std::uint8_t>(rng());
    if (decode_into(msg, buf.data(), len, bad)) ++accepted;
  }
  // Random bytes essentially never carry the 8-byte type fingerprint.
  EXPECT_EQ(accepted, 0);
  EXPECT_EQ(bad, n);
  // A valid encoding decodes; every truncation of it is rejected and counted.
  Msg good{};
  good.utime = 42;
  good.tick = 7;
  const int size = encode_into(good, buf.data(), static_cast<int>(buf.size()));
  ASSERT_GT(size, 0);
  std::int32_t bad2 = 0;
  Msg back{};
  EXPECT_TRUE(decode_into(back, buf.data(), size, bad2));
  EXPECT_EQ(back.tick, 7);
  EXPECT_EQ(back.utime, 42);
  for (int cut = 0; cut < size; cut += 3) EXPECT_FALSE(decode_into(back, buf.data(), cut, bad2));
  EXPECT_EQ(bad2, (size + 2) / 3);
  EXPECT_LT(encode_into(good, buf.data(), size - 1), 0);
}

TEST(CodecFuzz, NavState) { fuzz_type<reentry::nav_state_t>(); }
TEST(CodecFuzz, GuidanceCmd) { fuzz_type<reentry::guidance_cmd_t>(); }
TEST(CodecFuzz, GuidanceStatus) { fuzz_type<reentry::guidance_status_t>(); }
TEST(CodecFuzz, Plan) { fuzz_type<reentry::plan_t>(); }
TEST(CodecFuzz, TruthTelemetry) { fuzz_type<reentry::truth_telemetry_t>(); }
TEST(CodecFuzz, RunControl) { fuzz_type<reentry::run_control_t>(); }

}  // namespace
