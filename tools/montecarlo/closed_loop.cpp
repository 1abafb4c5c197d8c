#include "closed_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "guidance/guidance_stack.hpp"
#include "nav/relative_state.hpp"

namespace reentry::tools {

ClosedLoopResult run_closed_loop(const config::Mission& mission, std::uint64_t seed, bool dispersed) {
  const auto t0 = std::chrono::steady_clock::now();
  ClosedLoopResult r;
  r.seed = seed;
  r.dispersed = dispersed;
  truth::SimOverrides ov;
  if (dispersed) ov.dispersion = truth::draw_dispersions(mission.dispersions, seed);
  r.dispersion = ov.dispersion;
  std::string err;
  auto sim = truth::Simulator::create(mission, ov, &err);
  if (!sim) {
    r.error = "simulator: " + err;
    return r;
  }
  fsw::GuidanceStack stack;
  err = stack.create(mission, fsw::exec::PlanMode::kSynchronous);
  if (!err.empty()) {
    r.error = "guidance: " + err;
    return r;
  }
  const double dt = 1.0 / mission.guidance.gnc_rate_hz;
  double alpha_prev = 0.0, sigma_prev = 0.0;
  bool have_prev = false;
  const auto max_ticks = static_cast<std::int64_t>(std::ceil(sim->settings().time_limit_s / dt)) + 2;
  for (std::int64_t k = 0; k < max_ticks && !sim->finished(); ++k) {
    const truth::NavSample n = sim->nav_sample();
    const double r_I[3] = {n.r_I_m.x(), n.r_I_m.y(), n.r_I_m.z()};
    const double v_I[3] = {n.v_I_mps.x(), n.v_I_mps.y(), n.v_I_mps.z()};
    const double a_I[3] = {n.aero_accel_I_mps2.x(), n.aero_accel_I_mps2.y(), n.aero_accel_I_mps2.z()};
    fsw::exec::NavInput nav;
    nav.tick = k;
    if (fsw::relative_state_from_nav(n.t_s, r_I, v_I, a_I, n.earth_rotation_angle_rad, nav.state) == fsw::Status::kOk) {
      const fsw::exec::CycleOutput out = stack.executive->step(nav);
      if (out.emitted) {
        if (have_prev) {
          r.rates.alpha_rate_radps = std::max(r.rates.alpha_rate_radps, std::fabs(out.alpha_rad - alpha_prev) / dt);
          r.rates.sigma_rate_radps = std::max(r.rates.sigma_rate_radps, std::fabs(out.sigma_rad - sigma_prev) / dt);
        }
        alpha_prev = out.alpha_rad;
        sigma_prev = out.sigma_rad;
        have_prev = true;
        sim->set_command(out.alpha_rad, out.sigma_rad);
      }
    }
    sim->advance_to(static_cast<double>(k + 1) * dt);
  }
  r.summary = sim->summary();
  r.verdict = truth::judge_mission(mission, r.summary, r.rates);
  const auto& c = stack.executive->counters();
  r.planner_runs = c.planner_runs;
  r.plans_adopted = c.plans_adopted;
  r.planner_failures = c.planner_failures;
  r.planner_ms_max = c.planner_ms_max;
  r.cycle_us_max = c.cycle_us_max;
  stack.executive->shutdown();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace reentry::tools
