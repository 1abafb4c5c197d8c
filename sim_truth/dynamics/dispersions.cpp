#include "dynamics/dispersions.hpp"

#include <boost/math/special_functions/erf.hpp>

#include <cmath>
#include <random>

namespace reentry::truth {

double uniform_01(std::uint64_t raw) {
  constexpr double kTwoToMinus53 = 1.0 / 9007199254740992.0;  // 2^-53
  return static_cast<double>(raw >> 11) * kTwoToMinus53;
}

namespace {
// Uniform in [-half_width, +half_width] (closed up to rounding), one engine output per call.
double symmetric(std::mt19937_64& engine, double half_width) {
  return half_width * (2.0 * uniform_01(engine()) - 1.0);
}

// One engine output per quantity whatever its distribution, so a seed gives the same quantile
// of every quantity in the uniform and the Gaussian set (runs compare one to one).
double centred(std::mt19937_64& engine, const config::Dispersion& q) {
  if (q.distribution == config::Distribution::kUniform) return symmetric(engine, q.value);
  return q.value / 3.0 * truncated_standard_normal(uniform_01(engine()));
}
}  // namespace

double truncated_standard_normal(double u) {
  // Inverse CDF of N(0, 1) restricted to [-3, 3]: Phi(z) = Phi(-3) + u (Phi(3) - Phi(-3)), which
  // with Phi(z) = (1 + erf(z / sqrt 2)) / 2 is erf(z / sqrt 2) = (2u - 1) erf(3 / sqrt 2).
  const double erf3 = std::erf(3.0 / std::sqrt(2.0));
  const double x = (2.0 * u - 1.0) * erf3;  // |x| < erf3 < 1: inside erf_inv's domain
  return std::sqrt(2.0) * boost::math::erf_inv(x);
}

DispersionDraw draw_dispersions(const config::Dispersions& w, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  DispersionDraw d;
  d.seed = seed;
  d.dispersed = true;
  // Fixed draw order: never reorder, or every recorded seed changes meaning.
  d.entry_flight_path_rad = centred(engine, w.entry_flight_path_rad);
  d.entry_heading_rad = centred(engine, w.entry_heading_rad);
  d.entry_velocity_mps = centred(engine, w.entry_velocity_mps);
  d.entry_latitude_rad = centred(engine, w.entry_position_rad);
  d.entry_longitude_rad = centred(engine, w.entry_position_rad);
  d.density_scale = 1.0 + centred(engine, w.density_scale);
  d.density_perturbation = w.density_perturbation;
  d.density_correlation_m = w.density_correlation_m;
  d.density_seed = engine();
  d.cl_scale = 1.0 + centred(engine, w.cl_scale);
  d.cd_scale = 1.0 + centred(engine, w.cd_scale);
  d.mass_scale = 1.0 + centred(engine, w.mass_scale);
  const double u_wind = uniform_01(engine());
  if (w.wind_scale_distribution == config::Distribution::kUniform) {
    d.wind_scale = w.wind_scale_min + (w.wind_scale_max - w.wind_scale_min) * u_wind;
  } else {
    d.wind_scale = 0.5 * (w.wind_scale_min + w.wind_scale_max) +
                   (w.wind_scale_max - w.wind_scale_min) / 6.0 * truncated_standard_normal(u_wind);
  }
  return d;
}

}  // namespace reentry::truth
