#include "planner/profile_fit.hpp"

#include <cmath>

namespace reentry::fsw {
namespace {

// The profile shape with its level solved for the length (7.12), sampled on the grid.
template <class Profile>
Status fit_and_sample(Profile& profile, Status solved, const ProfileFitInput& in, PlannedDrag& out) {
  if (solved == Status::kNoBracket) {
    // Shorter than even the highest level flies: that level, clipped below to the corridor
    // maximum, is the shortest-range profile (flown as a best effort when the range is too
    // long for the vehicle, see length_iteration). Otherwise no level reaches the length.
    profile.d_c = kMaxLevel_mps2;
    const double shortest_m = profile.length_m();
    if (!(shortest_m > in.length_m)) return Status::kCorridorClosed;
    out.level_at_max = true;
    solved = Status::kOk;
  }
  out.level_mps2 = profile.d_c;
  if (solved != Status::kOk) return solved;
  for (int k = 0; k < kPlannerGrid; ++k) {
    out.drag_mps2[k] = profile.drag(in.energy_Jpkg[k]);
    out.drag_prime[k] = profile.slope(in.energy_Jpkg[k]);
    out.drag_second[k] = profile.curvature(in.energy_Jpkg[k]);
  }
  return Status::kOk;
}

}  // namespace

Status fit_drag_profile(const ProfileFitInput& in, PlannedDrag& out) {
  out.level_at_max = false;
  Status s;
  if (in.kind == DragProfileKind::kThreeSegment) {
    ThreeSegmentProfile p{in.e_initial_Jpkg, in.e1_Jpkg, in.e2_Jpkg, in.e_final_Jpkg, in.d_initial_mps2, 1.0, in.d_final_mps2};
    s = fit_and_sample(p, p.solve_constant_drag(in.length_m, kMinLevel_mps2, kMaxLevel_mps2), in, out);  // (7.12)
  } else {
    SmoothProfile p{in.e_initial_Jpkg, in.e_final_Jpkg, in.d_initial_mps2, 1.0, in.d_final_mps2};
    s = fit_and_sample(p, p.solve_level(in.length_m, kMinLevel_mps2, kMaxLevel_mps2), in, out);
  }
  if (s != Status::kOk) return s;
  return follow_drag_limit(in.energy_Jpkg, in.drag_max_mps2, out);
}

Status follow_drag_limit(const GridValues& e, const GridValues& d_max, PlannedDrag& out) {
  constexpr int n = kPlannerGrid;
  int clipped = 0;
  for (int k = 0; k < n; ++k) {
    if (out.drag_mps2[k] > d_max[k]) {
      ++clipped;
      out.drag_mps2[k] = d_max[k];
      const int km = k > 0 ? k - 1 : 0;
      const int kp = k + 1 < n ? k + 1 : n - 1;
      out.drag_prime[k] = (d_max[kp] - d_max[km]) / (e[kp] - e[km]);
      if (k > 0 && k + 1 < n) {  // second difference on the (possibly graded) grid
        const double h1 = e[k] - e[km], h2 = e[kp] - e[k];
        out.drag_second[k] = 2.0 * (h1 * d_max[kp] - (h1 + h2) * d_max[k] + h2 * d_max[km]) / (h1 * h2 * (h1 + h2));
      } else {
        out.drag_second[k] = 0.0;
      }
    }
    if (!std::isfinite(out.drag_mps2[k] + out.drag_prime[k] + out.drag_second[k])) return Status::kNonFinite;
  }
  out.clipped_points = clipped;
  return Status::kOk;
}

}  // namespace reentry::fsw
