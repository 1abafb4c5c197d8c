// Drag-acceleration profiles over energy whose trajectory length S = -int dE / D (7.10)
// is known: the thesis's three-segment linear spline (7.11) and a smooth, breakpoint-free
// quartic Bernstein profile integrated by fixed-step Gauss-Legendre quadrature.
#pragma once

#include "guidance_types.hpp"

namespace reentry::fsw {

/// Three linear segments (fig. 7.12): Di at Ei -> Dc at E1, Dc to E2, Dc -> Df at Ef.
/// Energies decrease: Ei > E1 > E2 > Ef.
struct ThreeSegmentProfile {
  double e_i = 0.0, e_1 = 0.0, e_2 = 0.0, e_f = 0.0;
  double d_i = 0.0, d_c = 0.0, d_f = 0.0;

  bool valid() const;
  double drag(double energy) const;
  double slope(double energy) const;     // D' (0 on the constant segment)
  double curvature(double) const { return 0.0; }  // D'' = 0 on linear segments
  double length_m() const;               // (7.11)
  /// Dc such that length_m() == s_m (7.12), bracketed secant/Brent on [dc_min, dc_max].
  Status solve_constant_drag(double s_m, double dc_min, double dc_max);
};

/// D(x) = Di B0(x) + Dc (B1 + B2 + B3)(x) + Df B4(x), x = (Ei - E) / (Ei - Ef), quartic
/// Bernstein basis: C-infinity, positive for positive data, S monotone in Dc.
struct SmoothProfile {
  double e_i = 0.0, e_f = 0.0;
  double d_i = 0.0, d_c = 0.0, d_f = 0.0;

  bool valid() const;
  double drag(double energy) const;
  double slope(double energy) const;     // dD/dE
  double curvature(double energy) const; // d2D/dE2
  /// -int dE / D by 5-point Gauss-Legendre on kPanels equal panels.
  double length_m() const;
  Status solve_level(double s_m, double dc_min, double dc_max);
  static constexpr int kPanels = 24;
};

/// Length of a linear drag segment from Da to Db over |dE| (C.9), stable when Da ~ Db.
double linear_segment_length(double delta_energy, double d_a, double d_b);

}  // namespace reentry::fsw
