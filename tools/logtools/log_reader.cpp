#include "log_reader.hpp"

#include "generated_csv_writers.hpp"
#include "transport/event_log.hpp"

namespace reentry::logtools {
namespace {

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

}  // namespace

std::map<int64_t, std::unique_ptr<MessageHandler>> make_handlers() {
  std::map<int64_t, std::unique_ptr<MessageHandler>> handlers;
#define REENTRY_ADD_HANDLER(T) handlers.emplace(T::getHash(), std::make_unique<TypedHandler<T>>(T::getTypeName()));
  REENTRY_LOG_TYPES(REENTRY_ADD_HANDLER)
#undef REENTRY_ADD_HANDLER
  return handlers;
}

std::string LogScan::describe() const {
  transport::LogFraming f;
  f.events = events;
  f.file_bytes = file_bytes;
  f.bytes_consumed = bytes_consumed;
  f.skipped_bytes = skipped_bytes;
  f.eventnum_gaps = eventnum_gaps;
  f.truncated_tail = truncated_tail;
  f.error = error;
  f.seal_problem = seal_problem;
  return f.describe();
}

LogScan read_log(const std::string& path, const std::function<void(const LogEventView&)>& on_event) {
  // The validating reader of common/transport (shared with the replay): every header is
  // checked against the file before it is used, damage is skipped and reported.
  std::string channel;
  const transport::LogFraming f = transport::read_event_log(path, [&](const transport::LogEventView& ev) {
    channel.assign(ev.channel, static_cast<size_t>(ev.channel_len));
    on_event(LogEventView{ev.eventnum, ev.timestamp_us, &channel, ev.data, ev.size});
    return true;
  });
  LogScan scan;
  scan.events = f.events;
  scan.file_bytes = f.file_bytes;
  scan.bytes_consumed = f.bytes_consumed;
  scan.skipped_bytes = f.skipped_bytes;
  scan.eventnum_gaps = f.eventnum_gaps;
  scan.truncated_tail = f.truncated_tail;
  scan.error = f.error;
  scan.sealed = f.sealed;
  scan.seal_problem = f.seal_problem;
  scan.seal_dropped = f.seal_dropped;
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
