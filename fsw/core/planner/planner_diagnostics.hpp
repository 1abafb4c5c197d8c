// What the entry planner reports about its last plan (tools, tests, telemetry of the plan).
#pragma once

#include "guidance_types.hpp"

namespace reentry::fsw {

struct PlannerDiagnostics {
  Status status = Status::kInvalidInput;
  bool converged = false;
  int iterations = 0;
  int reversal_evaluations = 0;
  double dc_mps2 = 0.0;
  double di_mps2 = 0.0;
  double df_mps2 = 0.0;
  double e1_Jpkg = 0.0;
  double e2_Jpkg = 0.0;
  double s_initial_m = 0.0;
  double s_final_m = 0.0;
  double crossrange_err_m = 0.0;
  double downrange_err_m = 0.0;
  double b_mission_rad = 0.0;
  double a_mission_rad = 0.0;
  double chi_minus_a_rad = 0.0;
  double reversal_energy_Jpkg = 0.0;
  int initial_bank_sign = 1;
  int corridor_closed_points = 0;  // grid points where max drag <= Lmin
  int clipped_points = 0;          // drag points set to the active max constraint
  int bank_saturated_points = 0;   // |D'' - a| / b exceeded L/D
  double ranging_blend = 0.0;      // alpha moved this fraction towards alpha(L/D max) (ranging)
  bool reversal_best_effort = false;  // no reversal nulls the crossrange: smallest one planned
};

}  // namespace reentry::fsw
