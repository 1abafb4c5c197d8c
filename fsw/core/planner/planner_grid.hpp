// The energy grid of the entry planner (thesis ch. 7) and the mission constants its stages
// read. Index 0 of every grid array is the planning energy, the last index the TAEM energy;
// the reference profile handed to the tracker has one point per grid point. Fixed capacity.
#pragma once

#include <array>

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"

namespace reentry::fsw {

inline constexpr int kPlannerGrid = kProfileCapacity;
using GridValues = std::array<double, kPlannerGrid>;

// Numerical settings shared by the altitude root finders of the stages (not tunables of the method).
inline constexpr double kPlannerMaxAltitude_m = 200000.0;  // top of every altitude bracket
inline constexpr int kPlannerRootIterations = 80;          // iteration bound of those root finders

/// Path-constraint limits the corridor is planned for (design margin applied), SI.
struct CorridorLimits {
  double heat_flux_Wpm2 = 0.0;
  double q_alpha_Pa_rad = 0.0;
  double load_mps2 = 0.0;            // n_max g0
  double dynamic_pressure_Pa = 0.0;
};

/// Mission constants of the planner, fixed at init().
struct PlannerMission {
  RelativeState entry{};                 // at the entry interface, drag from the on-board models
  double entry_energy_Jpkg = 0.0;        // normalises the alpha profile's energy
  double taem_energy_Jpkg = 0.0;
  double taem_radius_m = 0.0;
  double taem_lat_rad = 0.0;
  double taem_lon_rad = 0.0;
  double taem_drag_altitude_m = 0.0;     // altitude of the planned final drag
  double corridor_energy_Jpkg = 0.0;     // below it the trajectory is a great circle
  double terminal_span_fraction = 0.25;  // of the entry-to-TAEM span: ranging alpha and floor check end there
  CorridorLimits limits{};
  double alpha_max_rad = 0.0;
  double sigma_rate_max_radps = 0.0;
};

/// Stage 0 input: the energy span to plan over and how to space it.
struct EnergyGridInput {
  double planning_energy_Jpkg = 0.0;
  double taem_energy_Jpkg = 0.0;
  double entry_energy_Jpkg = 0.0;
  bool graded = false;  // quadratic spacing towards the planning energy
};

/// Stage 0 output: energies and alpha on the grid. alpha_rad is the alpha the plan flies (the
/// mission profile, or the ranging blend towards alpha(L/D max)); alpha_profile_rad the mission's.
struct EnergyGrid {
  GridValues energy_Jpkg{};
  GridValues alpha_profile_rad{};
  GridValues alpha_rad{};
};

/// Energy grid from the planning energy to TAEM. When the profile starts from a near-zero drag
/// (actual drag at the entry interface) the range flown per unit energy is huge at the start
/// (S = -int dE / D (7.10)), so the grid is graded quadratically towards the planning energy.
void build_energy_grid(const EnergyGridInput& in, const AlphaProfile& alpha_profile, EnergyGrid& out);

}  // namespace reentry::fsw
