// reentry_log2csv: one CSV per channel from an lcm-logger file, columns = message fields
// in .lcm order (generated writers); large fixed arrays go to <CHANNEL>_points.csv (long format).
// Exit: 0, 2 not an LCM log (or a bad argument), 6 damaged log (--lenient: 0), 8 a CSV file not
// written whole (the file and the reason named).
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "log_reader.hpp"
#include "transport/command_line.hpp"

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

/// The CSV files of one conversion; the first write failure is kept (file and reason) and
/// nothing more is written after it.
class CsvOutput {
 public:
  explicit CsvOutput(std::string dir) : dir_(std::move(dir)) {}
  const std::string& error() const { return error_; }
  const std::map<std::string, ChannelOutput>& channels() const { return outputs_; }

  void write(const std::string& ch, MessageHandler& h) {
    if (!error_.empty()) return;
    auto it = outputs_.find(ch);
    if (it == outputs_.end()) {
      if (!safe_file_name(ch)) {
        if (rejected_.insert(ch).second)
          std::cerr << "log2csv: channel name '" << ch << "' is not usable as a file name; skipped\n";
        return;
      }
      it = open_channel(ch, h);
      if (it == outputs_.end()) return;
    }
    ChannelOutput& out = it->second;
    if (out.type_name != h.type_name()) return;  // counted in stats.type_changes
    buf_.clear();
    h.csv_row(buf_);
    *out.rows << buf_;
    ++out.rows_written;
    if (out.points) {
      buf_.clear();
      out.point_rows += h.csv_points_rows(buf_);
      *out.points << buf_;
    }
    check(ch + ".csv", *out.rows);
    if (out.points) check(ch + "_points.csv", *out.points);
  }

  /// Flushes and closes every file; false after any write failure.
  bool finish() {
    for (auto& [ch, out] : outputs_) {
      if (out.rows) check(ch + ".csv", *out.rows, true);
      if (out.points) check(ch + "_points.csv", *out.points, true);
    }
    return error_.empty();
  }

 private:
  std::map<std::string, ChannelOutput>::iterator open_channel(const std::string& ch, MessageHandler& h) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) {
      error_ = dir_ + ": " + ec.message();
      return outputs_.end();
    }
    ChannelOutput out;
    out.type_name = h.type_name();
    out.rows = std::make_unique<std::ofstream>(fs::path(dir_) / (ch + ".csv"));
    buf_.clear();
    h.csv_header(buf_);
    *out.rows << buf_;
    if (!check(ch + ".csv", *out.rows)) return outputs_.end();
    if (h.has_points()) {
      out.points = std::make_unique<std::ofstream>(fs::path(dir_) / (ch + "_points.csv"));
      buf_.clear();
      h.csv_points_header(buf_);
      *out.points << buf_;
      if (!check(ch + "_points.csv", *out.points)) return outputs_.end();
    }
    return outputs_.emplace(ch, std::move(out)).first;
  }

  bool check(const std::string& name, std::ofstream& f, bool close = false) {
    // errno still holds the reason of the write that failed (nothing since has touched it).
    if (f && close) {
      errno = 0;
      f.close();
    }
    if (f || !error_.empty()) return !!f;
    error_ = (fs::path(dir_) / name).string() + ": " + std::strerror(errno != 0 ? errno : EIO);
    return false;
  }

  std::string dir_;
  std::map<std::string, ChannelOutput> outputs_;
  std::set<std::string> rejected_;
  std::string buf_;
  std::string error_;
};

void print_table(const std::map<std::string, ChannelStats>& stats, const CsvOutput& csv, const std::set<std::string>& wanted) {
  int64_t skipped = 0;
  std::printf("%-18s %-28s %8s %10s %8s\n", "channel", "type", "rows", "points", "skipped");
  for (const auto& [ch, st] : stats) {
    const auto it = csv.channels().find(ch);
    const int64_t rows = it == csv.channels().end() ? 0 : it->second.rows_written;
    const int64_t pts = it == csv.channels().end() ? 0 : it->second.point_rows;
    const int64_t bad = st.unknown_type + st.undecodable + st.type_changes;
    skipped += bad;
    std::printf("%-18s %-28s %8lld %10lld %8lld\n", ch.c_str(),
                st.type_name.empty() ? "(unknown)" : st.type_name.c_str(), static_cast<long long>(rows),
                static_cast<long long>(pts), static_cast<long long>(bad));
  }
  if (skipped > 0)
    std::fprintf(stderr, "log2csv: %lld event(s) of unknown type or undecodable were skipped\n",
                 static_cast<long long>(skipped));
  for (const auto& ch : wanted)
    if (stats.count(ch) == 0) std::fprintf(stderr, "log2csv: warning: channel '%s' not in the log\n", ch.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  namespace tx = reentry::transport;
  CLI::App app{"Convert an LCM log of reentry messages into one CSV file per channel", "log2csv"};
  std::string log_path, out_dir;
  std::vector<std::string> channels;
  bool lenient = false;
  app.add_option("log", log_path, "lcm-logger file")->required();
  app.add_option("--channel,-c", channels, "only these channels (repeatable)");
  app.add_option("--out,-o", out_dir, "output folder (default: <log dir>/<log name>_csv)");
  app.add_flag("--lenient", lenient, "exit 0 even when the log framing is damaged");
  const int parsed = tx::parse_command_line(app, argc, argv, "log2csv");
  if (parsed >= 0) return parsed;
  if (out_dir.empty()) out_dir = default_out_dir(log_path);
  const std::set<std::string> wanted(channels.begin(), channels.end());
  auto handlers = make_handlers();
  std::map<std::string, ChannelStats> stats;
  CsvOutput csv(out_dir);
  const LogScan scan = read_log(log_path, [&](const LogEventView& ev) {
    const std::string& ch = *ev.channel;
    if (!wanted.empty() && wanted.count(ch) == 0) return;
    MessageHandler* h = classify_event(handlers, ev, stats[ch]);
    if (h != nullptr) csv.write(ch, *h);
  });
  if (!scan.error.empty()) {
    std::cerr << "log2csv: not an LCM log: " << scan.error << "\n";
    return tx::kExitUsage;
  }
  const bool written = csv.finish();
  print_table(stats, csv, wanted);
  if (!written) {
    std::cerr << "log2csv: write failed: " << csv.error() << "; the CSV files in " << out_dir << " are not whole\n";
    return tx::kExitWriteFailed;
  }
  std::printf("wrote %zu channel(s) to %s\n", csv.channels().size(), out_dir.c_str());
  if (scan.malformed()) {
    std::cerr << "log2csv: damaged log: '" << log_path << "': " << scan.describe() << "\n";
    return lenient ? tx::kExitOk : tx::kExitLogDamaged;
  }
  return tx::kExitOk;
}
