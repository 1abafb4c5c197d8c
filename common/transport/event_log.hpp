// LCM event logs (the lcm-logger / lcm::LogFile format) written by the processes themselves,
// and a validating reader for every tool that reads one.
//
// EventLogWriter: each process records every message it sends and receives into its own log.
// A record is copied into a preallocated single-producer ring in the caller's thread (no I/O,
// no allocation); a writer thread drains the ring into lcm::LogFile and flushes after every
// batch, so a log holds every message of the process even when the machine is busy: nothing
// crosses a socket on the way, so nothing can be lost on the way. When the ring is full the
// caller either waits for room (lockstep: the run waits, the log stays complete) or the record
// is dropped and counted (realtime: the cycle never waits); a log with drops is named as
// incomplete by its readers through the counters the processes publish.
//
// Every log the writer closes ends with a seal (log_seal_t on channel LOG_SEAL): the event
// count and a CRC-32 (zlib) over every event before it as stored. A log is then verifiable
// byte for byte; one without a seal was not closed (its process was killed, or another tool
// such as lcm-logger wrote it).
//
// read_event_log: reads a log without trusting it (LCM 1.3.1's reader trusts the length
// fields; a huge one crashes it): every header is checked against the file before use,
// garbage between events is skipped and counted, a truncated tail, jumps in the event numbers
// (events missing from the middle) and a seal that does not match are reported.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace lcm {
class LogFile;
struct LogEvent;
}

namespace reentry::transport {

/// Channel of the seal event.
inline constexpr const char* kSealChannel = "LOG_SEAL";

/// CRC-32 of a log's events as stored (from the event number to the last data byte).
class LogDigest {
 public:
  void add(std::int64_t eventnum, std::int64_t timestamp_us, const char* channel, int channel_len, const void* data,
           int size);
  std::uint32_t crc() const { return crc_; }
  std::int64_t events() const { return events_; }
  std::int64_t bytes() const { return bytes_; }

 private:
  std::uint32_t crc_ = 0;
  std::int64_t events_ = 0;
  std::int64_t bytes_ = 0;
};

class EventLogWriter {
 public:
  enum class WhenFull : std::int8_t { kWait = 0, kDrop = 1 };

  EventLogWriter();
  ~EventLogWriter();
  EventLogWriter(const EventLogWriter&) = delete;
  EventLogWriter& operator=(const EventLogWriter&) = delete;

  /// Start-up: creates the file, the ring (ring_bytes, rounded up to a power of two, >= 1 MiB)
  /// and the writer thread.
  bool open(const std::string& path, std::size_t ring_bytes, WhenFull when_full, std::string& error);
  bool is_open() const { return ring_ != nullptr; }

  /// Records one message stamped with the wall-clock time now [us since the epoch], as
  /// lcm-logger stamps what it receives. Copies into the ring; never allocates, never does I/O.
  /// kWait waits for room at most max_wait_s, then drops. False when the record was dropped.
  bool record(const char* channel, const void* data, int len);
  /// The same with a given time stamp (tools that copy or merge logs).
  bool record_at(const char* channel, const void* data, int len, std::int64_t timestamp_us);

  /// Drains the ring, writes the seal, flushes and closes the file, joins the writer thread.
  /// False when anything could not be written (see error()): the log is not whole.
  bool close();

  std::int64_t recorded() const { return recorded_.load(std::memory_order_relaxed); }
  std::int64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  std::int64_t written() const { return written_.load(std::memory_order_relaxed); }
  bool io_error() const { return io_error_.load(std::memory_order_acquire); }
  /// "<path>: <reason> (log: <n> of <m> records written)" after a write error, else "".
  std::string error() const;
  const std::string& path() const { return path_; }
  double max_wait_s = 10.0;

 private:
  void writer_loop();
  bool write_seal();
  void note_io_error();

  std::unique_ptr<std::uint8_t[]> ring_;
  std::uint64_t capacity_ = 0;
  alignas(64) std::atomic<std::uint64_t> head_{0};  // producer position
  alignas(64) std::atomic<std::uint64_t> tail_{0};  // consumer position
  std::atomic<bool> stop_{false};
  std::atomic<std::int64_t> recorded_{0};
  std::atomic<std::int64_t> dropped_{0};
  std::atomic<std::int64_t> written_{0};
  std::atomic<bool> io_error_{false};
  std::atomic<int> io_errno_{0};  // errno of the first failed write (writer thread)
  std::string path_;
  WhenFull when_full_ = WhenFull::kWait;
  static constexpr std::size_t kIoBufferBytes = 1u << 20;
  std::unique_ptr<lcm::LogFile> file_;
  std::unique_ptr<char[]> io_buffer_;
  std::unique_ptr<lcm::LogEvent> event_;  // writer thread's event and channel, prepared at open()
  std::string channel_;
  std::vector<std::uint8_t> seal_buffer_;
  std::thread writer_;
  LogDigest digest_;  // writer thread
};

/// One event of a log; pointers into the mapped file, valid during the callback.
struct LogEventView {
  std::int64_t eventnum = 0;
  std::int64_t timestamp_us = 0;
  const char* channel = nullptr;
  int channel_len = 0;
  const std::uint8_t* data = nullptr;
  int size = 0;
};

/// How the file's framing looked.
struct LogFraming {
  std::int64_t events = 0;
  std::int64_t file_bytes = 0;
  std::int64_t bytes_consumed = 0;  // end of the last whole event
  std::int64_t skipped_bytes = 0;   // garbage between events (skipped to the next plausible event)
  std::int64_t eventnum_gaps = 0;   // event numbers not following each other: events missing
  bool truncated_tail = false;      // trailing bytes that do not form a whole event
  std::string error;                // non-empty: the file cannot be read as an LCM log at all
  bool sealed = false;              // the last event is a seal
  std::string seal_problem;         // non-empty: a seal that does not match, or not at the end
  std::int64_t seal_dropped = 0;    // records the writer reported dropped
  bool malformed() const {
    return !error.empty() || skipped_bytes > 0 || truncated_tail || eventnum_gaps > 0 || !seal_problem.empty();
  }
  std::string describe() const;
};

/// Reads every event of `path` in file order; `on_event` returns false to stop early.
LogFraming read_event_log(const std::string& path, const std::function<bool(const LogEventView&)>& on_event);

/// Wall-clock time [us since the epoch] (the log's event time base).
std::int64_t wall_clock_us();

}  // namespace reentry::transport
