// Small interpolation helpers of the truth simulator: natural cubic spline (fit allocates
// at construction; evaluation does not, and is scalar-generic), bracketing, bilinear lookup
// (scalar-generic) and a Brent root finder.
// The truth keeps its own copies so that it shares no numerical code path with the
// flight models it judges.
#pragma once

#include <cmath>
#include <vector>

#include "environment/scalar.hpp"

namespace reentry::truth::detail {

/// Index j with x[j] <= xq <= x[j+1], clamped to [0, n-2] (bisection). n >= 2.
inline int bracket(const double* x, int n, double xq) {
  if (xq <= x[0]) return 0;
  if (xq >= x[n - 1]) return n - 2;
  int lo = 0;
  int hi = n - 1;
  while (hi - lo > 1) {  // bounded: halves every pass
    const int mid = (lo + hi) / 2;
    if (x[mid] <= xq) lo = mid; else hi = mid;
  }
  return lo;
}

/// Natural cubic spline second derivatives M (M_0 = M_{n-1} = 0), tridiagonal solve.
inline std::vector<double> natural_spline_moments(const std::vector<double>& x, const std::vector<double>& y) {
  const int n = static_cast<int>(x.size());
  std::vector<double> m(n, 0.0);
  if (n < 3) return m;
  std::vector<double> c(n, 0.0), d(n, 0.0);
  for (int i = 1; i < n - 1; ++i) {
    const double h0 = x[i] - x[i - 1];
    const double h1 = x[i + 1] - x[i];
    const double a = h0 / 6.0, b = (h0 + h1) / 3.0, cc = h1 / 6.0;
    const double rhs = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
    const double denom = b - a * c[i - 1];
    c[i] = cc / denom;
    d[i] = (rhs - a * d[i - 1]) / denom;
  }
  for (int i = n - 2; i >= 1; --i) m[i] = d[i] - c[i] * m[i + 1];
  return m;
}

/// The spline's value for an AD query: value, slope and curvature at the query's value, the
/// derivatives by the chain rule (scalar::chain; the same function as spline_eval's own).
template <class T>
T spline_chain(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& m, const T& xq) {
  const int n = static_cast<int>(x.size());
  const double xv = scalar::value(xq);
  const int j = bracket(x.data(), n, xv);
  const double h = x[j + 1] - x[j];
  if (xv < x[0] || xv > x[n - 1]) {
    const bool low = xv < x[0];
    const int k = low ? 0 : n - 1;
    const double slope = low ? (y[1] - y[0]) / h - h * (2.0 * m[0] + m[1]) / 6.0
                             : (y[n - 1] - y[n - 2]) / h + h * (m[n - 2] + 2.0 * m[n - 1]) / 6.0;
    return scalar::chain(xq, y[k] + slope * (xv - x[k]), slope, 0.0);
  }
  const double a = (x[j + 1] - xv) / h, b = (xv - x[j]) / h;
  const double f = a * y[j] + b * y[j + 1] + ((a * a * a - a) * m[j] + (b * b * b - b) * m[j + 1]) * h * h / 6.0;
  const double d1 = (y[j + 1] - y[j]) / h + h * ((3.0 * b * b - 1.0) * m[j + 1] - (3.0 * a * a - 1.0) * m[j]) / 6.0;
  return scalar::chain(xq, f, d1, a * m[j] + b * m[j + 1]);
}

/// Spline value (derivative when want_slope) at xq inside [x0, x_{n-1}]; outside, linear
/// extrapolation with the end slope (a natural spline has zero curvature there). Scalar-generic
/// in the query (environment/scalar.hpp): the interval is chosen on the value of xq.
template <class T>
T spline_eval(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& m, const T& xq,
              bool want_slope = false) {
  if constexpr (!scalar::is_double<T>) {
    if (!want_slope) return spline_chain(x, y, m, xq);
  }
  const int n = static_cast<int>(x.size());
  const double xv = scalar::value(xq);
  const int j = bracket(x.data(), n, xv);
  const double h = x[j + 1] - x[j];
  if (xv < x[0] || xv > x[n - 1]) {
    const bool low = xv < x[0];
    const int k = low ? 0 : n - 1;
    const double slope = low ? (y[1] - y[0]) / h - h * (2.0 * m[0] + m[1]) / 6.0
                             : (y[n - 1] - y[n - 2]) / h + h * (m[n - 2] + 2.0 * m[n - 1]) / 6.0;
    return want_slope ? T(slope) : T(y[k] + slope * (xq - x[k]));
  }
  const T a = (x[j + 1] - xq) / h;
  const T b = (xq - x[j]) / h;
  if (want_slope) {
    return (y[j + 1] - y[j]) / h + h * ((3.0 * b * b - 1.0) * m[j + 1] - (3.0 * a * a - 1.0) * m[j]) / 6.0;
  }
  return a * y[j] + b * y[j + 1] + ((a * a * a - a) * m[j] + (b * b * b - b) * m[j + 1]) * h * h / 6.0;
}

/// Bilinear interpolation on a row-major (x-major) grid, clamped at the edges; scalar-generic
/// in the query point (the cell is chosen on its value).
template <class T>
T bilinear(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& v, const T& xq,
           const T& yq) {
  const int nx = static_cast<int>(x.size());
  const int ny = static_cast<int>(y.size());
  const T xc = scalar::fmin(scalar::fmax(xq, x.front()), x.back());
  const T yc = scalar::fmin(scalar::fmax(yq, y.front()), y.back());
  if (nx == 1 && ny == 1) return T(v[0]);
  const int i = nx > 1 ? bracket(x.data(), nx, scalar::value(xc)) : 0;
  const int j = ny > 1 ? bracket(y.data(), ny, scalar::value(yc)) : 0;
  const T tx = nx > 1 ? T((xc - x[i]) / (x[i + 1] - x[i])) : T(0.0);
  const T ty = ny > 1 ? T((yc - y[j]) / (y[j + 1] - y[j])) : T(0.0);
  const int i1 = nx > 1 ? i + 1 : i;
  const int j1 = ny > 1 ? j + 1 : j;
  const double v00 = v[i * ny + j], v01 = v[i * ny + j1], v10 = v[i1 * ny + j], v11 = v[i1 * ny + j1];
  return (1.0 - tx) * ((1.0 - ty) * v00 + ty * v01) + tx * ((1.0 - ty) * v10 + ty * v11);
}

struct BrentResult {
  double x;
  bool converged;
};

/// Brent's method on [a, b] with f(a) f(b) <= 0 (caller guarantees the bracket).
template <class F>
BrentResult brent(F&& f, double a, double b, double x_tol, int max_iter) {
  double fa = f(a), fb = f(b);
  if (fa == 0.0) return {a, true};
  if (fb == 0.0) return {b, true};
  if (fa * fb > 0.0) return {std::fabs(fa) < std::fabs(fb) ? a : b, false};
  double c = a, fc = fa, d = b - a, e = d;
  for (int it = 0; it < max_iter; ++it) {
    if (fb * fc > 0.0) { c = a; fc = fa; d = b - a; e = d; }
    if (std::fabs(fc) < std::fabs(fb)) { a = b; b = c; c = a; fa = fb; fb = fc; fc = fa; }
    const double tol = 2.0 * 2.2e-16 * std::fabs(b) + 0.5 * x_tol;
    const double xm = 0.5 * (c - b);
    if (std::fabs(xm) <= tol || fb == 0.0) return {b, true};
    if (std::fabs(e) >= tol && std::fabs(fa) > std::fabs(fb)) {
      const double s = fb / fa;
      double p, q;
      if (a == c) {
        p = 2.0 * xm * s; q = 1.0 - s;
      } else {
        const double qq = fa / fc, r = fb / fc;
        p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
        q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q; else p = -p;
      if (2.0 * p < std::fmin(3.0 * xm * q - std::fabs(tol * q), std::fabs(e * q))) { e = d; d = p / q; }
      else { d = xm; e = d; }
    } else {
      d = xm; e = d;
    }
    a = b; fa = fb;
    b += std::fabs(d) > tol ? d : (xm > 0.0 ? tol : -tol);
    fb = f(b);
  }
  return {b, false};
}

}  // namespace reentry::truth::detail
