// Reading LCM event logs (lcm-logger / lcm::LogFile format) with the validating reader of
// common/transport and dispatching each event to the generated message type whose
// fingerprint it carries.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace reentry::logtools {

// One decoder per generated LCM type; the implementation uses the type's own decode().
class MessageHandler {
 public:
  virtual ~MessageHandler() = default;
  virtual const char* type_name() const = 0;
  // Decodes one message; false when the payload does not decode.
  virtual bool decode(const void* data, int size) = 0;
  // Valid after a successful decode().
  virtual bool utime(int64_t* utime) const = 0;
  virtual void csv_header(std::string& out) const = 0;
  virtual void csv_row(std::string& out) const = 0;
  virtual bool has_points() const = 0;
  virtual void csv_points_header(std::string& out) const = 0;
  virtual long csv_points_rows(std::string& out) const = 0;
};

// Fresh handlers for every known type, keyed by the 64-bit fingerprint that starts each message.
std::map<int64_t, std::unique_ptr<MessageHandler>> make_handlers();

struct LogEventView {
  int64_t event_number;
  int64_t timestamp_us;  // logger receive / process send time (wall clock)
  const std::string* channel;
  const void* data;
  int size;
};

// How the file's framing looked while reading it.
struct LogScan {
  int64_t events = 0;
  int64_t file_bytes = 0;
  int64_t bytes_consumed = 0;
  int64_t skipped_bytes = 0;     // garbage between events (skipped to the next plausible event)
  int64_t eventnum_gaps = 0;     // jumps in the event numbers: events missing from the middle
  bool truncated_tail = false;   // trailing bytes that do not form a whole event
  std::string error;             // non-empty: the file cannot be read as an LCM log at all
  bool sealed = false;           // closed by our writer with a matching seal (LOG_SEAL)
  std::string seal_problem;      // a seal that does not match its events
  int64_t seal_dropped = 0;      // records its writer dropped
  bool malformed() const {
    return !error.empty() || skipped_bytes > 0 || truncated_tail || eventnum_gaps > 0 || !seal_problem.empty();
  }
  std::string describe() const;
};

// Reads every event of `path` in order and calls `on_event` for each.
// Returns the framing summary; scan.error is set when the file is not an LCM log.
LogScan read_log(const std::string& path, const std::function<void(const LogEventView&)>& on_event);

// Per-channel accounting shared by log2csv and loginfo (so both count rows identically).
struct ChannelStats {
  std::string type_name;           // empty until a message decoded
  int64_t events = 0;              // events on the channel
  int64_t decoded = 0;             // messages decoded (= CSV rows)
  int64_t unknown_type = 0;        // fingerprint not one of ours
  int64_t undecodable = 0;         // fingerprint known, decode() failed
  int64_t type_changes = 0;        // decoded with a type other than the channel's first type
  int64_t first_event_us = 0, last_event_us = 0;
  bool have_utime = false;
  int64_t first_utime = 0, last_utime = 0;
  int64_t bytes = 0;
};

// Decodes an event with the matching handler; returns the handler or nullptr and updates stats.
MessageHandler* classify_event(std::map<int64_t, std::unique_ptr<MessageHandler>>& handlers,
                               const LogEventView& ev, ChannelStats& stats);

}  // namespace reentry::logtools
