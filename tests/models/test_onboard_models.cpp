// On-board vehicle models (fsw/core/models): heat-flux models against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "models/onboard_models.hpp"

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

}  // namespace
