// The command-line front end of the processes and tools: CLI11, with a bad argument mapped to
// the usage status (2) of the exit table (transport/exit_status.hpp), never CLI11's own codes.
#pragma once

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "transport/exit_status.hpp"

namespace reentry::transport {

/// Parses the command line. Returns -1 when the program goes on; otherwise the exit status:
/// 0 after --help, kExitUsage after a bad argument (CLI11's message and "--help" on stderr).
inline int parse_command_line(CLI::App& app, int argc, char** argv, const char* tool) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: bad argument: %s (see --help)\n", tool, e.what());
    return kExitUsage;
  }
  return -1;
}

/// An integer in [0, 2^63 - 1] written as decimal digits (no sign, no exponent, no wrap).
inline CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        if (v.empty() || v.find_first_not_of("0123456789") != std::string::npos)
          return "value '" + v + "' is not an integer >= 0";
        errno = 0;
        const unsigned long long x = std::strtoull(v.c_str(), nullptr, 10);
        if (errno == ERANGE || x > static_cast<unsigned long long>(std::numeric_limits<std::int64_t>::max()))
          return "value '" + v + "' is beyond 2^63 - 1";
        return {};
      },
      "INT>=0");
}

}  // namespace reentry::transport
