#include "smooth_models.hpp"

#include <algorithm>

#include "environment/interpolation.hpp"

namespace reentry::optimal {

namespace {

// Slopes of the natural cubic spline through (x, y) at its nodes (zero for a single node).
std::vector<double> natural_spline_slopes(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  std::vector<double> d(n, 0.0);
  if (n < 2) return d;
  const std::vector<double> m = truth::detail::natural_spline_moments(x, y);
  for (size_t i = 0; i + 1 < n; ++i) {
    const double h = x[i + 1] - x[i];
    d[i] = (y[i + 1] - y[i]) / h - h * (2.0 * m[i] + m[i + 1]) / 6.0;
  }
  const double h = x[n - 1] - x[n - 2];
  d[n - 1] = (y[n - 1] - y[n - 2]) / h + h * (m[n - 2] + 2.0 * m[n - 1]) / 6.0;
  return d;
}

// Cubic Hermite basis on [0, 1] as coefficients of 1, s, s^2, s^3: values at 0 and 1 (h0, h1)
// and slopes at 0 and 1 (g0, g1) per unit of s.
constexpr double kHermite[4][4] = {
    {1.0, 0.0, -3.0, 2.0},   // h0
    {0.0, 0.0, 3.0, -2.0},   // h1
    {0.0, 1.0, -2.0, 1.0},   // g0
    {0.0, 0.0, -1.0, 1.0}};  // g1

// The axis with every interval divided into `parts` equal ones.
std::vector<double> refine(const std::vector<double>& axis, int parts) {
  std::vector<double> out;
  for (size_t i = 0; i + 1 < axis.size(); ++i)
    for (int k = 0; k < parts; ++k) out.push_back(axis[i] + (axis[i + 1] - axis[i]) * k / parts);
  out.push_back(axis.back());
  return out;
}

// The axis with every interval divided into equal ones of at most `step`.
std::vector<double> refine(const std::vector<double>& axis, double step) {
  std::vector<double> out;
  for (size_t i = 0; i + 1 < axis.size(); ++i) {
    const int parts = std::max(1, static_cast<int>(std::ceil((axis[i + 1] - axis[i]) / step - 1e-9)));
    for (int k = 0; k < parts; ++k) out.push_back(axis[i] + (axis[i + 1] - axis[i]) * k / parts);
  }
  out.push_back(axis.back());
  return out;
}

}  // namespace

SmoothPiecewiseLinear::SmoothPiecewiseLinear(const std::vector<double>& x, const std::vector<double>& y,
                                             double max_deviation) {
  const size_t n = std::min(x.size(), y.size());
  if (n == 0) return;
  has_value_ = true;
  y0_ = y[0];
  if (n == 1) return;
  // f = y0 + sum_k (s_k - s_{k-1}) w_k R((x - x_k) / w_k), slopes 0 outside [x_0, x_{n-1}].
  std::vector<double> slope(n + 1, 0.0);  // slope[k + 1]: interval k
  for (size_t k = 0; k + 1 < n; ++k) slope[k + 1] = (y[k + 1] - y[k]) / (x[k + 1] - x[k]);
  for (size_t k = 0; k < n; ++k) {
    const double jump = slope[k + 1] - slope[k];
    if (jump == 0.0) continue;
    const double left = k > 0 ? x[k] - x[k - 1] : x[1] - x[0];
    const double right = k + 1 < n ? x[k + 1] - x[k] : x[n - 1] - x[n - 2];
    corner_x_.push_back(x[k]);
    slope_jump_.push_back(jump);
    width_.push_back(std::min(0.25 * std::min(left, right), max_deviation / (smooth_ramp(0.0).r * std::fabs(jump))));
  }
  // The ramps are zero left of every window: y0 is the value at the far left.
}

Ramp BicubicSpline::clamp_axis(double q, const std::vector<double>& axis) {
  if (axis.size() < 2) return {axis.front(), 0.0, 0.0};
  const double first = axis[1] - axis[0], last = axis.back() - axis[axis.size() - 2];
  return smooth_clamp(q, axis.front(), axis.back(), kClampWindow * std::min(first, last));
}

truth::scalar::Taylor2 BicubicSpline::taylor(double xq, double yq, bool derivatives) const {
  const Ramp cx = clamp_axis(xq, x_), cy = clamp_axis(yq, y_);
  const int i = cell(x_, cx.r), j = cell(y_, cy.r);
  const double hx = x_.size() > 1 ? x_[i + 1] - x_[i] : 1.0, hy = y_.size() > 1 ? y_[j + 1] - y_[j] : 1.0;
  const double s = x_.size() > 1 ? (cx.r - x_[i]) / hx : 0.0, u = y_.size() > 1 ? (cy.r - y_[j]) / hy : 0.0;
  const std::array<double, 16>& a = coef_[static_cast<size_t>(i * ny_cells() + j)];
  if (!derivatives) {
    double f = 0.0;
    for (int p = 3; p >= 0; --p) {
      const double* c = &a[static_cast<size_t>(p * 4)];
      f = f * s + (c[0] + u * (c[1] + u * (c[2] + u * c[3])));
    }
    return {f, 0.0, 0.0, 0.0, 0.0, 0.0};
  }
  // Powers of s and u with their first and second derivatives.
  const double ps[4] = {1.0, s, s * s, s * s * s}, pu[4] = {1.0, u, u * u, u * u * u};
  const double ds[4] = {0.0, 1.0, 2.0 * s, 3.0 * s * s}, du[4] = {0.0, 1.0, 2.0 * u, 3.0 * u * u};
  const double d2s[4] = {0.0, 0.0, 2.0, 6.0 * s}, d2u[4] = {0.0, 0.0, 2.0, 6.0 * u};
  double f = 0.0, fs = 0.0, fu = 0.0, fss = 0.0, fsu = 0.0, fuu = 0.0;
  for (int p = 0; p < 4; ++p)
    for (int q = 0; q < 4; ++q) {
      const double c = a[static_cast<size_t>(p * 4 + q)];
      f += c * ps[p] * pu[q];
      fs += c * ds[p] * pu[q];
      fu += c * ps[p] * du[q];
      fss += c * d2s[p] * pu[q];
      fsu += c * ds[p] * du[q];
      fuu += c * ps[p] * d2u[q];
    }
  // Through the cell coordinates and the clamps to the queries.
  const double gx = cx.r1 / hx, gy = cy.r1 / hy;
  return {f,           fs * gx,      fu * gy, fss * gx * gx + fs * cx.r2 / hx, fsu * gx * gy,
          fuu * gy * gy + fu * cy.r2 / hy};
}

int BicubicSpline::cell(const std::vector<double>& axis, double q) {
  if (axis.size() < 2) return 0;
  return truth::detail::bracket(axis.data(), static_cast<int>(axis.size()), q);
}

BicubicSpline BicubicSpline::fit(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& v) {
  BicubicSpline b;
  b.x_ = x;
  b.y_ = y;
  const size_t nx = x.size(), ny = y.size();
  // Node values f, slopes fx (splines along x), fy (along y) and twists fxy (fx along y).
  std::vector<double> fx(nx * ny), fy(nx * ny), fxy(nx * ny);
  for (size_t j = 0; j < ny; ++j) {
    std::vector<double> col(nx);
    for (size_t i = 0; i < nx; ++i) col[i] = v[i * ny + j];
    const std::vector<double> d = natural_spline_slopes(x, col);
    for (size_t i = 0; i < nx; ++i) fx[i * ny + j] = d[i];
  }
  for (size_t i = 0; i < nx; ++i) {
    const std::vector<double> row(v.begin() + static_cast<long>(i * ny), v.begin() + static_cast<long>((i + 1) * ny));
    const std::vector<double> d = natural_spline_slopes(y, row);
    const std::vector<double> rx(fx.begin() + static_cast<long>(i * ny), fx.begin() + static_cast<long>((i + 1) * ny));
    const std::vector<double> dd = natural_spline_slopes(y, rx);
    for (size_t j = 0; j < ny; ++j) {
      fy[i * ny + j] = d[j];
      fxy[i * ny + j] = dd[j];
    }
  }
  const size_t cx = std::max<size_t>(1, nx - 1), cy = std::max<size_t>(1, ny - 1);
  b.coef_.assign(cx * cy, {});
  for (size_t i = 0; i < cx; ++i) {
    for (size_t j = 0; j < cy; ++j) {
      const size_t i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1);
      const double hx = nx > 1 ? x[i1] - x[i] : 0.0, hy = ny > 1 ? y[j1] - y[j] : 0.0;
      // Corner data per Hermite role (value 0/1, slope 0/1) in each direction, per unit cell.
      double g[4][4];
      const size_t ii[2] = {i, i1}, jj[2] = {j, j1};
      for (int a = 0; a < 4; ++a) {
        for (int c = 0; c < 4; ++c) {
          const size_t k = ii[a % 2] * ny + jj[c % 2];
          const bool dx = a >= 2, dy = c >= 2;
          g[a][c] = dx && dy ? fxy[k] * hx * hy : dx ? fx[k] * hx : dy ? fy[k] * hy : v[k];
        }
      }
      std::array<double, 16>& out = b.coef_[i * cy + j];
      for (int p = 0; p < 4; ++p)
        for (int q = 0; q < 4; ++q) {
          double sum = 0.0;
          for (int a = 0; a < 4; ++a)
            for (int c = 0; c < 4; ++c) sum += kHermite[a][p] * kHermite[c][q] * g[a][c];
          out[static_cast<size_t>(p * 4 + q)] = sum;
        }
    }
  }
  return b;
}

truth::AeroCoefficients SmoothAero::truth_coefficients(const truth::PointModel& model, double alpha, double mach,
                                                       double q) {
  return model.aero->coefficients(alpha, mach, q, model.trim, 1.0, 1.0);
}

SmoothAero::SmoothAero(const truth::PointModel& model) : cl_scale_(model.cl_scale), cd_scale_(model.cd_scale) {
  const config::AeroModel& m = model.aero->model();
  const bool trims = model.trim && model.aero->has_moment_data() && !m.surfaces.empty();
  trimmed_ = trims;
  blended_ = trims && m.q_flap_fixed_Pa > 0.0;
  q_switch_Pa_ = m.q_flap_fixed_Pa;
  auto sample = [&](const config::Table2D& grid, double q, bool lift) {
    const std::vector<double> alpha = refine(grid.alpha_rad, kAlphaSample_rad), mach = refine(grid.mach, kMachSubdivisions);
    std::vector<double> v(alpha.size() * mach.size());
    for (size_t i = 0; i < alpha.size(); ++i)
      for (size_t j = 0; j < mach.size(); ++j) {
        const truth::AeroCoefficients c = truth_coefficients(model, alpha[i], mach[j], q);
        v[i * mach.size() + j] = lift ? c.cl : c.cd;
      }
    return BicubicSpline::fit(alpha, mach, v);
  };
  // Above the switch (or without trim) the tables' own regime; below it the fixed flap.
  const double q_high = std::max(1e6, 10.0 * q_switch_Pa_);
  cl_ = sample(m.cl, q_high, true);
  cd_ = sample(m.cd, q_high, false);
  if (blended_) {
    cl_low_q_ = sample(m.cl, 0.0, true);
    cd_low_q_ = sample(m.cd, 0.0, false);
  }
}

}  // namespace reentry::optimal
