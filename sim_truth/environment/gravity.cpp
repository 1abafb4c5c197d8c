#include "environment/gravity.hpp"

#include "environment/earth.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace reentry::truth {
namespace {

void set_error(std::string* error, const std::string& msg) {
  if (error) *error = msg;
}

// Normalisation N_nm = sqrt((2 - delta_m0)(2n + 1)(n - m)! / (n + m)!): C_nm = N_nm * Cbar_nm.
double normalisation(int n, int m) {
  double ratio = 1.0;  // (n - m)! / (n + m)!
  for (int k = n - m + 1; k <= n + m; ++k) ratio /= static_cast<double>(k);
  return std::sqrt((m == 0 ? 1.0 : 2.0) * (2.0 * n + 1.0) * ratio);
}

}  // namespace

std::optional<Gravity> Gravity::from_coefficients(double mu_m3ps2, double radius_m, int degree,
                                                  const std::vector<std::vector<double>>& c_nm,
                                                  const std::vector<std::vector<double>>& s_nm,
                                                  std::string* error) {
  if (!(mu_m3ps2 > 0.0) || !(radius_m > 0.0) || degree < 0 || degree > kMaxDegree) {
    set_error(error, "gravity: invalid mu, radius or degree");
    return std::nullopt;
  }
  Gravity g;
  g.model_ = GravityModel::kSphericalHarmonics;
  g.mu_m3ps2_ = mu_m3ps2;
  g.radius_m_ = radius_m;
  g.degree_ = degree;
  const int stride = degree + 3;
  g.c_.assign(static_cast<size_t>(stride * stride), 0.0);
  g.s_.assign(static_cast<size_t>(stride * stride), 0.0);
  g.c_[0] = 1.0;  // central term
  for (int n = 1; n <= degree; ++n) {
    for (int m = 0; m <= n; ++m) {
      const double cbar = (n < static_cast<int>(c_nm.size()) && m < static_cast<int>(c_nm[n].size())) ? c_nm[n][m] : 0.0;
      const double sbar = (n < static_cast<int>(s_nm.size()) && m < static_cast<int>(s_nm[n].size())) ? s_nm[n][m] : 0.0;
      if (!std::isfinite(cbar) || !std::isfinite(sbar)) {
        set_error(error, "gravity: non-finite coefficient at n=" + std::to_string(n) + " m=" + std::to_string(m));
        return std::nullopt;
      }
      const double nn = normalisation(n, m);
      g.c_[n * stride + m] = nn * cbar;
      g.s_[n * stride + m] = nn * sbar;
    }
  }
  return g;
}

std::optional<Gravity> Gravity::create(GravityModel model, const std::string& egm96_file, int degree_order,
                                       std::string* error) {
  if (model != GravityModel::kSphericalHarmonics) {
    Gravity g;
    g.model_ = model;
    g.mu_m3ps2_ = EarthConstants::kMu_m3ps2;
    g.radius_m_ = EarthConstants::kEquatorialRadius_m;
    g.degree_ = model == GravityModel::kJ2J4 ? 4 : 0;
    return g;
  }
  if (degree_order < 2 || degree_order > kMaxDegree) {
    set_error(error, egm96_file + ": degree/order " + std::to_string(degree_order) + " outside [2, " + std::to_string(kMaxDegree) + "]");
    return std::nullopt;
  }
  std::ifstream in(egm96_file);
  if (!in) {
    set_error(error, egm96_file + ": cannot open");
    return std::nullopt;
  }
  std::string line;
  int line_no = 0;
  double mu = 0.0, radius = 0.0;
  std::vector<std::vector<double>> c(degree_order + 1), s(degree_order + 1);
  for (int n = 0; n <= degree_order; ++n) {
    c[n].assign(n + 1, 0.0);
    s[n].assign(n + 1, 0.0);
  }
  std::vector<std::vector<bool>> seen(degree_order + 1);
  for (int n = 0; n <= degree_order; ++n) seen[n].assign(n + 1, false);
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '%' || line[0] == '#') continue;
    std::istringstream ls(line);
    if (!header) {
      if (!(ls >> mu >> radius) || !(mu > 0.0) || !(radius > 0.0) || !std::isfinite(mu) || !std::isfinite(radius)) {
        set_error(error, egm96_file + ":" + std::to_string(line_no) + ": expected 'mu R' (positive), got '" + line + "'");
        return std::nullopt;
      }
      header = true;
      continue;
    }
    int n = 0, m = 0;
    double cv = 0.0, sv = 0.0;
    if (!(ls >> n >> m >> cv >> sv) || n < 0 || m < 0 || m > n || !std::isfinite(cv) || !std::isfinite(sv)) {
      set_error(error, egm96_file + ":" + std::to_string(line_no) + ": expected 'n m C S' with 0 <= m <= n, got '" + line + "'");
      return std::nullopt;
    }
    if (n > degree_order) continue;
    c[n][m] = cv;
    s[n][m] = sv;
    seen[n][m] = true;
  }
  if (!header) {
    set_error(error, egm96_file + ": empty file (no 'mu R' line)");
    return std::nullopt;
  }
  for (int n = 2; n <= degree_order; ++n) {
    for (int m = 0; m <= n; ++m) {
      if (!seen[n][m]) {
        set_error(error, egm96_file + ": missing coefficient n=" + std::to_string(n) + " m=" + std::to_string(m));
        return std::nullopt;
      }
    }
  }
  return from_coefficients(mu, radius, degree_order, c, s, error);
}

double Gravity::potential(const Eigen::Vector3d& r_R) const {
  const double r = r_R.norm();
  if (model_ == GravityModel::kCentral) return mu_m3ps2_ / r;
  if (model_ == GravityModel::kSphericalHarmonics) return potential_harmonics(r_R);
  const double s = r_R.z() / r, q = radius_m_ / r, s2 = s * s;
  const double p2 = 0.5 * (3.0 * s2 - 1.0);
  const double p3 = 0.5 * (5.0 * s2 - 3.0) * s;
  const double p4 = (35.0 * s2 * s2 - 30.0 * s2 + 3.0) / 8.0;
  return mu_m3ps2_ / r * (1.0 - kJ2 * q * q * p2 - kJ3 * q * q * q * p3 - kJ4 * q * q * q * q * p4);  // (2.14)
}

double Gravity::potential_harmonics(const Eigen::Vector3d& r_R) const {
  constexpr int kWork = (kMaxDegree + 3) * (kMaxDegree + 3);
  double v[kWork];
  double w[kWork];
  const int stride = degree_ + 3;
  detail::fill_vw<double>(r_R, radius_m_, degree_, stride, v, w);
  double u = 0.0;
  for (int n = 0; n <= degree_; ++n) {
    for (int m = 0; m <= n; ++m) u += c_[n * stride + m] * v[n * stride + m] + s_[n * stride + m] * w[n * stride + m];
  }
  return mu_m3ps2_ / radius_m_ * u;
}

}  // namespace reentry::truth
