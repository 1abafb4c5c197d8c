#include "tracker/drag_loop.hpp"

#include <cmath>

#include "models/onboard_models.hpp"

namespace reentry::fsw {

TrackerGains derive_gains(const TrackerParams& p) {
  TrackerGains g;
  g.omega0_radps = p.gain_frequency_factor * std::sqrt(kG0_mps2 / OnboardAtmosphere::kScaleHeight_m);
  g.zeta = 1.0 / std::sqrt(2.0);
  g.k_integral = g.omega0_radps * g.omega0_radps * g.omega0_radps / p.gain_integral_pole_ratio;
  if (p.zeta > 0.0) g.zeta = p.zeta;
  if (p.omega0_radps > 0.0) g.omega0_radps = p.omega0_radps;
  if (p.k_integral_ps3 > 0.0) g.k_integral = p.k_integral_ps3;
  return g;
}

double scheduled_omega(double omega0, double q_Pa, double q_ref_Pa) {
  if (!(q_ref_Pa > 0.0)) return omega0;
  const double x = q_Pa / q_ref_Pa;
  if (x >= 1.0) return omega0;
  if (x <= 0.0) return 0.0;
  return omega0 * (2.0 * x - x * x);  // (3.13)
}

double terminal_omega_floor_radps(double omega0_radps, double t_go_s, double settling, double omega_max_factor) {
  if (!(t_go_s > 0.0)) return omega_max_factor * omega0_radps;
  return std::fmin(settling / t_go_s, omega_max_factor * omega0_radps);
}

DragLoopCommand DragLoop::command(const DragLoopInput& in) const {
  const RefPoint& ref = in.ref;
  DragLoopCommand c;
  double d2_cmd = ref.drag_second;
  c.error = in.drag_mps2 - ref.drag;
  const double err_prime = in.drag_prime - ref.drag_prime;
  if (std::fabs(in.e_dot) > 1e-9) {
    const double inv_edot2 = 1.0 / (in.e_dot * in.e_dot);
    const double k_e = in.omega_radps * in.omega_radps * inv_edot2;                            // (3.15)
    const double c_e = in.e_ddot * inv_edot2 + 2.0 * gains_.zeta * in.omega_radps / in.e_dot;  // (3.14)
    d2_cmd -= c_e * err_prime + k_e * c.error + gains_.k_integral * integral_ * inv_edot2;     // (3.12)
  }
  const double u_ref = ref.lod * std::cos(ref.sigma);
  c.u_drag = u_ref + (d2_cmd - ref.drag_second) / in.b;  // (3.10)
  c.saturated = std::fabs(c.u_drag) > in.lift_over_drag;
  return c;
}

void DragLoop::update_integral(const DragLoopCommand& c, bool reversing, double drag_ref_mps2, double dt_s) {
  if (!reversing && !(c.saturated && ((c.error > 0.0) == (integral_ > 0.0)))) integral_ += c.error * dt_s;
  const double w0 = gains_.omega0_radps;
  const double i_max = integral_bias_max_fraction_ * drag_ref_mps2 * w0 * w0 / gains_.k_integral;
  integral_ = clamp(integral_, -i_max, i_max);
}

}  // namespace reentry::fsw
