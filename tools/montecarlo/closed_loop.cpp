#include "closed_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "dynamics/open_loop.hpp"
#include "guidance/guidance_stack.hpp"
#include "nav/relative_state.hpp"

namespace reentry::tools {

namespace {
// The truth simulator of run `seed`: dispersed runs draw from the mission's [dispersions]. The
// closed loop and its pull-out bound fly the same draw.
std::unique_ptr<truth::Simulator> make_run_simulator(const config::Mission& mission, std::uint64_t seed,
                                                     bool dispersed, truth::DispersionDraw* draw,
                                                     std::string* error) {
  truth::SimOverrides ov;
  if (dispersed) ov.dispersion = truth::draw_dispersions(mission.dispersions, seed);
  *draw = ov.dispersion;
  auto sim = truth::Simulator::create(mission, ov, error);
  if (!sim) *error = "simulator: " + *error;
  return sim;
}
// The trace CSV of a run (header written); nullptr and `error` when it cannot be created.
std::FILE* open_trace(const std::string& path, std::string& error) {
  if (path.empty()) return nullptr;
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    error = "write failed: " + path + ": " + std::strerror(errno);
    return nullptr;
  }
  std::fprintf(f,
               "t_s,h_km,V_mps,gamma_deg,chi_deg,lat_deg,lon_deg,range_to_taem_km,bearing_to_taem_deg,E_Jpkg,"
               "D_mps2,D_ref_mps2,alpha_cmd_deg,sigma_cmd_deg,heading_err_deg,qdot_kWpm2,q_kPa,n_g,mach,phase,plan_seq\n");
  return f;
}

void write_trace_row(std::FILE* trace, const truth::TruthSample& t, const fsw::exec::CycleOutput& out) {
  constexpr double d = 180.0 / M_PI;
  std::fprintf(trace, "%.1f,%.4f,%.2f,%.4f,%.3f,%.5f,%.5f,%.3f,%.3f,%.1f,%.4f,%.4f,%.3f,%.3f,%.3f,%.2f,%.3f,%.4f,%.3f,%d,%d\n",
               t.t_s, t.h_m * 1e-3, t.V_mps, t.gamma_rad * d, t.chi_rad * d, t.lat_rad * d, t.lon_rad * d,
               t.range_to_taem_m * 1e-3, t.heading_to_taem_rad * d, t.E_Jpkg, t.D_mps2, out.drag_ref_mps2,
               out.alpha_rad * d, out.sigma_rad * d, out.heading_err_rad * d, t.qdot_Wpm2 * 1e-3, t.q_Pa * 1e-3, t.n_g,
               t.mach, static_cast<int>(out.phase), static_cast<int>(out.plan_seq));
}

// Closes the trace; a write that failed on the way (disk full) is named in `error`.
void close_trace(std::FILE* trace, const std::string& path, std::string& error) {
  if (trace == nullptr) return;
  const bool failed = std::ferror(trace) != 0;
  errno = 0;
  if ((std::fclose(trace) != 0 || failed) && error.empty())
    error = "write failed: " + path + ": " + std::strerror(errno != 0 ? errno : EIO);
}

}  // namespace

PulloutBound wings_level_pullout_bound(const config::Mission& mission, std::uint64_t seed, bool dispersed) {
  PulloutBound b;
  truth::DispersionDraw draw;
  auto sim = make_run_simulator(mission, seed, dispersed, &draw, &b.error);
  if (!sim) return b;
  b.maxima = truth::wings_level_pullout_maxima(*sim, mission.constraints.alpha_max_rad);
  b.exceeded = truth::path_constraint_violations(mission.constraints, b.maxima);
  return b;
}

ClosedLoopResult run_closed_loop(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                                 const std::string& trace_csv, bool guidance_knows_vehicle,
                                 const FlownSampleHandler& on_sample) {
  const auto t0 = std::chrono::steady_clock::now();
  ClosedLoopResult r;
  r.seed = seed;
  r.dispersed = dispersed;
  auto sim = make_run_simulator(mission, seed, dispersed, &r.dispersion, &r.error);
  if (!sim) return r;
  config::Mission guidance_mission = mission;
  if (guidance_knows_vehicle) {
    // The truth scales the coefficients it looks up (trimmed or not) by these factors.
    config::Vehicle& v = guidance_mission.vehicle;
    v.mass_kg *= r.dispersion.mass_scale;
    for (double& c : v.aero.cl.values) c *= r.dispersion.cl_scale;
    for (double& c : v.aero.cd.values) c *= r.dispersion.cd_scale;
  }
  fsw::GuidanceStack stack;
  const std::string err = stack.create(guidance_mission, fsw::exec::PlanMode::kSynchronous);
  if (!err.empty()) {
    r.error = "guidance: " + err;
    return r;
  }
  const double dt = 1.0 / mission.guidance.gnc_rate_hz;
  double alpha_prev = 0.0, sigma_prev = 0.0;
  bool have_prev = false;
  std::FILE* trace = open_trace(trace_csv, r.trace_error);
  const int trace_every = std::max(1, static_cast<int>(std::lround(mission.guidance.gnc_rate_hz)));
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
        if (on_sample) on_sample(*sim, out.alpha_rad, out.sigma_rad);
        if (trace && k % trace_every == 0) write_trace_row(trace, sim->sample(), out);
      }
    }
    sim->advance_to(static_cast<double>(k + 1) * dt);
  }
  close_trace(trace, trace_csv, r.trace_error);
  if (on_sample) on_sample(*sim, alpha_prev, sigma_prev);
  r.summary = sim->summary();
  r.verdict = truth::judge_mission(mission, r.summary, r.rates);
  const auto& c = stack.executive->counters();
  r.planner_runs = c.planner_runs;
  r.plans_adopted = c.plans_adopted;
  r.planner_failures = c.planner_failures;
  r.planner_ms_max = c.planner_ms_max;
  r.cycle_us_max = c.cycle_us_max;
  r.nav_rejected = c.invalid_nav;
  stack.executive->shutdown();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace reentry::tools
