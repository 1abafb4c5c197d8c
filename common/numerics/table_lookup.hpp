#pragma once
// Table look-up helpers: bisection search with hint (thesis sec. 4.1), linear and bilinear
// interpolation with clamping at the table edges. Allocation-free, no exceptions.
// Abscissae must be strictly increasing and n >= 2 (n == 1 is tolerated: index 0 is returned).

namespace reentry::numerics {

// Index j with x[j] <= xq <= x[j+1], clamped to [0, n-2] (xq below x[0] -> 0, above x[n-1] -> n-2);
// inside the table x[j] <= xq < x[j+1] (a knot belongs to the interval it starts), hint or not.
// If hint is a valid index its interval and the neighbouring ones are tried first, otherwise bisection
// is used (bounded by ceil(log2 n) + 1 iterations). NaN xq returns 0.
int bracket_index(const double* x, int n, double xq, int hint = -1);

// Piecewise-linear interpolation (4.1)-(4.3); clamps to y[0] / y[n-1] outside the table.
// hint (optional) is read as the starting interval and updated with the interval used.
double linear(const double* x, const double* y, int n, double xq, int* hint = nullptr);

// Bilinear interpolation on a rectangular grid; v is row-major with x as the major (slow) index:
// v[i * ny + j] = f(x[i], y[j]). Query coordinates are clamped to the grid edges.
double bilinear(const double* x, int nx, const double* y, int ny, const double* v_rowmajor_x_major,
                double xq, double yq, int* hint_x = nullptr, int* hint_y = nullptr);

}  // namespace reentry::numerics
