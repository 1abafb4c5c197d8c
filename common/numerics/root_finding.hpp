#pragma once
// Scalar root finders (thesis sec. 4.2): the secant method (4.9), its bracketed variant (false position
// with the Illinois modification, as suggested in sec. 4.2 when the secant converges poorly) and
// Brent's method. Every loop is bounded by max_iter; failures are reported through NumStatus.
// "iterations" counts function evaluations after the initial ones at the end points / guesses.

#include <cmath>
#include <limits>

#include "numerics/status.hpp"

namespace reentry::numerics {

struct RootResult {
  double x;        // best root estimate
  double f;        // f(x)
  int iterations;  // iterations performed
  NumStatus status;
};

namespace detail {
inline bool valid_root_inputs(double a, double b, double x_tol, int max_iter) {
  return std::isfinite(a) && std::isfinite(b) && x_tol > 0.0 && std::isfinite(x_tol) && max_iter >= 1;
}

// Common start of the bracketing methods: checks the inputs, evaluates f at both ends and
// decides the cases that need no iteration (invalid input, non-finite value, a root at an
// end point, no sign change). Returns true with `early` set when the caller is done.
template <class F>
bool bracket_check(F& f, double a, double b, double x_tol, int max_iter, double& fa, double& fb, RootResult& early) {
  if (!valid_root_inputs(a, b, x_tol, max_iter)) {
    early = {a, 0.0, 0, NumStatus::kInvalidInput};
    return true;
  }
  fa = f(a);
  fb = f(b);
  if (!std::isfinite(fa)) early = {a, fa, 0, NumStatus::kNonFinite};
  else if (!std::isfinite(fb)) early = {b, fb, 0, NumStatus::kNonFinite};
  else if (fa == 0.0) early = {a, fa, 0, NumStatus::kOk};
  else if (fb == 0.0) early = {b, fb, 0, NumStatus::kOk};
  else if ((fa > 0.0) == (fb > 0.0))
    early = {(std::fabs(fa) < std::fabs(fb)) ? a : b, std::fmin(std::fabs(fa), std::fabs(fb)), 0, NumStatus::kNoBracket};
  else return false;
  return true;
}
}  // namespace detail

// Brent's method (inverse quadratic interpolation / secant / bisection) on a bracket [a, b].
// Converged when the bracket half-width is below 0.5 * x_tol + 2 eps |x| or |f(x)| <= f_tol
// (f_tol = 0: only an exact zero).
template <class F>
RootResult brent(F&& f, double a, double b, double x_tol, int max_iter, double f_tol = 0.0) {
  double fa = 0.0, fb = 0.0;
  RootResult early{};
  if (detail::bracket_check(f, a, b, x_tol, max_iter, fa, fb, early)) return early;
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  double c = a;
  double fc = fa;
  double d = b - a;
  double e = d;
  for (int it = 1; it <= max_iter; ++it) {
    if ((fb > 0.0) == (fc > 0.0)) {  // keep the root between b and c
      c = a;
      fc = fa;
      d = b - a;
      e = d;
    }
    if (std::fabs(fc) < std::fabs(fb)) {  // b is the best estimate
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = 2.0 * kEps * std::fabs(b) + 0.5 * x_tol;
    const double m = 0.5 * (c - b);
    if (std::fabs(m) <= tol || std::fabs(fb) <= f_tol) return {b, fb, it - 1, NumStatus::kOk};
    if (std::fabs(e) >= tol && std::fabs(fa) > std::fabs(fb)) {
      double p = 0.0;
      double q = 0.0;
      const double s = fb / fa;
      if (a == c) {  // secant step
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {  // inverse quadratic interpolation
        const double qa = fa / fc;
        const double r = fb / fc;
        p = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
        q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) {
        q = -q;
      } else {
        p = -p;
      }
      if (2.0 * p < std::fmin(3.0 * m * q - std::fabs(tol * q), std::fabs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += (std::fabs(d) > tol) ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
    if (!std::isfinite(fb)) return {b, fb, it, NumStatus::kNonFinite};
  }
  return {b, fb, max_iter, NumStatus::kMaxIterations};
}

// False position with the Illinois modification on a bracket [a, b]: the retained end point's function
// value is halved when the same end is kept twice, which gives superlinear convergence.
// Converged when |x_k - x_{k-1}| <= x_tol, the bracket is narrower than x_tol, or f(x_k) == 0.
template <class F>
RootResult bracketed_secant(F&& f, double a, double b, double x_tol, int max_iter) {
  double fa = 0.0, fb = 0.0;
  RootResult early{};
  if (detail::bracket_check(f, a, b, x_tol, max_iter, fa, fb, early)) return early;
  double x_prev = (std::fabs(fa) < std::fabs(fb)) ? a : b;
  double f_prev = (std::fabs(fa) < std::fabs(fb)) ? fa : fb;
  int side = 0;  // +1: b was retained last time, -1: a was retained last time
  for (int it = 1; it <= max_iter; ++it) {
    double x = (a * fb - b * fa) / (fb - fa);  // secant through the bracket ends, cf. (4.9)
    if (!(x > std::fmin(a, b) && x < std::fmax(a, b))) x = 0.5 * (a + b);  // guard against round-off
    const double fx = f(x);
    if (!std::isfinite(fx)) return {x, fx, it, NumStatus::kNonFinite};
    if (fx == 0.0) return {x, fx, it, NumStatus::kOk};
    if ((fx > 0.0) == (fa > 0.0)) {  // root in [x, b]: replace a, b retained
      a = x;
      fa = fx;
      if (side == +1) fb *= 0.5;  // Illinois
      side = +1;
    } else {  // root in [a, x]: replace b, a retained
      b = x;
      fb = fx;
      if (side == -1) fa *= 0.5;  // Illinois
      side = -1;
    }
    const bool small_step = std::fabs(x - x_prev) <= x_tol;
    const bool small_bracket = std::fabs(b - a) <= x_tol;
    x_prev = x;
    f_prev = fx;
    if (small_step || small_bracket) return {x, fx, it, NumStatus::kOk};
  }
  return {x_prev, f_prev, max_iter, NumStatus::kMaxIterations};
}

// Plain secant method (4.9): x_{i+1} = x_i - f(x_i) (x_i - x_{i-1}) / (f(x_i) - f(x_{i-1})).
// Converged when |x_{i+1} - x_i| <= x_tol (thesis criterion) or f == 0. No bracket is needed, so
// convergence is not guaranteed; a flat secant (f(x_i) == f(x_{i-1}) != 0) returns kNonFinite.
template <class F>
RootResult secant(F&& f, double x0, double x1, double x_tol, int max_iter) {
  if (!detail::valid_root_inputs(x0, x1, x_tol, max_iter) || x0 == x1) return {x1, 0.0, 0, NumStatus::kInvalidInput};
  double f0 = f(x0);
  double f1 = f(x1);
  if (!std::isfinite(f0)) return {x0, f0, 0, NumStatus::kNonFinite};
  if (!std::isfinite(f1)) return {x1, f1, 0, NumStatus::kNonFinite};
  if (f1 == 0.0) return {x1, f1, 0, NumStatus::kOk};
  if (f0 == 0.0) return {x0, f0, 0, NumStatus::kOk};
  for (int it = 1; it <= max_iter; ++it) {
    const double df = f1 - f0;
    if (df == 0.0) return {x1, f1, it - 1, NumStatus::kNonFinite};
    const double x2 = x1 - f1 * (x1 - x0) / df;  // (4.9)
    if (!std::isfinite(x2)) return {x1, f1, it, NumStatus::kNonFinite};
    const double f2 = f(x2);
    if (!std::isfinite(f2)) return {x2, f2, it, NumStatus::kNonFinite};
    const double step = std::fabs(x2 - x1);
    x0 = x1;
    f0 = f1;
    x1 = x2;
    f1 = f2;
    if (step <= x_tol || f1 == 0.0) return {x1, f1, it, NumStatus::kOk};
  }
  return {x1, f1, max_iter, NumStatus::kMaxIterations};
}

}  // namespace reentry::numerics
