// Angle-of-attack planning (thesis ch. 6, appendix B.1).
//
// 2D entry corridor in the height-velocity plane: the upper boundary is the equilibrium glide
// (6.6) at alpha(CL max) (searched per Mach within [0, alpha_max], thesis 6.1.2 for X-33); the
// lower boundary is the highest of the equilibrium glide at alpha(L/D max) and the minimum
// heights of the heat flux (6.2), g-load (6.7), q*alpha (6.8) and dynamic pressure (6.5)
// constraints. All heights are found by bracketed root finding on the height with the on-board
// models (exponential or tabulated atmosphere, 6.1.3). A path h(V) is shaped by the heating /
// ranging / TAEM-matching parameters of 6.3.1, alpha(V) is extracted from the equilibrium glide
// (6.6), smoothed monotonically and mapped to normalised energy E/E_entry with E from (7.8).
//
// Flight-code style: fixed-capacity arrays, no heap, no exceptions, bounded loops, Status codes.
#pragma once

#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"

namespace reentry::fsw {

/// Shaping parameters of thesis 6.3.1, all in percent [0, 100].
/// Default choice (documented, checked on all four missions by the tests): heating 30 %,
/// ranging 50 %, heating->ranging switch at the intersection velocity (0 %), ranging->TAEM
/// switch at 80 % of [V_intersection, V_taem + dV]. The TAEM-matching phase is a ramp: the
/// path height blends linearly in V from the ranging path at the switch to the alpha(L/D max)
/// glide at V_taem + dV ((6.12) gives the least dV the alpha rate allows; an alpha step there
/// outruns the rate limit and leaves the vehicle high at TAEM). The campaign behind the 80 %
/// switch is in docs/guidance_design.md (alpha planning).
struct AlphaPlanParams {
  double heating_pct = 30.0;         // heating phase: 0 % = lower boundary (heat flux), 100 % = alpha(CL max) glide
  double ranging_pct = 50.0;         // ranging phase: alpha = alpha(L/D max) + pct (alpha(CL max) - alpha(L/D max))
  double heating_switch_pct = 0.0;   // heating->ranging switch on [V_intersection (0 %), V_taem + dV (100 %)]
  double taem_switch_pct = 80.0;     // start of the ranging->alpha(L/D max) ramp on the same range; >= heating_switch_pct
};

enum class AlphaPhase : int { kHeating = 0, kRanging = 1, kTaem = 2 };

/// One velocity node of the corridor and of the planned path. Heights in m above R_eq.
/// A constraint that is not set (infinite limit) or never violated in [kMinHeight, kMaxHeight]
/// gives kMinHeight.
struct AlphaCorridorPoint {
  double velocity_mps = 0.0;
  double alpha_cl_max_rad = 0.0;       // at the Mach of the alpha(CL max) glide
  double alpha_ld_max_rad = 0.0;       // at the Mach of the alpha(L/D max) glide
  double h_glide_cl_max_m = 0.0;       // upper boundary (6.6)
  double h_glide_ld_max_m = 0.0;       // (6.6) at alpha(L/D max)
  double h_heat_flux_m = 0.0;          // (6.2)
  double h_load_factor_cl_max_m = 0.0; // (6.7) at alpha(CL max) (for plotting, thesis fig. 6.1)
  double h_load_factor_ld_max_m = 0.0; // (6.7) at alpha(L/D max)
  double h_q_alpha_cl_max_m = 0.0;     // (6.8) at alpha(CL max) (for plotting)
  double h_q_alpha_ld_max_m = 0.0;     // (6.8) at alpha(L/D max)
  double h_dynamic_pressure_m = 0.0;   // (6.5)
  // Lower boundary (thesis 6.1.1 conclusion): highest of the alpha(L/D max) glide and the
  // constraint heights, the alpha-dependent ones evaluated at alpha(L/D max). The planned path is
  // afterwards checked against all constraints at the alpha it actually flies (path_violation).
  double h_lower_m = 0.0;
  bool closed = false;                 // h_lower_m > h_glide_cl_max_m
  AlphaPhase phase = AlphaPhase::kHeating;
  double h_path_m = 0.0;               // planned h(V), clipped into the corridor (upper bound when closed)
  double alpha_extracted_rad = 0.0;    // alpha giving equilibrium glide (6.6) at (h_path, V)
  bool extraction_clamped = false;     // CL needed outside [CL(alpha_LD), CL(alpha_CLmax)]: alpha clamped
  double alpha_rad = 0.0;              // after monotonic smoothing and clamping into [alpha_LD, alpha_CLmax]
  double energy_norm = 0.0;            // E(h_path, V) / E_entry, E from (7.8)
  double path_heat_flux_Wpm2 = 0.0;    // constraint values at (h_path, V, alpha_rad)
  double path_load_factor_g = 0.0;
  double path_q_alpha_Pa_rad = 0.0;
  double path_dynamic_pressure_Pa = 0.0;
  bool path_violation = false;         // any of them above its limit (relative margin 1e-6)
};

struct AlphaPlanResult {
  static constexpr int kGridPoints = 100;
  static constexpr int kProfileCapacity = 64;

  AlphaCorridorPoint corridor[kGridPoints];   // index 0 = entry velocity, last = TAEM velocity
  int n_corridor = 0;
  int closed_points = 0;
  int clamped_points = 0;
  int violation_points = 0;            // planned points violating a path constraint

  // Profile that can replace mission.alpha_profile: x = E/E_entry strictly increasing.
  double profile_energy_norm[kProfileCapacity] = {};
  double profile_alpha_rad[kProfileCapacity] = {};
  int n_profile = 0;

  double v_intersection_mps = 0.0;   // end of heat-flux dominance (entry velocity if never dominant)
  double v_heating_switch_mps = 0.0;
  double v_taem_switch_mps = 0.0;
  double dv_taem_mps = 0.0;          // (6.12)
  double alpha_entry_rad = 0.0;
  double alpha_taem_rad = 0.0;
  double alpha_min_rad = 0.0;
  double alpha_max_rad = 0.0;
};

class AlphaPlanner {
 public:
  static constexpr double kMinHeight_m = 0.0;
  static constexpr double kMaxHeight_m = 150000.0;
  static constexpr int kAlphaScanPoints = 241;

  /// The models are copied.
  Status init(const OnboardModels& models, const GuidanceMission& mission);
  Status plan(const AlphaPlanParams& params, AlphaPlanResult& out) const;

  // ---- building blocks (public for tests and tools) --------------------------------------
  /// alpha in [0, alpha_max] of maximum CL (and of maximum CL/CD) at a Mach number:
  /// scan plus golden-section refinement.
  double alpha_cl_max_rad(double mach) const;
  double alpha_ld_max_rad(double mach) const;
  /// alpha law along a path: alpha(M) = alpha_LD(M) + blend (alpha_CL(M) - alpha_LD(M)),
  /// or a fixed alpha when fixed_alpha_rad >= 0.
  struct AlphaLaw {
    double blend = 1.0;
    double fixed_alpha_rad = -1.0;
  };
  double alpha_of(const AlphaLaw& law, double mach) const;

  Status glide_height(double velocity_mps, const AlphaLaw& law, double& h_m) const;        // (6.6)
  /// law: the alpha where the heat flux depends on it (leading-edge model); the corridor uses
  /// the alpha(L/D max) law, as for its other lower-boundary constraints.
  Status heat_flux_height(double velocity_mps, const AlphaLaw& law, double& h_m) const;      // (6.2)
  Status load_factor_height(double velocity_mps, const AlphaLaw& law, double& h_m) const;   // (6.7)
  Status q_alpha_height(double velocity_mps, const AlphaLaw& law, double& h_m) const;       // (6.8)
  Status dynamic_pressure_height(double velocity_mps, double& h_m) const;                   // (6.5)
  /// alpha with CL(alpha, M) = CL needed for equilibrium glide (6.6) at (h, V), searched on
  /// [alpha_LD(M), alpha_CL(M)]; clamped (and flagged) when the need is outside that range.
  Status extract_alpha(double altitude_m, double velocity_mps, double& alpha_rad, bool& clamped) const;

  const OnboardModels& models() const { return models_; }
  double entry_energy_Jpkg() const { return entry_energy_Jpkg_; }

 private:
  template <class F>
  Status min_height(F&& excess, double& h_m) const;
  // The steps of plan().
  Status build_corridor(const AlphaLaw& law_ranging, double* h_ranging_m, AlphaPlanResult& out) const;
  void phase_switch_velocities(const AlphaPlanParams& params, const AlphaLaw& law_ranging, AlphaPlanResult& out) const;
  Status extract_path_alpha(const AlphaPlanParams& params, const double* h_ranging_m, AlphaPlanResult& out) const;
  void smooth_alpha_monotonic(AlphaPlanResult& out) const;
  void evaluate_path(AlphaPlanResult& out) const;
  Status sample_profile(AlphaPlanResult& out) const;

  OnboardModels models_;
  double alpha_max_rad_ = 0.0;
  double alpha_rate_max_radps_ = 0.0;
  double v_entry_mps_ = 0.0;
  double h_entry_m_ = 0.0;
  double v_taem_mps_ = 0.0;
  double entry_energy_Jpkg_ = 0.0;
  double heat_flux_max_Wpm2_ = 0.0;
  double load_factor_max_g_ = 0.0;
  double q_alpha_max_Pa_rad_ = 0.0;
  double dynamic_pressure_max_Pa_ = 0.0;
  bool initialised_ = false;
};

}  // namespace reentry::fsw
