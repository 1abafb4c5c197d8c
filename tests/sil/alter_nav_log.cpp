// Copies a run log, changing one value of the NAV_STATE message of a given tick
// (position_I_m[0] += delta), and seals the copy: the replay must then report that tick as
// a difference (a semantic change), where an unsealed edit would be refused as damage.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#include <reentry/nav_state_t.hpp>

#include "transport/event_log.hpp"

int main(int argc, char** argv) {
  namespace tr = reentry::transport;
  if (argc != 5) {
    std::fprintf(stderr, "usage: alter_nav_log IN OUT TICK DELTA_M\n");
    return 2;
  }
  tr::EventLogWriter out;
  std::string err;
  if (!out.open(argv[2], 16u << 20, tr::EventLogWriter::WhenFull::kWait, err)) {
    std::fprintf(stderr, "alter_nav_log: %s\n", err.c_str());
    return 2;
  }
  const long long tick = std::atoll(argv[3]);
  const double delta = std::atof(argv[4]);
  int altered = 0;
  std::vector<unsigned char> buf(70000);
  const tr::LogFraming fr = tr::read_event_log(argv[1], [&](const tr::LogEventView& ev) {
    const std::string ch(ev.channel, static_cast<std::size_t>(ev.channel_len));
    if (ch == tr::kSealChannel) return true;  // the copy gets its own seal
    reentry::nav_state_t nav{};
    if (ch == "NAV_STATE" && nav.decode(ev.data, 0, ev.size) == ev.size && nav.tick == tick) {
      nav.position_I_m[0] += delta;
      const int n = nav.encode(buf.data(), 0, static_cast<int>(buf.size()));
      out.record_at(ch.c_str(), buf.data(), n, ev.timestamp_us);
      ++altered;
    } else {
      out.record_at(ch.c_str(), ev.data, ev.size, ev.timestamp_us);
    }
    return true;
  });
  out.close();
  if (fr.malformed()) return 2;
  std::printf("altered %d message(s)\n", altered);
  return altered > 0 ? 0 : 1;
}
