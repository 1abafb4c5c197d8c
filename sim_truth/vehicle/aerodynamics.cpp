#include "vehicle/aerodynamics.hpp"

#include "environment/interpolation.hpp"

#include <cmath>

namespace reentry::truth {
namespace {
using detail::aero_lookup;
using detail::interpolate_in_deflection;

void set_error(std::string* error, const std::string& msg) {
  if (error) *error = msg;
}

bool strictly_increasing(const std::vector<double>& v) {
  for (size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return false;
    if (i > 0 && !(v[i] > v[i - 1])) return false;
  }
  return true;
}

bool check_table(const config::Table2D& t, const std::string& name, std::string* error) {
  if (t.alpha_rad.empty() || t.mach.empty() || !strictly_increasing(t.alpha_rad) || !strictly_increasing(t.mach)) {
    set_error(error, "aero table " + name + ": alpha/Mach axes must be non-empty and strictly increasing");
    return false;
  }
  if (t.values.size() != t.alpha_rad.size() * t.mach.size()) {
    set_error(error, "aero table " + name + ": " + std::to_string(t.values.size()) + " values for a " +
                         std::to_string(t.alpha_rad.size()) + " x " + std::to_string(t.mach.size()) + " grid");
    return false;
  }
  for (size_t i = 0; i < t.values.size(); ++i) {
    if (!std::isfinite(t.values[i])) {
      set_error(error, "aero table " + name + ": non-finite value at index " + std::to_string(i));
      return false;
    }
  }
  return true;
}

double lookup(const config::Table2D& t, double alpha, double mach) { return aero_lookup(t, alpha, mach); }

// The same increment with the tables evaluated once at one (alpha, Mach): the trim solve below
// evaluates the moment at many deflections for one flight condition, and re-interpolating the
// tables in alpha and Mach each time was a fifth of a HORUS closed-loop run.
struct IncrementAtCondition {
  const std::vector<double>& deflection;
  double value[64];  // Aerodynamics::create() bounds the deflections to 64
  IncrementAtCondition(const std::vector<config::Table2D>& tables, const std::vector<double>& defl, double alpha,
                       double mach)
      : deflection(defl), value{} {
    for (size_t k = 0; k < defl.size() && k < 64; ++k) value[k] = lookup(tables[k], alpha, mach);
  }
  double operator()(double delta) const {
    return interpolate_in_deflection<double>(deflection, delta, [this](int k) { return value[k]; });
  }
};

}  // namespace

namespace detail {
// Solve base + count * dcm(delta) = 0 for delta in [min, max]. The increment is piecewise
// linear in delta, so each sub-interval between tabulated deflections is checked for a sign
// change; the root closest to zero deflection is refined with Brent. Without a root, the
// limit with the smaller |Cm| is returned.
SurfaceSolution solve_surface(const config::ControlSurface& s, double base, double alpha, double mach) {
  const IncrementAtCondition dcm(s.dcm, s.deflection_rad, alpha, mach);
  auto cm_of = [&](double delta) { return base + s.count * dcm(delta); };
  // Break points: the limits and the tabulated deflections strictly inside them.
  double pts[66];
  int np = 0;
  pts[np++] = s.min_rad;
  for (size_t k = 0; k < s.deflection_rad.size() && np < 65; ++k) {
    if (s.deflection_rad[k] > s.min_rad && s.deflection_rad[k] < s.max_rad) pts[np++] = s.deflection_rad[k];
  }
  pts[np++] = s.max_rad;
  bool found = false;
  double best = 0.0;
  double f_prev = cm_of(pts[0]);
  for (int k = 0; k + 1 < np; ++k) {
    const double f_next = cm_of(pts[k + 1]);
    if (f_prev == 0.0 || f_prev * f_next < 0.0 || f_next == 0.0) {
      const detail::BrentResult r = detail::brent(cm_of, pts[k], pts[k + 1], 1e-14, 200);
      if (!found || std::fabs(r.x) < std::fabs(best)) best = r.x;
      found = true;
    }
    f_prev = f_next;
  }
  if (found) return {best, true};
  const double f_min = cm_of(s.min_rad), f_max = cm_of(s.max_rad);
  return {std::fabs(f_min) <= std::fabs(f_max) ? s.min_rad : s.max_rad, false};
}

}  // namespace detail

std::optional<Aerodynamics> Aerodynamics::create(const config::AeroModel& model, std::string* error) {
  if (!check_table(model.cl, "cl", error) || !check_table(model.cd, "cd", error)) return std::nullopt;
  if (!model.cm.empty() && !check_table(model.cm, "cm", error)) return std::nullopt;
  Aerodynamics a;
  a.model_ = model;
  for (size_t i = 0; i < model.surfaces.size(); ++i) {
    const config::ControlSurface& s = model.surfaces[i];
    const std::string name = "surface " + s.name;
    const size_t nd = s.deflection_rad.size();
    if (nd == 0 || !strictly_increasing(s.deflection_rad) || s.dcl.size() != nd || s.dcd.size() != nd ||
        s.dcm.size() != nd || !(s.min_rad <= s.max_rad) || s.count < 1 || nd > 64) {
      set_error(error, name + ": need 1..64 strictly increasing deflections, one dcl/dcd/dcm table each, min <= max, count >= 1");
      return std::nullopt;
    }
    for (size_t k = 0; k < nd; ++k) {
      const std::string tag = name + " deflection " + std::to_string(s.deflection_rad[k]) + " rad ";
      if (!check_table(s.dcl[k], tag + "dcl", error) || !check_table(s.dcd[k], tag + "dcd", error) ||
          !check_table(s.dcm[k], tag + "dcm", error)) {
        return std::nullopt;
      }
    }
    const bool is_flap = s.name.find("flap") != std::string::npos;
    const bool is_elevon = s.name.find("elevon") != std::string::npos;
    if (is_flap && a.flap_index_ < 0) a.flap_index_ = static_cast<int>(i);
    else if (is_elevon && a.elevon_index_ < 0) a.elevon_index_ = static_cast<int>(i);
  }
  // Unnamed surfaces: trim priority order (first the body flap, then the elevons).
  if (a.flap_index_ < 0 && a.elevon_index_ < 0 && model.surfaces.size() >= 1) {
    a.flap_index_ = 0;
    if (model.surfaces.size() >= 2) a.elevon_index_ = 1;
  }
  return a;
}

}  // namespace reentry::truth
