// Alpha of maximum lift-to-drag ratio of the on-board aero tables at one Mach number, by a
// bounded scan: the planner's ranging alpha (planner/ranging_alpha.hpp) and the
// predictor-corrector's ranging floor (predictor_corrector/point_mass.hpp) both use it.
#pragma once

#include "models/onboard_models.hpp"

namespace reentry::fsw {

/// alpha of maximum C_L / C_D at `mach` over scan_steps + 1 alphas evenly in [0, alpha_max]
/// (the first of equal maxima); `fallback_rad` where no alpha has C_D > 0.
double alpha_of_max_lift_over_drag_rad(const OnboardAero& aero, double mach, double alpha_max_rad, int scan_steps,
                                       double fallback_rad);

}  // namespace reentry::fsw
