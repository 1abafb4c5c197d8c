#include "alpha_planner/alpha_planner.hpp"

#include <cmath>

#include "numerics/root_finding.hpp"

namespace reentry::fsw {
namespace {

constexpr double kHeightTol_m = 1e-4;
constexpr double kAlphaTol_rad = 1e-10;
constexpr int kRootMaxIter = 200;
constexpr int kGoldenIter = 60;

bool valid_pct(double p) { return std::isfinite(p) && p >= 0.0 && p <= 100.0; }

}  // namespace

Status AlphaPlanner::init(const OnboardModels& models, const GuidanceMission& mission) {
  initialised_ = false;
  models_ = models;
  const PathLimits& c = mission.limits;
  if (!(c.alpha_max_rad > 0.0) || !(c.alpha_rate_max_radps > 0.0)) return Status::kInvalidInput;
  if (!(mission.entry.velocity_mps > mission.taem.velocity_mps) || !(mission.taem.velocity_mps > 0.0)) {
    return Status::kInvalidInput;
  }
  alpha_max_rad_ = c.alpha_max_rad;
  alpha_rate_max_radps_ = c.alpha_rate_max_radps;
  v_entry_mps_ = mission.entry.velocity_mps;
  h_entry_m_ = mission.entry.altitude_m;
  v_taem_mps_ = mission.taem.velocity_mps;
  entry_energy_Jpkg_ = specific_energy_Jpkg(kEarthRadius_m + h_entry_m_, v_entry_mps_);  // (7.8)
  heat_flux_max_Wpm2_ = c.heat_flux_max_Wpm2;
  load_factor_max_g_ = c.load_factor_max_g;
  q_alpha_max_Pa_rad_ = c.q_alpha_max_Pa_rad;
  dynamic_pressure_max_Pa_ = c.dynamic_pressure_max_Pa;
  if (!(entry_energy_Jpkg_ > 0.0)) return Status::kInvalidInput;
  initialised_ = true;
  return Status::kOk;
}

// ------------------------------------------------------------------ alpha searches
namespace {
// Maximise g(alpha) on [0, alpha_max]: uniform scan, then golden section on the two cells
// around the best node. Bounded by kAlphaScanPoints + kGoldenIter evaluations.
template <class G>
double argmax_alpha(G&& g, double alpha_max_rad, int scan_points) {
  const double step = alpha_max_rad / (scan_points - 1);
  int best = 0;
  double best_value = g(0.0);
  for (int i = 1; i < scan_points; ++i) {
    const double v = g(step * i);
    if (v > best_value) {
      best_value = v;
      best = i;
    }
  }
  double a = step * (best > 0 ? best - 1 : 0);
  double b = step * (best < scan_points - 1 ? best + 1 : scan_points - 1);
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - ratio * (b - a);
  double x2 = a + ratio * (b - a);
  double g1 = g(x1);
  double g2 = g(x2);
  for (int it = 0; it < kGoldenIter && (b - a) > kAlphaTol_rad; ++it) {
    if (g1 < g2) {
      a = x1;
      x1 = x2;
      g1 = g2;
      x2 = a + ratio * (b - a);
      g2 = g(x2);
    } else {
      b = x2;
      x2 = x1;
      g2 = g1;
      x1 = b - ratio * (b - a);
      g1 = g(x1);
    }
  }
  const double x_mid = 0.5 * (a + b);
  const double g_mid = g(x_mid);
  return g_mid >= best_value ? x_mid : step * best;
}
}  // namespace

double AlphaPlanner::alpha_cl_max_rad(double mach) const {
  const OnboardAero& aero = models_.aero();
  return argmax_alpha([&](double a) { return aero.cl(a, mach); }, alpha_max_rad_, kAlphaScanPoints);
}

double AlphaPlanner::alpha_ld_max_rad(double mach) const {
  const OnboardAero& aero = models_.aero();
  return argmax_alpha(
      [&](double a) {
        double cl = 0.0, cd = 0.0;
        aero.coefficients(a, mach, cl, cd);
        return cl / cd;
      },
      alpha_max_rad_, kAlphaScanPoints);
}

double AlphaPlanner::alpha_of(const AlphaLaw& law, double mach) const {
  if (law.fixed_alpha_rad >= 0.0) return law.fixed_alpha_rad;
  const double a_ld = alpha_ld_max_rad(mach);
  const double a_cl = alpha_cl_max_rad(mach);
  return a_ld + law.blend * (a_cl - a_ld);
}

// ------------------------------------------------------------------ heights
// Height where excess(h) changes sign, excess > 0 meaning "too low" (constraint violated or
// lift too large for equilibrium). Not violated anywhere -> kMinHeight_m; violated everywhere
// -> kMaxHeight_m (both kOk: the corridor logic handles them as boundaries of the search box).
template <class F>
Status AlphaPlanner::min_height(F&& excess, double& h_m) const {
  const double f_low = excess(kMinHeight_m);
  const double f_high = excess(kMaxHeight_m);
  if (!std::isfinite(f_low) || !std::isfinite(f_high)) return Status::kNonFinite;
  if (f_low <= 0.0) {
    h_m = kMinHeight_m;
    return Status::kOk;
  }
  if (f_high >= 0.0) {
    h_m = kMaxHeight_m;
    return Status::kOk;
  }
  const numerics::RootResult r = numerics::brent(excess, kMinHeight_m, kMaxHeight_m, kHeightTol_m, kRootMaxIter);
  if (r.status != numerics::NumStatus::kOk) return to_status(r.status);
  h_m = r.x;
  return Status::kOk;
}

Status AlphaPlanner::glide_height(double velocity_mps, const AlphaLaw& law, double& h_m) const {
  if (!initialised_ || !(velocity_mps > 0.0)) return Status::kInvalidInput;
  const double v2 = velocity_mps * velocity_mps;
  auto excess = [&](double h) {
    const double r = kEarthRadius_m + h;
    const double alpha = alpha_of(law, models_.mach(h, velocity_mps));
    // (6.6) divided by m: L/m + V^2/r - g
    return models_.lift_mps2(alpha, h, velocity_mps) + v2 / r - gravity_mps2(r);
  };
  return min_height(excess, h_m);
}

Status AlphaPlanner::heat_flux_height(double velocity_mps, const AlphaLaw& law, double& h_m) const {
  if (!initialised_ || !(velocity_mps > 0.0)) return Status::kInvalidInput;
  if (!std::isfinite(heat_flux_max_Wpm2_)) {
    h_m = kMinHeight_m;
    return Status::kOk;
  }
  auto excess = [&](double h) {  // (6.2) in log form: ln q(h) - ln q_max (alpha: leading-edge models)
    const double alpha = alpha_of(law, models_.mach(h, velocity_mps));
    return std::log(models_.heat_flux_Wpm2(models_.atmosphere().density_kgpm3(h), velocity_mps, alpha)) -
           std::log(heat_flux_max_Wpm2_);
  };
  return min_height(excess, h_m);
}

Status AlphaPlanner::load_factor_height(double velocity_mps, const AlphaLaw& law, double& h_m) const {
  if (!initialised_ || !(velocity_mps > 0.0)) return Status::kInvalidInput;
  if (!std::isfinite(load_factor_max_g_)) {
    h_m = kMinHeight_m;
    return Status::kOk;
  }
  auto excess = [&](double h) {  // (6.7): sqrt(L^2 + D^2) / (m g0) - n_max
    const double alpha = alpha_of(law, models_.mach(h, velocity_mps));
    const double lift = models_.lift_mps2(alpha, h, velocity_mps);
    const double drag = models_.drag_mps2(alpha, h, velocity_mps);
    return std::log(std::sqrt(lift * lift + drag * drag) / kG0_mps2) - std::log(load_factor_max_g_);
  };
  return min_height(excess, h_m);
}

Status AlphaPlanner::q_alpha_height(double velocity_mps, const AlphaLaw& law, double& h_m) const {
  if (!initialised_ || !(velocity_mps > 0.0)) return Status::kInvalidInput;
  if (!std::isfinite(q_alpha_max_Pa_rad_)) {
    h_m = kMinHeight_m;
    return Status::kOk;
  }
  auto excess = [&](double h) {  // (6.8): q alpha - (q alpha)_max
    const double alpha = alpha_of(law, models_.mach(h, velocity_mps));
    const double q = 0.5 * models_.atmosphere().density_kgpm3(h) * velocity_mps * velocity_mps;
    return std::log(q * alpha) - std::log(q_alpha_max_Pa_rad_);
  };
  return min_height(excess, h_m);
}

Status AlphaPlanner::dynamic_pressure_height(double velocity_mps, double& h_m) const {
  if (!initialised_ || !(velocity_mps > 0.0)) return Status::kInvalidInput;
  if (!std::isfinite(dynamic_pressure_max_Pa_)) {
    h_m = kMinHeight_m;
    return Status::kOk;
  }
  auto excess = [&](double h) {  // (6.5)
    const double q = 0.5 * models_.atmosphere().density_kgpm3(h) * velocity_mps * velocity_mps;
    return std::log(q) - std::log(dynamic_pressure_max_Pa_);
  };
  return min_height(excess, h_m);
}

Status AlphaPlanner::extract_alpha(double altitude_m, double velocity_mps, double& alpha_rad, bool& clamped) const {
  if (!initialised_ || !(velocity_mps > 0.0) || !std::isfinite(altitude_m)) return Status::kInvalidInput;
  const double r = kEarthRadius_m + altitude_m;
  const double mach = models_.mach(altitude_m, velocity_mps);
  const double q_s_over_m = 0.5 * models_.atmosphere().density_kgpm3(altitude_m) * velocity_mps * velocity_mps *
                            models_.area_over_mass();
  if (!(q_s_over_m > 0.0)) return Status::kNonFinite;
  const double cl_needed = (gravity_mps2(r) - velocity_mps * velocity_mps / r) / q_s_over_m;  // (6.6)
  const double a_lo = alpha_ld_max_rad(mach);
  const double a_hi = alpha_cl_max_rad(mach);
  const OnboardAero& aero = models_.aero();
  clamped = false;
  if (!(a_hi > a_lo)) {
    alpha_rad = a_hi;
    clamped = true;
    return Status::kOk;
  }
  const double f_lo = aero.cl(a_lo, mach) - cl_needed;
  const double f_hi = aero.cl(a_hi, mach) - cl_needed;
  const double tol_cl = 1e-6 * std::fabs(cl_needed);  // mismatch below this is root-finding noise
  if (f_lo >= 0.0) {
    alpha_rad = a_lo;
    clamped = f_lo > tol_cl;
    return Status::kOk;
  }
  if (f_hi <= 0.0) {
    alpha_rad = a_hi;
    clamped = f_hi < -tol_cl;
    return Status::kOk;
  }
  const numerics::RootResult root =
      numerics::brent([&](double a) { return aero.cl(a, mach) - cl_needed; }, a_lo, a_hi, kAlphaTol_rad, kRootMaxIter);
  if (root.status != numerics::NumStatus::kOk) return to_status(root.status);
  alpha_rad = root.x;
  return Status::kOk;
}

// ------------------------------------------------------------------ plan
Status AlphaPlanner::plan(const AlphaPlanParams& params, AlphaPlanResult& out) const {
  if (!initialised_) return Status::kInvalidInput;
  if (!valid_pct(params.heating_pct) || !valid_pct(params.ranging_pct) || !valid_pct(params.heating_switch_pct) ||
      !valid_pct(params.taem_switch_pct) || params.taem_switch_pct < params.heating_switch_pct) {
    return Status::kInvalidInput;
  }
  out.n_corridor = 0;
  out.n_profile = 0;
  out.closed_points = 0;
  out.clamped_points = 0;
  out.violation_points = 0;
  const AlphaLaw law_ranging{params.ranging_pct / 100.0, -1.0};
  double h_ranging_m[AlphaPlanResult::kGridPoints] = {};
  Status s = build_corridor(law_ranging, h_ranging_m, out);  // 1. corridor over V, entry -> TAEM
  if (s != Status::kOk) return s;
  phase_switch_velocities(params, law_ranging, out);         // 2-3. intersection velocity, dV (6.12)
  s = extract_path_alpha(params, h_ranging_m, out);          // 4. path h(V) per phase, alpha (6.6)
  if (s != Status::kOk) return s;
  smooth_alpha_monotonic(out);                               // 5. isotonic alpha(V)
  evaluate_path(out);                                        //    clamped, constraints on the path
  return sample_profile(out);                                // 6. alpha(E / E_entry)
}

Status AlphaPlanner::build_corridor(const AlphaLaw& law_ranging, double* h_ranging_m, AlphaPlanResult& out) const {
  constexpr int n = AlphaPlanResult::kGridPoints;
  const AlphaLaw law_cl{1.0, -1.0};
  const AlphaLaw law_ld{0.0, -1.0};
  for (int i = 0; i < n; ++i) {
    AlphaCorridorPoint& p = out.corridor[i];
    p = AlphaCorridorPoint{};
    p.velocity_mps = v_entry_mps_ + (v_taem_mps_ - v_entry_mps_) * i / (n - 1);
    const double v = p.velocity_mps;
    Status s = glide_height(v, law_cl, p.h_glide_cl_max_m);
    if (s == Status::kOk) s = glide_height(v, law_ld, p.h_glide_ld_max_m);
    if (s == Status::kOk) s = glide_height(v, law_ranging, h_ranging_m[i]);
    if (s == Status::kOk) s = heat_flux_height(v, law_ld, p.h_heat_flux_m);
    if (s == Status::kOk) s = load_factor_height(v, law_cl, p.h_load_factor_cl_max_m);
    if (s == Status::kOk) s = load_factor_height(v, law_ld, p.h_load_factor_ld_max_m);
    if (s == Status::kOk) s = q_alpha_height(v, law_cl, p.h_q_alpha_cl_max_m);
    if (s == Status::kOk) s = q_alpha_height(v, law_ld, p.h_q_alpha_ld_max_m);
    if (s == Status::kOk) s = dynamic_pressure_height(v, p.h_dynamic_pressure_m);
    if (s != Status::kOk) return s;
    p.alpha_cl_max_rad = alpha_cl_max_rad(models_.mach(p.h_glide_cl_max_m, v));
    p.alpha_ld_max_rad = alpha_ld_max_rad(models_.mach(p.h_glide_ld_max_m, v));
    p.h_lower_m = std::fmax(std::fmax(std::fmax(p.h_glide_ld_max_m, p.h_heat_flux_m), std::fmax(p.h_load_factor_ld_max_m, p.h_q_alpha_ld_max_m)),
                            p.h_dynamic_pressure_m);
    p.closed = p.h_lower_m > p.h_glide_cl_max_m;
    if (p.closed) ++out.closed_points;
  }
  out.n_corridor = n;

  return Status::kOk;
}

void AlphaPlanner::phase_switch_velocities(const AlphaPlanParams& params, const AlphaLaw& law_ranging,
                                           AlphaPlanResult& out) const {
  constexpr int n = AlphaPlanResult::kGridPoints;
  // Intersection velocity (thesis 6.3.1): below it the heat flux no longer sets the lower
  // boundary, i.e. the grid velocity after the last heat-dominated node; the entry velocity
  // when the heat flux never dominates.
  out.v_intersection_mps = v_entry_mps_;
  for (int i = n - 1; i >= 0; --i) {
    const AlphaCorridorPoint& p = out.corridor[i];
    const bool heat_dominant = p.h_heat_flux_m > kMinHeight_m && p.h_heat_flux_m >= p.h_lower_m;
    if (heat_dominant) {
      out.v_intersection_mps = (i < n - 1) ? out.corridor[i + 1].velocity_mps : v_taem_mps_;
      break;
    }
  }

  // dV of (6.12): dalpha/dV = alpha_dot_max / (D/m), with dV/dt = -D/m on the alpha(L/D max)
  // glide at the TAEM velocity and dalpha the ranging-to-TAEM alpha step there.
  {
    const AlphaCorridorPoint& last = out.corridor[n - 1];
    const double mach = models_.mach(last.h_glide_ld_max_m, v_taem_mps_);
    const double d_alpha = std::fabs(alpha_of(law_ranging, mach) - alpha_ld_max_rad(mach));
    const double drag = models_.drag_mps2(alpha_ld_max_rad(mach), last.h_glide_ld_max_m, v_taem_mps_);
    out.dv_taem_mps = d_alpha * drag / alpha_rate_max_radps_;  // (6.12)
  }
  const double v_end = std::fmin(v_taem_mps_ + out.dv_taem_mps, out.v_intersection_mps);
  out.v_heating_switch_mps = out.v_intersection_mps - params.heating_switch_pct / 100.0 * (out.v_intersection_mps - v_end);
  out.v_taem_switch_mps = out.v_intersection_mps - params.taem_switch_pct / 100.0 * (out.v_intersection_mps - v_end);
}

Status AlphaPlanner::extract_path_alpha(const AlphaPlanParams& params, const double* h_ranging_m,
                                        AlphaPlanResult& out) const {
  constexpr int n = AlphaPlanResult::kGridPoints;
  const double v_end = std::fmin(v_taem_mps_ + out.dv_taem_mps, out.v_intersection_mps);
  // Path h(V) per phase, clipped into the corridor; alpha extraction (6.6)
  for (int i = 0; i < n; ++i) {
    AlphaCorridorPoint& p = out.corridor[i];
    const double v = p.velocity_mps;
    double h = 0.0;
    if (v > out.v_heating_switch_mps) {
      p.phase = AlphaPhase::kHeating;
      const double h_heating = p.h_lower_m + params.heating_pct / 100.0 * (p.h_glide_cl_max_m - p.h_lower_m);
      h = std::fmax(h_heating, h_ranging_m[i]);  // ranging path when already above (smoothness, 6.3.1)
    } else if (v > out.v_taem_switch_mps) {
      p.phase = AlphaPhase::kRanging;
      h = h_ranging_m[i];
    } else {
      p.phase = AlphaPhase::kTaem;
      // TAEM matching: ramp from the ranging path to the alpha(L/D max) glide, reached at
      // V_taem + dV (6.12) and held to TAEM (an alpha step here outruns the rate limit).
      const double span = out.v_taem_switch_mps - v_end;
      const double w = span > 0.0 ? std::fmin(1.0, std::fmax(0.0, (out.v_taem_switch_mps - v) / span)) : 1.0;
      h = h_ranging_m[i] + w * (p.h_glide_ld_max_m - h_ranging_m[i]);
    }
    h = std::fmax(h, p.h_lower_m);
    h = std::fmin(h, p.h_glide_cl_max_m);  // closed corridor: fly the upper boundary
    p.h_path_m = h;
    const Status s = extract_alpha(h, v, p.alpha_extracted_rad, p.extraction_clamped);
    if (s != Status::kOk) return s;
    if (p.extraction_clamped) ++out.clamped_points;
  }

  return Status::kOk;
}

void AlphaPlanner::smooth_alpha_monotonic(AlphaPlanResult& out) const {
  constexpr int n = AlphaPlanResult::kGridPoints;
  // Monotonic smoothing: alpha non-increasing as V decreases (pool-adjacent-violators,
  //    least-squares isotonic fit), then clamped into [alpha_LD(M), alpha_CL(M)] on the path.
  double block_sum[n] = {};
  int block_count[n] = {};
  int blocks = 0;
  for (int i = 0; i < n; ++i) {
    block_sum[blocks] = out.corridor[i].alpha_extracted_rad;
    block_count[blocks] = 1;
    ++blocks;
    // merge while the later block (lower V) has a larger mean than the one before it
    for (int guard = 0; guard < n && blocks > 1; ++guard) {
      const double mean_prev = block_sum[blocks - 2] / block_count[blocks - 2];
      const double mean_last = block_sum[blocks - 1] / block_count[blocks - 1];
      if (mean_last <= mean_prev) break;
      block_sum[blocks - 2] += block_sum[blocks - 1];
      block_count[blocks - 2] += block_count[blocks - 1];
      --blocks;
    }
  }
  {
    int i = 0;
    for (int b = 0; b < blocks; ++b) {
      const double mean = block_sum[b] / block_count[b];
      for (int k = 0; k < block_count[b] && i < n; ++k, ++i) out.corridor[i].alpha_rad = mean;
    }
  }
}

void AlphaPlanner::evaluate_path(AlphaPlanResult& out) const {
  constexpr int n = AlphaPlanResult::kGridPoints;
  out.alpha_min_rad = out.corridor[0].alpha_rad;
  out.alpha_max_rad = out.corridor[0].alpha_rad;
  for (int i = 0; i < n; ++i) {
    AlphaCorridorPoint& p = out.corridor[i];
    const double mach = models_.mach(p.h_path_m, p.velocity_mps);
    const double a_lo = alpha_ld_max_rad(mach);
    const double a_hi = alpha_cl_max_rad(mach);
    p.alpha_rad = std::fmin(std::fmax(p.alpha_rad, a_lo), a_hi);
    p.energy_norm = specific_energy_Jpkg(kEarthRadius_m + p.h_path_m, p.velocity_mps) / entry_energy_Jpkg_;  // (7.8)
    // constraint values where the profile is actually flown (zero bank, equilibrium glide)
    const double rho = models_.atmosphere().density_kgpm3(p.h_path_m);
    const double q = 0.5 * rho * p.velocity_mps * p.velocity_mps;
    const double lift = models_.lift_mps2(p.alpha_rad, p.h_path_m, p.velocity_mps);
    const double drag = models_.drag_mps2(p.alpha_rad, p.h_path_m, p.velocity_mps);
    p.path_heat_flux_Wpm2 = models_.heat_flux_Wpm2(rho, p.velocity_mps, p.alpha_rad);  // (3.6)
    p.path_load_factor_g = std::sqrt(lift * lift + drag * drag) / kG0_mps2;
    p.path_q_alpha_Pa_rad = q * p.alpha_rad;
    p.path_dynamic_pressure_Pa = q;
    constexpr double kMargin = 1.0 + 1e-6;
    p.path_violation = p.path_heat_flux_Wpm2 > heat_flux_max_Wpm2_ * kMargin ||
                       p.path_load_factor_g > load_factor_max_g_ * kMargin ||
                       p.path_q_alpha_Pa_rad > q_alpha_max_Pa_rad_ * kMargin ||
                       p.path_dynamic_pressure_Pa > dynamic_pressure_max_Pa_ * kMargin;
    if (p.path_violation) ++out.violation_points;
    out.alpha_min_rad = std::fmin(out.alpha_min_rad, p.alpha_rad);
    out.alpha_max_rad = std::fmax(out.alpha_max_rad, p.alpha_rad);
  }
  out.alpha_entry_rad = out.corridor[0].alpha_rad;
  out.alpha_taem_rad = out.corridor[n - 1].alpha_rad;

}

Status AlphaPlanner::sample_profile(AlphaPlanResult& out) const {
  constexpr int n = AlphaPlanResult::kGridPoints;
  // Profile over E/E_entry (x increasing = from TAEM to entry), down-sampled to capacity
  constexpr int cap = AlphaPlanResult::kProfileCapacity;
  for (int k = 0; k < cap; ++k) {
    const int j = (n - 1) - static_cast<int>(std::lround(static_cast<double>(k) * (n - 1) / (cap - 1)));
    const AlphaCorridorPoint& p = out.corridor[j];
    if (out.n_profile > 0 && !(p.energy_norm > out.profile_energy_norm[out.n_profile - 1])) continue;
    out.profile_energy_norm[out.n_profile] = p.energy_norm;
    out.profile_alpha_rad[out.n_profile] = p.alpha_rad;
    ++out.n_profile;
  }
  if (out.n_profile < 2) return Status::kExtractionFailed;
  return Status::kOk;
}

}  // namespace reentry::fsw
