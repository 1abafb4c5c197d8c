#include "entry_problem.hpp"

#include <algorithm>

namespace reentry::optimal {

const char* to_string(EntryMode m) {
  switch (m) {
    case EntryMode::kMinMiss: return "min_miss";
    case EntryMode::kMaxMargin: return "max_margin";
    case EntryMode::kMaxDownrange: return "max_downrange";
    case EntryMode::kMinDownrange: return "min_downrange";
    case EntryMode::kMaxCrossrange: return "max_crossrange";
    case EntryMode::kMinCrossrange: return "min_crossrange";
  }
  return "unknown";
}

EntryProblem::EntryProblem(const truth::Simulator& sim, EntryMode mode, double tf_guess_s, double downrange_m,
                           double alpha_band_rad, double extent_limit_m)
    : model_(sim.point_model()),
      mission_(sim.mission()),
      aero_(sim.point_model()),
      profile_(sim.mission().alpha_profile.x, sim.mission().alpha_profile.y, kProfileCornerDeviation_rad),
      mode_(mode),
      tf_guess_s_(tf_guess_s),
      downrange_m_(downrange_m),
      extent_limit_m_(extent_limit_m) {
  const auto& y = sim.state();
  for (int i = 0; i < kStates; ++i) x0_[i] = y[static_cast<size_t>(i)];
  e_taem_ = sim.taem_energy_Jpkg();
  skip_alt_m_ = sim.settings().skip_out_altitude_m;
  const config::TaemInterface& tm = mission_.taem;
  const config::PathConstraints& c = mission_.constraints;
  const double re = truth::EarthConstants::kEquatorialRadius_m;
  chord_tol_ = 2.0 * std::sin(0.5 * tm.range_tol_m / re);
  const double alpha_table_min = mission_.vehicle.aero.cl.alpha_rad.empty() ? 0.0 : mission_.vehicle.aero.cl.alpha_rad.front();
  alpha_min_rad_ = std::max(0.0, alpha_table_min);

  // Aim point and the arrival line through it (R frame, geocentric latitude as the referee).
  const double la = tm.latitude_rad, lo = tm.longitude_rad, hd = tm.heading_rad;
  const double n_a[3] = {std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la)};
  const double e_n[3] = {-std::sin(la) * std::cos(lo), -std::sin(la) * std::sin(lo), std::cos(la)};
  const double e_e[3] = {-std::sin(lo), std::cos(lo), 0.0};
  for (int i = 0; i < 3; ++i) {
    aim_[i] = n_a[i];
    line_dir_[i] = std::cos(hd) * e_n[i] + std::sin(hd) * e_e[i];
    line_right_[i] = -std::sin(hd) * e_n[i] + std::cos(hd) * e_e[i];
  }

  limit_[0] = c.heat_flux_max_Wpm2;
  limit_[1] = c.load_factor_max_g;
  limit_[2] = c.dynamic_pressure_max_Pa;
  limit_[3] = c.q_alpha_max_Pa_rad;
  const PathRow rows[4] = {PathRow::kHeatFlux, PathRow::kLoadFactor, PathRow::kDynamicPressure, PathRow::kQAlpha};
  for (int k = 0; k < 4; ++k)
    if (std::isfinite(limit_[k]) && limit_[k] > 0.0) path_rows_.push_back(rows[k]);
  path_rows_.push_back(PathRow::kSkipOut);

  const bool footprint = mode == EntryMode::kMaxDownrange || mode == EntryMode::kMinDownrange ||
                         mode == EntryMode::kMaxCrossrange || mode == EntryMode::kMinCrossrange;
  footprint_ = footprint;
  if (footprint) path_rows_.push_back(PathRow::kGlide);
  {
    const truth::scalar::Vec3<double> r0(x0_[0], x0_[1], x0_[2]), v0(x0_[3], x0_[4], x0_[5]);
    e_entry_ = truth::PointModel::specific_energy(r0, v0);
  }
  alpha_band_rad_ = footprint ? kFootprintAlphaBand_rad : alpha_band_rad;
  if (alpha_band_rad_ > 0.0 && !mission_.alpha_profile.x.empty()) path_rows_.push_back(PathRow::kAlphaProfile);
  terminal_rows_.push_back(TermRow::kEnergy);
  if (mode == EntryMode::kMaxMargin) terminal_rows_.push_back(TermRow::kRange);
  terminal_rows_.push_back(TermRow::kAltHigh);
  terminal_rows_.push_back(TermRow::kAltLow);
  if (tm.mach_target > 0.0 && std::isfinite(tm.mach_tol)) {
    terminal_rows_.push_back(TermRow::kMachHigh);
    terminal_rows_.push_back(TermRow::kMachLow);
  }
  if (std::isfinite(tm.flight_path_tol_rad)) {
    terminal_rows_.push_back(TermRow::kGammaHigh);
    terminal_rows_.push_back(TermRow::kGammaLow);
  }
  if (!footprint && tm.heading_tol_rad > 0.0 && tm.heading_tol_rad < 0.5 * M_PI) {
    sin_heading_tol_ = std::sin(tm.heading_tol_rad);
    terminal_rows_.push_back(TermRow::kHeadingPos);
    terminal_rows_.push_back(TermRow::kHeadingNeg);
    terminal_rows_.push_back(TermRow::kHeadingCos);
  }
  if (mode == EntryMode::kMaxCrossrange || mode == EntryMode::kMinCrossrange) terminal_rows_.push_back(TermRow::kDownrange);
  if (mode == EntryMode::kMaxDownrange || mode == EntryMode::kMinDownrange) terminal_rows_.push_back(TermRow::kCrossrange);
  if (footprint && std::isfinite(extent_limit_m)) terminal_rows_.push_back(TermRow::kExtentLimit);
}

void EntryProblem::initial_state(double* x) const {
  for (int i = 0; i < kStates; ++i) x[i] = x0_[i];
}

void EntryProblem::state_bounds(double* lo, double* hi) const {
  for (int i = 0; i < kStates; ++i) {
    lo[i] = -std::numeric_limits<double>::infinity();
    hi[i] = std::numeric_limits<double>::infinity();
  }
}

void EntryProblem::control_bounds(double* lo, double* hi) const {
  lo[0] = alpha_min_rad_;
  hi[0] = mission_.constraints.alpha_max_rad;
  lo[1] = -M_PI;
  hi[1] = M_PI;
}

void EntryProblem::param_bounds(double* lo, double* hi) const {
  lo[0] = 0.2 * tf_guess_s_;
  hi[0] = 3.0 * tf_guess_s_;
  if (mode_ == EntryMode::kMaxMargin) {
    lo[1] = -1.0;
    hi[1] = 100.0;
  } else {
    lo[1] = hi[1] = 0.0;
  }
}

namespace {
/// A limit of the vehicle (heat flux, load, q, q alpha): backed off in the footprint modes and
/// relaxed by the margin. The skip-out altitude, the glide row and the alpha band are
/// restrictions of the trajectory sought, neither.
bool is_vehicle_limit(PathRow row) {
  return row != PathRow::kSkipOut && row != PathRow::kGlide && row != PathRow::kAlphaProfile;
}
}  // namespace

void EntryProblem::path_bounds(double* lo, double* hi) const {
  for (size_t k = 0; k < path_rows_.size(); ++k) {
    lo[k] = -std::numeric_limits<double>::infinity();
    // Footprint modes ride a path limit at the collocation points; the flight between them
    // (the open-loop replay that proves a point reached) overshoots it by a fraction of a
    // percent (HORUS heat flux), hence the back-off.
    hi[k] = path_rows_[k] == PathRow::kSkipOut
                ? skip_alt_m_
                : (is_vehicle_limit(path_rows_[k]) && footprint_ ? 1.0 - kFootprintPathBackoff : 1.0);
    if (path_rows_[k] == PathRow::kAlphaProfile) lo[k] = -1.0;
  }
}

void EntryProblem::path_param_coupling(double* a) const {
  for (size_t k = 0; k < path_rows_.size(); ++k) {
    a[k * kParams + 0] = 0.0;
    a[k * kParams + 1] = (mode_ == EntryMode::kMaxMargin && is_vehicle_limit(path_rows_[k])) ? -1.0 : 0.0;
  }
}

void EntryProblem::control_rate_limits(double* rate) const {
  const double inf = std::numeric_limits<double>::infinity();
  const auto& c = mission_.constraints;
  rate[0] = c.alpha_rate_max_radps > 0.0 ? c.alpha_rate_max_radps : inf;
  rate[1] = c.sigma_rate_max_radps > 0.0 ? c.sigma_rate_max_radps : inf;
}

void EntryProblem::terminal_bounds(double* lo, double* hi) const {
  const double inf = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < terminal_rows_.size(); ++k) {
    switch (terminal_rows_[k]) {
      case TermRow::kEnergy: lo[k] = hi[k] = 0.0; break;
      case TermRow::kHeadingCos: lo[k] = 0.0; hi[k] = inf; break;
      case TermRow::kDownrange: lo[k] = hi[k] = downrange_m_; break;
      case TermRow::kCrossrange: lo[k] = hi[k] = 0.0; break;
      case TermRow::kExtentLimit: lo[k] = -inf; hi[k] = extent_limit_m_; break;
      default: lo[k] = -inf; hi[k] = 1.0; break;
    }
  }
}

void EntryProblem::state_scales(double* s) const {
  for (int i = 0; i < 3; ++i) {
    s[i] = 1e6;
    s[3 + i] = 1e3;
  }
}

void EntryProblem::defect_scales(double* s) const {
  // A position defect of 1 m or a velocity defect of 1 mm/s counts like a limit exceeded by
  // 1e-3 of itself: the states are 1e6-sized, their defects must not look 1e6 times smaller.
  // (The energy row likewise: 1 J/kg, about 0.1 m of altitude, counts 1e-3.)
  const double position_m = 1e3, velocity_mps = 1.0;
  for (int i = 0; i < 3; ++i) {
    s[i] = position_m;
    s[3 + i] = velocity_mps;
  }
}

void EntryProblem::control_scales(double* s) const { s[0] = s[1] = 1.0; }

void EntryProblem::param_scales(double* s) const {
  s[0] = 1e3;
  s[1] = 1.0;
}

void EntryProblem::path_scales(double* s) const {
  for (size_t k = 0; k < path_rows_.size(); ++k) s[k] = path_rows_[k] == PathRow::kSkipOut ? 1e4 : 1.0;
}

void EntryProblem::terminal_scales(double* s) const {
  for (size_t k = 0; k < terminal_rows_.size(); ++k) {
    switch (terminal_rows_[k]) {
      case TermRow::kEnergy: s[k] = 1e3; break;
      case TermRow::kDownrange:
      case TermRow::kCrossrange:
      case TermRow::kExtentLimit: s[k] = 1e4; break;
      default: s[k] = 1.0; break;
    }
  }
}

}  // namespace reentry::optimal
