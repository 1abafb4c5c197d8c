#include "environment/atmosphere.hpp"

#include "environment/interpolation.hpp"
#include "reentry/config/environment_files.hpp"

#include <cmath>
#include <random>

namespace reentry::truth {
namespace {
void set_error(std::string* error, const std::string& msg) {
  if (error) *error = msg;
}
constexpr double kTwoPi = 6.283185307179586;
}  // namespace

std::optional<Atmosphere> Atmosphere::create(AtmosphereModel model, const std::string& us76_table_file,
                                             std::string* error) {
  Atmosphere a;
  a.model_ = model;
  if (model == AtmosphereModel::kExponential) return a;
  config::AtmosphereTable table;
  const std::string err = config::read_atmosphere_table(us76_table_file, table);
  if (!err.empty()) {
    set_error(error, err);
    return std::nullopt;
  }
  for (std::size_t i = 0; i < table.h_m.size(); ++i) {
    a.h_m_.push_back(table.h_m[i]);
    a.ln_rho_.push_back(std::log(table.density_kgpm3[i]));
    a.ln_p_.push_back(std::log(table.pressure_Pa[i]));
    a.t_K_.push_back(table.temperature_K[i]);
  }
  // Density and pressure fall off exponentially: a cubic spline of the values would
  // overshoot and could go negative between nodes; a spline of the logarithm interpolates
  // the local scale height smoothly and is exact for an isothermal layer.
  a.ln_rho_m2_ = detail::natural_spline_moments(a.h_m_, a.ln_rho_);
  a.ln_p_m2_ = detail::natural_spline_moments(a.h_m_, a.ln_p_);
  a.t_m2_ = detail::natural_spline_moments(a.h_m_, a.t_K_);
  return a;
}

void Atmosphere::set_density_dispersion(double scale, double perturbation_amplitude, double correlation_length_m,
                                        uint64_t seed) {
  density_scale_ = scale;
  perturbation_amplitude_ = perturbation_amplitude;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double length = correlation_length_m > 0.0 ? correlation_length_m : 10000.0;
  for (int k = 0; k < kModes; ++k) {
    // wavelengths log-uniform in [L/2, 2L]
    const double wavelength = length * std::pow(2.0, 2.0 * unit(rng) - 1.0);
    wavenumber_radpm_[k] = kTwoPi / wavelength;
    phase_rad_[k] = kTwoPi * unit(rng);
  }
}

}  // namespace reentry::truth
