// reentry_log2csv: one CSV per channel from an lcm-logger file, columns = message fields
// in .lcm order (generated writers); large fixed arrays go to <CHANNEL>_points.csv (long format).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "log_reader.hpp"

namespace fs = std::filesystem;
using namespace reentry::logtools;

namespace {

struct ChannelOutput {
  std::unique_ptr<std::ofstream> rows;
  std::unique_ptr<std::ofstream> points;
  std::string type_name;
  int64_t rows_written = 0;
  int64_t point_rows = 0;
};

std::string default_out_dir(const std::string& log_path) {
  fs::path p(log_path);
  return (p.parent_path() / (p.stem().string() + "_csv")).string();
}

bool safe_file_name(const std::string& channel) {
  if (channel.empty() || channel == "." || channel == "..") return false;
  for (char c : channel)
    if (c == '/' || c == '\\' || c == '\0') return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Convert an LCM log of reentry messages into one CSV file per channel"};
  std::string log_path, out_dir;
  std::vector<std::string> channels;
  bool lenient = false;
  app.add_option("log", log_path, "lcm-logger file")->required();
  app.add_option("--channel,-c", channels, "only these channels (repeatable)");
  app.add_option("--out,-o", out_dir, "output folder (default: <log dir>/<log name>_csv)");
  app.add_flag("--lenient", lenient, "exit 0 even when the log framing is damaged");
  CLI11_PARSE(app, argc, argv);
  if (out_dir.empty()) out_dir = default_out_dir(log_path);
  const std::set<std::string> wanted(channels.begin(), channels.end());

  auto handlers = make_handlers();
  std::map<std::string, ChannelStats> stats;
  std::map<std::string, ChannelOutput> outputs;
  std::string buf;
  bool io_error = false;
  bool dir_made = false;
  std::set<std::string> rejected;

  const LogScan scan = read_log(log_path, [&](const LogEventView& ev) {
    const std::string& ch = *ev.channel;
    if (!wanted.empty() && wanted.count(ch) == 0) return;
    ChannelStats& st = stats[ch];
    MessageHandler* h = classify_event(handlers, ev, st);
    if (h == nullptr || io_error) return;
    ChannelOutput& out = outputs[ch];
    if (!out.rows) {
      if (!safe_file_name(ch)) {
        if (rejected.insert(ch).second)
          std::cerr << "log2csv: channel name '" << ch << "' is not usable as a file name; skipped\n";
        outputs.erase(ch);
        return;
      }
      if (!dir_made) {
        std::error_code ec;
        fs::create_directories(out_dir, ec);
        if (ec) {
          std::cerr << "log2csv: cannot create '" << out_dir << "': " << ec.message() << "\n";
          io_error = true;
          return;
        }
        dir_made = true;
      }
      out.type_name = h->type_name();
      out.rows = std::make_unique<std::ofstream>(fs::path(out_dir) / (ch + ".csv"));
      buf.clear();
      h->csv_header(buf);
      *out.rows << buf;
      if (h->has_points()) {
        out.points = std::make_unique<std::ofstream>(fs::path(out_dir) / (ch + "_points.csv"));
        buf.clear();
        h->csv_points_header(buf);
        *out.points << buf;
      }
    }
    if (out.type_name != h->type_name()) return;  // counted in stats.type_changes
    buf.clear();
    h->csv_row(buf);
    *out.rows << buf;
    ++out.rows_written;
    if (out.points) {
      buf.clear();
      out.point_rows += h->csv_points_rows(buf);
      *out.points << buf;
    }
  });

  if (!scan.error.empty()) {
    std::cerr << "log2csv: error: " << scan.error << "\n";
    return 2;
  }
  int64_t skipped = 0;
  for (auto& [ch, out] : outputs) {
    if (out.rows) out.rows->flush();
    if (out.points) out.points->flush();
    if ((out.rows && !*out.rows) || (out.points && !*out.points)) io_error = true;
  }
  std::printf("%-18s %-28s %8s %10s %8s\n", "channel", "type", "rows", "points", "skipped");
  for (const auto& [ch, st] : stats) {
    const auto it = outputs.find(ch);
    const int64_t rows = it == outputs.end() ? 0 : it->second.rows_written;
    const int64_t pts = it == outputs.end() ? 0 : it->second.point_rows;
    const int64_t bad = st.unknown_type + st.undecodable + st.type_changes;
    skipped += bad;
    std::printf("%-18s %-28s %8lld %10lld %8lld\n", ch.c_str(),
                st.type_name.empty() ? "(unknown)" : st.type_name.c_str(), static_cast<long long>(rows),
                static_cast<long long>(pts), static_cast<long long>(bad));
  }
  std::printf("wrote %zu channel(s) to %s\n", outputs.size(), out_dir.c_str());
  if (skipped > 0)
    std::fprintf(stderr, "log2csv: %lld event(s) of unknown type or undecodable were skipped\n",
                 static_cast<long long>(skipped));
  for (const auto& ch : wanted)
    if (stats.count(ch) == 0) std::fprintf(stderr, "log2csv: warning: channel '%s' not in the log\n", ch.c_str());
  if (io_error) {
    std::cerr << "log2csv: error writing CSV files in " << out_dir << "\n";
    return 4;
  }
  if (scan.malformed()) {
    std::cerr << "log2csv: error: damaged log '" << log_path << "': " << scan.describe() << "\n";
    return lenient ? 0 : 3;
  }
  return 0;
}
