// Decoder fuzz: per message type 2e4 random buffers, every truncation and 2e4 extended and
// 2e4 bit-flipped valid encodings (3.6e5 decodes over the six types, under ASan/UBSan in CI).
// Random bytes and truncated/extended encodings are refused and counted; a flip in the 8-byte
// fingerprint is refused, a flip anywhere else decodes (fixed-size types) to a message that
// differs from the original in exactly the flipped byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
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
  for (int cut = 0; cut < size; ++cut) EXPECT_FALSE(decode_into(back, buf.data(), cut, bad2));
  EXPECT_EQ(bad2, size);
  EXPECT_LT(encode_into(good, buf.data(), size - 1), 0);
  const std::vector<std::uint8_t> valid(buf.begin(), buf.begin() + size);
  std::vector<std::uint8_t> m(static_cast<std::size_t>(size) + 64), re(static_cast<std::size_t>(size));
  std::int32_t bad3 = 0;
  int refused = 0, flipped_ok = 0;
  for (int i = 0; i < n; ++i) {
    // Extended: trailing bytes after a valid encoding are refused (a message is one datagram).
    std::copy(valid.begin(), valid.end(), m.begin());
    const int extra = 1 + static_cast<int>(rng() % 64);
    for (int j = 0; j < extra; ++j) m[static_cast<std::size_t>(size + j)] = static_cast<std::uint8_t>(rng());
    EXPECT_FALSE(decode_into(back, m.data(), size + extra, bad3));
    // One bit flipped.
    std::copy(valid.begin(), valid.end(), m.begin());
    const int pos = static_cast<int>(rng() % static_cast<unsigned>(size));
    m[static_cast<std::size_t>(pos)] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
    if (decode_into(back, m.data(), size, bad3)) {
      ASSERT_GE(pos, 8) << "a flipped fingerprint decoded";
      ++flipped_ok;
      // Re-encoding gives back the flipped bytes: the decoder read every byte, and only them.
      ASSERT_EQ(back.encode(re.data(), 0, size), size);
      ASSERT_EQ(std::memcmp(re.data(), m.data(), static_cast<std::size_t>(size)), 0) << "byte " << pos;
    } else {
      ASSERT_LT(pos, 8) << "a flip at byte " << pos << " was refused";
      ++refused;
    }
  }
  EXPECT_EQ(bad3, n + refused);
  EXPECT_GT(flipped_ok, 0);
  EXPECT_GT(refused, 0);
}

TEST(CodecFuzz, NavState) { fuzz_type<reentry::nav_state_t>(); }
TEST(CodecFuzz, GuidanceCmd) { fuzz_type<reentry::guidance_cmd_t>(); }
TEST(CodecFuzz, GuidanceStatus) { fuzz_type<reentry::guidance_status_t>(); }
TEST(CodecFuzz, Plan) { fuzz_type<reentry::plan_t>(); }
TEST(CodecFuzz, TruthTelemetry) { fuzz_type<reentry::truth_telemetry_t>(); }
TEST(CodecFuzz, RunControl) { fuzz_type<reentry::run_control_t>(); }

}  // namespace
