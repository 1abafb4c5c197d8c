// reentry_loginfo: channels, message counts, rates and time span of an lcm-logger file.
// Counts use the same decoding as reentry_log2csv: "messages" equals that channel's CSV rows.
// Exit: 0, 2 not an LCM log (or a bad argument), 6 damaged log (--lenient: 0), 8 the output could
// not be written.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <string>

#include "log_reader.hpp"
#include "transport/command_line.hpp"
#include "transport/run_log.hpp"

using namespace reentry::logtools;

namespace {

struct Timing {
  const char* source;  // "utime" (inside the messages) or "event" (logger receive time)
  double span_s;
  double rate_hz;
};

Timing timing_of(const ChannelStats& st) {
  Timing t{"event", 0.0, 0.0};
  int64_t first = st.first_event_us, last = st.last_event_us;
  int64_t n = st.events;
  if (st.have_utime && st.decoded > 0) {
    t.source = "utime";
    first = st.first_utime;
    last = st.last_utime;
    n = st.decoded;
  }
  t.span_s = static_cast<double>(last - first) * 1e-6;
  if (n > 1 && t.span_s > 0.0) t.rate_hz = static_cast<double>(n - 1) / t.span_s;
  return t;
}

struct RunVerdict {
  bool whole = false;
  std::string problem;
};

// Is it a complete run log (the replay's rule: every tick from 0, a command for each,
// END_OF_RUN after the last sample) and whole (sealed, nothing dropped by its writer)?
RunVerdict run_verdict(const LogScan& scan, const reentry::transport::RunCompleteness& run) {
  RunVerdict v;
  v.whole = run.complete() && !scan.malformed() && scan.sealed && scan.seal_dropped == 0;
  v.problem = scan.malformed()         ? "damaged log: " + scan.describe()
              : !run.problem().empty() ? run.problem()
              : !scan.sealed           ? std::string("not sealed: its writer did not close it, or another tool wrote it")
              : scan.seal_dropped > 0  ? "its writer dropped " + std::to_string(scan.seal_dropped) + " records"
                                       : std::string();
  return v;
}

void print_json(const std::string& log_path, const LogScan& scan, double event_span_s,
                const reentry::transport::RunCompleteness& run, const RunVerdict& v,
                const std::map<std::string, ChannelStats>& stats) {
  nlohmann::ordered_json j;
  j["log"] = log_path;
  j["events"] = scan.events;
  j["bytes"] = scan.file_bytes;
  j["event_span_s"] = event_span_s;
  j["malformed"] = scan.malformed();
  if (scan.malformed()) j["problem"] = scan.describe();
  nlohmann::ordered_json r;
  r["complete"] = v.whole;
  r["problem"] = v.problem;
  r["sealed"] = scan.sealed;
  r["nav_events"] = run.nav_events;
  r["nav_ticks"] = run.nav_ticks;
  r["first_tick"] = run.first_tick;
  r["last_tick"] = run.last_tick;
  r["missing_ticks"] = run.missing_ticks;
  r["unanswered_ticks"] = run.unanswered_ticks;
  r["end_of_run"] = run.end_of_run;
  r["end_event"] = run.end_of_run ? reentry::transport::end_event_name(run.end_event) : "";
  j["run"] = r;
  for (const auto& [ch, st] : stats) {
    const Timing t = timing_of(st);
    nlohmann::ordered_json c;
    c["type"] = st.type_name;
    c["events"] = st.events;
    c["messages"] = st.decoded - st.type_changes;
    c["unknown_type"] = st.unknown_type;
    c["undecodable"] = st.undecodable;
    c["type_changes"] = st.type_changes;
    c["time_source"] = t.source;
    c["span_s"] = t.span_s;
    c["rate_hz"] = t.rate_hz;
    c["bytes"] = st.bytes;
    j["channels"][ch] = c;
  }
  std::cout << j.dump(2) << "\n";
}

void print_text(const std::string& log_path, const LogScan& scan, double event_span_s,
                const reentry::transport::RunCompleteness& run, const RunVerdict& v,
                const std::map<std::string, ChannelStats>& stats) {
  std::printf("log      %s\n", log_path.c_str());
  std::printf("events   %lld in %lld bytes, logger time span %.3f s\n", static_cast<long long>(scan.events),
              static_cast<long long>(scan.file_bytes), event_span_s);
  if (run.nav_events > 0) {
    std::printf("run      %s\n", v.whole ? ("complete and sealed: ticks 0.." + std::to_string(run.last_tick) +
                                             ", END_OF_RUN " + reentry::transport::end_event_name(run.end_event))
                                                .c_str()
                                       : ("incomplete: " + v.problem).c_str());
  }
  std::printf("\n%-18s %-28s %9s %9s %10s %10s %6s\n", "channel", "type", "messages", "skipped", "rate_Hz", "span_s",
              "clock");
  for (const auto& [ch, st] : stats) {
    const Timing t = timing_of(st);
    std::printf("%-18s %-28s %9lld %9lld %10.3f %10.3f %6s\n", ch.c_str(),
                st.type_name.empty() ? "(unknown)" : st.type_name.c_str(),
                static_cast<long long>(st.decoded - st.type_changes),
                static_cast<long long>(st.unknown_type + st.undecodable + st.type_changes), t.rate_hz, t.span_s,
                t.source);
  }
}

}  // namespace

int main(int argc, char** argv) {
  namespace tx = reentry::transport;
  CLI::App app{"Summarise an LCM log of reentry messages", "loginfo"};
  std::string log_path;
  bool as_json = false, lenient = false;
  app.add_option("log", log_path, "lcm-logger file")->required();
  app.add_flag("--json", as_json, "machine-readable output");
  app.add_flag("--lenient", lenient, "exit 0 even when the log framing is damaged");
  const int parsed = tx::parse_command_line(app, argc, argv, "loginfo");
  if (parsed >= 0) return parsed;
  auto handlers = make_handlers();
  std::map<std::string, ChannelStats> stats;
  int64_t first_event_us = 0, last_event_us = 0;
  tx::RunLogCheck run_check;
  const LogScan scan = read_log(log_path, [&](const LogEventView& ev) {
    if (stats.empty()) first_event_us = ev.timestamp_us;
    last_event_us = ev.timestamp_us;
    classify_event(handlers, ev, stats[*ev.channel]);
    run_check.add(*ev.channel, static_cast<const std::uint8_t*>(ev.data), ev.size);
  });
  const tx::RunCompleteness run = run_check.result();
  if (!scan.error.empty()) {
    std::cerr << "loginfo: not an LCM log: " << scan.error << "\n";
    return tx::kExitUsage;
  }
  const RunVerdict v = run_verdict(scan, run);
  const double span_s = static_cast<double>(last_event_us - first_event_us) * 1e-6;
  if (as_json) print_json(log_path, scan, span_s, run, v, stats);
  else print_text(log_path, scan, span_s, run, v, stats);
  std::cout.flush();
  // errno still holds the reason of the write that failed.
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
    std::fprintf(stderr, "loginfo: write failed: standard output: %s\n", std::strerror(errno != 0 ? errno : EIO));
    return tx::kExitWriteFailed;
  }
  if (scan.malformed()) {
    std::cerr << "loginfo: damaged log: '" << log_path << "': " << scan.describe() << "\n";
    return lenient ? tx::kExitOk : tx::kExitLogDamaged;
  }
  return tx::kExitOk;
}
