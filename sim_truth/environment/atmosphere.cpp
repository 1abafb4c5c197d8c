#include "environment/atmosphere.hpp"

#include "environment/interpolation.hpp"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

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
  std::ifstream in(us76_table_file);
  if (!in) {
    set_error(error, us76_table_file + ": cannot open");
    return std::nullopt;
  }
  std::string line;
  int line_no = 0;
  std::vector<double> rho, p;
  while (std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '%') continue;
    std::istringstream ls(line);
    double h = 0.0, d = 0.0, pr = 0.0, t = 0.0;
    const std::string where = us76_table_file + ":" + std::to_string(line_no) + ": ";
    if (!(ls >> h >> d >> pr >> t)) {
      set_error(error, where + "expected 'altitude density pressure temperature', got '" + line + "'");
      return std::nullopt;
    }
    if (!std::isfinite(h) || !(d > 0.0) || !(pr > 0.0) || !(t > 0.0) || !std::isfinite(d) || !std::isfinite(pr) ||
        !std::isfinite(t)) {
      set_error(error, where + "density, pressure and temperature must be finite and positive, got '" + line + "'");
      return std::nullopt;
    }
    if (!a.h_m_.empty() && !(h > a.h_m_.back())) {
      set_error(error, where + "altitude " + std::to_string(h) + " m not strictly increasing");
      return std::nullopt;
    }
    a.h_m_.push_back(h);
    a.ln_rho_.push_back(std::log(d));
    a.ln_p_.push_back(std::log(pr));
    a.t_K_.push_back(t);
  }
  if (a.h_m_.size() < 3) {
    set_error(error, us76_table_file + ": fewer than 3 data rows");
    return std::nullopt;
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
