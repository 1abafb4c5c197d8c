#include "environment/wind.hpp"

#include "environment/interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <sstream>

namespace reentry::truth {
namespace {
void set_error(std::string* error, const std::string& msg) {
  if (error) *error = msg;
}
}  // namespace

Wind Wind::disabled() { return Wind(); }

std::optional<Wind> Wind::create(const std::string& earthgram_file, std::string* error) {
  std::ifstream in(earthgram_file);
  if (!in) {
    set_error(error, earthgram_file + ": cannot open");
    return std::nullopt;
  }
  std::string line;
  int line_no = 0;
  int col_h = -1, col_e = -1, col_n = -1, col_w = -1, n_cols = 0;
  struct Row { double h, n, e, u; };
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream ls(line);
    std::vector<std::string> tokens;
    std::string tok;
    while (ls >> tok) tokens.push_back(tok);
    if (col_h < 0) {  // header line
      for (int i = 0; i < static_cast<int>(tokens.size()); ++i) {
        if (tokens[i] == "Hgtkm") col_h = i;
        if (tokens[i] == "EWmean") col_e = i;
        if (tokens[i] == "NSmean") col_n = i;
        if (tokens[i] == "Wmean" || tokens[i] == "UDmean") col_w = i;  // +up, only if present
      }
      if (col_h < 0 || col_e < 0 || col_n < 0) {
        set_error(error, earthgram_file + ":" + std::to_string(line_no) + ": header must name Hgtkm, EWmean and NSmean");
        return std::nullopt;
      }
      n_cols = static_cast<int>(tokens.size());
      continue;
    }
    const std::string where = earthgram_file + ":" + std::to_string(line_no) + ": ";
    if (static_cast<int>(tokens.size()) < n_cols) {
      set_error(error, where + "expected " + std::to_string(n_cols) + " columns, got " + std::to_string(tokens.size()));
      return std::nullopt;
    }
    auto number = [&](int col, double& out) {
      char* end = nullptr;
      out = std::strtod(tokens[col].c_str(), &end);
      return end && *end == '\0' && std::isfinite(out);
    };
    Row r{0.0, 0.0, 0.0, 0.0};
    if (!number(col_h, r.h) || !number(col_n, r.n) || !number(col_e, r.e) || (col_w >= 0 && !number(col_w, r.u))) {
      set_error(error, where + "non-numeric or non-finite value in '" + line + "'");
      return std::nullopt;
    }
    r.h *= 1000.0;
    rows.push_back(r);
  }
  if (rows.size() < 3) {
    set_error(error, earthgram_file + ": fewer than 3 data rows");
    return std::nullopt;
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.h < b.h; });
  Wind w;
  w.enabled_ = true;
  for (const Row& r : rows) {
    if (!w.h_m_.empty() && !(r.h > w.h_m_.back())) {
      set_error(error, earthgram_file + ": duplicate altitude " + std::to_string(r.h) + " m");
      return std::nullopt;
    }
    w.h_m_.push_back(r.h);
    w.north_.push_back(r.n);
    w.east_.push_back(r.e);
    w.up_.push_back(r.u);
  }
  w.north_m2_ = detail::natural_spline_moments(w.h_m_, w.north_);
  w.east_m2_ = detail::natural_spline_moments(w.h_m_, w.east_);
  w.up_m2_ = detail::natural_spline_moments(w.h_m_, w.up_);
  return w;
}

}  // namespace reentry::truth
