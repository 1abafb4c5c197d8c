#include "numerics/table_lookup.hpp"

#include <cmath>

namespace reentry::numerics {

int bracket_index(const double* x, int n, double xq, int hint) {
  if (x == nullptr || n < 2) return 0;
  if (!(xq > x[0])) return 0;          // also catches NaN
  if (xq >= x[n - 1]) return n - 2;
  if (hint >= 0 && hint <= n - 2) {
    // Half-open intervals [x_j, x_{j+1}) so that the answer equals the bisection one exactly.
    if (x[hint] <= xq && xq < x[hint + 1]) return hint;
    if (hint + 1 <= n - 2 && x[hint + 1] <= xq && xq < x[hint + 2]) return hint + 1;
    if (hint - 1 >= 0 && x[hint - 1] <= xq && xq < x[hint]) return hint - 1;
  }
  // Bisection: invariant x[lo] < xq < x[hi]. Each pass halves hi - lo, so at most ~log2(n) passes.
  int lo = 0;
  int hi = n - 1;
  for (int guard = 0; guard < 64 && hi - lo > 1; ++guard) {
    const int mid = lo + (hi - lo) / 2;
    if (x[mid] <= xq) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

double linear(const double* x, const double* y, int n, double xq, int* hint) {
  if (x == nullptr || y == nullptr || n < 1) return 0.0;
  if (n == 1) return y[0];
  const int j = bracket_index(x, n, xq, hint != nullptr ? *hint : -1);
  if (hint != nullptr) *hint = j;
  if (!(xq > x[0])) return y[0];
  if (xq >= x[n - 1]) return y[n - 1];
  const double a = (x[j + 1] - xq) / (x[j + 1] - x[j]);  // (4.2)
  const double b = 1.0 - a;                              // (4.3)
  return a * y[j] + b * y[j + 1];                        // (4.1)
}

namespace {
// Clamped interval and weight of the upper node along one axis.
void axis_weight(const double* g, int n, double q, int* hint, int* j_out, double* w_out) {
  if (n < 2) {
    *j_out = 0;
    *w_out = 0.0;
    return;
  }
  const int j = bracket_index(g, n, q, hint != nullptr ? *hint : -1);
  if (hint != nullptr) *hint = j;
  double w = 0.0;
  if (!(q > g[0])) {
    w = 0.0;
  } else if (q >= g[n - 1]) {
    w = 1.0;
  } else {
    w = (q - g[j]) / (g[j + 1] - g[j]);
  }
  *j_out = j;
  *w_out = w;
}
}  // namespace

double bilinear(const double* x, int nx, const double* y, int ny, const double* v, double xq, double yq,
                int* hint_x, int* hint_y) {
  if (x == nullptr || y == nullptr || v == nullptr || nx < 1 || ny < 1) return 0.0;
  int i = 0;
  int j = 0;
  double wx = 0.0;
  double wy = 0.0;
  axis_weight(x, nx, xq, hint_x, &i, &wx);
  axis_weight(y, ny, yq, hint_y, &j, &wy);
  const int i1 = (nx >= 2) ? i + 1 : i;
  const int j1 = (ny >= 2) ? j + 1 : j;
  const double v00 = v[i * ny + j];
  const double v01 = v[i * ny + j1];
  const double v10 = v[i1 * ny + j];
  const double v11 = v[i1 * ny + j1];
  return (1.0 - wx) * ((1.0 - wy) * v00 + wy * v01) + wx * ((1.0 - wy) * v10 + wy * v11);
}

}  // namespace reentry::numerics
