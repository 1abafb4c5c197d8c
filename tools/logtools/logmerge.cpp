// reentry_logmerge: one run log from the processes' own logs.
//   reentry_logmerge OUT IN[:CH1,CH2,...] [IN[:...] ...]
// Each input contributes the events of the listed channels (all when none are listed), e.g.
// the messages each process sent: tools/sil merges sim.lcm:NAV_STATE,TRUTH,RUN_CONTROL and
// fsw.lcm:GUIDANCE_CMD,GUIDANCE_STATUS,PLAN into run.lcm. Events are ordered by their time
// stamps (one wall clock on one machine: a command is stamped after the sample it answers),
// ties in input order, renumbered, and the output is sealed (common/transport/event_log.hpp).
// An input that is damaged, not sealed (its process did not close it) or reports dropped
// records is merged as far as it reads and reported: exit 3. Exit 4: the output cannot be written.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "transport/event_log.hpp"

namespace {

struct Event {
  std::int64_t timestamp_us;
  std::int64_t order;
  std::string channel;
  std::vector<std::uint8_t> data;
};

}  // namespace

int main(int argc, char** argv) {
  namespace tr = reentry::transport;
  if (argc < 3) {
    std::fprintf(stderr, "usage: reentry_logmerge OUT IN[:CH1,CH2,...] [IN[:...] ...]\n");
    return 2;
  }
  std::vector<Event> events;
  bool damaged = false;
  for (int i = 2; i < argc; ++i) {
    std::string arg = argv[i], path = arg;
    std::set<std::string> channels;
    const std::size_t colon = arg.rfind(':');
    if (colon != std::string::npos) {
      path = arg.substr(0, colon);
      const std::string list = arg.substr(colon + 1);
      for (std::size_t pos = 0; pos <= list.size();) {
        std::size_t comma = list.find(',', pos);
        if (comma == std::string::npos) comma = list.size();
        if (comma > pos) channels.insert(list.substr(pos, comma - pos));
        pos = comma + 1;
      }
    }
    std::int64_t taken = 0;
    const tr::LogFraming fr = tr::read_event_log(path, [&](const tr::LogEventView& ev) {
      std::string ch(ev.channel, static_cast<std::size_t>(ev.channel_len));
      if (ch == tr::kSealChannel || (!channels.empty() && channels.count(ch) == 0)) return true;
      events.push_back(Event{ev.timestamp_us, static_cast<std::int64_t>(events.size()), std::move(ch),
                             std::vector<std::uint8_t>(ev.data, ev.data + ev.size)});
      ++taken;
      return true;
    });
    std::string problem;
    if (fr.malformed()) problem = "damaged: " + fr.describe();
    else if (!fr.sealed) problem = "not sealed: its writer did not close it (killed?); it may end early";
    else if (fr.seal_dropped > 0) problem = "its writer dropped " + std::to_string(fr.seal_dropped) + " records";
    if (!problem.empty()) {
      std::fprintf(stderr, "logmerge: error: input '%s' %s (%lld events taken)\n", path.c_str(), problem.c_str(),
                   static_cast<long long>(taken));
      damaged = true;
    }
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
    return a.timestamp_us != b.timestamp_us ? a.timestamp_us < b.timestamp_us : a.order < b.order;
  });
  tr::EventLogWriter out;
  std::string err;
  if (!out.open(argv[1], 16u << 20, tr::EventLogWriter::WhenFull::kWait, err)) {
    std::fprintf(stderr, "logmerge: error: %s\n", err.c_str());
    return 4;
  }
  for (const Event& e : events) {
    if (!out.record_at(e.channel.c_str(), e.data.data(), static_cast<int>(e.data.size()), e.timestamp_us)) {
      std::fprintf(stderr, "logmerge: error: an event on '%s' could not be written\n", e.channel.c_str());
      return 4;
    }
  }
  out.close();
  if (out.io_error()) {
    std::fprintf(stderr, "logmerge: error: writing '%s' failed\n", argv[1]);
    return 4;
  }
  std::printf("logmerge: %zu events -> %s (sealed)\n", events.size(), argv[1]);
  return damaged ? 3 : 0;
}
