// Mission loader tests. Expected values are the thesis's numbers (tables 3.1, 3.3) converted
// here independently with the exact unit definitions, not read back from the loader's files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "reentry/config/mission.hpp"
#include "temp_mission.hpp"

namespace {

using reentry_test::kConfigDir;
using reentry_test::replace_once;
using reentry_test::slurp;
using reentry_test::TempMission;

using reentry::config::load_mission;
using reentry::config::LoadResult;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
// Exact definitions: 1 BTU(IT) = 1055.05585262 J, 1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N.
constexpr double kFt = 0.3048;
constexpr double kBtuPerFt2s = 1055.05585262 / (kFt * kFt);
constexpr double kPsf = 4.4482216152605 / (kFt * kFt);

TEST(ConfigLoad, AllFourMissionsLoad) {
  for (const char* name : {"horus", "x33", "orbiter", "x38"}) {
    const LoadResult r = load_mission(name);
    EXPECT_TRUE(r.ok) << name << ": " << r.error;
    EXPECT_EQ(r.mission.name, name);
    EXPECT_FALSE(r.mission.vehicle.aero.cl.empty());
    EXPECT_FALSE(reentry::config::summary_line(r.mission).empty());
  }
}

TEST(ConfigLoad, X33MatchesThesisTable33) {
  const LoadResult r = load_mission("x33");
  ASSERT_TRUE(r.ok) << r.error;
  const auto& m = r.mission;
  EXPECT_NEAR(kBtuPerFt2s * 75.0, 851739.5, 0.1);  // the conversion itself
  EXPECT_NEAR(m.constraints.heat_flux_max_Wpm2, 75.0 * kBtuPerFt2s, 1e-2);
  EXPECT_NEAR(m.constraints.dynamic_pressure_max_Pa, 300.0 * kPsf, 1e-3);
  EXPECT_NEAR(m.constraints.dynamic_pressure_max_Pa, 14364.08, 0.01);
  EXPECT_NEAR(m.constraints.q_alpha_max_Pa_rad, 7000.0 * kPsf * kDeg, 1e-3);
  EXPECT_DOUBLE_EQ(m.constraints.load_factor_max_g, 3.0);
  EXPECT_NEAR(m.constraints.alpha_max_rad, 50.0 * kDeg, 1e-12);
  EXPECT_NEAR(m.constraints.sigma_rate_max_radps, 5.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(m.vehicle.mass_kg, 37650.0);
  EXPECT_DOUBLE_EQ(m.vehicle.reference_area_m2, 149.4);
  EXPECT_DOUBLE_EQ(m.entry.altitude_m, 120100.0);
  EXPECT_NEAR(m.entry.latitude_rad, -23.75 * kDeg, 1e-12);
  EXPECT_NEAR(m.entry.flight_path_rad, -1.249 * kDeg, 1e-12);
  EXPECT_NEAR(m.taem.longitude_rad, 279.5 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(m.taem.range_tol_m, 11000.0);
  EXPECT_DOUBLE_EQ(m.taem.altitude_tol_m, 1800.0);
  EXPECT_NEAR(m.taem.heading_tol_rad, 10.0 * kDeg, 1e-12);
  EXPECT_NEAR(2.0 * m.taem.hac_radius_m, 9300.0, 1.0);
  // Required heading = great-circle arrival azimuth at TAEM, computed here independently.
  const double p1 = m.entry.latitude_rad, p2 = m.taem.latitude_rad, dl = m.taem.longitude_rad - m.entry.longitude_rad;
  const double az_back = std::atan2(std::sin(-dl) * std::cos(p1),
                                    std::cos(p2) * std::sin(p1) - std::sin(p2) * std::cos(p1) * std::cos(-dl));
  const double arrival = std::fmod(az_back + kPi + 2.0 * kPi, 2.0 * kPi);
  EXPECT_NEAR(m.taem.heading_rad, arrival, 1e-4);
  // The alpha profile covers [E_taem/E_entry, 1] and starts near 46 deg (fig 3.17).
  EXPECT_GE(m.alpha_profile.x.back(), 1.0);
  EXPECT_NEAR(m.alpha_profile.y.back(), 46.0 * kDeg, 1e-12);
  // Thesis 8.3: breakpoint at E = 0.414 where alpha starts decreasing from 46 deg.
  bool found_breakpoint = false;
  for (size_t i = 0; i < m.alpha_profile.x.size(); ++i) {
    if (std::fabs(m.alpha_profile.x[i] - 0.414) < 1e-9) {
      found_breakpoint = true;
      EXPECT_NEAR(m.alpha_profile.y[i], 46.0 * kDeg, 1e-12);
      ASSERT_GT(i, 0u);
      EXPECT_LT(m.alpha_profile.y[i - 1], m.alpha_profile.y[i]);
    }
  }
  EXPECT_TRUE(found_breakpoint);
}

TEST(ConfigLoad, HorusAndOrbiterMatchTables) {
  const LoadResult h = load_mission("horus");
  ASSERT_TRUE(h.ok) << h.error;
  EXPECT_NEAR(h.mission.taem.latitude_rad, 4.9537 * kDeg, 1e-12);  // DESIGN 7 reading
  EXPECT_NEAR(h.mission.constraints.q_alpha_max_Pa_rad, 191397.0 * kDeg, 1e-6);
  EXPECT_DOUBLE_EQ(h.mission.constraints.heat_flux_max_Wpm2, 530e3);
  EXPECT_NEAR(h.mission.taem.mach_target, 2.5, 1e-12);
  EXPECT_NEAR(h.mission.taem.flight_path_rad, -7.0 * kDeg, 1e-12);
  EXPECT_NEAR(h.mission.vehicle.aero.flap_fixed_rad, 15.0 * kDeg, 1e-12);
  ASSERT_EQ(h.mission.vehicle.aero.surfaces.size(), 2u);
  EXPECT_EQ(h.mission.vehicle.aero.surfaces[0].name, "body_flap");
  EXPECT_NEAR(h.mission.vehicle.aero.surfaces[0].min_rad, -20.0 * kDeg, 1e-12);  // table 3.2
  EXPECT_NEAR(h.mission.vehicle.aero.surfaces[0].max_rad, 30.0 * kDeg, 1e-12);

  const LoadResult o = load_mission("orbiter");
  ASSERT_TRUE(o.ok) << o.error;
  EXPECT_NEAR(o.mission.constraints.heat_flux_max_Wpm2, 70.0 * kBtuPerFt2s, 1e-2);
  EXPECT_NEAR(o.mission.constraints.dynamic_pressure_max_Pa, 342.0 * kPsf, 1e-3);
  EXPECT_DOUBLE_EQ(o.mission.vehicle.mass_kg, 104330.0);
  EXPECT_EQ(o.mission.constraints.q_alpha_max_Pa_rad, reentry::config::kNotConstrained);
  // The 70 BTU/(ft^2 s) limit is Betts's wing-leading-edge one (README, vehicle file).
  EXPECT_EQ(o.mission.vehicle.heating_model, reentry::config::HeatingModel::kBettsLeadingEdge);
  EXPECT_EQ(h.mission.vehicle.heating_model, reentry::config::HeatingModel::kChapmanStagnation);  // default
}

// Orbiter table entries equal the public data file (parsed here with a separate reader).
TEST(ConfigLoad, OrbiterTableEqualsPublicDataFile) {
  const LoadResult o = load_mission("orbiter");
  ASSERT_TRUE(o.ok) << o.error;
  std::ifstream in(kConfigDir + "/aero/STS_CL.dat");
  int ndim = 0;
  in >> ndim;
  ASSERT_EQ(ndim, 2);
  std::vector<double> alpha(9), mach(8);
  for (double& a : alpha) in >> a;
  for (double& mm : mach) in >> mm;
  const auto& t = o.mission.vehicle.aero.cl;
  for (size_t i = 0; i < alpha.size(); ++i) {
    for (size_t j = 0; j < mach.size(); ++j) {
      double v = 0.0;
      in >> v;
      // Loaded grid has an extra Mach 2 column first; alpha grid starts at the same 0 deg.
      ASSERT_NEAR(t.alpha_rad[i], alpha[i], 1e-8);
      ASSERT_DOUBLE_EQ(t.mach[j + 1], mach[j]);
      EXPECT_NEAR(t.values[i * t.mach.size() + j + 1], v, 1e-6);
    }
  }
}

TEST(ConfigLoad, EnvVarOverridesConfigDir) {
  const reentry_test::TempDir tmp("reentry_cfg_env_test");
  const std::filesystem::path& dir = tmp.path();
  std::filesystem::create_directories(dir / "missions");
  ::setenv("REENTRY_CONFIG_DIR", dir.c_str(), 1);
  {
    std::ofstream(dir / "missions" / "x33.toml") << "name = \"broken\"\n";
  }
  const LoadResult r = load_mission("x33");
  ::unsetenv("REENTRY_CONFIG_DIR");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find((dir / "missions" / "x33.toml").string()), std::string::npos) << r.error;
  EXPECT_TRUE(load_mission("x33").ok);
}

struct BadCase {
  const char* label;
  bool in_vehicle;
  const char* from;
  const char* to;
  const char* key;    // expected in the message
  const char* value;  // expected in the message
};

// 70 increasing values (more than the 64 the on-board tables hold).
std::string seventy(double first, double step, const char* key, bool open_array) {
  std::string s = std::string(key) + " = [";
  for (int i = 0; i < 70; ++i) s += std::to_string(first + step * i) + (i + 1 < 70 || open_array ? ", " : "]");
  return s;
}
const std::string kSeventyEnergiesText = seventy(0.0, 1.0 / 69.0, "energy", false);
const std::string kSeventyAlphasText = seventy(-70.0, 1.0, "alpha_deg", true);  // + the file's 55 = 125
const char* const kSeventyEnergies = kSeventyEnergiesText.c_str();
const char* const kSeventyAlphas = kSeventyAlphasText.c_str();

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, IsRejectedNamingFileKeyAndValue) {
  const BadCase& c = GetParam();
  TempMission t;
  replace_once(c.in_vehicle ? t.vehicle() : t.mission(), c.from, c.to);
  const LoadResult r = t.load();
  ASSERT_FALSE(r.ok) << c.label;
  const std::string file = c.in_vehicle ? t.vehicle_path() : t.mission_path();
  EXPECT_NE(r.error.find(file), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(c.key), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(c.value), std::string::npos) << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Config, BadInput,
    ::testing::Values(
        BadCase{"missing_key", false, "altitude_m = 120100.0", "", "entry.altitude_m", "missing"},
        BadCase{"typo", false, "heading_deg = 49.59", "heading_deg = 49.59\nheadng_deg = 49.59", "entry.headng_deg", "unknown"},
        BadCase{"wrong_unit", false, "load_factor_max_g = 3.0", "load_factor_max_gs = 3.0", "constraints.load_factor_max_gs", "3"},
        BadCase{"wrong_type", false, "alpha_max_deg = 50.0", "alpha_max_deg = \"50\"", "constraints.alpha_max_deg", "\"50\""},
        BadCase{"nan", false, "rel_tol = 1e-10", "rel_tol = nan", "sim.rel_tol", "nan"},
        BadCase{"inf", false, "time_limit_s = 4000.0", "time_limit_s = inf", "sim.time_limit_s", "inf"},
        BadCase{"enum", false, "gravity = \"j2j4\"", "gravity = \"foo\"", "sim.gravity", "\"foo\""},
        BadCase{"latitude", false, "latitude_deg = -23.75", "latitude_deg = -123.75", "entry.latitude_deg", "-123.75"},
        BadCase{"taem_energy", false, "velocity_mps = 918.8", "velocity_mps = 9000.0", "taem.velocity_mps", "9000"},
        BadCase{"alpha_cover", false, "energy = [0.000,", "energy = [0.100,", "alpha_profile.energy", "0.1"},
        BadCase{"alpha_monotonic", false, "0.120, 0.414", "0.414, 0.120", "alpha_profile.energy[2]", "0.12"},
        BadCase{"alpha_source_enum", false, "[alpha_profile]\n", "[alpha_profile]\nsource = \"guess\"\n",
                "alpha_profile.source", "\"guess\""},
        BadCase{"alpha_planned_with_table", false, "[alpha_profile]\n", "[alpha_profile]\nsource = \"planned\"\n",
                "alpha_profile.energy", "not allowed"},
        BadCase{"parse_error", false, "[guidance]", "[guidance", "parse error", "line"},
        BadCase{"distribution_enum", false, "\ndistribution = \"gaussian\"", "\ndistribution = \"normal\"",
                "dispersions.distribution", "\"normal\""},
        BadCase{"distribution_override_enum", false, "entry_heading_deg = 0.5\n",
                "entry_heading_deg = 0.5\nentry_heading_distribution = \"lognormal\"\n",
                "dispersions.entry_heading_distribution", "\"lognormal\""},
        BadCase{"stress_distribution_enum", false, "\ndistribution = \"uniform\"", "\ndistribution = \"flat\"",
                "stress_dispersions.distribution", "\"flat\""},
        BadCase{"negative_three_sigma", false, "cl_scale = 0.10", "cl_scale = -0.10", "dispersions.cl_scale", "-0.1"},
        BadCase{"wind_order", false, "wind_scale_min = 0.0", "wind_scale_min = 2.0", "dispersions.wind_scale_max", "1.5"},
        BadCase{"negative_mass", true, "mass_kg = 37650.0", "mass_kg = -1.0", "vehicle.mass_kg", "-1"},
        BadCase{"zero_area", true, "reference_area_m2 = 149.4", "reference_area_m2 = 0.0", "vehicle.reference_area_m2", "0"},
        BadCase{"heating_enum", true, "nose_radius_m = 0.8", "nose_radius_m = 0.8\nheating_model = \"fay_riddell\"",
                "vehicle.heating_model", "\"fay_riddell\""},
        BadCase{"zero_nose", true, "nose_radius_m = 0.8", "nose_radius_m = 0", "vehicle.nose_radius_m", "0"},
        BadCase{"ragged_row", true, "cl = [\n  [0.000000, ", "cl = [\n  [", "aero.cl[0]", "5 values"},
        BadCase{"mach_order", true, "mach = [2.010000, 3.490000", "mach = [3.490000, 2.010000", "aero.mach[1]", "2.01"},
        BadCase{"policy_enum", true, "out_of_range = \"clamp\"", "out_of_range = \"wrap\"", "aero.out_of_range", "\"wrap\""},
        BadCase{"negative_cd", true, "cd = [\n  [0.200841", "cd = [\n  [-0.200841", "aero.cd[0][0]", "-0.200841"},
        // Limits equal to the on-board capacities and rates guidance can run at (issue 29).
        BadCase{"gnc_rate_tiny", false, "gnc_rate_hz = 10.0", "gnc_rate_hz = 1e-9", "guidance.gnc_rate_hz", "1e-09"},
        BadCase{"gnc_rate_huge", false, "gnc_rate_hz = 10.0", "gnc_rate_hz = 5000.0", "guidance.gnc_rate_hz", "5000"},
        BadCase{"latency_zero", false, "plan_latency_ticks = 5", "plan_latency_ticks = 0", "guidance.plan_latency_ticks", "0"},
        BadCase{"alpha_profile_70_rows", false, "energy = [0.000, 0.120, 0.414, 1.000]", kSeventyEnergies,
                "alpha_profile.energy", "has 70 values"},
        BadCase{"aero_alpha_over_64_rows", true, "alpha_deg = [0.000000,", kSeventyAlphas, "aero.alpha_deg",
                "has 125 values; the on-board aerodynamic table holds at most 64"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return std::string(info.param.label); });

// The temporary copy of a test is one folder directly in the temporary directory, gone with
// everything in it when the test ends: also in a parameterized test, whose name holds a '/'
// (a folder named after the test left its parent behind, one per case and run).
class TempFolder : public ::testing::TestWithParam<int> {};

TEST_P(TempFolder, IsRemovedWholeAfterTheTest) {
  std::filesystem::path dir;
  {
    TempMission t;
    dir = t.dir();
    ASSERT_TRUE(t.load().ok);
    ASSERT_TRUE(std::filesystem::exists(dir / "mission.toml"));
  }
  EXPECT_EQ(dir.parent_path(), std::filesystem::temp_directory_path());
  EXPECT_FALSE(std::filesystem::exists(dir));
}

INSTANTIATE_TEST_SUITE_P(Config, TempFolder, ::testing::Values(0));

TEST(ConfigLoad, DispersionSetsAreGaussianReferenceAndUniformStress) {
  const LoadResult r = load_mission("x33");
  ASSERT_TRUE(r.ok) << r.error;
  const auto& ref = r.mission.dispersions;
  ASSERT_TRUE(r.mission.has_stress_dispersions);
  const auto& stress = r.mission.stress_dispersions;
  using reentry::config::Distribution;
  EXPECT_EQ(ref.entry_flight_path_rad.distribution, Distribution::kGaussian);
  EXPECT_NEAR(ref.entry_flight_path_rad.value, 0.2 * kDeg, 1e-15);  // 3 sigma
  EXPECT_EQ(ref.wind_scale_distribution, Distribution::kGaussian);
  EXPECT_EQ(stress.entry_flight_path_rad.distribution, Distribution::kUniform);
  EXPECT_NEAR(stress.entry_flight_path_rad.value, 0.2 * kDeg, 1e-15);  // half-width
  EXPECT_EQ(stress.cd_scale.distribution, Distribution::kUniform);
  EXPECT_EQ(stress.wind_scale_distribution, Distribution::kUniform);
  EXPECT_DOUBLE_EQ(stress.wind_scale_max, 1.5);
  // A quantity's own distribution overrides the section's.
  TempMission t;
  const std::string from = "entry_heading_deg = 0.5\n";
  const size_t at = t.mission().find(from);
  ASSERT_NE(at, std::string::npos);
  t.mission().insert(at + from.size(), "entry_heading_distribution = \"uniform\"\n");
  const LoadResult o = t.load();
  ASSERT_TRUE(o.ok) << o.error;
  EXPECT_EQ(o.mission.dispersions.entry_heading_rad.distribution, Distribution::kUniform);
  EXPECT_EQ(o.mission.dispersions.entry_velocity_mps.distribution, Distribution::kGaussian);
}

TEST(ConfigLoad, PlannedAlphaProfileNeedsNoTable) {
  const LoadResult r = load_mission("x33_planned_alpha");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.mission.alpha_profile_planned);
  EXPECT_TRUE(r.mission.alpha_profile.x.empty());
  const LoadResult table = load_mission("x33");
  ASSERT_TRUE(table.ok) << table.error;
  EXPECT_FALSE(table.mission.alpha_profile_planned);
}

TEST(ConfigLoad, MissingRowCountIsRejected) {
  TempMission t;
  const size_t begin = t.vehicle().find("cl = [\n");
  ASSERT_NE(begin, std::string::npos);
  const size_t row_end = t.vehicle().find("],\n", begin);  // drop the first alpha row
  t.vehicle().erase(begin + 7, row_end + 3 - (begin + 7));
  const LoadResult r = t.load();
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("aero.cl"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("rows, expected 56"), std::string::npos) << r.error;
}

// HORUS moment model: trimming with the body flap alone at alpha_max-like (40 deg) and at
// alpha(L/D max) needs deflections of the size of thesis fig 3.6 (about -15..+20 deg), inside the
// flap limits of table 3.2.
TEST(ConfigLoad, HorusFlapTrimHasFig36Size) {
  const LoadResult h = load_mission("horus");
  ASSERT_TRUE(h.ok) << h.error;
  const auto& aero = h.mission.vehicle.aero;
  const auto& flap = aero.surfaces[0];
  const size_t nm = aero.cm.mach.size();
  auto index_of = [](const std::vector<double>& v, double x) {
    for (size_t i = 0; i < v.size(); ++i)
      if (std::fabs(v[i] - x) < 1e-9) return i;
    return v.size();
  };
  double lowest = 1e9, highest = -1e9;
  for (double mach : {2.0, 5.0, 10.0, 20.0}) {
    const size_t jm = index_of(aero.cm.mach, mach);
    ASSERT_LT(jm, nm);
    for (double alpha_deg : {14.0, 20.0, 40.0}) {
      const size_t ia = index_of(aero.cm.alpha_rad, alpha_deg * kDeg);
      ASSERT_LT(ia, aero.cm.alpha_rad.size());
      const double cm0 = aero.cm.values[ia * nm + jm];
      // Cm(delta) piecewise linear over the deflection grid; find the sign change.
      double trim = std::nan("");
      for (size_t k = 0; k + 1 < flap.deflection_rad.size(); ++k) {
        const double c0 = cm0 + flap.dcm[k].values[ia * nm + jm];
        const double c1 = cm0 + flap.dcm[k + 1].values[ia * nm + jm];
        if (c0 * c1 <= 0.0 && c0 != c1) {
          trim = flap.deflection_rad[k] + (flap.deflection_rad[k + 1] - flap.deflection_rad[k]) * c0 / (c0 - c1);
          break;
        }
      }
      ASSERT_TRUE(std::isfinite(trim)) << "no flap trim at alpha " << alpha_deg << " Mach " << mach;
      lowest = std::min(lowest, trim / kDeg);
      highest = std::max(highest, trim / kDeg);
    }
  }
  EXPECT_GE(lowest, -16.0);
  EXPECT_LE(lowest, -8.0);
  EXPECT_GE(highest, 15.0);
  EXPECT_LE(highest, 21.0);
}

TEST(ConfigLoad, MissingFileIsReportedWithoutThrowing) {
  const LoadResult r = load_mission("/nonexistent/dir/none.toml");
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("/nonexistent/dir/none.toml"), std::string::npos) << r.error;
}

TEST(ConfigLoad, OutOfRangePolicyParsed) {
  {
    TempMission t;
    const LoadResult r = t.load();
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mission.vehicle.aero.out_of_range, reentry::config::OutOfRangePolicy::kClamp);
  }
  {
    TempMission t;
    replace_once(t.vehicle(), "out_of_range = \"clamp\"", "out_of_range = \"error\"");
    const LoadResult r = t.load();
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.mission.vehicle.aero.out_of_range, reentry::config::OutOfRangePolicy::kError);
  }
}

}  // namespace
