// Stage 1 of the entry planner: the drag-energy corridor (thesis §7.1, appendix B.2), the
// breakpoints E1, E2 of the profile (§7.2) and its end drags Di, Df (§7.6).
//   h(E):  zero-bank equilibrium glide L = g - V^2/r (2.50) at the grid's alpha;
//   upper: active path-constraint drag, the least of (7.3)-(7.6);
//   lower: Lmin CD/CL (7.7), and the floor with the Earth-rate term of (2.33) for the closure test.
#pragma once

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"
#include "planner/planner_grid.hpp"
#include "planner/planner_params.hpp"

namespace reentry::fsw {

// ---- constraint drags at one point (each a single formula)
/// (7.3): heat flux q = C sqrt(rho) V^c2 at its limit, D = q_max^2 CD S / (2 m C^2 V^(2(c2-1))).
double heat_flux_drag_mps2(double heat_flux_max_Wpm2, double cd, double area_over_mass_m2pkg,
                           double heat_coefficient, double velocity_mps, double velocity_exponent);
/// (7.4): D = (q alpha)_max CD S / (m alpha); unbounded at (near) zero alpha.
double q_alpha_drag_mps2(double q_alpha_max_Pa_rad, double cd, double area_over_mass_m2pkg, double alpha_rad);
/// (7.5): D = n_max g / (CL/CD cos(alpha) + sin(alpha)).
double load_factor_drag_mps2(double load_max_mps2, double cl, double cd, double alpha_rad);
/// (7.6): D = q_max CD S / m.
double dynamic_pressure_drag_mps2(double dynamic_pressure_max_Pa, double cd, double area_over_mass_m2pkg);
/// (7.7) / (B.14): the drag of a vertical lift need, D = L_need CD / CL.
double lift_need_drag_mps2(double lift_need_mps2, double cl, double cd);

/// The four constraint drags of (7.3)-(7.6) at one point.
struct ConstraintDrags {
  double heat_flux_mps2 = 0.0;
  double q_alpha_mps2 = 0.0;
  double load_mps2 = 0.0;
  double dynamic_pressure_mps2 = 0.0;
};
/// The active (least) maximum-drag constraint; a non-positive load limit (lift and drag
/// cancelling in the body axis) does not bound.
double active_drag_limit_mps2(const ConstraintDrags& c);

// ---- the corridor on the grid
struct DragCorridor {
  GridValues heat_flux_mps2{};  // (7.3)
  GridValues q_alpha_mps2{};    // (7.4)
  GridValues max_mps2{};        // active maximum, least of (7.3)-(7.6)
  GridValues min_mps2{};        // Lmin (7.7), rotation-free
  GridValues floor_mps2{};      // Lmin with the Earth-rate term of (2.33): the closure test
};

/// Great circle from the planning point to the TAEM point.
struct TrackEnds {
  double lat1_rad = 0.0, lon1_rad = 0.0, lat2_rad = 0.0, lon2_rad = 0.0;
};

/// Breakpoints of the three-segment profile (fig. 7.12).
struct Breakpoints {
  double e1_Jpkg = 0.0;
  double e2_Jpkg = 0.0;
};

struct CorridorStageInput {
  const OnboardModels& models;
  const EnergyGrid& grid;
  const PlannerParams& params;
  const PlannerMission& mission;
  TrackEnds track;                    // planning point -> TAEM
  double planning_energy_Jpkg = 0.0;  // E0, the grid's first energy
  double d_actual_mps2 = 0.0;         // sensed (or modelled) drag at the planning point
};

/// Stage 1 output. The scalars are written where the stage reaches them (a failing stage
/// leaves the later ones as they were).
struct CorridorStage {
  DragCorridor corridor;
  int closed_points = 0;        // grid points where the maximum drag <= the floor
  Breakpoints breakpoints;
  double d_initial_mps2 = 0.0;  // Di: actual drag or Lmin at the planning energy (§7.6)
  double d_final_mps2 = 0.0;    // Df: from the TAEM conditions and alpha
};

/// Initial h(E) of the stage: r(E) of the zero-bank equilibrium glide (2.50), one root per energy.
Status equilibrium_glide_radius(const OnboardModels& models, const EnergyGrid& grid, GridValues& radius_m);

/// The corridor bounds on the grid at the radii radius_m.
void corridor_bounds(const CorridorStageInput& in, const GridValues& radius_m, DragCorridor& out);

/// Closed corridor: the active maximum drag at or below the floor. Lmin is a manoeuvrability
/// limit, not a structural one (§7.1), so short closures are flown on the maximum constraint;
/// a closure over more than max_closed_fraction of the grid is a failure. closed_points is
/// written when every point could be judged.
Status corridor_closure(const DragCorridor& c, double max_closed_fraction, int& closed_points);

/// E1: heat-flux / q-alpha intersection (first crossing from the planning energy down);
/// E2: energy of the highest maximum of Lmin below E1 (§7.2). Each segment keeps a least span.
Breakpoints profile_breakpoints(const EnergyGrid& grid, const DragCorridor& c, double planning_energy_Jpkg,
                                double taem_energy_Jpkg, const PlannerParams& params);

/// Stage 1: equilibrium-glide radius into radius_m, corridor, closure test, breakpoints, Di and Df.
Status drag_energy_corridor(const CorridorStageInput& in, GridValues& radius_m, CorridorStage& out);

}  // namespace reentry::fsw
