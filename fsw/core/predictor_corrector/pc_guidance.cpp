#include "predictor_corrector/pc_guidance.hpp"

#include <cmath>

#include "planner/mission_geometry.hpp"
#include "tracker/constraint_limiter.hpp"
#include "tracker/lateral_logic.hpp"

namespace reentry::fsw {
namespace {

constexpr double kUnbounded = 1e300;

bool limited(double v) { return v > 0.0 && std::isfinite(v); }

// Vertical energy balance of a wings-level pull-out, speed held, rho ~ exp(-h / H) (the
// tracker's, tracker/constraint_limiter.cpp): f(D_p) = (L/D) H (D_p - D) - g_eff H ln(D_p / D)
// - hdot^2 / 2. f(D) < 0 and the root above D is unique, so the bottom drag exceeds `limit`
// exactly when f(limit) < 0: one evaluation decides, no root is needed. The roll from sigma0
// to wings level first is flown with the mean vertical lift L sin(sigma0) / sigma0 of a uniform
// roll at constant vertical acceleration (conservative).
bool pullout_exceeds(double drag, double lod, double hdot, double g_eff, double scale_height_m, double sigma0_rad,
                     double t_roll_s, double limit) {
  if (!(drag > 0.0) || !(lod > 0.0) || !(scale_height_m > 0.0) || !(hdot < 0.0)) return false;
  const double sigma = std::fabs(sigma0_rad);
  if (sigma > 1e-6 && t_roll_s > 0.0) {
    const double h_ddot = lod * drag * std::sin(sigma) / sigma - g_eff;
    // The descent may be arrested during the roll itself: its bottom is then the roll's.
    const double t = h_ddot > 0.0 ? std::fmin(t_roll_s, -hdot / h_ddot) : t_roll_s;
    const double dh = hdot * t + 0.5 * h_ddot * t * t;
    hdot += h_ddot * t;
    drag *= std::exp(std::fmin(-dh / scale_height_m, 5.0));
  }
  if (drag >= limit) return true;
  if (!(hdot < 0.0)) return false;  // the bottom is reached in the roll, below the limit
  const double f = lod * scale_height_m * (limit - drag) - g_eff * scale_height_m * std::log(limit / drag) -
                   0.5 * hdot * hdot;
  return f < 0.0;
}

}  // namespace

PcLimits pc_limits_from(const PathLimits& l, double margin, double drag_uncertainty) {
  // For a sensed drag D the vehicle's q is D / (C_D S/m)_vehicle: with the on-board C_D S/m
  // larger by the share u, q (and rho, so the heat flux as sqrt(rho)) is underestimated by it.
  PcLimits p;
  p.margin = margin;
  const double q_share = 1.0 - drag_uncertainty;
  p.heat_flux_max_Wpm2 = limited(l.heat_flux_max_Wpm2) ? margin * std::sqrt(q_share) * l.heat_flux_max_Wpm2 : 0.0;
  p.q_max_Pa = limited(l.dynamic_pressure_max_Pa) ? margin * q_share * l.dynamic_pressure_max_Pa : 0.0;
  p.q_alpha_max_Pa_rad = limited(l.q_alpha_max_Pa_rad) ? margin * q_share * l.q_alpha_max_Pa_rad : 0.0;
  p.load_factor_max_mps2 = limited(l.load_factor_max_g) ? margin * l.load_factor_max_g * kG0_mps2 : 0.0;
  return p;
}

double constraint_drag_limit_mps2(const OnboardModels& models, const PcLimits& lim, double v_mps, double alpha_rad,
                                  double cl, double cd) {
  // D = q C_D S/m: a q-type limit is a drag limit; heat flux q = C(alpha) sqrt(rho) V^c2 (3.5)
  // gives rho <= (q_max / (C V^c2))^2; hypot(L, D) = D hypot(1, L/D).
  const double s_over_m = models.area_over_mass();
  double d = kUnbounded;
  if (lim.q_max_Pa > 0.0) d = std::fmin(d, lim.q_max_Pa * cd * s_over_m);
  if (lim.q_alpha_max_Pa_rad > 0.0 && alpha_rad > 1e-3) d = std::fmin(d, lim.q_alpha_max_Pa_rad / alpha_rad * cd * s_over_m);
  if (lim.load_factor_max_mps2 > 0.0 && cd > 0.0) d = std::fmin(d, lim.load_factor_max_mps2 / std::hypot(1.0, cl / cd));
  if (lim.heat_flux_max_Wpm2 > 0.0 && v_mps > 0.0) {
    const double c = models.heat_flux_coefficient(alpha_rad) * std::pow(v_mps, models.heat_flux_velocity_exponent());
    if (c > 0.0) {
      const double sqrt_rho = lim.heat_flux_max_Wpm2 / c;
      d = std::fmin(d, 0.5 * sqrt_rho * sqrt_rho * v_mps * v_mps * cd * s_over_m);
    }
  }
  return d;
}

double constraint_drag_limit_rate_ps(const OnboardModels& models, const PcLimits& limits, double v_mps, double drag_mps2,
                                     double alpha_rad, double cl, double cd) {
  const double now = constraint_drag_limit_mps2(models, limits, v_mps, alpha_rad, cl, cd);
  const double later = constraint_drag_limit_mps2(models, limits, std::fmax(v_mps - drag_mps2, 1.0), alpha_rad, cl, cd);
  return now > 0.0 && now < kUnbounded && later < kUnbounded ? std::log(later / now) : 0.0;
}

double qeg_altitude_rate_mps(double velocity_mps, double radius_m, double latitude_rad, double heading_rad,
                             double drag_mps2, double scale_height_m, double sigma_rad, double sigma_dot_radps) {
  // L(h, V) cos(sigma) = need(V), L ~ rho(h) V^2: (2/V - need'/need) dV - dh / H
  // - tan(sigma) dsigma = 0, need' = dneed/dV = -2 V / r - 2 w cos(lat) sin(chi); V' = -D. The
  // need is held at a tenth of g0 or more (near orbital speed the glide's height is undetermined).
  const double v = std::fmax(velocity_mps, 1.0);
  const double need = std::fmax(level_flight_lift_need_mps2(radius_m, v, latitude_rad, heading_rad), 0.1 * kG0_mps2);
  const double need_prime = -2.0 * v / radius_m - 2.0 * kEarthRate_radps * std::cos(latitude_rad) * std::sin(heading_rad);
  const double tan_sigma = std::tan(clamp(sigma_rad, 0.0, 85.0 * M_PI / 180.0));
  return scale_height_m * (-drag_mps2 * (2.0 / v - need_prime / need) - tan_sigma * sigma_dot_radps);
}

TerminalCommand TerminalAltitude::at(double energy_Jpkg, double altitude_m, double velocity_mps, double drag_mps2,
                                     const PredictorCorrectorParams& p) const {
  TerminalCommand c;
  if (!in_phase(energy_Jpkg, p)) return c;
  const double de = energy_Jpkg - taem_energy_Jpkg;
  const double phase = p.terminal_span_fraction * span_Jpkg;
  c.weight = clamp((phase - de) / (p.terminal_ramp_fraction * phase), 0.0, 1.0);
  // On the line h = h_f + s (E - E_f) the slope s is constant: hdot = s E' = -s D V.
  const double line = de > 0.0 ? -(altitude_m - target_altitude_m) * drag_mps2 * velocity_mps / de : 0.0;
  c.hdot_mps = clamp(line, velocity_mps * std::sin(p.terminal_gamma_min_rad), velocity_mps * std::sin(p.terminal_gamma_max_rad));
  return c;
}

double modulated_alpha_rad(const OnboardAero& aero, double alpha_rad, double mach, double sigma_cmd_mag_rad,
                           double sigma_flown_rad, double sigma_rate_radps, double alpha_min_rad,
                           const PredictorCorrectorParams& p) {
  const double c_flown = std::cos(sigma_flown_rad), c_cmd = std::cos(sigma_cmd_mag_rad);
  if (!(c_flown > c_cmd) || !(c_flown > 1e-3) || !(alpha_min_rad < alpha_rad)) return alpha_rad;
  // A fast roll's lift pulse is short: modulation only where the reversal lasts (2 |sigma| / rate).
  if (!(sigma_rate_radps > 0.0) || 2.0 * sigma_cmd_mag_rad / sigma_rate_radps < p.modulation_min_roll_s) return alpha_rad;
  const double target = std::fmax(c_cmd / c_flown, p.modulation_min_lift_ratio) * aero.cl(alpha_rad, mach);
  double lo = alpha_min_rad, hi = alpha_rad;
  if (aero.cl(lo, mach) >= target) return lo;
  for (int i = 0; i < 12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (aero.cl(mid, mach) < target ? lo : hi) = mid;
  }
  return hi;
}

double heat_relief_alpha_rad(const OnboardModels& models, double alpha_mod_rad, double alpha_rad, double density_kgpm3,
                             double velocity_mps, const PcLimits& limits) {
  if (!(limits.heat_flux_max_Wpm2 > 0.0) || !(alpha_mod_rad < alpha_rad) || !(density_kgpm3 > 0.0)) return alpha_mod_rad;
  // q = C(alpha) sqrt(rho) V^c2 (3.6): only C varies along the bisection.
  const OnboardModels::HeatFluxFlow flow = models.heat_flux_flow(density_kgpm3, velocity_mps);
  auto heat = [&](double a) { return models.heat_flux_Wpm2(flow, a); };
  const double allowed = std::fmax(limits.heat_flux_max_Wpm2, heat(alpha_rad));
  if (heat(alpha_mod_rad) <= allowed) return alpha_mod_rad;
  double lo = alpha_mod_rad, hi = alpha_rad;
  for (int i = 0; i < 12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (heat(mid) > allowed ? lo : hi) = mid;
  }
  return hi;
}

double reversal_alpha_rad(const OnboardModels& models, double alpha_rad, double mach, double sigma_cmd_mag_rad,
                          double sigma_flown_rad, double sigma_rate_radps, double alpha_min_rad, double density_kgpm3,
                          double velocity_mps, const PcLimits& limits, const PredictorCorrectorParams& p) {
  const double alpha_mod = modulated_alpha_rad(models.aero(), alpha_rad, mach, sigma_cmd_mag_rad, sigma_flown_rad,
                                               sigma_rate_radps, alpha_min_rad, p);
  return heat_relief_alpha_rad(models, alpha_mod, alpha_rad, density_kgpm3, velocity_mps, limits);
}

bool capture_due(double drag_mps2, double lift_mps2, double hdot_mps, double need_mps2, double scale_height_m,
                 double threshold_mps2, const PredictorCorrectorParams& p) {
  if (drag_mps2 >= threshold_mps2) return true;
  if (!(drag_mps2 >= p.capture_drag_fraction * threshold_mps2) || !(drag_mps2 > 0.0)) return false;
  const double bottom =
      wings_level_pullout_drag_mps2(drag_mps2, lift_mps2 / drag_mps2, hdot_mps, need_mps2, scale_height_m);
  return bottom < threshold_mps2;
}

double load_relief_alpha_rad(const OnboardAero& aero, double alpha_rad, double mach, double q_s_over_m,
                             const PcLimits& limits, double alpha_min_rad) {
  auto accel = [&](double a) {
    double cl = 0.0, cd = 0.0;
    aero.coefficients(a, mach, cl, cd);
    return q_s_over_m * std::hypot(cl, cd);
  };
  const double limit = limits.load_factor_max_mps2;
  if (!(limit > 0.0) || !(alpha_min_rad < alpha_rad) || accel(alpha_rad) <= limit) return alpha_rad;
  double lo = alpha_min_rad, hi = alpha_rad;
  if (accel(lo) > limit) return lo;
  for (int i = 0; i < 12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (accel(mid) > limit ? hi : lo) = mid;
  }
  return lo;
}

double damping_gain_ps(double need_mps2, double scale_height_m, const PredictorCorrectorParams& p) {
  // Altitude-rate damping (Lu 2014): the glide's altitude mode has the stiffness L / H ~ g_eff / H.
  return 2.0 * p.damping_ratio * std::sqrt(std::fmax(need_mps2, 0.1 * kG0_mps2) / scale_height_m);
}

double position_gain_ps(double need_mps2, double scale_height_m, const PredictorCorrectorParams& p) {
  return p.glide_position_factor > 0.0 ? damping_gain_ps(need_mps2, scale_height_m, p) / p.glide_position_factor : 0.0;
}

BankLawOutput bank_magnitude(const BankLawInput& in, const PredictorCorrectorParams& p) {
  BankLawOutput out;
  const double v = in.velocity_mps, hdot = v * std::sin(in.flight_path_rad);
  const double need = level_flight_lift_need_mps2(in.radius_m, v * std::cos(in.flight_path_rad), in.latitude_rad,
                                                  in.heading_rad);
  out.damping_gain_ps = damping_gain_ps(need, in.scale_height_m, p);
  double cos_sigma = std::cos(in.sigma_base_rad);
  if (in.lift_mps2 > 1e-6) {
    cos_sigma -= out.damping_gain_ps * (hdot - in.hdot_ref_mps) / in.lift_mps2;
    if (in.terminal.weight > 0.0) {
      const double cos_terminal = (need + p.terminal_rate_gain_ps * (in.terminal.hdot_mps - hdot)) / in.lift_mps2;
      cos_sigma += in.terminal.weight * (cos_terminal - cos_sigma);
    }
  }
  // Below the capture drag (a shallow entry's skip) the damping may take the bank past bank_max,
  // lift down against the climb, up to bank_damped_max; elsewhere within bank_max, or the
  // profile's own bank where it is past it (the range-long end of the family).
  const double upper = in.skip_phase ? p.bank_damped_max_rad
                                     : clamp(in.sigma_base_rad, p.bank_max_rad, p.bank_damped_max_rad);
  double sigma = clamp(std::acos(clamp(cos_sigma, -1.0, 1.0)), p.bank_min_rad, upper);
  // Constraint bound (Lu 2014's predictive bound on the descent, in drag form): the drag may
  // approach its limit no faster than d ln(D / D_lim)/dt <= ln(D_lim / D) / tau; with
  // D ~ rho V^2, rho ~ exp(-h / H) and V' = -D - g sin(gamma) = -D - g hdot / V (gravity along
  // the path: a dive keeps its speed, and its q grows, at low speed the larger share) this is a
  // least altitude rate,
  //   hdot_min = -H (ln(D_lim / D) / tau + 2 D / V + d ln(D_lim)/dt) / (1 + 2 g H / V^2),
  // held by the altitude-rate law L cos(sigma) = need + k_c (hdot_min - hdot) when the vehicle
  // sinks faster (an upper bound on |sigma|; above the limit hdot_min > 0: a climb).
  const double lod = in.drag_mps2 > 1e-9 ? in.lift_mps2 / in.drag_mps2 : 0.0;
  if (in.drag_limit_mps2 < kUnbounded && in.drag_mps2 > 1e-6 && in.lift_mps2 > 1e-6) {
    // The horizon grows by the roll to wings level (a slow roll from a large bank lets the
    // vehicle sink for that long before the lift comes back).
    const double roll_s = in.sigma_rate_radps > 0.0 ? std::fabs(in.sigma_flown_rad) / in.sigma_rate_radps : 0.0;
    const double dive_share = 2.0 * gravity_mps2(in.radius_m) * in.scale_height_m / (v * v);
    out.hdot_min_mps = -in.scale_height_m * (std::log(in.drag_limit_mps2 / in.drag_mps2) / (p.constraint_time_s + roll_s) +
                                             2.0 * in.drag_mps2 / v + in.drag_limit_rate_ps) / (1.0 + dive_share);
    if (hdot < out.hdot_min_mps) {
      const double cos_bound = (need + p.constraint_gain_ps * (out.hdot_min_mps - hdot)) / in.lift_mps2;
      if (cos_bound > std::cos(sigma)) {
        sigma = std::acos(clamp(cos_bound, -1.0, 1.0));
        out.bounded = true;
      }
    }
  }
  // Predictive pull-out guard on the sink in excess of the glide's (the glide's own descent
  // follows its falling equilibrium height and needs no arresting). Near orbital speed the
  // glide's height is undetermined (need -> 0): the whole sink is judged there, the glide's
  // share phased in as the need reaches pullout_glide_need of g0. Roll time from the bank flown
  // plus the filter lag.
  const double t_roll =
      in.sigma_rate_radps > 0.0 ? std::fabs(in.sigma_flown_rad) / in.sigma_rate_radps + p.roll_lag_s : p.roll_lag_s;
  const double glide_share = clamp(need / (p.pullout_glide_need * kG0_mps2), 0.0, 1.0);
  const double hdot_glide = qeg_altitude_rate_mps(v, in.radius_m, in.latitude_rad, in.heading_rad, in.drag_mps2,
                                                  in.scale_height_m);
  if (in.drag_limit_mps2 < kUnbounded &&
      pullout_exceeds(in.drag_mps2, lod, hdot - glide_share * hdot_glide, need, in.scale_height_m, in.sigma_flown_rad,
                      t_roll, in.drag_limit_mps2)) {
    sigma = 0.0;
    out.pullout_guard = true;
  }
  out.sigma_rad = sigma;
  return out;
}

void PcLateral::init(const PredictorCorrectorParams& params, const TaemTarget& taem, double sigma_rate_max_radps,
                     double entry_energy_Jpkg, double taem_energy_Jpkg) {
  bind(params);
  sigma_rate_max_radps_ = sigma_rate_max_radps;
  taem_ = taem;
  entry_energy_Jpkg_ = entry_energy_Jpkg;
  taem_energy_Jpkg_ = taem_energy_Jpkg;
}

ArrivalGeometry PcLateral::geometry(double latitude_rad, double longitude_rad, double velocity_mps,
                                    double flight_path_rad, double lift_mps2, double sigma_mag_rad) const {
  // Right spherical triangle aim - vehicle - foot on the line: hypotenuse b, angle eps at the aim
  // between the reversed arrival heading and the vehicle: tan(along) = tan b cos eps,
  // sin(cross) = sin b sin eps. Target heading: the field of Nelson et al. 2007 onto the line,
  // chi_d = chi_line + sign(y) min(chi_inf (2/pi) atan(|y| / y_s), sqrt(2 k |y| / R_turn)),
  // R_turn = V^2 cos(gamma) / (L sin|sigma|).
  const PredictorCorrectorParams& p = *params_;
  ArrivalGeometry g;
  const GreatCircleBothWays to_aim =
      great_circle_both_ways(latitude_rad, longitude_rad, taem_.latitude_rad, taem_.longitude_rad);
  const double b = to_aim.arc_rad;
  g.range_m = kEarthRadius_m * b;
  double eps = 0.0;
  if (g.range_m > p.aim_min_range_m) eps = wrap_pi(to_aim.back_azimuth_rad - (taem_.heading_rad + M_PI));
  const double sb = std::sin(b);
  g.along_m = kEarthRadius_m * std::atan2(sb * std::cos(eps), std::cos(b));
  g.cross_m = kEarthRadius_m * std::asin(clamp(sb * std::sin(eps), -1.0, 1.0));
  g.line_heading_rad = to_aim.azimuth_rad - eps;
  double approach = p.approach_angle_max_rad * (2.0 / M_PI) * std::atan(std::fabs(g.cross_m) / p.cross_track_scale_m);
  const double turn_accel = lift_mps2 * std::sin(sigma_mag_rad);
  if (turn_accel > 1e-6) {
    const double r_turn = velocity_mps * velocity_mps * std::cos(flight_path_rad) / turn_accel;
    approach = std::fmin(approach, std::sqrt(2.0 * p.approach_turn_factor * std::fabs(g.cross_m) / r_turn));
  }
  // At most n times the line of sight's angle off the line (eps): flown at n |eps| towards the
  // line, the offset falls as y ~ x^n with the distance x to go, so with n > 1 the vehicle joins
  // the line ahead of the aim on its heading, spreading the turn over the flight; far from the
  // aim the field alone would steer up to chi_inf for an offset of a few degrees of sight line.
  approach = std::fmin(approach, p.sight_line_factor * std::fabs(eps));
  g.target_heading_rad = wrap_pi(g.line_heading_rad + std::copysign(approach, g.cross_m));
  return g;
}

double PcLateral::half_width_rad(double energy_Jpkg) const {
  const double x = clamp((energy_Jpkg - taem_energy_Jpkg_) / (entry_energy_Jpkg_ - taem_energy_Jpkg_), 0.0, 1.0);
  return params_->corridor_taem_rad + (params_->corridor_entry_rad - params_->corridor_taem_rad) * x;
}

bool PcLateral::capture_waits_for_plan(double energy_Jpkg, double plan_reversal_energy_Jpkg) const {
  return params_->capture_waits_for_plan != 0 && plan_reversal_energy_Jpkg > 0.0 &&
         energy_Jpkg > plan_reversal_energy_Jpkg;
}

double PcLateral::time_to_go_s(const PcLateralInput& in) const {
  const double v_f = std::fmin(taem_.velocity_mps, in.velocity_mps);
  return (in.energy_Jpkg - taem_energy_Jpkg_) / std::fmax(in.drag_mps2 * 0.5 * (in.velocity_mps + v_f), 1e-6);
}

bool PcLateral::final_balance_passed(const PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g,
                                     double t_go_s) const {
  // No reversal when the turn flown now already ends within final_keep_fraction of the TAEM
  // heading and range tolerances (each reversal rolls through wings level: a climb).
  // Heading and cross-track at TAEM after a roll started now to the other side (the tracker's
  // final-turn prediction): the balance psi_f - (heading_tol / range_tol) y_f has passed zero on
  // the side being turned to when it would not come back even with that roll.
  const PredictorCorrectorParams& p = *params_;
  FinalTurnInput f;
  f.speed_mps = in.velocity_mps;
  f.taem_speed_mps = taem_.velocity_mps;
  f.t_go_s = t_go_s;
  f.lift_horizontal_mps2 = in.lift_mps2 / std::cos(in.flight_path_rad);
  f.sigma_now_rad = in.sigma_flown_rad;
  f.sigma_end_rad = -st.sign * in.sigma_mag_rad;
  f.sigma_rate_radps = sigma_rate_max_radps_;
  f.roll_lag_s = p.roll_lag_s;
  f.heading_err_rad = wrap_pi(in.heading_rad - g.line_heading_rad);
  f.cross_track_m = g.cross_m;
  f.steps = p.final_turn_steps;
  FinalTurnInput keep = f;
  keep.sigma_end_rad = st.sign * in.sigma_mag_rad;
  const FinalTurnState kept = predict_final_turn(keep);
  if (std::fabs(kept.heading_err_rad) < p.final_keep_fraction * taem_.heading_tol_rad &&
      std::fabs(kept.cross_track_m) < p.final_keep_fraction * taem_.range_tol_m) {
    return false;
  }
  const FinalTurnState turn = predict_final_turn(f);
  const double w = taem_.range_tol_m > 0.0 && taem_.heading_tol_rad > 0.0 ? taem_.heading_tol_rad / taem_.range_tol_m : 0.0;
  return st.sign * (turn.heading_err_rad - w * turn.cross_track_m) >= 0.0;
}

void PcLateral::decide(PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g) const {
  const int before = st.sign;
  decide_sign(st, in, g);
  if (before != 0 && st.sign != before) st.reversing = true;
  else if (st.reversing && in.sigma_flown_rad * st.sign > 0.0 &&
           std::fabs(in.sigma_flown_rad - st.sign * in.sigma_mag_rad) < params_->bank_settled_rad) {
    st.reversing = false;
  }
}

void PcLateral::decide_sign(PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g) const {
  const PredictorCorrectorParams& p = *params_;
  const double err = wrap_pi(in.heading_rad - g.target_heading_rad);
  if (st.sign == 0) {
    st.sign = err > 0.0 ? -1 : 1;  // towards the target heading
    return;
  }
  const bool rolling = in.sigma_flown_rad * st.sign < 0.0;
  const double t_go = time_to_go_s(in);
  const double t_rev = 2.0 * in.sigma_mag_rad / sigma_rate_max_radps_;
  if (t_go < p.final_reversal_window * t_rev) {
    const bool settled = !rolling && std::fabs(in.sigma_flown_rad - st.sign * in.sigma_mag_rad) < p.bank_settled_rad;
    const bool may_roll = st.final_done ? settled && !st.correction_done : !rolling;
    if (may_roll && final_balance_passed(st, in, g, t_go)) {
      if (st.final_done) st.correction_done = true;
      st.final_done = true;
      st.sign = -st.sign;
    }
    return;
  }
  if (rolling || in.hold_side) return;
  const double w = half_width_rad(in.energy_Jpkg);
  if (st.sign > 0 && err > w) st.sign = -1;  // right of the corridor while turning right: bank left
  else if (st.sign < 0 && err < -w) st.sign = 1;
  if (!in.capture_waits) {
    const double limit = capture_limit_m(g);
    if (capture_overshoot_m(st, in, g, limit) > limit) st.sign = -st.sign;
  }
}

double PcLateral::capture_limit_m(const ArrivalGeometry& g) const {
  return std::fmax(params_->capture_overshoot_m, params_->capture_overshoot_range_fraction * std::fmax(g.along_m, 0.0));
}

double PcLateral::capture_overshoot_m(const PcLateralState& st, const PcLateralInput& in, const ArrivalGeometry& g,
                                      double limit_m) const {
  // Farther than the limit from the line and turning towards it at heading psi to the line: a
  // turn away started now rolls for T = (|sigma_flown| + |sigma|) / rate + lag, flying V T sin(psi)
  // towards the line, then follows the circular arc R (1 - cos psi) of its turn radius
  // R = V^2 cos(gamma) / (L sin|sigma|) (the tracker's capture guard, docs/guidance_design.md 5.3,
  // in closed form). Not with the bank past 90 deg (the roll through wings level takes long).
  const int toward = g.cross_m >= 0.0 ? 1 : -1;
  const double y = std::fabs(g.cross_m);
  if (st.sign != toward || y <= limit_m || in.sigma_mag_rad >= 0.5 * M_PI) return 0.0;
  const double psi = toward * wrap_pi(in.heading_rad - g.line_heading_rad);
  const double turn = in.lift_mps2 * std::sin(in.sigma_mag_rad);
  if (!(psi > 0.0) || !(turn > 1e-6)) return 0.0;
  const double v = in.velocity_mps;
  const double r_turn = v * v * std::cos(in.flight_path_rad) / turn;
  const double t_roll = (std::fabs(in.sigma_flown_rad) + in.sigma_mag_rad) / sigma_rate_max_radps_ + params_->roll_lag_s;
  return r_turn * (1.0 - std::cos(psi)) + v * t_roll * std::sin(psi) - y;
}

}  // namespace reentry::fsw
