#include "planner/entry_planner.hpp"

#include <cmath>

#include "numerics/root_finding.hpp"
#include "planner/drag_derivatives.hpp"
#include "planner/mission_geometry.hpp"

namespace reentry::fsw {
namespace {

// Numerical settings of the planner's root finders (not tunables of the method): brackets of
// the equilibrium-glide height and of the profile level Dc (7.12), the finite-difference step
// of d ln rho / dr and the iteration bound.
constexpr double kMaxAltitude_m = 200000.0;
constexpr double kMinLevel_mps2 = 1e-3;
constexpr double kMaxLevel_mps2 = 500.0;   // far above any corridor maximum: clipped to it
constexpr double kDensityStep_m = 25.0;
constexpr int kRootIterations = 80;

bool finite_state(const RelativeState& s) {
  return std::isfinite(s.radius_m) && std::isfinite(s.latitude_rad) && std::isfinite(s.longitude_rad) &&
         std::isfinite(s.velocity_mps) && std::isfinite(s.heading_rad) && std::isfinite(s.energy_Jpkg) &&
         std::isfinite(s.drag_mps2);
}

}  // namespace

Status EntryPlanner::init(const OnboardModels& models, const AlphaProfile& alpha_profile,
                          const GuidanceMission& mission, const GuidanceLawParams& params) {
  initialised_ = false;
  models_ = models;
  alpha_profile_ = alpha_profile;
  params_ = params.planner;
  if (params_.rk4_steps < 10 || params_.rk4_steps > kMaxRkSteps || params_.max_length_iterations < 1 ||
      params_.max_length_iterations > 1000 || !(params_.downrange_tol_m > 0.0) || !(params_.crossrange_tol_m > 0.0)) {
    return Status::kInvalidInput;
  }
  terminal_span_fraction_ = params.terminal_span_fraction;

  const PathLimits& c = mission.limits;
  // The corridor is planned with a design margin on every path constraint: the tracker's
  // transients at drag capture and the on-board/true aerodynamics differences (trim) must fit.
  const double margin = params.constraint_margin;
  heat_max_ = margin * c.heat_flux_max_Wpm2;
  q_alpha_max_ = margin * c.q_alpha_max_Pa_rad;
  alpha_max_ = c.alpha_max_rad;
  n_max_ = margin * c.load_factor_max_g * kG0_mps2;
  q_max_ = margin * c.dynamic_pressure_max_Pa;
  sigma_rate_max_ = c.sigma_rate_max_radps;
  if (!(sigma_rate_max_ > 0.0)) return Status::kInvalidInput;

  const EntryInterface& e = mission.entry;
  entry_ = RelativeState{};
  entry_.radius_m = kEarthRadius_m + e.altitude_m;
  entry_.altitude_m = e.altitude_m;
  entry_.longitude_rad = e.longitude_rad;
  entry_.latitude_rad = e.latitude_rad;
  entry_.velocity_mps = e.velocity_mps;
  entry_.flight_path_rad = e.flight_path_rad;
  entry_.heading_rad = e.heading_rad;
  entry_.energy_Jpkg = specific_energy_Jpkg(entry_.radius_m, e.velocity_mps);  // (7.8)
  entry_energy_ = entry_.energy_Jpkg;
  const double alpha_entry = alpha_profile_.alpha_rad(1.0);
  entry_.drag_mps2 = models_.drag_mps2(alpha_entry, e.altitude_m, e.velocity_mps);
  entry_.lift_mps2 = models_.lift_mps2(alpha_entry, e.altitude_m, e.velocity_mps);

  const TaemTarget& t = mission.taem;
  taem_radius_ = surface_radius_m(t.latitude_rad) + t.altitude_m;
  taem_velocity_ = t.velocity_mps;
  taem_lat_ = t.latitude_rad;
  taem_lon_ = t.longitude_rad;
  taem_energy_ = specific_energy_Jpkg(taem_radius_, taem_velocity_);
  taem_drag_altitude_m_ = taem_box_altitude(t);
  e_corridor_ = taem_energy_ + params.lateral_corridor_span_fraction * (entry_energy_ - taem_energy_);
  if (!(entry_energy_ > taem_energy_) || !(taem_energy_ > 0.0) || !std::isfinite(entry_.drag_mps2)) {
    return Status::kInvalidInput;
  }
  ranging_blend_min_ = 0.0;
  flown_side_known_ = false;
  initialised_ = true;
  return Status::kOk;
}

RelativeState EntryPlanner::entry_state() const { return entry_; }

double EntryPlanner::taem_box_altitude(const TaemTarget& t) const {
  // Final drag of the profile: the vehicle meets the TAEM energy where the drag equals it, so
  // that drag sets the TAEM altitude (and, the energy being fixed, the speed and Mach). Rule:
  // of the altitudes in the TAEM altitude band, take the one whose state at the TAEM energy
  // lies deepest inside both bands, min over {altitude, Mach} of the normalised distance to
  // the band edge, among the altitudes where q and q*alpha at the TAEM alpha are within their
  // limits (the mission altitude itself when no Mach band is given).
  if (!has_mach_band(t) || !(t.altitude_tol_m > 0.0)) return t.altitude_m;
  double best_h = t.altitude_m, best_depth = -1e300;
  const double alpha_taem = alpha_profile_.alpha_rad(taem_energy_ / entry_energy_);
  for (int i = 0; i <= params_.taem_box_samples; ++i) {
    const double h = t.altitude_m + t.altitude_tol_m * (2.0 * i / params_.taem_box_samples - 1.0);
    const double v = OnboardModels::taem_speed_mps(t.latitude_rad, taem_energy_, h);
    if (!(v > 0.0)) continue;
    // The TAEM state must itself satisfy the dynamic-pressure constraints at the TAEM alpha.
    const double q = 0.5 * models_.atmosphere().density_kgpm3(h) * v * v;
    if (q * alpha_taem > q_alpha_max_ || q > q_max_) continue;
    const double depth = models_.taem_band_depth(t, taem_energy_, h);
    if (depth > best_depth) { best_depth = depth; best_h = h; }
  }
  return best_h;
}

// ------------------------------------------------------------------ corridor
// Energy grid from the planning energy to TAEM. When the profile starts from a near-zero
// drag (actual drag at the entry interface) the range flown per unit energy is huge at the
// start (S = -int dE / D), so the grid is graded quadratically towards the planning energy.
Status EntryPlanner::build_grid(double e0, bool graded) {
  e0_ = e0;
  const double span = e0 - taem_energy_;
  for (int k = 0; k < kGrid; ++k) {
    const double u = static_cast<double>(k) / (kGrid - 1);
    e_[k] = e0 - span * (graded ? u * u : u);
    alpha_[k] = alpha_profile_.alpha_rad(e_[k] / entry_energy_);
    alpha_base_[k] = alpha_[k];
  }
  e_[kGrid - 1] = taem_energy_;
  return Status::kOk;
}

Status EntryPlanner::equilibrium_glide_radius() {
  // Initial h(E): zero-bank equilibrium glide L = g - V^2 / r (2.50), one root per energy.
  for (int k = 0; k < kGrid; ++k) {
    const double energy = e_[k];
    const double alpha = alpha_[k];
    const double r_top = radius_for_speed_m(energy, 50.0);
    const double h_top = clamp(r_top - kEarthRadius_m, 0.0, kMaxAltitude_m);
    if (!(h_top > 1000.0)) return Status::kExtractionFailed;
    auto residual = [&](double h) {
      const double r = kEarthRadius_m + h;
      const double v = velocity_from_energy_mps(energy, r);
      return models_.lift_mps2(alpha, h, v) - (gravity_mps2(r) - v * v / r);
    };
    const numerics::RootResult root = numerics::brent(residual, 0.0, h_top, 1.0, kRootIterations);
    const Status st = to_status(root.status);
    if (st == Status::kOk || st == Status::kMaxIterations) {
      r_[k] = kEarthRadius_m + root.x;
    } else if (st == Status::kNoBracket && residual(h_top) > 0.0) {
      r_[k] = kEarthRadius_m + h_top;  // lift exceeds the need everywhere: highest admissible point
    } else {
      return st == Status::kNoBracket ? Status::kExtractionFailed : st;
    }
  }
  return Status::kOk;
}

void EntryPlanner::corridor() {
  const double s_over_m = models_.area_over_mass();
  const double two_c2m2 = 2.0 * (models_.heat_flux_velocity_exponent() - 1.0);
  const double span = e0_ - taem_energy_;
  for (int k = 0; k < kGrid; ++k) {
    const double r = r_[k];
    const double h = r - kEarthRadius_m;
    const double v = velocity_from_energy_mps(e_[k], r);
    const double g = gravity_mps2(r);
    double cl, cd;
    models_.aero().coefficients(alpha_[k], models_.mach(h, v), cl, cd);
    const double alpha = alpha_[k];
    const double c_heat = models_.heat_flux_coefficient(alpha);  // q = C(alpha) sqrt(rho) V^c2
    d_heat_[k] = (heat_max_ * heat_max_ * cd * s_over_m) / (2.0 * c_heat * c_heat * std::pow(v, two_c2m2));  // (7.3)
    d_qalpha_[k] = alpha > 1e-6 ? q_alpha_max_ * cd * s_over_m / alpha : kUnconstrained;         // (7.4)
    const double d_load = n_max_ / (cl / cd * std::cos(alpha) + std::sin(alpha));                           // (7.5)
    const double d_q = q_max_ * cd * s_over_m;                                                               // (7.6)
    double dmax = d_heat_[k];
    if (d_qalpha_[k] < dmax) dmax = d_qalpha_[k];
    if (d_load > 0.0 && d_load < dmax) dmax = d_load;
    if (d_q < dmax) dmax = d_q;
    d_max_[k] = dmax;
    d_min_[k] = (g - v * v / r) * cd / cl;                                                                  // (7.7)
    // Feasibility floor: (7.7) with the Earth-rate term of (2.45) (see below_glide_floor), lat
    // and chi on the planning-point -> TAEM great circle at the energy fraction (the range
    // fraction is not known before the fit). (7.7) itself stays the thesis's Lmin for the
    // initial drag and the E2 breakpoint; the closure test needs the floor the vehicle really
    // has: for the eastbound Orbiter at 40 deg alpha the rotation-free Lmin lies above the
    // heat-flux limit between 7.2 and 5.5 km/s, the true floor below it.
    const double f = span > 0.0 ? (e0_ - e_[k]) / span : 0.0;
    const TrackPoint p = great_circle_point(from_.latitude_rad, from_.longitude_rad, taem_lat_, taem_lon_, f);
    d_floor_[k] = level_flight_lift_need_mps2(r, v, p.lat_rad, p.azimuth_rad) * cd / cl;
  }
}

void EntryPlanner::breakpoints() {
  const double span = e0_ - taem_energy_;
  // E1: heat-flux / q-alpha intersection (first crossing from the planning energy down).
  double e1 = e0_ - 0.3 * span;
  bool found = false;
  for (int k = 0; k + 1 < kGrid && !found; ++k) {
    const double f0 = d_heat_[k] - d_qalpha_[k];
    const double f1 = d_heat_[k + 1] - d_qalpha_[k + 1];
    if (std::isfinite(f0) && std::isfinite(f1) && f0 < 0.0 && f1 >= 0.0) {
      e1 = e_[k] + (e_[k + 1] - e_[k]) * (f0 / (f0 - f1));
      found = true;
    }
  }
  e1 = clamp(e1, taem_energy_ + 0.1 * span, e0_ - 0.02 * span);
  // E2: energy of the (highest) maximum of Lmin below E1.
  double best = -1.0;
  double e2 = taem_energy_ + 0.05 * span;
  for (int k = 0; k < kGrid; ++k) {
    if (e_[k] < e1 && d_min_[k] > best) { best = d_min_[k]; e2 = e_[k]; }
  }
  e2 = clamp(e2, taem_energy_ + 0.02 * span, e1 - 0.02 * span);
  diag_.e1_Jpkg = e1;
  diag_.e2_Jpkg = e2;
}

// ------------------------------------------------------------------ drag profile
Status EntryPlanner::fit_profile(double s_m) {
  Status s;
  level_at_max_ = false;
  const bool three = params_.drag_profile == DragProfileKind::kThreeSegment;
  if (three) {
    three_ = ThreeSegmentProfile{e0_, diag_.e1_Jpkg, diag_.e2_Jpkg, taem_energy_, diag_.di_mps2, 1.0, diag_.df_mps2};
    s = three_.solve_constant_drag(s_m, kMinLevel_mps2, kMaxLevel_mps2);   // (7.12)
  } else {
    smooth_ = SmoothProfile{e0_, taem_energy_, diag_.di_mps2, 1.0, diag_.df_mps2};
    s = smooth_.solve_level(s_m, kMinLevel_mps2, kMaxLevel_mps2);
  }
  if (s == Status::kNoBracket) {
    // Shorter than even the highest level flies: that level, clipped below to the corridor
    // maximum, is the shortest-range profile (flown as a best effort when the range is too
    // long for the vehicle, see length_iteration). Otherwise no level reaches the length.
    if (three) three_.d_c = kMaxLevel_mps2;
    else smooth_.d_c = kMaxLevel_mps2;
    const double shortest_m = three ? three_.length_m() : smooth_.length_m();
    if (!(shortest_m > s_m)) return Status::kCorridorClosed;
    level_at_max_ = true;
    s = Status::kOk;
  }
  diag_.dc_mps2 = three ? three_.d_c : smooth_.d_c;
  if (s != Status::kOk) return s;
  int clipped = 0;
  for (int k = 0; k < kGrid; ++k) {
    if (params_.drag_profile == DragProfileKind::kThreeSegment) {
      d_[k] = three_.drag(e_[k]);
      dp_[k] = three_.slope(e_[k]);
      dpp_[k] = 0.0;  // linear segments
    } else {
      d_[k] = smooth_.drag(e_[k]);
      dp_[k] = smooth_.slope(e_[k]);
      dpp_[k] = smooth_.curvature(e_[k]);
    }
  }
  // Where the profile violates the active maximum constraint, follow the constraint (§7.2).
  for (int k = 0; k < kGrid; ++k) {
    if (d_[k] > d_max_[k]) {
      ++clipped;
      d_[k] = d_max_[k];
      const int km = k > 0 ? k - 1 : 0;
      const int kp = k + 1 < kGrid ? k + 1 : kGrid - 1;
      dp_[k] = (d_max_[kp] - d_max_[km]) / (e_[kp] - e_[km]);
      if (k > 0 && k + 1 < kGrid) {  // second difference on the (possibly graded) grid
        const double h1 = e_[k] - e_[km], h2 = e_[kp] - e_[k];
        dpp_[k] = 2.0 * (h1 * d_max_[kp] - (h1 + h2) * d_max_[k] + h2 * d_max_[km]) / (h1 * h2 * (h1 + h2));
      } else {
        dpp_[k] = 0.0;
      }
    }
    if (!std::isfinite(d_[k] + dp_[k] + dpp_[k])) return Status::kNonFinite;
  }
  diag_.clipped_points = clipped;
  return Status::kOk;
}

// ------------------------------------------------------------------ extraction
Status EntryPlanner::extract() {
  for (int k = 0; k < kGrid; ++k) {
    const double energy = e_[k];
    const double alpha = alpha_[k];
    const double drag = d_[k];
    const double h_top = clamp(radius_for_speed_m(energy, 1.0) - kEarthRadius_m, 0.0, kMaxAltitude_m);
    auto residual = [&](double h) {  // (7.13)
      return models_.drag_mps2(alpha, h, velocity_from_energy_mps(energy, kEarthRadius_m + h)) - drag;
    };
    const numerics::RootResult root = numerics::brent(residual, 0.0, h_top, 0.05, kRootIterations);
    const Status st = to_status(root.status);
    if (st == Status::kNoBracket) return Status::kExtractionFailed;
    if (st != Status::kOk && st != Status::kMaxIterations) return st;
    const double h = root.x;
    r_[k] = kEarthRadius_m + h;
    v_[k] = velocity_from_energy_mps(energy, r_[k]);
    double cl, cd;
    models_.aero().coefficients(alpha, models_.mach(h, v_[k]), cl, cd);
    cd_[k] = cd;
    lod_[k] = cl / cd;
    q_[k] = 0.5 * models_.atmosphere().density_kgpm3(h) * v_[k] * v_[k];
  }
  for (int k = 0; k < kGrid; ++k) {
    const int km = k > 0 ? k - 1 : 0;
    const int kp = k + 1 < kGrid ? k + 1 : kGrid - 1;
    const double h = r_[k] - kEarthRadius_m;
    DragLocal l;
    l.drag = d_[k];
    l.velocity = v_[k];
    l.radius = r_[k];
    l.gravity = gravity_mps2(r_[k]);
    // d ln rho / dr and CD' by finite differences on the models; CD'' = 0 (Mease et al.).
    l.rho_r_over_rho = models_.dlnrho_dr_fd(h, kDensityStep_m);
    l.cd_prime_over_cd = models_.drag_coefficient_slope(alpha_[km], e_[km], r_[km] - kEarthRadius_m, alpha_[kp], e_[kp],
                                                        r_[kp] - kEarthRadius_m) / cd_[k];
    l.cd_second_over_cd = 0.0;
    const double sin_gamma = sin_gamma_from_drag_slope(l, dp_[k]);  // (7.14)
    if (!std::isfinite(sin_gamma)) return Status::kNonFinite;
    if (std::fabs(sin_gamma) >= 1.0) return Status::kExtractionFailed;
    gamma_[k] = std::asin(sin_gamma);
    a0_[k] = drag_second_a_no_coriolis(l, dp_[k]);  // (7.19) without C_gamma
    kfac_[k] = density_gravity_factor(l);
    b_[k] = drag_second_b(l);                       // (7.20)
    if (!std::isfinite(a0_[k] + kfac_[k] + b_[k] + lod_[k])) return Status::kNonFinite;
  }
  return Status::kOk;
}

// ------------------------------------------------------------------ reduced-order system
double EntryPlanner::bank_magnitude(int k, double w, double lat, double chi, double& lod) const {
  const RangePoint p = range_point_at(k, w, true);
  lod = p.lod;
  return vertical_lod(p, std::cos(lat), std::sin(chi));
}

double EntryPlanner::vertical_lod(const RangePoint& p, double cos_lat, double sin_chi) const {
  const double a = p.a0 + p.kf * coriolis_gamma_trig(kEarthRate_radps, cos_lat, sin_chi, p.drag, p.v);  // (7.18)-(7.19)
  return (p.dpp - a) / p.b;  // (L/D) cos(sigma) from D'' = a + b (L/D) cos(sigma) (7.17)
}

double EntryPlanner::sigma_sign_schedule(double energy, double lod_sin_abs, double lod) const {
  if (energy > e_rev_) return sign0_ * lod_sin_abs;
  if (energy > e_rev_ - de_rev_) {
    // Method 3 of §7.4: sigma goes linearly (in energy) from s0 sigma_rev0 to -s0 sigma_rev0.
    const double sigma = sign0_ * sigma_rev0_ * (1.0 - 2.0 * (e_rev_ - energy) / de_rev_);
    return lod * std::sin(sigma);
  }
  return -sign0_ * lod_sin_abs;
}

// The reduced-order system is integrated with the flown range s = -int dE / D (7.10) as
// independent variable: d()/ds = -D d()/dE. Steps uniform in s stay accurate where the
// drag is tiny (planning from the actual drag at entry), where steps uniform in energy
// would badly misestimate the range flown.
void EntryPlanner::build_range_table() {
  s_cum_[0] = 0.0;
  for (int k = 0; k + 1 < kGrid; ++k) {
    d_slope_[k] = (d_[k + 1] - d_[k]) / (e_[k + 1] - e_[k]);
    s_cum_[k + 1] = s_cum_[k] + linear_segment_length(e_[k] - e_[k + 1], d_[k], d_[k + 1]);
  }
  d_slope_[kGrid - 1] = d_slope_[kGrid - 2];
  s_total_ = s_cum_[kGrid - 1];
}

double EntryPlanner::energy_at_range(double s_m, int& k, double& w) const {
  // Cell k with s_cum_[k] <= s_m < s_cum_[k + 1] (s_cum_ strictly increasing), clamped to the
  // first and last cells. The integration walks the cells in order, so the last cell and its
  // successor are tried before the bisection; the cell found is the same either way.
  const int h = range_hint_;
  if (s_m > 0.0 && s_m < s_total_ && h >= 0 && h + 1 < kGrid && s_cum_[h] <= s_m && s_m < s_cum_[h + 1]) {
    k = h;
  } else if (s_m > 0.0 && s_m < s_total_ && h >= 0 && h + 2 < kGrid && s_cum_[h + 1] <= s_m && s_m < s_cum_[h + 2]) {
    k = h + 1;
  } else {
    int lo = 0, hi = kGrid - 1;
    if (s_m <= 0.0) { hi = 1; }
    else if (s_m >= s_total_) { lo = kGrid - 2; }
    for (int it = 0; it < 16 && hi - lo > 1; ++it) {
      const int mid = (lo + hi) / 2;
      if (s_cum_[mid] <= s_m) lo = mid; else hi = mid;
    }
    k = lo;
  }
  range_hint_ = k;
  // Linear D in E within the cell: D(s) = D_k exp(-m (s - s_k)), E = E_k + (D - D_k) / m.
  const double ds = s_m - s_cum_[k];
  const double m = d_slope_[k];
  const double x = -m * ds;
  const double energy = std::fabs(x) < 1e-12 ? e_[k] - d_[k] * ds : e_[k] + d_[k] * std::expm1(x) / m;
  w = clamp((e_[k] - energy) / (e_[k] - e_[k + 1]), 0.0, 1.0);
  return energy;
}

EntryPlanner::RangePoint EntryPlanner::range_point_at(int k, double w, bool lift_terms) const {
  RangePoint p;
  p.r = r_[k] + w * (r_[k + 1] - r_[k]);
  const double gamma = gamma_[k] + w * (gamma_[k + 1] - gamma_[k]);
  p.drag = d_[k] + w * (d_[k + 1] - d_[k]);
  p.v = v_[k] + w * (v_[k + 1] - v_[k]);
  p.cos_gamma = std::cos(gamma);
  if (lift_terms) {
    p.tan_gamma = std::tan(gamma);
    p.a0 = a0_[k] + w * (a0_[k + 1] - a0_[k]);
    p.kf = kfac_[k] + w * (kfac_[k + 1] - kfac_[k]);
    p.b = b_[k] + w * (b_[k + 1] - b_[k]);
    p.dpp = dpp_[k] + w * (dpp_[k + 1] - dpp_[k]);
    p.lod = lod_[k] + w * (lod_[k + 1] - lod_[k]);
  }
  return p;
}

EntryPlanner::RangePoint EntryPlanner::range_point(double s_m) const {
  int k;
  double w;
  const double energy = energy_at_range(s_m, k, w);
  // The lift and Coriolis terms are not needed in the corridor phase (see rop_derivative).
  RangePoint p = range_point_at(k, w, energy >= e_corridor_);
  p.energy = energy;
  return p;
}

void EntryPlanner::rop_derivative(const RangePoint& p, const Rop& y, Rop& dy) const {
  const double cg = p.cos_gamma, r = p.r, sd = std::sin(y.lat), cd = std::cos(y.lat);
  const double sc = std::sin(y.chi), cc = std::cos(y.chi);
  // (2.42)-(2.45) multiplied by dE/ds = -D.
  dy.lon = sc * cg / (r * cd);                                              // (2.42)
  dy.lat = cc * cg / r;                                                     // (2.43)
  if (p.energy < e_corridor_) {
    // Lateral corridor phase: the tracker's heading corridor holds the vehicle on a great
    // circle and averages the lateral lift out, so the trajectory is that circle: (2.44)
    // without the lift and Coriolis terms.
    dy.chi = cg * (sd / cd) * sc / r;
    return;
  }
  const double drag = p.drag, v = p.v, lod = p.lod;
  const double lc = clamp(vertical_lod(p, cd, sc), -lod, lod);
  const double lod_sin_abs = std::sqrt(lod * lod - lc * lc);  // (7.21)
  const double lod_sin = sigma_sign_schedule(p.energy, lod_sin_abs, lod);
  const double c_chi = -2.0 * kEarthRate_radps * (sd - cd * p.tan_gamma * cc) / (drag * v);  // (2.45)
  dy.chi = drag * (lod_sin / (v * v * cg) - c_chi) + cg * (sd / cd) * sc / r;                 // (2.44)
}

void EntryPlanner::rk4(double s_m, const Rop& y, double h, Rop& out) const {
  Rop k1, k2, k3, k4, t;
  const RangePoint p_mid = range_point(s_m + 0.5 * h);  // both midpoint stages
  rop_derivative(range_point(s_m), y, k1);
  t = {y.lon + 0.5 * h * k1.lon, y.lat + 0.5 * h * k1.lat, y.chi + 0.5 * h * k1.chi};
  rop_derivative(p_mid, t, k2);
  t = {y.lon + 0.5 * h * k2.lon, y.lat + 0.5 * h * k2.lat, y.chi + 0.5 * h * k2.chi};
  rop_derivative(p_mid, t, k3);
  t = {y.lon + h * k3.lon, y.lat + h * k3.lat, y.chi + h * k3.chi};
  rop_derivative(range_point(s_m + h), t, k4);
  out.lon = y.lon + h / 6.0 * (k1.lon + 2.0 * k2.lon + 2.0 * k3.lon + k4.lon);
  out.lat = y.lat + h / 6.0 * (k1.lat + 2.0 * k2.lat + 2.0 * k3.lat + k4.lat);
  out.chi = y.chi + h / 6.0 * (k1.chi + 2.0 * k2.chi + 2.0 * k3.chi + k4.chi);
}

// s_rev >= total range: no reversal, states stored in base_. Otherwise restart from base_ at
// the step containing s_rev; with store, every step boundary goes to track_.
Status EntryPlanner::integrate(double s_rev, bool store, Rop& final_state) {
  const int n = params_.rk4_steps;
  const double h = s_total_ / n;
  Rop y{from_.longitude_rad, from_.latitude_rad, from_.heading_rad};
  if (s_rev >= s_total_) {
    e_rev_ = taem_energy_ - 1e12;  // never reached
    de_rev_ = 1.0;
    sigma_rev0_ = 0.0;
    base_[0] = y;
    for (int i = 0; i < n; ++i) rk4(i * h, base_[i], h, base_[i + 1]);
    final_state = base_[n];
    if (store) {
      for (int i = 0; i <= n; ++i) track_[i] = base_[i];
    }
    return std::isfinite(final_state.lon + final_state.lat + final_state.chi) ? Status::kOk : Status::kNonFinite;
  }
  if (s_rev < 0.0) s_rev = 0.0;
  int j = static_cast<int>(s_rev / h);
  j = j < 0 ? 0 : (j > n - 1 ? n - 1 : j);
  if (store) {
    for (int i = 0; i <= j; ++i) track_[i] = base_[i];
  }
  int k;
  double w;
  e_rev_ = energy_at_range(s_rev, k, w);
  de_rev_ = 1.0;
  sigma_rev0_ = 0.0;
  y = base_[j];
  const double h_part = s_rev - j * h;  // >= 0
  if (h_part > 0.0) rk4(j * h, y, h_part, y);
  // Reversal start: bank magnitude and D V at E_rev, span dE = 2 sigma_rev0 / sigma_dot_max * D V.
  {
    double lod;
    const double lod_cos = bank_magnitude(k, w, y.lat, y.chi, lod);
    sigma_rev0_ = std::acos(clamp(lod_cos / lod, -1.0, 1.0));
    const double drag = d_[k] + w * (d_[k + 1] - d_[k]);
    const double v = v_[k] + w * (v_[k + 1] - v_[k]);
    de_rev_ = 2.0 * sigma_rev0_ / sigma_rate_max_ * drag * v;
    if (!(de_rev_ > 1e-9)) de_rev_ = 1e-9;
  }
  if (h - h_part > 0.0) rk4(s_rev, y, h - h_part, y);
  if (store) track_[j + 1] = y;
  for (int i = j + 1; i < n; ++i) {
    rk4(i * h, y, h, y);
    if (store) track_[i + 1] = y;
  }
  final_state = y;
  return std::isfinite(y.lon + y.lat + y.chi) ? Status::kOk : Status::kNonFinite;
}

Status EntryPlanner::reversal_search(double& s_rev, double& crossrange_rad, double& downrange_rad) {
  diag_.reversal_best_effort = false;
  build_range_table();
  if (!(s_total_ > 0.0) || !std::isfinite(s_total_)) return Status::kNonFinite;
  Rop end{};
  Status s = integrate(2.0 * s_total_, false, end);  // base run, no reversal
  if (s != Status::kOk) return s;
  int evaluations = 1;
  const double f_tol_base = 0.25 * params_.crossrange_tol_m / r_mean_;
  const TrackErrors base = track_errors(from_.latitude_rad, from_.longitude_rad, a_mission_, end.lat, end.lon);
  if (from_.energy_Jpkg <= e_corridor_ || std::fabs(base.crossrange_rad) < f_tol_base) {
    // Planning inside the corridor phase, where the tracker steers laterally and a planned
    // reversal has no effect (or already on target): no reversal to search.
    s_rev = 2.0 * s_total_;
    crossrange_rad = base.crossrange_rad;
    downrange_rad = base.downrange_rad;
    diag_.reversal_evaluations += evaluations;
    return Status::kOk;
  }
  auto crossrange = [&](double s_trial) {
    ++evaluations;
    Rop y{};
    if (integrate(s_trial, false, y) != Status::kOk) return std::nan("");
    return track_errors(from_.latitude_rad, from_.longitude_rad, a_mission_, y.lat, y.lon).crossrange_rad;
  };
  const double f_tol = 0.25 * params_.crossrange_tol_m / r_mean_;
  // Reversal range from (just after) the planning point to the end; secant/Brent on a2.
  const double s_lo = 1e-9 * s_total_, s_hi = s_total_ * (1.0 - 1e-9);
  numerics::RootResult root = numerics::brent(crossrange, s_lo, s_hi, 1e-9 * s_total_, 60, f_tol);
  Status st = to_status(root.status);
  if (st == Status::kNoBracket) {
    // The quadrant rule (fig. 7.20) picks the first turn from the heading offset alone; after
    // a long wings-level descent (or with a large offset) the one-reversal solution may need
    // the opposite first turn. Try it once before reporting that no reversal exists.
    sign0_ = -sign0_;
    root = numerics::brent(crossrange, s_lo, s_hi, 1e-9 * s_total_, 60, f_tol);
    st = to_status(root.status);
    if (st != Status::kOk) sign0_ = -sign0_;
    diag_.initial_bank_sign = sign0_;
  }
  diag_.reversal_evaluations += evaluations;
  if (st == Status::kNoBracket) {
    // No single reversal nulls the crossrange (typically just after a flown reversal, when
    // the remaining turn is short). Best effort: the smallest crossrange of no reversal and
    // the interval ends; accepted when it is a small fraction of the range to go, which the
    // lateral corridor phase steers out, since a stale plan would be worse.
    double best_s = 2.0 * s_total_, best_abs = std::fabs(base.crossrange_rad);
    const double ends[2] = {s_lo, s_hi};
    for (double s_end : ends) {
      const double c = crossrange(s_end);
      if (std::isfinite(c) && std::fabs(c) < best_abs) {
        best_abs = std::fabs(c);
        best_s = s_end;
      }
    }
    if (!(best_abs < params_.best_effort_crossrange_fraction * diag_.b_mission_rad)) {
      lateral_unreachable_ = true;
      return st;
    }
    s_rev = best_s;
    s = integrate(s_rev, false, end);
    if (s != Status::kOk) return s;
    const TrackErrors te = track_errors(from_.latitude_rad, from_.longitude_rad, a_mission_, end.lat, end.lon);
    crossrange_rad = te.crossrange_rad;
    downrange_rad = te.downrange_rad;
    diag_.reversal_best_effort = true;
    return Status::kOk;
  }
  if (st != Status::kOk) return st;
  s_rev = root.x;
  s = integrate(s_rev, false, end);
  if (s != Status::kOk) return s;
  const TrackErrors te = track_errors(from_.latitude_rad, from_.longitude_rad, a_mission_, end.lat, end.lon);
  crossrange_rad = te.crossrange_rad;
  downrange_rad = te.downrange_rad;
  return Status::kOk;
}

// ------------------------------------------------------------------ corridor + length iteration
Status EntryPlanner::prepare_corridor(double d_actual) {
  Status s = equilibrium_glide_radius();
  if (s != Status::kOk) return s;
  corridor();
  // Closed corridor: the active maximum drag below Lmin. Lmin is a manoeuvrability limit,
  // not a structural one (§7.1), so short closures are flown on the maximum constraint;
  // a corridor closed over more than max_closed_fraction of the grid is a failure.
  int closed = 0;
  for (int k = 0; k < kGrid; ++k) {
    if (!std::isfinite(d_floor_[k]) || !(d_max_[k] > 0.0)) return Status::kCorridorClosed;
    if (d_max_[k] <= d_floor_[k]) ++closed;
  }
  diag_.corridor_closed_points = closed;
  if (closed > params_.max_closed_fraction * kGrid) return Status::kCorridorClosed;
  breakpoints();
  diag_.di_mps2 = params_.initial_drag == InitialDrag::kActual ? d_actual : d_min_[0];
  if (diag_.di_mps2 < params_.drag_floor_mps2) diag_.di_mps2 = params_.drag_floor_mps2;
  diag_.df_mps2 = models_.drag_mps2(alpha_[kGrid - 1], taem_drag_altitude_m_,
                                    OnboardModels::taem_speed_mps(taem_lat_, taem_energy_, taem_drag_altitude_m_));
  return Status::kOk;
}

Status EntryPlanner::length_iteration(double range_desired, double& s_m, double& s_rev, bool& converged) {
  // Trajectory-length iteration (7.22): fit, extract, reversal search, correct the length.
  double cross = 0.0, down = 0.0;
  converged = false;
  lateral_unreachable_ = false;  // set by reversal_search, read by lateral_short()
  for (int it = 0; it < params_.max_length_iterations; ++it) {
    diag_.iterations = it + 1;
    Status s = fit_profile(s_m);
    if (s != Status::kOk) return s;
    s = extract();
    if (s != Status::kOk) return s;
    s = reversal_search(s_rev, cross, down);
    if (s != Status::kOk) return s;
    const double range_flown = down * r_mean_;  // R_i
    diag_.s_final_m = s_m;
    diag_.crossrange_err_m = cross * r_mean_;
    diag_.downrange_err_m = range_desired - range_flown;
    // The shortest-range (maximum-drag) profile still flies past the aim point: no length
    // fits. Reported, with this profile kept as the best effort.
    if (level_at_max_ && range_desired - range_flown < -params_.downrange_tol_m) return Status::kRangeTooLong;
    if (std::fabs(range_desired - range_flown) < params_.downrange_tol_m) {
      converged = diag_.reversal_best_effort || std::fabs(diag_.crossrange_err_m) < params_.crossrange_tol_m;
      break;
    }
    s_m += range_desired - range_flown;  // (7.22)
    if (!(s_m > 0.0)) return Status::kNotConverged;
  }
  return Status::kOk;
}

bool EntryPlanner::lateral_short() const {
  // No single reversal nulls the crossrange and the best effort leaves more than the
  // tolerance: the bank needed for the range is too small to turn (low L/D, long range).
  // Judged only in the first tenth of the energy span, before the heat pulse: later, a
  // best-effort plan just after a flown reversal is normal (the lateral corridor steers the
  // rest out), and moving alpha then swaps a profile on the heat-flux limit for one the
  // vehicle cannot reach without exceeding it.
  const double early = taem_energy_ + params_.lateral_move_span_fraction * (entry_energy_ - taem_energy_);
  return from_.energy_Jpkg > early &&
         (lateral_unreachable_ || (diag_.reversal_best_effort && std::fabs(diag_.crossrange_err_m) > params_.crossrange_tol_m));
}

bool EntryPlanner::below_glide_floor() const {
  // The drag the range needs is below the wings-level equilibrium glide somewhere between
  // the end of the capture part of the profile (where it first reaches the floor, or after
  // capture_span_fraction of the span) and the terminal phase (where the tracker's range
  // control takes over). Floor: L = g - V^2/r - 2 omega V cos(lat) sin(chi) ((2.45) with
  // gamma' = 0 and sigma = 0; the Earth-rate term is a sixth of the need for the eastbound
  // X-33 at Mach 20, so the rotation-free Lmin (7.7) would call its nominal plan infeasible),
  // lat and chi on the planning-point -> TAEM great circle at the planned range fraction.
  const double span = e0_ - taem_energy_;
  const double e_terminal = taem_energy_ + terminal_span_fraction_ * (entry_energy_ - taem_energy_);
  const double s_end = s_cum_[kGrid - 1];
  bool entered = false;
  for (int k = 0; k < kGrid && e_[k] > e_terminal; ++k) {
    const double f = s_end > 0.0 ? s_cum_[k] / s_end : 0.0;  // planned range fraction
    const TrackPoint p = great_circle_point(from_.latitude_rad, from_.longitude_rad, taem_lat_, taem_lon_, f);
    const double floor = level_flight_lift_need_mps2(r_[k], v_[k], p.lat_rad, p.azimuth_rad) / lod_[k];
    if (!entered) entered = d_[k] >= floor || e_[k] < e0_ - params_.capture_span_fraction * span;
    if (entered && d_[k] < floor) return true;
  }
  return false;
}

void EntryPlanner::alpha_ld_max_on_grid() {
  // alpha of maximum C_L / C_D at the Mach of the grid's equilibrium-glide state, by a
  // bounded scan over [0, alpha_max].
  for (int k = 0; k < kGrid; ++k) {
    const double h = r_[k] - kEarthRadius_m;
    const double mach = models_.mach(h, velocity_from_energy_mps(e_[k], r_[k]));
    double best_alpha = alpha_base_[k], best_lod = -1.0;
    for (int i = 0; i <= params_.alpha_scan_steps; ++i) {
      const double a = alpha_max_ * i / params_.alpha_scan_steps;
      double cl, cd;
      models_.aero().coefficients(a, mach, cl, cd);
      if (cd > 0.0 && cl / cd > best_lod) { best_lod = cl / cd; best_alpha = a; }
    }
    alpha_ld_[k] = best_alpha;
  }
}

void EntryPlanner::set_ranging_blend(double blend) {
  // alpha = alpha_profile + blend w(E) (alpha_LD - alpha_profile) where alpha_LD is lower.
  // w ramps 0 -> 1 over ranging_ramp_fraction of the span below the planning energy (no alpha
  // step at the first ranging plan; later plans keep w = 1 there, continuing the flown alpha)
  // and back to 0 over the next-to-last such span before TAEM (0 over the last one), so the
  // TAEM alpha (and with it the TAEM Mach and q alpha) stays the mission's.
  const double span = entry_energy_ - taem_energy_;
  const double ramp = params_.ranging_ramp_fraction * span;
  for (int k = 0; k < kGrid; ++k) {
    const double w = (ranging_blend_min_ > 0.0 ? 1.0 : clamp((e0_ - e_[k]) / ramp, 0.0, 1.0)) *
                     clamp((e_[k] - taem_energy_ - ramp) / ramp, 0.0, 1.0);
    const double delta = alpha_ld_[k] - alpha_base_[k];
    alpha_[k] = alpha_base_[k] + (delta < 0.0 ? blend * w * delta : 0.0);
  }
  diag_.ranging_blend = blend;
}

// ------------------------------------------------------------------ plan
Status EntryPlanner::set_planning_state() {
  if (!finite_state(from_)) return Status::kNonFinite;
  // In-flight L/D estimate (1 before the drag is measurable): the corridor floor (7.7), the
  // equilibrium-glide radius and the bank extraction then use the vehicle's sensed L/D.
  const double lod_scale = from_.lift_over_drag_scale;
  if (!(lod_scale >= params_.lift_scale_min && lod_scale <= params_.lift_scale_max)) return Status::kInvalidInput;
  models_.aero().set_lift_scale(lod_scale);
  if (!(from_.energy_Jpkg > taem_energy_ * 1.001) || !(from_.radius_m > kEarthRadius_m)) return Status::kInvalidInput;

  // Mission geometry (7.1), (7.2) from the planning position to the TAEM point.
  const GreatCircle gc = great_circle(from_.latitude_rad, from_.longitude_rad, taem_lat_, taem_lon_);
  a_mission_ = gc.azimuth_rad;
  diag_.b_mission_rad = gc.arc_rad;
  diag_.a_mission_rad = gc.azimuth_rad;
  diag_.chi_minus_a_rad = wrap_pi(from_.heading_rad - a_mission_);
  // First bank side: the quadrant rule (fig. 7.20) at the first plan. A replan keeps the side
  // the last plan flies at the planning energy (reversal search tries the other side only
  // when no single reversal nulls the crossrange with it): the heading offset crosses zero
  // while the first bank turns the vehicle towards the target, and re-applying the rule there
  // reverses the bank for nothing (with a slow roll at high speed, a roll through wings level
  // of a minute or more and a phugoid).
  sign0_ = initial_bank_sign(from_.heading_rad, a_mission_);
  if (flown_side_known_ && from_.energy_Jpkg > e_corridor_) {
    sign0_ = from_.energy_Jpkg > flown_e_rev_ ? flown_sign0_ : -flown_sign0_;
  }
  diag_.initial_bank_sign = sign0_;
  r_mean_ = 0.5 * (from_.radius_m + taem_radius_);
  diag_.s_initial_m = gc.arc_rad * r_mean_;  // R_d, the first length S0 (7.22)
  return Status::kOk;
}

Status EntryPlanner::ranging_alpha(double range_desired, double d_actual, Status first, double& s_m, double& s_rev,
                                   bool& converged) {
  // Ranging alpha (thesis 6.3.1, ranging phase): the range needs less drag than the vehicle
  // can hold even wings level at the profile alpha (low L/D, a long way to go). alpha moves
  // towards alpha(L/D max) from the planning point to near TAEM; the smallest move that lifts
  // the floor below the needed drag is found by bisection on the blend (the full move when
  // even that is not enough: the longest range the vehicle can fly). The same move is made
  // when no single reversal can null the crossrange early in the flight (lateral_short: a
  // vehicle that needs too little bank for its range cannot turn). Once used, the blend never
  // decreases in later plans, so the alpha reference stays continuous from plan to plan.
  alpha_ld_max_on_grid();
  auto feasible = [&](double blend) {
    set_ranging_blend(blend);
    double s_trial = range_desired;
    bool conv_trial = false;
    if (prepare_corridor(d_actual) != Status::kOk) return false;
    return length_iteration(range_desired, s_trial, s_rev, conv_trial) == Status::kOk && !below_glide_floor() &&
           !lateral_short();
  };
  double lo = ranging_blend_min_, hi = 1.0;
  if (ranging_blend_min_ > 0.0 && feasible(ranging_blend_min_)) hi = lo;
  for (int i = 0; i < params_.ranging_bisections && hi - lo > params_.ranging_blend_tol; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (feasible(mid)) hi = mid;
    else lo = mid;
  }
  set_ranging_blend(hi);
  s_m = range_desired;
  Status s = prepare_corridor(d_actual);
  if (s == Status::kOk) s = length_iteration(range_desired, s_m, s_rev, converged);
  if (s != Status::kOk && first != Status::kOk) s = first;  // report the original failure
  return s;
}

Status EntryPlanner::plan(const RelativeState& from, ReferenceProfile& out) {
  diag_ = PlannerDiagnostics{};
  out.status = Status::kInvalidInput;
  out.converged = false;
  if (!initialised_) {
    out.n_points = 0;
    return Status::kInvalidInput;
  }
  from_ = from;
  if (!(from_.energy_Jpkg > 0.0)) from_.energy_Jpkg = specific_energy_Jpkg(from_.radius_m, from_.velocity_mps);
  auto fail = [&](Status s) {  // no partial profile is handed out on failure
    diag_.status = s;
    out.status = s;
    out.converged = false;
    out.n_points = 0;
    return s;
  };

  const Status state = set_planning_state();
  if (state != Status::kOk) return fail(state);
  const double range_desired = diag_.s_initial_m;  // R_d
  double s_m = range_desired;                      // S0

  const double alpha_from = alpha_profile_.alpha_rad(from_.energy_Jpkg / entry_energy_);
  const double d_actual = from_.drag_mps2 > 0.0
                              ? from_.drag_mps2
                              : models_.drag_mps2(alpha_from, from_.radius_m - kEarthRadius_m, from_.velocity_mps);
  Status s = build_grid(from_.energy_Jpkg, params_.initial_drag == InitialDrag::kActual && d_actual < params_.graded_grid_drag_mps2);
  if (s != Status::kOk) return fail(s);
  s = prepare_corridor(d_actual);
  if (s != Status::kOk) return fail(s);
  double s_rev = 0.0;
  bool converged = false;
  s = length_iteration(range_desired, s_m, s_rev, converged);
  const Status first = s;
  const bool lateral = lateral_short();
  if ((s == Status::kOk || lateral) && (ranging_blend_min_ > 0.0 || lateral || below_glide_floor())) {
    s = ranging_alpha(range_desired, d_actual, first, s_m, s_rev, converged);
  }
  const bool too_long = s == Status::kRangeTooLong;
  if (s != Status::kOk && !too_long) return fail(s);
  Rop end{};
  s = integrate(s_rev, true, end);
  if (s != Status::kOk) return fail(s);
  diag_.reversal_energy_Jpkg = e_rev_;
  diag_.converged = converged && !too_long;
  diag_.status = too_long ? Status::kRangeTooLong : (converged ? Status::kOk : Status::kNotConverged);
  fill_output(out);
  if (converged) ranging_blend_min_ = diag_.ranging_blend;
  if (diag_.status == Status::kOk || too_long) {  // the plans the tracker flies
    flown_side_known_ = true;
    flown_sign0_ = sign0_;
    flown_e_rev_ = e_rev_;
  }
  return diag_.status;
}

void EntryPlanner::fill_output(ReferenceProfile& out) {
  const int n = params_.rk4_steps;
  const double h = s_total_ / n;
  int saturated = 0;
  out.n_points = kGrid;
  for (int k = 0; k < kGrid; ++k) {
    const double energy = e_[k];
    double u = s_cum_[k] / h;
    int i = static_cast<int>(u);
    i = i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
    const double w = clamp(u - i, 0.0, 1.0);
    const double lat = track_[i].lat + w * (track_[i + 1].lat - track_[i].lat);
    const double chi = track_[i].chi + w * (track_[i + 1].chi - track_[i].chi);
    const int kk = k < kGrid - 1 ? k : kGrid - 2;
    const double wk = k < kGrid - 1 ? 0.0 : 1.0;
    double lod;
    const double lod_cos = bank_magnitude(kk, wk, lat, chi, lod);
    if (std::fabs(lod_cos) > lod) ++saturated;
    const double sigma_mag = std::acos(clamp(lod_cos / lod, -1.0, 1.0));
    double sigma;
    if (energy > e_rev_) sigma = sign0_ * sigma_mag;
    else if (energy > e_rev_ - de_rev_) sigma = sign0_ * sigma_rev0_ * (1.0 - 2.0 * (e_rev_ - energy) / de_rev_);
    else sigma = -sign0_ * sigma_mag;
    out.energy_Jpkg[k] = energy;
    out.e_norm[k] = energy / entry_energy_;
    out.drag_mps2[k] = d_[k];
    out.drag_prime[k] = dp_[k];
    out.drag_second[k] = dpp_[k];
    out.a_coef[k] = a0_[k] + kfac_[k] * coriolis_gamma(kEarthRate_radps, lat, chi, d_[k], v_[k]);
    out.b_coef[k] = b_[k];
    out.radius_m[k] = r_[k];
    out.velocity_mps[k] = v_[k];
    out.gamma_rad[k] = gamma_[k];
    out.alpha_rad[k] = alpha_[k];
    out.lift_over_drag[k] = lod_[k];
    out.sigma_rad[k] = sigma;
    out.heading_rad[k] = chi;
    out.dynamic_pressure_Pa[k] = q_[k];
    out.drag_max_mps2[k] = d_max_[k];
  }
  diag_.bank_saturated_points = saturated;
  out.reversal_energy_Jpkg = diag_.reversal_energy_Jpkg;
  out.initial_bank_sign = sign0_;
  out.entry_energy_Jpkg = entry_energy_;
  out.taem_energy_Jpkg = taem_energy_;
  out.taem_altitude_m = taem_drag_altitude_m_;
  out.dc_mps2 = diag_.dc_mps2;
  out.e1_Jpkg = diag_.e1_Jpkg;
  out.e2_Jpkg = diag_.e2_Jpkg;
  out.trajectory_length_m = diag_.s_final_m;
  out.ranging_blend = diag_.ranging_blend;
  out.crossrange_err_m = diag_.crossrange_err_m;
  out.downrange_err_m = diag_.downrange_err_m;
  out.iterations = diag_.iterations;
  out.status = diag_.status;
  out.converged = diag_.converged;
}

}  // namespace reentry::fsw
