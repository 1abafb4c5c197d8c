#include "tracker/entry_tracker.hpp"

#include <cmath>

#include "reentry/config/mission.hpp"

namespace reentry::fsw {
namespace {

constexpr double kScaleHeight_m = 7050.0;   // exponential-atmosphere scale height (2.20)
constexpr double kMinDrag_mps2 = 1e-3;      // below this L/D is not measurable
constexpr double kMinLiftOverDrag = 1e-3;    // below this the sensed L/D is not used
constexpr double kMaxSpeed_mps = 12000.0;    // above escape speed: not an entry state
constexpr double kMaxAccel_mps2 = 100.0 * 9.80665;
// Terminal phase: last kTerminalSpanFraction of the entry-to-TAEM energy span, lateral
// logic on a heading-to-aim-point corridor from kTerminalCorridorMax_rad down to _Min_rad.
constexpr double kTerminalSpanFraction = 0.06;
constexpr double kTerminalCorridorMax_rad = 6.0 * M_PI / 180.0;
constexpr double kTerminalCorridorMin_rad = 2.0 * M_PI / 180.0;
constexpr double kTerminalDragScale = 0.3;        // bound of the range-error drag scaling
constexpr double kTerminalMinRange_m = 20000.0;   // no scaling closer than this to the aim point

double clamp(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

double wrap_pi(double a) {
  a = std::fmod(a, 2.0 * M_PI);
  if (a <= -M_PI) a += 2.0 * M_PI;
  if (a > M_PI) a -= 2.0 * M_PI;
  return a;
}

bool finite_state(const RelativeState& s) {
  const double v[] = {s.t_s, s.radius_m, s.altitude_m, s.latitude_rad, s.velocity_mps, s.flight_path_rad,
                      s.heading_rad, s.energy_Jpkg, s.drag_mps2, s.lift_mps2};
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

}  // namespace

TrackerGains derive_gains(const config::Mission& mission) {
  TrackerGains g;
  const auto& p = mission.guidance;
  g.omega0_radps = 2.0 * std::sqrt(kG0_mps2 / kScaleHeight_m);
  g.zeta = 1.0 / std::sqrt(2.0);
  g.k_integral = g.omega0_radps * g.omega0_radps * g.omega0_radps / 20.0;
  g.k_heading = 1.0;
  g.k_heading_integral = 0.0;
  g.blend_start_e_norm = 0.0;  // set in init() from the TAEM energy (last 15 % of the span)
  g.blend_min_weight = 0.8;
  if (p.zeta > 0.0) g.zeta = p.zeta;
  if (p.omega0_radps > 0.0) g.omega0_radps = p.omega0_radps;
  if (p.k_integral > 0.0) g.k_integral = p.k_integral;
  if (p.k_heading > 0.0) g.k_heading = p.k_heading;
  if (p.k_heading_integral > 0.0) g.k_heading_integral = p.k_heading_integral;
  return g;
}

double EntryTracker::scheduled_omega(double omega0, double q_Pa, double q_ref_Pa) {
  if (!(q_ref_Pa > 0.0)) return omega0;
  const double x = q_Pa / q_ref_Pa;
  if (x >= 1.0) return omega0;
  if (x <= 0.0) return 0.0;
  return omega0 * (2.0 * x - x * x);  // (3.13)
}

Status EntryTracker::init(const config::Mission& mission) {
  Status st = models_.init(mission);
  if (st != Status::kOk) return st;
  st = alpha_profile_.init(mission.alpha_profile);
  if (st != Status::kOk) return st;
  gains_ = derive_gains(mission);
  const double r_entry = kEarthRadius_m + mission.entry.altitude_m;
  entry_energy_Jpkg_ = specific_energy_Jpkg(r_entry, mission.entry.velocity_mps);
  taem_energy_Jpkg_ = specific_energy_Jpkg(kEarthRadius_m + mission.taem.altitude_m, mission.taem.velocity_mps);
  if (!(entry_energy_Jpkg_ > taem_energy_Jpkg_)) return Status::kInvalidInput;
  const double e_taem_norm = taem_energy_Jpkg_ / entry_energy_Jpkg_;
  gains_.blend_start_e_norm = e_taem_norm + 0.15 * (1.0 - e_taem_norm);
  terminal_e_norm_ = e_taem_norm + kTerminalSpanFraction * (1.0 - e_taem_norm);
  aim_lat_rad_ = mission.taem.latitude_rad;
  aim_lon_rad_ = mission.taem.longitude_rad;
  initial_descent_drag_mps2_ = mission.guidance.initial_descent_drag_mps2;
  sigma_rate_max_radps_ = mission.constraints.sigma_rate_max_radps;
  alpha_max_rad_ = mission.constraints.alpha_max_rad;
  if (!(sigma_rate_max_radps_ > 0.0) || !(gains_.omega0_radps > 0.0)) return Status::kInvalidInput;
  has_profile_ = false;
  captured_ = false;
  drag_integral_ = 0.0;
  heading_integral_ = 0.0;
  last_sign_ = 0;
  reversal_until_t_s_ = -1.0;
  initialised_ = true;
  return Status::kOk;
}

void EntryTracker::set_profile(const ReferenceProfile& profile) {
  if (profile.n_points < 2 || profile.status != Status::kOk) return;
  profile_ = profile;
  has_profile_ = true;
  hint_ = 0;
  heading_integral_ = 0.0;
  // Reference dynamic pressure of (3.13): half the largest planned dynamic pressure, so the
  // loop reaches full bandwidth once the vehicle is in the dense part of the entry.
  double q_max = 0.0;
  for (int k = 0; k < profile_.n_points; ++k) q_max = std::fmax(q_max, profile_.dynamic_pressure_Pa[k]);
  q_ref_Pa_ = q_max > 0.0 ? 0.5 * q_max : 1.0;
}

EntryTracker::RefPoint EntryTracker::reference_at(double energy) {
  const ReferenceProfile& p = profile_;
  const int n = p.n_points;
  // Energies decrease with the index; find k with E[k] >= energy >= E[k+1] (bounded walk).
  int k = clamp(hint_, 0, n - 2);
  for (int i = 0; i < n && k > 0 && energy > p.energy_Jpkg[k]; ++i) --k;
  for (int i = 0; i < n && k < n - 2 && energy < p.energy_Jpkg[k + 1]; ++i) ++k;
  hint_ = k;
  const double e0 = p.energy_Jpkg[k], e1 = p.energy_Jpkg[k + 1];
  const double w = e0 != e1 ? clamp((e0 - energy) / (e0 - e1), 0.0, 1.0) : 0.0;
  auto lerp = [&](const double* a) { return a[k] + w * (a[k + 1] - a[k]); };
  RefPoint r;
  r.drag = lerp(p.drag_mps2);
  r.drag_prime = lerp(p.drag_prime);
  r.drag_second = lerp(p.drag_second);
  r.a = lerp(p.a_coef);
  r.b = lerp(p.b_coef);
  r.gamma = lerp(p.gamma_rad);
  r.alpha = lerp(p.alpha_rad);
  r.lod = lerp(p.lift_over_drag);
  r.sigma = lerp(p.sigma_rad);
  r.heading = p.heading_rad[k] + w * wrap_pi(p.heading_rad[k + 1] - p.heading_rad[k]);
  r.heading_prime = e0 != e1 ? wrap_pi(p.heading_rad[k + 1] - p.heading_rad[k]) / (e1 - e0) : 0.0;
  r.q = lerp(p.dynamic_pressure_Pa);
  r.velocity = lerp(p.velocity_mps);
  r.radius = lerp(p.radius_m);
  return r;
}

double EntryTracker::planned_range_to_go(double energy, double drag_here) const {
  // Trapezoidal quadrature of -int dE / D_ref from the current energy to the profile end.
  const ReferenceProfile& p = profile_;
  int k = hint_;
  double range_m = 0.0;
  double e_prev = energy, inv_prev = drag_here > 0.0 ? 1.0 / drag_here : 0.0;
  for (int j = k + 1; j < p.n_points; ++j) {
    if (!(p.drag_mps2[j] > 0.0)) return -1.0;
    const double inv = 1.0 / p.drag_mps2[j];
    range_m += 0.5 * (inv_prev + inv) * (e_prev - p.energy_Jpkg[j]);
    e_prev = p.energy_Jpkg[j];
    inv_prev = inv;
  }
  return range_m;
}

double EntryTracker::blend_weight(double e_norm) const {
  const double e_taem = taem_energy_Jpkg_ / entry_energy_Jpkg_;
  const double e_start = gains_.blend_start_e_norm;
  if (e_norm >= e_start || e_start <= e_taem) return 1.0;
  const double x = clamp((e_start - e_norm) / (e_start - e_taem), 0.0, 1.0);
  return 1.0 - (1.0 - gains_.blend_min_weight) * x;
}

Status EntryTracker::step(const RelativeState& s, double dt_s, TrackerOutput& out) {
  if (!initialised_) return Status::kInvalidInput;
  if (!finite_state(s) || !std::isfinite(dt_s)) return Status::kNonFinite;
  if (!(dt_s > 0.0) || !(s.velocity_mps > 0.0) || !(s.radius_m > 0.0)) return Status::kInvalidInput;
  // Physically impossible navigation (faster than escape, sensed accelerations beyond 100 g)
  // is rejected rather than pushed through the drag dynamics, where it would overflow.
  if (s.velocity_mps > kMaxSpeed_mps || s.drag_mps2 < 0.0 || s.drag_mps2 > kMaxAccel_mps2 || s.lift_mps2 < 0.0 ||
      s.lift_mps2 > kMaxAccel_mps2) {
    return Status::kInvalidInput;
  }

  const double e_norm = s.energy_Jpkg / entry_energy_Jpkg_;
  out = TrackerOutput{};
  out.alpha_rad = clamp(alpha_profile_.alpha_rad(e_norm), 0.0, alpha_max_rad_);
  if (!captured_ && s.drag_mps2 >= initial_descent_drag_mps2_) captured_ = true;
  if (!has_profile_ || !captured_) {
    // Initial descent: profile alpha, wings level (maximum vertical lift) until the drag is
    // large enough for the drag dynamics to be controllable (DESIGN §6).
    out.phase = Phase::kInitialDescent;
    return Status::kOk;
  }

  RefPoint ref = reference_at(s.energy_Jpkg);
  out.alpha_rad = clamp(ref.alpha, 0.0, alpha_max_rad_);
  const double V = s.velocity_mps, D = s.drag_mps2, r = s.radius_m;
  const double g = gravity_mps2(r);
  const double slat = std::sin(s.latitude_rad), clat = std::cos(s.latitude_rad);
  const bool terminal = e_norm < terminal_e_norm_;
  if (terminal) {
    // Terminal range control (as the Shuttle's drag reference update): the range the plan
    // still flies from here, S = -int dE / D_ref (C.2), against the great-circle distance to
    // the aim point; the drag reference is scaled by their ratio so a range error left by
    // the last plan is removed continuously instead of at the next replan.
    const double cos_arc = slat * std::sin(aim_lat_rad_) +
                           clat * std::cos(aim_lat_rad_) * std::cos(aim_lon_rad_ - s.longitude_rad);
    const double range_to_aim_m = kEarthRadius_m * std::acos(clamp(cos_arc, -1.0, 1.0));
    const double planned_range_m = planned_range_to_go(s.energy_Jpkg, ref.drag);
    if (range_to_aim_m > kTerminalMinRange_m && planned_range_m > 0.0) {
      const double scale = clamp(planned_range_m / range_to_aim_m, 1.0 - kTerminalDragScale, 1.0 + kTerminalDragScale);
      ref.drag *= scale;
      ref.drag_prime *= scale;
      ref.drag_second *= scale;
    }
  }
  const double sg = std::sin(s.flight_path_rad), cg = std::cos(s.flight_path_rad);
  const double V2 = V * V;
  // Sensed L/D where it is measurable, else the planned one (a lift-less or drag-less
  // measurement must not turn into a 0/0 bank command).
  const double lod_sensed = D > kMinDrag_mps2 ? s.lift_mps2 / D : 0.0;
  const double lod = lod_sensed >= kMinLiftOverDrag ? lod_sensed : ref.lod;
  if (!(lod >= kMinLiftOverDrag)) return Status::kInvalidInput;

  // Actual D' from (7.14): density gradient and C_D' from the on-board models.
  const double dlnrho_dr = models_.dlnrho_dr_fd(s.altitude_m, 100.0);
  const double de = 1e-3 * entry_energy_Jpkg_;
  const double e_a = s.energy_Jpkg + de, e_b = s.energy_Jpkg - de;
  const double cd = models_.drag_coefficient(out.alpha_rad, s.energy_Jpkg, s.altitude_m);
  const double cd_slope = models_.drag_coefficient_slope(
      alpha_profile_.alpha_rad(e_a / entry_energy_Jpkg_), e_a, s.altitude_m,
      alpha_profile_.alpha_rad(e_b / entry_energy_Jpkg_), e_b, s.altitude_m);
  const double cd_ratio = cd > 0.0 ? cd_slope / cd : 0.0;
  const double density_term = -dlnrho_dr + 2.0 * g / V2;
  const double drag_prime = D * (2.0 / V2 + cd_ratio) + density_term * sg;   // (7.14)
  double b = -density_term / V2;                                             // (7.20)
  if (!(std::fabs(b) > 0.0)) b = ref.b;

  // Dynamic pressure from the sensed drag and the model C_D; scheduled omega (3.13).
  const double q = cd > 0.0 ? D / (cd * models_.area_over_mass()) : ref.q;
  const double omega_t = scheduled_omega(gains_.omega0_radps, q, q_ref_Pa_);

  // Time -> energy conversion (3.14)-(3.18), E' = -D V.
  const double e_dot = -D * V;
  const double e_ddot = drag_prime * D * V2 + D * D + D * g * sg;            // (3.18)
  double d2_cmd = ref.drag_second;
  const double err = D - ref.drag, err_prime = drag_prime - ref.drag_prime;
  const bool reversing = s.t_s < reversal_until_t_s_;
  if (std::fabs(e_dot) > 1e-9) {
    const double inv_edot2 = 1.0 / (e_dot * e_dot);
    const double k_e = omega_t * omega_t * inv_edot2;                        // (3.15)
    const double c_e = e_ddot * inv_edot2 + 2.0 * gains_.zeta * omega_t / e_dot;  // (3.14)
    d2_cmd -= c_e * err_prime + k_e * err + gains_.k_integral * drag_integral_ * inv_edot2;  // (3.12)
  }
  const double u_ref = ref.lod * std::cos(ref.sigma);
  double u_drag = u_ref + (d2_cmd - ref.drag_second) / b;                    // (3.10)
  out.saturated = std::fabs(u_drag) > lod;
  u_drag = clamp(u_drag, -lod, lod);
  out.u_drag = u_drag;
  const double sigma_d = std::acos(clamp(u_drag / lod, -1.0, 1.0));          // (3.20)

  // Integral with anti-windup: frozen in reversals and while saturated in the same direction,
  // bounded to an equivalent drag bias of 20 % of the reference.
  if (!reversing && !(out.saturated && ((err > 0.0) == (drag_integral_ > 0.0)))) {
    drag_integral_ += err * dt_s;
  }
  const double i_max = 0.2 * ref.drag * gains_.omega0_radps * gains_.omega0_radps / gains_.k_integral;
  drag_integral_ = clamp(drag_integral_, -i_max, i_max);

  // Heading loop (3.19) through (3.11), Coriolis term C_chi of (2.45).
  const double tan_lat = slat / clat;
  const double chi = s.heading_rad;
  const double heading_err = wrap_pi(chi - ref.heading);
  const double omega_e = std::fabs(e_dot) > 1e-9 ? omega_t / std::fabs(e_dot) : 0.0;
  heading_integral_ -= heading_err * std::fabs(e_dot) * dt_s;  // int (chi_ref - chi) dE
  const double chi_prime_cmd = ref.heading_prime - gains_.k_heading * omega_e * heading_err +
                               gains_.k_heading_integral * heading_integral_;
  const double c_chi = -2.0 * kEarthRate_radps * (slat - clat * std::tan(s.flight_path_rad) * std::cos(chi)) / (D * V);
  const double u_chi = -V2 * cg * (chi_prime_cmd + cg * tan_lat * std::sin(chi) / (r * D) - c_chi);
  const double sigma_chi = std::asin(clamp(u_chi / lod, -1.0, 1.0));         // (3.21)

  // Reversal: a sign change of the reference bank is flown open loop at the maximum rate.
  int sign_ref = ref.sigma >= 0.0 ? 1 : -1;
  if (terminal && last_sign_ != 0) {
    // Terminal heading corridor: close to TAEM the bank sign turns the vehicle towards the
    // aim point, reversing only when the heading error to it leaves a corridor that narrows
    // towards the interface (Shuttle-style lateral logic; a planned reversal there would be
    // an uncorrectable lift-up pulse just before the interface).
    const double bearing = std::atan2(std::sin(aim_lon_rad_ - s.longitude_rad) * std::cos(aim_lat_rad_),
                                      clat * std::sin(aim_lat_rad_) -
                                          slat * std::cos(aim_lat_rad_) * std::cos(aim_lon_rad_ - s.longitude_rad));
    const double err_to_aim = wrap_pi(chi - bearing);
    const double e_taem_norm = taem_energy_Jpkg_ / entry_energy_Jpkg_;
    const double x = clamp((e_norm - e_taem_norm) / (terminal_e_norm_ - e_taem_norm), 0.0, 1.0);
    const double corridor = kTerminalCorridorMin_rad + (kTerminalCorridorMax_rad - kTerminalCorridorMin_rad) * x;
    sign_ref = last_sign_;
    if (err_to_aim > corridor) sign_ref = -1;        // heading right of the aim point: bank left
    else if (err_to_aim < -corridor) sign_ref = 1;   // heading left of it: bank right
    out.heading_err_rad = err_to_aim;
  }
  if (last_sign_ != 0 && sign_ref != last_sign_) {
    reversal_until_t_s_ = s.t_s + 2.0 * sigma_d / sigma_rate_max_radps_ + dt_s;
  }
  last_sign_ = sign_ref;

  const double w = (reversing || terminal) ? 1.0 : blend_weight(e_norm);
  out.sigma_rad = w * sign_ref * sigma_d + (1.0 - w) * sigma_chi;            // (3.22)
  if (!std::isfinite(out.sigma_rad) || !std::isfinite(out.alpha_rad)) return Status::kNonFinite;
  out.sigma_d_rad = sigma_d;
  out.sigma_chi_rad = sigma_chi;
  out.phase = s.t_s < reversal_until_t_s_ ? Phase::kReversal : Phase::kTracking;
  out.drag_ref_mps2 = ref.drag;
  out.drag_err_mps2 = err;
  if (!terminal) out.heading_err_rad = heading_err;
  return Status::kOk;
}

}  // namespace reentry::fsw
