#include "tracker/constraint_limiter.hpp"

#include <cmath>

#include "numerics/root_finding.hpp"

namespace reentry::fsw {

double wings_level_pullout_drag_mps2(double drag_mps2, double lift_over_drag, double h_dot_mps, double g_eff_mps2,
                                     double scale_height_m) {
  // Vertical energy balance of a wings-level pull-out, speed held, rho ~ exp(-h / H):
  //   f(D_p) = (L/D) H (D_p - D) - g_eff H ln(D_p / D) - h_dot^2 / 2 = 0,  g_eff = g - V_h^2 / r.
  // f(D) < 0 and f grows without bound: f falls while (L/D) D_p < g_eff, then rises, so the
  // root above D is unique. Bracketed (doubling) and solved by Brent's method; a fixed-point
  // iteration on the same balance diverges where g_eff < 0 (an eastbound entry above circular
  // speed) or (L/D) D < g_eff.
  const double D = drag_mps2;
  if (!(h_dot_mps < 0.0) || !(D > 0.0)) return D;
  if (!(lift_over_drag > 0.0) || !(scale_height_m > 0.0) || !std::isfinite(g_eff_mps2)) return kNoPullOut_mps2;
  const double kinetic = 0.5 * h_dot_mps * h_dot_mps;
  auto balance = [&](double d_p) {
    return lift_over_drag * scale_height_m * (d_p - D) - g_eff_mps2 * scale_height_m * std::log(d_p / D) - kinetic;
  };
  double hi = D + kinetic / (lift_over_drag * scale_height_m);  // the root without gravity
  for (int i = 0; i < 64 && balance(hi) <= 0.0; ++i) {
    if (hi > kNoPullOut_mps2) return kNoPullOut_mps2;
    hi *= 2.0;
  }
  // An unbracketed or non-finite balance comes back from brent as a failed status.
  const numerics::RootResult root = numerics::brent(balance, D, hi, 1e-9 * D, 100);
  return root.status == numerics::NumStatus::kOk && root.x <= kNoPullOut_mps2 ? root.x : kNoPullOut_mps2;
}

double pullout_drag_after_roll_mps2(double drag_mps2, double lift_over_drag, double h_dot_mps, double g_eff_mps2,
                                    double scale_height_m, double sigma0_rad, double t_roll_s) {
  double h_dot = h_dot_mps, drag = drag_mps2;
  const double sigma = std::fabs(sigma0_rad);
  if (sigma > 1e-6 && t_roll_s > 0.0 && drag_mps2 > 0.0 && scale_height_m > 0.0) {
    const double h_ddot = lift_over_drag * drag_mps2 * std::sin(sigma) / sigma - g_eff_mps2;
    const double dh = h_dot * t_roll_s + 0.5 * h_ddot * t_roll_s * t_roll_s;
    h_dot += h_ddot * t_roll_s;
    drag *= std::exp(std::fmin(-dh / scale_height_m, 5.0));  // bounded: e^5 is far past any limit
  }
  return wings_level_pullout_drag_mps2(drag, lift_over_drag, h_dot, g_eff_mps2, scale_height_m);
}

void ConstraintLimiter::init(const OnboardModels& models, const TrackerParams& params, const TrackerLimits& limits) {
  bind(models, params);
  limits_ = limits;
  reset();
}

double ConstraintLimiter::pullout_drag_mps2(const RelativeState& s, double sigma_now_rad) const {
  const double D = s.drag_mps2;
  if (!(D > params_->min_drag_mps2)) return D;
  const double dlnrho_dr = models_->dlnrho_dr_fd(s.altitude_m, kTrackerDensityGradientStep_m);
  if (!(dlnrho_dr < 0.0)) return D;
  // Net downward acceleration without lift, with the Earth-rate term of (2.33) (an eastbound
  // vehicle near orbital speed is held up by it).
  const double g_eff = level_flight_lift_need_mps2(s.radius_m, s.velocity_mps * std::cos(s.flight_path_rad),
                                                   s.latitude_rad, s.heading_rad);
  const double sigma = std::fabs(sigma_now_rad);
  const double rate = limits_.sigma_rate_max_radps;
  const double t_roll = rate > 0.0 && sigma > 1e-6 ? sigma / rate + params_->roll_lag_s : 0.0;
  return pullout_drag_after_roll_mps2(D, s.lift_mps2 / D, s.velocity_mps * std::sin(s.flight_path_rad), g_eff,
                                      -1.0 / dlnrho_dr, sigma, t_roll);
}

double ConstraintLimiter::pullout_guard(const RelativeState& s, double sigma_flown_rad, double u_drag, double lod,
                                        bool terminal, double limit_mps2) {
  if (pullout_arrested_ && params_->pullout_guard_every_descent == 0) return u_drag;
  const double d_pullout = pullout_drag_mps2(s, sigma_flown_rad);
  pullout_arrested_ = d_pullout < params_->pullout_complete_ratio * s.drag_mps2;
  // The linear drag loop alone follows the planned drag ramp after capture with lift down and
  // reaches the plateau in a dive it can no longer arrest. With a slow bank rate the same holds
  // for later descents (pullout_guard_every_descent): the climb a reversal through wings level
  // leaves is answered by the drag loop with lift down, and the roll back out of it takes as
  // long as the reversal itself.
  if (!pullout_arrested_ && !terminal && u_drag < lod && d_pullout > limit_mps2) return lod;
  return u_drag;
}

double ConstraintLimiter::sensed_drag_limit_mps2(const RelativeState& s, double alpha_rad, double cd) const {
  // Every constraint depends on the sensed drag through D / (C_D S/m): q, q alpha and the load
  // factor linearly, the heat flux (3.5) through sqrt(rho) = sqrt(2 q) / V, so each gives its
  // limit by scaling the present drag. A density error does not move the limit; a C_D error
  // moves it as it moves q itself.
  const double D = s.drag_mps2;
  if (!(D > params_->min_drag_mps2) || !(cd > 0.0)) return kUnconstrainedDrag_mps2;
  const double q = models_->sensed_dynamic_pressure_Pa(D, cd);
  const double margin = limits_.constraint_margin;
  double limit = kUnconstrainedDrag_mps2;
  auto scale_linear = [&](double value, double max) {
    if (max > 0.0 && value > 0.0) limit = std::fmin(limit, D * margin * max / value);
  };
  scale_linear(q, limits_.q_max_Pa);
  scale_linear(q * alpha_rad, limits_.q_alpha_max_Pa_rad);
  scale_linear(std::hypot(D, s.lift_mps2), limits_.load_factor_max_mps2);
  const double heat = models_->heat_flux_Wpm2(OnboardModels::density_of_dynamic_pressure_kgpm3(q, s.velocity_mps),
                                              s.velocity_mps, alpha_rad);
  if (limits_.heat_flux_max_Wpm2 > 0.0 && heat > 0.0) {
    const double ratio = margin * limits_.heat_flux_max_Wpm2 / heat;
    limit = std::fmin(limit, D * ratio * ratio);
  }
  return limit;
}

double ConstraintLimiter::load_relief_alpha(double alpha_cmd_rad, double alpha_floor_rad, double alpha_flown_rad,
                                            double mach, double aero_accel_mps2) const {
  // The aerodynamic acceleration at the sensed dynamic pressure scales with the resultant
  // coefficient C_R = hypot(C_L, C_D); the command is lowered (bisection, bounded). Ratios of
  // table coefficients, so a C_L / C_D scale error does not move the limit.
  const OnboardAero::MachSlice aero = models_->aero().at_mach(mach);  // one Mach: alpha alone varies
  const double c_flown = std::hypot(aero.cl(alpha_flown_rad), aero.cd(alpha_flown_rad));
  const double limit = limits_.constraint_margin * limits_.load_factor_max_mps2;
  if (!(c_flown > 0.0) || !(aero_accel_mps2 > 0.0) || !(limit > 0.0)) return alpha_cmd_rad;
  auto accel_at = [&](double alpha) { return aero_accel_mps2 * std::hypot(aero.cl(alpha), aero.cd(alpha)) / c_flown; };
  if (accel_at(alpha_cmd_rad) <= limit) return alpha_cmd_rad;
  // Never below the floor: shedding lift in a dive would deepen it (q then grows without bound).
  double lo = std::fmin(std::fmax(alpha_floor_rad, 0.0), alpha_cmd_rad), hi = alpha_cmd_rad;
  if (accel_at(lo) > limit) return lo;
  for (int i = 0; i < kAlphaBisectionSteps; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (accel_at(mid) > limit) hi = mid; else lo = mid;
  }
  return lo;
}

}  // namespace reentry::fsw
