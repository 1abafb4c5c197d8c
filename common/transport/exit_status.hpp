// Exit statuses of every reentry process and tool (the table in tools/README.md) and the
// stop-signal flag of the processes. Messages follow one form:
// "<tool>: <what failed>: <file/field/value>".
#pragma once

#include <csignal>
#include <cstdio>

namespace reentry::transport {

inline constexpr int kExitOk = 0;              // done; the mission succeeded; the replay is identical
inline constexpr int kExitMissionFailure = 1;  // the flight ended outside a tolerance or beyond a limit
inline constexpr int kExitUsage = 2;           // bad argument, or an input refused (mission, data, campaign)
inline constexpr int kExitLinkLoss = 3;        // a process died or lost the link
inline constexpr int kExitReplayDiffers = 4;   // a replayed command differs from the logged one
inline constexpr int kExitLogIncomplete = 5;   // a log misses ticks, commands, END_OF_RUN or its seal
inline constexpr int kExitLogDamaged = 6;      // a log is truncated, has garbage, or its seal does not match
inline constexpr int kExitTransport = 7;       // the network socket failed
inline constexpr int kExitWriteFailed = 8;     // an output could not be written whole (disk full, read-only)
inline constexpr int kExitNoNetns = 9;         // no private network namespace (tools/sil)
inline constexpr int kExitBusy = 10;           // the output folder is in use by another run
inline constexpr int kExitRunError = 11;       // a run could not be flown (set-up or numerical failure)
inline constexpr int kExitNotReplayable = 12;  // a whole log that cannot be replayed here (other mission, realtime)
inline constexpr int kExitSignalBase = 128;    // + signal number: interrupted, children ended, logs sealed

inline const char* exit_name(int code) {
  switch (code) {
    case kExitOk: return "ok";
    case kExitMissionFailure: return "mission_failure";
    case kExitUsage: return "usage";
    case kExitLinkLoss: return "link_loss";
    case kExitReplayDiffers: return "replay_differs";
    case kExitLogIncomplete: return "log_incomplete";
    case kExitLogDamaged: return "log_damaged";
    case kExitTransport: return "transport_error";
    case kExitWriteFailed: return "write_failed";
    case kExitNoNetns: return "no_netns";
    case kExitBusy: return "busy";
    case kExitRunError: return "run_error";
    case kExitNotReplayable: return "not_replayable";
    default: return code > kExitSignalBase && code < kExitSignalBase + 65 ? "interrupted" : "unknown";
  }
}

/// The signal that asked the process to stop (0: none). Set by the handler of
/// install_stop_handlers; the process's loops poll it and end the run cleanly.
inline volatile std::sig_atomic_t g_stop_signal = 0;

inline void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = [](int sig) { g_stop_signal = sig; };
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocking wait returns and sees the flag
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
}

}  // namespace reentry::transport
