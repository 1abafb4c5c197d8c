#include "tracker/reference_track.hpp"

#include <cmath>

#include "planner/mission_geometry.hpp"

namespace reentry::fsw {

bool ReferenceTrack::adopt(const ReferenceProfile& profile) {
  if (profile.n_points < 2 || (profile.status != Status::kOk && profile.status != Status::kRangeTooLong)) return false;
  profile_ = profile;
  has_profile_ = true;
  hint_ = 0;
  // (3.13): the loop reaches full bandwidth once the vehicle is in the dense part of the entry.
  double q_max = 0.0;
  for (int k = 0; k < profile_.n_points; ++k) q_max = std::fmax(q_max, profile_.dynamic_pressure_Pa[k]);
  q_ref_Pa_ = q_max > 0.0 ? q_ref_fraction_ * q_max : 1.0;
  return true;
}

RefPoint ReferenceTrack::at(double energy) {
  const ReferenceProfile& p = profile_;
  const int n = p.n_points;
  // Energies decrease with the index; find k with E[k] >= energy >= E[k+1] (bounded walk).
  int k = clamp(hint_, 0, n - 2);
  for (int i = 0; i < n && k > 0 && energy > p.energy_Jpkg[k]; ++i) --k;
  for (int i = 0; i < n && k < n - 2 && energy < p.energy_Jpkg[k + 1]; ++i) ++k;
  hint_ = k;
  const double e0 = p.energy_Jpkg[k], e1 = p.energy_Jpkg[k + 1];
  const double w = e0 != e1 ? clamp((e0 - energy) / (e0 - e1), 0.0, 1.0) : 0.0;
  auto lerp = [&](const double* a) { return a[k] + w * (a[k + 1] - a[k]); };
  RefPoint r;
  r.drag = lerp(p.drag_mps2);
  r.drag_prime = lerp(p.drag_prime);
  r.drag_second = lerp(p.drag_second);
  r.b = lerp(p.b_coef);
  r.alpha = lerp(p.alpha_rad);
  r.alpha_prime = e0 != e1 ? (p.alpha_rad[k + 1] - p.alpha_rad[k]) / (e1 - e0) : 0.0;
  r.lod = lerp(p.lift_over_drag);
  r.sigma = lerp(p.sigma_rad);
  r.heading = p.heading_rad[k] + w * wrap_pi(p.heading_rad[k + 1] - p.heading_rad[k]);
  r.q = lerp(p.dynamic_pressure_Pa);
  r.drag_max = lerp(p.drag_max_mps2);
  return r;
}

}  // namespace reentry::fsw
