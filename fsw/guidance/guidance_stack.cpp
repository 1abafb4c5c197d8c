#include "guidance/guidance_stack.hpp"

#include <algorithm>
#include <cmath>

#include "guidance/alpha_profile_source.hpp"
#include "guidance/mission_adapter.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::fsw {
namespace {

// The alpha and sigma rate filters of either law, from the mission's control limits.
std::string init_filters(const config::Mission& m, double dt_s, RateFilter& alpha, RateFilter& sigma) {
  Status st = alpha.init(m.constraints.alpha_rate_max_radps, m.constraints.alpha_accel_max_radps2, dt_s);
  if (st != Status::kOk) return std::string("alpha filter init (constraints.alpha_rate/accel): ") + to_string(st);
  alpha.set_bounds(0.0, m.constraints.alpha_max_rad);
  st = sigma.init(m.constraints.sigma_rate_max_radps, m.constraints.sigma_accel_max_radps2, dt_s);
  if (st != Status::kOk) return std::string("sigma filter init (constraints.sigma_rate/accel): ") + to_string(st);
  return {};
}

// A law's commands through the rate filters, which start at its first command (no artificial
// ramp from zero at the entry interface), and its telemetry.
template <class LawCommand>
void filtered_output(const LawCommand& c, bool& started, RateFilter& alpha, RateFilter& sigma, exec::LawOutput& out) {
  if (!started) {
    alpha.reset(c.alpha_rad);
    sigma.reset(c.sigma_rad);
    started = true;
  }
  out.alpha_rad = alpha.step(c.alpha_rad);
  out.sigma_rad = sigma.step(c.sigma_rad);
  out.phase = c.phase;
  out.lift_over_drag_scale = c.lift_over_drag_scale;
  out.tracker = c.telemetry;
}

}  // namespace

Status TrackerLaw::step(const RelativeState& s, double dt_s, bool /*has_profile*/, exec::LawOutput& out) {
  if (started_) tracker.set_flown_attitude(alpha_filter.value(), sigma_filter.value());
  const Status st = tracker.step(s, dt_s, last);
  if (st == Status::kOk) filtered_output(last, started_, alpha_filter, sigma_filter, out);
  return st;
}

Status PcLaw::step(const RelativeState& s, double dt_s, bool /*has_profile*/, exec::LawOutput& out) {
  if (started_) cycle.set_flown_attitude(alpha_filter.value(), sigma_filter.value());
  const Status st = cycle.step(s, dt_s, last);
  if (st == Status::kOk) filtered_output(last, started_, alpha_filter, sigma_filter, out);
  return st;
}

exec::PlanComputer& GuidanceStack::plan_computer() {
  if (pc_planner) return *pc_planner;
  return *planner;
}

exec::CommandLaw& GuidanceStack::command_law() {
  if (pc_law) return *pc_law;
  return *law;
}

namespace {

/// The mission's entry interface as the executive's first-sample check sees it: the entry
/// state, its dispersions (the wider of the reference and stress sets: the guidance does not
/// know which campaign flies it) and a navigation allowance; the sensed force bound from the
/// on-board density at the entry altitude (x3 for the model, times the density dispersion) and
/// the largest force coefficient of the aero tables at the lightest dispersed mass.
exec::EntryEnvelope entry_envelope(const config::Mission& m, const OnboardModels& models) {
  const config::Dispersions& a = m.dispersions;
  const config::Dispersions& b = m.has_stress_dispersions ? m.stress_dispersions : m.dispersions;
  auto widest = [](const config::Dispersion& x, const config::Dispersion& y) { return std::max(x.value, y.value); };
  exec::EntryEnvelope e;
  e.known = true;
  e.latitude_rad = m.entry.latitude_rad;
  e.longitude_rad = m.entry.longitude_rad;
  e.radius_m = surface_radius_m(m.entry.latitude_rad) + m.entry.altitude_m;
  e.radius_tol_m = 1000.0 + kEarthRadius_m * kEarthFlattening;  // navigation + sphere or ellipsoid
  e.velocity_mps = m.entry.velocity_mps;
  e.velocity_tol_mps = widest(a.entry_velocity_mps, b.entry_velocity_mps) + 20.0;
  e.flight_path_rad = m.entry.flight_path_rad;
  e.flight_path_tol_rad = widest(a.entry_flight_path_rad, b.entry_flight_path_rad) + 0.005;
  e.position_tol_rad = std::sqrt(2.0) * widest(a.entry_position_rad, b.entry_position_rad) + 0.001;
  const double e_entry =
      specific_energy_Jpkg(e.radius_m + e.radius_tol_m, e.velocity_mps + e.velocity_tol_mps);  // (7.8)
  e.energy_max_Jpkg = e_entry + 0.02 * std::fabs(e_entry);  // J2 and Earth-rate work on the relative energy
  double coeff_max = 0.0;
  const auto& cl = m.vehicle.aero.cl.values;
  const auto& cd = m.vehicle.aero.cd.values;
  const double cl_scale = 1.0 + widest(a.cl_scale, b.cl_scale), cd_scale = 1.0 + widest(a.cd_scale, b.cd_scale);
  for (std::size_t i = 0; i < cl.size() && i < cd.size(); ++i)
    coeff_max = std::max(coeff_max, std::hypot(cl[i] * cl_scale, cd[i] * cd_scale));
  const double density_scale =
      3.0 * (1.0 + std::max(a.density_scale.value, b.density_scale.value) +
             std::max(a.density_perturbation, b.density_perturbation));
  const double mass_min_kg = m.vehicle.mass_kg * (1.0 - widest(a.mass_scale, b.mass_scale));
  const double rho_kgpm3 = models.atmosphere().density_kgpm3(m.entry.altitude_m) * density_scale;
  // At least 0.5 m/s^2: accelerometer bias and noise at the entry interface.
  e.specific_force_max_mps2 = std::max(0.5, 0.5 * rho_kgpm3 * e.velocity_mps * e.velocity_mps * coeff_max *
                                                m.vehicle.reference_area_m2 / mass_min_kg);
  return e;
}

}  // namespace

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
  std::string err = make_guidance_setup(m, *setup);
  if (!err.empty()) return err;
  executive = std::make_unique<exec::Executive>();
  const GuidanceSetup& g = *setup;
  config.gnc_rate_hz = m.guidance.gnc_rate_hz;
  config.plan_latency_ticks = m.guidance.plan_latency_ticks;
  config.replan_period_s = m.guidance.replan_period_s;
  config.replan_drag_error_frac = m.guidance.replan_drag_error_frac;
  config.drag_error_replan_spacing_s = m.guidance.drag_error_replan_spacing_s;
  config.initial_descent_drag_mps2 = m.guidance.initial_descent_drag_mps2;
  config.mode = mode;
  Status st = Status::kOk;
  if (g.law == GuidanceLaw::kPredictorCorrector) {
    pc_planner = std::make_unique<PcPlannerAdapter>();
    pc_law = std::make_unique<PcLaw>();
    const PcPlanTiming timing{m.guidance.plan_latency_ticks, dt_s};
    const double capture = g.params.tracker.initial_descent_drag_mps2;
    st = pc_planner->planner.init(g.models, g.alpha_profile, g.mission, g.pc_params, capture, timing);
    if (st != Status::kOk) return std::string("predictor-corrector plan init: ") + to_string(st);
    st = pc_law->cycle.init(g.models, g.alpha_profile, g.mission, g.pc_params, g.params.tracker, capture);
    if (st != Status::kOk) return std::string("predictor-corrector cycle init: ") + to_string(st);
    err = init_filters(m, dt_s, pc_law->alpha_filter, pc_law->sigma_filter);
    // The law's own schedule: its period, and plans until the last fraction of the span.
    config.replan_period_s = g.pc_params.replan_period_s;
    config.replan_floor_energy_Jpkg = pc_law->cycle.replan_floor_energy_Jpkg();
  } else {
    planner = std::make_unique<PlannerAdapter>();
    law = std::make_unique<TrackerLaw>();
    st = planner->planner.init(g.models, g.alpha_profile, g.mission, g.params);
    if (st != Status::kOk) return std::string("planner init: ") + to_string(st);
    st = law->tracker.init(g.models, g.alpha_profile, g.mission, g.params);
    if (st != Status::kOk) return std::string("tracker init: ") + to_string(st);
    err = init_filters(m, dt_s, law->alpha_filter, law->sigma_filter);
    config.replan_floor_energy_Jpkg = law->tracker.terminal_energy_Jpkg();
  }
  if (!err.empty()) return err;
  config.nav.entry = entry_envelope(m, g.models);
  st = executive->init(config, plan_computer(), command_law());
  if (st != Status::kOk) return std::string("executive init (guidance timing parameters): ") + to_string(st);
  return {};
}

}  // namespace reentry::fsw
