#include "environment/gravity.hpp"

#include "environment/earth.hpp"
#include "reentry/config/environment_files.hpp"

#include <cmath>

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
  config::GravityCoefficients coeff;
  const std::string err = config::read_gravity_coefficients(egm96_file, degree_order, coeff);
  if (!err.empty()) {
    set_error(error, err);
    return std::nullopt;
  }
  return from_coefficients(coeff.mu_m3ps2, coeff.radius_m, degree_order, coeff.c, coeff.s, error);
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
