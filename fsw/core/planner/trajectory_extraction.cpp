#include "planner/trajectory_extraction.hpp"

#include <cmath>

#include "numerics/root_finding.hpp"
#include "planner/drag_derivatives.hpp"

namespace reentry::fsw {
namespace {

// Altitude bracket of (7.13): from the surface to where the energy leaves only this speed.
constexpr double kDragBracketSpeed_mps = 1.0;
constexpr double kDragAltitudeTol_m = 0.05;

// r, V, CD, L/D and q at every point from (7.13).
Status extract_radius(const ExtractionInput& in, GridValues& radius_m, ExtractedTrajectory& out) {
  for (int k = 0; k < kPlannerGrid; ++k) {
    const double energy = in.grid.energy_Jpkg[k];
    const double alpha = in.grid.alpha_rad[k];
    double h = 0.0;
    const Status st = altitude_for_drag(in.models, energy, alpha, in.drag.drag_mps2[k], h);
    if (st != Status::kOk) return st;
    radius_m[k] = kEarthRadius_m + h;
    const double v = velocity_from_energy_mps(energy, radius_m[k]);
    out.velocity_mps[k] = v;
    double cl, cd;
    in.models.aero().coefficients(alpha, in.models.mach(h, v), cl, cd);
    out.drag_coefficient[k] = cd;
    out.lift_over_drag[k] = cl / cd;
    out.dynamic_pressure_Pa[k] = 0.5 * in.models.atmosphere().density_kgpm3(h) * v * v;
  }
  return Status::kOk;
}

// gamma (7.14) and the D'' coefficients (7.19)-(7.20) at every point.
Status extract_flight_path(const ExtractionInput& in, const GridValues& radius_m, ExtractedTrajectory& out) {
  const GridValues& e = in.grid.energy_Jpkg;
  const GridValues& alpha = in.grid.alpha_rad;
  for (int k = 0; k < kPlannerGrid; ++k) {
    const int km = k > 0 ? k - 1 : 0;
    const int kp = k + 1 < kPlannerGrid ? k + 1 : kPlannerGrid - 1;
    const double h = radius_m[k] - kEarthRadius_m;
    const double dp = in.drag.drag_prime[k];
    DragLocal l;
    l.drag = in.drag.drag_mps2[k];
    l.velocity = out.velocity_mps[k];
    l.radius = radius_m[k];
    l.gravity = gravity_mps2(radius_m[k]);
    // d ln rho / dr and CD' by finite differences on the models; CD'' = 0 (Mease et al.).
    l.rho_r_over_rho = in.models.dlnrho_dr_fd(h, kDensityGradientStep_m);
    l.cd_prime_over_cd = in.models.drag_coefficient_slope(alpha[km], e[km], radius_m[km] - kEarthRadius_m, alpha[kp], e[kp],
                                                          radius_m[kp] - kEarthRadius_m) / out.drag_coefficient[k];
    l.cd_second_over_cd = 0.0;
    const double sin_gamma = sin_gamma_from_drag_slope(l, dp);  // (7.14)
    if (!std::isfinite(sin_gamma)) return Status::kNonFinite;
    if (std::fabs(sin_gamma) >= 1.0) return Status::kExtractionFailed;
    out.gamma_rad[k] = std::asin(sin_gamma);
    out.a_no_coriolis[k] = drag_second_a_no_coriolis(l, dp);  // (7.19) without C_gamma
    out.density_gravity[k] = density_gravity_factor(l);
    out.b[k] = drag_second_b(l);  // (7.20)
    if (!std::isfinite(out.a_no_coriolis[k] + out.density_gravity[k] + out.b[k] + out.lift_over_drag[k])) {
      return Status::kNonFinite;
    }
  }
  return Status::kOk;
}

}  // namespace

Status altitude_for_drag(const OnboardModels& models, double energy_Jpkg, double alpha_rad, double drag_mps2,
                         double& altitude_m) {
  const double h_top = clamp(radius_for_speed_m(energy_Jpkg, kDragBracketSpeed_mps) - kEarthRadius_m, 0.0, kPlannerMaxAltitude_m);
  auto residual = [&](double h) {  // (7.13)
    return models.drag_mps2(alpha_rad, h, velocity_from_energy_mps(energy_Jpkg, kEarthRadius_m + h)) - drag_mps2;
  };
  const numerics::RootResult root = numerics::brent(residual, 0.0, h_top, kDragAltitudeTol_m, kPlannerRootIterations);
  const Status st = to_status(root.status);
  if (st == Status::kNoBracket) return Status::kExtractionFailed;
  if (st != Status::kOk && st != Status::kMaxIterations) return st;
  altitude_m = root.x;
  return Status::kOk;
}

Status extract_trajectory(const ExtractionInput& in, GridValues& radius_m, ExtractedTrajectory& out) {
  const Status s = extract_radius(in, radius_m, out);
  if (s != Status::kOk) return s;
  return extract_flight_path(in, radius_m, out);
}

}  // namespace reentry::fsw
