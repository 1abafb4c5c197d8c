#include "planner/planner_grid.hpp"

namespace reentry::fsw {

void build_energy_grid(const EnergyGridInput& in, const AlphaProfile& alpha_profile, EnergyGrid& out) {
  const double e0 = in.planning_energy_Jpkg;
  const double span = e0 - in.taem_energy_Jpkg;
  for (int k = 0; k < kPlannerGrid; ++k) {
    const double u = static_cast<double>(k) / (kPlannerGrid - 1);
    out.energy_Jpkg[k] = e0 - span * (in.graded ? u * u : u);
    out.alpha_rad[k] = alpha_profile.alpha_rad(out.energy_Jpkg[k] / in.entry_energy_Jpkg);
    out.alpha_profile_rad[k] = out.alpha_rad[k];
  }
  out.energy_Jpkg[kPlannerGrid - 1] = in.taem_energy_Jpkg;  // exact end (alpha above from the computed one)
}

}  // namespace reentry::fsw
