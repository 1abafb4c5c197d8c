// Gravity models of the truth simulator (thesis 2.2): central, J2-J4 zonal (2.16)-(2.17),
// and EGM96 spherical harmonics to degree/order 20 (fully normalised coefficients).
#pragma once

#include <Eigen/Dense>

#include <optional>
#include <string>
#include <vector>

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
  Eigen::Vector3d acceleration_R(const Eigen::Vector3d& r_R) const;

  /// Gravitational potential U (acceleration = grad U), same model.
  double potential(const Eigen::Vector3d& r_R) const;

  GravityModel model() const { return model_; }
  int degree() const { return degree_; }

 private:
  Gravity() = default;
  Eigen::Vector3d acceleration_harmonics(const Eigen::Vector3d& r_R) const;
  double potential_harmonics(const Eigen::Vector3d& r_R) const;

  GravityModel model_ = GravityModel::kCentral;
  double mu_m3ps2_ = 3.986004418e14;
  double radius_m_ = 6378137.0;
  int degree_ = 0;
  // Un-normalised coefficients, index n*(degree+3)+m, for the Cunningham V/W recursion.
  // Evaluation uses a stack workspace (no allocation, thread-safe).
  std::vector<double> c_, s_;
};

}  // namespace reentry::truth
