// reentry_config_check: load one or more missions (names or paths), print one summary line each.
// Exit status 1 with the loader's message on the first failure.
#include <cstdio>

#include "reentry/config/mission.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <mission name or file> [...]\n", argv[0]);
    return 2;
  }
  for (int i = 1; i < argc; ++i) {
    const reentry::config::LoadResult result = reentry::config::load_mission(argv[i]);
    if (!result.ok) {
      std::fprintf(stderr, "%s\n", result.error.c_str());
      return 1;
    }
    std::printf("%s\n", reentry::config::summary_line(result.mission).c_str());
  }
  return 0;
}
