// The process transport without a network: the datagram validator against hand-made LCM
// datagrams (the liblcm 1.3.1 crash case included) and >= 1e5 random / mutated datagrams, the
// udpm URL parser, and the processes' event logs (writer -> validating reader round trip,
// ring wrap, drops, and damaged files that must be reported, never trusted).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "transport/event_log.hpp"
#include "transport/udpm.hpp"

namespace {

using namespace reentry::transport;

std::vector<std::uint8_t> be32(std::uint32_t v) {
  return {static_cast<std::uint8_t>(v >> 24), static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
          static_cast<std::uint8_t>(v)};
}

std::vector<std::uint8_t> short_msg(const std::string& channel, const std::vector<std::uint8_t>& payload) {
  std::vector<std::uint8_t> d = be32(kMagicShort);
  const auto seq = be32(7);
  d.insert(d.end(), seq.begin(), seq.end());
  d.insert(d.end(), channel.begin(), channel.end());
  d.push_back(0);
  d.insert(d.end(), payload.begin(), payload.end());
  return d;
}

// Status only (the view points into a buffer freed on return).
DatagramStatus parse(const std::vector<std::uint8_t>& d, Datagram& out) {
  // Copy into an exactly sized heap block so that ASan sees any read past the end.
  std::unique_ptr<std::uint8_t[]> buf(new std::uint8_t[d.size() + (d.empty() ? 1 : 0)]);
  if (!d.empty()) std::memcpy(buf.get(), d.data(), d.size());
  return parse_datagram(buf.get(), static_cast<int>(d.size()), out);
}

TEST(Datagram, ValidShortMessageIsParsedInPlace) {
  Datagram g;
  const auto d = short_msg("NAV_STATE", {1, 2, 3});
  ASSERT_EQ(parse_datagram(d.data(), static_cast<int>(d.size()), g), DatagramStatus::kOk);
  EXPECT_EQ(g.payload, d.data() + d.size() - 3);
  EXPECT_EQ(g.seqno, 7u);
  EXPECT_EQ(std::string(g.channel, g.channel_len), "NAV_STATE");
  EXPECT_EQ(g.payload_len, 3);
  EXPECT_EQ(parse(short_msg("X", {}), g), DatagramStatus::kOk);  // empty payload: the decoder rejects it
  EXPECT_EQ(g.payload_len, 0);
}

TEST(Datagram, MalformedDatagramsAreRefusedWithTheirReason) {
  Datagram g;
  // The liblcm 1.3.1 crash (../shared/repro/frag_wrap_one.py): LC03 with fragment_offset 0xFFFFFF00.
  std::vector<std::uint8_t> frag = be32(kMagicFragment);
  for (std::uint32_t v : {12345u, 1000u, 0xFFFFFF00u}) {
    const auto b = be32(v);
    frag.insert(frag.end(), b.begin(), b.end());
  }
  frag.insert(frag.end(), {0, 0, 0, 2});
  const std::string ch = "NAV_STATE";
  frag.insert(frag.end(), ch.begin(), ch.end());
  frag.push_back(0);
  frag.insert(frag.end(), 300, 0x55);
  EXPECT_EQ(parse(frag, g), DatagramStatus::kFragment);
  EXPECT_EQ(parse({}, g), DatagramStatus::kTooShort);
  EXPECT_EQ(parse({0x4c, 0x43, 0x30}, g), DatagramStatus::kTooShort);
  EXPECT_EQ(parse({0x4c, 0x43, 0x30, 0x32, 0, 0, 0, 1}, g), DatagramStatus::kTooShort);
  EXPECT_EQ(parse({'X', 'X', 'X', 'X', 0, 0, 0, 1, 'A', 0}, g), DatagramStatus::kBadMagic);
  EXPECT_EQ(parse(short_msg("", {1}), g), DatagramStatus::kChannelEmpty);
  EXPECT_EQ(parse(short_msg("NAV STATE", {1}), g), DatagramStatus::kChannelInvalid);
  EXPECT_EQ(parse(short_msg(std::string(64, 'A'), {1}), g), DatagramStatus::kChannelUnterminated);
  EXPECT_EQ(parse(short_msg(std::string(63, 'A'), {1}), g), DatagramStatus::kOk);
  auto unterminated = short_msg("NAV_STATE", {});
  unterminated.pop_back();  // drop the NUL: the channel runs to the end of the datagram
  EXPECT_EQ(parse(unterminated, g), DatagramStatus::kChannelUnterminated);
}

TEST(Datagram, FrameAndParseRoundTripAndLimits) {
  std::vector<std::uint8_t> buf(70000);
  const std::uint8_t payload[5] = {9, 8, 7, 6, 5};
  const int n = frame_datagram(42, "GUIDANCE_CMD", payload, 5, buf.data(), static_cast<int>(buf.size()));
  ASSERT_EQ(n, 8 + 12 + 1 + 5);
  Datagram g;
  ASSERT_EQ(parse_datagram(buf.data(), n, g), DatagramStatus::kOk);
  EXPECT_EQ(g.seqno, 42u);
  EXPECT_EQ(std::memcmp(g.payload, payload, 5), 0);
  EXPECT_LT(frame_datagram(1, "", payload, 5, buf.data(), 1000), 0);
  EXPECT_LT(frame_datagram(1, "BAD CHANNEL", payload, 5, buf.data(), 1000), 0);
  EXPECT_LT(frame_datagram(1, std::string(64, 'A').c_str(), payload, 5, buf.data(), 1000), 0);
  EXPECT_LT(frame_datagram(1, "A", payload, 5, buf.data(), 10), 0);
  std::vector<std::uint8_t> big(65500);
  EXPECT_LT(frame_datagram(1, "A", big.data(), 65500, buf.data(), 70000), 0);  // more than one UDP datagram
}

TEST(Datagram, FuzzedDatagramsNeverReadOutOfBoundsAndAreClassified) {
  // 2e5 datagrams (random, truncated, bit-flipped valid ones, wrapping LC03 headers) into the
  // validator; every accepted one lies inside its buffer. ASan checks the reads in CI.
  std::mt19937_64 rng(20261203);
  const auto valid = short_msg("NAV_STATE", std::vector<std::uint8_t>(108, 0x42));
  int ok = 0, bad = 0;
  for (int i = 0; i < 200000; ++i) {
    std::vector<std::uint8_t> d;
    switch (i % 4) {
      case 0:
        d.resize(rng() % 300);
        for (auto& b : d) b = static_cast<std::uint8_t>(rng());
        break;
      case 1:
        d.assign(valid.begin(), valid.begin() + static_cast<long>(rng() % (valid.size() + 1)));
        break;
      case 2:
        d = valid;
        for (int f = 0; f < 1 + static_cast<int>(rng() % 3); ++f) d[rng() % d.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
        break;
      default: {
        d = be32(rng() % 2 ? kMagicFragment : kMagicShort);
        for (int w = 0; w < 3; ++w) {
          const auto b = be32(static_cast<std::uint32_t>(rng()));
          d.insert(d.end(), b.begin(), b.end());
        }
        d.resize(d.size() + rng() % 100, static_cast<std::uint8_t>(rng()));
      }
    }
    Datagram g;
    std::unique_ptr<std::uint8_t[]> buf(new std::uint8_t[d.size() + 1]);
    if (!d.empty()) std::memcpy(buf.get(), d.data(), d.size());
    const DatagramStatus st = parse_datagram(buf.get(), static_cast<int>(d.size()), g);
    if (st == DatagramStatus::kOk) {
      ++ok;
      ASSERT_GE(reinterpret_cast<const std::uint8_t*>(g.channel), buf.get() + 8);
      ASSERT_EQ(g.payload + g.payload_len, buf.get() + d.size());
      ASSERT_EQ(g.channel[g.channel_len], '\0');
      ASSERT_GE(g.channel_len, 1);
    } else {
      ++bad;
    }
  }
  EXPECT_GT(ok, 10000);  // truncations and flips that keep a valid frame
  EXPECT_GT(bad, 100000);
}

TEST(UdpmUrl, ParsesLcmUrlsAndNamesWhatIsWrong) {
  UdpmUrl u;
  std::string err;
  ASSERT_TRUE(parse_udpm_url("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304", u, err)) << err;
  EXPECT_EQ(u.group, 0xEFFF4C43u);
  EXPECT_EQ(u.port, 7667);
  EXPECT_EQ(u.ttl, 0);
  EXPECT_EQ(u.recv_buf_bytes, 4194304);
  ASSERT_TRUE(parse_udpm_url("udpm://239.255.76.67:7667", u, err));
  EXPECT_EQ(u.recv_buf_bytes, kDefaultRecvBufferBytes);
  for (const char* bad : {"file:///tmp/x.lcm", "udpm://10.0.0.1:7667", "udpm://239.255.76.67:0", "udpm://239.255.76.67:99999",
                          "udpm://nonsense:7667", "udpm://239.255.76.67:7667?ttl=300", "udpm://239.255.76.67:7667?foo=1",
                          "udpm://239.255.76.67:7667?recv_buf_size=-5"}) {
    EXPECT_FALSE(parse_udpm_url(bad, u, err)) << bad;
    EXPECT_NE(err.find("URL"), std::string::npos) << err;
  }
}

std::string temp_path(const char* name) {
  return std::string(::testing::TempDir()) + "/" + std::to_string(::getpid()) + "_" + name;
}

TEST(EventLog, WriterRecordsEveryMessageInOrderThroughRingWraps) {
  const std::string path = temp_path("writer.lcm");
  EventLogWriter w;
  std::string err;
  ASSERT_TRUE(w.open(path, 1 << 20, EventLogWriter::WhenFull::kWait, err)) << err;
  std::vector<std::uint8_t> payload(10000);
  const int n = 5000;  // 50 MB through a 1 MiB ring: many wraps, the producer waits for room
  for (int i = 0; i < n; ++i) {
    const int len = 1 + (i * 7919) % 10000;
    for (int j = 0; j < 8 && j < len; ++j) payload[static_cast<std::size_t>(j)] = static_cast<std::uint8_t>(i >> (j % 4 * 8));
    ASSERT_TRUE(w.record(i % 2 ? "A" : "CHANNEL_B", payload.data(), len));
  }
  w.close();
  EXPECT_EQ(w.dropped(), 0);
  EXPECT_EQ(w.written(), n);
  int seen = 0;
  const LogFraming fr = read_event_log(path, [&](const LogEventView& ev) {
    if (seen == n) {
      EXPECT_EQ(std::string(ev.channel, ev.channel_len), kSealChannel);  // the seal closes the log
      return true;
    }
    EXPECT_EQ(ev.size, 1 + (seen * 7919) % 10000);
    EXPECT_EQ(std::string(ev.channel, ev.channel_len), seen % 2 ? "A" : "CHANNEL_B");
    EXPECT_EQ(ev.data[0], static_cast<std::uint8_t>(seen));
    EXPECT_EQ(ev.eventnum, seen);
    ++seen;
    return true;
  });
  EXPECT_EQ(seen, n);
  EXPECT_FALSE(fr.malformed()) << fr.describe();
  EXPECT_TRUE(fr.sealed);
  EXPECT_EQ(fr.seal_dropped, 0);
  std::remove(path.c_str());
}

TEST(EventLog, DropPolicyCountsInsteadOfWaiting) {
  const std::string path = temp_path("drop.lcm");
  EventLogWriter w;
  std::string err;
  ASSERT_TRUE(w.open(path, 1 << 20, EventLogWriter::WhenFull::kDrop, err)) << err;
  std::vector<std::uint8_t> payload(60000);
  int kept = 0;
  for (int i = 0; i < 2000; ++i) kept += w.record("X", payload.data(), 60000) ? 1 : 0;  // 120 MB at once
  w.close();
  EXPECT_EQ(kept + w.dropped(), 2000);
  EXPECT_GT(w.dropped(), 0);
  EXPECT_EQ(w.written(), kept);
  const LogFraming fr = read_event_log(path, [](const LogEventView&) { return true; });
  EXPECT_TRUE(fr.sealed);
  EXPECT_EQ(fr.seal_dropped, w.dropped());  // the seal says the log is incomplete
  std::remove(path.c_str());
}

TEST(EventLog, DamagedLogsAreReportedNeverTrusted) {
  const std::string path = temp_path("good.lcm");
  {
    EventLogWriter w;
    std::string err;
    ASSERT_TRUE(w.open(path, 1 << 20, EventLogWriter::WhenFull::kWait, err)) << err;
    std::uint8_t payload[100] = {};
    for (int i = 0; i < 50; ++i) w.record("NAV_STATE", payload, 20 + i);
  }
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(good.size(), 1000u);
  auto read_blob = [&](const std::vector<char>& blob) {
    const std::string p = temp_path("damaged.lcm");
    std::ofstream(p, std::ios::binary).write(blob.data(), static_cast<std::streamsize>(blob.size()));
    int events = 0;
    LogFraming fr = read_event_log(p, [&](const LogEventView& ev) {
      EXPECT_GE(ev.size, 0);
      ++events;
      return true;
    });
    std::remove(p.c_str());
    return fr;
  };
  // Every truncation: a cut inside an event is a truncated tail, never silently complete.
  std::int64_t boundary = 0;
  std::vector<std::int64_t> ends;
  read_event_log(path, [&](const LogEventView& ev) {
    boundary += 28 + ev.channel_len + ev.size;
    ends.push_back(boundary);
    return true;
  });
  for (std::size_t cut = 1; cut < good.size(); cut += 7) {
    const LogFraming fr = read_blob(std::vector<char>(good.begin(), good.begin() + static_cast<long>(cut)));
    const bool at_boundary = std::find(ends.begin(), ends.end(), static_cast<std::int64_t>(cut)) != ends.end();
    EXPECT_EQ(fr.malformed(), !at_boundary) << "cut " << cut;
  }
  // Garbage in the middle, a huge length, a broken sync word, a removed event.
  std::vector<char> garbage = good;
  garbage.insert(garbage.begin() + 300, 77, '\x5a');
  EXPECT_GT(read_blob(garbage).skipped_bytes, 0);
  std::vector<char> huge = good;
  huge[static_cast<std::size_t>(ends[3]) + 24] = '\x7f';  // data length of event 4 -> ~2 GB
  EXPECT_TRUE(read_blob(huge).malformed());
  std::vector<char> sync = good;
  sync[static_cast<std::size_t>(ends[5])] ^= 1;
  EXPECT_TRUE(read_blob(sync).malformed());
  std::vector<char> removed(good.begin(), good.begin() + ends[9]);
  removed.insert(removed.end(), good.begin() + ends[10], good.end());
  const LogFraming rm = read_blob(removed);
  EXPECT_EQ(rm.eventnum_gaps, 1);
  EXPECT_TRUE(rm.malformed());
  EXPECT_NE(rm.seal_problem, "");
  EXPECT_TRUE(read_blob(good).sealed);
  EXPECT_FALSE(read_blob(good).malformed());
  // Random bit flips: never a crash (ASan), and never a sealed log that reads as intact: the
  // seal's CRC covers every byte before it (a flip in the seal itself breaks or removes it).
  std::mt19937 rng(7);
  for (int i = 0; i < 300; ++i) {
    std::vector<char> b = good;
    for (int f = 0; f < 1 + static_cast<int>(rng() % 4); ++f) b[rng() % b.size()] ^= static_cast<char>(1 << (rng() % 8));
    const LogFraming fr = read_blob(b);
    EXPECT_TRUE(fr.malformed() || !fr.sealed) << "flips " << i << " went unnoticed";
  }
  EXPECT_NE(read_blob({}).error, "");
  EXPECT_NE(read_blob({'a', 'b'}).error, "");
  std::remove(path.c_str());
}

}  // namespace
