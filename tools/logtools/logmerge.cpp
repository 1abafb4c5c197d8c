// reentry_logmerge: one run log from the processes' own logs.
//   reentry_logmerge OUT IN[:CH1,CH2,...] [IN[:...] ...]
// Each input contributes the events of the listed channels (all when none are listed), e.g.
// the messages each process sent: tools/sil merges sim.lcm:NAV_STATE,TRUTH,RUN_CONTROL and
// fsw.lcm:GUIDANCE_CMD,GUIDANCE_STATUS,PLAN into run.lcm. Events are ordered by their time
// stamps (one wall clock on one machine: a command is stamped after the sample it answers),
// ties in input order, renumbered, and the output is sealed (common/transport/event_log.hpp).
// An input that is damaged, not sealed (its process did not close it) or reports dropped
// records is merged as far as it reads and reported: exit 6 (damaged) or 5 (not sealed, records
// dropped). Exit 8: the output cannot be written whole.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "transport/event_log.hpp"
#include "transport/exit_status.hpp"

namespace {

struct Event {
  std::int64_t timestamp_us;
  std::int64_t order;
  std::string channel;
  std::vector<std::uint8_t> data;
};

namespace tr = reentry::transport;

// "IN[:CH1,CH2,...]": the path and the channels taken (all when none are listed).
void parse_input(const std::string& arg, std::string& path, std::set<std::string>& channels) {
  path = arg;
  const std::size_t colon = arg.rfind(':');
  if (colon == std::string::npos) return;
  path = arg.substr(0, colon);
  const std::string list = arg.substr(colon + 1);
  for (std::size_t pos = 0; pos <= list.size();) {
    std::size_t comma = list.find(',', pos);
    if (comma == std::string::npos) comma = list.size();
    if (comma > pos) channels.insert(list.substr(pos, comma - pos));
    pos = comma + 1;
  }
}

// Reads one input into `events`; the exit status of its state (0, 5 not sealed or records
// dropped, 6 damaged), reported.
int read_input(const std::string& arg, std::vector<Event>& events) {
  std::string path;
  std::set<std::string> channels;
  parse_input(arg, path, channels);
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
  int rc = tr::kExitOk;
  if (fr.malformed()) problem = "damaged: " + fr.describe(), rc = tr::kExitLogDamaged;
  else if (!fr.sealed) problem = "not sealed: its writer did not close it (killed?); it may end early", rc = tr::kExitLogIncomplete;
  else if (fr.seal_dropped > 0) problem = "its writer dropped " + std::to_string(fr.seal_dropped) + " records", rc = tr::kExitLogIncomplete;
  if (rc != tr::kExitOk) {
    std::fprintf(stderr, "logmerge: input '%s' %s (%lld events taken)\n", path.c_str(), problem.c_str(),
                 static_cast<long long>(taken));
  }
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: reentry_logmerge OUT IN[:CH1,CH2,...] [IN[:...] ...]\n");
    return tr::kExitUsage;
  }
  std::vector<Event> events;
  int inputs_rc = tr::kExitOk;
  for (int i = 2; i < argc; ++i) inputs_rc = std::max(inputs_rc, read_input(argv[i], events));
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
    return a.timestamp_us != b.timestamp_us ? a.timestamp_us < b.timestamp_us : a.order < b.order;
  });
  tr::EventLogWriter out;
  std::string err;
  if (!out.open(argv[1], 16u << 20, tr::EventLogWriter::WhenFull::kWait, err)) {
    std::fprintf(stderr, "logmerge: write failed: %s\n", err.c_str());
    return tr::kExitWriteFailed;
  }
  for (const Event& e : events) {
    if (!out.record_at(e.channel.c_str(), e.data.data(), static_cast<int>(e.data.size()), e.timestamp_us)) {
      out.close();
      std::fprintf(stderr, "logmerge: write failed: an event on '%s' could not be recorded in '%s'\n",
                   e.channel.c_str(), argv[1]);
      return tr::kExitWriteFailed;
    }
  }
  if (!out.close()) {
    std::fprintf(stderr, "logmerge: write failed: %s\n", out.error().c_str());
    return tr::kExitWriteFailed;
  }
  std::printf("logmerge: %zu events -> %s (sealed)\n", events.size(), argv[1]);
  return inputs_rc;
}
