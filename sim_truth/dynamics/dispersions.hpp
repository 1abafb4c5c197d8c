// Monte Carlo dispersion draw for the truth simulator: one seed, one run, everywhere.
//
// Uniform variates come from std::mt19937_64 (whose output sequence the C++ standard fixes)
// through an explicit 53-bit mapping, not std::uniform_real_distribution (whose output is
// implementation-defined), so a seed reproduces a run bit for bit on any standard library.
#pragma once

#include <cstdint>

#include "reentry/config/mission.hpp"

namespace reentry::truth {

/// Offsets and factors applied to a nominal mission. Default-constructed: the nominal run.
struct DispersionDraw {
  std::uint64_t seed = 0;
  bool dispersed = false;                 // false: nominal (all offsets zero, factors one)
  double entry_flight_path_rad = 0.0;     // added to the entry gamma
  double entry_heading_rad = 0.0;         // added to the entry heading
  double entry_velocity_mps = 0.0;        // added to the entry ground speed
  double entry_latitude_rad = 0.0;        // added to the entry latitude
  double entry_longitude_rad = 0.0;       // added to the entry longitude
  double density_scale = 1.0;             // multiplies the density everywhere
  double density_perturbation = 0.0;      // amplitude of the altitude-correlated part (fraction)
  double density_correlation_m = 10000.0;
  std::uint64_t density_seed = 0;         // seed of the altitude-correlated perturbation
  double cl_scale = 1.0;
  double cd_scale = 1.0;
  double mass_scale = 1.0;
  double wind_scale = 1.0;
};

/// Uniform variate in [0, 1) from the top 53 bits of one mt19937_64 output.
double uniform_01(std::uint64_t raw);

/// Standard normal truncated at +-3 sigma at the quantile u in [0, 1) of the truncated
/// distribution (inverse CDF, Boost.Math erf_inv): u = 0.5 gives 0, u -> 0 / 1 gives -3 / +3.
double truncated_standard_normal(double u);

/// Draw every dispersed quantity of `set` with std::mt19937_64(seed), one engine output per
/// quantity in a fixed order (the order of the DispersionDraw fields). A uniform quantity with
/// half-width w is uniform in [-w, +w]; a Gaussian one with 3 sigma w is N(0, (w/3)^2)
/// truncated at +-w, by the inverse CDF of the same output (same seed, same quantile). The wind
/// scale is uniform in [wind_scale_min, wind_scale_max] or Gaussian about its centre with 3 sigma
/// at its ends; the density perturbation amplitude is the configured value, its realisation is
/// fixed by density_seed.
DispersionDraw draw_dispersions(const config::Dispersions& set, std::uint64_t seed);

}  // namespace reentry::truth
