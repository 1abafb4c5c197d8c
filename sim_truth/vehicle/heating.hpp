// Heat flux and load factor (thesis 3.2).
#pragma once

#include "reentry/config/mission.hpp"

namespace reentry::truth {

inline constexpr double kChapmanC1_Wpm1p5 = 1.06584e8;  // c1 in W/m^(3/2) ... (3.5)
inline constexpr double kChapmanC2 = 3.0;
inline constexpr double kChapmanRho0_kgpm3 = 1.225;
inline constexpr double kStandardGravity_mps2 = 9.80665;

/// Circular velocity at the equatorial surface, Vc = sqrt(mu / R_eq) ~ 7905.4 m/s (3.5).
double chapman_circular_velocity_mps();

/// Stagnation-point heat flux (3.5): q = c1 / sqrt(Rn) * sqrt(rho / rho0) * (V / Vc)^c2.
double chapman_heat_flux_Wpm2(double density_kgpm3, double velocity_mps, double nose_radius_m);

/// Betts's Space Shuttle wing-leading-edge heat flux (J. T. Betts, Practical Methods for Optimal
/// Control and Estimation Using Nonlinear Programming, 2nd ed., SIAM 2010, sec. 6.1, p. 248):
/// q = qa(a) * 17700 sqrt(rho) (1e-4 v)^3.07 BTU/(ft^2 s) with rho in slug/ft^3, v in ft/s and
/// qa = 1.0672181 - 1.9213774e-2 a + 2.1286289e-4 a^2 - 1.0117249e-6 a^3, a = alpha in deg.
/// SI in and out; the fit is evaluated in its own US units.
double betts_leading_edge_heat_flux_Wpm2(double density_kgpm3, double velocity_mps, double alpha_rad);

/// The vehicle's heat-flux model (config::HeatingModel) at a flight condition.
double heat_flux_Wpm2(config::HeatingModel model, double density_kgpm3, double velocity_mps, double alpha_rad,
                      double nose_radius_m);

/// Body-normal load factor (3.7): n = (L cos a + D sin a) / (m g0), in g.
double body_normal_load_factor(double lift_N, double drag_N, double alpha_rad, double mass_kg);

}  // namespace reentry::truth
