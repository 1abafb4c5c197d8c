// Absolute-deadline pacing on CLOCK_MONOTONIC, shared by the guidance process and the
// simulator process (realtime mode): clock_nanosleep with TIMER_ABSTIME, retried on EINTR;
// and the thread CPU-time clock of the guidance cycle's compute-time figures.
#pragma once

#include <time.h>

#include <cerrno>
#include <cstdint>

namespace reentry::transport {

inline std::int64_t mono_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

/// CPU time consumed by the calling thread [ns] (the executive's cycle-time clock).
inline std::int64_t thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

/// Sleeps until the absolute monotonic time t_ns (no drift from relative sleeps).
inline void sleep_until_ns(std::int64_t t_ns) {
  timespec ts{};
  ts.tv_sec = t_ns / 1000000000LL;
  ts.tv_nsec = t_ns % 1000000000LL;
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace reentry::transport
