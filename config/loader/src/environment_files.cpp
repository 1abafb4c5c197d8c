// Readers of the environment data files (see environment_files.hpp): one set of rules for the
// loader and the truth simulator.
#include "reentry/config/environment_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <sstream>

namespace reentry::config {
namespace {

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

std::string where(const std::string& path, int line_no) { return path + ":" + std::to_string(line_no) + ": "; }

// The 'n m C S' lines into c/s; marks what was seen. "" or the error.
std::string read_gravity_rows(std::ifstream& in, const std::string& path, int degree, GravityCoefficients& g,
                              std::vector<std::vector<bool>>& seen) {
  std::string line;
  int line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (blank(line) || line[0] == '%' || line[0] == '#') continue;
    std::istringstream ls(line);
    if (!header) {
      if (!(ls >> g.mu_m3ps2 >> g.radius_m) || !(g.mu_m3ps2 > 0.0) || !(g.radius_m > 0.0) ||
          !std::isfinite(g.mu_m3ps2) || !std::isfinite(g.radius_m)) {
        return where(path, line_no) + "expected 'mu R' (positive), got '" + line + "'";
      }
      header = true;
      continue;
    }
    int n = 0, m = 0;
    double cv = 0.0, sv = 0.0;
    if (!(ls >> n >> m >> cv >> sv) || n < 0 || m < 0 || m > n || !std::isfinite(cv) || !std::isfinite(sv)) {
      return where(path, line_no) + "expected 'n m C S' with 0 <= m <= n, got '" + line + "'";
    }
    if (n > degree) continue;
    g.c[n][m] = cv;
    g.s[n][m] = sv;
    seen[n][m] = true;
  }
  return header ? std::string() : path + ": empty file (no 'mu R' line)";
}

}  // namespace

std::string read_gravity_coefficients(const std::string& path, int degree, GravityCoefficients& out) {
  if (degree < 2) return path + ": degree/order " + std::to_string(degree) + " below 2";
  std::ifstream in(path);
  if (!in) return path + ": cannot open";
  GravityCoefficients g;
  g.c.resize(static_cast<std::size_t>(degree) + 1);
  g.s.resize(static_cast<std::size_t>(degree) + 1);
  std::vector<std::vector<bool>> seen(static_cast<std::size_t>(degree) + 1);
  for (int n = 0; n <= degree; ++n) {
    g.c[n].assign(static_cast<std::size_t>(n) + 1, 0.0);
    g.s[n].assign(static_cast<std::size_t>(n) + 1, 0.0);
    seen[n].assign(static_cast<std::size_t>(n) + 1, false);
  }
  const std::string err = read_gravity_rows(in, path, degree, g, seen);
  if (!err.empty()) return err;
  for (int n = 2; n <= degree; ++n) {
    for (int m = 0; m <= n; ++m) {
      if (!seen[n][m]) return path + ": missing coefficient n=" + std::to_string(n) + " m=" + std::to_string(m);
    }
  }
  out = std::move(g);
  return {};
}

namespace {

struct WindColumns {
  int h = -1, e = -1, n = -1, w = -1, count = 0;
};

// Header: the columns by name. "" or the error.
std::string wind_header(const std::vector<std::string>& tokens, const std::string& at, WindColumns& col) {
  for (int i = 0; i < static_cast<int>(tokens.size()); ++i) {
    if (tokens[i] == "Hgtkm") col.h = i;
    if (tokens[i] == "EWmean") col.e = i;
    if (tokens[i] == "NSmean") col.n = i;
    if (tokens[i] == "Wmean" || tokens[i] == "UDmean") col.w = i;  // +up, only if present
  }
  if (col.h < 0 || col.e < 0 || col.n < 0) return at + "header must name Hgtkm, EWmean and NSmean";
  col.count = static_cast<int>(tokens.size());
  return {};
}

struct WindRow {
  double h = 0.0, n = 0.0, e = 0.0, u = 0.0;
};

std::string wind_row(const std::vector<std::string>& tokens, const WindColumns& col, const std::string& at,
                     const std::string& line, WindRow& r) {
  if (static_cast<int>(tokens.size()) < col.count) {
    return at + "expected " + std::to_string(col.count) + " columns, got " + std::to_string(tokens.size());
  }
  auto number = [&](int c, double& out) {
    char* end = nullptr;
    out = std::strtod(tokens[c].c_str(), &end);
    return end && *end == '\0' && std::isfinite(out);
  };
  if (!number(col.h, r.h) || !number(col.n, r.n) || !number(col.e, r.e) || (col.w >= 0 && !number(col.w, r.u))) {
    return at + "non-numeric or non-finite value in '" + line + "'";
  }
  for (const double v : {r.n, r.e, r.u}) {
    if (std::fabs(v) > kWindComponentMax_mps) {
      std::ostringstream os;
      os << at << "wind component " << v << " m/s beyond +-" << kWindComponentMax_mps << " m/s";
      return os.str();
    }
  }
  if (!(r.h >= -1.0 && r.h <= 1000.0)) {
    std::ostringstream os;
    os << at << "altitude Hgtkm " << r.h << " km outside [-1, 1000]";
    return os.str();
  }
  r.h *= 1000.0;
  return {};
}

}  // namespace

std::string read_wind_profile(const std::string& path, WindProfile& out) {
  std::ifstream in(path);
  if (!in) return path + ": cannot open";
  std::string line;
  int line_no = 0;
  WindColumns col;
  std::vector<WindRow> rows;
  while (std::getline(in, line)) {
    ++line_no;
    if (blank(line)) continue;
    std::istringstream ls(line);
    std::vector<std::string> tokens;
    std::string tok;
    while (ls >> tok) tokens.push_back(tok);
    const std::string at = where(path, line_no);
    if (col.h < 0) {
      const std::string err = wind_header(tokens, at, col);
      if (!err.empty()) return err;
      continue;
    }
    WindRow r;
    const std::string err = wind_row(tokens, col, at, line, r);
    if (!err.empty()) return err;
    rows.push_back(r);
  }
  if (rows.size() < 3) return path + ": fewer than 3 data rows";
  std::sort(rows.begin(), rows.end(), [](const WindRow& a, const WindRow& b) { return a.h < b.h; });
  WindProfile w;
  for (const WindRow& r : rows) {
    if (!w.h_m.empty() && !(r.h > w.h_m.back())) return path + ": duplicate altitude " + std::to_string(r.h) + " m";
    w.h_m.push_back(r.h);
    w.north_mps.push_back(r.n);
    w.east_mps.push_back(r.e);
    w.up_mps.push_back(r.u);
  }
  out = std::move(w);
  return {};
}

std::string read_atmosphere_table(const std::string& path, AtmosphereTable& out) {
  std::ifstream in(path);
  if (!in) return path + ": cannot open";
  std::string line;
  int line_no = 0;
  AtmosphereTable a;
  while (std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '%') continue;
    std::istringstream ls(line);
    double h = 0.0, d = 0.0, pr = 0.0, t = 0.0;
    const std::string at = where(path, line_no);
    if (!(ls >> h >> d >> pr >> t)) return at + "expected 'altitude density pressure temperature', got '" + line + "'";
    if (!std::isfinite(h) || !(d > 0.0) || !(pr > 0.0) || !(t > 0.0) || !std::isfinite(d) || !std::isfinite(pr) ||
        !std::isfinite(t)) {
      return at + "density, pressure and temperature must be finite and positive, got '" + line + "'";
    }
    if (!a.h_m.empty() && !(h > a.h_m.back())) return at + "altitude " + std::to_string(h) + " m not strictly increasing";
    a.h_m.push_back(h);
    a.density_kgpm3.push_back(d);
    a.pressure_Pa.push_back(pr);
    a.temperature_K.push_back(t);
  }
  if (a.h_m.size() < 3) return path + ": fewer than 3 data rows";
  out = std::move(a);
  return {};
}

}  // namespace reentry::config
