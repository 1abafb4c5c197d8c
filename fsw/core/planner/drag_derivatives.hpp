// First and second derivative of the drag acceleration with respect to energy
// (thesis 7.14, 7.17-7.20, appendix D). Pure functions of local quantities.
#pragma once

#include <cmath>

namespace reentry::fsw {

/// Local quantities at one energy; rho_r_over_rho = (1/rho) d rho / dr.
struct DragLocal {
  double drag = 0.0;          // D [m/s^2]
  double velocity = 0.0;      // V
  double radius = 0.0;        // r
  double gravity = 0.0;       // g(r)
  double rho_r_over_rho = 0.0;
  double cd_prime_over_cd = 0.0;    // C_D' / C_D
  double cd_second_over_cd = 0.0;   // C_D'' / C_D
};

/// k = -(1/rho) d rho/dr + 2 g / V^2, the factor multiplying sin(gamma) in (7.14).
inline double density_gravity_factor(const DragLocal& l) {
  return -l.rho_r_over_rho + 2.0 * l.gravity / (l.velocity * l.velocity);
}

/// (7.14): D' = D (2/V^2 + CD'/CD) + k sin(gamma).
inline double drag_first_derivative(const DragLocal& l, double sin_gamma) {
  return l.drag * (2.0 / (l.velocity * l.velocity) + l.cd_prime_over_cd) + density_gravity_factor(l) * sin_gamma;
}

/// sin(gamma) from a planned D' by inverting (7.14).
inline double sin_gamma_from_drag_slope(const DragLocal& l, double drag_prime) {
  return (drag_prime - l.drag * (2.0 / (l.velocity * l.velocity) + l.cd_prime_over_cd)) / density_gravity_factor(l);
}

/// a of (7.19) without the Coriolis part, and the factor multiplying C_gamma (7.18).
inline double drag_second_a_no_coriolis(const DragLocal& l, double drag_prime) {
  const double v2 = l.velocity * l.velocity;
  const double k = density_gravity_factor(l);
  return l.drag * (l.cd_second_over_cd - l.cd_prime_over_cd * l.cd_prime_over_cd) +
         drag_prime * (l.cd_prime_over_cd + 2.0 / v2) - 4.0 * l.drag / (v2 * v2) +
         k * (l.gravity - v2 / l.radius) / (l.drag * v2);
}

/// C_gamma = -2 omega cos(delta) sin(chi) / (D V)  (7.18).
inline double coriolis_gamma_trig(double omega, double cos_latitude, double sin_heading, double drag, double velocity) {
  return -2.0 * omega * cos_latitude * sin_heading / (drag * velocity);
}
inline double coriolis_gamma(double omega, double latitude, double heading, double drag, double velocity) {
  return coriolis_gamma_trig(omega, std::cos(latitude), std::sin(heading), drag, velocity);
}

/// (7.20): b = -k / V^2.
inline double drag_second_b(const DragLocal& l) { return -density_gravity_factor(l) / (l.velocity * l.velocity); }

/// (7.17): D'' = a + b (L/D) cos(sigma), a = a_no_coriolis + k C_gamma.
inline double drag_second_derivative(const DragLocal& l, double drag_prime, double c_gamma, double lod_cos_sigma) {
  return drag_second_a_no_coriolis(l, drag_prime) + density_gravity_factor(l) * c_gamma + drag_second_b(l) * lod_cos_sigma;
}

}  // namespace reentry::fsw

