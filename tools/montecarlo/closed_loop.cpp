#include "closed_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "app/guidance_messages.hpp"
#include "dynamics/open_loop.hpp"
#include "guidance/guidance_stack.hpp"
#include "nav/relative_state.hpp"
#include "physics/angles.hpp"
#include "sim_messages.hpp"
#include "transport/event_log.hpp"
#include "transport/lcm_codec.hpp"

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

/// The run once per second in the channels of a SIL run's log, each message filled by the
/// functions the two processes use (generated from interfaces/*.lcm).
class TraceLog {
 public:
  /// False and `error` (the file and the reason) when the log cannot be created.
  bool open(const std::string& path, int every_ticks, std::string& error) {
    every_ = every_ticks;
    if (log_.open(path, 1u << 20, transport::EventLogWriter::WhenFull::kWait, error)) return true;
    error = "write failed: " + error;
    return false;
  }
  bool is_open() const { return log_.is_open(); }
  /// Tick k after its command (the simulator's state with the command in effect).
  void record(std::int64_t k, const truth::Simulator& sim, const fsw::exec::CycleOutput& out,
              const fsw::exec::Executive& exec) {
    if (out.plan_adopted) {
      fsw::app::fill_plan(exec.active_profile(), std::llround(out.t_s * 1e6), k, exec.counters().planner_ms_last, plan_);
      put("PLAN", plan_);
    }
    if (k % every_ != 0) return;
    const truth::TruthSample t = sim.sample();
    truth::fill_truth(t, std::llround(t.t_s * 1e6), k, truth_);
    put("TRUTH", truth_);
    fsw::app::fill_command(out, cmd_);
    put("GUIDANCE_CMD", cmd_);
    fsw::app::fill_tracker_status(out, tracker_);
    put("TRACKER_STATUS", tracker_);
  }
  /// Ends the log; false and `error` when it could not be written whole (disk full).
  bool close(const truth::RunSummary& summary, std::int64_t k, double taem_heading_rad, std::string& error) {
    truth::fill_end_of_run(summary, k, truth::end_event_code(summary.event), taem_heading_rad, end_);
    put("RUN_CONTROL", end_);
    if (log_.close()) return true;
    error = "write failed: " + log_.error();
    return false;
  }

 private:
  template <class Msg>
  void put(const char* channel, const Msg& msg) {
    const int n = transport::encode_into(msg, buf_.data(), static_cast<int>(buf_.size()));
    if (n > 0) log_.record(channel, buf_.data(), n);
  }
  transport::EventLogWriter log_;
  std::vector<std::uint8_t> buf_ = std::vector<std::uint8_t>(65000);
  int every_ = 1;
  truth_telemetry_t truth_{};
  guidance_cmd_t cmd_{};
  tracker_status_t tracker_{};
  plan_t plan_{};
  run_control_t end_{};
};

// The guidance's view of the run's vehicle: the drawn C_L, C_D and mass when it "knows" them
// (a diagnosis; the truth scales the coefficients it looks up by these factors).
config::Mission guidance_mission_of(const config::Mission& mission, const truth::DispersionDraw& d, bool knows) {
  config::Mission m = mission;
  if (!knows) return m;
  config::Vehicle& v = m.vehicle;
  v.mass_kg *= d.mass_scale;
  for (double& c : v.aero.cl.values) c *= d.cl_scale;
  for (double& c : v.aero.cd.values) c *= d.cd_scale;
  return m;
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
                                 const std::string& trace_log, bool guidance_knows_vehicle,
                                 const FlownSampleHandler& on_sample) {
  const auto t0 = std::chrono::steady_clock::now();
  ClosedLoopResult r;
  r.seed = seed;
  r.dispersed = dispersed;
  auto sim = make_run_simulator(mission, seed, dispersed, &r.dispersion, &r.error);
  if (!sim) return r;
  fsw::GuidanceStack stack;
  const std::string err =
      stack.create(guidance_mission_of(mission, r.dispersion, guidance_knows_vehicle), fsw::exec::PlanMode::kSynchronous);
  if (!err.empty()) {
    r.error = "guidance: " + err;
    return r;
  }
  const double dt = 1.0 / mission.guidance.gnc_rate_hz;
  double alpha_prev = 0.0, sigma_prev = 0.0;
  bool have_prev = false;
  TraceLog trace;
  if (!trace_log.empty())
    trace.open(trace_log, std::max(1, static_cast<int>(std::lround(mission.guidance.gnc_rate_hz))), r.trace_error);
  const auto max_ticks = static_cast<std::int64_t>(std::ceil(sim->settings().time_limit_s / dt)) + 2;
  std::int64_t k = 0;
  for (; k < max_ticks && !sim->finished(); ++k) {
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
          r.rates.sigma_rate_radps = std::max(r.rates.sigma_rate_radps, std::fabs(physics::wrap_pi(out.sigma_rad - sigma_prev)) / dt);
        }
        alpha_prev = out.alpha_rad;
        sigma_prev = out.sigma_rad;
        have_prev = true;
        sim->set_command(out.alpha_rad, out.sigma_rad);
        if (on_sample) on_sample(*sim, out.alpha_rad, out.sigma_rad);
        if (trace.is_open()) trace.record(k, *sim, out, *stack.executive);
      }
    }
    sim->advance_to(static_cast<double>(k + 1) * dt);
  }
  if (on_sample) on_sample(*sim, alpha_prev, sigma_prev);
  r.summary = sim->summary();
  if (trace.is_open()) trace.close(r.summary, k, mission.taem.heading_rad, r.trace_error);
  r.verdict = truth::judge_mission(mission, r.summary, r.rates);
  r.counters = stack.executive->counters();
  stack.executive->shutdown();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace reentry::tools
