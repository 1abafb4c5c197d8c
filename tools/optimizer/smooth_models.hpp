// Smooth (C2) models of the truth's tabulated quantities, for the optimizer only.
//
// The truth simulator interpolates its aerodynamic tables bilinearly and its trim deflections
// linearly: piecewise-linear functions whose curvature sits on the cell edges, where an exact
// Hessian cannot see it, so Newton steps on them overshoot and cycle. The optimizer therefore
// differentiates C2 fits of the very same tables, built once per run from the truth's own model
// (its trimmed coefficients sampled at the table nodes): tensor-product natural cubic splines
// over (alpha, Mach). The atmosphere (natural cubic splines of ln rho, ln p and T) and the wind
// (natural cubic splines in altitude) of the truth are already C2 inside their tables and are
// used as they are; gravity is analytic. The simulator keeps flying the tables: every
// "feasible" of the optimizer is proven by an open-loop truth flight, and the collocated
// dynamics are corrected towards the tables' values at the collocation points
// (entry_problem.hpp, model correction).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "dynamics/point_model.hpp"
#include "environment/scalar.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::optimal {

/// The C2 ramp R(t): 0 for t <= -1, t for t >= 1, and in between the double integral of the
/// quartic kernel 15/16 (1 - t^2)^2 (so R'' is C1). w R((x - c) / w) is max(x - c, 0) with its
/// corner rounded over [c - w, c + w]. Value, slope and curvature at t.
struct Ramp {
  double r, r1, r2;
};
inline Ramp smooth_ramp(double t) {
  if (t <= -1.0) return {0.0, 0.0, 0.0};
  if (t >= 1.0) return {t, 1.0, 0.0};
  const double t2 = t * t;
  const double r = 0.5 * (t + 1.0) + (15.0 / 16.0) * (t2 * (0.5 + t2 * (-1.0 / 6.0 + t2 / 30.0)) - 11.0 / 30.0);
  const double r1 = 0.5 + (15.0 / 16.0) * t * (1.0 + t2 * (-2.0 / 3.0 + t2 / 5.0));
  const double r2 = (15.0 / 16.0) * (1.0 - t2) * (1.0 - t2);
  return {r, r1, r2};
}
/// x held between lo - w and hi + w with C2 corners there of half-width w: the value is x
/// inside [lo, hi], lo - w below lo - 2 w and hi + w above hi + 2 w. Value, slope, curvature.
inline Ramp smooth_clamp(double x, double lo, double hi, double w) {
  const Ramp a = smooth_ramp((x - (lo - w)) / w);
  const double y = (lo - w) + w * a.r;  // held below
  const Ramp b = smooth_ramp(((hi + w) - y) / w);
  const double dy = a.r1, d2y = a.r2 / w;
  return {(hi + w) - w * b.r, b.r1 * dy, b.r1 * d2y - b.r2 / w * dy * dy};
}

/// Quintic smoothstep (C2): 0 for t <= 0, 1 for t >= 1.
template <class T>
T smooth_step(const T& t) {
  const double tv = truth::scalar::value(t);
  if (tv <= 0.0) return T(0.0);
  if (tv >= 1.0) return T(1.0);
  const double f = tv * tv * tv * (10.0 + tv * (-15.0 + 6.0 * tv));
  const double f1 = 30.0 * tv * tv * (1.0 - tv) * (1.0 - tv);
  const double f2 = 60.0 * tv * (1.0 - tv) * (1.0 - 2.0 * tv);
  return truth::scalar::chain(t, f, f1, f2);
}

/// A piecewise-linear table y(x) (held constant outside its range) with every corner rounded:
/// C2, equal to the table outside the windows, at most `max_deviation` from it inside them
/// (the deviation at a corner is R(0) = 5/32 of the slope jump times the half-width); each
/// window's half-width is also at most a quarter of the shorter neighbouring interval.
class SmoothPiecewiseLinear {
 public:
  SmoothPiecewiseLinear() = default;
  SmoothPiecewiseLinear(const std::vector<double>& x, const std::vector<double>& y, double max_deviation);
  template <class T>
  T operator()(const T& x) const {
    const double xv = truth::scalar::value(x);
    double f = y0_, f1 = 0.0, f2 = 0.0;
    for (size_t k = 0; k < corner_x_.size(); ++k) {
      const Ramp r = smooth_ramp((xv - corner_x_[k]) / width_[k]);
      f += slope_jump_[k] * width_[k] * r.r;
      f1 += slope_jump_[k] * r.r1;
      f2 += slope_jump_[k] * r.r2 / width_[k];
    }
    return truth::scalar::chain(x, f, f1, f2);
  }
  bool empty() const { return corner_x_.empty() && !has_value_; }

 private:
  double y0_ = 0.0;
  bool has_value_ = false;
  std::vector<double> corner_x_, slope_jump_, width_;
};

/// Tensor-product natural cubic spline interpolating values on a grid x (rows) by y (columns),
/// stored as one bicubic patch per cell; C2 in each variable. Outside the grid the query is held
/// (as the truth clamps its tables) beyond a margin of kClampWindow of the end cell, with C2
/// corners (the end patches extrapolated over that margin).
class BicubicSpline {
 public:
  /// `v` row-major: v[i * y.size() + j] at (x[i], y[j]); axes strictly increasing (size >= 1).
  static BicubicSpline fit(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& v);

  template <class T>
  T operator()(const T& xq, const T& yq) const {
    return truth::scalar::chain(xq, yq, taylor(truth::scalar::value(xq), truth::scalar::value(yq), !truth::scalar::is_double<T>));
  }
  /// Value, gradient and Hessian at (x, y) (only the value unless `derivatives`).
  truth::scalar::Taylor2 taylor(double xq, double yq, bool derivatives = true) const;

  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& y() const { return y_; }

 private:
  int ny_cells() const { return std::max(1, static_cast<int>(y_.size()) - 1); }
  static int cell(const std::vector<double>& axis, double q);
  static Ramp clamp_axis(double q, const std::vector<double>& axis);
  static constexpr double kClampWindow = 0.05;  // of the end cell
  std::vector<double> x_, y_;
  std::vector<std::array<double, 16>> coef_;  // a[p * 4 + q]: coefficient of s^p u^q
};

/// The smooth aerodynamic model of one run: C2 fits of the truth's (trimmed) C_L and C_D over
/// (alpha, Mach), times the run's scales. With trim and a body flap that is fixed below
/// q_flap_fixed (thesis 5.5), the fixed-flap and the trimmed fits are blended by a C2 step over
/// +-kFlapBlend of that dynamic pressure (the truth switches at it).
class SmoothAero {
 public:
  static constexpr double kFlapBlend = 0.1;

  /// Fits the truth model of `model` (its tables, trim setting and scales), sampled at the
  /// table nodes and inside each table interval: alpha every kAlphaSample_rad at most, Mach at
  /// kMachSubdivisions equal steps. Sampling inside the cells keeps the fit close to the table
  /// where its slope jumps at a node (HORUS C_L falls by half from Mach 1.5 to 2, then
  /// flattens): the fit's deviation there is about a thirtieth of the slope jump times the
  /// sampling step (fit error at the cell centres, Mach sampled at the nodes only: 5.5 % of
  /// HORUS's C_L range; every quarter interval: 1.3 %).
  explicit SmoothAero(const truth::PointModel& model);
  static constexpr double kAlphaSample_rad = 1.25 * M_PI / 180.0;
  static constexpr int kMachSubdivisions = 4;

  template <class T>
  truth::AeroCoefficientsT<T> operator()(const T& alpha, const T& mach, const T& q) const {
    truth::AeroCoefficientsT<T> c;
    c.cl = cl_(alpha, mach);
    c.cd = cd_(alpha, mach);
    if (blended_) {
      const T b = smooth_step(T((q - (1.0 - kFlapBlend) * q_switch_Pa_) / (2.0 * kFlapBlend * q_switch_Pa_)));
      c.cl = cl_low_q_(alpha, mach) + b * (c.cl - cl_low_q_(alpha, mach));
      c.cd = cd_low_q_(alpha, mach) + b * (c.cd - cd_low_q_(alpha, mach));
    }
    c.cl *= cl_scale_;
    c.cd *= cd_scale_;
    c.trimmed = trimmed_;
    return c;
  }

  /// The truth's unscaled coefficients the fits interpolate, at (alpha, Mach) and dynamic
  /// pressure q (for the fit-error test and the model correction).
  static truth::AeroCoefficients truth_coefficients(const truth::PointModel& model, double alpha, double mach, double q);

  bool blended() const { return blended_; }
  double switch_q_Pa() const { return q_switch_Pa_; }

 private:
  BicubicSpline cl_, cd_, cl_low_q_, cd_low_q_;
  bool blended_ = false, trimmed_ = false;
  double q_switch_Pa_ = 0.0, cl_scale_ = 1.0, cd_scale_ = 1.0;
};

}  // namespace reentry::optimal
