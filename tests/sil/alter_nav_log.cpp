// Copies an LCM log, changing one value of the NAV_STATE message of a given tick
// (position_I_m[0] += delta), to check that replay reports the right tick.
#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#include <reentry/nav_state_t.hpp>

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: alter_nav_log IN OUT TICK DELTA_M\n");
    return 2;
  }
  lcm::LogFile in(argv[1], "r");
  lcm::LogFile out(argv[2], "w");
  if (!in.good() || !out.good()) return 2;
  const long long tick = std::atoll(argv[3]);
  const double delta = std::atof(argv[4]);
  int altered = 0;
  std::vector<unsigned char> buf(70000);
  for (const lcm::LogEvent* ev = in.readNextEvent(); ev != nullptr; ev = in.readNextEvent()) {
    lcm::LogEvent copy = *ev;
    reentry::nav_state_t nav{};
    if (ev->channel == "NAV_STATE" && nav.decode(ev->data, 0, ev->datalen) == ev->datalen && nav.tick == tick) {
      nav.position_I_m[0] += delta;
      const int n = nav.encode(buf.data(), 0, static_cast<int>(buf.size()));
      copy.data = buf.data();
      copy.datalen = n;
      ++altered;
    }
    out.writeEvent(&copy);
  }
  std::printf("altered %d message(s)\n", altered);
  return altered > 0 ? 0 : 1;
}
