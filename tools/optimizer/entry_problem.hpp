// The entry of one run as an optimal-control problem on the truth simulator's own models.
//
// State: the simulator's inertial position and velocity (r_I, v_I), controls: alpha and sigma,
// parameters: t_f and a margin s. The dynamics are truth::PointModel::evaluate_with, the function
// the simulator integrates (rotating oblate Earth, J2-J4 gravity, US76 with the run's density
// dispersion, the run's wind, the run's aero scales, mass and trim, the vehicle's heating
// model), with the aerodynamic coefficients from the C2 fits of the truth's own tables
// (smooth_models.hpp); the initial state is the simulator's entry state of that run. Nothing is
// modelled twice: a dispersion or a model change in the truth reaches the optimizer through
// truth::Simulator::create. point_on_tables() evaluates the same rows on the truth's tables.
//
// Constraints, as the referee (truth::judge_mission) judges a flight:
// - path, at every collocation point: heat flux, load factor (3.7), q and q alpha at most their
//   limits (normalised, value / limit <= 1 + s); altitude below the skip-out altitude;
// - controls: alpha in [alpha_min, alpha_max], |sigma| <= 180 deg, |d alpha/dt|, |d sigma/dt| at
//   most the mission's rate limits (between successive points);
// - terminal: the TAEM energy (7.8) reached at t_f (the event that ends a run), and the
//   interface bands, each normalised to its tolerance (<= 1 + s): range to the aim point
//   (chord of the R_eq sphere, smoothed within 1e-3 of the tolerance around zero), altitude,
//   Mach, flight-path angle, heading (sine of the error; its cosine kept positive).
// Modes: kMinMiss minimises the squared range to the aim point (in tolerances) with every other
// band and path constraint hard; kMaxMargin minimises s over all of them (s* <= 0: feasible,
// and -s* is the common margin, as a fraction of each limit or tolerance); the footprint modes
// maximise or minimise the final downrange / crossrange (along / across the arrival line, as
// truth::arrival_line_offset) with the heading free, the crossrange ones at a given downrange,
// the downrange ones on the arrival line (zero crossrange).
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "environment/interpolation.hpp"
#include "hermite_simpson.hpp"
#include "reentry/config/mission.hpp"
#include "smooth_models.hpp"

namespace reentry::optimal {

enum class EntryMode { kMinMiss, kMaxMargin, kMaxDownrange, kMinDownrange, kMaxCrossrange, kMinCrossrange };
const char* to_string(EntryMode m);

/// Rows of the path constraints (when the mission limits them).
/// Footprint modes only: kGlide, the flight-path angle at most kFootprintGlideMaxGamma_rad.
/// kAlphaProfile: alpha within a band of the mission's profile alpha(E/E_entry)
/// (kFootprintAlphaBand_rad in the footprint modes; optional in the others).
enum class PathRow { kHeatFlux, kLoadFactor, kDynamicPressure, kQAlpha, kSkipOut, kGlide, kAlphaProfile };

/// The footprint is that of gliding entries: a trajectory that climbs (skips) could carry the
/// vehicle further below the skip-out altitude, but no entry guidance flies one and the solver
/// wanders into them (X-33 max downrange: 16800 km after 1000 iterations, not converged). Two
/// degrees admit the climbs of a pull-out and of a bank reversal flown at the rate limit.
constexpr double kFootprintGlideMaxGamma_rad = 2.0 * M_PI / 180.0;
/// The footprint is the one the mission's guidance can reach: flying its angle-of-attack profile
/// (within the band the tracker's reversal modulation uses), the bank free within its limits.
/// With alpha free the solver seeks the vehicle's L/D max far from any flown profile and does
/// not converge in 1000 iterations (X-33: 13000 km beyond the aim point, still rising).
constexpr double kFootprintAlphaBand_rad = 3.0 * M_PI / 180.0;
/// kMaxMargin: weight of the squared miss (in range tolerances) added to the objective. Every
/// trajectory whose worst margin is the best one is optimal, the miss anywhere inside its band
/// above that margin; this picks the one nearest the aim point (the band the open-loop replay
/// tests hardest: its end lies tens to hundreds of metres from the collocated one). It lowers
/// the common margin by at most this weight.
constexpr double kMarginMissWeight = 0.01;
/// The alpha profile's corners are rounded (C2) by at most this much (SmoothPiecewiseLinear).
constexpr double kProfileCornerDeviation_rad = 0.1 * M_PI / 180.0;
/// Footprint modes keep every path limit 1 % below its value at the collocation points.
constexpr double kFootprintPathBackoff = 0.01;

class EntryProblem {
 public:
  static constexpr int kStates = 6;    // r_I [m], v_I [m/s]
  static constexpr int kControls = 2;  // alpha, sigma [rad]
  static constexpr int kParams = 2;    // t_f [s], margin s [-]

  /// `sim` is the run's simulator right after Simulator::create (its state is the entry state);
  /// it must outlive the problem. `downrange_m` is the fixed downrange of the crossrange modes.
  /// `alpha_band_rad` > 0 keeps alpha within that band of the mission's alpha profile in the
  /// margin and miss modes (the feasibility of a guidance that flies its profile and modulates
  /// alpha only that far); 0 leaves alpha free in [alpha_min, alpha_max]. The footprint modes
  /// always use kFootprintAlphaBand_rad.
  /// `extent_limit_m` (footprint modes): the extreme sought at most this far (crossrange right
  /// of the arrival line for kMaxCrossrange, left for kMinCrossrange, downrange beyond the aim
  /// for kMaxDownrange, short of it for kMinDownrange): a step of the footprint's homotopy.
  EntryProblem(const truth::Simulator& sim, EntryMode mode, double tf_guess_s, double downrange_m = 0.0,
               double alpha_band_rad = 0.0, double extent_limit_m = std::numeric_limits<double>::infinity());

  EntryMode mode() const { return mode_; }
  const truth::PointModel& model() const { return model_; }
  const config::Mission& mission() const { return mission_; }
  const std::vector<PathRow>& path_rows() const { return path_rows_; }

  // ---- Problem interface (hermite_simpson.hpp) ----------------------------------------------
  int n_path() const { return static_cast<int>(path_rows_.size()); }
  int n_terminal() const { return static_cast<int>(terminal_rows_.size()); }
  double t0() const { return 0.0; }
  /// With zonal gravity (central, J2-J4) the models are invariant under the Earth's rotation
  /// about its axis (shape, gravity, atmosphere and wind by altitude), so the point rows of a
  /// state in inertial coordinates do not depend on t; the sh20 field does.
  bool time_invariant() const { return model_.gravity->model() != truth::GravityModel::kSphericalHarmonics; }
  void initial_state(double* x) const;
  void state_bounds(double* lo, double* hi) const;
  void control_bounds(double* lo, double* hi) const;
  void param_bounds(double* lo, double* hi) const;
  void path_bounds(double* lo, double* hi) const;
  void path_param_coupling(double* a) const;
  void control_rate_limits(double* rate) const;
  void terminal_bounds(double* lo, double* hi) const;
  void state_scales(double* s) const;
  void defect_scales(double* s) const;
  void control_scales(double* s) const;
  void param_scales(double* s) const;
  void path_scales(double* s) const;
  void terminal_scales(double* s) const;
  double objective_scale() const { return 1.0; }

  template <class T>
  void point(const T& t, const T* x, const T* u, T* xdot, T* path) const;
  template <class T>
  void terminal(const T* x, const T* u, const T* p, T* psi) const;
  template <class T>
  T objective(const T* x, const T* u, const T* p) const;

  /// The same point rows with the truth's own aerodynamic tables (double: the reference of the
  /// model correction and of the fit checks).
  void point_on_tables(double t, const double* x, const double* u, double* xdot, double* path) const {
    point_with(TableAero{model_}, t, x, u, xdot, path);
  }

  /// The mission's alpha profile at normalised energy E/E_entry: the table (linear, held at its
  /// ends) with its corners rounded by at most kProfileCornerDeviation_rad (C2, smooth_models.hpp).
  template <class T>
  T profile_alpha(const T& e_norm) const {
    return profile_(e_norm);
  }
  const SmoothAero& smooth_aero() const { return aero_; }

  /// Final-point quantities the terminal rows and the objectives use.
  template <class T>
  struct Final {
    T energy, h, mach, gamma, heading_sin, heading_cos, chord2, along, cross;
  };
  template <class T>
  Final<T> final_quantities(const T& t, const T* x, const T* u) const;
  /// Footprint modes: the signed extent the objective maximises (m).
  template <class T>
  T extent(const Final<T>& f) const;

 private:
  enum class TermRow { kEnergy, kRange, kAltHigh, kAltLow, kMachHigh, kMachLow, kGammaHigh, kGammaLow, kHeadingPos,
                       kHeadingNeg, kHeadingCos, kDownrange, kCrossrange, kExtentLimit };
  template <class T, class AeroAt>
  void point_with(const AeroAt& aero_at, const T& t, const T* x, const T* u, T* xdot, T* path) const;
  /// The truth's own aerodynamic tables, as evaluate_with takes them.
  struct TableAero {
    const truth::PointModel& m;
    truth::AeroCoefficients operator()(double a, double mach, double q) const {
      return m.aero->coefficients(a, mach, q, m.trim, m.cl_scale, m.cd_scale);
    }
  };

  const truth::PointModel& model_;
  const config::Mission& mission_;
  SmoothAero aero_;
  SmoothPiecewiseLinear profile_;
  EntryMode mode_;
  double tf_guess_s_;
  double downrange_m_;
  double extent_limit_m_;
  double x0_[kStates] = {};
  double e_taem_ = 0.0;
  double skip_alt_m_ = 0.0;
  double chord_tol_ = 0.0;
  double sin_heading_tol_ = 1.0;
  double alpha_min_rad_ = 0.0;
  double aim_[3] = {}, line_dir_[3] = {}, line_right_[3] = {};  // aim point and arrival-line frame (R)
  double limit_[4] = {};
  bool footprint_ = false;
  double e_entry_ = 0.0;  // specific energy of the entry state (the alpha profile's scale)
  double alpha_band_rad_ = 0.0;  // kAlphaProfile row: alpha within this of the profile [rad]
  std::vector<PathRow> path_rows_;
  std::vector<TermRow> terminal_rows_;
};

// ---- templates ---------------------------------------------------------------------------------

template <class T>
void EntryProblem::point(const T& t, const T* x, const T* u, T* xdot, T* path) const {
  point_with(aero_, t, x, u, xdot, path);
}

template <class T, class AeroAt>
void EntryProblem::point_with(const AeroAt& aero_at, const T& t, const T* x, const T* u, T* xdot, T* path) const {
  const truth::scalar::Vec3<T> r(x[0], x[1], x[2]), v(x[3], x[4], x[5]);
  const truth::PointOutputs<T> o = model_.evaluate_with(aero_at, t, r, v, u[0], u[1], true);
  for (int i = 0; i < 3; ++i) {
    xdot[i] = x[3 + i];
    xdot[3 + i] = o.accel_I[i];
  }
  for (size_t k = 0; k < path_rows_.size(); ++k) {
    switch (path_rows_[k]) {
      case PathRow::kHeatFlux: path[k] = o.qdot / limit_[0]; break;
      case PathRow::kLoadFactor: path[k] = o.n_g / limit_[1]; break;
      case PathRow::kDynamicPressure: path[k] = o.q / limit_[2]; break;
      case PathRow::kQAlpha: path[k] = o.q * o.alpha / limit_[3]; break;
      case PathRow::kSkipOut: path[k] = o.h_m; break;
      case PathRow::kGlide: path[k] = o.gamma / kFootprintGlideMaxGamma_rad; break;
      case PathRow::kAlphaProfile: {
        const T e_norm = truth::PointModel::specific_energy(r, v) / e_entry_;
        path[k] = (u[0] - profile_alpha(e_norm)) / alpha_band_rad_;
        break;
      }
    }
  }
}

template <class T>
EntryProblem::Final<T> EntryProblem::final_quantities(const T& t, const T* x, const T* u) const {
  using std::cos;
  using std::sin;
  using std::atan2;
  using std::asin;
  const truth::scalar::Vec3<T> r(x[0], x[1], x[2]), v(x[3], x[4], x[5]);
  const truth::PointOutputs<T> o = model_.evaluate_with(aero_, t, r, v, u[0], u[1], true);
  Final<T> f;
  f.energy = truth::PointModel::specific_energy(r, v);
  f.h = o.h_m;
  f.mach = o.mach;
  f.gamma = o.gamma;
  const double hr = mission_.taem.heading_rad;
  f.heading_sin = sin(o.chi) * std::cos(hr) - cos(o.chi) * std::sin(hr);
  f.heading_cos = cos(o.chi) * std::cos(hr) + sin(o.chi) * std::sin(hr);
  // Geocentric direction of the final point in R (the referee's range uses geocentric latitude
  // on the R_eq sphere).
  const truth::scalar::Vec3<T> r_R = truth::rotation_I_to_R(t) * r;
  const T rn = r_R.norm();
  T n[3] = {r_R.x() / rn, r_R.y() / rn, r_R.z() / rn};
  f.chord2 = T(0.0);
  T nd = T(0.0), nr = T(0.0), na = T(0.0);
  for (int i = 0; i < 3; ++i) {
    const T c = n[i] - aim_[i];
    f.chord2 += c * c;
    nd += n[i] * line_dir_[i];
    nr += n[i] * line_right_[i];
    na += n[i] * aim_[i];
  }
  const double re = truth::EarthConstants::kEquatorialRadius_m;
  f.along = re * atan2(nd, na);
  f.cross = re * asin(nr);
  return f;
}

template <class T>
void EntryProblem::terminal(const T* x, const T* u, const T* p, T* psi) const {
  const Final<T> f = final_quantities(p[0], x, u);
  // The margin s relaxes every band in kMaxMargin (the only mode with a range row).
  const T s = mode_ == EntryMode::kMaxMargin ? p[1] : T(0.0);
  const config::TaemInterface& tm = mission_.taem;
  for (size_t k = 0; k < terminal_rows_.size(); ++k) {
    switch (terminal_rows_[k]) {
      case TermRow::kEnergy: psi[k] = f.energy - e_taem_; break;
      case TermRow::kRange: {  // |chord| / tol, smoothed at zero
        using std::sqrt;
        psi[k] = sqrt(f.chord2 + 1e-6 * chord_tol_ * chord_tol_) / chord_tol_ - s;
        break;
      }
      case TermRow::kAltHigh: psi[k] = (f.h - tm.altitude_m) / tm.altitude_tol_m - s; break;
      case TermRow::kAltLow: psi[k] = -(f.h - tm.altitude_m) / tm.altitude_tol_m - s; break;
      case TermRow::kMachHigh: psi[k] = (f.mach - tm.mach_target) / tm.mach_tol - s; break;
      case TermRow::kMachLow: psi[k] = -(f.mach - tm.mach_target) / tm.mach_tol - s; break;
      case TermRow::kGammaHigh: psi[k] = (f.gamma - tm.flight_path_rad) / tm.flight_path_tol_rad - s; break;
      case TermRow::kGammaLow: psi[k] = -(f.gamma - tm.flight_path_rad) / tm.flight_path_tol_rad - s; break;
      case TermRow::kHeadingPos: psi[k] = f.heading_sin / sin_heading_tol_ - s; break;
      case TermRow::kHeadingNeg: psi[k] = -f.heading_sin / sin_heading_tol_ - s; break;
      case TermRow::kHeadingCos: psi[k] = f.heading_cos; break;
      case TermRow::kDownrange: psi[k] = f.along; break;
      case TermRow::kCrossrange: psi[k] = f.cross; break;
      case TermRow::kExtentLimit: psi[k] = extent(f); break;
    }
  }
}

template <class T>
T EntryProblem::extent(const Final<T>& f) const {
  switch (mode_) {
    case EntryMode::kMaxDownrange: return f.along;
    case EntryMode::kMinDownrange: return -f.along;
    case EntryMode::kMaxCrossrange: return f.cross;
    case EntryMode::kMinCrossrange: return -f.cross;
    default: return T(0.0);
  }
}

template <class T>
T EntryProblem::objective(const T* x, const T* u, const T* p) const {
  switch (mode_) {
    case EntryMode::kMaxMargin:  // the miss centred as a secondary aim (its band is the one the replay tests hardest)
      return p[1] + kMarginMissWeight * final_quantities(p[0], x, u).chord2 / (chord_tol_ * chord_tol_);
    case EntryMode::kMinMiss: return final_quantities(p[0], x, u).chord2 / (chord_tol_ * chord_tol_);
    case EntryMode::kMaxDownrange: return -final_quantities(p[0], x, u).along / 1e6;
    case EntryMode::kMinDownrange: return final_quantities(p[0], x, u).along / 1e6;
    case EntryMode::kMaxCrossrange: return -final_quantities(p[0], x, u).cross / 1e5;
    case EntryMode::kMinCrossrange: return final_quantities(p[0], x, u).cross / 1e5;
  }
  return T(0.0);
}

}  // namespace reentry::optimal
