#include "guidance/guidance_stack.hpp"

#include "guidance/alpha_profile_source.hpp"
#include "guidance/mission_adapter.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::fsw {

Status TrackerLaw::step(const RelativeState& s, double dt_s, bool /*has_profile*/, exec::LawOutput& out) {
  if (started_) tracker.set_flown_attitude(alpha_filter.value(), sigma_filter.value());
  const Status st = tracker.step(s, dt_s, last);
  if (st != Status::kOk) return st;
  if (!started_) {
    alpha_filter.reset(last.alpha_rad);
    sigma_filter.reset(last.sigma_rad);
    started_ = true;
  }
  out.alpha_rad = alpha_filter.step(last.alpha_rad);
  out.sigma_rad = sigma_filter.step(last.sigma_rad);
  out.phase = last.phase;
  out.lift_over_drag_scale = last.lift_over_drag_scale;
  out.tracker = last.telemetry;
  return Status::kOk;
}

std::string GuidanceStack::create(const config::Mission& mission, exec::PlanMode mode) {
  // A planned alpha profile is planned here, at start-up, on a copy of the mission.
  const config::Mission* source = &mission;
  config::Mission planned;
  if (mission.alpha_profile_planned) {
    planned = mission;
    const std::string err = resolve_alpha_profile(planned);
    if (!err.empty()) return err;
    source = &planned;
  }
  const config::Mission& m = *source;
  const double dt_s = 1.0 / m.guidance.gnc_rate_hz;
  auto setup = std::make_unique<GuidanceSetup>();
  const std::string err = make_guidance_setup(m, *setup);
  if (!err.empty()) return err;
  planner = std::make_unique<PlannerAdapter>();
  law = std::make_unique<TrackerLaw>();
  executive = std::make_unique<exec::Executive>();
  const GuidanceSetup& g = *setup;
  Status st = planner->planner.init(g.models, g.alpha_profile, g.mission, g.params);
  if (st != Status::kOk) return std::string("planner init: ") + to_string(st);
  st = law->tracker.init(g.models, g.alpha_profile, g.mission, g.params);
  if (st != Status::kOk) return std::string("tracker init: ") + to_string(st);
  st = law->alpha_filter.init(m.constraints.alpha_rate_max_radps, m.constraints.alpha_accel_max_radps2, dt_s);
  if (st != Status::kOk) return std::string("alpha filter init (constraints.alpha_rate/accel): ") + to_string(st);
  law->alpha_filter.set_bounds(0.0, m.constraints.alpha_max_rad);
  st = law->sigma_filter.init(m.constraints.sigma_rate_max_radps, m.constraints.sigma_accel_max_radps2, dt_s);
  if (st != Status::kOk) return std::string("sigma filter init (constraints.sigma_rate/accel): ") + to_string(st);
  config.gnc_rate_hz = m.guidance.gnc_rate_hz;
  config.plan_latency_ticks = m.guidance.plan_latency_ticks;
  config.replan_period_s = m.guidance.replan_period_s;
  config.replan_drag_error_frac = m.guidance.replan_drag_error_frac;
  config.drag_error_replan_spacing_s = m.guidance.drag_error_replan_spacing_s;
  config.initial_descent_drag_mps2 = m.guidance.initial_descent_drag_mps2;
  config.replan_floor_energy_Jpkg = law->tracker.terminal_energy_Jpkg();
  config.mode = mode;
  st = executive->init(config, *planner, *law);
  if (st != Status::kOk) return std::string("executive init (guidance timing parameters): ") + to_string(st);
  return {};
}

}  // namespace reentry::fsw
