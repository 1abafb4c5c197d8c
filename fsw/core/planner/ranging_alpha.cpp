#include "planner/ranging_alpha.hpp"

namespace reentry::fsw {

void alpha_of_max_lift_over_drag(const OnboardModels& models, const EnergyGrid& grid, const GridValues& radius_m,
                                 double alpha_max_rad, int scan_steps, GridValues& alpha_ld_rad) {
  for (int k = 0; k < kPlannerGrid; ++k) {
    const double h = radius_m[k] - kEarthRadius_m;
    const double mach = models.mach(h, velocity_from_energy_mps(grid.energy_Jpkg[k], radius_m[k]));
    alpha_ld_rad[k] =
        alpha_of_max_lift_over_drag_rad(models.aero(), mach, alpha_max_rad, scan_steps, grid.alpha_profile_rad[k]);
  }
}

double ranging_weight(const RangingBlendInput& in, double ramp_Jpkg, double energy_Jpkg) {
  const double ramp_in = in.continuing ? 1.0 : clamp((in.planning_energy_Jpkg - energy_Jpkg) / ramp_Jpkg, 0.0, 1.0);
  return ramp_in * clamp((energy_Jpkg - in.taem_energy_Jpkg - ramp_Jpkg) / ramp_Jpkg, 0.0, 1.0);
}

void apply_ranging_blend(const RangingBlendInput& in, const GridValues& alpha_ld_rad, EnergyGrid& grid) {
  const double span = in.entry_energy_Jpkg - in.taem_energy_Jpkg;
  const double ramp = in.ramp_fraction * span;
  for (int k = 0; k < kPlannerGrid; ++k) {
    const double w = ranging_weight(in, ramp, grid.energy_Jpkg[k]);
    const double delta = alpha_ld_rad[k] - grid.alpha_profile_rad[k];
    grid.alpha_rad[k] = grid.alpha_profile_rad[k] + (delta < 0.0 ? in.blend * w * delta : 0.0);
  }
}

}  // namespace reentry::fsw
