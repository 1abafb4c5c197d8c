// Atmosphere models of the truth simulator (thesis 2.3): US Standard Atmosphere 1976
// from the tabulated file, and the exponential model (2.20).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "environment/interpolation.hpp"
#include "environment/scalar.hpp"

namespace reentry::truth {

template <class T>
struct AtmosphereSampleT {
  T density_kgpm3 = T(0.0);
  T pressure_Pa = T(0.0);
  T temperature_K = T(0.0);
  T speed_of_sound_mps = T(0.0);
};
using AtmosphereSample = AtmosphereSampleT<double>;

enum class AtmosphereModel { kUS76, kExponential };

class Atmosphere {
 public:
  static constexpr double kGamma = 1.4;
  static constexpr double kGasConstant_JpkgK = 287.05287;
  // Exponential model (2.20).
  static constexpr double kRho0_kgpm3 = 1.225;
  static constexpr double kScaleHeight_m = 7050.0;   // beta = 1 / 7050 m
  static constexpr double kExponentialTemperature_K = 288.15;  // isothermal (documented choice)

  /// US76: reads the table (geometric altitude m, density, pressure, temperature; '%' comments).
  /// The exponential model ignores the file. nullopt + *error (file and line) on bad data.
  static std::optional<Atmosphere> create(AtmosphereModel model, const std::string& us76_table_file,
                                          std::string* error = nullptr);

  /// Sample at geometric altitude. US76: natural cubic splines on ln(rho), ln(p) and on T.
  /// Outside the table: below the bottom, values at the bottom; above the top, ln(rho) and
  /// ln(p) extrapolated linearly (exponential decay with the top-node slope), T held.
  AtmosphereSample at(double altitude_m) const { return at<double>(altitude_m); }
  /// The same model, scalar-generic (environment/scalar.hpp).
  template <class T>
  AtmosphereSampleT<T> at(const T& altitude_m) const;

  /// Density dispersion: rho *= scale * (1 + amplitude * p(h)), p a smooth seeded function
  /// of altitude in [-1, 1] (sum of random-phase sinusoids with wavelengths around
  /// correlation_length_m). scale = 1, amplitude = 0 restores the nominal model.
  void set_density_dispersion(double scale, double perturbation_amplitude,
                              double correlation_length_m, uint64_t seed);

  /// The perturbation shape p(h) in [-1, 1] (0 when no dispersion is set).
  double perturbation(double altitude_m) const { return perturbation<double>(altitude_m); }
  template <class T>
  T perturbation(const T& altitude_m) const;

  AtmosphereModel model() const { return model_; }

 private:
  Atmosphere() = default;
  static constexpr int kModes = 4;
  AtmosphereModel model_ = AtmosphereModel::kExponential;
  std::vector<double> h_m_;
  std::vector<double> ln_rho_, ln_rho_m2_;  // values and spline second derivatives
  std::vector<double> ln_p_, ln_p_m2_;
  std::vector<double> t_K_, t_m2_;
  double density_scale_ = 1.0;
  double perturbation_amplitude_ = 0.0;
  double wavenumber_radpm_[kModes] = {0.0, 0.0, 0.0, 0.0};
  double phase_rad_[kModes] = {0.0, 0.0, 0.0, 0.0};
};

template <class T>
AtmosphereSampleT<T> Atmosphere::at(const T& altitude_m) const {
  using std::exp;
  using std::sqrt;
  AtmosphereSampleT<T> s;
  if (model_ == AtmosphereModel::kExponential) {
    s.density_kgpm3 = kRho0_kgpm3 * exp(-altitude_m / kScaleHeight_m);  // (2.20)
    s.temperature_K = T(kExponentialTemperature_K);
    s.pressure_Pa = s.density_kgpm3 * kGasConstant_JpkgK * s.temperature_K;  // ideal gas, isothermal
  } else {
    // Below the table bottom: values at the bottom. Above the top: ln(rho), ln(p) continue
    // linearly (exponential decay with the top scale height), temperature held.
    const T h = scalar::fmax(altitude_m, h_m_.front());
    s.density_kgpm3 = exp(detail::spline_eval(h_m_, ln_rho_, ln_rho_m2_, h));
    s.pressure_Pa = exp(detail::spline_eval(h_m_, ln_p_, ln_p_m2_, h));
    s.temperature_K = detail::spline_eval(h_m_, t_K_, t_m2_, scalar::fmin(h, h_m_.back()));
  }
  if (perturbation_amplitude_ != 0.0 || density_scale_ != 1.0) {
    s.density_kgpm3 *= density_scale_ * (1.0 + perturbation_amplitude_ * perturbation(altitude_m));
  }
  s.speed_of_sound_mps = sqrt(kGamma * kGasConstant_JpkgK * s.temperature_K);
  return s;
}

template <class T>
T Atmosphere::perturbation(const T& altitude_m) const {
  using std::sin;
  if (perturbation_amplitude_ == 0.0) return T(0.0);
  T p = T(0.0);
  for (int k = 0; k < kModes; ++k) p += sin(wavenumber_radpm_[k] * altitude_m + phase_rad_[k]);
  return p / kModes;  // equal weights: |p| <= 1
}

}  // namespace reentry::truth
