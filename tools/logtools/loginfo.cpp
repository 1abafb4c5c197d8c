// reentry_loginfo: channels, message counts, rates and time span of an lcm-logger file.
// Counts use the same decoding as reentry_log2csv: "messages" equals that channel's CSV rows.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <map>
#include <string>

#include "log_reader.hpp"
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Summarise an LCM log of reentry messages"};
  std::string log_path;
  bool as_json = false, lenient = false;
  app.add_option("log", log_path, "lcm-logger file")->required();
  app.add_flag("--json", as_json, "machine-readable output");
  app.add_flag("--lenient", lenient, "exit 0 even when the log framing is damaged");
  CLI11_PARSE(app, argc, argv);

  auto handlers = make_handlers();
  std::map<std::string, ChannelStats> stats;
  int64_t first_event_us = 0, last_event_us = 0;
  reentry::transport::RunLogCheck run_check;
  const LogScan scan = read_log(log_path, [&](const LogEventView& ev) {
    if (stats.empty()) first_event_us = ev.timestamp_us;
    last_event_us = ev.timestamp_us;
    classify_event(handlers, ev, stats[*ev.channel]);
    run_check.add(*ev.channel, static_cast<const std::uint8_t*>(ev.data), ev.size);
  });
  const reentry::transport::RunCompleteness run = run_check.result();
  if (!scan.error.empty()) {
    std::cerr << "loginfo: error: " << scan.error << "\n";
    return 2;
  }
  // Is it a complete run log (the replay's rule: every tick from 0, a command for each,
  // END_OF_RUN after the last sample) and whole (sealed, nothing dropped by its writer)?
  const bool run_whole = run.complete() && !scan.malformed() && scan.sealed && scan.seal_dropped == 0;
  const std::string run_problem =
      scan.malformed()         ? "damaged log: " + scan.describe()
      : !run.problem().empty() ? run.problem()
      : !scan.sealed           ? std::string("not sealed: its writer did not close it, or another tool wrote it")
      : scan.seal_dropped > 0  ? "its writer dropped " + std::to_string(scan.seal_dropped) + " records"
                               : std::string();

  if (as_json) {
    nlohmann::ordered_json j;
    j["log"] = log_path;
    j["events"] = scan.events;
    j["bytes"] = scan.file_bytes;
    j["event_span_s"] = static_cast<double>(last_event_us - first_event_us) * 1e-6;
    j["malformed"] = scan.malformed();
    if (scan.malformed()) j["problem"] = scan.describe();
    nlohmann::ordered_json r;
    r["complete"] = run_whole;
    r["problem"] = run_problem;
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
  } else {
    std::printf("log      %s\n", log_path.c_str());
    std::printf("events   %lld in %lld bytes, logger time span %.3f s\n", static_cast<long long>(scan.events),
                static_cast<long long>(scan.file_bytes),
                static_cast<double>(last_event_us - first_event_us) * 1e-6);
    if (run.nav_events > 0) {
      std::printf("run      %s\n", run_whole ? ("complete and sealed: ticks 0.." + std::to_string(run.last_tick) +
                                                ", END_OF_RUN " + reentry::transport::end_event_name(run.end_event))
                                                   .c_str()
                                          : ("incomplete: " + run_problem).c_str());
    }
    std::printf("\n%-18s %-28s %9s %9s %10s %10s %6s\n", "channel", "type", "messages", "skipped", "rate_Hz",
                "span_s", "clock");
    for (const auto& [ch, st] : stats) {
      const Timing t = timing_of(st);
      std::printf("%-18s %-28s %9lld %9lld %10.3f %10.3f %6s\n", ch.c_str(),
                  st.type_name.empty() ? "(unknown)" : st.type_name.c_str(),
                  static_cast<long long>(st.decoded - st.type_changes),
                  static_cast<long long>(st.unknown_type + st.undecodable + st.type_changes), t.rate_hz,
                  t.span_s, t.source);
    }
  }
  if (scan.malformed()) {
    std::cerr << "loginfo: error: damaged log '" << log_path << "': " << scan.describe() << "\n";
    return lenient ? 0 : 3;
  }
  return 0;
}
