// Heat flux and load factor (thesis 3.2).
#pragma once

#include <cmath>

namespace reentry::truth {

inline constexpr double kChapmanC1_Wpm1p5 = 1.06584e8;  // c1 in W/m^(3/2) ... (3.5)
inline constexpr double kChapmanC2 = 3.0;
inline constexpr double kChapmanRho0_kgpm3 = 1.225;
inline constexpr double kStandardGravity_mps2 = 9.80665;

/// Circular velocity at the equatorial surface, Vc = sqrt(mu / R_eq) ~ 7905.4 m/s (3.5).
double chapman_circular_velocity_mps();

/// Stagnation-point heat flux (3.5): q = c1 / sqrt(Rn) * sqrt(rho / rho0) * (V / Vc)^c2.
/// Scalar-generic (environment/scalar.hpp), like the load factor.
template <class T>
T chapman_heat_flux_Wpm2(const T& density_kgpm3, const T& velocity_mps, double nose_radius_m) {
  using std::sqrt;
  // (3.5) q = c1 / sqrt(Rn) * sqrt(rho / rho0) * (V / Vc)^c2
  const T v_ratio = velocity_mps / chapman_circular_velocity_mps();
  return kChapmanC1_Wpm1p5 / std::sqrt(nose_radius_m) * sqrt(density_kgpm3 / kChapmanRho0_kgpm3) * v_ratio * v_ratio *
         v_ratio;
}

/// Body-normal load factor (3.7): n = (L cos a + D sin a) / (m g0), in g.
template <class T>
T body_normal_load_factor(const T& lift_N, const T& drag_N, const T& alpha_rad, double mass_kg) {
  using std::cos;
  using std::sin;
  return (lift_N * cos(alpha_rad) + drag_N * sin(alpha_rad)) / (mass_kg * kStandardGravity_mps2);  // (3.7)
}

}  // namespace reentry::truth
