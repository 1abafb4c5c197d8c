// reentry_fsw: the guidance process.
//   reentry_fsw --mission <name|file> [--mode lockstep|realtime] [--replay run.lcm] [--compare]
// Wires the core components (nav conversion, entry planner, tracker, rate filters) into the
// executive and runs the LCM adapter. All allocation happens here, before the loop starts.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "app/guidance_node.hpp"
#include "filter/rate_filter.hpp"
#include "nav/relative_state.hpp"
#include "planner/entry_planner.hpp"
#include "reentry/config/mission.hpp"
#include "tracker/entry_tracker.hpp"

namespace {

using namespace reentry::fsw;

class PlannerAdapter : public exec::PlanComputer {
 public:
  EntryPlanner planner;
  Status compute(const RelativeState& from, ReferenceProfile& out) override { return planner.plan(from, out); }
};

// Tracker followed by the alpha and sigma rate filters.
class TrackerLaw : public exec::CommandLaw {
 public:
  EntryTracker tracker;
  RateFilter alpha_filter;
  RateFilter sigma_filter;
  void set_profile(const ReferenceProfile& profile) override { tracker.set_profile(profile); }
  Status step(const RelativeState& s, double dt_s, bool, exec::LawOutput& out) override {
    TrackerOutput t;
    const Status st = tracker.step(s, dt_s, t);
    if (st != Status::kOk) return st;
    out.alpha_rad = alpha_filter.step(t.alpha_rad);
    out.sigma_rad = sigma_filter.step(t.sigma_rad);
    out.phase = t.phase;
    out.drag_ref_mps2 = t.drag_ref_mps2;
    out.drag_err_mps2 = t.drag_err_mps2;
    out.heading_err_rad = t.heading_err_rad;
    return Status::kOk;
  }
};

Status convert_nav(const reentry::nav_state_t& nav, RelativeState& out, void*) {
  return relative_state_from_nav(nav.t_s, nav.position_I_m, nav.velocity_I_mps, nav.aero_accel_I_mps2,
                                 nav.earth_rotation_angle_rad, out);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"reentry guidance process"};
  std::string mission_arg, mode = "lockstep", replay, status_json;
  bool compare = false;
  double link_timeout_s = 2.0;
  cli.add_option("--mission", mission_arg, "mission name or TOML file")->required();
  cli.add_option("--mode", mode, "lockstep or realtime")->check(CLI::IsMember({"lockstep", "realtime"}));
  cli.add_option("--replay", replay, "replay the NAV_STATE messages of an LCM log");
  cli.add_flag("--compare", compare, "with --replay: compare with the logged GUIDANCE_CMD");
  cli.add_option("--status-json", status_json, "write the executive counters here at exit");
  cli.add_option("--link-timeout", link_timeout_s, "lockstep: seconds without nav before link loss");
  CLI11_PARSE(cli, argc, argv);

  const auto loaded = reentry::config::load_mission(mission_arg);
  if (!loaded.ok) {
    std::fprintf(stderr, "reentry_fsw: %s\n", loaded.error.c_str());
    return app::kExitUsage;
  }
  const auto& m = loaded.mission;
  const double dt_s = 1.0 / m.guidance.gnc_rate_hz;
  auto planner = std::make_unique<PlannerAdapter>();
  auto law = std::make_unique<TrackerLaw>();
  if (planner->planner.init(m) != Status::kOk || law->tracker.init(m) != Status::kOk ||
      law->alpha_filter.init(m.constraints.alpha_rate_max_radps, m.constraints.alpha_accel_max_radps2, dt_s) !=
          Status::kOk ||
      law->sigma_filter.init(m.constraints.sigma_rate_max_radps, m.constraints.sigma_accel_max_radps2, dt_s) !=
          Status::kOk) {
    std::fprintf(stderr, "reentry_fsw: component initialisation failed for mission %s\n", m.name.c_str());
    return app::kExitUsage;
  }
  exec::ExecConfig cfg;
  cfg.gnc_rate_hz = m.guidance.gnc_rate_hz;
  cfg.plan_latency_ticks = m.guidance.plan_latency_ticks;
  cfg.replan_period_s = m.guidance.replan_period_s;
  cfg.replan_drag_error_frac = m.guidance.replan_drag_error_frac;
  cfg.initial_descent_drag_mps2 = m.guidance.initial_descent_drag_mps2;
  cfg.mode = !replay.empty() ? exec::PlanMode::kSynchronous
             : mode == "realtime" ? exec::PlanMode::kRealtime
                                  : exec::PlanMode::kLockstep;
  auto executive = std::make_unique<exec::Executive>();
  if (executive->init(cfg, *planner, *law) != Status::kOk) {
    std::fprintf(stderr, "reentry_fsw: invalid guidance timing parameters\n");
    return app::kExitUsage;
  }
  auto node = std::make_unique<app::GuidanceNode>(*executive, &convert_nav, nullptr, cfg.gnc_rate_hz);
  int rc = app::kExitOk;
  if (!replay.empty()) {
    rc = node->run_replay(replay, compare);
  } else {
    lcm::LCM lcm;
    if (!lcm.good()) {
      std::fprintf(stderr, "reentry_fsw: LCM initialisation failed\n");
      return app::kExitUsage;
    }
    rc = node->run_live(lcm, mode == "realtime" ? app::RunMode::kRealtime : app::RunMode::kLockstep,
                        link_timeout_s, 30.0);
  }
  node->write_status_json(status_json);
  executive->shutdown();
  return rc;
}
