// Bounded, allocation-free bracketed root finding (Brent) for the planner.
#pragma once

#include <cmath>

#include "guidance_types.hpp"

namespace reentry::fsw {

struct BracketedRoot {
  double x = 0.0;
  double f = 0.0;
  int iterations = 0;
  Status status = Status::kInvalidInput;
};

/// Brent's method on [a, b]. kNoBracket when f(a) f(b) > 0 (nothing else is returned),
/// kNonFinite on NaN, kMaxIterations when the bound is hit (x holds the best estimate).
/// Stops when |b - a| / 2 <= x_tol or |f| <= f_tol.
template <class F>
BracketedRoot brent_root(F&& f, double a, double b, double x_tol, double f_tol, int max_iter) {
  BracketedRoot out;
  double fa = f(a);
  double fb = f(b);
  if (!std::isfinite(fa) || !std::isfinite(fb)) { out.status = Status::kNonFinite; return out; }
  if (fa == 0.0) { out.x = a; out.f = 0.0; out.status = Status::kOk; return out; }
  if (fb == 0.0) { out.x = b; out.f = 0.0; out.status = Status::kOk; return out; }
  if ((fa > 0.0) == (fb > 0.0)) { out.status = Status::kNoBracket; return out; }
  double c = a, fc = fa, d = b - a, e = d;
  for (int it = 1; it <= max_iter; ++it) {
    if ((fb > 0.0) == (fc > 0.0)) { c = a; fc = fa; d = b - a; e = d; }
    if (std::fabs(fc) < std::fabs(fb)) { a = b; b = c; c = a; fa = fb; fb = fc; fc = fa; }
    const double tol = 2.0 * 2.2e-16 * std::fabs(b) + 0.5 * x_tol;
    const double m = 0.5 * (c - b);
    out.iterations = it;
    if (std::fabs(m) <= tol || std::fabs(fb) <= f_tol) {
      out.x = b; out.f = fb; out.status = Status::kOk; return out;
    }
    if (std::fabs(e) >= tol && std::fabs(fa) > std::fabs(fb)) {
      const double s = fb / fa;
      double p, q;
      if (a == c) {
        p = 2.0 * m * s; q = 1.0 - s;  // secant
      } else {
        const double qq = fa / fc, r = fb / fc;  // inverse quadratic interpolation
        p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
        q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q; else p = -p;
      if (2.0 * p < std::fmin(3.0 * m * q - std::fabs(tol * q), std::fabs(e * q))) { e = d; d = p / q; }
      else { d = m; e = m; }
    } else {
      d = m; e = m;
    }
    a = b; fa = fb;
    b += (std::fabs(d) > tol) ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
    if (!std::isfinite(fb)) { out.x = b; out.status = Status::kNonFinite; return out; }
  }
  out.x = b; out.f = fb; out.status = Status::kMaxIterations;
  return out;
}

}  // namespace reentry::fsw
