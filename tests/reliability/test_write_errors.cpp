// One write-error path (issue 38 item 2): the event log writer reports a full device and an
// unwritable path with the file and the reason, and never calls a truncated log whole.
// /dev/full is a device on which every write fails with ENOSPC: a full filesystem without a mount.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "transport/command_line.hpp"
#include "transport/event_log.hpp"

namespace {

namespace tx = reentry::transport;

TEST(WriteErrors, FullDeviceIsReportedAndTheLogIsNotWhole) {
  tx::EventLogWriter log;
  std::string err;
  ASSERT_TRUE(log.open("/dev/full", 1u << 20, tx::EventLogWriter::WhenFull::kWait, err)) << err;
  std::vector<std::uint8_t> payload(2000, 0x5a);
  for (int i = 0; i < 2000; ++i) log.record("NAV_STATE", payload.data(), static_cast<int>(payload.size()));
  EXPECT_FALSE(log.close());
  EXPECT_TRUE(log.io_error());
  // The tools' form after "tool: write failed: ": the file, then the reason.
  EXPECT_EQ(log.error().rfind("/dev/full: No space left on device (log: ", 0), 0u) << log.error();
  EXPECT_LT(log.written(), log.recorded());
}

TEST(WriteErrors, UncreatableLogNamesThePath) {
  tx::EventLogWriter log;
  std::string err;
  EXPECT_FALSE(log.open("/nonexistent_dir_reentry/x.lcm", 1u << 20, tx::EventLogWriter::WhenFull::kWait, err));
  EXPECT_EQ(err.rfind("/nonexistent_dir_reentry/x.lcm: No such file or directory", 0), 0u) << err;
}

TEST(WriteErrors, WholeLogClosesTrueAndSealed) {
  const std::string path = ::testing::TempDir() + "/reliability_whole.lcm";
  tx::EventLogWriter log;
  std::string err;
  ASSERT_TRUE(log.open(path, 1u << 20, tx::EventLogWriter::WhenFull::kWait, err)) << err;
  const std::uint8_t b[4] = {1, 2, 3, 4};
  for (int i = 0; i < 100; ++i) log.record("X", b, 4);
  EXPECT_TRUE(log.close());
  EXPECT_EQ(log.error(), "");
  const tx::LogFraming fr = tx::read_event_log(path, [](const tx::LogEventView&) { return true; });
  EXPECT_TRUE(fr.sealed);
  EXPECT_EQ(fr.events, 101);
  std::remove(path.c_str());
}

TEST(ExitTable, BadArgumentsAreUsageNeverCli11Codes) {
  for (const char* bad : {"abc", "-1", "99999999999999999999999"}) {
    CLI::App app{"test", "test_tool"};
    std::int64_t seed = 0;
    app.add_option("--seed", seed)->check(tx::non_negative_integer());
    const char* argv[] = {"test_tool", "--seed", bad};
    EXPECT_EQ(tx::parse_command_line(app, 3, const_cast<char**>(argv), "test_tool"), tx::kExitUsage) << bad;
  }
  EXPECT_STREQ(tx::exit_name(tx::kExitWriteFailed), "write_failed");
  EXPECT_STREQ(tx::exit_name(130), "interrupted");
}

}  // namespace
