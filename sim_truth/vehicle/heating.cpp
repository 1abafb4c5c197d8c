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

double body_normal_load_factor(double lift_N, double drag_N, double alpha_rad, double mass_kg) {
  return (lift_N * std::cos(alpha_rad) + drag_N * std::sin(alpha_rad)) / (mass_kg * kStandardGravity_mps2);  // (3.7)
}

}  // namespace reentry::truth
