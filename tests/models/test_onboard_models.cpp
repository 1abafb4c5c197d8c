// On-board vehicle models (fsw/core/models): heat-flux models against hand-computed values,
// the start-up trim solve against hand-solved cases and the truth model's trim, the tables at
// one Mach against the general bilinear look-up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>

#include <reentry/config/mission.hpp>

#include "guidance/mission_adapter.hpp"
#include "models/onboard_models.hpp"
#include "numerics/table_lookup.hpp"
#include "vehicle/aerodynamics.hpp"

namespace {
using reentry::fsw::HeatFluxModel;
using reentry::fsw::OnboardModels;

constexpr double kDeg = M_PI / 180.0;
constexpr double kSlugPerFt3_kgpm3 = 515.378818393196;   // 14.59390294 kg / 0.3048^3 m^3
constexpr double kFtps_mps = 0.3048;
constexpr double kBtuPerFt2s_Wpm2 = 11356.526682226975;  // 1055.05585262 J / 0.3048^2 m^2

OnboardModels with_heating(HeatFluxModel model, double nose_radius_m) {
  OnboardModels m;
  m.set_vehicle(1e5, 250.0, nose_radius_m, model);
  return m;
}

TEST(OnboardHeating, BettsLeadingEdgeHandComputedInUsUnits) {
  // q = qa(a) 17700 sqrt(rho) (1e-4 v)^3.07 BTU/(ft^2 s), rho slug/ft^3, v ft/s, a deg;
  // evaluated with a calculator from the published coefficients (Betts 2010, 6.1).
  struct Case {
    double rho_slugpft3, v_ftps, alpha_deg, q_btu;
  };
  const Case cases[] = {
      {2e-7, 20000.0, 40.0, 38.189009652307355},
      {1e-6, 15000.0, 30.0, 40.258516456617386},
      {5e-8, 25000.0, 45.0, 35.702136852170234},
      {2e-7, 20000.0, 0.0, 70.94201718215056},
  };
  const OnboardModels m = with_heating(HeatFluxModel::kBettsLeadingEdge, 0.3);
  EXPECT_EQ(m.heat_flux_velocity_exponent(), 3.07);
  for (const Case& c : cases) {
    const double q = m.heat_flux_Wpm2(c.rho_slugpft3 * kSlugPerFt3_kgpm3, c.v_ftps * kFtps_mps, c.alpha_deg * kDeg);
    EXPECT_NEAR(q / kBtuPerFt2s_Wpm2, c.q_btu, 1e-9 * c.q_btu) << "alpha " << c.alpha_deg;
  }
}

TEST(OnboardHeating, ChapmanIsAlphaFreeAndHandComputed) {
  // (3.5): 1.06584e8 / sqrt(0.8) * sqrt(1e-4 / 1.225) * (7000 / 7905.3657)^3 = 747493.118 W/m^2
  const OnboardModels m = with_heating(HeatFluxModel::kChapmanStagnation, 0.8);
  EXPECT_EQ(m.heat_flux_velocity_exponent(), 3.0);
  EXPECT_NEAR(m.heat_flux_Wpm2(1e-4, 7000.0, 0.0), 747493.118, 1e-2);
  EXPECT_EQ(m.heat_flux_Wpm2(1e-4, 7000.0, 40.0 * kDeg), m.heat_flux_Wpm2(1e-4, 7000.0, 0.0));
}

TEST(OnboardHeating, CoefficientAndExponentReproduceTheHeatFlux) {
  // The planner's corridor (7.3) uses q = C(alpha) sqrt(rho) V^c2 in closed form.
  for (HeatFluxModel model : {HeatFluxModel::kChapmanStagnation, HeatFluxModel::kBettsLeadingEdge}) {
    const OnboardModels m = with_heating(model, 0.3);
    for (double a_deg : {10.0, 25.0, 40.0}) {
      const double rho = 3e-5, v = 6500.0;
      const double c = m.heat_flux_coefficient(a_deg * kDeg);
      EXPECT_NEAR(c * std::sqrt(rho) * std::pow(v, m.heat_flux_velocity_exponent()),
                  m.heat_flux_Wpm2(rho, v, a_deg * kDeg), 1e-9 * m.heat_flux_Wpm2(rho, v, a_deg * kDeg));
    }
  }
}


// ------------------------------------------------------------------ trim (thesis 3.4)
namespace trim_tests {
using reentry::fsw::OnboardAero;
using reentry::fsw::solve_trimmed_coefficients;
using reentry::fsw::Status;
using reentry::fsw::TrimAeroData;
using reentry::fsw::TrimNode;
using reentry::fsw::TrimSurfaceData;

// Synthetic vehicle with hand-solvable trim: Cm0 = c0 (alpha_deg - 20), flap increments linear
// in the deflection (dCm = -0.002 / deg, dCL = 0.003 / deg, dCD = 0.0001 / deg), elevon pair
// dCm = -0.001 / deg each, dCL = 0.002 / deg, dCD = 0.00005 / deg; flap -10..+20 deg,
// elevons -30..+30 deg.
std::unique_ptr<TrimAeroData> synthetic(double c0) {
  auto d = std::make_unique<TrimAeroData>();
  d->n_alpha = 5;
  d->n_mach = 2;
  for (int i = 0; i < 5; ++i) d->alpha_rad[i] = 10.0 * i * kDeg;  // 0..40 deg
  d->mach[0] = 5.0;
  d->mach[1] = 20.0;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 2; ++j) {
      const int n = i * 2 + j;
      d->cl[n] = 0.03 * 10.0 * i;
      d->cd[n] = 0.05 + 0.001 * 10.0 * i * 10.0 * i / 10.0;
      d->cm[n] = c0 * (10.0 * i - 20.0);
    }
  }
  d->n_surfaces = 2;
  auto fill = [&](TrimSurfaceData& s, int count, double lo, double hi, std::initializer_list<double> defl_deg, double kl,
                  double kd, double km) {
    s.count = count;
    s.min_rad = lo * kDeg;
    s.max_rad = hi * kDeg;
    s.n_deflections = 0;
    for (double x : defl_deg) {
      const int k = s.n_deflections++;
      s.deflection_rad[k] = x * kDeg;
      for (int n = 0; n < 10; ++n) {
        s.dcl[k][n] = kl * x;
        s.dcd[k][n] = kd * std::fabs(x);
        s.dcm[k][n] = km * x;
      }
    }
  };
  fill(d->surface[0], 1, -10.0, 20.0, {-10.0, 0.0, 10.0, 20.0}, 0.003, 0.0001, -0.002);
  fill(d->surface[1], 2, -30.0, 30.0, {-30.0, 0.0, 30.0}, 0.002, 0.00005, -0.001);
  return d;
}

TEST(OnboardTrim, FlapTrimsWhereItCanAndTheElevonsTakeTheRest) {
  // c0 = 0.001: trim needs dCm = -0.001 (a - 20) from the flap, delta_f = 0.5 (a - 20) deg:
  // -10 deg at 0 deg alpha (the flap limit), -5 at 10, 0 at 20, +5 at 30, +10 at 40. None
  // saturates, the elevons stay neutral.
  auto d = synthetic(0.001);
  double cl[10], cd[10];
  TrimNode nodes[10];
  ASSERT_EQ(solve_trimmed_coefficients(*d, cl, cd, nodes), Status::kOk);
  for (int i = 0; i < 5; ++i) {
    const double a = 10.0 * i, flap = 0.5 * (a - 20.0);
    for (int j = 0; j < 2; ++j) {
      const int n = 2 * i + j;
      EXPECT_TRUE(nodes[n].trimmed) << a;
      EXPECT_NEAR(nodes[n].deflection_rad[0] / kDeg, flap, 1e-12) << a;
      EXPECT_EQ(nodes[n].deflection_rad[1], 0.0) << a;
      EXPECT_NEAR(cl[n], 0.03 * a + 0.003 * flap, 1e-12) << a;
      EXPECT_NEAR(cd[n], d->cd[n] + 0.0001 * std::fabs(flap), 1e-12) << a;
    }
  }
  // c0 = 0.003: the flap needs 1.5 (a - 20) deg: -30 at 0 deg (limit -10: the elevon pair adds
  // -0.002 dCm per deg for the remaining 0.003*(-20) + 0.002*10 = -0.04 -> -20 deg), +30 at 40
  // (limit +20: remaining 0.06 - 0.04 = 0.02 -> +10 deg elevons).
  d = synthetic(0.003);
  ASSERT_EQ(solve_trimmed_coefficients(*d, cl, cd, nodes), Status::kOk);
  EXPECT_TRUE(nodes[0].trimmed);
  EXPECT_NEAR(nodes[0].deflection_rad[0] / kDeg, -10.0, 1e-12);
  EXPECT_NEAR(nodes[0].deflection_rad[1] / kDeg, -20.0, 1e-12);
  EXPECT_NEAR(cl[0], 0.003 * -10.0 + 2.0 * 0.002 * -20.0, 1e-12);
  EXPECT_NEAR(cd[0], d->cd[0] + 0.0001 * 10.0 + 2.0 * 0.00005 * 20.0, 1e-12);
  EXPECT_NEAR(nodes[8].deflection_rad[0] / kDeg, 20.0, 1e-12);
  EXPECT_NEAR(nodes[8].deflection_rad[1] / kDeg, 10.0, 1e-12);
  // c0 = 0.01 at 40 deg: 0.2 to remove, flap 0.04 + elevons 0.06 at their limits: saturated,
  // left with the residual, surfaces at the limits.
  d = synthetic(0.01);
  ASSERT_EQ(solve_trimmed_coefficients(*d, cl, cd, nodes), Status::kOk);
  EXPECT_FALSE(nodes[8].trimmed);
  EXPECT_NEAR(nodes[8].cm_residual, 0.2 - 0.04 - 0.06, 1e-12);
  EXPECT_NEAR(nodes[8].deflection_rad[0] / kDeg, 20.0, 1e-12);
  EXPECT_NEAR(nodes[8].deflection_rad[1] / kDeg, 30.0, 1e-12);
}

TEST(OnboardTrim, BadDataIsRefused) {
  double cl[10], cd[10];
  auto d = synthetic(0.001);
  d->surface[0].deflection_rad[2] = d->surface[0].deflection_rad[1];  // not increasing
  EXPECT_EQ(solve_trimmed_coefficients(*d, cl, cd), Status::kInvalidInput);
  d = synthetic(0.001);
  d->cm[3] = std::nan("");
  EXPECT_EQ(solve_trimmed_coefficients(*d, cl, cd), Status::kInvalidInput);
  d = synthetic(0.001);
  d->n_surfaces = 3;
  EXPECT_EQ(solve_trimmed_coefficients(*d, cl, cd), Status::kCapacityExceeded);
  d = synthetic(0.001);
  d->surface[1].max_rad = d->surface[1].min_rad;
  EXPECT_EQ(solve_trimmed_coefficients(*d, cl, cd), Status::kInvalidInput);
}

TEST(OnboardTrim, TrimmedTablesInterpolateLikeTheBasicOnes) {
  auto d = synthetic(0.001);
  OnboardAero aero;
  ASSERT_EQ(aero.init_trimmed(*d), Status::kOk);
  // Between the nodes 10 and 20 deg at Mach 5: the mean of the trimmed node values.
  double cl10, cd10, cl20, cd20, cl15, cd15;
  aero.coefficients(10.0 * kDeg, 5.0, cl10, cd10);
  aero.coefficients(20.0 * kDeg, 5.0, cl20, cd20);
  aero.coefficients(15.0 * kDeg, 5.0, cl15, cd15);
  EXPECT_NEAR(cl10, 0.3 + 0.003 * -5.0, 1e-12);
  EXPECT_NEAR(cl15, 0.5 * (cl10 + cl20), 1e-12);
  EXPECT_NEAR(cd15, 0.5 * (cd10 + cd20), 1e-12);
}
}  // namespace trim_tests

}  // namespace

// HORUS: the on-board start-up trim equals, at every node of its table grid, the truth model's
// trim (sim_truth/vehicle/aerodynamics: separate code, Brent in the deflection) above the
// fixed-flap dynamic pressure; between the nodes it is the bilinear interpolant of the nodes.
namespace {
TEST(OnboardTrim, HorusNodesEqualTheTruthModelsTrim) {
  const reentry::config::LoadResult loaded = reentry::config::load_mission("horus");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  OnboardModels models;
  ASSERT_EQ(init_from_mission(models, loaded.mission), reentry::fsw::Status::kOk);
  ASSERT_TRUE(models.aero_trimmed());
  const auto truth = reentry::truth::Aerodynamics::create(loaded.mission.vehicle.aero);
  ASSERT_TRUE(truth.has_value());
  const auto& grid = loaded.mission.vehicle.aero.cl;
  int trimmed = 0, nodes = 0;
  double largest_flap_effect = 0.0;
  for (double a : grid.alpha_rad) {
    for (double m : grid.mach) {
      const auto t = truth->coefficients(a, m, 5000.0, true);
      const auto basic = truth->coefficients(a, m, 5000.0, false);
      double cl, cd;
      models.aero().coefficients(a, m, cl, cd);
      EXPECT_NEAR(cl, t.cl, 1e-9) << a / kDeg << " " << m;
      EXPECT_NEAR(cd, t.cd, 1e-9) << a / kDeg << " " << m;
      trimmed += t.trimmed ? 1 : 0;
      ++nodes;
      largest_flap_effect = std::fmax(largest_flap_effect, std::fabs(cd / basic.cd - 1.0));
    }
  }
  EXPECT_GT(trimmed, nodes / 2);
  EXPECT_GT(largest_flap_effect, 0.05);  // trim matters: the surfaces move C_D by more than 5 %
  // Without the on-board trim the tables are the basic ones.
  reentry::config::Mission basic_mission = loaded.mission;
  basic_mission.guidance.onboard_trim = false;
  OnboardModels basic;
  ASSERT_EQ(init_from_mission(basic, basic_mission), reentry::fsw::Status::kOk);
  EXPECT_FALSE(basic.aero_trimmed());
  double cl, cd;
  basic.aero().coefficients(grid.alpha_rad[30], grid.mach[4], cl, cd);
  EXPECT_EQ(cd, truth->coefficients(grid.alpha_rad[30], grid.mach[4], 5000.0, false).cd);
}
}  // namespace

// ------------------------------------------------------------------ the aero tables at one Mach
// OnboardAero::MachSlice (the Mach interval found once, alpha bracketed alone) must give the
// general bilinear look-up bit for bit: the guidance commands are computed through both. The
// reference is numerics::bilinear on the same arrays, called directly, and OnboardAero::cl/cd;
// OnboardAero::coefficients (both tables through one slice) is held to the same reference.
namespace {
using reentry::fsw::OnboardAero;

uint64_t bits(double x) {
  uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

struct RandomTable {
  int n_alpha = 0, n_mach = 0;
  double alpha[OnboardAero::kMaxAlpha] = {}, mach[OnboardAero::kMaxMach] = {};
  double cl[OnboardAero::kMaxAlpha * OnboardAero::kMaxMach] = {}, cd[OnboardAero::kMaxAlpha * OnboardAero::kMaxMach] = {};
};

// A table with uneven axes (spacings over two decades) and rough values, C_L of both signs.
std::unique_ptr<RandomTable> random_table(std::mt19937_64& rng, int n_alpha, int n_mach) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto t = std::make_unique<RandomTable>();
  t->n_alpha = n_alpha;
  t->n_mach = n_mach;
  double a = -5.0 * kDeg * u(rng), m = 0.3 + u(rng);
  for (int i = 0; i < n_alpha; ++i) t->alpha[i] = (a += std::pow(10.0, -2.0 * u(rng)) * 2.0 * kDeg);
  for (int j = 0; j < n_mach; ++j) t->mach[j] = (m += std::pow(10.0, -2.0 * u(rng)) * 3.0);
  for (int k = 0; k < n_alpha * n_mach; ++k) {
    t->cl[k] = 2.0 * u(rng) - 0.5;
    t->cd[k] = 0.02 + u(rng);
  }
  return t;
}

// Queries on one axis: inside (uniform), on the knots, far outside, and NaN.
double axis_query(std::mt19937_64& rng, const double* g, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double lo = g[0], hi = g[n - 1], span = hi - lo, r = u(rng);
  if (r < 0.15) return g[static_cast<int>(u(rng) * n) % n];
  if (r < 0.20) return lo - span * u(rng);
  if (r < 0.25) return hi + span * u(rng);
  if (r < 0.26) return std::nan("");
  return lo + span * u(rng);
}

// Compares a slice at `mach` with the general look-up at `n` alphas: random ones, then the
// midpoints of a bisection (the tracker's use, where the slice's last-interval path applies).
void expect_slice_equals_bilinear(const OnboardAero& aero, const RandomTable& t, double mach, std::mt19937_64& rng,
                                  int n) {
  const OnboardAero::MachSlice slice = aero.at_mach(mach);
  const double scale = aero.lift_scale();
  auto check = [&](double alpha) {
    const double cl_general = scale * reentry::numerics::bilinear(t.alpha, t.n_alpha, t.mach, t.n_mach, t.cl, alpha, mach);
    const double cd_general = reentry::numerics::bilinear(t.alpha, t.n_alpha, t.mach, t.n_mach, t.cd, alpha, mach);
    ASSERT_EQ(bits(slice.cl(alpha)), bits(cl_general)) << alpha << " " << mach;
    ASSERT_EQ(bits(slice.cd(alpha)), bits(cd_general)) << alpha << " " << mach;
    ASSERT_EQ(bits(slice.cl(alpha)), bits(aero.cl(alpha, mach))) << alpha << " " << mach;
    ASSERT_EQ(bits(slice.cd(alpha)), bits(aero.cd(alpha, mach))) << alpha << " " << mach;
    double cl_pair = 0.0, cd_pair = 0.0;  // both tables in one look-up
    aero.coefficients(alpha, mach, cl_pair, cd_pair);
    ASSERT_EQ(bits(cl_pair), bits(cl_general)) << alpha << " " << mach;
    ASSERT_EQ(bits(cd_pair), bits(cd_general)) << alpha << " " << mach;
  };
  for (int k = 0; k < n; ++k) check(axis_query(rng, t.alpha, t.n_alpha));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double target = 2.0 * u(rng) - 0.5;
  double lo = t.alpha[0] - 0.1, hi = t.alpha[t.n_alpha - 1] + 0.1;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    check(mid);
    (slice.cl(mid) > target ? hi : lo) = mid;
  }
}

TEST(OnboardAeroMachSlice, EqualsTheBilinearLookUpBitForBitOnRandomTables) {
  std::mt19937_64 rng(20240611);
  std::uniform_int_distribution<int> n_alpha(2, OnboardAero::kMaxAlpha), n_mach(1, OnboardAero::kMaxMach);
  for (int table = 0; table < 200; ++table) {
    // Every fourth table has a single Mach column (the slice then has no Mach weight).
    const auto t = random_table(rng, n_alpha(rng), table % 4 == 0 ? 1 : n_mach(rng));
    OnboardAero aero;
    ASSERT_EQ(aero.init(t->alpha, t->n_alpha, t->mach, t->n_mach, t->cl, t->cd), reentry::fsw::Status::kOk);
    aero.set_lift_scale(table % 2 == 0 ? 1.0 : 0.8 + 0.4 * std::uniform_real_distribution<double>(0.0, 1.0)(rng));
    for (int m = 0; m < 25; ++m) {
      expect_slice_equals_bilinear(aero, *t, axis_query(rng, t->mach, t->n_mach), rng, 40);
      if (HasFatalFailure()) return;
    }
  }
}

TEST(OnboardAeroMachSlice, EqualsTheBilinearLookUpBitForBitOnTheVehicleTables) {
  // The flown tables (X-33 basic, HORUS trimmed at start-up, X-38), over their whole grids.
  std::mt19937_64 rng(7);
  for (const char* name : {"x33", "horus", "x38"}) {
    const reentry::config::LoadResult loaded = reentry::config::load_mission(name);
    ASSERT_TRUE(loaded.ok) << loaded.error;
    OnboardModels models;
    ASSERT_EQ(init_from_mission(models, loaded.mission), reentry::fsw::Status::kOk);
    const auto& grid = loaded.mission.vehicle.aero.cl;
    auto t = std::make_unique<RandomTable>();
    t->n_alpha = static_cast<int>(grid.alpha_rad.size());
    t->n_mach = static_cast<int>(grid.mach.size());
    std::copy(grid.alpha_rad.begin(), grid.alpha_rad.end(), t->alpha);
    std::copy(grid.mach.begin(), grid.mach.end(), t->mach);
    // The tables as the models hold them (trimmed or not), read back at the nodes.
    for (int i = 0; i < t->n_alpha; ++i) {
      for (int j = 0; j < t->n_mach; ++j) {
        t->cl[i * t->n_mach + j] = models.aero().cl(t->alpha[i], t->mach[j]);
        t->cd[i * t->n_mach + j] = models.aero().cd(t->alpha[i], t->mach[j]);
      }
    }
    for (int m = 0; m < 400; ++m) {
      expect_slice_equals_bilinear(models.aero(), *t, axis_query(rng, t->mach, t->n_mach), rng, 50);
      if (HasFatalFailure()) return;
    }
  }
}

TEST(OnboardAeroMachSlice, AnEmptySliceOrTableGivesZero) {
  const OnboardAero::MachSlice empty;
  EXPECT_EQ(empty.cl(0.3), 0.0);
  EXPECT_EQ(empty.cd(0.3), 0.0);
  const OnboardAero aero;  // not initialised
  EXPECT_EQ(aero.at_mach(5.0).cl(0.3), aero.cl(0.3, 5.0));
  EXPECT_EQ(aero.at_mach(5.0).cd(0.3), 0.0);
}
}  // namespace
