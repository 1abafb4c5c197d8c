#include "predictor_corrector/pc_planner.hpp"

#include <cmath>

namespace reentry::fsw {
namespace {

constexpr double kSkipOutMargin_m = 20000.0;  // above the entry altitude after capture: skip-out

int sign_of(double bank_rad) { return bank_rad > 0.0 ? 1 : (bank_rad < 0.0 ? -1 : 0); }

bool finite_state(const RelativeState& s) {
  const double v[] = {s.t_s,           s.radius_m,      s.longitude_rad, s.latitude_rad,         s.velocity_mps,
                      s.flight_path_rad, s.heading_rad, s.energy_Jpkg,   s.drag_mps2, s.lift_over_drag_scale,
                      s.bank_rad, s.alpha_rad};
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

/// A prediction's path maxima within the planned limits, or no worse than the reference's where
/// that one already exceeds them (0: not constrained).
bool within_planned_limits(const Prediction& pr, const Prediction& ref, const PcLimits& lim) {
  const auto ok = [](double x, double x_ref, double limit) { return !(limit > 0.0) || x <= std::fmax(limit, x_ref); };
  return ok(pr.q_max_Pa, ref.q_max_Pa, lim.q_max_Pa) && ok(pr.q_alpha_max_Pa_rad, ref.q_alpha_max_Pa_rad, lim.q_alpha_max_Pa_rad) &&
         ok(pr.heat_flux_max_Wpm2, ref.heat_flux_max_Wpm2, lim.heat_flux_max_Wpm2) &&
         ok(pr.aero_accel_max_mps2, ref.aero_accel_max_mps2, lim.load_factor_max_mps2);
}

}  // namespace

Status PredictorCorrectorPlanner::init(const OnboardModels& models, const AlphaProfile& alpha_profile,
                                       const GuidanceMission& mission, const PredictorCorrectorParams& params,
                                       double capture_drag_mps2, const PcPlanTiming& timing) {
  initialised_ = false;
  if (pc_params_inconsistency(params) != nullptr || timing.latency_ticks < 0 || !(timing.tick_s > 0.0)) {
    return Status::kInvalidInput;
  }
  models_ = models;
  alpha_profile_ = alpha_profile;
  mission_ = mission;
  params_ = params;
  timing_ = timing;
  capture_drag_mps2_ = capture_drag_mps2;
  entry_energy_ = specific_energy_Jpkg(kEarthRadius_m + mission.entry.altitude_m, mission.entry.velocity_mps);
  const TaemTarget& t = mission.taem;
  taem_energy_ = specific_energy_Jpkg(surface_radius_m(t.latitude_rad) + t.altitude_m, t.velocity_mps);
  if (!(entry_energy_ > taem_energy_)) return Status::kInvalidInput;
  model_.init(&models_, &alpha_profile_, entry_energy_, mission.limits.alpha_max_rad);
  lateral_.init(params_, t, mission.limits.sigma_rate_max_radps, entry_energy_, taem_energy_);
  limits_ = pc_limits_from(mission.limits, params.constraint_margin, params.drag_model_uncertainty);
  limits_unmargined_ = pc_limits_from(mission.limits, 1.0, params.drag_model_uncertainty);
  PredictorConfig cfg;
  cfg.limits = limits_;
  cfg.capture_drag_mps2 = capture_drag_mps2;
  cfg.sigma_rate_max_radps = mission.limits.sigma_rate_max_radps;
  cfg.sigma_accel_max_radps2 = mission.limits.sigma_accel_max_radps2;
  cfg.skip_out_altitude_m = mission.entry.altitude_m + kSkipOutMargin_m;
  taem_altitude_ = taem_altitude_target();
  cfg.terminal = TerminalAltitude{taem_energy_, entry_energy_ - taem_energy_, taem_altitude_};
  const Status st = predictor_.init(&model_, &lateral_, &params_, cfg);
  if (st != Status::kOk) return st;
  have_last_ = false;
  last_hold_Jpkg_ = 0.0;
  initialised_ = true;
  return Status::kOk;
}

double PredictorCorrectorPlanner::taem_altitude_target() {
  // The altitude deepest inside the TAEM altitude and Mach bands at the TAEM energy where q and
  // q alpha at the TAEM alpha stay within their planned fraction (as the drag law's planner).
  const TaemTarget& t = mission_.taem;
  const PcLimits& lim = limits_;
  if (!(t.altitude_tol_m > 0.0)) return t.altitude_m;
  const double alpha = model_.alpha_at(taem_energy_);
  double best_h = t.altitude_m, best_depth = -1e300;
  taem_aim_min_m_ = t.altitude_m + t.altitude_tol_m;
  const int n = params_.taem_altitude_samples;
  const auto altitude = [&](int i) { return t.altitude_m - t.altitude_tol_m + 2.0 * t.altitude_tol_m * i / n; };
  const auto within_q = [&](double h) {
    const double v = OnboardModels::taem_speed_mps(t.latitude_rad, taem_energy_, h);
    const double q = 0.5 * models_.atmosphere().density_kgpm3(h) * v * v;
    return v > 0.0 && !(lim.q_max_Pa > 0.0 && q > lim.q_max_Pa) &&
           !(lim.q_alpha_max_Pa_rad > 0.0 && q * alpha > lim.q_alpha_max_Pa_rad);
  };
  for (int i = 0; i <= n; ++i) {
    const double h = altitude(i);
    if (!within_q(h)) continue;
    taem_aim_min_m_ = std::fmin(taem_aim_min_m_, h);  // the lowest TAEM altitude within q and q alpha
    const double depth = models_.taem_band_depth(t, taem_energy_, h);
    if (depth > best_depth) {
      best_depth = depth;
      best_h = h;
    }
  }
  // The range aim's span: the altitudes (within q and q alpha) whose depth in the TAEM altitude and
  // Mach bands is at least (1 - terminal_range_aim_fraction) of the deepest one's.
  range_aim_lo_m_ = range_aim_hi_m_ = best_h;
  for (int i = 0; i <= n && best_depth > 0.0 && params_.terminal_range_aim_fraction > 0.0; ++i) {
    const double h = altitude(i);
    if (!within_q(h) ||
        models_.taem_band_depth(t, taem_energy_, h) < (1.0 - params_.terminal_range_aim_fraction) * best_depth) {
      continue;
    }
    range_aim_lo_m_ = std::fmin(range_aim_lo_m_, h);
    range_aim_hi_m_ = std::fmax(range_aim_hi_m_, h);
  }
  return best_h;
}

double PredictorCorrectorPlanner::final_bank_rad(double density_ratio) const {
  // Quasi-equilibrium glide at the target TAEM state: L cos(sigma_f) = g - V^2/r - 2 w V cos(lat)
  // sin(chi) ((2.45), gamma' = 0), L at K times the model's density.
  const TaemTarget& t = mission_.taem;
  const double h = taem_altitude_;
  const double v = OnboardModels::taem_speed_mps(t.latitude_rad, taem_energy_, h);
  if (!(v > 0.0)) return params_.final_bank_max_rad;
  const double rho = density_ratio * models_.atmosphere().density_kgpm3(h);
  const double lift = 0.5 * rho * v * v * models_.area_over_mass() *
                      models_.aero().cl(model_.alpha_at(taem_energy_), models_.mach(h, v));
  const double need = level_flight_lift_need_mps2(surface_radius_m(t.latitude_rad) + h, v, t.latitude_rad, t.heading_rad);
  const double c = lift > 0.0 ? need / lift : 1.0;
  return std::acos(clamp(c, std::cos(params_.final_bank_max_rad), 1.0));
}

BankProfile PredictorCorrectorPlanner::bank_family() const {
  BankProfile b;
  b.lateral_bank_rad = params_.lateral_bank_rad;
  b.bank_max_rad = params_.bank_max_rad;
  b.bank_far_rad = params_.bank_damped_max_rad;
  b.alpha_band_rad = params_.alpha_band_rad;
  b.alpha_span = params_.alpha_control_scale * params_.alpha_band_rad;
  b.final_share = params_.final_bank_share;
  return b;
}

RelativeState PredictorCorrectorPlanner::entry_state() const {
  const EntryInterface& e = mission_.entry;
  RelativeState s;
  s.radius_m = surface_radius_m(e.latitude_rad) + e.altitude_m;
  s.altitude_m = s.radius_m - kEarthRadius_m;
  s.longitude_rad = e.longitude_rad;
  s.latitude_rad = e.latitude_rad;
  s.velocity_mps = e.velocity_mps;
  s.flight_path_rad = e.flight_path_rad;
  s.heading_rad = e.heading_rad;
  s.energy_Jpkg = specific_energy_Jpkg(s.radius_m, s.velocity_mps);
  const AeroSample a = model_.aero_at(point_mass_from(s));
  s.drag_mps2 = a.drag_mps2 / model_.density_ratio();
  s.lift_mps2 = a.lift_mps2 / model_.density_ratio();
  return s;
}

PredictionStart PredictorCorrectorPlanner::start_from(const RelativeState& from, double& density_ratio) {
  // The executive advanced speed and energy over the latency by V' = -D, E' = -D V with the
  // position frozen (exec::predict_state): the speed is taken back to the navigated one and the
  // whole state is predicted over the latency by the on-board equations, the flown bank held.
  PointMassState x = point_mass_from(from);
  for (int i = 0; i < timing_.latency_ticks; ++i) x.velocity_mps += from.drag_mps2 * timing_.tick_s;
  models_.aero().set_lift_scale(clamp(from.lift_over_drag_scale, params_.lod_ratio_min, params_.lod_ratio_max));
  // K at the alpha flown (given by the executive; else the profile's with the last plan's shift).
  model_.set_density_ratio(1.0);
  model_.set_alpha_shift(have_last_ ? last_bank_.alpha_shift_rad() : 0.0,
                         taem_energy_ + params_.terminal_span_fraction * (entry_energy_ - taem_energy_), taem_energy_);
  const AeroSample a = from.alpha_rad > 0.0 ? model_.aero(x, from.alpha_rad) : model_.aero_at(x);
  density_ratio = 1.0;
  if (from.drag_mps2 >= 0.1 * capture_drag_mps2_ && a.drag_mps2 > 0.0) {
    density_ratio = clamp(from.drag_mps2 / a.drag_mps2, params_.drag_ratio_min, params_.drag_ratio_max);
  }
  model_.set_density_ratio(density_ratio);
  for (int i = 0; i < timing_.latency_ticks; ++i) model_.rk4(x, from.bank_rad, from.bank_rad, timing_.tick_s, x);
  PredictionStart st;
  st.x = x;
  st.sigma_flown_rad = from.bank_rad;
  st.lateral.sign = sign_of(from.bank_rad);
  st.captured = from.drag_mps2 >= capture_drag_mps2_;
  return st;
}

void PredictorCorrectorPlanner::fill(const CorrectorResult& r, const BankProfile& bank, ReferenceProfile& out) const {
  out.n_points = kProfileCapacity;
  out.reversal_energy_Jpkg = r.best.first_reversal_energy_Jpkg;
  out.initial_bank_sign = r.best.first_sign < 0 ? -1 : 1;
  out.entry_energy_Jpkg = entry_energy_;
  out.taem_energy_Jpkg = taem_energy_;
  out.taem_altitude_m = bank.terminal_altitude_m;  // the terminal line's aim (the cycle flies it)
  out.reversal_hold_energy_Jpkg = bank.reversal_hold_Jpkg;
  out.dc_mps2 = 0.0;
  out.e1_Jpkg = 0.0;
  out.e2_Jpkg = 0.0;
  out.trajectory_length_m = r.best.range_flown_m;
  out.ranging_blend = 0.0;
  out.crossrange_err_m = r.best.cross_m;
  out.downrange_err_m = r.best.along_m;
  out.iterations = r.predictions;
  out.converged = r.converged;
}

Status PredictorCorrectorPlanner::plan(const RelativeState& from, ReferenceProfile& out) {
  diag_ = PcPlanDiagnostics{};
  out.n_points = 0;
  if (!initialised_) return out.status = Status::kInvalidInput;
  if (!finite_state(from)) return out.status = Status::kNonFinite;
  if (!(from.velocity_mps > 0.0) || !(from.radius_m > 0.0) || !(from.drag_mps2 >= 0.0)) {
    return out.status = Status::kInvalidInput;
  }
  double k = 1.0;
  const PredictionStart start = start_from(from, k);
  BankProfile bank = bank_family();
  bank.e0_Jpkg = energy_of(start.x);
  bank.ef_Jpkg = taem_energy_;
  if (!(bank.e0_Jpkg > taem_energy_)) return out.status = Status::kInvalidInput;
  bank.sigma_glide_rad = final_bank_rad(k);
  bank.terminal_altitude_m = taem_altitude_ + (have_last_ ? terminal_offset_m_ : 0.0);
  bank.control = have_last_ ? last_bank_.control : bank.control_for_bank(0.5 * params_.bank_max_rad);
  const CorrectorResult r = solve(start, bank, out);
  Status st = r.status;
  // Out of predictions: the best plan is still flown when it misses by little (a replan follows).
  if (st == Status::kNotConverged && std::fabs(r.best.along_m) <= params_.accept_miss_m) st = Status::kOk;
  bank.control = r.control;
  fill(r, bank, out);
  out.status = st;
  if (st == Status::kOk || st == Status::kRangeTooLong || st == Status::kRangeTooShort) {
    last_bank_ = bank;
    have_last_ = true;
    terminal_offset_m_ = bank.terminal_altitude_m - taem_altitude_;
    last_hold_Jpkg_ = bank.reversal_hold_Jpkg;
  } else {
    out.n_points = 0;
  }
  diag_.status = st;
  diag_.converged = r.converged;
  diag_.predictions = r.predictions;
  diag_.sigma0_rad = r.sigma0_rad;
  diag_.alpha_shift_rad = r.alpha_shift_rad;
  diag_.control = r.control;
  diag_.sigmaf_rad = bank.sigmaf_rad();
  diag_.density_ratio = k;
  diag_.lift_scale = models_.aero().lift_scale();
  diag_.miss_along_m = r.best.along_m;
  diag_.miss_cross_m = r.best.cross_m;
  diag_.final_altitude_m = r.best.altitude_m;
  diag_.final_heading_err_rad = r.best.heading_err_rad;
  diag_.reversals = r.best.reversals;
  diag_.best = r.best;
  return st;
}

CorrectorResult PredictorCorrectorPlanner::solve(const PredictionStart& start, BankProfile& bank, ReferenceProfile& out) {
  // sigma_0 for the range; then, while the predicted TAEM altitude misses its target (a late
  // reversal rolls through wings level), the terminal line's aim moved by the miss and sigma_0
  // solved again from its last value, within one budget of predictions.
  const int first = params_.max_predictions - (params_.altitude_iterations > 0 ? params_.altitude_predictions : 0);
  CorrectorResult r = corrector_.solve(predictor_, start, bank, params_, first, &out, &scratch_);
  int used = r.predictions;
  const double band = mission_.taem.altitude_tol_m;
  for (int i = 0; i < params_.altitude_iterations && used < params_.max_predictions && r.best.usable(); ++i) {
    const double dh = r.best.altitude_m - taem_altitude_;
    if (std::fabs(dh) <= params_.altitude_tol_fraction * band) break;
    // The aim within the band, never below the lowest TAEM altitude q and q alpha allow.
    bank.terminal_altitude_m = clamp(bank.terminal_altitude_m - dh, std::fmax(taem_altitude_ - band, taem_aim_min_m_),
                                     taem_altitude_ + band);
    bank.control = r.control;
    r = corrector_.solve(predictor_, start, bank, params_, params_.max_predictions - used, &out, &scratch_);
    used += r.predictions;
  }
  r.predictions = used;
  bank.control = r.control;  // the range controls below fly the member the corrector chose
  // Not before capture: the initial descent flies wings level, and the plan at capture replaces
  // this one.
  if (start.captured && (r.status == Status::kRangeTooLong || r.status == Status::kRangeTooShort)) {
    range_by_terminal_aim(start, bank, r, out);
  }
  if (start.captured && r.status == Status::kRangeTooLong) range_by_reversal_hold(start, bank, r, out);
  return r;
}

void PredictorCorrectorPlanner::range_by_reversal_hold(const PredictionStart& start, BankProfile& bank,
                                                       CorrectorResult& r, ReferenceProfile& out) {
  // Still long at the family's range-long end (the constraint bound, not the bank, holds the
  // vehicle up): the range goes into the ground track. The side flown is held, no corridor
  // reversal, down to the energy E_h: the turn carries the heading off the line of sight and
  // the along-track progress falls with that excursion; below E_h the lateral logic brings the
  // vehicle back onto the arrival line. The miss is not monotonic in E_h (a long hold turns the
  // track past the aim), so E_h marches down from now (first from the last plan's hold) in
  // quarters of the span to the TAEM energy until a hold ends short, then regula falsi inside
  // that bracket. The hold stops corridor and capture-guard reversals only: the final reversal
  // and its correction still turn the vehicle onto the TAEM heading. A prediction is kept when its miss (along and
  // across) is smaller, its TAEM heading no worse than the tolerance or the bound's, and its path
  // maxima within the mission's limits (the planned margin is the cycle's to keep).
  const double e_now = bank.e0_Jpkg;
  const double e_lo = taem_energy_;
  if (params_.reversal_hold_predictions <= 0 || !(e_now > e_lo) || !r.best.usable()) return;
  const Prediction bound = r.best;
  const double heading_ok = std::fmax(mission_.taem.heading_tol_rad, std::fabs(bound.heading_err_rad));
  const double quarter = 0.25 * (e_now - e_lo);
  double ea = e_now, za = bound.along_m;  // the long side of the bracket (z < 0)
  double eb = e_lo, zb = 0.0;             // the short side, once found
  bool bracket = false;
  double best_hold = 0.0;
  double e = last_hold_Jpkg_ > e_lo && last_hold_Jpkg_ < e_now ? last_hold_Jpkg_ : e_now - quarter;
  for (int i = 0; i < params_.reversal_hold_predictions; ++i) {
    bank.reversal_hold_Jpkg = e;
    const Prediction pr = predictor_.run(start, bank, &scratch_);
    ++r.predictions;
    if (!pr.usable()) break;
    if (std::hypot(pr.along_m, pr.cross_m) < std::hypot(r.best.along_m, r.best.cross_m) &&
        std::fabs(pr.heading_err_rad) <= heading_ok && within_planned_limits(pr, bound, limits_unmargined_)) {
      r.best = pr;
      best_hold = e;
      out = scratch_;
    }
    if (std::fabs(pr.along_m) <= params_.miss_tol_m) break;
    if (pr.along_m < 0.0) {  // along-track to go: < 0 long
      ea = e;
      za = pr.along_m;
    } else {
      eb = e;
      zb = pr.along_m;
      bracket = true;
    }
    if (bracket) {
      e = ea - za * (eb - ea) / (zb - za);
    } else {
      if (!(e > e_lo)) break;  // the longest hold is still long
      e = std::fmax(e - quarter, e_lo);
    }
  }
  bank.reversal_hold_Jpkg = best_hold;
  if (std::fabs(r.best.along_m) <= params_.miss_tol_m) {
    r.status = Status::kOk;
    r.converged = true;
  }
}

void PredictorCorrectorPlanner::range_by_terminal_aim(const PredictionStart& start, BankProfile& bank,
                                                      CorrectorResult& r, ReferenceProfile& out) {
  // sigma_0 out of reach: the terminal line's aim becomes the range control, within the range
  // aim's span of the TAEM altitude and Mach bands (taem_altitude_target). Along-track to go
  // falls as the aim rises (thinner air, less drag per unit energy: ds/dE = -1/D). Secant on the
  // aim from the plan's aim; a prediction is kept when it misses less, its TAEM altitude lies
  // within the span (widened by the altitude iteration's own dead band) and its path maxima
  // within the planned limits (no worse than the bank bound's where that one exceeds them).
  const double lo = range_aim_lo_m_, hi = range_aim_hi_m_, band = hi - lo;
  if (!(hi > lo) || !r.best.usable()) return;
  const double alt_slack = params_.altitude_tol_fraction * mission_.taem.altitude_tol_m;
  const Prediction bound = r.best;
  // A fixed step of a quarter of the span towards a shorter (z < 0: long) or longer flight.
  const auto step = [band](double z) { return (z < 0.0 ? -0.25 : 0.25) * band; };
  double h0 = bank.terminal_altitude_m, z0 = r.best.along_m, best_h = h0;
  double h1 = clamp(h0 + step(z0), lo, hi);
  for (int i = 0; i < params_.terminal_range_predictions && h1 != h0; ++i) {
    bank.terminal_altitude_m = h1;
    const Prediction pr = predictor_.run(start, bank, &scratch_);
    ++r.predictions;
    if (!pr.usable()) break;
    if (std::fabs(pr.along_m) < std::fabs(r.best.along_m) && pr.altitude_m >= lo - alt_slack &&
        pr.altitude_m <= hi + alt_slack && within_planned_limits(pr, bound, limits_)) {
      r.best = pr;
      best_h = h1;
      out = scratch_;
    }
    if (std::fabs(pr.along_m) <= params_.miss_tol_m) break;
    const double slope = (pr.along_m - z0) / (h1 - h0);
    const double h2 = slope < 0.0 && std::isfinite(slope) ? h1 - pr.along_m / slope : h1 + step(pr.along_m);
    h0 = h1;
    z0 = pr.along_m;
    h1 = clamp(h2, lo, hi);
  }
  bank.terminal_altitude_m = best_h;
  if (std::fabs(r.best.along_m) <= params_.miss_tol_m) {
    r.status = Status::kOk;
    r.converged = true;
  }
}

Prediction PredictorCorrectorPlanner::predict(const RelativeState& s, double sigma0_rad, double density_ratio,
                                              ReferenceProfile* record, double sigmaf_rad, PredictionTrace* trace) {
  BankProfile bank = bank_family();
  bank.control = bank.control_for_bank(sigma0_rad);
  if (sigmaf_rad >= 0.0) {
    bank.sigma_glide_rad = sigmaf_rad;
    bank.final_share = 0.0;
  } else {
    bank.sigma_glide_rad = final_bank_rad(density_ratio);
  }
  return predict_profile(s, bank, density_ratio, record, trace);
}

Prediction PredictorCorrectorPlanner::predict_profile(const RelativeState& s, BankProfile bank, double density_ratio,
                                                      ReferenceProfile* record, PredictionTrace* trace) {
  models_.aero().set_lift_scale(clamp(s.lift_over_drag_scale, params_.lod_ratio_min, params_.lod_ratio_max));
  model_.set_density_ratio(density_ratio);
  PredictionStart st;
  st.x = point_mass_from(s);
  st.sigma_flown_rad = s.bank_rad;
  st.lateral.sign = sign_of(s.bank_rad);
  st.captured = s.drag_mps2 >= capture_drag_mps2_;
  bank.e0_Jpkg = energy_of(st.x);
  bank.ef_Jpkg = taem_energy_;
  if (!(bank.terminal_altitude_m > 0.0)) bank.terminal_altitude_m = taem_altitude_;
  return predictor_.run(st, bank, record, trace);
}

}  // namespace reentry::fsw
