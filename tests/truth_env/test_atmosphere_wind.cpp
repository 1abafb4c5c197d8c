// Atmosphere against an independent US76 layer-equation evaluator; wind against the file; the
// HORUS mission's TAEM alpha against the altitude window the layer equations leave.
#include "environment/atmosphere.hpp"
#include "environment/wind.hpp"
#include "reentry/config/mission.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace rt = reentry::truth;

namespace {
const std::string kUs76 = std::string(REENTRY_CONFIG_DIR) + "/environment/us76.dat";
const std::string kWind = std::string(REENTRY_CONFIG_DIR) + "/environment/earthgram_nominal_wind.txt";

// US Standard Atmosphere 1976, layers below 86 km: geopotential base heights (m') and
// molecular-temperature lapse rates (K/m'), hydrostatic pressure, ideal gas.
struct Us76Truth {
  double temperature_K, pressure_Pa, density_kgpm3;
};
constexpr double kR0_m = 6356766.0;
constexpr double kG0 = 9.80665, kRstar = 8314.32, kM0 = 28.9644;
Us76Truth us76_layers_geopotential(double h_gp_m) {
  const double hb[] = {0.0, 11000.0, 20000.0, 32000.0, 47000.0, 51000.0, 71000.0, 84852.0};
  const double lapse[] = {-0.0065, 0.0, 0.001, 0.0028, 0.0, -0.0028, -0.002};
  const double gmr = kG0 * kM0 / kRstar;  // 0.034163195 K/m
  double t = 288.15, p = 101325.0;
  int layer = 0;
  for (; layer < 6 && h_gp_m > hb[layer + 1]; ++layer) {
    const double dh = hb[layer + 1] - hb[layer];
    const double t1 = t + lapse[layer] * dh;
    p = lapse[layer] == 0.0 ? p * std::exp(-gmr * dh / t) : p * std::pow(t / t1, gmr / lapse[layer]);
    t = t1;
  }
  const double dh = h_gp_m - hb[layer];
  const double t1 = t + lapse[layer] * dh;
  p = lapse[layer] == 0.0 ? p * std::exp(-gmr * dh / t) : p * std::pow(t / t1, gmr / lapse[layer]);
  return {t1, p, p * kM0 / (kRstar * t1)};
}
double geometric_from_geopotential(double h_m) { return kR0_m * h_m / (kR0_m - h_m); }
}  // namespace

TEST(Us76Truth, LayerEvaluatorReproducesPublishedValues) {
  // Guard on the independent evaluator itself (standard's tabulated values).
  const auto a = us76_layers_geopotential(11000.0);
  EXPECT_NEAR(a.temperature_K, 216.65, 1e-9);
  EXPECT_NEAR(a.pressure_Pa / 22632.06 - 1.0, 0.0, 2e-6);
  EXPECT_NEAR(a.density_kgpm3 / 0.3639178 - 1.0, 0.0, 2e-6);
  const auto b = us76_layers_geopotential(20000.0);
  EXPECT_NEAR(b.pressure_Pa / 5474.889 - 1.0, 0.0, 2e-6);
  EXPECT_NEAR(b.density_kgpm3 / 0.0880348 - 1.0, 0.0, 5e-6);
  const auto c = us76_layers_geopotential(32000.0);
  EXPECT_NEAR(c.temperature_K, 228.65, 1e-9);
  EXPECT_NEAR(c.pressure_Pa / 868.0187 - 1.0, 0.0, 2e-6);
  EXPECT_NEAR(us76_layers_geopotential(47000.0).pressure_Pa / 110.906 - 1.0, 0.0, 1e-5);
  EXPECT_NEAR(us76_layers_geopotential(51000.0).pressure_Pa / 66.9388 - 1.0, 0.0, 1e-5);
  EXPECT_NEAR(us76_layers_geopotential(71000.0).pressure_Pa / 3.95642 - 1.0, 0.0, 1e-5);
  EXPECT_NEAR(us76_layers_geopotential(71000.0).temperature_K, 214.65, 1e-9);
}

TEST(Atmosphere, Us76TableMatchesLayerEquations) {
  std::string err;
  auto atm = rt::Atmosphere::create(rt::AtmosphereModel::kUS76, kUs76, &err);
  ASSERT_TRUE(atm.has_value()) << err;
  const double heights_gp_m[] = {0.0, 1234.0, 5000.0, 11000.0, 15500.0, 20000.0, 26789.0, 32000.0,
                                 40050.0, 47000.0, 51000.0, 60321.0, 71000.0, 78000.0, 84000.0};
  double worst_rho = 0.0, worst_p = 0.0, worst_t = 0.0;
  for (double hg : heights_gp_m) {
    const auto truth = us76_layers_geopotential(hg);
    const auto s = atm->at(geometric_from_geopotential(hg));
    worst_rho = std::fmax(worst_rho, std::fabs(s.density_kgpm3 / truth.density_kgpm3 - 1.0));
    worst_p = std::fmax(worst_p, std::fabs(s.pressure_Pa / truth.pressure_Pa - 1.0));
    worst_t = std::fmax(worst_t, std::fabs(s.temperature_K / truth.temperature_K - 1.0));
    EXPECT_NEAR(s.speed_of_sound_mps, std::sqrt(1.4 * 287.05287 * s.temperature_K), 1e-9);
  }
  EXPECT_LT(worst_rho, 1e-3);
  EXPECT_LT(worst_p, 1e-3);
  EXPECT_LT(worst_t, 1e-3);
  std::printf("[figure] US76 vs layer equations (15 altitudes 0-84 km): max rel err rho %.2e p %.2e T %.2e\n",
              worst_rho, worst_p, worst_t);
}

TEST(Atmosphere, Us76ContinuousUpTo120km) {
  auto atm = rt::Atmosphere::create(rt::AtmosphereModel::kUS76, kUs76);
  ASSERT_TRUE(atm.has_value());
  // Value and slope of ln(rho), ln(p) and T continuous across the 100 m -> 1 km step at 100 km.
  auto ln_rho = [&](double h) { return std::log(atm->at(h).density_kgpm3); };
  auto ln_p = [&](double h) { return std::log(atm->at(h).pressure_Pa); };
  auto temp = [&](double h) { return atm->at(h).temperature_K; };
  const double h0 = 100000.0, d = 1.0;
  for (auto f : {std::function<double(double)>(ln_rho), std::function<double(double)>(ln_p)}) {
    const double left_slope = (f(h0) - f(h0 - d)) / d, right_slope = (f(h0 + d) - f(h0)) / d;
    EXPECT_NEAR(right_slope / left_slope - 1.0, 0.0, 1e-3);
    EXPECT_NEAR(f(h0 + 1e-6) - f(h0 - 1e-6), 0.0, 1e-9);
  }
  EXPECT_NEAR((temp(h0 + d) - temp(h0)) - (temp(h0) - temp(h0 - d)), 0.0, 1e-3);
  // No jumps anywhere: density strictly decreasing and step-to-step change bounded by the
  // local scale height (H > 4 km below 120 km).
  double prev = ln_rho(0.0);
  for (double h = 10.0; h <= 120000.0; h += 10.0) {
    const double cur = ln_rho(h);
    EXPECT_LT(cur, prev);
    EXPECT_LT(prev - cur, 10.0 / 4000.0) << h;
    prev = cur;
  }
  // Above the top and below the bottom: finite, documented behaviour.
  const auto high = atm->at(1.2e6), top = atm->at(1.0e6);
  EXPECT_LT(high.density_kgpm3, top.density_kgpm3);
  EXPECT_GT(high.density_kgpm3, 0.0);
  EXPECT_DOUBLE_EQ(high.temperature_K, top.temperature_K);
  EXPECT_DOUBLE_EQ(atm->at(-10000.0).density_kgpm3, atm->at(-5000.0).density_kgpm3);
}

TEST(Atmosphere, ExponentialModel) {
  auto atm = rt::Atmosphere::create(rt::AtmosphereModel::kExponential, "");
  ASSERT_TRUE(atm.has_value());
  EXPECT_DOUBLE_EQ(atm->at(0.0).density_kgpm3, 1.225);
  EXPECT_NEAR(atm->at(7050.0).density_kgpm3, 1.225 / std::exp(1.0), 1e-15);  // (2.20)
  EXPECT_NEAR(atm->at(70500.0).density_kgpm3, 1.225 * std::exp(-10.0), 1e-18);
  EXPECT_NEAR(atm->at(50000.0).speed_of_sound_mps, 340.293988026089, 1e-9);
  EXPECT_NEAR(atm->at(0.0).pressure_Pa, 1.225 * 287.05287 * 288.15, 1e-9);
}

TEST(Atmosphere, DensityDispersion) {
  auto atm = rt::Atmosphere::create(rt::AtmosphereModel::kUS76, kUs76);
  ASSERT_TRUE(atm.has_value());
  auto nominal = *atm;
  atm->set_density_dispersion(1.1, 0.0, 10000.0, 7);
  EXPECT_NEAR(atm->at(40000.0).density_kgpm3 / nominal.at(40000.0).density_kgpm3, 1.1, 1e-12);
  atm->set_density_dispersion(1.0, 0.2, 10000.0, 7);
  auto other = nominal;
  other.set_density_dispersion(1.0, 0.2, 10000.0, 8);
  double max_ratio_dev = 0.0, max_step = 0.0, seed_diff = 0.0;
  double prev = atm->perturbation(0.0);
  for (double h = 0.0; h <= 120000.0; h += 100.0) {
    const double p = atm->perturbation(h);
    EXPECT_LE(std::fabs(p), 1.0);
    max_step = std::fmax(max_step, std::fabs(p - prev));
    prev = p;
    max_ratio_dev = std::fmax(max_ratio_dev, std::fabs(atm->at(h).density_kgpm3 / nominal.at(h).density_kgpm3 - 1.0));
    seed_diff = std::fmax(seed_diff, std::fabs(p - other.perturbation(h)));
    EXPECT_NEAR(atm->at(h).density_kgpm3 / nominal.at(h).density_kgpm3, 1.0 + 0.2 * p, 1e-12);
  }
  EXPECT_LE(max_ratio_dev, 0.2 + 1e-12);
  EXPECT_GT(max_ratio_dev, 0.05);
  EXPECT_LT(max_step, 2.0 * M_PI * 100.0 / 5000.0);  // smooth: slope bounded by the shortest wavelength L/2
  EXPECT_GT(seed_diff, 0.1);                         // seeds give different profiles
}

TEST(Atmosphere, BadTableReportsFileAndLine) {
  const std::string path = ::testing::TempDir() + "bad_us76.dat";
  std::ofstream(path) << "% comment\n0 1.225 101325 288.15\n100 -1 100000 288\n";
  std::string err;
  EXPECT_FALSE(rt::Atmosphere::create(rt::AtmosphereModel::kUS76, path, &err).has_value());
  EXPECT_NE(err.find(path + ":3"), std::string::npos) << err;
}

TEST(Wind, ReproducesTableNodes) {
  std::string err;
  auto wind = rt::Wind::create(kWind, &err);
  ASSERT_TRUE(wind.has_value()) << err;
  std::ifstream in(kWind);
  std::string line;
  std::getline(in, line);  // header: Time Hgtkm ... EWmean(7) NSmean(8)
  int rows = 0;
  double worst = 0.0;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<double> v;
    double x;
    while (ls >> x) v.push_back(x);
    if (v.size() < 9) continue;
    const Eigen::Vector3d w = wind->velocity_V(v[1] * 1000.0);
    worst = std::fmax(worst, std::fabs(w.x() - v[8]) + std::fabs(w.y() - v[7]) + std::fabs(w.z()));
    ++rows;
  }
  EXPECT_GT(rows, 300);
  EXPECT_LT(worst, 1e-9);
  // Surface row of the file: EWmean 0.63 (+east), NSmean 0.84 (+north)
  const Eigen::Vector3d w0 = wind->velocity_V(0.0);
  EXPECT_NEAR(w0.x(), 0.84, 1e-12);
  EXPECT_NEAR(w0.y(), 0.63, 1e-12);
  // Between nodes the spline stays between plausible bounds (no overshoot blow-up).
  const Eigen::Vector3d mid = wind->velocity_V(250.0);
  EXPECT_NEAR(mid.x(), 0.5 * (0.84 + 0.82), 0.05);
  wind->set_scale(2.0);
  EXPECT_NEAR(wind->velocity_V(0.0).x(), 1.68, 1e-12);
  wind->set_scale(0.0);
  EXPECT_EQ(wind->velocity_V(30000.0).norm(), 0.0);
  EXPECT_EQ(rt::Wind::disabled().velocity_V(30000.0).norm(), 0.0);
}

TEST(Wind, BadFileReportsFileAndLine) {
  const std::string path = ::testing::TempDir() + "bad_wind.txt";
  std::ofstream(path) << "Hgtkm EWmean NSmean\n0 1 2\n1 abc 3\n";
  std::string err;
  EXPECT_FALSE(rt::Wind::create(path, &err).has_value());
  EXPECT_NE(err.find(path + ":3"), std::string::npos) << err;
  const std::string path2 = ::testing::TempDir() + "bad_wind2.txt";
  std::ofstream(path2) << "Hgtkm EWmean\n0 1\n";
  EXPECT_FALSE(rt::Wind::create(path2, &err).has_value());
  EXPECT_NE(err.find("NSmean"), std::string::npos) << err;
}

TEST(Us76Truth, HorusTaemAlphaLeavesAnAltitudeWindowWiderThanTheEndGameScatter) {
  // Mission design check (config/missions/horus.toml, [alpha_profile] note): at the TAEM
  // energy, q*alpha <= its limit at the profile's TAEM alpha bounds the altitude from below
  // and Mach >= mach_target - mach_tol from above. With the US76 layer equations (not the
  // table the models read) and the energy E = V^2/2 - mu/r on the ellipsoid, that window must
  // be wider than the dispersed end-game altitude scatter (sd 0.4 km, three sd: 1.2 km); a
  // 20 deg TAEM alpha would leave 0.57 km.
  const reentry::config::LoadResult loaded = reentry::config::load_mission("horus");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  const auto& m = loaded.mission;
  constexpr double kMu = 3.986004418e14, kReq = 6378137.0, kFlattening = 1.0 / 298.257223563;
  const double r_surface = kReq * (1.0 - kFlattening * std::pow(std::sin(m.taem.latitude_rad), 2));
  const double e_taem = 0.5 * m.taem.velocity_mps * m.taem.velocity_mps - kMu / (r_surface + m.taem.altitude_m);
  const double e_entry = 0.5 * m.entry.velocity_mps * m.entry.velocity_mps - kMu / (kReq + m.entry.altitude_m);
  // Normalised as the guidance does: energies above the -mu/R_eq reference.
  const double e_norm = (e_taem + kMu / kReq) / (e_entry + kMu / kReq);
  const auto& x = m.alpha_profile.x;
  const auto& y = m.alpha_profile.y;
  ASSERT_GE(x.size(), 2u);
  std::size_t k = 1;
  while (k + 1 < x.size() && x[k] < e_norm) ++k;
  const double alpha_taem = y[k - 1] + (y[k] - y[k - 1]) * (e_norm - x[k - 1]) / (x[k] - x[k - 1]);
  double lowest = 1e9, highest = -1e9;
  // Inside the mission's TAEM altitude band.
  const double band_m = m.taem.altitude_tol_m;
  for (double h = m.taem.altitude_m - band_m; h <= m.taem.altitude_m + band_m; h += 10.0) {
    const double v = std::sqrt(2.0 * (e_taem + kMu / (r_surface + h)));
    const Us76Truth air = us76_layers_geopotential(kR0_m * h / (kR0_m + h));
    const double q = 0.5 * air.density_kgpm3 * v * v;
    const double mach = v / std::sqrt(1.4 * 287.05287 * air.temperature_K);
    if (q * alpha_taem <= m.constraints.q_alpha_max_Pa_rad && mach >= m.taem.mach_target - m.taem.mach_tol) {
      lowest = std::fmin(lowest, h);
      highest = std::fmax(highest, h);
    }
  }
  EXPECT_GT(highest - lowest, 1200.0) << "window " << lowest << " .. " << highest << " m at alpha "
                                      << alpha_taem * 180.0 / M_PI << " deg";
}
