// Wind profile of the truth simulator from an Earth-GRAM output (nominal mean winds).
#pragma once

#include <Eigen/Dense>

#include <optional>
#include <string>
#include <vector>

#include "environment/interpolation.hpp"
#include "environment/scalar.hpp"

namespace reentry::truth {

class Wind {
 public:
  /// Reads columns by header name: Hgtkm (km), EWmean (+east), NSmean (+north), and a
  /// vertical column (Wmean, +up) if present. nullopt + *error (file and line) on bad data.
  static std::optional<Wind> create(const std::string& earthgram_file, std::string* error = nullptr);

  /// A wind that is always zero.
  static Wind disabled();

  /// Wind velocity in the vertical frame V (north, east, down), natural cubic spline in
  /// altitude; outside the table the edge value is held. Zero when disabled.
  Eigen::Vector3d velocity_V(double altitude_m) const { return velocity_V<double>(altitude_m); }
  /// The same profile, scalar-generic (environment/scalar.hpp).
  template <class T>
  Eigen::Matrix<T, 3, 1> velocity_V(const T& altitude_m) const;

  /// Multiply the wind by `scale` (dispersions); 0 disables it.
  void set_scale(double scale) { scale_ = scale; }
  double scale() const { return scale_; }
  bool enabled() const { return enabled_; }

  /// Table nodes (altitude increasing), for checks.
  const std::vector<double>& altitudes_m() const { return h_m_; }

 private:
  Wind() = default;
  bool enabled_ = false;
  double scale_ = 1.0;
  std::vector<double> h_m_;
  std::vector<double> north_, north_m2_, east_, east_m2_, up_, up_m2_;
};

template <class T>
Eigen::Matrix<T, 3, 1> Wind::velocity_V(const T& altitude_m) const {
  if (!enabled_ || scale_ == 0.0) return Eigen::Matrix<T, 3, 1>::Zero();
  const T h = scalar::fmin(scalar::fmax(altitude_m, h_m_.front()), h_m_.back());
  const T north = detail::spline_eval(h_m_, north_, north_m2_, h);
  const T east = detail::spline_eval(h_m_, east_, east_m2_, h);
  const T down = -detail::spline_eval(h_m_, up_, up_m2_, h);
  return Eigen::Matrix<T, 3, 1>(scale_ * north, scale_ * east, scale_ * down);
}

}  // namespace reentry::truth
