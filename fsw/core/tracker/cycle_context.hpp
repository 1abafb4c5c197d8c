// The per-cycle context of the tracker: what its components need of the sensed state,
// computed once per tracking cycle by EntryTracker::make_context.
#pragma once

#include "guidance_types.hpp"
#include "tracker/lateral_logic.hpp"

namespace reentry::fsw {

struct CycleContext {
  const RelativeState* state = nullptr;  // the navigated state of this cycle
  double dt_s = 0.0;
  double e_norm = 0.0;                   // E / E_entry
  double mach = 0.0;                     // at the navigated altitude and speed
  double alpha_flown_rad = 0.0;          // the alpha the sensed accelerations belong to
  double alpha_ref_rad = 0.0;            // the reference alpha (before modulation, load relief)
  RelativeState referred;                // the sensed state referred to the reference alpha
  double lift_over_drag_sensed = 0.0;    // at the reference alpha (0: not measurable)
  double gravity_mps2 = 0.0;             // central gravity at the vehicle
  double sin_gamma = 0.0, cos_gamma = 1.0;
  double cd_ref = 0.0;                   // C_D at the reference alpha (energy-based Mach, 7.9)
  double cd_flown = 0.0;                 // C_D at the flown alpha
  double dynamic_pressure_Pa = 0.0;      // from the sensed drag and the model C_D
  double constraint_limit_mps2 = 0.0;    // sensed constraint drag limit at the reference alpha
  double plan_bound_mps2 = 0.0;          // the plan's path-constraint bound on the drag
  double taem_speed_mps = 0.0;           // min(TAEM speed, V)
  double time_to_go_s = 0.0;             // to the TAEM energy, speed falling linearly to v_TAEM
  double sigma_flown_rad = 0.0;          // the bank flown now
  ArrivalLineTarget target;              // arrival-line geometry (corridor and terminal phases)
};

}  // namespace reentry::fsw
