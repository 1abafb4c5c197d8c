#include "betts_shuttle.hpp"

namespace reentry::optimal {

Trajectory BettsShuttle::linear_guess(const Mesh& mesh) const {
  Trajectory g;
  g.tau = mesh.point_tau();
  g.p = {2000.0};
  const double x0[kStates] = {260000.0, 0.0, 0.0, 25600.0, -1.0 * kDeg, 90.0 * kDeg};
  const double x1[kStates] = {80000.0, 75.0 * kDeg, 25.0 * kDeg, 2500.0, -5.0 * kDeg, 10.0 * kDeg};
  for (double s : g.tau) {
    for (int i = 0; i < kStates; ++i) g.x.push_back(x0[i] + s * (x1[i] - x0[i]));
    g.u.push_back(17.4 * kDeg);
    g.u.push_back((-75.0 + 75.0 * s) * kDeg);
  }
  return g;
}

}  // namespace reentry::optimal
