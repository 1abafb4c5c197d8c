// Stage 4 of the entry planner: the reduced-order system (2.42)-(2.45) flown along the planned
// drag profile, with the bank reversal modelled by method 3 of §7.4. The independent variable
// is the flown range s = -int dE / D (7.10): d()/ds = -D d()/dE. Steps uniform in s stay
// accurate where the drag is tiny (planning from the actual drag at entry), where steps uniform
// in energy would badly misestimate the range flown. RK4, fixed step count.
#pragma once

#include <array>

#include "guidance_types.hpp"
#include "planner/planner_grid.hpp"
#include "planner/planner_params.hpp"
#include "planner/profile_fit.hpp"
#include "planner/trajectory_extraction.hpp"

namespace reentry::fsw {

/// Reduced-order state (2.42)-(2.44): longitude, latitude, heading.
struct RopState {
  double lon = 0.0, lat = 0.0, chi = 0.0;
};
using RopTrack = std::array<RopState, PlannerParams::kMaxRkSteps + 1>;

/// Flown range at the grid points for a drag linear in energy within each cell ((C.9) per cell).
struct RangeTable {
  GridValues s_cum_m{};      // -int dE / D from the planning energy
  GridValues drag_slope{};   // dD/dE of the linear interpolant in each cell
  double s_total_m = 0.0;
};
void build_range_table(const GridValues& energy_Jpkg, const GridValues& drag_mps2, RangeTable& out);

/// Bank reversal, method 3 of §7.4: the first side (sign of sigma) down to energy_Jpkg, then
/// sigma goes linearly in energy from first_sign * bank_start_rad to -first_sign * bank_start_rad
/// over span_Jpkg, then the second side.
struct ReversalModel {
  int first_sign = 1;
  double energy_Jpkg = 0.0;
  double span_Jpkg = 1.0;
  double bank_start_rad = 0.0;
};
enum class ReversalPhase { kFirstSide, kReversing, kSecondSide };
ReversalPhase reversal_phase(const ReversalModel& m, double energy_Jpkg);
/// Signed bank during the reversal (method 3 of §7.4), linear in energy.
double reversal_ramp_bank_rad(const ReversalModel& m, double energy_Jpkg);
/// Signed bank at an energy for the bank magnitude there.
double scheduled_bank_rad(const ReversalModel& m, double energy_Jpkg, double bank_magnitude_rad);
/// Method 3 of §7.4: energy spent in the reversal, dE = 2 sigma_rev0 / sigma_dot_max D V (floored).
double reversal_energy_span_Jpkg(double bank_start_rad, double bank_rate_max_radps, double drag_mps2, double velocity_mps);

/// The planned trajectory the system flies (stages 2-3) and the settings of the integration.
struct ReducedOrderInput {
  const GridValues& energy_Jpkg;
  const GridValues& radius_m;
  const PlannedDrag& drag;
  const ExtractedTrajectory& trajectory;
  const RangeTable& range;
  double corridor_energy_Jpkg = 0.0;  // below: great circle (lateral corridor phase)
  double taem_energy_Jpkg = 0.0;
  double sigma_rate_max_radps = 0.0;
  int rk4_steps = 0;                  // <= PlannerParams::kMaxRkSteps
};

/// Result of one integration: end state and the reversal it flew (an energy below TAEM when
/// there is none).
struct RopFlight {
  RopState end{};
  ReversalModel reversal{};
};

/// (L/D) cos(sigma) and L/D at grid cell k, weight w, for the latitude and heading:
/// D'' = a + b (L/D) cos(sigma) (7.17) solved with C_gamma (7.18) in a (7.19).
double vertical_lift_over_drag(const ReducedOrderInput& sys, int k, double w, double lat_rad, double chi_rad,
                               double& lift_over_drag);

/// |sigma| from (L/D) cos(sigma) and L/D (7.17), saturated at wings level / upside down.
double bank_magnitude_rad(double lod_cos, double lod);

/// Integration over the whole flown range with the reversal at flown range s_rev_m.
/// s_rev_m >= the total range: no reversal, every step boundary is written to `base` (flown
/// with first_sign throughout). Otherwise the integration restarts from `base` at the step
/// that holds s_rev_m: the states before it are the base run's, flown with the first side the
/// base run had. With `track` non-null every step boundary is also written there.
Status fly_reduced_order(const ReducedOrderInput& sys, const RopState& start, int first_sign, double s_rev_m,
                         RopTrack& base, RopTrack* track, RopFlight& out);

}  // namespace reentry::fsw
