#pragma once
// Natural cubic spline interpolation, thesis sec. 4.1, eqs (4.1)-(4.8) (after Press et al. 1988).
// Fixed capacity, allocation-free, no exceptions. The interval search is a bisection with a cached
// hint (mutable, so const evaluation is safe from ONE thread at a time; use the explicit-hint
// overloads for concurrent readers).

#include <cmath>

#include "numerics/status.hpp"
#include "numerics/table_lookup.hpp"

namespace reentry::numerics {

// Thomas algorithm for a tridiagonal system: sub[i] x[i-1] + diag[i] x[i] + sup[i] x[i+1] = rhs[i],
// i = 0..n-1 (sub[0] and sup[n-1] are ignored). work must hold n doubles. Returns kInvalidInput for
// n < 1 and kNonFinite on a zero/non-finite pivot (no pivoting: intended for diagonally dominant systems
// such as (4.8)). x may alias rhs.
inline NumStatus solve_tridiagonal(const double* sub, const double* diag, const double* sup, const double* rhs,
                                   double* x, int n, double* work) {
  if (n < 1 || diag == nullptr || rhs == nullptr || x == nullptr || work == nullptr) return NumStatus::kInvalidInput;
  if (n > 1 && (sub == nullptr || sup == nullptr)) return NumStatus::kInvalidInput;
  double pivot = diag[0];
  if (!(std::isfinite(pivot)) || pivot == 0.0) return NumStatus::kNonFinite;
  x[0] = rhs[0] / pivot;
  for (int i = 1; i < n; ++i) {
    work[i] = sup[i - 1] / pivot;
    pivot = diag[i] - sub[i] * work[i];
    if (!(std::isfinite(pivot)) || pivot == 0.0) return NumStatus::kNonFinite;
    x[i] = (rhs[i] - sub[i] * x[i - 1]) / pivot;
  }
  for (int i = n - 2; i >= 0; --i) x[i] -= work[i + 1] * x[i + 1];
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) return NumStatus::kNonFinite;
  }
  return NumStatus::kOk;
}

template <int Capacity>
class NaturalCubicSpline {
  static_assert(Capacity >= 2, "a spline needs at least two knots");

 public:
  NaturalCubicSpline() = default;

  // Fits the spline through (x[i], y[i]), i = 0..n-1, 2 <= n <= Capacity, x strictly increasing, all
  // finite. Second derivatives at both ends are zero (natural spline); interior ones from (4.7)/(4.8).
  // On failure the spline is left empty (size() == 0).
  NumStatus fit(const double* x, const double* y, int n) {
    n_ = 0;
    hint_ = 0;
    if (x == nullptr || y == nullptr || n < 2 || n > Capacity) return NumStatus::kInvalidInput;
    for (int i = 0; i < n; ++i) {
      if (!std::isfinite(x[i]) || !std::isfinite(y[i])) return NumStatus::kNonFinite;
      if (i > 0 && !(x[i] > x[i - 1])) return NumStatus::kInvalidInput;
      x_[i] = x[i];
      y_[i] = y[i];
      y2_[i] = 0.0;
    }
    const int m = n - 2;  // interior unknowns y2[1..n-2]
    if (m > 0) {
      // (4.8) rows j = 1..n-2 with h_j = x_{j+1} - x_j, solved in place by the tridiagonal (Thomas)
      // algorithm; work_[j] holds the eliminated super-diagonal. y2_[0] = y2_[n-1] = 0 (natural).
      for (int j = 1; j <= m; ++j) {
        const double h_lo = x_[j] - x_[j - 1];
        const double h_hi = x_[j + 1] - x_[j];
        const double rhs = 6.0 * ((y_[j + 1] - y_[j]) / h_hi - (y_[j] - y_[j - 1]) / h_lo);  // (4.7) x 6
        const double pivot = 2.0 * (h_lo + h_hi) - (j > 1 ? h_lo * work_[j - 1] : 0.0);
        if (!std::isfinite(pivot) || pivot <= 0.0) return NumStatus::kNonFinite;
        work_[j] = h_hi / pivot;
        y2_[j] = (rhs - h_lo * y2_[j - 1]) / pivot;
      }
      for (int j = m; j >= 1; --j) {
        y2_[j] -= work_[j] * y2_[j + 1];
        if (!std::isfinite(y2_[j])) return NumStatus::kNonFinite;
      }
    }
    n_ = n;
    return NumStatus::kOk;
  }

  int size() const { return n_; }
  static constexpr int capacity() { return Capacity; }
  double x_min() const { return n_ > 0 ? x_[0] : 0.0; }
  double x_max() const { return n_ > 0 ? x_[n_ - 1] : 0.0; }
  double knot_x(int i) const { return x_[i]; }
  double knot_y(int i) const { return y_[i]; }
  double knot_second_derivative(int i) const { return y2_[i]; }

  // Interval j with x_j <= xq <= x_{j+1} (clamped), using and updating the cached hint.
  int interval(double xq) const {
    hint_ = bracket_index(x_, n_, xq, hint_);
    return hint_;
  }
  // Same, with a caller-owned hint (thread-safe for concurrent const readers).
  int interval(double xq, int* hint) const {
    const int j = bracket_index(x_, n_, xq, hint != nullptr ? *hint : -1);
    if (hint != nullptr) *hint = j;
    return j;
  }

  // (4.4); linear extrapolation with the end slope outside [x_min, x_max]. Returns 0 if not fitted.
  double value(double xq) const { return eval_value(xq, interval(xq)); }
  double value(double xq, int* hint) const { return eval_value(xq, interval(xq, hint)); }
  // dy/dx of (4.4); constant end slope outside the knots.
  double derivative(double xq) const { return eval_derivative(xq, interval(xq)); }
  double derivative(double xq, int* hint) const { return eval_derivative(xq, interval(xq, hint)); }
  // d2y/dx2, linear between knots; zero outside (natural end conditions + linear extrapolation).
  double second_derivative(double xq) const { return eval_second(xq, interval(xq)); }
  double second_derivative(double xq, int* hint) const { return eval_second(xq, interval(xq, hint)); }

 private:
  double slope_in(int j, double xq) const {
    const double h = x_[j + 1] - x_[j];
    const double a = (x_[j + 1] - xq) / h;  // (4.2)
    const double b = 1.0 - a;               // (4.3)
    return (y_[j + 1] - y_[j]) / h - (3.0 * a * a - 1.0) / 6.0 * h * y2_[j] + (3.0 * b * b - 1.0) / 6.0 * h * y2_[j + 1];
  }
  double eval_value(double xq, int j) const {
    if (n_ < 2) return 0.0;
    if (xq < x_[0]) return y_[0] + slope_in(0, x_[0]) * (xq - x_[0]);
    if (xq > x_[n_ - 1]) return y_[n_ - 1] + slope_in(n_ - 2, x_[n_ - 1]) * (xq - x_[n_ - 1]);
    const double h = x_[j + 1] - x_[j];
    const double a = (x_[j + 1] - xq) / h;               // (4.2)
    const double b = 1.0 - a;                            // (4.3)
    const double c = (a * a * a - a) * h * h / 6.0;      // (4.5)
    const double d = (b * b * b - b) * h * h / 6.0;      // (4.6)
    return a * y_[j] + b * y_[j + 1] + c * y2_[j] + d * y2_[j + 1];  // (4.4)
  }
  double eval_derivative(double xq, int j) const {
    if (n_ < 2) return 0.0;
    if (xq < x_[0]) return slope_in(0, x_[0]);
    if (xq > x_[n_ - 1]) return slope_in(n_ - 2, x_[n_ - 1]);
    return slope_in(j, xq);
  }
  double eval_second(double xq, int j) const {
    if (n_ < 2) return 0.0;
    if (xq < x_[0] || xq > x_[n_ - 1]) return 0.0;
    const double a = (x_[j + 1] - xq) / (x_[j + 1] - x_[j]);
    return a * y2_[j] + (1.0 - a) * y2_[j + 1];
  }

  double x_[Capacity] = {};
  double y_[Capacity] = {};
  double y2_[Capacity] = {};
  double work_[Capacity] = {};
  int n_ = 0;
  mutable int hint_ = 0;
};

}  // namespace reentry::numerics
