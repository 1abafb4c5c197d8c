// Ranging alpha (thesis 6.3.1, ranging phase): when the range needs less drag than the vehicle
// can hold even wings level at the profile alpha (low L/D, a long way to go), or when the bank
// the range needs is too small to turn, alpha moves towards alpha(L/D max):
//   alpha = alpha_profile + blend w(E) (alpha_LD - alpha_profile) where alpha_LD is lower.
// These are the pieces of that step; the blend search is in length_iteration.hpp.
#pragma once

#include "models/lift_over_drag.hpp"
#include "models/onboard_models.hpp"
#include "planner/planner_grid.hpp"

namespace reentry::fsw {

/// alpha of maximum C_L / C_D at the Mach of each grid point's state on radius_m, by a bounded
/// scan of scan_steps + 1 values over [0, alpha_max] (the mission alpha where no C_D > 0).
void alpha_of_max_lift_over_drag(const OnboardModels& models, const EnergyGrid& grid, const GridValues& radius_m,
                                 double alpha_max_rad, int scan_steps, GridValues& alpha_ld_rad);

struct RangingBlendInput {
  double blend = 0.0;               // share of the move towards alpha(L/D max)
  bool continuing = false;          // an earlier plan flies a blend: no ramp-in at the planning energy
  double planning_energy_Jpkg = 0.0;
  double entry_energy_Jpkg = 0.0;
  double taem_energy_Jpkg = 0.0;
  double ramp_fraction = 0.0;       // ramp span over the entry-to-TAEM span
};

/// w(E): ramps 0 -> 1 over the ramp span below the planning energy (1 there when continuing, so
/// the flown alpha continues) and back to 0 over the next-to-last ramp span before TAEM (0 over
/// the last one), so the TAEM alpha (and with it the TAEM Mach and q alpha) stays the mission's.
double ranging_weight(const RangingBlendInput& in, double ramp_Jpkg, double energy_Jpkg);

/// grid.alpha_rad from grid.alpha_profile_rad and alpha_ld_rad for the blend.
void apply_ranging_blend(const RangingBlendInput& in, const GridValues& alpha_ld_rad, EnergyGrid& grid);

}  // namespace reentry::fsw
