// reentry_logmerge: one run log from the processes' own logs.
//   reentry_logmerge OUT IN[:CH1,CH2,...] [IN[:...] ...]
// Each input contributes the events of the listed channels (all when none are listed), e.g.
// the messages each process sent: tools/sil merges sim.lcm:NAV_STATE,TRUTH,RUN_CONTROL and
// fsw.lcm:GUIDANCE_CMD,GUIDANCE_STATUS,PLAN into run.lcm. Events are ordered by their time
// stamps (one wall clock on one machine: a command is stamped after the sample it answers),
// ties in input order; event numbers are renumbered. A damaged input is merged as far as it
// reads and reported (exit 3); the output is written with lcm::LogFile.
#include <lcm/lcm-cpp.hpp>

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
  int input;
  std::int64_t order;
  std::string channel;
  std::vector<std::uint8_t> data;
};

}  // namespace

int main(int argc, char** argv) {
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
      std::string list = arg.substr(colon + 1);
      for (std::size_t pos = 0; pos <= list.size();) {
        std::size_t comma = list.find(',', pos);
        if (comma == std::string::npos) comma = list.size();
        if (comma > pos) channels.insert(list.substr(pos, comma - pos));
        pos = comma + 1;
      }
    }
    std::int64_t taken = 0;
    const reentry::transport::LogFraming fr =
        reentry::transport::read_event_log(path, [&](const reentry::transport::LogEventView& ev) {
          std::string ch(ev.channel, static_cast<std::size_t>(ev.channel_len));
          if (!channels.empty() && channels.count(ch) == 0) return true;
          events.push_back(Event{ev.timestamp_us, i, static_cast<std::int64_t>(events.size()), std::move(ch),
                                 std::vector<std::uint8_t>(ev.data, ev.data + ev.size)});
          ++taken;
          return true;
        });
    if (fr.malformed()) {
      std::fprintf(stderr, "logmerge: error: damaged input '%s': %s (%lld events taken)\n", path.c_str(),
                   fr.describe().c_str(), static_cast<long long>(taken));
      damaged = true;
    }
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
    return a.timestamp_us != b.timestamp_us ? a.timestamp_us < b.timestamp_us : a.order < b.order;
  });
  lcm::LogFile out(argv[1], "w");
  if (!out.good()) {
    std::fprintf(stderr, "logmerge: error: cannot create '%s': %s\n", argv[1], std::strerror(errno));
    return 4;
  }
  for (Event& e : events) {
    lcm::LogEvent ev{};
    ev.timestamp = e.timestamp_us;
    ev.channel = e.channel;
    ev.datalen = static_cast<std::int32_t>(e.data.size());
    ev.data = e.data.data();
    if (out.writeEvent(&ev) != 0) {
      std::fprintf(stderr, "logmerge: error: writing '%s' failed\n", argv[1]);
      return 4;
    }
  }
  std::printf("logmerge: %zu events -> %s\n", events.size(), argv[1]);
  return damaged ? 3 : 0;
}
