#include "planner/reduced_order.hpp"

#include <cmath>

#include "planner/drag_derivatives.hpp"
#include "planner/drag_profile.hpp"

namespace reentry::fsw {
namespace {

// Below |m ds| of this the energy of a flown range uses the first-order series of expm1 / m.
constexpr double kLinearCellLimit = 1e-12;
// Bisection steps of the range lookup: 2^16 cells, far above the grid.
constexpr int kRangeBisections = 16;
// Least reversal span: method 3 needs a positive span even for a zero bank magnitude.
constexpr double kMinReversalSpan_Jpkg = 1e-9;
// "No reversal": a reversal energy this far below TAEM is never reached.
constexpr double kNoReversalEnergyOffset_Jpkg = 1e12;
// Span (and zero bank) of a reversal whose start bank is not known yet: used while the run
// reaches the start (no point of it lies below the start energy by more than rounding) and
// for "no reversal".
constexpr double kUnsetReversalSpan_Jpkg = 1.0;

// Grid values interpolated at one flown range, shared by the RK4 stages evaluated there.
struct RangePoint {
  double energy = 0.0, r = 0.0, drag = 0.0, v = 0.0, cos_gamma = 0.0, tan_gamma = 0.0;
  double a0 = 0.0, kf = 0.0, b = 0.0, dpp = 0.0, lod = 0.0;
};

// Energy and grid cell of a flown range. The integration walks the cells in order, so the cell
// of the last lookup and its successor are tried before the bisection; the cell found is the
// same either way (s_cum_m strictly increasing), the hint only saves the search.
class RangeLookup {
 public:
  explicit RangeLookup(const ReducedOrderInput& sys) : sys_(sys) {}
  double energy_at(double s_m, int& k, double& w);

 private:
  const ReducedOrderInput& sys_;
  int hint_ = -1;
};

double RangeLookup::energy_at(double s_m, int& k, double& w) {
  const GridValues& s_cum = sys_.range.s_cum_m;
  const double s_total = sys_.range.s_total_m;
  const int h = hint_;
  if (s_m > 0.0 && s_m < s_total && h >= 0 && h + 1 < kPlannerGrid && s_cum[h] <= s_m && s_m < s_cum[h + 1]) {
    k = h;
  } else if (s_m > 0.0 && s_m < s_total && h >= 0 && h + 2 < kPlannerGrid && s_cum[h + 1] <= s_m && s_m < s_cum[h + 2]) {
    k = h + 1;
  } else {  // cell with s_cum[k] <= s_m < s_cum[k + 1], clamped to the first and last cells
    int lo = 0, hi = kPlannerGrid - 1;
    if (s_m <= 0.0) {
      hi = 1;
    } else if (s_m >= s_total) {
      lo = kPlannerGrid - 2;
    }
    for (int it = 0; it < kRangeBisections && hi - lo > 1; ++it) {
      const int mid = (lo + hi) / 2;
      if (s_cum[mid] <= s_m) lo = mid;
      else hi = mid;
    }
    k = lo;
  }
  hint_ = k;
  // Linear D in E within the cell: D(s) = D_k exp(-m (s - s_k)), E = E_k + (D - D_k) / m.
  const GridValues& e = sys_.energy_Jpkg;
  const GridValues& d = sys_.drag.drag_mps2;
  const double ds = s_m - s_cum[k];
  const double m = sys_.range.drag_slope[k];
  const double x = -m * ds;
  const double energy = std::fabs(x) < kLinearCellLimit ? e[k] - d[k] * ds : e[k] + d[k] * std::expm1(x) / m;
  w = clamp((e[k] - energy) / (e[k] - e[k + 1]), 0.0, 1.0);
  return energy;
}

// Grid values in cell k at weight w; the bank-extraction coefficients only with lift_terms.
RangePoint range_point_at(const ReducedOrderInput& sys, int k, double w, bool lift_terms) {
  const ExtractedTrajectory& t = sys.trajectory;
  const GridValues& r = sys.radius_m;
  const GridValues& d = sys.drag.drag_mps2;
  RangePoint p;
  p.r = r[k] + w * (r[k + 1] - r[k]);
  const double gamma = t.gamma_rad[k] + w * (t.gamma_rad[k + 1] - t.gamma_rad[k]);
  p.drag = d[k] + w * (d[k + 1] - d[k]);
  p.v = t.velocity_mps[k] + w * (t.velocity_mps[k + 1] - t.velocity_mps[k]);
  p.cos_gamma = std::cos(gamma);
  if (lift_terms) {
    const GridValues& dpp = sys.drag.drag_second;
    p.tan_gamma = std::tan(gamma);
    p.a0 = t.a_no_coriolis[k] + w * (t.a_no_coriolis[k + 1] - t.a_no_coriolis[k]);
    p.kf = t.density_gravity[k] + w * (t.density_gravity[k + 1] - t.density_gravity[k]);
    p.b = t.b[k] + w * (t.b[k + 1] - t.b[k]);
    p.dpp = dpp[k] + w * (dpp[k + 1] - dpp[k]);
    p.lod = t.lift_over_drag[k] + w * (t.lift_over_drag[k + 1] - t.lift_over_drag[k]);
  }
  return p;
}

RangePoint range_point(const ReducedOrderInput& sys, RangeLookup& lookup, double s_m) {
  int k;
  double w;
  const double energy = lookup.energy_at(s_m, k, w);
  // The lift and Coriolis terms are not needed in the corridor phase (see rop_derivative).
  RangePoint p = range_point_at(sys, k, w, energy >= sys.corridor_energy_Jpkg);
  p.energy = energy;
  return p;
}

// (L/D) cos(sigma) from D'' = a + b (L/D) cos(sigma) (7.17), a with C_gamma (7.18)-(7.19).
double vertical_lod(const RangePoint& p, double cos_lat, double sin_chi) {
  const double a = p.a0 + p.kf * coriolis_gamma_trig(kEarthRate_radps, cos_lat, sin_chi, p.drag, p.v);  // (7.18)-(7.19)
  return (p.dpp - a) / p.b;  // (7.17)
}

// (L/D) sin(sigma) with the sign of the reversal schedule, from |(L/D) sin(sigma)| (7.21).
double signed_lateral_lod(const ReversalModel& m, double energy, double lod_sin_abs, double lod) {
  switch (reversal_phase(m, energy)) {
    case ReversalPhase::kFirstSide: return m.first_sign * lod_sin_abs;
    case ReversalPhase::kReversing: return lod * std::sin(reversal_ramp_bank_rad(m, energy));
    case ReversalPhase::kSecondSide: break;
  }
  return -m.first_sign * lod_sin_abs;
}

void rop_derivative(const ReversalModel& rev, double corridor_energy, const RangePoint& p, const RopState& y, RopState& dy) {
  const double cg = p.cos_gamma, r = p.r, sd = std::sin(y.lat), cd = std::cos(y.lat);
  const double sc = std::sin(y.chi), cc = std::cos(y.chi);
  // (2.42)-(2.45) multiplied by dE/ds = -D.
  dy.lon = sc * cg / (r * cd);  // (2.42)
  dy.lat = cc * cg / r;         // (2.43)
  if (p.energy < corridor_energy) {
    // Lateral corridor phase: the tracker's heading corridor holds the vehicle on a great
    // circle and averages the lateral lift out, so the trajectory is that circle: (2.44)
    // without the lift and Coriolis terms.
    dy.chi = cg * (sd / cd) * sc / r;
    return;
  }
  const double drag = p.drag, v = p.v, lod = p.lod;
  const double lc = clamp(vertical_lod(p, cd, sc), -lod, lod);
  const double lod_sin_abs = std::sqrt(lod * lod - lc * lc);  // (7.21)
  const double lod_sin = signed_lateral_lod(rev, p.energy, lod_sin_abs, lod);
  const double c_chi = -2.0 * kEarthRate_radps * (sd - cd * p.tan_gamma * cc) / (drag * v);  // (2.45)
  dy.chi = drag * (lod_sin / (v * v * cg) - c_chi) + cg * (sd / cd) * sc / r;                 // (2.44)
}

void rk4(const ReducedOrderInput& sys, const ReversalModel& rev, RangeLookup& lookup, double s_m, const RopState& y,
         double h, RopState& out) {
  const double ec = sys.corridor_energy_Jpkg;
  RopState k1, k2, k3, k4, t;
  const RangePoint p_mid = range_point(sys, lookup, s_m + 0.5 * h);  // both midpoint stages
  rop_derivative(rev, ec, range_point(sys, lookup, s_m), y, k1);
  t = {y.lon + 0.5 * h * k1.lon, y.lat + 0.5 * h * k1.lat, y.chi + 0.5 * h * k1.chi};
  rop_derivative(rev, ec, p_mid, t, k2);
  t = {y.lon + 0.5 * h * k2.lon, y.lat + 0.5 * h * k2.lat, y.chi + 0.5 * h * k2.chi};
  rop_derivative(rev, ec, p_mid, t, k3);
  t = {y.lon + h * k3.lon, y.lat + h * k3.lat, y.chi + h * k3.chi};
  rop_derivative(rev, ec, range_point(sys, lookup, s_m + h), t, k4);
  out.lon = y.lon + h / 6.0 * (k1.lon + 2.0 * k2.lon + 2.0 * k3.lon + k4.lon);
  out.lat = y.lat + h / 6.0 * (k1.lat + 2.0 * k2.lat + 2.0 * k3.lat + k4.lat);
  out.chi = y.chi + h / 6.0 * (k1.chi + 2.0 * k2.chi + 2.0 * k3.chi + k4.chi);
}

Status finite_end(const RopState& y) {
  return std::isfinite(y.lon + y.lat + y.chi) ? Status::kOk : Status::kNonFinite;
}

Status fly_without_reversal(const ReducedOrderInput& sys, const RopState& start, int first_sign, RopTrack& base,
                            RopTrack* track, RopFlight& out) {
  const int n = sys.rk4_steps;
  const double h = sys.range.s_total_m / n;
  out.reversal = ReversalModel{first_sign, sys.taem_energy_Jpkg - kNoReversalEnergyOffset_Jpkg, kUnsetReversalSpan_Jpkg, 0.0};
  RangeLookup lookup(sys);
  base[0] = start;
  for (int i = 0; i < n; ++i) rk4(sys, out.reversal, lookup, i * h, base[i], h, base[i + 1]);
  out.end = base[n];
  if (track) {
    for (int i = 0; i <= n; ++i) (*track)[i] = base[i];
  }
  return finite_end(out.end);
}

Status fly_with_reversal(const ReducedOrderInput& sys, const RopTrack& base, int first_sign, double s_rev,
                         RopTrack* track, RopFlight& out) {
  const int n = sys.rk4_steps;
  const double h = sys.range.s_total_m / n;
  if (s_rev < 0.0) s_rev = 0.0;
  int j = static_cast<int>(s_rev / h);
  j = j < 0 ? 0 : (j > n - 1 ? n - 1 : j);
  if (track) {
    for (int i = 0; i <= j; ++i) (*track)[i] = base[i];
  }
  RangeLookup lookup(sys);
  int k;
  double w;
  // Up to the reversal start: the first side (no ramp yet, its bank still unknown).
  out.reversal = ReversalModel{first_sign, lookup.energy_at(s_rev, k, w), kUnsetReversalSpan_Jpkg, 0.0};
  RopState y = base[j];
  const double h_part = s_rev - j * h;  // >= 0
  if (h_part > 0.0) rk4(sys, out.reversal, lookup, j * h, y, h_part, y);
  // Reversal start: bank magnitude and D V at E_rev give the span of method 3.
  double lod;
  const double lod_cos = vertical_lift_over_drag(sys, k, w, y.lat, y.chi, lod);
  out.reversal.bank_start_rad = bank_magnitude_rad(lod_cos, lod);
  const GridValues& d = sys.drag.drag_mps2;
  const GridValues& v = sys.trajectory.velocity_mps;
  out.reversal.span_Jpkg = reversal_energy_span_Jpkg(out.reversal.bank_start_rad, sys.sigma_rate_max_radps,
                                                     d[k] + w * (d[k + 1] - d[k]), v[k] + w * (v[k + 1] - v[k]));
  if (h - h_part > 0.0) rk4(sys, out.reversal, lookup, s_rev, y, h - h_part, y);
  if (track) (*track)[j + 1] = y;
  for (int i = j + 1; i < n; ++i) {
    rk4(sys, out.reversal, lookup, i * h, y, h, y);
    if (track) (*track)[i + 1] = y;
  }
  out.end = y;
  return finite_end(y);
}

}  // namespace

void build_range_table(const GridValues& e, const GridValues& d, RangeTable& out) {
  out.s_cum_m[0] = 0.0;
  for (int k = 0; k + 1 < kPlannerGrid; ++k) {
    out.drag_slope[k] = (d[k + 1] - d[k]) / (e[k + 1] - e[k]);
    out.s_cum_m[k + 1] = out.s_cum_m[k] + linear_segment_length(e[k] - e[k + 1], d[k], d[k + 1]);  // (7.10), (C.9)
  }
  out.drag_slope[kPlannerGrid - 1] = out.drag_slope[kPlannerGrid - 2];
  out.s_total_m = out.s_cum_m[kPlannerGrid - 1];
}

ReversalPhase reversal_phase(const ReversalModel& m, double energy_Jpkg) {
  if (energy_Jpkg > m.energy_Jpkg) return ReversalPhase::kFirstSide;
  if (energy_Jpkg > m.energy_Jpkg - m.span_Jpkg) return ReversalPhase::kReversing;
  return ReversalPhase::kSecondSide;
}

double reversal_ramp_bank_rad(const ReversalModel& m, double energy_Jpkg) {
  return m.first_sign * m.bank_start_rad * (1.0 - 2.0 * (m.energy_Jpkg - energy_Jpkg) / m.span_Jpkg);  // §7.4 method 3
}

double scheduled_bank_rad(const ReversalModel& m, double energy_Jpkg, double bank_magnitude_rad) {
  switch (reversal_phase(m, energy_Jpkg)) {
    case ReversalPhase::kFirstSide: return m.first_sign * bank_magnitude_rad;
    case ReversalPhase::kReversing: return reversal_ramp_bank_rad(m, energy_Jpkg);
    case ReversalPhase::kSecondSide: break;
  }
  return -m.first_sign * bank_magnitude_rad;
}

double reversal_energy_span_Jpkg(double bank_start_rad, double bank_rate_max_radps, double drag_mps2, double velocity_mps) {
  const double span = 2.0 * bank_start_rad / bank_rate_max_radps * drag_mps2 * velocity_mps;  // §7.4 method 3
  return span > kMinReversalSpan_Jpkg ? span : kMinReversalSpan_Jpkg;
}

double bank_magnitude_rad(double lod_cos, double lod) { return std::acos(clamp(lod_cos / lod, -1.0, 1.0)); }

double vertical_lift_over_drag(const ReducedOrderInput& sys, int k, double w, double lat_rad, double chi_rad,
                               double& lift_over_drag) {
  const RangePoint p = range_point_at(sys, k, w, true);
  lift_over_drag = p.lod;
  return vertical_lod(p, std::cos(lat_rad), std::sin(chi_rad));
}

Status fly_reduced_order(const ReducedOrderInput& sys, const RopState& start, int first_sign, double s_rev_m,
                         RopTrack& base, RopTrack* track, RopFlight& out) {
  if (s_rev_m >= sys.range.s_total_m) return fly_without_reversal(sys, start, first_sign, base, track, out);
  return fly_with_reversal(sys, base, first_sign, s_rev_m, track, out);
}

}  // namespace reentry::fsw
