#include "predictor_corrector/predictor.hpp"

#include <cmath>

#include "filter/rate_filter.hpp"
#include "planner/mission_geometry.hpp"

namespace reentry::fsw {
namespace {

bool finite_state(const PointMassState& x) {
  return std::isfinite(x.radius_m) && std::isfinite(x.longitude_rad) && std::isfinite(x.latitude_rad) &&
         std::isfinite(x.velocity_mps) && std::isfinite(x.flight_path_rad) && std::isfinite(x.heading_rad);
}

/// Samples a prediction on kProfileCapacity energies, uniform from the start energy to the TAEM
/// energy, as the steps pass them (state linear in energy within a step).
class ProfileRecorder {
 public:
  ProfileRecorder(ReferenceProfile* out, const PointMassModel& model, const PcLimits& limits, double e0, double ef)
      : out_(out), model_(model), limits_(limits), e0_(e0), de_((e0 - ef) / (kProfileCapacity - 1)) {}

  /// Every grid energy in [e_b, e_a] from the step a -> b, flown at the signed command sigma.
  void add(const PointMassState& a, double e_a, const PointMassState& b, double e_b, double sigma_rad) {
    if (out_ == nullptr) return;
    for (; next_ < kProfileCapacity; ++next_) {
      const double e = e0_ - de_ * next_;
      if (e < e_b) return;
      const double w = e_a > e_b ? (e_a - e) / (e_a - e_b) : 0.0;
      store(next_, interpolate(a, b, clamp(w, 0.0, 1.0)), e, sigma_rad);
    }
  }
  /// The points not reached get the final state (a prediction ended early).
  void finish(const PointMassState& x, double e, double sigma_rad) {
    if (out_ == nullptr) return;
    for (; next_ < kProfileCapacity; ++next_) store(next_, x, e, sigma_rad);
    out_->n_points = kProfileCapacity;
  }

 private:
  void store(int k, const PointMassState& x, double e, double sigma_rad) {
    ReferenceProfile& p = *out_;
    const AeroSample a = model_.aero_at(x, e);
    const double alpha = a.alpha_rad;
    p.energy_Jpkg[k] = e;
    p.e_norm[k] = e / model_.entry_energy_Jpkg();
    p.drag_mps2[k] = a.drag_mps2;
    p.radius_m[k] = x.radius_m;
    p.velocity_mps[k] = x.velocity_mps;
    p.gamma_rad[k] = x.flight_path_rad;
    p.heading_rad[k] = x.heading_rad;
    p.alpha_rad[k] = alpha;
    p.lift_over_drag[k] = a.cd > 0.0 ? a.cl / a.cd : 0.0;
    p.sigma_rad[k] = sigma_rad;
    p.dynamic_pressure_Pa[k] = 0.5 * a.density_kgpm3 * x.velocity_mps * x.velocity_mps;
    p.drag_max_mps2[k] = constraint_drag_limit_mps2(model_.models(), limits_, x.velocity_mps, alpha, a.cl, a.cd);
    p.drag_prime[k] = p.drag_second[k] = p.a_coef[k] = p.b_coef[k] = 0.0;
  }

  ReferenceProfile* out_;
  const PointMassModel& model_;
  const PcLimits& limits_;
  double e0_, de_;
  int next_ = 0;
};

}  // namespace

double BankProfile::sigma0_rad() const {
  const double u = clamp(control, 0.0, control_max());
  if (u <= lateral_bank_rad) return u;
  if (u <= lateral_bank_rad + alpha_span) return lateral_bank_rad;
  const double far = u - (bank_max_rad + 2.0 * alpha_span);
  return far > 0.0 ? bank_max_rad + far : std::fmin(u - alpha_span, bank_max_rad);
}

double BankProfile::alpha_shift_rad() const {
  if (!(alpha_span > 0.0)) return 0.0;
  const double u = clamp(control, 0.0, control_max());
  if (u <= lateral_bank_rad) return -alpha_band_rad;
  if (u <= lateral_bank_rad + alpha_span) return -alpha_band_rad * (1.0 - (u - lateral_bank_rad) / alpha_span);
  const double past = u - (bank_max_rad + alpha_span);
  return past > 0.0 ? alpha_band_rad * std::fmin(past / alpha_span, 1.0) : 0.0;
}

double BankProfile::control_for_bank(double sigma0_rad) const {
  const double s = clamp(sigma0_rad, 0.0, bank_max_rad);
  return s <= lateral_bank_rad ? s : s + alpha_span;
}

double BankProfile::at(double energy_Jpkg) const {
  const double s0 = sigma0_rad();
  if (!(e0_Jpkg > ef_Jpkg)) return sigmaf_rad();
  const double x = clamp((e0_Jpkg - energy_Jpkg) / (e0_Jpkg - ef_Jpkg), 0.0, 1.0);
  return s0 + (sigmaf_rad() - s0) * x;  // Lu 2014: linear in energy
}

double local_scale_height_m(const OnboardModels& models, double altitude_m) {
  const double slope = models.atmosphere().dlnrho_dr_pm(altitude_m);
  return slope < 0.0 ? clamp(-1.0 / slope, 3000.0, 15000.0) : 15000.0;
}

Status Predictor::init(PointMassModel* model, const PcLateral* lateral, const PredictorCorrectorParams* params,
                       const PredictorConfig& config) {
  model_ = model;
  lateral_ = lateral;
  params_ = params;
  config_ = config;
  if (model == nullptr || lateral == nullptr || params == nullptr) return Status::kInvalidInput;
  if (!(config.sigma_rate_max_radps > 0.0) || !(config.sigma_accel_max_radps2 > 0.0) || !(params->step_s > 0.0) ||
      params->max_steps < 1 || params->max_steps > PredictorCorrectorParams::kMaxSteps) {
    return Status::kInvalidInput;
  }
  return Status::kOk;
}

double Predictor::command(const PointMassState& x, const AeroSample& a, double energy, const BankProfile& bank,
                          double sigma_flown_rad, PcLateralState& lateral) const {
  const OnboardModels& models = model_->models();
  const double H = local_scale_height_m(models, a.altitude_m);
  BankLawInput in;
  in.sigma_base_rad = clamp(bank.at(energy), 0.0, params_->bank_damped_max_rad);  // alpha: a.alpha_rad (shifted)
  in.sigma_flown_rad = sigma_flown_rad;
  in.velocity_mps = x.velocity_mps;
  in.radius_m = x.radius_m;
  in.latitude_rad = x.latitude_rad;
  in.heading_rad = x.heading_rad;
  in.flight_path_rad = x.flight_path_rad;
  in.drag_mps2 = a.drag_mps2;
  in.lift_mps2 = a.lift_mps2;
  in.scale_height_m = H;
  // The profile's bank rate along E' = -D V (|sigma| linear in E).
  const double sigma_dot = bank.slope_per_Jpkg() * a.drag_mps2 * x.velocity_mps;
  const double hdot_glide = qeg_altitude_rate_mps(x.velocity_mps, x.radius_m, x.latitude_rad, x.heading_rad,
                                                  a.drag_mps2, H, in.sigma_base_rad, sigma_dot);
  // The glide's height differs from the vehicle's by H ln(L cos(sigma_base) / need) (L ~ rho).
  const double need = level_flight_lift_need_mps2(x.radius_m, x.velocity_mps * std::cos(x.flight_path_rad),
                                                  x.latitude_rad, x.heading_rad);
  const double vertical = a.lift_mps2 * std::cos(in.sigma_base_rad);
  const double to_glide_m = need > 0.0 && vertical > 0.0 ? H * std::log(vertical / need) : 0.0;
  in.hdot_ref_mps = hdot_glide + position_gain_ps(need, H, *params_) * clamp(to_glide_m, -3.0 * H, 3.0 * H);
  TerminalAltitude terminal = config_.terminal;
  terminal.target_altitude_m = bank.terminal_altitude_m;
  in.terminal = terminal.at(energy, a.altitude_m, x.velocity_mps, a.drag_mps2, *params_);
  in.drag_limit_mps2 = constraint_drag_limit_mps2(models, config_.limits, x.velocity_mps, a.alpha_rad, a.cl, a.cd);
  in.drag_limit_rate_ps =
      constraint_drag_limit_rate_ps(models, config_.limits, x.velocity_mps, a.drag_mps2, a.alpha_rad, a.cl, a.cd);
  in.sigma_rate_radps = config_.sigma_rate_max_radps;
  in.skip_phase = a.drag_mps2 < config_.capture_drag_mps2;
  PcLateralInput li;
  li.energy_Jpkg = energy;
  li.velocity_mps = x.velocity_mps;
  li.heading_rad = x.heading_rad;
  li.flight_path_rad = x.flight_path_rad;
  li.drag_mps2 = a.drag_mps2;
  li.lift_mps2 = a.lift_mps2;
  li.sigma_flown_rad = sigma_flown_rad;
  li.hold_side = bank.reversal_hold_Jpkg > 0.0 && energy > bank.reversal_hold_Jpkg;
  const BankLawOutput law = bank_magnitude(in, *params_);
  const ArrivalGeometry g =
      lateral_->geometry(x.latitude_rad, x.longitude_rad, x.velocity_mps, x.flight_path_rad, a.lift_mps2, law.sigma_rad);
  li.sigma_mag_rad = law.sigma_rad;
  lateral_->decide(lateral, li, g);
  return lateral.sign * law.sigma_rad;
}

void Predictor::note_air(const AeroSample& a, double v_mps, Prediction& pr) const {
  const double q = 0.5 * a.density_kgpm3 * v_mps * v_mps;
  pr.heat_flux_max_Wpm2 = std::fmax(pr.heat_flux_max_Wpm2, model_->models().heat_flux_Wpm2(a.density_kgpm3, v_mps, a.alpha_rad));
  pr.q_max_Pa = std::fmax(pr.q_max_Pa, q);
  pr.q_alpha_max_Pa_rad = std::fmax(pr.q_alpha_max_Pa_rad, q * a.alpha_rad);
  pr.aero_accel_max_mps2 = std::fmax(pr.aero_accel_max_mps2, std::hypot(a.drag_mps2, a.lift_mps2));
}

bool Predictor::step(const PointMassState& x, const AeroSample& air_of_x, double e, double sigma_a, double sigma_b,
                     double ef, PointMassState& xn, double& en, double& h) const {
  // One step; a step that passes the TAEM energy is shortened onto it (fraction by secant on E,
  // bounded refinements). Returns true when the TAEM energy is reached.
  h = params_->step_s;
  model_->rk4(x, sigma_a, sigma_b, h, xn, &air_of_x);
  en = energy_of(xn);
  if (!(en <= ef) || !finite_state(xn)) return false;
  double f = (e - ef) / (e - en);
  for (int i = 0; i < 3; ++i) {
    model_->rk4(x, sigma_a, sigma_a + f * (sigma_b - sigma_a), f * params_->step_s, xn, &air_of_x);
    en = energy_of(xn);
    if (std::fabs(en - ef) < 1e-3 * std::fabs(e - ef) + 1e-6) break;
    f = clamp(f * (e - ef) / (e - en), 0.0, 1.0);
  }
  h = f * params_->step_s;
  return true;
}

void Predictor::finish(const PointMassState& x, double e, double t, double range_rad, Prediction& pr) const {
  pr.final_state = x;
  pr.energy_Jpkg = e;
  pr.time_s = t;
  pr.range_flown_m = kEarthRadius_m * range_rad;
  const ArrivalGeometry g = lateral_->geometry(x.latitude_rad, x.longitude_rad, x.velocity_mps, x.flight_path_rad, 0.0, 0.0);
  pr.along_m = g.along_m;
  pr.cross_m = g.cross_m;
  pr.heading_err_rad = wrap_pi(x.heading_rad - lateral_->taem().heading_rad);
  pr.altitude_m = height_above_ellipsoid_m(x.radius_m, x.latitude_rad);
}

double Predictor::step_alpha_rad(const AeroSample& a, double v_mps, double e, double sigma_cmd_rad, double sigma_mid_rad,
                                 bool reversing) const {
  // The roll's lift modulation over the step (the bank at mid-step), within the band, as far as
  // the heat flux allows; then the load relief.
  const double alpha_min = model_->profile_alpha_at(e) - params_->alpha_band_rad;
  double alpha = a.alpha_rad;
  if (reversing) {
    alpha = reversal_alpha_rad(model_->models(), a.alpha_rad, a.mach, std::fabs(sigma_cmd_rad), sigma_mid_rad,
                               config_.sigma_rate_max_radps, alpha_min, a.density_kgpm3, v_mps, config_.limits, *params_);
  }
  if (a.cd > 0.0) {
    alpha = load_relief_alpha_rad(model_->models().aero(), alpha, a.mach, a.drag_mps2 / a.cd, config_.limits, alpha_min);
  }
  return alpha;
}

Prediction Predictor::run(const PredictionStart& start, const BankProfile& bank, ReferenceProfile* record,
                          PredictionTrace* trace) const {
  Prediction pr;
  const double ef = bank.ef_Jpkg;
  model_->set_alpha_shift(bank.alpha_shift_rad(), config_.terminal.taem_energy_Jpkg +
                                                      params_->terminal_span_fraction * config_.terminal.span_Jpkg,
                          ef);
  RateFilter filter;  // the cycle's bank filter, at the step
  filter.init(config_.sigma_rate_max_radps, config_.sigma_accel_max_radps2, params_->step_s);
  filter.reset(start.sigma_flown_rad);
  PointMassState x = start.x;
  double e = energy_of(x), t = 0.0, range_rad = 0.0, sigma_cmd = 0.0;
  PcLateralState lateral = start.lateral;
  bool captured = start.captured;
  pr.first_sign = lateral.sign;
  ProfileRecorder rec(record, *model_, config_.limits, e, ef);
  if (trace != nullptr) trace->n = 0;
  pr.end = PredictionEnd::kTimeOut;
  for (int k = 0; k < params_->max_steps; ++k) {
    const AeroSample a = model_->aero_at(x, e);
    note_air(a, x.velocity_mps, pr);
    if (!captured) {
      const double need = level_flight_lift_need_mps2(x.radius_m, x.velocity_mps * std::cos(x.flight_path_rad),
                                                      x.latitude_rad, x.heading_rad);
      captured = capture_due(a.drag_mps2, a.lift_mps2, x.velocity_mps * std::sin(x.flight_path_rad), need,
                             local_scale_height_m(model_->models(), a.altitude_m), config_.capture_drag_mps2, *params_);
    }
    if (captured) {
      const int sign = lateral.sign;
      sigma_cmd = command(x, a, e, bank, filter.value(), lateral);
      if (sign == 0) pr.first_sign = lateral.sign;
      else if (lateral.sign != sign && ++pr.reversals == 1) pr.first_reversal_energy_Jpkg = e;
    }
    const double s_a = filter.value(), s_b = filter.step(sigma_cmd);
    const double alpha_mod = step_alpha_rad(a, x.velocity_mps, e, sigma_cmd, 0.5 * (s_a + s_b),
                                           lateral.reversing && config_.terminal.modulates(e, *params_));
    model_->set_alpha_modulation(alpha_mod - a.alpha_rad);
    if (trace != nullptr && trace->n < PredictionTrace::kCapacity) {
      trace->t_s[trace->n] = t;
      trace->sigma_rad[trace->n] = s_a;
      trace->alpha_rad[trace->n++] = alpha_mod;
    }
    PointMassState xn;
    double en = 0.0, h = 0.0;
    const bool at_taem = step(x, a, e, s_a, s_b, ef, xn, en, h);
    model_->set_alpha_modulation(0.0);
    if (!finite_state(xn) || !std::isfinite(en)) {
      pr.end = PredictionEnd::kNonFinite;
      break;
    }
    range_rad += great_circle_arc_rad(x.latitude_rad, x.longitude_rad, xn.latitude_rad, xn.longitude_rad);
    rec.add(x, e, xn, at_taem ? ef : en, sigma_cmd);
    x = xn;
    e = en;
    t += h;
    pr.steps = k + 1;
    if (trace != nullptr && at_taem && trace->n < PredictionTrace::kCapacity) {
      trace->t_s[trace->n] = t;
      trace->sigma_rad[trace->n] = s_a + (s_b - s_a) * h / params_->step_s;
      trace->alpha_rad[trace->n++] = model_->alpha_at(e);
    }
    const double alt = height_above_ellipsoid_m(x.radius_m, x.latitude_rad);
    pr.end = at_taem ? PredictionEnd::kTaem
                     : (alt <= 0.0 ? PredictionEnd::kGround
                                   : (captured && alt > config_.skip_out_altitude_m ? PredictionEnd::kSkipOut
                                                                                   : PredictionEnd::kTimeOut));
    if (pr.end != PredictionEnd::kTimeOut) break;
  }
  rec.finish(x, e, sigma_cmd);
  finish(x, e, t, range_rad, pr);
  return pr;
}

}  // namespace reentry::fsw
