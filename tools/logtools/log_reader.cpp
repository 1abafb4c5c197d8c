#include "log_reader.hpp"

#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <cerrno>
#include <cstring>
#include <sys/stat.h>

#include "generated_csv_writers.hpp"

namespace reentry::logtools {
namespace {

constexpr uint8_t kSyncWord[4] = {0xED, 0xA1, 0xDA, 0x01};  // lcm eventlog magic, big-endian
constexpr int64_t kEventHeaderBytes = 4 + 8 + 8 + 4 + 4;     // sync, eventnum, utime, chan len, data len

template <class Msg>
class TypedHandler final : public MessageHandler {
 public:
  explicit TypedHandler(const char* name) : name_(name) {}
  const char* type_name() const override { return name_; }
  bool decode(const void* data, int size) override {
    return msg_.decode(data, 0, size) == size;
  }
  bool utime(int64_t* utime) const override { return message_utime(msg_, utime); }
  void csv_header(std::string& out) const override { logtools::csv_header(out, &msg_); }
  void csv_row(std::string& out) const override { logtools::csv_row(out, msg_); }
  bool has_points() const override { return logtools::has_points(&msg_); }
  void csv_points_header(std::string& out) const override { logtools::csv_points_header(out, &msg_); }
  long csv_points_rows(std::string& out) const override { return logtools::csv_points_rows(out, msg_); }

 private:
  const char* name_;
  Msg msg_{};
};

int64_t file_size(const std::string& path) {
  struct stat st{};
  if (stat(path.c_str(), &st) != 0) return -1;
  return static_cast<int64_t>(st.st_size);
}

uint32_t read_be32(const uint8_t* p) {
  return (static_cast<uint32_t>(p[0]) << 24) | (static_cast<uint32_t>(p[1]) << 16) |
         (static_cast<uint32_t>(p[2]) << 8) | static_cast<uint32_t>(p[3]);
}

// True when a whole event with sane lengths starts at `pos`; leaves the stream at `pos`.
bool event_header_plausible(std::FILE* fp, int64_t pos, int64_t file_bytes) {
  uint8_t head[kEventHeaderBytes];
  if (std::fseek(fp, static_cast<long>(pos), SEEK_SET) != 0) return false;
  const size_t got = std::fread(head, 1, sizeof head, fp);
  std::fseek(fp, static_cast<long>(pos), SEEK_SET);
  if (got != sizeof head || std::memcmp(head, kSyncWord, 4) != 0) return false;
  const int64_t channel_len = static_cast<int32_t>(read_be32(head + 20));
  const int64_t data_len = static_cast<int32_t>(read_be32(head + 24));
  if (channel_len <= 0 || channel_len >= 1000 || data_len < 0) return false;  // 1.3.1 channel limit
  return pos + kEventHeaderBytes + channel_len + data_len <= file_bytes;
}

}  // namespace

std::map<int64_t, std::unique_ptr<MessageHandler>> make_handlers() {
  std::map<int64_t, std::unique_ptr<MessageHandler>> handlers;
#define REENTRY_ADD_HANDLER(T) handlers.emplace(T::getHash(), std::make_unique<TypedHandler<T>>(T::getTypeName()));
  REENTRY_LOG_TYPES(REENTRY_ADD_HANDLER)
#undef REENTRY_ADD_HANDLER
  return handlers;
}

std::string LogScan::describe() const {
  if (!error.empty()) return error;
  std::string s;
  if (skipped_bytes > 0)
    s += std::to_string(skipped_bytes) + " bytes of garbage between events were skipped; ";
  if (truncated_tail)
    s += "reading stopped at byte " + std::to_string(bytes_consumed) + " of " + std::to_string(file_bytes) +
         " after event " + std::to_string(events) + ": the remaining " +
         std::to_string(file_bytes - bytes_consumed) + " bytes are a truncated or corrupt event; ";
  if (!s.empty()) s.resize(s.size() - 2);
  return s;
}

LogScan read_log(const std::string& path, const std::function<void(const LogEventView&)>& on_event) {
  LogScan scan;
  scan.file_bytes = file_size(path);
  if (scan.file_bytes < 0) {
    scan.error = "cannot open '" + path + "': " + std::strerror(errno);
    return scan;
  }
  {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) {
      scan.error = "cannot open '" + path + "': " + std::strerror(errno);
      return scan;
    }
    uint8_t head[4] = {0, 0, 0, 0};
    const size_t got = std::fread(head, 1, 4, f);
    std::fclose(f);
    if (scan.file_bytes == 0) {
      scan.error = "'" + path + "' is empty (no LCM events)";
      return scan;
    }
    if (got != 4 || std::memcmp(head, kSyncWord, 4) != 0) {
      scan.error = "'" + path + "' is not an LCM log: it does not start with the event sync word 0xEDA1DA01";
      return scan;
    }
  }
  lcm::LogFile log(path, "r");
  if (!log.good()) {
    scan.error = "lcm::LogFile cannot open '" + path + "'";
    return scan;
  }
  std::FILE* fp = log.getFilePtr();
  int64_t pos = 0;
  std::string channel;
  for (;;) {
    // LCM 1.3.1 trusts the length fields of an event header (a huge data length crashes it), so
    // each header is checked against the file size before lcm::LogFile reads the event.
    if (!event_header_plausible(fp, pos, scan.file_bytes)) break;
    const lcm::LogEvent* ev = log.readNextEvent();
    if (ev == nullptr) break;
    const int64_t end = static_cast<int64_t>(std::ftell(fp));
    const int64_t frame = kEventHeaderBytes + static_cast<int64_t>(ev->channel.size()) + ev->datalen;
    if (end - frame > pos) scan.skipped_bytes += end - frame - pos;
    pos = end;
    ++scan.events;
    channel = ev->channel;
    on_event(LogEventView{ev->eventnum, ev->timestamp, &channel, ev->data, ev->datalen});
  }
  scan.bytes_consumed = pos;
  scan.truncated_tail = pos < scan.file_bytes;
  if (scan.events == 0 && scan.error.empty())
    scan.error = "'" + path + "' contains no readable LCM event";
  return scan;
}

MessageHandler* classify_event(std::map<int64_t, std::unique_ptr<MessageHandler>>& handlers,
                               const LogEventView& ev, ChannelStats& stats) {
  if (stats.events == 0) stats.first_event_us = ev.timestamp_us;
  ++stats.events;
  stats.last_event_us = ev.timestamp_us;
  stats.bytes += ev.size;
  int64_t hash = 0;
  if (ev.size >= 8 && __int64_t_decode_array(ev.data, 0, ev.size, &hash, 1) != 8) hash = 0;
  const auto it = handlers.find(hash);
  if (ev.size < 8 || it == handlers.end()) {
    ++stats.unknown_type;
    return nullptr;
  }
  MessageHandler* h = it->second.get();
  if (!h->decode(ev.data, ev.size)) {
    ++stats.undecodable;
    return nullptr;
  }
  if (stats.type_name.empty()) stats.type_name = h->type_name();
  if (stats.type_name != h->type_name()) ++stats.type_changes;
  ++stats.decoded;
  int64_t u = 0;
  if (h->utime(&u)) {
    if (!stats.have_utime) stats.first_utime = u;
    stats.have_utime = true;
    stats.last_utime = u;
  }
  return h;
}

}  // namespace reentry::logtools
