// Stage 3 of the entry planner: trajectory extraction from the planned drag (thesis §7.3,
// appendix D): r(E) from D(E) (7.13), gamma(E) from D'(E) (7.14), and the coefficients of
// D'' = a + b (L/D) cos(sigma) (7.17)-(7.20) that give the bank magnitude once the latitude
// and heading (C_gamma (7.18)) are known from the reduced-order integration.
#pragma once

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"
#include "planner/planner_grid.hpp"
#include "planner/profile_fit.hpp"

namespace reentry::fsw {

/// Step of the central difference of ln(rho) that gives (1/rho) d rho / dr in (7.14)-(7.16).
/// The tracker takes its own 100 m step for the same derivative at the sensed altitude.
inline constexpr double kDensityGradientStep_m = 25.0;

struct ExtractionInput {
  const OnboardModels& models;
  const EnergyGrid& grid;
  const PlannedDrag& drag;
};

/// Stage 3 output (with the radius r(E), which the stage writes into the plan's h(E) profile).
struct ExtractedTrajectory {
  GridValues velocity_mps{};
  GridValues drag_coefficient{};
  GridValues lift_over_drag{};
  GridValues dynamic_pressure_Pa{};
  GridValues gamma_rad{};
  GridValues a_no_coriolis{};    // a of (7.19) without its C_gamma term
  GridValues density_gravity{};  // k = -(1/rho) d rho/dr + 2 g / V^2: a = a_no_coriolis + k C_gamma
  GridValues b{};                // (7.20)
};

/// Altitude where the drag at (E, alpha) equals the planned drag (7.13).
Status altitude_for_drag(const OnboardModels& models, double energy_Jpkg, double alpha_rad, double drag_mps2,
                         double& altitude_m);

/// Stage 3: r(E) (7.13) into radius_m point by point, then gamma(E) (7.14) and the D''
/// coefficients (7.19)-(7.20). Stops at the first point that fails.
Status extract_trajectory(const ExtractionInput& in, GridValues& radius_m, ExtractedTrajectory& out);

}  // namespace reentry::fsw
