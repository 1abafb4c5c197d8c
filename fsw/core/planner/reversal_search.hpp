// Stage 5 of the entry planner: the bank-reversal search (thesis §7.4). The reversal point is
// the root of the end-point crossrange a2 (triangle steps 1-4 of §7.4) over the flown range at
// which the reversal starts, found by Brent's method on the reduced-order system (stage 4).
// The first bank side comes from the quadrant rule (fig. 7.20); when no reversal nulls the
// crossrange with it, the other side is tried once, and then the smallest crossrange of no
// reversal and the interval ends is taken as a best effort when it is small.
#pragma once

#include "guidance_types.hpp"
#include "planner/reduced_order.hpp"

namespace reentry::fsw {

struct ReversalSearchInput {
  const ReducedOrderInput& sys;
  RopState start{};                 // planning position and heading
  double azimuth_mission_rad = 0.0; // A of (7.2) from the planning point
  double b_mission_rad = 0.0;       // b of (7.1) from the planning point
  double r_mean_m = 0.0;            // radius that turns the angles into distances (7.22)
  double planning_energy_Jpkg = 0.0;
  double crossrange_tol_m = 0.0;
  double best_effort_crossrange_fraction = 0.0;  // of b: largest accepted best-effort crossrange
};

struct ReversalSearchResult {
  double crossrange_rad = 0.0;  // a2 at the end point
  double downrange_rad = 0.0;   // b2 at the end point
  int evaluations = 0;          // integrations of the search proper (0 when it stopped before)
  bool best_effort = false;     // no reversal nulls the crossrange: the smallest one
  bool lateral_unreachable = false;  // not even the best effort is small enough
};

/// Stage 5: flies the base run (no reversal) into `base`, then searches the reversal. first_sign
/// is the side flown first; the search may turn it over (see above). s_rev_m is the flown range
/// of the reversal start (>= the total range: none), written once the search has chosen it
/// (before the final flight); crossrange_rad and downrange_rad are valid when the status is kOk.
Status bank_reversal_search(const ReversalSearchInput& in, int& first_sign, double& s_rev_m, RopTrack& base,
                            ReversalSearchResult& out);

}  // namespace reentry::fsw
