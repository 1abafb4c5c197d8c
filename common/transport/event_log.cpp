#include "transport/event_log.hpp"

#include <fcntl.h>
#include <lcm/lcm-cpp.hpp>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include <reentry/log_seal_t.hpp>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

namespace reentry::transport {
namespace {

// Ring record: header, channel, data, padded to 8 bytes. A record never wraps: when it does
// not fit before the end, a wrap marker sends the reader back to offset 0.
struct RecordHeader {
  std::uint32_t bytes;        // whole record incl. padding; kWrapMarker: wrap to offset 0
  std::uint16_t channel_len;
  std::uint16_t reserved;
  std::int64_t timestamp_us;
  std::uint32_t data_len;
  std::uint32_t reserved2;
};
static_assert(sizeof(RecordHeader) == 24, "record header layout");
constexpr std::uint32_t kWrapMarker = 0xFFFFFFFFu;
constexpr std::uint8_t kSync[4] = {0xED, 0xA1, 0xDA, 0x01};  // LCM event sync word (big-endian)
constexpr std::int64_t kEventHeaderBytes = 4 + 8 + 8 + 4 + 4;
constexpr std::int64_t kMaxChannelLen = 999;                  // LCM 1.3.1's reader limit

std::uint64_t round_up8(std::uint64_t n) { return (n + 7u) & ~std::uint64_t{7}; }

std::int64_t be64(const std::uint8_t* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | p[i];
  return static_cast<std::int64_t>(v);
}

std::int64_t be32s(const std::uint8_t* p) {
  const std::uint32_t v = (static_cast<std::uint32_t>(p[0]) << 24) | (static_cast<std::uint32_t>(p[1]) << 16) |
                          (static_cast<std::uint32_t>(p[2]) << 8) | static_cast<std::uint32_t>(p[3]);
  return static_cast<std::int32_t>(v);
}

// A whole, plausible event starts at `pos`: sync word, channel length in [1, 999] of printable
// bytes, data length >= 0, everything inside the file.
bool plausible_event(const std::uint8_t* f, std::int64_t size, std::int64_t pos, std::int64_t& chan_len,
                     std::int64_t& data_len) {
  if (pos < 0 || size - pos < kEventHeaderBytes) return false;
  if (std::memcmp(f + pos, kSync, 4) != 0) return false;
  chan_len = be32s(f + pos + 20);
  data_len = be32s(f + pos + 24);
  if (chan_len < 1 || chan_len > kMaxChannelLen || data_len < 0) return false;
  if (size - pos - kEventHeaderBytes < chan_len + data_len) return false;
  for (std::int64_t i = 0; i < chan_len; ++i) {
    const std::uint8_t c = f[pos + kEventHeaderBytes + i];
    if (c < 0x20 || c > 0x7e) return false;
  }
  return true;
}

void put_be64(std::uint8_t* p, std::int64_t v) {
  for (int i = 7; i >= 0; --i, v = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) >> 8)) {
    p[i] = static_cast<std::uint8_t>(v & 0xff);
  }
}

void put_be32(std::uint8_t* p, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  p[0] = static_cast<std::uint8_t>(u >> 24), p[1] = static_cast<std::uint8_t>(u >> 16);
  p[2] = static_cast<std::uint8_t>(u >> 8), p[3] = static_cast<std::uint8_t>(u);
}

}  // namespace

void LogDigest::add(std::int64_t eventnum, std::int64_t timestamp_us, const char* channel, int channel_len,
                    const void* data, int size) {
  std::uint8_t head[24];
  put_be64(head, eventnum);
  put_be64(head + 8, timestamp_us);
  put_be32(head + 16, channel_len);
  put_be32(head + 20, size);
  uLong c = crc32(crc_, head, sizeof head);
  c = crc32(c, reinterpret_cast<const Bytef*>(channel), static_cast<uInt>(channel_len));
  if (size > 0) c = crc32(c, static_cast<const Bytef*>(data), static_cast<uInt>(size));
  crc_ = static_cast<std::uint32_t>(c);
  ++events_;
  bytes_ += channel_len + size;
}

std::int64_t wall_clock_us() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000LL + ts.tv_nsec / 1000;
}

EventLogWriter::EventLogWriter() = default;
EventLogWriter::~EventLogWriter() { close(); }

void EventLogWriter::note_io_error() {
  // The first failure is the one reported; nothing is written after it (a partial write has
  // already broken the framing), the ring is still drained so that no caller waits on it.
  if (io_error_.load(std::memory_order_relaxed)) return;
  io_errno_.store(errno != 0 ? errno : EIO, std::memory_order_relaxed);
  io_error_.store(true, std::memory_order_release);
}

std::string EventLogWriter::error() const {
  if (!io_error()) return {};
  return path_ + ": " + std::strerror(io_errno_.load(std::memory_order_relaxed)) + " (log: " +
         std::to_string(written()) + " of " + std::to_string(recorded()) + " records written)";
}

bool EventLogWriter::open(const std::string& path, std::size_t ring_bytes, WhenFull when_full, std::string& error) {
  if (is_open()) {
    error = "log already open";
    return false;
  }
  std::uint64_t cap = 1u << 20;
  while (cap < ring_bytes && cap < (std::uint64_t{1} << 34)) cap <<= 1;
  path_ = path;
  io_error_.store(false);
  io_errno_.store(0);
  written_.store(0);
  errno = 0;
  file_ = std::make_unique<lcm::LogFile>(path, "w");
  if (!file_->good()) {
    error = path + ": " + std::strerror(errno) + " (the log cannot be created)";
    file_.reset();
    return false;
  }
  // The FILE buffer is ours, set before the first write: glibc would allocate it lazily in the
  // writer thread after start-up.
  io_buffer_.reset(new char[kIoBufferBytes]);
  std::setvbuf(file_->getFilePtr(), io_buffer_.get(), _IOFBF, kIoBufferBytes);
  digest_ = LogDigest{};
  event_ = std::make_unique<lcm::LogEvent>();
  event_->channel.reserve(256);
  channel_.reserve(256);
  seal_buffer_.assign(256, 0);
  ring_.reset(new std::uint8_t[cap]);
  std::memset(ring_.get(), 0, cap);  // touch the pages now, not in the first cycles
  capacity_ = cap;
  when_full_ = when_full;
  head_.store(0);
  tail_.store(0);
  stop_.store(false);
  writer_ = std::thread([this] { writer_loop(); });
  return true;
}

bool EventLogWriter::record(const char* channel, const void* data, int len) {
  return record_at(channel, data, len, wall_clock_us());
}

bool EventLogWriter::record_at(const char* channel, const void* data, int len, std::int64_t stamp) {
  if (!is_open() || channel == nullptr || len < 0) return false;
  const std::size_t ch_len = strnlen(channel, 256);
  const std::uint64_t need = round_up8(sizeof(RecordHeader) + ch_len + static_cast<std::uint64_t>(len));
  if (ch_len == 0 || ch_len > 255 || need > capacity_ / 4) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  const std::uint64_t head = head_.load(std::memory_order_relaxed);
  const std::uint64_t off = head & (capacity_ - 1);
  const std::uint64_t to_end = capacity_ - off;
  const std::uint64_t total = need <= to_end ? need : to_end + need;  // incl. the skipped end
  std::int64_t wait_until_ns = -1;
  for (;;) {
    const std::uint64_t used = head - tail_.load(std::memory_order_acquire);
    if (capacity_ - used >= total) break;
    if (when_full_ == WhenFull::kDrop) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                 std::chrono::steady_clock::now().time_since_epoch()).count();
    if (wait_until_ns < 0) wait_until_ns = now + static_cast<std::int64_t>(max_wait_s * 1e9);
    if (now > wait_until_ns) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
  std::uint64_t pos = head;
  if (need > to_end) {
    const std::uint32_t marker = kWrapMarker;
    std::memcpy(ring_.get() + off, &marker, sizeof marker);
    pos += to_end;
  }
  std::uint8_t* p = ring_.get() + (pos & (capacity_ - 1));
  RecordHeader h{};
  h.bytes = static_cast<std::uint32_t>(need);
  h.channel_len = static_cast<std::uint16_t>(ch_len);
  h.timestamp_us = stamp;
  h.data_len = static_cast<std::uint32_t>(len);
  std::memcpy(p, &h, sizeof h);
  std::memcpy(p + sizeof h, channel, ch_len);
  if (len > 0) std::memcpy(p + sizeof h + ch_len, data, static_cast<std::size_t>(len));
  head_.store(pos + need, std::memory_order_release);
  recorded_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void EventLogWriter::writer_loop() {
  // Prepared by open() before this thread started: nothing here allocates after start-up.
  lcm::LogEvent& ev = *event_;
  std::string& channel = channel_;
  bool unflushed = false;
  for (;;) {
    const std::uint64_t head = head_.load(std::memory_order_acquire);
    std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head) {
      if (unflushed) {
        // Flushed after every batch: a process killed mid-run leaves a log up to its last batch.
        if (!io_error() && std::fflush(file_->getFilePtr()) != 0) note_io_error();
        unflushed = false;
      }
      if (stop_.load(std::memory_order_acquire) && head_.load(std::memory_order_acquire) == tail) {
        if (!io_error()) write_seal();  // the seal covers every event written
        break;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(500));
      continue;
    }
    while (tail != head) {
      const std::uint64_t off = tail & (capacity_ - 1);
      std::uint32_t bytes = 0;
      std::memcpy(&bytes, ring_.get() + off, sizeof bytes);
      if (bytes == kWrapMarker) {
        tail += capacity_ - off;
        continue;
      }
      RecordHeader h{};
      std::memcpy(&h, ring_.get() + off, sizeof h);
      const char* ch = reinterpret_cast<const char*>(ring_.get() + off + sizeof h);
      channel.assign(ch, h.channel_len);
      ev.eventnum = 0;  // lcm::LogFile numbers the events itself
      ev.timestamp = h.timestamp_us;
      ev.channel = channel;
      ev.datalen = static_cast<std::int32_t>(h.data_len);
      ev.data = const_cast<std::uint8_t*>(ring_.get() + off + sizeof h + h.channel_len);
      if (!io_error()) {
        if (file_->writeEvent(&ev) != 0) {
          note_io_error();
        } else {
          digest_.add(digest_.events(), ev.timestamp, ch, h.channel_len, ev.data, ev.datalen);
          written_.fetch_add(1, std::memory_order_relaxed);
        }
      }
      tail += h.bytes;
      tail_.store(tail, std::memory_order_release);  // room for the producer as soon as possible
    }
    unflushed = true;
  }
}

bool EventLogWriter::write_seal() {
  lcm::LogEvent& ev = *event_;
  reentry::log_seal_t seal{};
  seal.utime = wall_clock_us();
  seal.events = digest_.events();
  seal.bytes = digest_.bytes();
  seal.crc32 = digest_.crc();
  seal.dropped = dropped_.load(std::memory_order_relaxed);
  const int n = seal.encode(seal_buffer_.data(), 0, static_cast<int>(seal_buffer_.size()));
  ev.eventnum = 0;
  ev.timestamp = seal.utime;
  ev.channel = kSealChannel;
  ev.datalen = static_cast<std::int32_t>(n > 0 ? n : 0);
  ev.data = seal_buffer_.data();
  if (file_->writeEvent(&ev) != 0 || std::fflush(file_->getFilePtr()) != 0) {
    note_io_error();
    return false;
  }
  return true;
}

bool EventLogWriter::close() {
  if (!is_open()) return !io_error();
  stop_.store(true, std::memory_order_release);
  if (writer_.joinable()) writer_.join();
  // Everything was flushed after the seal; a flush now reports what the stream still holds.
  errno = 0;
  if (!io_error() && std::fflush(file_->getFilePtr()) != 0) note_io_error();
  file_.reset();  // closes the file
  io_buffer_.reset();
  ring_.reset();
  capacity_ = 0;
  return !io_error();
}

std::string LogFraming::describe() const {
  if (!error.empty()) return error;
  std::string s;
  if (skipped_bytes > 0) s += std::to_string(skipped_bytes) + " bytes of garbage between events were skipped; ";
  if (!seal_problem.empty()) s += seal_problem + "; ";
  if (eventnum_gaps > 0) {
    s += std::to_string(eventnum_gaps) + " jump(s) in the event numbers: events are missing from the middle; ";
  }
  if (truncated_tail) {
    s += "reading stopped at byte " + std::to_string(bytes_consumed) + " of " + std::to_string(file_bytes) +
         " after event " + std::to_string(events) + ": the remaining " + std::to_string(file_bytes - bytes_consumed) +
         " bytes are a truncated or corrupt event; ";
  }
  if (!s.empty()) s.resize(s.size() - 2);
  return s;
}

namespace {

// The first plausible event at or after `pos` (-1: none); its lengths in chan_len, data_len.
std::int64_t next_plausible_event(const std::uint8_t* f, std::int64_t size, std::int64_t pos, std::int64_t& chan_len,
                                  std::int64_t& data_len) {
  if (plausible_event(f, size, pos, chan_len, data_len)) return pos;
  for (std::int64_t next = pos + 1; next + kEventHeaderBytes <= size; ++next) {
    if (f[next] == kSync[0] && plausible_event(f, size, next, chan_len, data_len)) return next;
  }
  return -1;
}

// A seal against the digest of the events before it.
void judge_seal(const LogEventView& ev, const LogDigest& digest, LogFraming& fr) {
  reentry::log_seal_t seal{};
  const bool decodes = seal.decode(ev.data, 0, ev.size) == ev.size;
  if (decodes && (seal.events != digest.events() || seal.bytes != digest.bytes() ||
                  seal.crc32 != static_cast<std::int64_t>(digest.crc()))) {
    fr.seal_problem = "the seal does not match the events before it (" + std::to_string(digest.events()) +
                      " events read, " + std::to_string(seal.events) + " sealed; CRC " +
                      (seal.crc32 == static_cast<std::int64_t>(digest.crc()) ? "equal" : "differs") +
                      "): bytes were changed, added or removed";
  } else if (!decodes) {
    fr.seal_problem = "the seal does not decode";
  }
  fr.seal_dropped = decodes ? seal.dropped : 0;
}

}  // namespace

LogFraming read_event_log(const std::string& path, const std::function<bool(const LogEventView&)>& on_event) {
  LogFraming fr;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    fr.error = "cannot open '" + path + "': " + std::strerror(errno);
    return fr;
  }
  struct stat st{};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    fr.error = "'" + path + "' is not a regular file";
    ::close(fd);
    return fr;
  }
  fr.file_bytes = static_cast<std::int64_t>(st.st_size);
  if (fr.file_bytes == 0) {
    fr.error = "'" + path + "' is empty (no LCM events)";
    ::close(fd);
    return fr;
  }
  void* map = ::mmap(nullptr, static_cast<std::size_t>(fr.file_bytes), PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (map == MAP_FAILED) {
    fr.error = "cannot map '" + path + "': " + std::strerror(errno);
    return fr;
  }
  const auto* f = static_cast<const std::uint8_t*>(map);
  const std::int64_t size = fr.file_bytes;
  if (size < 4 || std::memcmp(f, kSync, 4) != 0) {
    fr.error = "'" + path + "' is not an LCM log: it does not start with the event sync word 0xEDA1DA01";
    ::munmap(map, static_cast<std::size_t>(size));
    return fr;
  }
  std::int64_t pos = 0;
  std::int64_t last_eventnum = 0;
  bool have_eventnum = false;
  bool stopped = false;
  LogDigest digest;
  std::int64_t seal_at_event = -1;
  for (;;) {
    std::int64_t chan_len = 0, data_len = 0;
    const std::int64_t next = next_plausible_event(f, size, pos, chan_len, data_len);
    if (next < 0) break;
    fr.skipped_bytes += next - pos;  // damage: skipped to the next plausible event
    pos = next;
    LogEventView ev;
    ev.eventnum = be64(f + pos + 4);
    ev.timestamp_us = be64(f + pos + 12);
    ev.channel = reinterpret_cast<const char*>(f + pos + kEventHeaderBytes);
    ev.channel_len = static_cast<int>(chan_len);
    ev.data = f + pos + kEventHeaderBytes + chan_len;
    ev.size = static_cast<int>(data_len);
    if (have_eventnum && ev.eventnum != last_eventnum + 1) ++fr.eventnum_gaps;
    last_eventnum = ev.eventnum;
    have_eventnum = true;
    pos += kEventHeaderBytes + chan_len + data_len;
    fr.bytes_consumed = pos;
    ++fr.events;
    const bool is_seal = ev.channel_len == static_cast<int>(std::strlen(kSealChannel)) &&
                         std::memcmp(ev.channel, kSealChannel, static_cast<std::size_t>(ev.channel_len)) == 0;
    if (is_seal) {
      if (seal_at_event >= 0 && fr.seal_problem.empty()) fr.seal_problem = "more than one seal";
      seal_at_event = fr.events - 1;
      judge_seal(ev, digest, fr);
    } else {
      digest.add(ev.eventnum, ev.timestamp_us, ev.channel, ev.channel_len, ev.data, ev.size);
    }
    if (!on_event(ev)) {
      stopped = true;
      break;
    }
  }
  fr.truncated_tail = !stopped && fr.bytes_consumed < size;
  if (seal_at_event >= 0 && !stopped) {
    fr.sealed = seal_at_event == fr.events - 1;
    if (!fr.sealed && fr.seal_problem.empty()) fr.seal_problem = "events follow the seal";
  }
  if (fr.events == 0) fr.error = "'" + path + "' contains no readable LCM event";
  ::munmap(map, static_cast<std::size_t>(size));
  return fr;
}

}  // namespace reentry::transport
