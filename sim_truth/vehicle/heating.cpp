#include "vehicle/heating.hpp"

#include "environment/earth.hpp"

#include <cmath>

namespace reentry::truth {

double chapman_circular_velocity_mps() {
  return std::sqrt(EarthConstants::kMu_m3ps2 / EarthConstants::kEquatorialRadius_m);
}

double chapman_heat_flux_Wpm2(double density_kgpm3, double velocity_mps, double nose_radius_m) {
  // (3.5) q = c1 / sqrt(Rn) * sqrt(rho / rho0) * (V / Vc)^c2
  const double v_ratio = velocity_mps / chapman_circular_velocity_mps();
  return kChapmanC1_Wpm1p5 / std::sqrt(nose_radius_m) * std::sqrt(density_kgpm3 / kChapmanRho0_kgpm3) *
         v_ratio * v_ratio * v_ratio;
}

double betts_leading_edge_heat_flux_Wpm2(double density_kgpm3, double velocity_mps, double alpha_rad) {
  constexpr double kFt_m = 0.3048;
  constexpr double kSlugPerFt3_kgpm3 = 14.59390293720636 / (kFt_m * kFt_m * kFt_m);  // 515.3788 kg/m^3
  constexpr double kBtuPerFt2s_Wpm2 = 1055.05585262 / (kFt_m * kFt_m);               // 11356.53 W/m^2
  constexpr double kPi = 3.14159265358979323846;
  const double rho_slugpft3 = density_kgpm3 / kSlugPerFt3_kgpm3;
  const double v_fps = velocity_mps / kFt_m;
  const double a = alpha_rad * 180.0 / kPi;
  const double q_r = 17700.0 * std::sqrt(rho_slugpft3) * std::pow(1e-4 * v_fps, 3.07);
  const double q_a = 1.0672181 + a * (-1.9213774e-2 + a * (2.1286289e-4 + a * -1.0117249e-6));
  return q_a * q_r * kBtuPerFt2s_Wpm2;
}

double heat_flux_Wpm2(config::HeatingModel model, double density_kgpm3, double velocity_mps, double alpha_rad,
                      double nose_radius_m) {
  if (model == config::HeatingModel::kBettsLeadingEdge)
    return betts_leading_edge_heat_flux_Wpm2(density_kgpm3, velocity_mps, alpha_rad);
  return chapman_heat_flux_Wpm2(density_kgpm3, velocity_mps, nose_radius_m);  // (3.5)
}

double body_normal_load_factor(double lift_N, double drag_N, double alpha_rad, double mass_kg) {
  return (lift_N * std::cos(alpha_rad) + drag_N * std::sin(alpha_rad)) / (mass_kg * kStandardGravity_mps2);  // (3.7)
}

}  // namespace reentry::truth
