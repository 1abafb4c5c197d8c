// The environment data files a mission names ([environment]): their formats and the rules a
// file must meet, in one place. The loader reads every named file with these readers (so a
// mission it accepts has usable data whatever model a run selects), and the truth simulator
// builds its models from what the same readers return: the two cannot disagree on what is
// valid. Every error names the file, the line and the value.
#pragma once

#include <string>
#include <vector>

namespace reentry::config {

/// Degree and order of the spherical-harmonic gravity field the simulator flies (sh20) and the
/// loader checks the coefficient file for.
inline constexpr int kGravityFileDegree = 20;
/// Largest wind component a profile may hold [m/s]: above the strongest measured winds of the
/// upper atmosphere (about 200 m/s in the thermosphere); a larger value is a broken file.
inline constexpr double kWindComponentMax_mps = 300.0;
/// Largest scaled wind [m/s] (file component times the dispersion's wind_scale_max).
inline constexpr double kScaledWindMax_mps = 1000.0;

/// EGM96-style file: a 'mu R' line, then 'n m C S' lines (fully normalised), '%' or '#'
/// comments. c[n][m], s[n][m] for n <= degree; every (n, m) with 2 <= n <= degree present.
struct GravityCoefficients {
  double mu_m3ps2 = 0.0;
  double radius_m = 0.0;
  std::vector<std::vector<double>> c, s;
};
std::string read_gravity_coefficients(const std::string& path, int degree, GravityCoefficients& out);

/// Earth-GRAM style profile: a header naming Hgtkm, EWmean and NSmean (and Wmean or UDmean,
/// +up, if present), then one row per altitude. Rows sorted by altitude, no duplicates.
struct WindProfile {
  std::vector<double> h_m, north_mps, east_mps, up_mps;
};
std::string read_wind_profile(const std::string& path, WindProfile& out);

/// US76 table: rows "altitude_m density_kgpm3 pressure_Pa temperature_K" ('%' comments),
/// altitude strictly increasing, the others finite and positive, at least 3 rows.
struct AtmosphereTable {
  std::vector<double> h_m, density_kgpm3, pressure_Pa, temperature_K;
};
std::string read_atmosphere_table(const std::string& path, AtmosphereTable& out);

}  // namespace reentry::config
