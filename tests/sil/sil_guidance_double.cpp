// TEST DOUBLE of the guidance process for the SIL machinery tests: the real LCM adapter
// (reentry_fsw_app) and executive (reentry_fsw_exec) around a deliberately simple guidance
// law (constant angle of attack, bank from the plan) and a simple inertial -> relative
// conversion. It exercises lockstep, link loss, logging and replay, not guidance quality.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/guidance_node.hpp"
#include "transport/monotonic_clock.hpp"

namespace {

using reentry::fsw::ReferenceProfile;
using reentry::fsw::RelativeState;
using reentry::fsw::Status;
namespace exec = reentry::fsw::exec;

constexpr double kMu = 3.986004418e14;
constexpr double kRe = 6378137.0;
constexpr double kOmega = 7.2921159e-5;

Status convert(const reentry::nav_state_t& nav, RelativeState& s, void*) {
  const double* r = nav.position_I_m;
  const double* v = nav.velocity_I_mps;
  const double vr[3] = {v[0] + kOmega * r[1], v[1] - kOmega * r[0], v[2]};  // v - omega x r
  const double rn = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  const double vn = std::sqrt(vr[0] * vr[0] + vr[1] * vr[1] + vr[2] * vr[2]);
  if (!(rn > 0.0) || !(vn > 0.0)) return Status::kNonFinite;
  const double* a = nav.aero_accel_I_mps2;
  const double drag = -(a[0] * vr[0] + a[1] * vr[1] + a[2] * vr[2]) / vn;
  s.t_s = nav.t_s;
  s.radius_m = rn;
  s.altitude_m = rn - kRe;
  s.velocity_mps = vn;
  s.flight_path_rad = std::asin((r[0] * vr[0] + r[1] * vr[1] + r[2] * vr[2]) / (rn * vn));
  s.energy_Jpkg = 0.5 * vn * vn - kMu / rn + kMu / kRe;
  s.drag_mps2 = drag;
  const double a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  s.lift_mps2 = std::sqrt(std::fmax(0.0, a2 - drag * drag));
  return Status::kOk;
}

class PlanDouble : public exec::PlanComputer {
 public:
  Status compute(const RelativeState& from, ReferenceProfile& out) override {
    out.n_points = 2;
    out.energy_Jpkg[0] = from.energy_Jpkg;
    out.energy_Jpkg[1] = 0.0;
    out.drag_mps2[0] = from.drag_mps2;
    out.sigma_rad[0] = 0.9 - 0.1 * std::tanh(from.flight_path_rad * 10.0);
    out.status = Status::kOk;
    return Status::kOk;
  }
};

class LawDouble : public exec::CommandLaw {
 public:
  double alpha_rad = 0.6;
  ReferenceProfile p;
  void set_profile(const ReferenceProfile& profile) override { p = profile; }
  Status step(const RelativeState& s, double, bool has_profile, exec::LawOutput& out) override {
    out.alpha_rad = alpha_rad;
    out.sigma_rad = (has_profile ? p.sigma_rad[0] : 0.2) + 1e-3 * s.flight_path_rad;
    out.phase = has_profile ? reentry::fsw::Phase::kTracking : reentry::fsw::Phase::kInitialDescent;
    return Status::kOk;
  }
};

}  // namespace

int main(int argc, char** argv) {
  namespace app = reentry::fsw::app;
  CLI::App cli{"SIL test double of the guidance process"};
  std::string mission, mode = "lockstep", replay, replay_log, status_json, log_path, digest;
  bool compare = false, unsealed = false;
  app::LiveOptions live;
  cli.add_option("--mission", mission);
  cli.add_option("--mode", mode);
  cli.add_option("--replay", replay);
  cli.add_flag("--compare", compare);
  cli.add_flag("--unsealed", unsealed);
  cli.add_option("--replay-log", replay_log);
  cli.add_option("--mission-digest", digest);  // the double flies no mission: accepted, not checked
  cli.add_option("--status-json", status_json);
  cli.add_option("--log", log_path);
  cli.add_option("--link-timeout-ticks", live.link_timeout_ticks);
  cli.add_option("--startup-timeout", live.startup_timeout_s);
  CLI11_PARSE(cli, argc, argv);

  static PlanDouble planner;
  static LawDouble law;
  auto executive = std::make_unique<exec::Executive>();
  exec::ExecConfig cfg;
  cfg.gnc_rate_hz = 10.0;
  cfg.plan_latency_ticks = 5;
  cfg.replan_period_s = 50.0;
  cfg.mode = !replay.empty() ? exec::PlanMode::kSynchronous
             : mode == "realtime" ? exec::PlanMode::kRealtime
                                  : exec::PlanMode::kLockstep;
  if (executive->init(cfg, planner, law) != Status::kOk) return app::kExitUsage;
  executive->set_cycle_clock(&reentry::transport::thread_cpu_ns);
  auto node = std::make_unique<app::GuidanceNode>(*executive, &convert, nullptr, cfg.gnc_rate_hz);
  int rc = 0;
  auto net = std::make_unique<reentry::transport::UdpmSocket>();  // outlives the node's use of it
  if (!replay.empty()) {
    rc = node->run_replay(replay, compare, replay_log, unsealed);
  } else {
    const app::RunMode run_mode = mode == "realtime" ? app::RunMode::kRealtime : app::RunMode::kLockstep;
    reentry::transport::UdpmUrl url;
    std::string err;
    if (!reentry::transport::parse_udpm_url(reentry::transport::default_udpm_url(), url, err) || !net->open(url, err) ||
        !node->open_log(log_path, run_mode, err)) {
      std::fprintf(stderr, "sil_guidance_double: %s\n", err.c_str());
      return app::kExitTransport;
    }
    reentry::transport::install_stop_handlers();
    rc = node->run_live(*net, run_mode, live);
    if (!node->close_log()) rc = app::kExitWriteFailed;
  }
  if (!node->write_status_json(status_json, rc)) rc = app::kExitWriteFailed;
  executive->shutdown();
  return rc;
}
