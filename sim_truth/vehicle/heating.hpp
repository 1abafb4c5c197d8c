// Heat flux and load factor (thesis 3.2).
//
// Scalar-generic (environment/scalar.hpp): the simulator evaluates these in double, the
// trajectory optimizer (tools/optimizer) with Eigen AutoDiff scalars; one implementation.
#pragma once

#include <cmath>

#include "environment/scalar.hpp"
#include "physics/earth_constants.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::truth {

inline constexpr double kChapmanC1_Wpm1p5 = 1.06584e8;  // c1 in W/m^(3/2) ... (3.5)
inline constexpr double kChapmanC2 = 3.0;
inline constexpr double kChapmanRho0_kgpm3 = 1.225;
using physics::kStandardGravity_mps2;

/// Circular velocity at the equatorial surface, Vc = sqrt(mu / R_eq) ~ 7905.4 m/s (3.5).
double chapman_circular_velocity_mps();

/// Stagnation-point heat flux (3.5): q = c1 / sqrt(Rn) * sqrt(rho / rho0) * (V / Vc)^c2.
template <class T>
T chapman_heat_flux_Wpm2(const T& density_kgpm3, const T& velocity_mps, double nose_radius_m) {
  using std::sqrt;
  // (3.5) q = c1 / sqrt(Rn) * sqrt(rho / rho0) * (V / Vc)^c2
  const T v_ratio = velocity_mps / chapman_circular_velocity_mps();
  return kChapmanC1_Wpm1p5 / std::sqrt(nose_radius_m) * sqrt(density_kgpm3 / kChapmanRho0_kgpm3) * v_ratio * v_ratio *
         v_ratio;
}

/// Betts's Space Shuttle wing-leading-edge heat flux (J. T. Betts, Practical Methods for Optimal
/// Control and Estimation Using Nonlinear Programming, 2nd ed., SIAM 2010, sec. 6.1, p. 248):
/// q = qa(a) * 17700 sqrt(rho) (1e-4 v)^3.07 BTU/(ft^2 s) with rho in slug/ft^3, v in ft/s and
/// qa = 1.0672181 - 1.9213774e-2 a + 2.1286289e-4 a^2 - 1.0117249e-6 a^3, a = alpha in deg.
/// SI in and out; the fit is evaluated in its own US units.
template <class T>
T betts_leading_edge_heat_flux_Wpm2(const T& density_kgpm3, const T& velocity_mps, const T& alpha_rad) {
  using std::sqrt;
  constexpr double kFt_m = 0.3048;
  constexpr double kSlugPerFt3_kgpm3 = 14.59390293720636 / (kFt_m * kFt_m * kFt_m);  // 515.3788 kg/m^3
  constexpr double kBtuPerFt2s_Wpm2 = 1055.05585262 / (kFt_m * kFt_m);               // 11356.53 W/m^2
  const T rho_slugpft3 = density_kgpm3 / kSlugPerFt3_kgpm3;
  const T v_fps = velocity_mps / kFt_m;
  const T a = alpha_rad * 180.0 / M_PI;
  const T q_r = 17700.0 * sqrt(rho_slugpft3) * scalar::pow(T(1e-4 * v_fps), 3.07);
  const T q_a = 1.0672181 + a * (-1.9213774e-2 + a * (2.1286289e-4 + a * -1.0117249e-6));
  return q_a * q_r * kBtuPerFt2s_Wpm2;
}

/// The vehicle's heat-flux model (config::HeatingModel) at a flight condition.
template <class T>
T heat_flux_Wpm2(config::HeatingModel model, const T& density_kgpm3, const T& velocity_mps, const T& alpha_rad,
                 double nose_radius_m) {
  if (model == config::HeatingModel::kBettsLeadingEdge)
    return betts_leading_edge_heat_flux_Wpm2(density_kgpm3, velocity_mps, alpha_rad);
  return chapman_heat_flux_Wpm2(density_kgpm3, velocity_mps, nose_radius_m);  // (3.5)
}

/// Body-normal load factor (3.7): n = (L cos a + D sin a) / (m g0), in g.
template <class T>
T body_normal_load_factor(const T& lift_N, const T& drag_N, const T& alpha_rad, double mass_kg) {
  using std::cos;
  using std::sin;
  return (lift_N * cos(alpha_rad) + drag_N * sin(alpha_rad)) / (mass_kg * kStandardGravity_mps2);  // (3.7)
}

}  // namespace reentry::truth
