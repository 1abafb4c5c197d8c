#include "models/lift_over_drag.hpp"

namespace reentry::fsw {

double alpha_of_max_lift_over_drag_rad(const OnboardAero& aero, double mach, double alpha_max_rad, int scan_steps,
                                       double fallback_rad) {
  double best_alpha = fallback_rad, best_lod = -1.0;
  for (int i = 0; i <= scan_steps; ++i) {
    const double a = alpha_max_rad * i / scan_steps;
    double cl = 0.0, cd = 0.0;
    aero.coefficients(a, mach, cl, cd);
    if (cd > 0.0 && cl / cd > best_lod) {
      best_lod = cl / cd;
      best_alpha = a;
    }
  }
  return best_alpha;
}

}  // namespace reentry::fsw
