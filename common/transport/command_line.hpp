// The command-line front end of the processes and tools: CLI11, with a bad argument mapped to
// the usage status (2) of the exit table (transport/exit_status.hpp), never CLI11's own codes.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>

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

}  // namespace reentry::transport
