// pc_probe <mission> [seed]: one closed-loop run of the predictor-corrector law (in process, as
// tools/mc flies it) printing every plan's diagnostics: a development aid for the law's tuning.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "dynamics/simulator.hpp"
#include "evaluation/mission_verdict.hpp"
#include "guidance/guidance_stack.hpp"
#include "nav/relative_state.hpp"
#include "reentry/config/mission.hpp"

using namespace reentry;

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const auto loaded = config::load_mission(argv[1]);
  if (!loaded.ok) {
    std::fprintf(stderr, "%s\n", loaded.error.c_str());
    return 2;
  }
  const config::Mission& m = loaded.mission;
  truth::SimOverrides ov;
  if (argc > 2) ov.dispersion = truth::draw_dispersions(m.dispersions, std::strtoull(argv[2], nullptr, 10));
  std::string err;
  auto sim = truth::Simulator::create(m, ov, &err);
  fsw::GuidanceStack stack;
  err = stack.create(m, fsw::exec::PlanMode::kSynchronous);
  if (!err.empty() || !stack.pc_planner) {
    std::fprintf(stderr, "stack: %s (predictor-corrector mission needed)\n", err.c_str());
    return 2;
  }
  const double dt = 1.0 / m.guidance.gnc_rate_hz, d = 180.0 / M_PI;
  auto& pl = stack.pc_planner->planner;
  if (argc > 4 && std::string(argv[2]) == "--predict") {
    // pc_probe <mission> --predict sigma0_deg sigmaf_deg...: predictions from the entry interface.
    const fsw::RelativeState s = pl.entry_state();
    for (int i = 4; i < argc; ++i) {
      auto prof = std::make_unique<fsw::ReferenceProfile>();
      const fsw::Prediction p = pl.predict(s, std::atof(argv[3]) / d, 1.0, prof.get(), std::atof(argv[i]) / d);
      for (int k = 0; k < prof->n_points; k += 8) {
        std::printf("   E/E0 %.4f h %.2f V %.0f gam %.2f sig %.1f D %.2f Dmax %.2f\n", prof->e_norm[k],
                    (prof->radius_m[k] - fsw::kEarthRadius_m) / 1e3, prof->velocity_mps[k], prof->gamma_rad[k] * d,
                    prof->sigma_rad[k] * d, prof->drag_mps2[k], prof->drag_max_mps2[k]);
      }
      std::printf("s0 %s sf %s: end %d along %.1f km cross %.1f km h %.2f km V %.1f gamma %.2f psi %.2f t %.0f s "
                  "rev %d qdot %.0f q %.0f steps %d\n", argv[3], argv[i], static_cast<int>(p.end), p.along_m / 1e3,
                  p.cross_m / 1e3, p.altitude_m / 1e3, p.final_state.velocity_mps, p.final_state.flight_path_rad * d,
                  p.heading_err_rad * d, p.time_s, p.reversals, p.heat_flux_max_Wpm2 / 1e3, p.q_max_Pa, p.steps);
    }
    return 0;
  }
  int plans = 0;
  for (std::int64_t k = 0; k < 100000 && !sim->finished(); ++k) {
    const truth::NavSample n = sim->nav_sample();
    const double r_I[3] = {n.r_I_m.x(), n.r_I_m.y(), n.r_I_m.z()};
    const double v_I[3] = {n.v_I_mps.x(), n.v_I_mps.y(), n.v_I_mps.z()};
    const double a_I[3] = {n.aero_accel_I_mps2.x(), n.aero_accel_I_mps2.y(), n.aero_accel_I_mps2.z()};
    fsw::exec::NavInput nav;
    nav.tick = k;
    if (fsw::relative_state_from_nav(n.t_s, r_I, v_I, a_I, n.earth_rotation_angle_rad, nav.state) == fsw::Status::kOk) {
      const fsw::exec::CycleOutput out = stack.executive->step(nav);
      if (stack.executive->counters().planner_runs > plans) {
        plans = stack.executive->counters().planner_runs;
        const fsw::PcPlanDiagnostics& g = pl.diagnostics();
        std::printf("t %7.1f plan %3d %-14s pred %2d s0 %6.2f da %5.2f K %.3f LD %.3f z %9.0f y %8.0f hf %6.0f psi %6.2f rev %d E/E0 %.3f aim %.0f hold E/E0 %.4f\n",
                    nav.state.t_s, plans, fsw::to_string(g.status), g.predictions, g.sigma0_rad * d, g.alpha_shift_rad * d,
                    g.density_ratio, g.lift_scale, g.miss_along_m, g.miss_cross_m, g.final_altitude_m,
                    g.final_heading_err_rad * d, g.reversals, nav.state.energy_Jpkg / pl.entry_energy_Jpkg(),
                    stack.executive->active_profile().taem_altitude_m,
                    stack.executive->active_profile().reversal_hold_energy_Jpkg / pl.entry_energy_Jpkg());
      }
      sim->set_command(out.alpha_rad, out.sigma_rad);
    }
    sim->advance_to(static_cast<double>(k + 1) * dt);
  }
  const truth::RunSummary s = sim->summary();
  const truth::MissionVerdict v = truth::judge_mission(m, s, truth::CommandRateMaxima{});
  std::printf("end %s success %d miss %.2f km (along %.2f cross %.2f) alt err %.2f km mach %.2f heading %.2f deg "
              "gamma %.2f qdot %.0f kW/m2 q %.2f kPa n %.2f qa %.1f kPa deg\n",
              truth::to_string(s.event), v.success, v.taem_miss_m / 1e3, v.miss_along_m / 1e3, v.miss_cross_m / 1e3,
              v.altitude_err_m / 1e3, v.mach, v.heading_err_rad * d, s.final_state.gamma_rad * d,
              s.maxima.qdot_Wpm2 / 1e3, s.maxima.q_Pa / 1e3, s.maxima.n_g, s.maxima.q_alpha_Pa_rad / 1e3 / d);
  for (const auto& x : v.violations) std::printf("violation %s\n", x.c_str());
  stack.executive->shutdown();
  return 0;
}
