// Stage 2 of the entry planner: the drag profile that flies a trajectory length S (thesis
// §7.2, appendix C), sampled on the energy grid and held inside the corridor.
//   three segments: Di -> Dc at E1, Dc to E2, Dc -> Df (fig. 7.12), Dc from (7.12);
//   smooth: quartic Bernstein profile through Di, Dc, Df with Dc fitted the same way.
// Where the fitted profile exceeds the active maximum drag it follows that constraint (§7.2).
#pragma once

#include "guidance_types.hpp"
#include "planner/drag_profile.hpp"
#include "planner/planner_grid.hpp"
#include "planner/planner_params.hpp"

namespace reentry::fsw {

/// Bracket of the profile level Dc (7.12); the top is far above any corridor maximum and is
/// clipped to it (the shortest-range profile).
inline constexpr double kMinLevel_mps2 = 1e-3;
inline constexpr double kMaxLevel_mps2 = 500.0;

struct ProfileFitInput {
  DragProfileKind kind = DragProfileKind::kSmooth;
  double length_m = 0.0;          // S to fly (7.10)
  double e_initial_Jpkg = 0.0;    // Ei: planning energy
  double e1_Jpkg = 0.0;           // breakpoints (three segments only)
  double e2_Jpkg = 0.0;
  double e_final_Jpkg = 0.0;      // Ef: TAEM energy
  double d_initial_mps2 = 0.0;    // Di
  double d_final_mps2 = 0.0;      // Df
  const GridValues& energy_Jpkg;
  const GridValues& drag_max_mps2;  // active maximum of the corridor
};

/// Stage 2 output: D, dD/dE and d2D/dE2 on the grid. level_mps2 is written once the level is
/// known, clipped_points when every point is set.
struct PlannedDrag {
  GridValues drag_mps2{};
  GridValues drag_prime{};    // dD/dE [1/m]
  GridValues drag_second{};   // d2D/dE2 [kg/(J m)]
  double level_mps2 = 0.0;    // Dc
  int clipped_points = 0;     // points set to the active maximum constraint
  bool level_at_max = false;  // the length is below the shortest profile's: Dc at the bracket top
};

/// Dc for the length (7.12); a length shorter than the highest level flies gives that level
/// (level_at_max) when it is still longer than requested, else kCorridorClosed.
Status fit_drag_profile(const ProfileFitInput& in, PlannedDrag& out);

/// Where D exceeds the maximum: D, D' and D'' of the constraint (central differences on the
/// possibly graded grid). kNonFinite at the first point with a non-finite value.
Status follow_drag_limit(const GridValues& energy_Jpkg, const GridValues& drag_max_mps2, PlannedDrag& out);

}  // namespace reentry::fsw
