#include "dynamics/dispersions.hpp"

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
}  // namespace

DispersionDraw draw_dispersions(const config::Dispersions& w, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  DispersionDraw d;
  d.seed = seed;
  d.dispersed = true;
  // Fixed draw order: never reorder, or every recorded seed changes meaning.
  d.entry_flight_path_rad = symmetric(engine, w.entry_flight_path_rad);
  d.entry_heading_rad = symmetric(engine, w.entry_heading_rad);
  d.entry_velocity_mps = symmetric(engine, w.entry_velocity_mps);
  d.entry_latitude_rad = symmetric(engine, w.entry_position_rad);
  d.entry_longitude_rad = symmetric(engine, w.entry_position_rad);
  d.density_scale = 1.0 + symmetric(engine, w.density_scale);
  d.density_perturbation = w.density_perturbation;
  d.density_correlation_m = w.density_correlation_m;
  d.density_seed = engine();
  d.cl_scale = 1.0 + symmetric(engine, w.cl_scale);
  d.cd_scale = 1.0 + symmetric(engine, w.cd_scale);
  d.mass_scale = 1.0 + symmetric(engine, w.mass_scale);
  d.wind_scale = w.wind_scale_min + (w.wind_scale_max - w.wind_scale_min) * uniform_01(engine());
  return d;
}

}  // namespace reentry::truth
