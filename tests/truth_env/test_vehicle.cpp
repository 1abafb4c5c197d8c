// Aerodynamics with trim (thesis 3.4) on analytic tables whose exact trim is known; heating.
#include "vehicle/aerodynamics.hpp"
#include "vehicle/heating.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace rt = reentry::truth;
namespace cfg = reentry::config;

namespace {
constexpr double kDeg = M_PI / 180.0;

cfg::Table2D table(const std::function<double(double, double)>& f) {
  cfg::Table2D t;
  for (int i = 0; i <= 8; ++i) t.alpha_rad.push_back(5.0 * i * kDeg);
  t.mach = {1.0, 2.0, 5.0, 10.0, 20.0};
  for (double a : t.alpha_rad)
    for (double m : t.mach) t.values.push_back(f(a, m));
  return t;
}

// Bilinear-exact base tables (a + b alpha + c M + d alpha M) and surface increments that are
// linear (or piecewise linear with a node at 0) in deflection, so the exact trim is closed-form.
double cl0(double a, double m) { return 0.1 + 1.2 * a + 0.01 * m + 0.05 * a * m; }
double cd0(double a, double m) { return 0.05 + 0.3 * a + 0.002 * m; }
double cm0(double a, double m) { return 0.02 - 0.1 * a + 0.001 * m; }
constexpr double kFlapDcm = -0.1, kFlapDcl = 0.2, kFlapDcd = 0.05;
constexpr double kElevonDcm = -0.05, kElevonDcl = 0.1, kElevonDcd = 0.02;
constexpr double kFlapMin = -0.3, kFlapMax = 0.35, kElevonMin = -0.35, kElevonMax = 0.35, kFlapFixed = 0.1;

cfg::ControlSurface surface(const std::string& name, int count, double lo, double hi, std::vector<double> defl,
                            double dcm, double dcl, double dcd) {
  cfg::ControlSurface s;
  s.name = name;
  s.count = count;
  s.min_rad = lo;
  s.max_rad = hi;
  s.deflection_rad = defl;
  for (double d : defl) {
    s.dcm.push_back(table([=](double, double) { return dcm * d; }));
    s.dcl.push_back(table([=](double, double) { return dcl * d; }));
    s.dcd.push_back(table([=](double, double) { return dcd * std::fabs(d); }));
  }
  return s;
}

cfg::AeroModel analytic_model() {
  cfg::AeroModel m;
  m.source = "analytic test model";
  m.reference_length_m = 10.0;
  m.cl = table(cl0);
  m.cd = table(cd0);
  m.cm = table(cm0);
  m.surfaces.push_back(surface("body_flap", 1, kFlapMin, kFlapMax, {-0.35, -0.2, 0.0, 0.2, 0.4}, kFlapDcm, kFlapDcl, kFlapDcd));
  m.surfaces.push_back(surface("elevon", 2, kElevonMin, kElevonMax, {-0.4, -0.2, 0.0, 0.2, 0.4}, kElevonDcm, kElevonDcl, kElevonDcd));
  m.flap_fixed_rad = kFlapFixed;
  m.q_flap_fixed_Pa = 100.0;
  return m;
}
}  // namespace

TEST(Aerodynamics, BilinearExactAndClamped) {
  auto aero = rt::Aerodynamics::create(analytic_model());
  ASSERT_TRUE(aero.has_value());
  const auto c = aero->coefficients(17.3 * kDeg, 7.7, 5000.0, false);
  EXPECT_NEAR(c.cl, cl0(17.3 * kDeg, 7.7), 1e-14);
  EXPECT_NEAR(c.cd, cd0(17.3 * kDeg, 7.7), 1e-14);
  EXPECT_FALSE(c.trimmed);
  const auto s = aero->coefficients(17.3 * kDeg, 7.7, 5000.0, false, 1.1, 0.9);
  EXPECT_NEAR(s.cl, 1.1 * c.cl, 1e-14);
  EXPECT_NEAR(s.cd, 0.9 * c.cd, 1e-14);
  // Clamp policy: beyond the edges the edge values, no flag
  const auto e = aero->coefficients(50.0 * kDeg, 30.0, 5000.0, false);
  EXPECT_NEAR(e.cl, cl0(40.0 * kDeg, 20.0), 1e-14);
  EXPECT_FALSE(e.out_of_range);
  auto model = analytic_model();
  model.out_of_range = cfg::OutOfRangePolicy::kError;
  auto strict = rt::Aerodynamics::create(model);
  ASSERT_TRUE(strict.has_value());
  EXPECT_TRUE(strict->coefficients(50.0 * kDeg, 5.0, 5000.0, true).out_of_range);
  EXPECT_TRUE(std::isfinite(strict->coefficients(50.0 * kDeg, 5.0, 5000.0, true).cl));
  EXPECT_FALSE(strict->coefficients(20.0 * kDeg, 5.0, 5000.0, true).out_of_range);
}

TEST(Aerodynamics, TrimMatchesClosedFormOverGrid) {
  auto aero = rt::Aerodynamics::create(analytic_model());
  ASSERT_TRUE(aero.has_value());
  int trimmed = 0, flap_only = 0, with_elevon = 0, saturated = 0, fixed_flap = 0;
  double worst_cm = 0.0, worst_defl = 0.0;
  for (double a_deg = 0.0; a_deg <= 40.0; a_deg += 1.3) {
    for (double mach : {1.0, 3.7, 10.0, 19.0}) {
      for (double q : {20.0, 99.0, 100.0, 5000.0}) {
        const double a = a_deg * kDeg;
        const double c0 = cm0(a, mach);
        // Closed-form law: flap alone, else flap at the limit reducing |Cm| and the elevons.
        double flap, elevon = 0.0;
        if (q < 100.0) {
          flap = kFlapFixed;
          elevon = (c0 + kFlapDcm * flap) / (-2.0 * kElevonDcm);
          ++fixed_flap;
        } else {
          flap = c0 / -kFlapDcm;
          if (flap < kFlapMin || flap > kFlapMax) {
            flap = std::clamp(flap, kFlapMin, kFlapMax);
            elevon = (c0 + kFlapDcm * flap) / (-2.0 * kElevonDcm);
          }
        }
        const bool feasible = elevon >= kElevonMin && elevon <= kElevonMax;
        elevon = std::clamp(elevon, kElevonMin, kElevonMax);
        const auto c = aero->coefficients(a, mach, q, true);
        EXPECT_EQ(c.trimmed, feasible) << a_deg << " " << mach << " " << q;
        EXPECT_EQ(c.saturated, !feasible);
        EXPECT_GE(c.flap_rad, kFlapMin);
        EXPECT_LE(c.flap_rad, kFlapMax);
        EXPECT_GE(c.elevon_rad, kElevonMin);
        EXPECT_LE(c.elevon_rad, kElevonMax);
        if (q < 100.0) {
          EXPECT_EQ(c.flap_rad, kFlapFixed);
        }
        worst_defl = std::fmax(worst_defl, std::fabs(c.flap_rad - flap) + std::fabs(c.elevon_rad - elevon));
        const double cm_expected = c0 + kFlapDcm * flap + 2.0 * kElevonDcm * elevon;
        EXPECT_NEAR(c.cm_total, cm_expected, 1e-12);
        EXPECT_NEAR(c.cl, cl0(a, mach) + kFlapDcl * flap + 2.0 * kElevonDcl * elevon, 1e-12);
        EXPECT_NEAR(c.cd, cd0(a, mach) + kFlapDcd * std::fabs(flap) + 2.0 * kElevonDcd * std::fabs(elevon), 1e-12);
        if (feasible) {
          worst_cm = std::fmax(worst_cm, std::fabs(c.cm_total));
          ++trimmed;
          if (q >= 100.0 && elevon == 0.0) ++flap_only; else ++with_elevon;
        } else {
          ++saturated;
        }
      }
    }
  }
  EXPECT_LT(worst_cm, 1e-8);
  EXPECT_LT(worst_defl, 1e-10);
  EXPECT_GT(flap_only, 10);
  EXPECT_GT(with_elevon, 10);
  EXPECT_GT(saturated, 0);
  EXPECT_GT(fixed_flap, 10);
  std::printf("[figure] trim grid: %d trimmed (%d flap only, %d with elevons), %d saturated; max |Cm| %.2e, "
              "max deflection error %.2e rad\n", trimmed, flap_only, with_elevon, saturated, worst_cm, worst_defl);
}

TEST(Aerodynamics, TrimWithNonlinearIncrementsAndSaturation) {
  auto model = analytic_model();
  // Flap increment nonlinear in deflection: tabulated -0.1 d - 0.2 d |d|, interpolated linearly.
  for (size_t k = 0; k < model.surfaces[0].deflection_rad.size(); ++k) {
    const double d = model.surfaces[0].deflection_rad[k];
    model.surfaces[0].dcm[k] = table([=](double a, double) { return (-0.1 - 0.2 * std::fabs(d)) * d * (1.0 + a); });
  }
  auto aero = rt::Aerodynamics::create(model);
  ASSERT_TRUE(aero.has_value());
  double worst = 0.0;
  for (double a_deg = 0.0; a_deg <= 40.0; a_deg += 0.7) {
    for (double mach : {1.5, 6.0, 18.0}) {
      const auto c = aero->coefficients(a_deg * kDeg, mach, 2000.0, true);
      ASSERT_TRUE(c.trimmed);
      worst = std::fmax(worst, std::fabs(c.cm_total));
    }
  }
  EXPECT_LT(worst, 1e-8);
  // Far out of the control power: both surfaces at the limits that reduce |Cm|.
  for (double& v : model.cm.values) v += 0.2;
  auto sat = rt::Aerodynamics::create(model);
  const auto c = sat->coefficients(10.0 * kDeg, 5.0, 5000.0, true);
  EXPECT_FALSE(c.trimmed);
  EXPECT_TRUE(c.saturated);
  EXPECT_EQ(c.flap_rad, kFlapMax);
  EXPECT_EQ(c.elevon_rad, kElevonMax);
  EXPECT_GT(c.cm_total, 0.0);
}

TEST(Aerodynamics, NoMomentDataMeansNoTrim) {
  auto model = analytic_model();
  model.cm = cfg::Table2D{};
  auto aero = rt::Aerodynamics::create(model);
  ASSERT_TRUE(aero.has_value());
  EXPECT_FALSE(aero->has_moment_data());
  const auto c = aero->coefficients(20.0 * kDeg, 5.0, 5000.0, true);
  EXPECT_FALSE(c.trimmed);
  EXPECT_EQ(c.flap_rad, 0.0);
  EXPECT_NEAR(c.cl, cl0(20.0 * kDeg, 5.0), 1e-14);
}

TEST(Aerodynamics, BadTablesRejected) {
  auto model = analytic_model();
  model.cl.values.pop_back();
  std::string err;
  EXPECT_FALSE(rt::Aerodynamics::create(model, &err).has_value());
  EXPECT_NE(err.find("cl"), std::string::npos) << err;
  model = analytic_model();
  model.cd.values[3] = std::nan("");
  EXPECT_FALSE(rt::Aerodynamics::create(model, &err).has_value());
  EXPECT_NE(err.find("index 3"), std::string::npos) << err;
}

TEST(Heating, ChapmanHandComputed) {
  // Vc = sqrt(3.986004418e14 / 6378137) = 7905.3657 m/s
  EXPECT_NEAR(rt::chapman_circular_velocity_mps(), 7905.365719, 1e-5);
  // rho 1e-4, V 7000, Rn 0.8: 1.06584e8 / sqrt(0.8) * sqrt(1e-4 / 1.225) * (7000 / Vc)^3
  EXPECT_NEAR(rt::chapman_heat_flux_Wpm2(1e-4, 7000.0, 0.8), 747493.118, 1e-2);
}

// Betts's leading-edge fit evaluated by hand in its own units: q = qa(a) 17700 sqrt(rho)
// (1e-4 v)^3.07 BTU/(ft^2 s), rho in slug/ft^3, v in ft/s, a in deg (values computed with a
// calculator from the published coefficients).
namespace {
constexpr double kSlugPerFt3_kgpm3 = 515.378818393196;   // 14.59390294 kg / 0.3048^3 m^3
constexpr double kFtps_mps = 0.3048;
constexpr double kBtuPerFt2s_Wpm2 = 11356.526682226975;  // 1055.05585262 J / 0.3048^2 m^2
struct BettsCase {
  double rho_slugpft3, v_ftps, alpha_deg, q_btu;
};
constexpr BettsCase kBettsCases[] = {
    {2e-7, 20000.0, 40.0, 38.189009652307355},  // qa 0.5744973704, q_r 66.4737762
    {1e-6, 15000.0, 30.0, 40.258516456617386},  // qa 0.6550649087, q_r 61.4572937
    {5e-8, 25000.0, 45.0, 35.702136852170234},  // qa 0.5414521907, q_r 65.9377457
    {2e-7, 20000.0, 0.0, 70.94201718215056},    // qa = c0 = 1.0672181
};
}  // namespace

TEST(Heating, BettsLeadingEdgeHandComputedInUsUnits) {
  for (const BettsCase& c : kBettsCases) {
    const double q = rt::betts_leading_edge_heat_flux_Wpm2(c.rho_slugpft3 * kSlugPerFt3_kgpm3, c.v_ftps * kFtps_mps,
                                                           c.alpha_deg * kDeg);
    EXPECT_NEAR(q / kBtuPerFt2s_Wpm2, c.q_btu, 1e-9 * c.q_btu) << "alpha " << c.alpha_deg;
  }
}

TEST(Heating, VehicleModelSelectsTheFormula) {
  const double rho = 1e-4, v = 7000.0, a = 40.0 * kDeg;
  EXPECT_EQ(rt::heat_flux_Wpm2(cfg::HeatingModel::kChapmanStagnation, rho, v, a, 0.8),
            rt::chapman_heat_flux_Wpm2(rho, v, 0.8));
  EXPECT_EQ(rt::heat_flux_Wpm2(cfg::HeatingModel::kBettsLeadingEdge, rho, v, a, 0.8),
            rt::betts_leading_edge_heat_flux_Wpm2(rho, v, a));
  // The leading-edge heat flux falls with alpha (qa decreasing on 0-50 deg) and is below the
  // 0.3 m stagnation point's at the Orbiter's 40 deg: about 0.53 of it at 7 km/s.
  EXPECT_LT(rt::betts_leading_edge_heat_flux_Wpm2(rho, v, 45.0 * kDeg), rt::betts_leading_edge_heat_flux_Wpm2(rho, v, a));
  EXPECT_LT(rt::betts_leading_edge_heat_flux_Wpm2(rho, v, a), 0.6 * rt::chapman_heat_flux_Wpm2(rho, v, 0.3));
}

TEST(Heating, LoadFactorHandComputed) {
  // (1e5 cos 40 + 5e4 sin 40) / (1e4 * 9.80665)
  EXPECT_NEAR(rt::body_normal_load_factor(1e5, 5e4, 40.0 * kDeg, 1e4), 1.10887841206, 1e-10);
}
