// Aerodynamic coefficients and pitch trim of the truth simulator (thesis 3.4).
#pragma once

#include "reentry/config/mission.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "environment/interpolation.hpp"
#include "environment/scalar.hpp"

namespace reentry::truth {

template <class T>
struct AeroCoefficientsT {
  T cl = T(0.0);
  T cd = T(0.0);
  T cm_total = T(0.0);       // pitching moment with the trim deflections (0 when trimmed)
  T flap_rad = T(0.0);       // body-flap deflection used
  T elevon_rad = T(0.0);     // elevon deflection used (each of `count` elevons)
  bool trimmed = false;      // total Cm driven to zero
  bool saturated = false;    // trim impossible within the limits: surfaces at the limit
  bool out_of_range = false; // query outside the tables with OutOfRangePolicy::kError
};
using AeroCoefficients = AeroCoefficientsT<double>;

namespace detail {
/// One table at (alpha, Mach): bilinear, clamped.
template <class T>
T aero_lookup(const config::Table2D& t, const T& alpha, const T& mach) {
  return bilinear(t.alpha_rad, t.mach, t.values, alpha, mach);
}

/// Linear interpolation in deflection between the tabulated deflections (clamped to their
/// range); value(k) is table k at the flight condition.
template <class T, class D, class Value>
T interpolate_in_deflection(const std::vector<double>& deflection, const D& delta, const Value& value) {
  const int n = static_cast<int>(deflection.size());
  if (n == 1) return value(0);
  const D d = scalar::fmin(scalar::fmax(delta, deflection.front()), deflection.back());
  const int j = bracket(deflection.data(), n, scalar::value(d));
  const D t = (d - deflection[j]) / (deflection[j + 1] - deflection[j]);
  return (1.0 - t) * value(j) + t * value(j + 1);
}

/// Increment of one surface at a deflection.
template <class T>
T surface_increment(const std::vector<config::Table2D>& tables, const std::vector<double>& deflection, const T& delta,
                    const T& alpha, const T& mach) {
  return interpolate_in_deflection<T>(deflection, delta, [&](int k) { return aero_lookup(tables[k], alpha, mach); });
}

struct SurfaceSolution {
  double delta;
  bool solved;
};

/// Solve base + count * dcm(delta) = 0 for delta in [min, max] (double: the trim solve).
SurfaceSolution solve_surface(const config::ControlSurface& s, double base, double alpha, double mach);

/// The trim deflection as a function of the flight condition: the double root itself, and for
/// AD scalars the root with the derivatives of the implicit function theorem, d delta / dp =
/// -F_p / F_delta for F = base + count dcm(delta) (one Newton step from the exact root, whose
/// value is kept: the moment is piecewise linear in delta, so the second derivatives are exact
/// too). An unsolved (saturated) or fixed surface does not move with the condition.
template <class T>
T trim_deflection(const config::ControlSurface& s, const SurfaceSolution& sol, const T& base, const T& alpha,
                  const T& mach) {
  if constexpr (scalar::is_double<T>) {
    (void)s; (void)base; (void)alpha; (void)mach;
    return sol.delta;
  } else {
    const int n = static_cast<int>(s.deflection_rad.size());
    if (!sol.solved || n < 2) return T(sol.delta);
    const double count = static_cast<double>(s.count);
    const T f = base + count * interpolate_in_deflection<T>(s.deflection_rad, sol.delta,
                                                             [&](int k) { return aero_lookup(s.dcm[k], alpha, mach); });
    const double d = std::fmin(std::fmax(sol.delta, s.deflection_rad.front()), s.deflection_rad.back());
    const int j = bracket(s.deflection_rad.data(), n, d);
    const T f_delta = count * (aero_lookup(s.dcm[j + 1], alpha, mach) - aero_lookup(s.dcm[j], alpha, mach)) /
                      (s.deflection_rad[j + 1] - s.deflection_rad[j]);
    if (scalar::value(f_delta) == 0.0) return T(sol.delta);
    const T step = f / f_delta;
    return sol.delta - (step - scalar::value(step));
  }
}
}  // namespace detail

class Aerodynamics {
 public:
  /// Validates the tables (grid sizes, monotonic axes, finite values); nullopt + *error.
  static std::optional<Aerodynamics> create(const config::AeroModel& model, std::string* error = nullptr);

  /// Bilinear interpolation over (alpha, Mach). With trim and moment data: body flap first,
  /// then elevons (3.24); below q_flap_fixed_Pa the flap is fixed and the elevons trim.
  /// cl/cd include the increments of the trim deflections, then are scaled.
  AeroCoefficients coefficients(double alpha_rad, double mach, double q_Pa, bool trim,
                                double cl_scale = 1.0, double cd_scale = 1.0) const {
    return coefficients<double>(alpha_rad, mach, q_Pa, trim, cl_scale, cd_scale);
  }
  /// The same model, scalar-generic (environment/scalar.hpp).
  template <class T>
  AeroCoefficientsT<T> coefficients(const T& alpha_rad, const T& mach, const T& q_Pa, bool trim, double cl_scale = 1.0,
                                    double cd_scale = 1.0) const;

  bool has_moment_data() const { return !model_.cm.empty(); }
  const config::AeroModel& model() const { return model_; }

 private:
  Aerodynamics() = default;
  config::AeroModel model_;
  int flap_index_ = -1;
  int elevon_index_ = -1;
};

template <class T>
AeroCoefficientsT<T> Aerodynamics::coefficients(const T& alpha_rad, const T& mach, const T& q_Pa, bool trim,
                                                double cl_scale, double cd_scale) const {
  using detail::aero_lookup;
  using detail::surface_increment;
  AeroCoefficientsT<T> out;
  const config::Table2D& cl = model_.cl;
  if (model_.out_of_range == config::OutOfRangePolicy::kError) {
    const double a = scalar::value(alpha_rad), m = scalar::value(mach);
    out.out_of_range = a < cl.alpha_rad.front() || a > cl.alpha_rad.back() || m < cl.mach.front() || m > cl.mach.back();
  }
  T c_l = aero_lookup(model_.cl, alpha_rad, mach);
  T c_d = aero_lookup(model_.cd, alpha_rad, mach);
  const bool moments = !model_.cm.empty();
  const T cm0 = moments ? aero_lookup(model_.cm, alpha_rad, mach) : T(0.0);
  out.cm_total = cm0;
  if (trim && moments && (flap_index_ >= 0 || elevon_index_ >= 0)) {
    T flap = T(0.0), elevon = T(0.0);
    bool need_elevon = true;
    const config::ControlSurface* fs = flap_index_ >= 0 ? &model_.surfaces[flap_index_] : nullptr;
    const config::ControlSurface* es = elevon_index_ >= 0 ? &model_.surfaces[elevon_index_] : nullptr;
    const double a = scalar::value(alpha_rad), m = scalar::value(mach);
    if (fs) {
      if (scalar::value(q_Pa) < model_.q_flap_fixed_Pa) {
        flap = T(std::fmin(std::fmax(model_.flap_fixed_rad, fs->min_rad), fs->max_rad));  // thesis 5.5
      } else {
        const detail::SurfaceSolution sol = detail::solve_surface(*fs, scalar::value(cm0), a, m);
        flap = detail::trim_deflection(*fs, sol, cm0, alpha_rad, mach);
        need_elevon = !sol.solved;
      }
    }
    T cm_flap = cm0;
    if (fs) cm_flap += static_cast<double>(fs->count) * surface_increment(fs->dcm, fs->deflection_rad, flap, alpha_rad, mach);
    bool solved = !need_elevon;
    if (need_elevon && es) {
      const detail::SurfaceSolution sol = detail::solve_surface(*es, scalar::value(cm_flap), a, m);  // (3.24)
      elevon = detail::trim_deflection(*es, sol, cm_flap, alpha_rad, mach);
      solved = sol.solved;
    }
    T cm_total = cm_flap;
    if (fs) {
      c_l += static_cast<double>(fs->count) * surface_increment(fs->dcl, fs->deflection_rad, flap, alpha_rad, mach);
      c_d += static_cast<double>(fs->count) * surface_increment(fs->dcd, fs->deflection_rad, flap, alpha_rad, mach);
    }
    if (es) {
      c_l += static_cast<double>(es->count) * surface_increment(es->dcl, es->deflection_rad, elevon, alpha_rad, mach);
      c_d += static_cast<double>(es->count) * surface_increment(es->dcd, es->deflection_rad, elevon, alpha_rad, mach);
      cm_total += static_cast<double>(es->count) * surface_increment(es->dcm, es->deflection_rad, elevon, alpha_rad, mach);
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
