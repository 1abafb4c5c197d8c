// Entry planner after thesis ch. 7 (Mease et al. 2002 / Saraf et al. 2003):
//   1. drag-energy corridor (7.3)-(7.7) from alpha(E) and an equilibrium-glide h(E);
//   2. drag profile fitting a trajectory length S (three segments (7.11)-(7.12) or smooth);
//   3. extraction of r(E) (7.13), gamma(E) (7.14) and bank magnitude (7.17)-(7.20);
//   4. bank reversal search on the reduced-order system (2.42)-(2.45), method 3 of §7.4;
//   5. length update (7.22) until the downrange matches;
//   6. ranging alpha (ch. 6 ranging phase): when the range needs less drag than the
//      wings-level glide floor (L/D too low for the distance), alpha is moved towards
//      alpha(L/D max) by the smallest blend that restores feasibility, never decreasing in flight.
// Replans take the in-flight L/D estimate (RelativeState::lift_over_drag_scale) as a C_L scale.
// Fixed capacity, no heap after init(), bounded loops, every failure returned as a Status.
#pragma once

#include "guidance_params.hpp"
#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "planner/drag_profile.hpp"
#include "planner/planner_params.hpp"

namespace reentry::fsw {

struct PlannerDiagnostics {
  Status status = Status::kInvalidInput;
  bool converged = false;
  int iterations = 0;
  int reversal_evaluations = 0;
  double dc_mps2 = 0.0;
  double di_mps2 = 0.0;
  double df_mps2 = 0.0;
  double e1_Jpkg = 0.0;
  double e2_Jpkg = 0.0;
  double s_initial_m = 0.0;
  double s_final_m = 0.0;
  double crossrange_err_m = 0.0;
  double downrange_err_m = 0.0;
  double b_mission_rad = 0.0;
  double a_mission_rad = 0.0;
  double chi_minus_a_rad = 0.0;
  double reversal_energy_Jpkg = 0.0;
  int initial_bank_sign = 1;
  int corridor_closed_points = 0;  // grid points where max drag <= Lmin
  int clipped_points = 0;          // drag points set to the active max constraint
  int bank_saturated_points = 0;   // |D'' - a| / b exceeded L/D
  double ranging_blend = 0.0;      // alpha moved this fraction towards alpha(L/D max) (ranging)
  bool reversal_best_effort = false;  // no reversal nulls the crossrange: smallest one planned
};

class EntryPlanner {
 public:
  static constexpr int kGrid = kProfileCapacity;    // energy grid points
  static constexpr int kMaxRkSteps = PlannerParams::kMaxRkSteps;

  /// The models and the alpha profile are copied; the planner's tunables are params.planner.
  Status init(const OnboardModels& models, const AlphaProfile& alpha_profile, const GuidanceMission& mission,
              const GuidanceLawParams& params);
  /// Plan from a state (entry or in flight). No allocation. out.status mirrors the result.
  Status plan(const RelativeState& from, ReferenceProfile& out);
  const PlannerDiagnostics& diagnostics() const { return diag_; }
  const OnboardModels& models() const { return models_; }
  /// Options that a mission selects; may be overridden before plan() (tools, tests).
  void set_profile_kind(DragProfileKind k) { params_.drag_profile = k; }
  void set_initial_drag(InitialDrag d) { params_.initial_drag = d; }
  DragProfileKind profile_kind() const { return params_.drag_profile; }
  const PlannerParams& params() const { return params_; }
  double entry_energy_Jpkg() const { return entry_energy_; }
  double taem_energy_Jpkg() const { return taem_energy_; }
  /// RelativeState at the mission entry interface, drag from the on-board models.
  RelativeState entry_state() const;
  /// Active maximum-drag and minimum-drag (Lmin (7.7), rotation-free) corridor of the last plan, on the grid.
  double corridor_max(int k) const { return d_max_[k]; }
  double corridor_min(int k) const { return d_min_[k]; }
  /// Lmin with the Earth-rate term of (2.45): the floor the closure test uses.
  double corridor_floor(int k) const { return d_floor_[k]; }
  double grid_energy(int k) const { return e_[k]; }

 private:
  struct Rop { double lon, lat, chi; };   // reduced-order state (2.42)-(2.44)

  Status set_planning_state();
  Status ranging_alpha(double range_desired, double d_actual, Status first, double& s_m, double& s_rev, bool& converged);
  Status build_grid(double e0, bool graded);
  Status prepare_corridor(double d_actual);
  Status length_iteration(double range_desired, double& s_m, double& s_rev, bool& converged);
  bool below_glide_floor() const;
  bool lateral_short() const;
  void alpha_ld_max_on_grid();
  void set_ranging_blend(double blend);
  Status equilibrium_glide_radius();
  void corridor();
  void breakpoints();
  Status fit_profile(double s_m);
  Status extract();
  void build_range_table();
  double energy_at_range(double s_m, int& k, double& w) const;
  // The range-dependent part of the reduced-order derivative: grid values interpolated at
  // one flown range, shared by the RK4 stages evaluated there (the two midpoint stages).
  struct RangePoint {
    double energy = 0.0, r = 0.0, drag = 0.0, v = 0.0, cos_gamma = 0.0, tan_gamma = 0.0;
    double a0 = 0.0, kf = 0.0, b = 0.0, dpp = 0.0, lod = 0.0;
  };
  RangePoint range_point(double s_m) const;
  /// Grid values in cell k at weight w; the bank-extraction coefficients only with lift_terms.
  RangePoint range_point_at(int k, double w, bool lift_terms) const;
  /// (L/D) cos(sigma) from D'' = a + b (L/D) cos(sigma) (7.17)-(7.19) at a range point.
  double vertical_lod(const RangePoint& p, double cos_lat, double sin_chi) const;
  void rop_derivative(const RangePoint& p, const Rop& y, Rop& dy) const;
  double bank_magnitude(int k, double w, double lat, double chi, double& lod) const;
  void rk4(double s_m, const Rop& y, double h, Rop& out) const;
  Status integrate(double s_rev, bool store, Rop& final_state);
  Status reversal_search(double& e_rev, double& crossrange_rad, double& downrange_rad);
  void fill_output(ReferenceProfile& out);
  double sigma_sign_schedule(double energy, double lod_sin_abs, double lod) const;

  OnboardModels models_;
  AlphaProfile alpha_profile_;
  double taem_box_altitude(const TaemTarget& taem) const;
  PlannerParams params_;
  double terminal_span_fraction_ = 0.25;

  // mission data
  RelativeState entry_{};
  double entry_energy_ = 0.0;
  double taem_energy_ = 0.0;
  double taem_drag_altitude_m_ = 0.0;  // altitude of the planned final drag
  double e_corridor_ = 0.0;            // below this energy the trajectory is a great circle
  double taem_radius_ = 0.0, taem_velocity_ = 0.0, taem_lat_ = 0.0, taem_lon_ = 0.0;
  double heat_max_ = 0.0, q_alpha_max_ = 0.0, n_max_ = 0.0, q_max_ = 0.0;
  double alpha_max_ = 0.0;
  bool lateral_unreachable_ = false;  // reversal search: no bracket, best effort beyond its limit
  bool level_at_max_ = false;         // fit: the length is below the shortest profile's (maximum level)
  mutable int range_hint_ = -1;       // last cell of energy_at_range (search hint only)
  double ranging_blend_min_ = 0.0;  // blend of the last converged plan (never decreases in flight)
  // Bank side of the last plan handed out (first sign and reversal energy): a replan keeps the
  // side being flown (see plan()).
  bool flown_side_known_ = false;
  int flown_sign0_ = 1;
  double flown_e_rev_ = 0.0;
  double sigma_rate_max_ = 0.0;
  bool initialised_ = false;

  // per-plan state
  RelativeState from_{};
  double e0_ = 0.0, r_mean_ = 0.0;
  double a_mission_ = 0.0;
  int sign0_ = 1;
  ThreeSegmentProfile three_{};
  SmoothProfile smooth_{};
  // reversal modelling (method 3): start energy, span, bank at start
  double e_rev_ = 0.0, de_rev_ = 0.0, sigma_rev0_ = 0.0;

  // grid arrays (index 0 = planning energy, kGrid-1 = TAEM)
  double e_[kGrid] = {};
  double alpha_[kGrid] = {};
  double alpha_base_[kGrid] = {};   // the mission alpha profile on the grid
  double alpha_ld_[kGrid] = {};     // alpha(L/D max) at the grid's equilibrium-glide Mach
  double r_[kGrid] = {};
  double v_[kGrid] = {};
  double d_min_[kGrid] = {};
  double d_floor_[kGrid] = {};  // Lmin with the Earth-rate term: the closure test
  double d_max_[kGrid] = {};
  double d_heat_[kGrid] = {};
  double d_qalpha_[kGrid] = {};
  double d_[kGrid] = {};
  double dp_[kGrid] = {};
  double dpp_[kGrid] = {};
  double cd_[kGrid] = {};
  double gamma_[kGrid] = {};
  double lod_[kGrid] = {};
  double a0_[kGrid] = {};
  double kfac_[kGrid] = {};
  double b_[kGrid] = {};
  double q_[kGrid] = {};
  double s_cum_[kGrid] = {};      // -int dE / D from the planning energy (linear D per cell)
  double d_slope_[kGrid] = {};    // dD/dE of the linear interpolant in each cell
  double s_total_ = 0.0;
  // reduced-order states at the RK4 step boundaries (uniform in flown range)
  Rop base_[kMaxRkSteps + 1] = {};
  Rop track_[kMaxRkSteps + 1] = {};

  PlannerDiagnostics diag_{};
};

}  // namespace reentry::fsw
