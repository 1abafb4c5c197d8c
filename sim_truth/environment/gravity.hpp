// Gravity models of the truth simulator (thesis 2.2): central, J2-J4 zonal (2.16)-(2.17),
// and EGM96 spherical harmonics to degree/order 20 (fully normalised coefficients).
#pragma once

#include <Eigen/Dense>

#include <optional>
#include <string>
#include <vector>

#include "environment/scalar.hpp"
#include "physics/earth_constants.hpp"

namespace reentry::truth {

enum class GravityModel { kCentral, kJ2J4, kSphericalHarmonics };

class Gravity {
 public:
  static constexpr int kMaxDegree = 40;
  // Zonal coefficients J_n = -sqrt(2n+1) C_n0 (EGM96).
  static constexpr double kJ2 = 1.0826267e-3;
  static constexpr double kJ3 = -2.5326565e-6;
  static constexpr double kJ4 = -1.6196216e-6;

  /// Build a gravity model. The EGM96 file (first line: mu R; then "n m C S" per line,
  /// fully normalised) is read only for kSphericalHarmonics (and may be empty otherwise).
  /// Returns nullopt and fills *error (naming file and line) on bad data.
  static std::optional<Gravity> create(GravityModel model, const std::string& egm96_file,
                                       int degree_order = 20, std::string* error = nullptr);

  /// Build a spherical-harmonics model from explicit fully normalised coefficients
  /// (c_nm[n][m], s_nm[n][m], n = 0..degree); used for tests (e.g. zonal-only sets).
  static std::optional<Gravity> from_coefficients(double mu_m3ps2, double radius_m, int degree,
                                                  const std::vector<std::vector<double>>& c_nm,
                                                  const std::vector<std::vector<double>>& s_nm,
                                                  std::string* error = nullptr);

  /// Gravitational acceleration in the Earth-fixed frame R (no centrifugal term).
  Eigen::Vector3d acceleration_R(const Eigen::Vector3d& r_R) const { return acceleration_R<double>(r_R); }
  /// The same model, scalar-generic (environment/scalar.hpp).
  template <class T>
  Eigen::Matrix<T, 3, 1> acceleration_R(const Eigen::Matrix<T, 3, 1>& r_R) const;

  /// Gravitational potential U (acceleration = grad U), same model.
  double potential(const Eigen::Vector3d& r_R) const;

  GravityModel model() const { return model_; }
  int degree() const { return degree_; }

 private:
  Gravity() = default;
  template <class T>
  Eigen::Matrix<T, 3, 1> acceleration_harmonics(const Eigen::Matrix<T, 3, 1>& r_R) const;
  double potential_harmonics(const Eigen::Vector3d& r_R) const;

  GravityModel model_ = GravityModel::kCentral;
  double mu_m3ps2_ = physics::kMuEarth_m3ps2;
  double radius_m_ = physics::kEarthEquatorialRadius_m;
  int degree_ = 0;
  // Un-normalised coefficients, index n*(degree+3)+m, for the Cunningham V/W recursion.
  // Evaluation uses a stack workspace (no allocation, thread-safe).
  std::vector<double> c_, s_;
};

namespace detail {
// Cunningham / Montenbruck-Gill (3.29)-(3.33) recursion for V_nm, W_nm up to degree n_max + 1.
template <class T>
void fill_vw(const Eigen::Matrix<T, 3, 1>& r_R, double radius, int n_max, int stride, T* v, T* w) {
  using std::sqrt;
  const T r2 = r_R.squaredNorm();
  const T rho = radius * radius / r2;
  const T x0 = radius * r_R.x() / r2, y0 = radius * r_R.y() / r2, z0 = radius * r_R.z() / r2;
  const int nm1 = n_max + 1;
  v[0] = radius / sqrt(r2);
  w[0] = T(0.0);
  for (int m = 0; m <= nm1; ++m) {
    if (m > 0) {
      const T vp = v[(m - 1) * stride + m - 1], wp = w[(m - 1) * stride + m - 1];
      v[m * stride + m] = (2.0 * m - 1.0) * (x0 * vp - y0 * wp);
      w[m * stride + m] = (2.0 * m - 1.0) * (x0 * wp + y0 * vp);
    }
    if (m + 1 <= nm1) {
      v[(m + 1) * stride + m] = (2.0 * m + 1.0) * z0 * v[m * stride + m];
      w[(m + 1) * stride + m] = (2.0 * m + 1.0) * z0 * w[m * stride + m];
    }
    for (int n = m + 2; n <= nm1; ++n) {
      v[n * stride + m] = ((2.0 * n - 1.0) * z0 * v[(n - 1) * stride + m] - (n + m - 1.0) * rho * v[(n - 2) * stride + m]) / (n - m);
      w[n * stride + m] = ((2.0 * n - 1.0) * z0 * w[(n - 1) * stride + m] - (n + m - 1.0) * rho * w[(n - 2) * stride + m]) / (n - m);
    }
  }
}

// V/W workspace: on the stack for double (no allocation in the simulator); on the heap for AD
// scalars, which are too large for a (kMaxDegree + 3)^2 stack array.
template <class T, int kWork>
struct HarmonicsWork {
  std::vector<T> v, w;
  explicit HarmonicsWork(int n) : v(static_cast<size_t>(n)), w(static_cast<size_t>(n)) {}
};
template <int kWork>
struct HarmonicsWork<double, kWork> {
  double v[kWork];
  double w[kWork];
  explicit HarmonicsWork(int) {}
};
}  // namespace detail

template <class T>
Eigen::Matrix<T, 3, 1> Gravity::acceleration_R(const Eigen::Matrix<T, 3, 1>& r_R) const {
  using std::sqrt;
  const T r2 = r_R.squaredNorm();
  const T r = sqrt(r2);
  if (model_ == GravityModel::kCentral) return -mu_m3ps2_ / (r2 * r) * r_R;  // (2.19)
  if (model_ == GravityModel::kSphericalHarmonics) return acceleration_harmonics(r_R);
  // (2.16)-(2.17): radial (outward) and latitudinal (northward) components; the csc(delta)
  // of the J3 term is multiplied out so that the poles are regular.
  const T s = r_R.z() / r;
  const T q = radius_m_ / r;
  const T g0 = mu_m3ps2_ / r2;
  const T s2 = s * s;
  const T g_radial = -g0 * (1.0 - 1.5 * kJ2 * q * q * (3.0 * s2 - 1.0)
                            - 2.0 * kJ3 * q * q * q * s * (5.0 * s2 - 3.0)
                            - 0.625 * kJ4 * q * q * q * q * (35.0 * s2 * s2 - 30.0 * s2 + 3.0));
  // g_delta = -3 g0 q^2 cos(delta) [J2 s + J3 q (5 s^2 - 1)/2 + 5/6 J4 q^2 s (7 s^2 - 3)]
  const T bracket = kJ2 * s + 0.5 * kJ3 * q * (5.0 * s2 - 1.0) + (5.0 / 6.0) * kJ4 * q * q * s * (7.0 * s2 - 3.0);
  const T g_north_over_cos = -3.0 * g0 * q * q * bracket;
  // cos(delta) * i_north = (-s x / r, -s y / r, cos^2(delta))
  const Eigen::Matrix<T, 3, 1> cos_north(-s * r_R.x() / r, -s * r_R.y() / r, 1.0 - s2);
  return g_radial * r_R / r + g_north_over_cos * cos_north;
}

template <class T>
Eigen::Matrix<T, 3, 1> Gravity::acceleration_harmonics(const Eigen::Matrix<T, 3, 1>& r_R) const {
  constexpr int kWork = (kMaxDegree + 3) * (kMaxDegree + 3);
  const int stride = degree_ + 3;
  detail::HarmonicsWork<T, kWork> work(stride * stride);
  T* v = &work.v[0];
  T* w = &work.w[0];
  detail::fill_vw(r_R, radius_m_, degree_, stride, v, w);
  T ax = T(0.0), ay = T(0.0), az = T(0.0);
  for (int m = 0; m <= degree_; ++m) {
    for (int n = m; n <= degree_; ++n) {
      const double c = c_[n * stride + m], s = s_[n * stride + m];
      if (m == 0) {
        ax -= c * v[(n + 1) * stride + 1];
        ay -= c * w[(n + 1) * stride + 1];
        az += (n + 1.0) * (-c * v[(n + 1) * stride] - s * w[(n + 1) * stride]);
      } else {
        const double fac = 0.5 * (n - m + 1.0) * (n - m + 2.0);
        const T vp = v[(n + 1) * stride + m + 1], wp = w[(n + 1) * stride + m + 1];
        const T vm = v[(n + 1) * stride + m - 1], wm = w[(n + 1) * stride + m - 1];
        ax += 0.5 * (-c * vp - s * wp) + fac * (c * vm + s * wm);
        ay += 0.5 * (-c * wp + s * vp) + fac * (-c * wm + s * vm);
        az += (n - m + 1.0) * (-c * v[(n + 1) * stride + m] - s * w[(n + 1) * stride + m]);
      }
    }
  }
  const double k = mu_m3ps2_ / (radius_m_ * radius_m_);
  return Eigen::Matrix<T, 3, 1>(k * ax, k * ay, k * az);
}

}  // namespace reentry::truth
