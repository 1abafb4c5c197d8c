#include "vehicle/aerodynamics.hpp"

#include "environment/interpolation.hpp"

#include <cmath>

namespace reentry::truth {
namespace {

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

double lookup(const config::Table2D& t, double alpha, double mach) {
  return detail::bilinear(t.alpha_rad, t.mach, t.values, alpha, mach);
}

// Linear interpolation in deflection between the tabulated deflections (clamped to their
// range); value(k) is table k at the flight condition.
template <class Value>
double interpolate_in_deflection(const std::vector<double>& deflection, double delta, const Value& value) {
  const int n = static_cast<int>(deflection.size());
  if (n == 1) return value(0);
  const double d = std::fmin(std::fmax(delta, deflection.front()), deflection.back());
  const int j = detail::bracket(deflection.data(), n, d);
  const double t = (d - deflection[j]) / (deflection[j + 1] - deflection[j]);
  return (1.0 - t) * value(j) + t * value(j + 1);
}

// Increment of one surface at a deflection.
double increment(const std::vector<config::Table2D>& tables, const std::vector<double>& deflection, double delta,
                 double alpha, double mach) {
  return interpolate_in_deflection(deflection, delta, [&](int k) { return lookup(tables[k], alpha, mach); });
}

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
    return interpolate_in_deflection(deflection, delta, [this](int k) { return value[k]; });
  }
};

struct SurfaceSolution {
  double delta;
  bool solved;
};

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

}  // namespace

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

AeroCoefficients Aerodynamics::coefficients(double alpha_rad, double mach, double q_Pa, bool trim, double cl_scale,
                                            double cd_scale) const {
  AeroCoefficients out;
  const config::Table2D& cl = model_.cl;
  if (model_.out_of_range == config::OutOfRangePolicy::kError) {
    out.out_of_range = alpha_rad < cl.alpha_rad.front() || alpha_rad > cl.alpha_rad.back() ||
                       mach < cl.mach.front() || mach > cl.mach.back();
  }
  double c_l = lookup(model_.cl, alpha_rad, mach);
  double c_d = lookup(model_.cd, alpha_rad, mach);
  const bool moments = !model_.cm.empty();
  const double cm0 = moments ? lookup(model_.cm, alpha_rad, mach) : 0.0;
  out.cm_total = cm0;
  if (trim && moments && (flap_index_ >= 0 || elevon_index_ >= 0)) {
    double flap = 0.0, elevon = 0.0;
    bool need_elevon = true;
    const config::ControlSurface* fs = flap_index_ >= 0 ? &model_.surfaces[flap_index_] : nullptr;
    const config::ControlSurface* es = elevon_index_ >= 0 ? &model_.surfaces[elevon_index_] : nullptr;
    if (fs) {
      if (q_Pa < model_.q_flap_fixed_Pa) {
        flap = std::fmin(std::fmax(model_.flap_fixed_rad, fs->min_rad), fs->max_rad);  // thesis 5.5
      } else {
        const SurfaceSolution sol = solve_surface(*fs, cm0, alpha_rad, mach);
        flap = sol.delta;
        need_elevon = !sol.solved;
      }
    }
    double cm_flap = cm0;
    if (fs) cm_flap += fs->count * increment(fs->dcm, fs->deflection_rad, flap, alpha_rad, mach);
    bool solved = !need_elevon;
    if (need_elevon && es) {
      const SurfaceSolution sol = solve_surface(*es, cm_flap, alpha_rad, mach);  // (3.24)
      elevon = sol.delta;
      solved = sol.solved;
    }
    double cm_total = cm_flap;
    if (fs) {
      c_l += fs->count * increment(fs->dcl, fs->deflection_rad, flap, alpha_rad, mach);
      c_d += fs->count * increment(fs->dcd, fs->deflection_rad, flap, alpha_rad, mach);
    }
    if (es) {
      c_l += es->count * increment(es->dcl, es->deflection_rad, elevon, alpha_rad, mach);
      c_d += es->count * increment(es->dcd, es->deflection_rad, elevon, alpha_rad, mach);
      cm_total += es->count * increment(es->dcm, es->deflection_rad, elevon, alpha_rad, mach);
    }
    out.flap_rad = flap;
    out.elevon_rad = elevon;
    out.cm_total = cm_total;
    out.trimmed = solved;
    out.saturated = !solved;
  }
  out.cl = c_l * cl_scale;
  out.cd = c_d * cd_scale;
  return out;
}

}  // namespace reentry::truth
