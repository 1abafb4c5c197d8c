#include "tracker/entry_tracker.hpp"

#include <cmath>

#include "numerics/root_finding.hpp"
#include "planner/mission_geometry.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::fsw {
namespace {

constexpr double kScaleHeight_m = 7050.0;   // exponential-atmosphere scale height (2.20)
constexpr double kMinDrag_mps2 = 1e-3;      // below this L/D is not measurable
constexpr double kMinLiftOverDrag = 1e-3;    // below this the sensed L/D is not used
constexpr double kMaxSpeed_mps = 12000.0;    // above escape speed: not an entry state
constexpr double kMaxAccel_mps2 = 100.0 * 9.80665;
// Phases by normalised energy span x = (E/E_entry - E_f/E_entry) / (1 - E_f/E_entry):
//  - lateral heading corridor below x = kLateralCorridorSpanFraction (the planned reversal above),
//  - terminal range control below x = kTerminalSpanFraction (no replans there, DESIGN §6).
// Heading corridor half-width, linear in x from kCorridorMax_rad (corridor start) to
// kCorridorMin_rad (TAEM). The minimum is kept above the heading swing of one reversal late
// in the flight (a few degrees), so that the corridor does not reverse back and forth.
constexpr double kCorridorMax_rad = 6.0 * M_PI / 180.0;
constexpr double kCorridorMin_rad = 3.0 * M_PI / 180.0;
// Vector field onto the arrival great circle: approach angle chi_inf (2/pi) atan(y / y_s),
// at most the approach angle a turn of radius R_turn / kApproachTurnFactor takes out over the
// cross-track y, sqrt(2 k |y| / R_turn) (R_turn = V^2 cos(gamma) / (L sin|sigma|) at the present
// speed; the speed, hence R_turn, falls during the turn). Without the bound an X-38 120 km off
// the line at the corridor start took the 38 deg the field asks for, turned at 0.1 deg/s
// (R_turn 1700 km), crossed the line 16 deg off and reached TAEM 12.9 km out and 12 deg off the
// arrival heading. k = 1 / 1.5 / 2: X-38 nominal 4.0 / 6.2 / 9.7 km (altitude 1.82 km high
// at 2), 42 / 51 of 100 dispersed X-38 runs (16 without), X-33 192 / 195 of 200 (195).
constexpr double kApproachAngleMax_rad = 45.0 * M_PI / 180.0;
constexpr double kCrossTrackScale_m = 30000.0;
constexpr double kApproachTurnFactor = 1.5;
constexpr double kAimMinRange_m = 1000.0;       // the offset angle is undefined closer than this
// Capture guard (see step): past the line by more than half the field's cross-track scale,
// the field's approach angle is no longer small and the heading corridor cannot take the
// overshoot out before TAEM; closer than that the corridor and the final reversal govern.
constexpr double kCaptureOvershoot_m = 0.5 * kCrossTrackScale_m;
// Final reversal window: the last kFinalReversalWindow reversal durations before TAEM.
constexpr double kFinalReversalWindow = 2.0;
// Terminal range control: increment bounded to kTerminalDragScale of the reference drag,
// frozen closer than kTerminalMinRange_m to the aim point.
constexpr double kTerminalDragScale = 0.8;
constexpr double kTerminalMinRange_m = 5000.0;
// Weight of the terminal drag increment over u = (E - E_f) / (E_t - E_f): 1 at the phase start
// with zero slope, 0 at TAEM (the final drag stays the plan's). Quadratic rather than linear,
// so that late errors (the last corridor reversals) still meet some authority: w = 1 - (1 - u)^2.
double terminal_weight(double u) { return 1.0 - (1.0 - u) * (1.0 - u); }
// Scheduling of (3.13): full drag-loop bandwidth from kQrefFraction of the plan's largest q.
constexpr double kQrefFraction = 0.3;
// Alpha modulation in reversals: at most kAlphaModulationMax_rad below the profile in the final
// reversal and kCorridorModulationMax_rad in the earlier ones, lift kept at no less than
// kMinLiftRatio of the profile's, roll model led by the filter lag; only while the drag
// reference is below kModulationBoundMargin of the path-constraint bound, so that the range
// control can still add the drag the modulation costs. (Corridor reversals at 0/4/6/8/10/15
// deg: 169/175/193/179/173/163 of 200 dispersed X-33 runs; 500 runs: 6 deg 92.8 %, 8 deg 90.0 %.)
constexpr double kAlphaModulationMax_rad = 15.0 * M_PI / 180.0;
constexpr double kCorridorModulationMax_rad = 6.0 * M_PI / 180.0;  // before the final reversal
constexpr double kMinLiftRatio = 0.3;
constexpr double kAlphaModulationLead_s = 1.0;
constexpr double kMeanBankTimeConstant_s = 10.0;  // bank averaging for the final-reversal timing
constexpr int kFinalTurnSteps = 50;                // midpoint steps of the final-turn prediction
constexpr int kFinalFactorSamples = 20;  // scan of the final-drag factor between 1 and K
constexpr double kFinalAltitudeBandDepth = 0.5;  // predicted TAEM altitude within half the band
constexpr double kModulationBoundMargin = 0.85;
// Terminal drag-loop bandwidth: omega >= kTerminalSettling / t_go (time constant 1 / (zeta
// omega) within the time to go), at most kTerminalOmegaMaxFactor omega0 (bank-rate limit).
constexpr double kTerminalSettling = 1.5;
constexpr double kTerminalOmegaMaxFactor = 3.0;
constexpr double kDegree_rad = M_PI / 180.0;
constexpr double kBankSettled_rad = 5.0 * kDegree_rad;  // flown bank this close to the command: roll over
// Sensed drag-to-model ratio: first-order filter, bounded.
constexpr double kDragScaleTimeConstant_s = 20.0;
constexpr double kMinDragScale = 0.5;
constexpr double kMaxDragScale = 2.0;
constexpr double kSkipCaptureDragFraction = 0.1;  // of the initial-descent drag (see capture)
constexpr double kCaptureLookahead = 0.02;  // reference compared at E - 2 % of E_entry (pull-out energy)
constexpr double kPullOutComplete = 1.05;  // pull-out counted as complete when D would rise < 5 % more
constexpr double kRollLag_s = 1.0;  // bank filter lag before a roll starts (pull-out guard, final turn)
constexpr double kMinLodScale = 0.5;   // bounds of the L/D estimate (model / 2 .. model x 1.5)
constexpr double kMaxLodScale = 1.5;

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
  taem_energy_Jpkg_ = specific_energy_Jpkg(surface_radius_m(mission.taem.latitude_rad) + mission.taem.altitude_m,
                                           mission.taem.velocity_mps);
  if (!(entry_energy_Jpkg_ > taem_energy_Jpkg_)) return Status::kInvalidInput;
  const double e_taem_norm = taem_energy_Jpkg_ / entry_energy_Jpkg_;
  terminal_e_norm_ = e_taem_norm + kTerminalSpanFraction * (1.0 - e_taem_norm);
  lateral_e_norm_ = e_taem_norm + kLateralCorridorSpanFraction * (1.0 - e_taem_norm);
  taem_ = mission.taem;
  initial_descent_drag_mps2_ = mission.guidance.initial_descent_drag_mps2;
  sigma_rate_max_radps_ = mission.constraints.sigma_rate_max_radps;
  alpha_max_rad_ = mission.constraints.alpha_max_rad;
  heat_flux_max_Wpm2_ = mission.constraints.heat_flux_max_Wpm2;
  q_alpha_max_Pa_rad_ = mission.constraints.q_alpha_max_Pa_rad;
  q_max_Pa_ = mission.constraints.dynamic_pressure_max_Pa;
  load_factor_max_mps2_ = mission.constraints.load_factor_max_g * kG0_mps2;
  if (!(sigma_rate_max_radps_ > 0.0) || !(gains_.omega0_radps > 0.0)) return Status::kInvalidInput;
  has_profile_ = false;
  captured_ = false;
  first_pullout_done_ = false;
  drag_integral_ = 0.0;
  heading_integral_ = 0.0;
  drag_scale_ = 1.0;
  lod_scale_ = 1.0;
  last_alpha_cmd_rad_ = 0.0;
  last_sigma_d_rad_ = 0.0;
  flown_alpha_rad_ = -1.0;
  mean_sigma_d_rad_ = -1.0;
  final_reversal_done_ = false;
  final_correction_done_ = false;
  last_sign_ = 0;
  reversal_until_t_s_ = -1.0;
  reversal_start_t_s_ = -1.0;
  reversal_sigma0_rad_ = 0.0;
  reversal_ends_in_final_window_ = false;
  initialised_ = true;
  return Status::kOk;
}

void EntryTracker::set_profile(const ReferenceProfile& profile) {
  // A range-too-long plan is the maximum-drag best effort (see the executive): tracked too.
  if (profile.n_points < 2 || (profile.status != Status::kOk && profile.status != Status::kRangeTooLong)) return;
  profile_ = profile;
  has_profile_ = true;
  hint_ = 0;
  heading_integral_ = 0.0;
  // Reference dynamic pressure of (3.13): half the largest planned dynamic pressure, so the
  // loop reaches full bandwidth once the vehicle is in the dense part of the entry.
  double q_max = 0.0;
  for (int k = 0; k < profile_.n_points; ++k) q_max = std::fmax(q_max, profile_.dynamic_pressure_Pa[k]);
  q_ref_Pa_ = q_max > 0.0 ? kQrefFraction * q_max : 1.0;
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
  r.alpha_prime = e0 != e1 ? (p.alpha_rad[k + 1] - p.alpha_rad[k]) / (e1 - e0) : 0.0;
  r.lod = lerp(p.lift_over_drag);
  r.sigma = lerp(p.sigma_rad);
  r.heading = p.heading_rad[k] + w * wrap_pi(p.heading_rad[k + 1] - p.heading_rad[k]);
  r.heading_prime = e0 != e1 ? wrap_pi(p.heading_rad[k + 1] - p.heading_rad[k]) / (e1 - e0) : 0.0;
  r.q = lerp(p.dynamic_pressure_Pa);
  r.velocity = lerp(p.velocity_mps);
  r.radius = lerp(p.radius_m);
  r.drag_max = lerp(p.drag_max_mps2);
  return r;
}

EntryTracker::LateralTarget EntryTracker::lateral_target(const RelativeState& s) const {
  // Arrival line: the great circle through the aim point on the required TAEM heading chi_f.
  // The offset eps (bearing from the aim point to the vehicle minus the reversed arrival
  // heading) gives, in the local plane, the cross-track distance y = R sin(eps) and the line's
  // heading at the vehicle chi_line = lambda - eps (lambda: line of sight to the aim point);
  // measuring eps at the aim point keeps this valid over thousands of kilometres. The target
  // heading is a vector field onto the line (Nelson et al. 2007), bounded by the turn the
  // vehicle can make (kApproachTurnFactor):
  //   chi_d = chi_line + sign(y) min(chi_inf (2/pi) atan(|y| / y_s), sqrt(2 k |y| / R_turn)),
  // so the vehicle converges on the line and arrives along it, on chi_f (the heading is
  // targeted explicitly instead of following from the last reversal).
  LateralTarget t;
  const double aim_lat = taem_.latitude_rad, aim_lon = taem_.longitude_rad;
  const GreatCircle to_aim = great_circle(s.latitude_rad, s.longitude_rad, aim_lat, aim_lon);  // (7.1)-(7.2)
  t.range_m = kEarthRadius_m * to_aim.arc_rad;
  t.bearing_rad = to_aim.azimuth_rad;
  if (t.range_m > kAimMinRange_m) {
    const double back = great_circle(aim_lat, aim_lon, s.latitude_rad, s.longitude_rad).azimuth_rad;
    t.offset_rad = wrap_pi(back - (taem_.heading_rad + M_PI));
  }
  t.cross_track_m = t.range_m * std::sin(t.offset_rad);
  t.line_heading_rad = t.bearing_rad - t.offset_rad;
  double approach_rad = kApproachAngleMax_rad * (2.0 / M_PI) * std::atan(std::fabs(t.cross_track_m) / kCrossTrackScale_m);
  const double turn_accel_mps2 = s.lift_mps2 * std::sin(std::fmax(mean_sigma_d_rad_, 0.0));
  if (turn_accel_mps2 > 0.0) {
    const double turn_radius_m = s.velocity_mps * s.velocity_mps * std::cos(s.flight_path_rad) / turn_accel_mps2;
    approach_rad = std::fmin(approach_rad,
                             std::sqrt(2.0 * kApproachTurnFactor * std::fabs(t.cross_track_m) / turn_radius_m));
  }
  t.heading_rad = wrap_pi(t.line_heading_rad + std::copysign(approach_rad, t.cross_track_m));
  t.along_track_m = t.range_m * std::cos(t.offset_rad);
  return t;
}

bool EntryTracker::in_final_reversal_window(double t_go_s) const {
  // The last kFinalReversalWindow reversal durations 2 sigma / sigma_rate at the mean bank.
  return mean_sigma_d_rad_ > 0.0 && t_go_s < kFinalReversalWindow * 2.0 * mean_sigma_d_rad_ / sigma_rate_max_radps_;
}

double EntryTracker::flown_bank_rad() const {
  // The rate filter's output when the stack provides it, else the tracker's own last command.
  return flown_alpha_rad_ >= 0.0 ? flown_sigma_rad_ : last_sign_ * last_sigma_d_rad_;
}

EntryTracker::TerminalRange EntryTracker::terminal_range(double energy, double drag_here, double e_t,
                                                        double final_factor) const {
  // Trapezoidal quadrature from the current energy to the profile end of S = -int dE / D (C.2)
  // and dS/dc = -int w / D^2 dE, D = k_f(E) D_ref with the final-drag factor
  // k_f = 1 + (k - 1)(1 - w) (k: final_drag_factor) and w = terminal_weight((E - E_f) / (E_t - E_f)).
  const ReferenceProfile& p = profile_;
  TerminalRange t;
  const double span = e_t - taem_energy_Jpkg_;
  if (!(span > 0.0) || !(drag_here > 0.0)) return t;
  auto weight = [&](double e) { return terminal_weight(clamp((e - taem_energy_Jpkg_) / span, 0.0, 1.0)); };
  auto scaled = [&](double e, double d) { return d * (1.0 + (final_factor - 1.0) * (1.0 - weight(e))); };
  double e_prev = energy, inv_prev = 1.0 / scaled(energy, drag_here);
  double sens_prev = weight(energy) * inv_prev * inv_prev;
  t.range_m = 0.0;
  for (int j = hint_ + 1; j < p.n_points; ++j) {
    if (!(p.drag_mps2[j] > 0.0)) return TerminalRange{};
    const double inv = 1.0 / scaled(p.energy_Jpkg[j], p.drag_mps2[j]);
    const double sens = weight(p.energy_Jpkg[j]) * inv * inv;
    const double de = e_prev - p.energy_Jpkg[j];
    t.range_m += 0.5 * (inv_prev + inv) * de;
    t.sensitivity -= 0.5 * (sens_prev + sens) * de;
    e_prev = p.energy_Jpkg[j];
    inv_prev = inv;
    sens_prev = sens;
  }
  return t;
}

double EntryTracker::final_drag_factor() const {
  // Of the sensed drag-to-model ratio K, the part the final drag must take so that the TAEM
  // state stays inside its bands. Flying the planned final drag D_f in air K times the model's
  // meets the TAEM energy H ln(K / k) above the planned altitude when the final drag is k D_f.
  // Scaling the whole K (holding the planned altitude) makes the drag ramp by K - 1 over the
  // terminal phase, which cost range and heading (dispersed X-33, 700 runs: 652 successes
  // with k = K, 672 with k = 1; with k = K the failures were in the densest third of the
  // dispersions). k = 1 throughout left 42 of 500 dispersed HORUS runs below its Mach band
  // (planned Mach 2.23, band 2.2-2.8). So k is the value closest to 1 between 1 and K whose
  // TAEM state stays inside the bands: X-33 672/700, HORUS 75/500 (57 with k = K; 51 when a
  // quarter of the half band, or the planned depth, is kept: on its Mach band, see below).
  // The predicted TAEM altitude is held inside the inner part of the altitude band
  // (kFinalAltitudeBandDepth): K keeps moving after the factor is chosen, and with the band
  // edge as the aim the densest and thinnest dispersed X-33 runs ended 1.5-2.1 km off (seven
  // of 1000 outside +-1.8 km). Depth 0 / 0.25 / 0.5 / 0.75: X-33 seed 7 x 500: 496 / 497 /
  // 498 / 497 (range failures from 0.75 on); 0.5 over three seed sets 994 of 1000 (990),
  // HORUS 74 of 500 either way. The Mach band keeps depth 0: with the same margin there,
  // HORUS (planned Mach 2.23 in 2.2-2.8) ended short of range, 57 of 500.
  const double K = drag_scale_;
  if (!(taem_.altitude_tol_m > 0.0) || !has_profile_) return K;
  const double planned_altitude_m = profile_.taem_altitude_m;
  for (int i = 0; i <= kFinalFactorSamples; ++i) {
    const double k = 1.0 + (K - 1.0) * i / kFinalFactorSamples;
    const double altitude_m = planned_altitude_m + kScaleHeight_m * std::log(K / k);
    if (models_.taem_band_depth(taem_, taem_energy_Jpkg_, altitude_m) >= 0.0 &&
        OnboardModels::taem_altitude_depth(taem_, altitude_m) >= kFinalAltitudeBandDepth) {
      return k;
    }
  }
  return K;
}

bool EntryTracker::modulation_allowed(double drag_ref, double drag_max) const {
  return !(drag_max > 0.0) || drag_ref < kModulationBoundMargin * drag_max * drag_scale_;
}

double EntryTracker::load_relief_alpha(double alpha_cmd_rad, double alpha_floor_rad, double alpha_flown_rad, double mach,
                                       double aero_accel_mps2) const {
  // The aerodynamic acceleration at the sensed dynamic pressure scales with the resultant
  // coefficient C_R = hypot(C_L, C_D); the command is lowered (bisection, bounded) until the
  // sensed acceleration scaled to it stays within the planned fraction of the load limit.
  // Ratios of table coefficients, so a C_L / C_D scale error does not move the limit.
  double cl, cd;
  models_.aero().coefficients(alpha_flown_rad, mach, cl, cd);
  const double c_flown = std::hypot(cl, cd);
  const double limit = kConstraintMargin * load_factor_max_mps2_;
  if (!(c_flown > 0.0) || !(aero_accel_mps2 > 0.0) || !(limit > 0.0)) return alpha_cmd_rad;
  auto accel_at = [&](double alpha) {
    double l, d;
    models_.aero().coefficients(alpha, mach, l, d);
    return aero_accel_mps2 * std::hypot(l, d) / c_flown;
  };
  if (accel_at(alpha_cmd_rad) <= limit) return alpha_cmd_rad;
  // Never below the floor: shedding lift in a dive would deepen it (q then grows without
  // bound); the floor is the deepest reversal modulation below the reference.
  double lo = std::fmin(std::fmax(alpha_floor_rad, 0.0), alpha_cmd_rad), hi = alpha_cmd_rad;
  if (accel_at(lo) > limit) return lo;
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (accel_at(mid) > limit) hi = mid; else lo = mid;
  }
  return lo;
}

double EntryTracker::modulated_alpha(double alpha_rad, double mach, double lift_ratio, double max_rad) const {
  // alpha with C_L(alpha) = lift_ratio C_L(alpha_ref), by bisection below alpha_ref (bounded).
  const double cl_ref = models_.aero().cl(alpha_rad, mach);
  if (!(lift_ratio < 1.0) || !(cl_ref > 0.0)) return alpha_rad;
  double lo = std::fmax(0.0, alpha_rad - max_rad), hi = alpha_rad;
  // Only where lowering alpha lowers the lift (below alpha(C_L max)) and can reach the ratio;
  // elsewhere a lower alpha would only cost drag.
  if (!(models_.aero().cl(alpha_rad - kDegree_rad, mach) < cl_ref) || !(models_.aero().cl(lo, mach) < lift_ratio * cl_ref)) {
    return alpha_rad;
  }
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (models_.aero().cl(mid, mach) > lift_ratio * cl_ref) hi = mid; else lo = mid;
  }
  return 0.5 * (lo + hi);
}

double EntryTracker::reversal_lift_ratio(double sigma0_rad, double t_rel_s) const {
  // cos(sigma0) / cos(sigma(t)) for the rate-limited roll sigma(t) = sigma0 - rate t, bounded.
  const double sigma_now = std::fabs(sigma0_rad - sigma_rate_max_radps_ * t_rel_s);
  const double c_now = std::cos(std::fmin(sigma_now, 0.5 * M_PI));
  return c_now > 0.0 ? clamp(std::cos(sigma0_rad) / c_now, kMinLiftRatio, 1.0) : 1.0;
}

double EntryTracker::reversal_range_extension_m(const RelativeState& s, double alpha_rad, double sigma0_rad) const {
  // Range added by one modulated reversal flown now. Over the reversal time T the vehicle
  // covers V T whatever its drag, but dissipates only int D_mod V dt; the energy saved,
  // int (D - D_mod) V dt, is dissipated afterwards at the drag D over a distance
  //   dS = V int (1 - C_D(alpha_mod(t)) / C_D(alpha)) dt   (S = -int dE / D).
  if (!(sigma0_rad > 0.0)) return 0.0;
  const double mach = models_.mach(s.altitude_m, s.velocity_mps);
  const double cd_ref = models_.aero().cd(alpha_rad, mach);
  const double t_rev = 2.0 * sigma0_rad / sigma_rate_max_radps_;
  constexpr int kSamples = 20;
  double extension = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double t = (i + 0.5) * t_rev / kSamples;
    const double cd =
        models_.aero().cd(modulated_alpha(alpha_rad, mach, reversal_lift_ratio(sigma0_rad, t), kAlphaModulationMax_rad), mach);
    if (cd_ref > 0.0) extension += (1.0 - cd / cd_ref) * s.velocity_mps * t_rev / kSamples;
  }
  return extension;
}

RelativeState EntryTracker::referred_to_alpha(const RelativeState& s, double alpha_flown_rad, double alpha_rad) const {
  RelativeState out = s;
  double cl, cd, cl_flown, cd_flown;
  const double mach = models_.mach(s.altitude_m, s.velocity_mps);
  models_.aero().coefficients(alpha_rad, mach, cl, cd);
  models_.aero().coefficients(alpha_flown_rad, mach, cl_flown, cd_flown);
  if (cd > 0.0 && cd_flown > 0.0) out.drag_mps2 = s.drag_mps2 * cd / cd_flown;
  if (cl > 0.0 && cl_flown > 0.0) out.lift_mps2 = s.lift_mps2 * cl / cl_flown;
  return out;
}

void EntryTracker::update_drag_scale(const RelativeState& s, double alpha_rad, double dt_s) {
  // Ratio of the sensed drag to the on-board model's drag at the navigated height and speed:
  // the product of the density, drag-coefficient and mass errors (and wind), low-pass filtered.
  // The on-board altitude is above the R_eq sphere while the air is stratified over the
  // ellipsoid, so the model is evaluated at the height above the ellipsoid (first order in f).
  const double h_ellipsoid_m = s.radius_m - surface_radius_m(s.latitude_rad);
  const double d_model = models_.drag_mps2(alpha_rad, h_ellipsoid_m, s.velocity_mps);
  if (!(d_model > kMinDrag_mps2) || !(s.drag_mps2 > kMinDrag_mps2)) return;
  const double ratio = clamp(s.drag_mps2 / d_model, kMinDragScale, kMaxDragScale);
  drag_scale_ += clamp(dt_s / kDragScaleTimeConstant_s, 0.0, 1.0) * (ratio - drag_scale_);
}

double wings_level_pullout_drag_mps2(double drag_mps2, double lift_over_drag, double h_dot_mps, double g_eff_mps2,
                                     double scale_height_m) {
  // Vertical energy balance of a wings-level pull-out, speed held, rho ~ exp(-h / H):
  //   f(D_p) = (L/D) H (D_p - D) - g_eff H ln(D_p / D) - h_dot^2 / 2 = 0,  g_eff = g - V_h^2 / r.
  // f(D) < 0 and f grows without bound: f falls while (L/D) D_p < g_eff, then rises, so the
  // root above D is unique. Bracketed (doubling) and solved by Brent's method; a fixed-point
  // iteration on the same balance diverged where g_eff < 0 (an eastbound entry above circular
  // speed) or (L/D) D < g_eff, and reported no pull-out for a shallow entry that pulls out high.
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

double terminal_omega_floor_radps(double omega0_radps, double t_go_s) {
  if (!(t_go_s > 0.0)) return kTerminalOmegaMaxFactor * omega0_radps;
  return std::fmin(kTerminalSettling / t_go_s, kTerminalOmegaMaxFactor * omega0_radps);
}

FinalTurnState predict_final_turn(const FinalTurnInput& in) {
  // Midpoint rule over kFinalTurnSteps steps (bounded).
  FinalTurnState out{in.heading_err_rad, in.cross_track_m, 0.0};
  if (!(in.t_go_s > 0.0) || !(in.speed_mps > 0.0)) return out;
  const double side = in.cross_track_m >= 0.0 ? 1.0 : -1.0;
  const double h = in.t_go_s / kFinalTurnSteps;
  const double v_f = std::fmin(in.taem_speed_mps, in.speed_mps);
  for (int i = 0; i < kFinalTurnSteps; ++i) {
    const double t = (i + 0.5) * h;
    const double speed = in.speed_mps - (in.speed_mps - v_f) * t / in.t_go_s;
    const double roll = in.sigma_rate_radps * std::fmax(t - in.roll_lag_s, 0.0);
    const double sigma = in.sigma_now_rad + clamp(in.sigma_end_rad - in.sigma_now_rad, -roll, roll);
    const double turn = in.lift_horizontal_mps2 * std::sin(sigma) / speed * h;
    out.cross_track_m -= speed * std::sin(out.heading_err_rad + 0.5 * turn) * h;
    out.heading_err_rad += turn;
    out.overshoot_m = std::fmax(out.overshoot_m, -side * out.cross_track_m);
  }
  return out;
}

double EntryTracker::lift_up_pullout_drag_mps2(const RelativeState& s, double sigma_now_rad) const {
  // Drag at the bottom of a wings-level pull-out from the present state, in the local scale
  // height of the on-board atmosphere, with the sensed L/D. From a bank sigma_now the roll to
  // wings level takes sigma_now / sigma_rate_max (plus the filter lag), flown with the mean
  // vertical lift L sin(sigma) / sigma of a uniform roll: the pull-out starts from the state
  // at its end (descent rate and drag propagated at constant vertical acceleration).
  const double D = s.drag_mps2;
  if (!(D > kMinDrag_mps2)) return D;
  const double dlnrho_dr = models_.dlnrho_dr_fd(s.altitude_m, 100.0);
  if (!(dlnrho_dr < 0.0)) return D;
  // Net downward acceleration without lift, with the Earth-rate term of (2.45) (an eastbound
  // vehicle near orbital speed is held up by it).
  const double g_eff = level_flight_lift_need_mps2(s.radius_m, s.velocity_mps * std::cos(s.flight_path_rad),
                                                   s.latitude_rad, s.heading_rad);
  const double sigma = std::fabs(sigma_now_rad);
  const double t_roll = sigma_rate_max_radps_ > 0.0 && sigma > 1e-6 ? sigma / sigma_rate_max_radps_ + kRollLag_s : 0.0;
  return pullout_drag_after_roll_mps2(D, s.lift_mps2 / D, s.velocity_mps * std::sin(s.flight_path_rad), g_eff,
                                      -1.0 / dlnrho_dr, sigma, t_roll);
}

double EntryTracker::constraint_drag_limit_mps2(const RelativeState& s, double alpha_rad, double cd) const {
  // Largest drag at which the sensed path-constraint values stay within the planned fraction
  // of their limits. Every constraint depends on the sensed drag through D / (C_D S/m): q, q
  // alpha and the load factor linearly, the heat flux (3.5) through sqrt(rho) = sqrt(2 q) / V,
  // so each gives its limit by scaling the present drag. A density error does not move the
  // limit; a C_D error moves it as it moves q itself.
  const double D = s.drag_mps2;
  if (!(D > kMinDrag_mps2) || !(cd > 0.0)) return 1e300;
  const double q = D / (cd * models_.area_over_mass());
  double limit = 1e300;
  auto scale_linear = [&](double value, double max) {
    if (max > 0.0 && value > 0.0) limit = std::fmin(limit, D * kConstraintMargin * max / value);
  };
  scale_linear(q, q_max_Pa_);
  scale_linear(q * alpha_rad, q_alpha_max_Pa_rad_);
  scale_linear(std::hypot(D, s.lift_mps2), load_factor_max_mps2_);
  const double heat = models_.heat_flux_Wpm2(2.0 * q / (s.velocity_mps * s.velocity_mps), s.velocity_mps, alpha_rad);
  if (heat_flux_max_Wpm2_ > 0.0 && heat > 0.0) {
    const double ratio = kConstraintMargin * heat_flux_max_Wpm2_ / heat;
    limit = std::fmin(limit, D * ratio * ratio);
  }
  return limit;
}

void EntryTracker::update_lod_scale(const RelativeState& s, double alpha_rad, double dt_s) {
  // Sensed L/D over the model's at the commanded alpha and the navigated Mach, low-pass
  // filtered like the drag ratio; only where both accelerations are measurable. The planner
  // scales its lift with it, so that replans see the vehicle's true manoeuvrability (the
  // equilibrium-glide floor (7.7) and the bank extraction depend on L/D alone).
  if (!(s.drag_mps2 >= initial_descent_drag_mps2_) || !(s.lift_mps2 > 0.0)) return;
  double cl, cd;
  models_.aero().coefficients(alpha_rad, models_.mach(s.altitude_m, s.velocity_mps), cl, cd);
  if (!(cl > 0.0) || !(cd > 0.0)) return;
  const double ratio = clamp((s.lift_mps2 / s.drag_mps2) / (cl / cd), kMinLodScale, kMaxLodScale);
  lod_scale_ += clamp(dt_s / kDragScaleTimeConstant_s, 0.0, 1.0) * (ratio - lod_scale_);
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
  // The sensed accelerations belong to the alpha flown now: the rate filter's output when the
  // stack provides it, else the alpha commanded last cycle, else the profile's.
  const double alpha_flown =
      flown_alpha_rad_ >= 0.0 ? flown_alpha_rad_ : (last_alpha_cmd_rad_ > 0.0 ? last_alpha_cmd_rad_ : out.alpha_rad);
  update_lod_scale(s, alpha_flown, dt_s);
  out.lift_over_drag_scale = lod_scale_;
  if (!captured_ && has_profile_ && s.drag_mps2 >= kSkipCaptureDragFraction * initial_descent_drag_mps2_) {
    // Capture once the drag is measurable and a wings-level pull-out would level off below
    // the reference (lift down is needed to reach it) or is essentially complete. Before
    // that, the reference can only be reached by the pull-out itself: lift down would deepen
    // a dive the drag loop cannot arrest (the heat-flux overshoot of a steep entry). A
    // shallow entry whose pull-out would level off below the reference is captured from a
    // tenth of the threshold drag on: its drag may never reach the threshold (skip-out).
    const double d_ref = reference_at(s.energy_Jpkg - kCaptureLookahead * entry_energy_Jpkg_).drag;
    const double d_pullout = lift_up_pullout_drag_mps2(s);
    captured_ = d_pullout < d_ref ||
                (s.drag_mps2 >= initial_descent_drag_mps2_ && d_pullout < kPullOutComplete * s.drag_mps2);
  }
  if (!has_profile_ || !captured_) {
    // Initial descent: profile alpha, wings level (maximum vertical lift) until captured.
    out.phase = Phase::kInitialDescent;
    last_alpha_cmd_rad_ = out.alpha_rad;
    return Status::kOk;
  }

  RefPoint ref = reference_at(s.energy_Jpkg);
  out.alpha_rad = clamp(ref.alpha, 0.0, alpha_max_rad_);
  const double alpha_ref = out.alpha_rad;  // before any reversal modulation or load relief
  update_drag_scale(s, alpha_flown, dt_s);
  const double V = s.velocity_mps, D = s.drag_mps2, r = s.radius_m;
  // The sensed state referred to the reference alpha: drag and lift scaled by the table's C_D
  // and C_L ratios between the reference and the flown alpha. The drag loop controls the
  // density (altitude); a drag change made by the alpha channel (reversal modulation, load
  // relief) is not an altitude error. Fed the raw drag, the loop answered a 15 deg modulation
  // (C_D about -40 %) with lift down, and dispersed X-33 runs left the final reversal 2-3 km
  // low and diving (q 15.4 kPa against 14.4).
  const RelativeState s_ref_alpha = referred_to_alpha(s, alpha_flown, out.alpha_rad);
  const double D_ref_alpha = s_ref_alpha.drag_mps2;
  const double g = gravity_mps2(r);
  const double slat = std::sin(s.latitude_rad), clat = std::cos(s.latitude_rad);
  const bool terminal = e_norm < terminal_e_norm_;
  const bool lateral_corridor = e_norm < lateral_e_norm_;
  // Aim-point geometry, once per cycle, for the terminal range control and the corridor.
  const LateralTarget target = (terminal || lateral_corridor) ? lateral_target(s) : LateralTarget{};
  // The plan's path-constraint bound on the drag (terminal increment and pull-out guard). A
  // density error does not move a q-type bound in drag space, a C_D / mass error does, and
  // the sensed ratio K cannot tell them apart (no air data). The bound is taken as planned,
  // the same reading as constraint_drag_limit_mps2 (K is density). Scaled by min(K, 1) (K is
  // C_D when below 1) it held the low-density runs off the drag their range needs: HORUS seed
  // 7 x 500 65 -> 78 successes without it (range failures 274 -> 183, q*alpha 251 -> 304);
  // that reading everywhere, in the sensed limit too, gave 61 (range 291). and the
  // planned-alpha campaigns: 500, 133, 464 -> 465.
  const double plan_bound = ref.drag_max > 0.0 ? ref.drag_max : 1e300;
  if (terminal) {
    // Terminal range control (drag reference update, as the Shuttle's): the range the plan
    // still flies from here, S = -int dE / D_ref (C.2), is matched to the great-circle
    // distance to the aim point by a drag increment that vanishes at the TAEM energy,
    // dD(E) = c w(E), w = terminal_weight((E - E_f) / (E_t - E_f)): the final drag, which sets
    // the TAEM altitude, stays the plan's. c follows from the linearised range
    // dS/dc = -int w / D_ref^2 dE, re-evaluated every cycle, bounded to kTerminalDragScale D.
    // The final drag is multiplied by k = final_drag_factor() (blended in over the phase):
    // the part of the sensed drag-to-model ratio K needed to keep the TAEM state inside its
    // bands; the rest of K moves the TAEM altitude.
    const double e_t = terminal_e_norm_ * entry_energy_Jpkg_;
    const double span = e_t - taem_energy_Jpkg_;
    const double u = clamp((s.energy_Jpkg - taem_energy_Jpkg_) / span, 0.0, 1.0);
    const double w_here = terminal_weight(u);
    const double dw_dE = 2.0 * (1.0 - u) / span, d2w_dE2 = -2.0 / (span * span);
    const double k = final_drag_factor();
    const double k_f = 1.0 + (k - 1.0) * (1.0 - w_here);
    const TerminalRange tr = terminal_range(s.energy_Jpkg, ref.drag, e_t, k);
    // Range to go along the arrival line: negative once the aim point has been passed.
    const double range_to_aim_m = target.along_track_m;
    double c = 0.0;
    if (range_to_aim_m > kTerminalMinRange_m && tr.range_m > 0.0 && tr.sensitivity < 0.0) {
      const double c_max = kTerminalDragScale * ref.drag;
      // The final reversal is still to come: its alpha modulation lowers the drag for a
      // reversal time and so lengthens the range (reversal_range_extension_m).
      const double extra_m = final_reversal_done_ || !modulation_allowed(ref.drag, ref.drag_max)
                                 ? 0.0
                                 : reversal_range_extension_m(s, out.alpha_rad, std::fabs(ref.sigma));
      c = clamp((range_to_aim_m - tr.range_m - extra_m) / tr.sensitivity, -c_max, c_max);
    }
    const double d0 = ref.drag, d0p = ref.drag_prime;
    // The increment never takes the reference past the plan's path-constraint bound.
    if (d0 * k_f + c * w_here > plan_bound && w_here > 0.0) c = (plan_bound - d0 * k_f) / w_here;
    ref.drag = d0 * k_f + c * w_here;
    ref.drag_prime = d0p * k_f + (c - (k - 1.0) * d0) * dw_dE;
    ref.drag_second = ref.drag_second * k_f - 2.0 * (k - 1.0) * d0p * dw_dE + (c - (k - 1.0) * d0) * d2w_dE2;
  }
  // Constraint protection: the reference never asks for more drag than the sensed state
  // allows within the planned constraint fraction (the planner's bound is on the model
  // atmosphere; tracking lag and reversal transients must not eat the margin). The limits hold
  // at the flown alpha (true q, q alpha and load factor) and are referred to the reference alpha.
  const double cd = models_.drag_coefficient(out.alpha_rad, s.energy_Jpkg, s.altitude_m);
  const double cd_flown = models_.drag_coefficient(alpha_flown, s.energy_Jpkg, s.altitude_m);
  const double constraint_limit =
      constraint_drag_limit_mps2(s, alpha_flown, cd_flown) * D_ref_alpha / std::fmax(D, kMinDrag_mps2);
  ref.drag = std::fmin(ref.drag, constraint_limit);
  const double sg = std::sin(s.flight_path_rad), cg = std::cos(s.flight_path_rad);
  const double V2 = V * V;
  // Sensed L/D where it is measurable, else the planned one (a lift-less or drag-less
  // measurement must not turn into a 0/0 bank command).
  const double lod_sensed = D_ref_alpha > kMinDrag_mps2 ? s_ref_alpha.lift_mps2 / D_ref_alpha : 0.0;
  const double lod = lod_sensed >= kMinLiftOverDrag ? lod_sensed : ref.lod;
  if (!(lod >= kMinLiftOverDrag)) return Status::kInvalidInput;

  // Actual D' from (7.14): density gradient and C_D' from the on-board models.
  const double dlnrho_dr = models_.dlnrho_dr_fd(s.altitude_m, 100.0);
  const double de = 1e-3 * entry_energy_Jpkg_;
  const double e_a = s.energy_Jpkg + de, e_b = s.energy_Jpkg - de;
  // alpha along the plan (which may differ from the mission profile: ranging alpha).
  const double cd_slope = models_.drag_coefficient_slope(ref.alpha + ref.alpha_prime * de, e_a, s.altitude_m,
                                                         ref.alpha - ref.alpha_prime * de, e_b, s.altitude_m);
  const double cd_ratio = cd > 0.0 ? cd_slope / cd : 0.0;
  const double density_term = -dlnrho_dr + 2.0 * g / V2;
  const double drag_prime = D_ref_alpha * (2.0 / V2 + cd_ratio) + density_term * sg;  // (7.14)
  double b = -density_term / V2;                                             // (7.20)
  if (!(std::fabs(b) > 0.0)) b = ref.b;

  // Time to TAEM at the present drag with the speed falling linearly to the TAEM speed
  // (E' = -D V): with the present speed instead, t_go came out 25-35 % short (X-33: 40 s
  // predicted, 54 s flown), the final reversal was timed for a turn that short and the
  // vehicle arrived 5-12 deg past the line.
  const double v_f = std::fmin(taem_.velocity_mps, V);
  const double t_go_s = (s.energy_Jpkg - taem_energy_Jpkg_) / std::fmax(D * 0.5 * (V + v_f), 1e-6);

  // Dynamic pressure from the sensed drag and the model C_D; scheduled omega (3.13).
  const double q = cd > 0.0 ? D_ref_alpha / (cd * models_.area_over_mass()) : ref.q;
  double omega_t = scheduled_omega(gains_.omega0_radps, q, q_ref_Pa_);
  if (terminal) {
    // In the last seconds the drag loop is made fast enough to remove its error before TAEM,
    // where the drag sets the altitude: the final reversal leaves a drag deficit, the loop
    // dives to recover it and, at omega0 (period 85 s), was still about 12 % above the
    // reference at TAEM (60 dispersed X-33 runs, mean): 0.3-0.6 km low on average. X-33 seed
    // 7 x 500: 491 without it (TAEM altitude mean -0.31 km, sd 0.67), 493 with it alone (-0.07,
    // sd 0.54, but five heading failures), 499 with the lift-down limit below (-0.09, 0.52).
    omega_t = std::fmax(omega_t, terminal_omega_floor_radps(gains_.omega0_radps, t_go_s));
  }

  // Time -> energy conversion (3.14)-(3.18), E' = -D V.
  const double e_dot = -D * V;
  const double e_ddot = drag_prime * D * V2 + D * D + D * g * sg;            // (3.18)
  double d2_cmd = ref.drag_second;
  const double err = D_ref_alpha - ref.drag, err_prime = drag_prime - ref.drag_prime;
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
  // The pull-outs are judged from the bank the vehicle flies (the rate filter's), not from the
  // last command: judged from its own command, the guard below released lift down on the
  // cycle after it had commanded wings level and commanded wings level again on the next,
  // while the vehicle stayed lift down (HORUS seed 424: 541 kW/m^2 against 530).
  if (!first_pullout_done_) {
    const double d_pullout = lift_up_pullout_drag_mps2(s, flown_bank_rad());
    first_pullout_done_ = d_pullout < kPullOutComplete * D;
    // Pull-out guard, from capture until the entry descent is arrested: a descent whose
    // wings-level pull-out, started after the roll out of the present bank, would bottom out
    // above the sensed constraint limit is stopped now with full lift. The linear drag loop
    // alone follows the planned drag ramp after capture with lift down and reaches the
    // plateau in a dive it can no longer arrest (HORUS: drag 5 against 2.7, heat flux 700
    // kW/m^2 against 530). Later, on the plateau, small descents are the drag loop's own.
    if (!first_pullout_done_ && !terminal && u_drag < lod && d_pullout > std::fmin(constraint_limit, plan_bound)) {
      u_drag = lod;
    }
  }
  // No lift down in the final-reversal window (the last kFinalReversalWindow reversal
  // durations, at the bank averaged up to the last cycle): a dive started there cannot be
  // arrested before TAEM (the drag overshoots, the TAEM altitude comes out low) and a bank
  // past 90 deg turns the vehicle on after the final reversal (X-33 seeds 320, 408, 426, 460,
  // 506 ended 10-12 deg off heading with it, 2-5 deg without). Barred over the whole terminal
  // phase, the runs that need much more drag there flew on at 90 deg (seed 462: 33 km long).
  u_drag = clamp(u_drag, terminal && in_final_reversal_window(t_go_s) ? 0.0 : -lod, lod);
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

  // Lateral logic. Above the corridor phase the bank sign is the plan's (one planned
  // reversal, method 3 of §7.4); below it, the sign keeps the heading within a corridor
  // around the target heading of lateral_target, narrowing towards TAEM (Shuttle-style
  // lateral logic aimed along the arrival line). A sign change is flown as a reversal, open
  // loop at the maximum bank rate, t_rev = 2 |sigma| / sigma_rate_max long.
  int sign_ref = ref.sigma >= 0.0 ? 1 : -1;
  const double t_rev_s = 2.0 * sigma_d / sigma_rate_max_radps_;
  // Bank magnitude averaged over kMeanBankTimeConstant_s: the final-reversal window and the
  // heading turned until TAEM depend on the bank flown over the remaining flight, not on the
  // present command, which swings by tens of degrees after a reversal (a reversal started on
  // a transient 84 deg bank was timed for a 34 s roll and turned back a corridor reversal
  // made 18 s earlier).
  mean_sigma_d_rad_ = mean_sigma_d_rad_ < 0.0 ? sigma_d
                                              : mean_sigma_d_rad_ + clamp(dt_s / kMeanBankTimeConstant_s, 0.0, 1.0) *
                                                                        (sigma_d - mean_sigma_d_rad_);
  if (lateral_corridor && last_sign_ != 0) {
    const double err_to_target = wrap_pi(chi - target.heading_rad);
    const double e_taem_norm = taem_energy_Jpkg_ / entry_energy_Jpkg_;
    const double x = clamp((e_norm - e_taem_norm) / (lateral_e_norm_ - e_taem_norm), 0.0, 1.0);
    const double corridor = kCorridorMin_rad + (kCorridorMax_rad - kCorridorMin_rad) * x;
    sign_ref = last_sign_;
    // Heading and cross-track from now to TAEM with the bank rolled from the one flown to the
    // mean bank magnitude on the side `sign` (the final-reversal timing and the capture guard).
    auto turn_until_taem = [&](int sign) {
      FinalTurnInput in;
      in.speed_mps = V;
      in.taem_speed_mps = v_f;
      in.t_go_s = t_go_s;
      in.lift_horizontal_mps2 = s.lift_mps2 / cg;
      in.sigma_now_rad = flown_bank_rad();
      in.sigma_end_rad = sign * mean_sigma_d_rad_;
      in.sigma_rate_radps = sigma_rate_max_radps_;
      in.roll_lag_s = kRollLag_s;
      in.heading_err_rad = wrap_pi(chi - target.line_heading_rad);
      in.cross_track_m = target.cross_track_m;
      return predict_final_turn(in);
    };
    if (in_final_reversal_window(t_go_s)) {
      // The one last reversal starts when the TAEM state it leads to is balanced between
      // heading error and cross-track offset, weighted by the mission's tolerances (a corridor
      // reversal this late would leave the vehicle mid-swing); waiting moves both towards the
      // present turn. Predicted with the roll from the bank flown to the mean bank magnitude
      // on the other side.
      const FinalTurnState turn = turn_until_taem(-last_sign_);
      const double cross_weight =
          taem_.range_tol_m > 0.0 && taem_.heading_tol_rad > 0.0 ? taem_.heading_tol_rad / taem_.range_tol_m : 0.0;
      // The same test after the final reversal is the correction reversal: the turn it left
      // would carry the heading past the balance even if the vehicle rolled back now, so it
      // rolls back once (a turn too small cannot be corrected: the sign already turns towards
      // the line). The final turn comes out 1-2 deg larger than predicted (the time to go is
      // short by about a second on average, up to 4 s after a deep modulation); X-33 seed 7 x
      // 500: TAEM heading error sd 3.9 -> 2.5 deg, 494 -> 496 successful (heading failures
      // 4 -> 2), 988 -> 990 of 1000 over three seed sets, HORUS 73 -> 74 of 500.
      const bool balance_passed = last_sign_ * (turn.heading_err_rad - cross_weight * turn.cross_track_m) >= 0.0;
      // The correction may start once the final reversal's roll has settled on the bank the
      // loop asks for: its nominal duration 2 sigma0 / sigma_rate outlasts a roll from a
      // lift-down bank (seed 462: started at 87 deg, still counted as rolling at TAEM while
      // the turn overshot by 13.7 deg; X-33 seed 7 x 500: 498 -> 499, 994 -> 997 of 1000).
      const bool bank_settled = flown_alpha_rad_ >= 0.0 && flown_sigma_rad_ * last_sign_ > 0.0 &&
                                std::fabs(flown_sigma_rad_ - last_sign_ * sigma_d) < kBankSettled_rad;
      const bool roll_over = !reversing || (final_reversal_done_ && bank_settled);
      if (roll_over && balance_passed && !final_correction_done_) {
        sign_ref = -last_sign_;
        if (final_reversal_done_) final_correction_done_ = true;
        final_reversal_done_ = true;
        // The drag integral was built up on the range control's pre-reversal reference (it
        // asks for the drag the reversal's alpha modulation will give back); kept, it held
        // the bank 15-20 deg above the loop's demand after the roll (X-33: 80 against 62).
        drag_integral_ = 0.0;
      }
    } else if (!reversing) {
      if (last_sign_ > 0 && err_to_target > corridor) sign_ref = -1;        // right of the target: bank left
      else if (last_sign_ < 0 && err_to_target < -corridor) sign_ref = 1;   // left of it: bank right
      // Capture guard: farther than kCaptureOvershoot_m from the arrival line, a bank towards
      // it is flown only while a turn away started now (roll to the mean bank on the other
      // side, speed falling to TAEM) would still stop the vehicle within kCaptureOvershoot_m
      // past the line; otherwise the vehicle reverses (or does not reverse) to turn away. The
      // approach-angle bound of the field assumes the turn away starts at once, but the
      // corridor lets the heading run up to its half-width past the target and the reversal
      // takes 2 sigma / sigma_rate: X-38 nominal, 330 km off the line at the corridor start,
      // crossed it 16 deg off, overshot by 21 km and reached TAEM 6.31 km out, 8 deg off
      // heading; with the guard it reverses 50 km out and meets the line level (1.9 km).
      // X-38 seed 7 x 200: 123 -> 133, miss p50 6.4 -> 2.9 km. A limit of 10 km: 130 of 200,
      // but 12 more planned-alpha X-33 runs long (the guard's reversal 11-20 km out).
      // Not while the mean bank is past 90 deg: the drag loop is diving, a reversal from there
      // rolls through wings level for up to a minute (the climb it leaves costs the range
      // more than the overshoot; X-33 seeds 1046 and 2152 from 0.7 and 7.8 to 12-13 km).
      const int toward_line = target.cross_track_m >= 0.0 ? 1 : -1;
      if (sign_ref == toward_line && mean_sigma_d_rad_ < 0.5 * M_PI &&
          std::fabs(target.cross_track_m) > kCaptureOvershoot_m &&
          turn_until_taem(-toward_line).overshoot_m > kCaptureOvershoot_m) {
        sign_ref = -toward_line;
      }
    }
    out.heading_err_rad = err_to_target;
  }
  if (last_sign_ != 0 && sign_ref != last_sign_) {
    reversal_until_t_s_ = s.t_s + t_rev_s + dt_s;
    reversal_start_t_s_ = s.t_s;
    reversal_sigma0_rad_ = sigma_d;
    reversal_ends_in_final_window_ = in_final_reversal_window(std::fmax(t_go_s - t_rev_s, 0.0));
  }
  last_sign_ = sign_ref;
  // Bank flown now, carried towards the command at the maximum rate for the alpha lag.
  const double sigma_flown = flown_bank_rad();
  const double max_roll_rad = sigma_rate_max_radps_ * kAlphaModulationLead_s;
  const double cos_lead =
      std::cos(sigma_flown + clamp(sign_ref * sigma_d - sigma_flown, -max_roll_rad, max_roll_rad));
  // The modulation removes vertical lift the drag loop has not asked for: only while the
  // rolling bank gives more than the loop's demand u_drag / (L/D). An open-loop modulation
  // after a reversal from 101 deg (cos(sigma0) < 0: 30 % lift) held alpha 12 deg low for 40 s
  // in a dive that the loop was asking to arrest.
  const bool lift_unwanted = cos_lead > 0.0 && cos_lead > u_drag / lod;
  // Not in the correction reversal: seconds before TAEM, the drag a modulation removes
  // can no longer be made up (X-33 nominal 0.82 -> 2.30 km long with it, 0.82 km without).
  if (!final_correction_done_ && modulation_allowed(ref.drag, ref.drag_max) && s.t_s < reversal_until_t_s_ &&
      reversal_start_t_s_ >= 0.0 && lift_unwanted) {
    // Angle-of-attack modulation in a reversal: rolling through wings level at the maximum
    // rate raises the vertical lift from L cos(sigma0) to L; lowering alpha so that
    // C_L(alpha + d_alpha) = C_L(alpha) cos(sigma0) / cos(sigma(t)) keeps the vertical lift,
    // so the reversal no longer leaves a climb that the drag loop cannot remove before TAEM.
    // sigma(t) is the rate-limited roll, led by the filter lag.
    const double t_rel = s.t_s - reversal_start_t_s_ + kAlphaModulationLead_s;
    // The final reversal (its climb would set the TAEM altitude) keeps the full modulation;
    // corridor reversals get less, since their drag deficit is what the range control
    // corrects late. So does a corridor reversal that ends inside the final-reversal window:
    // the climb it leaves is still being recovered there with the lift-down limit, so the
    // final reversal starts from 82-90 deg and its modulation takes most of the lift and half
    // the drag (traced X-33 runs 2-6 km long, seeds 43 and 50 10-12 km). X-33 seed 7 x 500:
    // 499 -> 500, miss p50 2.57 -> 2.32 km, along-track sd 2.6 -> 2.1 km; 1495 -> 1497 of 1500
    // over four seed sets.
    const double max_rad =
        final_reversal_done_ || reversal_ends_in_final_window_ ? kAlphaModulationMax_rad : kCorridorModulationMax_rad;
    out.alpha_rad = modulated_alpha(out.alpha_rad, models_.mach(s.altitude_m, V),
                                    reversal_lift_ratio(reversal_sigma0_rad_, t_rel), max_rad);
  }

  // Load relief: the alpha command (a modulation ending at high dynamic pressure raises alpha
  // by up to 15 deg within seconds) never asks for more than the load-factor limit allows at
  // the sensed dynamic pressure. Dispersed X-33 runs reached 3.1-3.3 g (limit 3) in the last
  // seconds, at the end of the final reversal.
  if (alpha_flown > 0.0) {
    out.alpha_rad = load_relief_alpha(out.alpha_rad, alpha_ref - kAlphaModulationMax_rad, alpha_flown,
                                      models_.mach(s.altitude_m, V), std::hypot(D, s.lift_mps2));
  }

  // (3.22) with w = 1: the bank sign comes from the plan or the heading corridor; the heading
  // loop's bank sigma_chi (3.21) is computed and reported for telemetry only.
  out.sigma_rad = sign_ref * sigma_d;
  if (!std::isfinite(out.sigma_rad) || !std::isfinite(out.alpha_rad)) return Status::kNonFinite;
  out.sigma_d_rad = sigma_d;
  last_sigma_d_rad_ = sigma_d;
  out.sigma_chi_rad = sigma_chi;
  out.phase = s.t_s < reversal_until_t_s_ ? Phase::kReversal : Phase::kTracking;
  out.drag_ref_mps2 = ref.drag;
  out.drag_err_mps2 = err;
  if (!lateral_corridor) out.heading_err_rad = heading_err;
  last_alpha_cmd_rad_ = out.alpha_rad;
  return Status::kOk;
}

}  // namespace reentry::fsw
