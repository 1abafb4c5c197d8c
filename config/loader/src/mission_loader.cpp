// Mission loader: TOML -> reentry::config::Mission, with full validation.
//
// Every error names the file, the dotted key and the offending value. Keys carry their unit
// (`mass_kg`, `heading_deg`); a key with a different suffix is an unknown key. No exception
// leaves load_mission: toml++ parse errors and anything else are converted into messages.
#include <toml++/toml.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <exception>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "reentry/config/mission.hpp"

namespace reentry::config {
namespace {

constexpr double kDegToRad = physics::kRadPerDeg;
constexpr double kMu_m3ps2 = physics::kMuEarth_m3ps2;
constexpr double kEarthRadius_m = physics::kEarthEquatorialRadius_m;  // R_cb in (7.8)

std::string fmt_double(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// Sticky first error shared by all readers of one load.
struct ErrorSink {
  std::string message;
  bool failed() const { return !message.empty(); }
  void set(const std::string& m) {
    if (message.empty()) message = m;
  }
};

std::string describe(const toml::node& n) {
  if (auto v = n.value<double>()) return fmt_double(*v);
  if (auto s = n.value<std::string>()) return "\"" + *s + "\"";
  if (n.is_boolean()) return n.as_boolean()->get() ? "true" : "false";
  if (n.is_table()) return "<table>";
  if (n.is_array()) return "<array>";
  return "<value>";
}

/// Reads one TOML table, remembers which keys were consumed and reports the rest as unknown.
class Reader {
 public:
  Reader(const toml::table* table, std::string file, std::string prefix, ErrorSink* sink)
      : table_(table), file_(std::move(file)), prefix_(std::move(prefix)), sink_(sink) {}

  std::string key_path(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }

  void fail(const std::string& key, const std::string& what) {
    sink_->set(file_ + ": key '" + key_path(key) + "': " + what);
  }

  bool has(const std::string& key) const { return table_ && table_->contains(key); }

  const toml::node* get(const std::string& key, bool required) {
    used_.insert(key);
    const toml::node* n = table_ ? table_->get(key) : nullptr;
    if (!n && required) fail(key, "missing required key");
    return n;
  }

  /// Finite number within [lo, hi]; `lo_open` makes the lower bound exclusive.
  double number(const std::string& key, double lo, double hi, bool lo_open = false, bool required = true,
                double fallback = 0.0) {
    const toml::node* n = get(key, required);
    if (!n) return fallback;
    return check_number(key, *n, lo, hi, lo_open);
  }

  double check_number(const std::string& key, const toml::node& n, double lo, double hi, bool lo_open) {
    if (!(n.is_integer() || n.is_floating_point())) {
      fail(key, "expected a number, got " + describe(n));
      return 0.0;
    }
    const double v = *n.value<double>();
    if (!std::isfinite(v)) {
      fail(key, "value " + fmt_double(v) + " is not finite");
      return 0.0;
    }
    if ((lo_open ? v <= lo : v < lo) || v > hi) {
      fail(key, "value " + fmt_double(v) + " out of range " + (lo_open ? "(" : "[") + fmt_double(lo) + ", " +
                    fmt_double(hi) + "]");
      return 0.0;
    }
    return v;
  }

  int integer(const std::string& key, int lo, int hi, bool required = true, int fallback = 0) {
    const toml::node* n = get(key, required);
    if (!n) return fallback;
    if (!n->is_integer()) {
      fail(key, "expected an integer, got " + describe(*n));
      return fallback;
    }
    const int64_t v = n->as_integer()->get();
    if (v < lo || v > hi) {
      fail(key, "value " + std::to_string(v) + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      return fallback;
    }
    return static_cast<int>(v);
  }

  bool boolean(const std::string& key, bool required = true, bool fallback = false) {
    const toml::node* n = get(key, required);
    if (!n) return fallback;
    if (!n->is_boolean()) {
      fail(key, "expected true or false, got " + describe(*n));
      return fallback;
    }
    return n->as_boolean()->get();
  }

  std::string text(const std::string& key, bool required = true) {
    const toml::node* n = get(key, required);
    if (!n) return {};
    if (!n->is_string()) {
      fail(key, "expected a string, got " + describe(*n));
      return {};
    }
    return n->as_string()->get();
  }

  std::string choice(const std::string& key, const std::vector<std::string>& allowed, bool required = true,
                     const std::string& fallback = {}) {
    if (!required && !has(key)) {
      used_.insert(key);
      return fallback;
    }
    std::string v = text(key, required);
    if (sink_->failed()) return fallback;
    for (const auto& a : allowed)
      if (v == a) return v;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
    fail(key, "value \"" + v + "\" is not one of " + list);
    return fallback;
  }

  /// Array of finite numbers, non-empty; optionally strictly increasing.
  std::vector<double> numbers(const std::string& key, bool increasing, double lo, double hi) {
    const toml::node* n = get(key, true);
    return n ? check_numbers(key, *n, increasing, lo, hi) : std::vector<double>{};
  }

  std::vector<double> check_numbers(const std::string& key, const toml::node& n, bool increasing, double lo,
                                    double hi) {
    std::vector<double> out;
    const toml::array* arr = n.as_array();
    if (!arr) {
      fail(key, "expected an array of numbers, got " + describe(n));
      return out;
    }
    if (arr->empty()) {
      fail(key, "array is empty");
      return out;
    }
    for (size_t i = 0; i < arr->size(); ++i) {
      const std::string k = key + "[" + std::to_string(i) + "]";
      const double v = check_number(k, *arr->get(i), lo, hi, false);
      if (sink_->failed()) return {};
      if (increasing && !out.empty() && !(v > out.back())) {
        fail(k, "value " + fmt_double(v) + " is not strictly increasing (previous " + fmt_double(out.back()) + ")");
        return {};
      }
      out.push_back(v);
    }
    return out;
  }

  /// rows x cols matrix stored as array of arrays; returns row-major values.
  std::vector<double> matrix(const std::string& key, const toml::node& n, size_t rows, size_t cols, double lo,
                             double hi) {
    std::vector<double> out;
    const toml::array* arr = n.as_array();
    if (!arr) {
      fail(key, "expected an array of rows, got " + describe(n));
      return out;
    }
    if (arr->size() != rows) {
      fail(key, "has " + std::to_string(arr->size()) + " rows, expected " + std::to_string(rows) +
                    " (one per alpha_deg entry)");
      return out;
    }
    for (size_t i = 0; i < rows; ++i) {
      const std::string k = key + "[" + std::to_string(i) + "]";
      std::vector<double> row = check_numbers(k, *arr->get(i), false, lo, hi);
      if (sink_->failed()) return {};
      if (row.size() != cols) {
        fail(k, "row has " + std::to_string(row.size()) + " values, expected " + std::to_string(cols) +
                    " (one per mach entry)");
        return {};
      }
      out.insert(out.end(), row.begin(), row.end());
    }
    return out;
  }

  Reader sub(const std::string& key, bool required = true) {
    const toml::node* n = get(key, required);
    if (n && !n->is_table()) {
      fail(key, "expected a table, got " + describe(*n));
      n = nullptr;
    }
    return Reader(n ? n->as_table() : nullptr, file_, key_path(key), sink_);
  }

  bool present() const { return table_ != nullptr; }

  /// Every number of this table not consumed so far, and every entry of the sub-tables named
  /// in `nested` (as "sub.key"): values that another layer validates. Anything else there
  /// that is not a finite number is an error here.
  std::vector<TuningValue> pass_through_numbers(const std::vector<std::string>& nested) {
    std::vector<TuningValue> out;
    if (!table_ || sink_->failed()) return out;
    auto take = [&](const std::string& key, const toml::node& n) {
      if (!(n.is_integer() || n.is_floating_point())) {
        fail(key, "expected a number, got " + describe(n));
        return;
      }
      const double v = *n.value<double>();
      if (!std::isfinite(v)) {
        fail(key, "value " + fmt_double(v) + " is not finite");
        return;
      }
      out.push_back(TuningValue{key, v, n.is_integer()});
    };
    for (const auto& [k, v] : *table_) {
      const std::string key(k.str());
      if (used_.count(key)) continue;
      bool sub = false;
      for (const auto& name : nested) sub = sub || key == name;
      if (sub) {
        used_.insert(key);
        if (!v.is_table()) {
          fail(key, "expected a table, got " + describe(v));
          return out;
        }
        for (const auto& [k2, v2] : *v.as_table()) take(key + "." + std::string(k2.str()), v2);
      } else if (v.is_integer() || v.is_floating_point()) {
        used_.insert(key);
        take(key, v);
      }
    }
    return out;
  }

  /// Report the first key that was never consumed (typo or wrong unit suffix).
  void finish() {
    if (!table_ || sink_->failed()) return;
    for (const auto& [k, v] : *table_) {
      const std::string key(k.str());
      if (!used_.count(key)) {
        fail(key, "unknown key (value " + describe(v) + "); check spelling and unit suffix");
        return;
      }
    }
  }

  const std::string& file() const { return file_; }
  ErrorSink* sink() const { return sink_; }

 private:
  const toml::table* table_;
  std::string file_;
  std::string prefix_;
  ErrorSink* sink_;
  std::set<std::string> used_;
};

bool parse_file(const std::string& path, toml::table& out, ErrorSink& sink) {
#if TOML_EXCEPTIONS
  try {
    out = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << path << ": TOML parse error at line " << e.source().begin.line << ", column " << e.source().begin.column
       << ": " << e.description();
    sink.set(os.str());
    return false;
  }
#else
  toml::parse_result r = toml::parse_file(path);
  if (!r) {
    std::ostringstream os;
    os << path << ": TOML parse error at line " << r.error().source().begin.line << ", column "
       << r.error().source().begin.column << ": " << r.error().description();
    sink.set(os.str());
    return false;
  }
  out = std::move(r).table();
#endif
  return true;
}

constexpr double kAlphaLoDeg = -90.0, kAlphaHiDeg = 90.0;

// On-board capacities (fsw/core, fixed-size storage): a file the loader accepts must load on
// board too, so the loader's limits are these (tests/config/test_onboard_capacity.cpp checks
// that they equal the flight code's constants). The guidance tunables' limits (rk4_steps, ...)
// are checked by the flight software's parameter lists (fsw/guidance/mission_adapter).
constexpr std::size_t kOnboardAeroAlphaRows = 64;      // OnboardAero::kMaxAlpha
constexpr std::size_t kOnboardAeroMachColumns = 64;    // OnboardAero::kMaxMach
constexpr std::size_t kOnboardAlphaProfilePoints = 64; // AlphaProfile::kCapacity

void check_capacity(Reader& r, const std::string& key, std::size_t n, std::size_t capacity, const char* holder) {
  if (n > capacity) {
    r.fail(key, "has " + std::to_string(n) + " values; the on-board " + holder + " holds at most " +
                    std::to_string(capacity));
  }
}

void read_grid(Reader& r, std::vector<double>& alpha_rad, std::vector<double>& mach) {
  alpha_rad = r.numbers("alpha_deg", true, kAlphaLoDeg, kAlphaHiDeg);
  check_capacity(r, "alpha_deg", alpha_rad.size(), kOnboardAeroAlphaRows, "aerodynamic table");
  for (double& a : alpha_rad) a *= kDegToRad;
  mach = r.numbers("mach", true, 0.0, 100.0);
  check_capacity(r, "mach", mach.size(), kOnboardAeroMachColumns, "aerodynamic table");
}

Table2D read_table(Reader& r, const std::string& key, const std::vector<double>& alpha_rad,
                   const std::vector<double>& mach, bool required) {
  Table2D t;
  const toml::node* n = r.get(key, required);
  if (!n || r.sink()->failed()) return t;
  t.alpha_rad = alpha_rad;
  t.mach = mach;
  t.values = r.matrix(key, *n, alpha_rad.size(), mach.size(), -100.0, 100.0);
  return t;
}

void read_surface(Reader s, const std::vector<double>& alpha_rad, const std::vector<double>& mach,
                  ControlSurface& cs) {
  cs.name = s.choice("name", {"body_flap", "elevon"});
  cs.count = s.integer("count", 1, 8);
  const double lo = s.number("min_deg", -90.0, 90.0);
  const double hi = s.number("max_deg", -90.0, 90.0);
  if (!s.sink()->failed() && !(hi > lo)) s.fail("max_deg", "value " + fmt_double(hi) + " must exceed min_deg " + fmt_double(lo));
  cs.min_rad = lo * kDegToRad;
  cs.max_rad = hi * kDegToRad;
  std::vector<double> d = s.numbers("deflection_deg", true, lo, hi);
  if (s.sink()->failed()) return;
  bool has_zero = false;
  for (double v : d) has_zero = has_zero || v == 0.0;
  if (!has_zero) {
    s.fail("deflection_deg", "must include 0 (neutral)");
    return;
  }
  for (double v : d) cs.deflection_rad.push_back(v * kDegToRad);
  for (const char* key : {"dcl", "dcd", "dcm"}) {
    const toml::node* n = s.get(key, true);
    if (!n) return;
    const toml::array* arr = n->as_array();
    if (!arr || arr->size() != d.size()) {
      s.fail(key, "expected an array of " + std::to_string(d.size()) + " tables (one per deflection_deg entry), got " +
                      (arr ? std::to_string(arr->size()) + " entries" : describe(*n)));
      return;
    }
    std::vector<Table2D>& dst = key[2] == 'l' ? cs.dcl : (key[2] == 'd' ? cs.dcd : cs.dcm);
    for (size_t i = 0; i < arr->size(); ++i) {
      Table2D t;
      t.alpha_rad = alpha_rad;
      t.mach = mach;
      t.values = s.matrix(std::string(key) + "[" + std::to_string(i) + "]", *arr->get(i), alpha_rad.size(),
                          mach.size(), -100.0, 100.0);
      if (s.sink()->failed()) return;
      dst.push_back(std::move(t));
    }
  }
  s.finish();
}

void read_vehicle_file(const std::string& path, Vehicle& v, ErrorSink& sink) {
  toml::table root;
  if (!parse_file(path, root, sink)) return;
  Reader top(&root, path, "", &sink);
  Reader vr = top.sub("vehicle");
  v.name = vr.text("name");
  v.mass_kg = vr.number("mass_kg", 0.0, 1e7, true);
  v.reference_area_m2 = vr.number("reference_area_m2", 0.0, 1e4, true);
  v.nose_radius_m = vr.number("nose_radius_m", 0.0, 100.0, true);
  v.heating_model = vr.choice("heating_model", {"chapman_stagnation", "betts_leading_edge"}, false,
                              "chapman_stagnation") == "betts_leading_edge"
                        ? HeatingModel::kBettsLeadingEdge
                        : HeatingModel::kChapmanStagnation;
  vr.finish();

  Reader ar = top.sub("aero");
  AeroModel& a = v.aero;
  a.source = ar.text("source");
  const std::string policy = ar.choice("out_of_range", {"clamp", "error"});
  a.out_of_range = policy == "error" ? OutOfRangePolicy::kError : OutOfRangePolicy::kClamp;
  std::vector<double> alpha_rad, mach;
  read_grid(ar, alpha_rad, mach);
  if (sink.failed()) return;
  a.cl = read_table(ar, "cl", alpha_rad, mach, true);
  a.cd = read_table(ar, "cd", alpha_rad, mach, true);
  for (size_t i = 0; i < a.cd.values.size(); ++i) {
    if (a.cd.values[i] <= 0.0) {
      ar.fail("cd[" + std::to_string(i / mach.size()) + "][" + std::to_string(i % mach.size()) + "]",
              "value " + fmt_double(a.cd.values[i]) + " must be positive");
      return;
    }
  }
  a.cm = read_table(ar, "cm", alpha_rad, mach, false);
  if (ar.has("reference_length_m") || !a.cm.empty())
    a.reference_length_m = ar.number("reference_length_m", 0.0, 1000.0, true);
  a.flap_fixed_rad = ar.number("flap_fixed_deg", -90.0, 90.0, false, false, 0.0) * kDegToRad;
  a.q_flap_fixed_Pa = ar.number("q_flap_fixed_Pa", 0.0, 1e6, false, false, 100.0);
  if (const toml::node* n = ar.get("surface", false)) {
    const toml::array* arr = n->as_array();
    if (!arr || !arr->is_array_of_tables()) {
      ar.fail("surface", "expected an array of tables [[aero.surface]], got " + describe(*n));
      return;
    }
    for (size_t i = 0; i < arr->size() && !sink.failed(); ++i) {
      ControlSurface cs;
      read_surface(Reader(arr->get(i)->as_table(), path, "aero.surface[" + std::to_string(i) + "]", &sink), alpha_rad,
                   mach, cs);
      a.surfaces.push_back(std::move(cs));
    }
    if (!sink.failed() && !a.surfaces.empty() && a.cm.empty())
      ar.fail("surface", "control surfaces given without a cm table (trim needs moment data)");
  }
  ar.finish();
  top.finish();
}

Distribution to_distribution(const std::string& name) {
  return name == "uniform" ? Distribution::kUniform : Distribution::kGaussian;
}

// One campaign set: `distribution` for every quantity, `<name>_distribution` overriding it for
// one; each quantity's number is 3 sigma (gaussian) or the half-width (uniform).
void read_dispersions(Reader d, Dispersions& dp) {
  const std::vector<std::string> kinds{"gaussian", "uniform"};
  const Distribution all = to_distribution(d.choice("distribution", kinds));
  auto quantity = [&](Dispersion& q, const std::string& name, const std::string& key, double hi, double to_si) {
    q.value = d.number(key, 0.0, hi) * to_si;
    q.distribution = d.has(name + "_distribution") ? to_distribution(d.choice(name + "_distribution", kinds)) : all;
  };
  quantity(dp.entry_flight_path_rad, "entry_flight_path", "entry_flight_path_deg", 10.0, kDegToRad);
  quantity(dp.entry_heading_rad, "entry_heading", "entry_heading_deg", 90.0, kDegToRad);
  quantity(dp.entry_velocity_mps, "entry_velocity", "entry_velocity_mps", 1000.0, 1.0);
  quantity(dp.entry_position_rad, "entry_position", "entry_position_deg", 10.0, kDegToRad);
  quantity(dp.density_scale, "density_scale", "density_scale", 0.99, 1.0);
  dp.density_perturbation = d.number("density_perturbation", 0.0, 0.99);
  dp.density_correlation_m = d.number("density_correlation_m", 0.0, 1e6, true);
  quantity(dp.cl_scale, "cl_scale", "cl_scale", 0.99, 1.0);
  quantity(dp.cd_scale, "cd_scale", "cd_scale", 0.99, 1.0);
  quantity(dp.mass_scale, "mass_scale", "mass_scale", 0.99, 1.0);
  dp.wind_scale_min = d.number("wind_scale_min", 0.0, 10.0);
  dp.wind_scale_max = d.number("wind_scale_max", 0.0, 10.0);
  dp.wind_scale_distribution =
      d.has("wind_scale_distribution") ? to_distribution(d.choice("wind_scale_distribution", kinds)) : all;
  if (!d.sink()->failed() && dp.wind_scale_max < dp.wind_scale_min)
    d.fail("wind_scale_max", "value " + fmt_double(dp.wind_scale_max) + " below wind_scale_min " +
                                 fmt_double(dp.wind_scale_min));
  d.finish();
}

double specific_energy(double altitude_m, double velocity_mps) {  // (7.8)
  return 0.5 * velocity_mps * velocity_mps - kMu_m3ps2 / (kEarthRadius_m + altitude_m) + kMu_m3ps2 / kEarthRadius_m;
}

std::string resolve_relative(const std::filesystem::path& base_dir, const std::string& rel) {
  std::filesystem::path p(rel);
  if (p.is_relative()) p = base_dir / p;
  return p.lexically_normal().string();
}

// FNV-1a 64 over the contents of the files, in order (the mission's digest).
std::string files_digest(const std::vector<std::string>& paths) {
  std::uint64_t h = 14695981039346656037ull;
  for (const auto& p : paths) {
    std::ifstream in(p, std::ios::binary);
    char buf[65536];
    while (in.read(buf, sizeof buf) || in.gcount() > 0) {
      for (std::streamsize i = 0; i < in.gcount(); ++i) {
        h ^= static_cast<unsigned char>(buf[i]);
        h *= 1099511628211ull;
      }
    }
    h ^= 0xff;  // file separator
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

std::string find_mission_file(const std::string& name_or_path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                               (name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".toml");
  if (looks_like_path) return fs::absolute(name_or_path, ec).lexically_normal().string();
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("REENTRY_CONFIG_DIR"); env && *env) dirs.emplace_back(env);
  dirs.emplace_back(REENTRY_CONFIG_DIR);
  for (const auto& d : dirs) {
    fs::path p = fs::path(d) / "missions" / (name_or_path + ".toml");
    if (fs::exists(p, ec)) return p.lexically_normal().string();
  }
  return (fs::path(dirs.front()) / "missions" / (name_or_path + ".toml")).lexically_normal().string();
}

void read_entry(Reader e, Mission& m) {
  m.entry.altitude_m = e.number("altitude_m", 0.0, 1e6, true);
  m.entry.longitude_rad = e.number("longitude_deg", -360.0, 360.0) * kDegToRad;
  m.entry.latitude_rad = e.number("latitude_deg", -90.0, 90.0) * kDegToRad;
  m.entry.velocity_mps = e.number("velocity_mps", 0.0, 12000.0, true);
  m.entry.flight_path_rad = e.number("flight_path_deg", -90.0, 0.0) * kDegToRad;
  m.entry.heading_rad = e.number("heading_deg", -360.0, 360.0) * kDegToRad;
  e.finish();
}

void read_taem(Reader t, TaemInterface& ti) {
  ti.altitude_m = t.number("altitude_m", 0.0, 1e6, true);
  ti.velocity_mps = t.number("velocity_mps", 0.0, 12000.0, true);
  ti.longitude_rad = t.number("longitude_deg", -360.0, 360.0) * kDegToRad;
  ti.latitude_rad = t.number("latitude_deg", -90.0, 90.0) * kDegToRad;
  ti.heading_rad = t.number("heading_deg", -360.0, 360.0) * kDegToRad;
  ti.range_tol_m = t.number("range_tol_m", 0.0, 1e6, true);
  ti.altitude_tol_m = t.number("altitude_tol_m", 0.0, 1e5, true);
  ti.heading_tol_rad = t.number("heading_tol_deg", 0.0, 180.0, true) * kDegToRad;
  ti.hac_radius_m = t.number("hac_radius_m", 0.0, 1e5, true);
  if (t.has("mach_target") || t.has("mach_tol")) {
    ti.mach_target = t.number("mach_target", 0.0, 50.0, true);
    ti.mach_tol = t.number("mach_tol", 0.0, 50.0, true);
  }
  if (t.has("flight_path_deg") || t.has("flight_path_tol_deg")) {
    ti.flight_path_rad = t.number("flight_path_deg", -90.0, 90.0) * kDegToRad;
    ti.flight_path_tol_rad = t.number("flight_path_tol_deg", 0.0, 180.0, true) * kDegToRad;
  }
  t.finish();
}

void read_constraints(Reader c, PathConstraints& pc) {
  auto optional_limit = [&](const char* key, double hi) {
    return c.has(key) ? c.number(key, 0.0, hi, true) : (c.get(key, false), kNotConstrained);
  };
  pc.heat_flux_max_Wpm2 = optional_limit("heat_flux_max_Wpm2", 1e9);
  pc.heat_load_max_Jpm2 = optional_limit("heat_load_max_Jpm2", 1e12);
  pc.load_factor_max_g = optional_limit("load_factor_max_g", 100.0);
  pc.q_alpha_max_Pa_rad = optional_limit("q_alpha_max_Pa_rad", 1e8);
  pc.dynamic_pressure_max_Pa = optional_limit("dynamic_pressure_max_Pa", 1e8);
  pc.alpha_max_rad = c.number("alpha_max_deg", 0.0, 90.0, true) * kDegToRad;
  pc.alpha_rate_max_radps = c.number("alpha_rate_max_degps", 0.0, 1000.0, true) * kDegToRad;
  pc.sigma_rate_max_radps = c.number("sigma_rate_max_degps", 0.0, 1000.0, true) * kDegToRad;
  pc.alpha_accel_max_radps2 = c.number("alpha_accel_max_degps2", 0.0, 10000.0, true) * kDegToRad;
  pc.sigma_accel_max_radps2 = c.number("sigma_accel_max_degps2", 0.0, 10000.0, true) * kDegToRad;
  c.finish();
}

void read_alpha_profile(Reader ap, Mission& m) {
  const PathConstraints& pc = m.constraints;
  m.alpha_profile_planned = ap.choice("source", {"table", "planned"}, false, "table") == "planned";
  if (m.alpha_profile_planned) {
    if (ap.has("energy")) ap.fail("energy", "not allowed with source = \"planned\" (the profile is planned)");
    if (ap.has("alpha_deg")) ap.fail("alpha_deg", "not allowed with source = \"planned\" (the profile is planned)");
  } else {
    m.alpha_profile.x = ap.numbers("energy", true, 0.0, 2.0);
    check_capacity(ap, "energy", m.alpha_profile.x.size(), kOnboardAlphaProfilePoints, "alpha profile");
    m.alpha_profile.y = ap.numbers("alpha_deg", false, 0.0, 90.0);
  }
  for (double& a : m.alpha_profile.y) a *= kDegToRad;
  if (!ap.sink()->failed() && m.alpha_profile.x.size() != m.alpha_profile.y.size())
    ap.fail("alpha_deg", "has " + std::to_string(m.alpha_profile.y.size()) + " values but energy has " +
                             std::to_string(m.alpha_profile.x.size()));
  for (size_t i = 0; i < m.alpha_profile.y.size() && !ap.sink()->failed(); ++i)
    if (m.alpha_profile.y[i] > pc.alpha_max_rad * (1.0 + 1e-12))
      ap.fail("alpha_deg[" + std::to_string(i) + "]", "value " + fmt_double(m.alpha_profile.y[i] / kDegToRad) +
                                                     " exceeds constraints.alpha_max_deg " +
                                                     fmt_double(pc.alpha_max_rad / kDegToRad));
  ap.finish();
}

void read_guidance(Reader g, GuidanceParams& gp) {
  // A guidance cycle between 1 and 100 Hz: slower cannot track a drag profile through the
  // pull-out, faster leaves no time for the tracker and the link supervision in ticks.
  gp.gnc_rate_hz = g.number("gnc_rate_hz", 1.0, 100.0);
  gp.plan_latency_ticks = g.integer("plan_latency_ticks", 1, 1000);  // the executive adopts at k + L, L >= 1
  gp.replan_period_s = g.number("replan_period_s", 0.0, 1e5, true);
  gp.replan_drag_error_frac = g.number("replan_drag_error_frac", 0.0, 10.0, true);
  gp.drag_error_replan_spacing_s = g.number("drag_error_replan_spacing_s", 0.0, 1e4, false, false, 5.0);
  gp.drag_profile = g.choice("drag_profile", {"three_segment", "smooth"});
  gp.initial_drag = g.choice("initial_drag", {"actual", "lmin"});
  gp.onboard_atmosphere = g.choice("onboard_atmosphere", {"exponential", "table"});
  gp.onboard_trim = g.boolean("onboard_trim", false, true);
  gp.initial_descent_drag_mps2 = g.number("initial_descent_drag_mps2", 0.0, 100.0);
  // The guidance law; [guidance.predictor_corrector] holds that law's tunables.
  gp.law = g.choice("law", {"drag_tracking", "predictor_corrector"}, false, "drag_tracking");
  // The laws' tunables ([guidance] numbers not read above, [guidance.planner], [guidance.tracker],
  // [guidance.predictor_corrector]) are validated by the flight software's parameter lists.
  gp.tuning = g.pass_through_numbers({"planner", "tracker", "predictor_corrector"});
  g.finish();
}

void read_sim(Reader s, SimParams& sp) {
  sp.integrator = s.choice("integrator", {"rkf56", "rkf78"});
  sp.rel_tol = s.number("rel_tol", 0.0, 1.0, true);
  sp.abs_tol_position_m = s.number("abs_tol_position_m", 0.0, 1e6, true);
  sp.abs_tol_velocity_mps = s.number("abs_tol_velocity_mps", 0.0, 1e6, true);
  sp.gravity = s.choice("gravity", {"central", "j2j4", "sh20"});
  sp.atmosphere = s.choice("atmosphere", {"us76", "exponential"});
  sp.wind = s.boolean("wind");
  sp.shape = s.choice("shape", {"sphere", "oblate"});
  sp.trim = s.boolean("trim");
  sp.attitude = s.choice("attitude", {"ideal", "lag"});
  sp.attitude_time_constant_s = s.number("attitude_time_constant_s", 0.0, 100.0, true);
  sp.transport_delay_ticks = s.integer("transport_delay_ticks", 0, 1000);
  sp.time_limit_s = s.number("time_limit_s", 0.0, 1e6, true);
  s.finish();
}

void read_environment(Reader env, const std::filesystem::path& dir, EnvironmentData& data) {
  namespace fs = std::filesystem;
  auto env_file = [&](const char* key) {
    const std::string rel = env.text(key);
    if (env.sink()->failed()) return std::string();
    const std::string full = resolve_relative(dir, rel);
    std::error_code ec;
    if (!fs::is_regular_file(full, ec)) env.fail(key, "value \"" + rel + "\": file " + full + " not found");
    return full;
  };
  data.us76_table = env_file("us76_table");
  data.gravity_coefficients = env_file("gravity_coefficients");
  data.wind_profile = env_file("wind_profile");
  env.finish();
}

// Cross-field checks: the TAEM energy below the entry's, the alpha profile covering both.
void check_energies(Reader& top, Mission& m) {
  const TaemInterface& ti = m.taem;
  const double e_entry = specific_energy(m.entry.altitude_m, m.entry.velocity_mps);
  const double e_taem = specific_energy(ti.altitude_m, ti.velocity_mps);
  if (!(e_taem < e_entry)) {
    top.fail("taem.velocity_mps", "TAEM energy " + fmt_double(e_taem) + " J/kg (altitude_m " + fmt_double(ti.altitude_m) +
                                      ", velocity_mps " + fmt_double(ti.velocity_mps) + ") is not below the entry energy " +
                                      fmt_double(e_entry) + " J/kg");
    return;
  }
  const double e_ratio = e_taem / e_entry;
  if (!m.alpha_profile_planned && (m.alpha_profile.x.front() > e_ratio || m.alpha_profile.x.back() < 1.0)) {
    top.fail("alpha_profile.energy", "range [" + fmt_double(m.alpha_profile.x.front()) + ", " +
                                         fmt_double(m.alpha_profile.x.back()) + "] does not cover [E_taem/E_entry = " +
                                         fmt_double(e_ratio) + ", 1]");
  }
}

void load_into(const std::string& path, Mission& m, ErrorSink& sink) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    sink.set(path + ": mission file not found");
    return;
  }
  toml::table root;
  if (!parse_file(path, root, sink)) return;
  const fs::path dir = fs::path(path).parent_path();
  m.source_file = path;
  Reader top(&root, path, "", &sink);
  m.name = top.text("name");
  m.notes = top.text("notes", false);
  const std::string vehicle_rel = top.text("vehicle_file");
  if (sink.failed()) return;
  const std::string vehicle_path = resolve_relative(dir, vehicle_rel);
  if (!fs::is_regular_file(vehicle_path, ec)) {
    top.fail("vehicle_file", "value \"" + vehicle_rel + "\": file " + vehicle_path + " not found");
    return;
  }
  read_entry(top.sub("entry"), m);
  read_taem(top.sub("taem"), m.taem);
  read_constraints(top.sub("constraints"), m.constraints);
  read_alpha_profile(top.sub("alpha_profile"), m);
  read_guidance(top.sub("guidance"), m.guidance);
  read_sim(top.sub("sim"), m.sim);
  read_dispersions(top.sub("dispersions"), m.dispersions);
  m.has_stress_dispersions = top.has("stress_dispersions");
  if (m.has_stress_dispersions) read_dispersions(top.sub("stress_dispersions"), m.stress_dispersions);
  read_environment(top.sub("environment"), dir, m.environment);
  top.finish();
  if (sink.failed()) return;
  check_energies(top, m);
  if (sink.failed()) return;
  read_vehicle_file(vehicle_path, m.vehicle, sink);
  if (sink.failed()) return;
  sink.set(check_mission(m));
  if (sink.failed()) return;
  m.digest = files_digest({path, vehicle_path, m.environment.us76_table, m.environment.gravity_coefficients,
                           m.environment.wind_profile});
}

}  // namespace

LoadResult load_mission(const std::string& name_or_path) {
  LoadResult result;
  ErrorSink sink;
  try {
    const std::string path = find_mission_file(name_or_path);
    load_into(path, result.mission, sink);
  } catch (const std::exception& ex) {
    sink.set(name_or_path + ": unexpected error while loading: " + ex.what());
  } catch (...) {
    sink.set(name_or_path + ": unexpected error while loading");
  }
  result.ok = !sink.failed();
  result.error = sink.message;
  if (!result.ok) result.mission = Mission{};
  return result;
}

std::string summary_line(const Mission& m) {
  constexpr double r2d = 1.0 / kDegToRad;
  auto lim = [](double v) { return v == kNotConstrained ? std::string("-") : fmt_double(v); };
  std::ostringstream os;
  os.precision(6);
  os << m.name << ": " << m.vehicle.name << " m=" << m.vehicle.mass_kg << " kg S=" << m.vehicle.reference_area_m2
     << " m2 | entry h=" << m.entry.altitude_m << " m lon=" << m.entry.longitude_rad * r2d
     << " lat=" << m.entry.latitude_rad * r2d << " V=" << m.entry.velocity_mps << " m/s gamma="
     << m.entry.flight_path_rad * r2d << " chi=" << m.entry.heading_rad * r2d << " deg | TAEM h=" << m.taem.altitude_m
     << " m V=" << m.taem.velocity_mps << " m/s lon=" << m.taem.longitude_rad * r2d
     << " lat=" << m.taem.latitude_rad * r2d << " chi=" << m.taem.heading_rad * r2d
     << " deg | qdot<=" << lim(m.constraints.heat_flux_max_Wpm2) << " W/m2 n<=" << lim(m.constraints.load_factor_max_g)
     << " g q<=" << lim(m.constraints.dynamic_pressure_max_Pa) << " Pa qa<=" << lim(m.constraints.q_alpha_max_Pa_rad)
     << " Pa.rad alpha<=" << m.constraints.alpha_max_rad * r2d << " deg";
  return os.str();
}

}  // namespace reentry::config
