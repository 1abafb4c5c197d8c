#include "app/guidance_messages.hpp"

#include <algorithm>

namespace reentry::fsw::app {

void fill_plan(const ReferenceProfile& p, std::int64_t utime, std::int64_t tick, double compute_ms, plan_t& plan) {
  const int n = std::min(p.n_points, static_cast<int>(plan_t::MAX_POINTS));
  plan.utime = utime;
  plan.tick = tick;
  plan.seq = p.seq;
  plan.n_points = static_cast<std::int16_t>(n);
  for (int i = 0; i < plan_t::MAX_POINTS; ++i) {
    const bool in = i < n;
    plan.e_norm[i] = in ? p.e_norm[i] : 0.0;
    plan.drag_mps2[i] = in ? p.drag_mps2[i] : 0.0;
    plan.radius_m[i] = in ? p.radius_m[i] : 0.0;
    plan.gamma_rad[i] = in ? p.gamma_rad[i] : 0.0;
    plan.sigma_rad[i] = in ? p.sigma_rad[i] : 0.0;
    plan.alpha_rad[i] = in ? p.alpha_rad[i] : 0.0;
  }
  const double e0 = p.entry_energy_Jpkg != 0.0 ? p.entry_energy_Jpkg : 1.0;
  plan.reversal_e_norm = p.reversal_energy_Jpkg / e0;
  plan.dc_mps2 = p.dc_mps2;
  plan.e1_norm = p.e1_Jpkg / e0;
  plan.e2_norm = p.e2_Jpkg / e0;
  plan.trajectory_length_m = p.trajectory_length_m;
  plan.crossrange_err_m = p.crossrange_err_m;
  plan.downrange_err_m = p.downrange_err_m;
  plan.iterations = p.iterations;
  plan.status = static_cast<std::int8_t>(p.status);
  plan.converged = p.converged;
  plan.compute_ms = compute_ms;
}

}  // namespace reentry::fsw::app
