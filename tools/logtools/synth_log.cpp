// reentry_synth_log: writes a short synthetic but physically consistent run.lcm for the tool tests
// (used only by tests/tools; the SIL writes the real logs). A point mass with constant L/D flies
// through an exponential atmosphere over a spherical, non-rotating Earth; all channels the SIL
// publishes are written with lcm::LogFile, the messages encoded by the generated types. TRUTH
// and END_OF_RUN are filled by the generated copies from interfaces/*.lcm (the sample is named
// as the simulator's TruthSample), so the log tests check those copies against the physics too.
#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/tracker_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/run_control_t.hpp>
#include <reentry/telemetry_fill.hpp>
#include <reentry/truth_telemetry_t.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/earth_constants.hpp"

namespace {

using reentry::physics::kEarthRate_radps;
using reentry::physics::kMuEarth_m3ps2;
using reentry::physics::kStandardGravity_mps2;
using reentry::physics::kEarthEquatorialRadius_m;
constexpr double kRho0_kgpm3 = 1.225;
constexpr double kScaleHeight_m = 7050.0;

struct Vehicle {
  double mass_kg = 37000.0;
  double ref_area_m2 = 149.0;
  double cd = 0.55;
  double lift_over_drag = 1.1;
  double nose_radius_m = 0.8;
};

// One tick of the trajectory, its members named as the simulator's TruthSample (the source of
// truth_telemetry_t's fill).
struct Sample {
  double t_s, r_m, h_m, lon_rad, lat_rad, V_mps, gamma_rad, chi_rad, mach;
  double sigma_rad, alpha_rad, D_mps2, L_mps2, q_Pa, qdot_Wpm2, Q_Jpm2, n_g, E_Jpkg;
  double range_to_taem_m, heading_to_taem_rad;
};

// What run_control_t's END_OF_RUN is filled from (as the simulator's RunSummary and its extras).
struct RunMaxima {
  double qdot_Wpm2 = 0.0, n_g = 0.0, q_Pa = 0.0, q_alpha_Pa_rad = 0.0;
};
struct RunSummary {
  Sample final_state;
  RunMaxima maxima;
};
struct EndOfRun {
  std::int8_t command = reentry::run_control_t::END_OF_RUN;
  std::int8_t event_code = reentry::run_control_t::EVENT_TAEM;
  double heading_err_rad = 0.0;
};

// Planar-Earth-free 3-DOF point-mass equations over a spherical non-rotating Earth.
void derivatives(const Vehicle& veh, const double* y, double sigma, double* dy) {
  const double r = y[0], lat = y[2], v = y[3], gam = y[4], chi = y[5];
  const double rho = kRho0_kgpm3 * std::exp(-(r - kEarthEquatorialRadius_m) / kScaleHeight_m);
  const double drag = 0.5 * rho * v * v * veh.ref_area_m2 * veh.cd / veh.mass_kg;
  const double lift = drag * veh.lift_over_drag;
  const double g = kMuEarth_m3ps2 / (r * r);
  dy[0] = v * std::sin(gam);
  dy[1] = v * std::cos(gam) * std::sin(chi) / (r * std::cos(lat));
  dy[2] = v * std::cos(gam) * std::cos(chi) / r;
  dy[3] = -drag - g * std::sin(gam);
  dy[4] = (lift * std::cos(sigma) - (g - v * v / r) * std::cos(gam)) / v;
  dy[5] = lift * std::sin(sigma) / (v * std::cos(gam)) + v * std::cos(gam) * std::sin(chi) * std::tan(lat) / r;
}

Sample sample_of(const Vehicle& veh, const double* y, double t, double sigma, double alpha, double heat_load) {
  Sample s{};
  s.t_s = t;
  s.r_m = y[0];
  s.h_m = y[0] - kEarthEquatorialRadius_m;
  s.lon_rad = y[1];
  s.lat_rad = y[2];
  s.V_mps = y[3];
  s.gamma_rad = y[4];
  s.chi_rad = y[5];
  s.mach = y[3] / 295.0;
  s.sigma_rad = sigma;
  s.alpha_rad = alpha;
  const double rho = kRho0_kgpm3 * std::exp(-(y[0] - kEarthEquatorialRadius_m) / kScaleHeight_m);
  s.q_Pa = 0.5 * rho * y[3] * y[3];
  s.D_mps2 = s.q_Pa * veh.ref_area_m2 * veh.cd / veh.mass_kg;
  s.L_mps2 = s.D_mps2 * veh.lift_over_drag;
  s.qdot_Wpm2 = 1.7415e-4 * std::sqrt(rho / veh.nose_radius_m) * std::pow(y[3], 3.0);  // Sutton-Graves
  s.Q_Jpm2 = heat_load;
  s.n_g = std::hypot(s.D_mps2, s.L_mps2) / kStandardGravity_mps2;
  s.E_Jpkg = 0.5 * y[3] * y[3] - kMuEarth_m3ps2 / y[0] + kMuEarth_m3ps2 / kEarthEquatorialRadius_m;
  s.heading_to_taem_rad = 0.02 * std::sin(0.01 * t);
  return s;
}

template <class Msg>
void write(lcm::LogFile& log, const std::string& channel, const Msg& msg, int64_t wall_us) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  lcm::LogEvent ev{};
  ev.timestamp = wall_us;
  ev.channel = channel;
  ev.datalen = static_cast<int32_t>(buf.size());
  ev.data = buf.data();
  log.writeEvent(&ev);
}

reentry::plan_t plan_from(const std::vector<Sample>& traj, size_t from, int seq, int16_t n_points, double e_entry,
                          double drag_scale) {
  reentry::plan_t p{};
  p.utime = static_cast<int64_t>(std::llround(traj[from].t_s * 1e6));
  p.tick = static_cast<int64_t>(from);
  p.seq = seq;
  p.n_points = n_points;
  const double e0 = traj[from].E_Jpkg, e1 = traj.back().E_Jpkg;
  size_t j = from;
  for (int i = 0; i < reentry::plan_t::MAX_POINTS; ++i) {
    if (i >= n_points) continue;  // unused tail stays zero
    const double e = e0 + (e1 - e0) * i / (n_points - 1);
    while (j + 1 < traj.size() - 1 && traj[j + 1].E_Jpkg > e) ++j;
    const Sample& a = traj[j];
    const Sample& b = traj[std::min(j + 1, traj.size() - 1)];
    const double w = (a.E_Jpkg == b.E_Jpkg) ? 0.0 : (a.E_Jpkg - e) / (a.E_Jpkg - b.E_Jpkg);
    auto lerp = [w](double x, double y) { return x + w * (y - x); };
    p.e_norm[i] = e / e_entry;
    p.drag_mps2[i] = drag_scale * lerp(a.D_mps2, b.D_mps2);
    p.radius_m[i] = lerp(a.r_m, b.r_m);
    p.gamma_rad[i] = lerp(a.gamma_rad, b.gamma_rad);
    p.sigma_rad[i] = lerp(a.sigma_rad, b.sigma_rad);
    p.alpha_rad[i] = lerp(a.alpha_rad, b.alpha_rad);
  }
  p.reversal_e_norm = 0.55;
  p.dc_mps2 = 9.0 * drag_scale;
  p.e1_norm = 0.8;
  p.e2_norm = 0.3;
  p.trajectory_length_m = 4.0e6;
  p.crossrange_err_m = 120.0 * seq;
  p.downrange_err_m = -300.0 * seq;
  p.iterations = 3 + seq;
  p.status = 0;
  p.converged = 1;
  p.compute_ms = 12.5 * seq;
  return p;
}

// The trajectory: RK4 over each tick until about TAEM (20 km or 760 m/s).
std::vector<Sample> fly(const Vehicle& veh, int ticks, double dt_s) {
  const double alpha_rad = 40.0 * M_PI / 180.0;
  // Entry interface: 121.9 km, 7400 m/s, -1.2 deg, heading 60 deg, near Vandenberg.
  double y[6] = {kEarthEquatorialRadius_m + 121.9e3, -120.6 * M_PI / 180.0, 34.7 * M_PI / 180.0, 7400.0, -1.2 * M_PI / 180.0,
                 60.0 * M_PI / 180.0};
  std::vector<Sample> traj;
  double heat_load = 0.0;
  for (int k = 0; k < ticks; ++k) {
    const double t = k * dt_s;
    // Bank 65 deg right, reversal to the left at 40% of the run: a typical lateral profile.
    const double sigma = (k < (ticks * 2) / 5 ? 1.0 : -1.0) * 65.0 * M_PI / 180.0;
    traj.push_back(sample_of(veh, y, t, sigma, alpha_rad, heat_load));
    const int sub = 20;  // RK4 sub-steps per tick
    const double h = dt_s / sub;
    for (int s = 0; s < sub; ++s) {
      double k1[6], k2[6], k3[6], k4[6], tmp[6];
      derivatives(veh, y, sigma, k1);
      for (int i = 0; i < 6; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
      derivatives(veh, tmp, sigma, k2);
      for (int i = 0; i < 6; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
      derivatives(veh, tmp, sigma, k3);
      for (int i = 0; i < 6; ++i) tmp[i] = y[i] + h * k3[i];
      derivatives(veh, tmp, sigma, k4);
      for (int i = 0; i < 6; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
      heat_load += h * sample_of(veh, y, t, sigma, alpha_rad, 0.0).qdot_Wpm2;
    }
    if (y[0] - kEarthEquatorialRadius_m < 20e3 || y[3] < 760.0) break;  // about TAEM
  }
  // A range to go that shrinks with the energy (the aim point 4000 km ahead).
  const double e_entry = traj.front().E_Jpkg;
  for (Sample& s : traj) s.range_to_taem_m = std::max(0.0, 4.0e6 - 6.0e6 * (1.0 - s.E_Jpkg / e_entry));
  return traj;
}

reentry::nav_state_t nav_of(const Sample& s, std::int64_t k, bool last) {
  reentry::nav_state_t nav{};
  reentry::stamp(nav, s.t_s, k);
  nav.t_s = s.t_s;
  const double theta = kEarthRate_radps * s.t_s;
  const double lon_i = s.lon_rad + theta;
  const double cl = std::cos(s.lat_rad);
  nav.position_I_m[0] = s.r_m * cl * std::cos(lon_i);
  nav.position_I_m[1] = s.r_m * cl * std::sin(lon_i);
  nav.position_I_m[2] = s.r_m * std::sin(s.lat_rad);
  // Local north-east-down to inertial for the velocity direction.
  const double vn = s.V_mps * std::cos(s.gamma_rad) * std::cos(s.chi_rad);
  const double ve = s.V_mps * std::cos(s.gamma_rad) * std::sin(s.chi_rad);
  const double vu = s.V_mps * std::sin(s.gamma_rad);
  const double sl = std::sin(s.lat_rad), so = std::sin(lon_i), co = std::cos(lon_i);
  nav.velocity_I_mps[0] = vu * cl * co - vn * sl * co - ve * so;
  nav.velocity_I_mps[1] = vu * cl * so - vn * sl * so + ve * co;
  nav.velocity_I_mps[2] = vu * sl + vn * cl;
  for (int i = 0; i < 3; ++i) nav.aero_accel_I_mps2[i] = -s.D_mps2 * nav.velocity_I_mps[i] / s.V_mps;
  nav.earth_rotation_angle_rad = theta;
  nav.sim_flags = last ? reentry::nav_state_t::SIM_FLAGS_END_PENDING : 0;
  return nav;
}

// 3 events of a type that is not ours (an arbitrary fingerprint and payload) at ticks 10-12, and
// 2 TRUTH events cut short (decode() must fail) at ticks 20-21.
void write_foreign(lcm::LogFile& log, std::size_t k, const reentry::truth_telemetry_t& tr, int64_t wall) {
  std::vector<uint8_t> junk;
  lcm::LogEvent ev{};
  if (k >= 10 && k < 13) {
    junk.resize(40 + k);
    for (size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<uint8_t>(0x5A ^ (i * 37 + k));
    ev.timestamp = wall + 7;
    ev.channel = "FOREIGN";
    ev.datalen = static_cast<int32_t>(junk.size());
  } else if (k == 20 || k == 21) {
    junk.resize(static_cast<size_t>(tr.getEncodedSize()));
    tr.encode(junk.data(), 0, static_cast<int>(junk.size()));
    ev.timestamp = wall + 8;
    ev.channel = "TRUTH";
    ev.datalen = static_cast<int32_t>(junk.size() / 2);
  } else {
    return;
  }
  ev.data = junk.data();
  log.writeEvent(&ev);
}

// The guidance side of one tick: command, status, tracker state (synthetic values).
void write_guidance(lcm::LogFile& log, const std::vector<Sample>& traj, std::size_t k, std::size_t replan_tick,
                    int64_t wall) {
  const Sample& s = traj[k];
  const int plan_seq = k < replan_tick ? 1 : 2;
  reentry::guidance_cmd_t cmd{};
  reentry::stamp(cmd, s.t_s, static_cast<int64_t>(k));
  cmd.alpha_rad = s.alpha_rad;
  cmd.sigma_rad = s.sigma_rad + 0.03 * std::sin(0.05 * s.t_s);
  cmd.mode = reentry::guidance_cmd_t::MODE_REVERSAL;
  cmd.plan_seq = plan_seq;
  write(log, "GUIDANCE_CMD", cmd, wall + 20);

  reentry::guidance_status_t st{};
  reentry::stamp(st, s.t_s, static_cast<int64_t>(k));
  st.phase = reentry::guidance_status_t::PHASE_REVERSAL;
  st.cycle_us_last = 40.0 + (k % 7);
  st.cycle_us_max = 46.0;
  st.planner_runs = plan_seq;
  st.planner_ms_last = 12.5 * plan_seq;
  st.planner_ms_max = 25.0;
  st.plan_age_s = s.t_s - traj[k < replan_tick ? 0 : replan_tick].t_s;
  st.plan_seq = plan_seq;
  st.drag_err_mps2 = 0.01 * s.D_mps2;
  write(log, "GUIDANCE_STATUS", st, wall + 25);

  reentry::tracker_status_t ts{};
  reentry::stamp(ts, s.t_s, static_cast<int64_t>(k));
  ts.phase = k < replan_tick ? reentry::tracker_status_t::PHASE_PLANNED : reentry::tracker_status_t::PHASE_HEADING_CORRIDOR;
  ts.drag_ref_mps2 = 0.99 * s.D_mps2;
  ts.drag_err_mps2 = 0.01 * s.D_mps2;
  ts.drag_ratio = 1.0;
  ts.lift_over_drag_ratio = 1.0;
  ts.corridor_half_width_rad = k < replan_tick ? 0.0 : 0.1;
  write(log, "TRACKER_STATUS", ts, wall + 27);
}

// Every channel of every tick, then END_OF_RUN.
void write_run(lcm::LogFile& log, const std::vector<Sample>& traj, bool foreign) {
  const int64_t wall0_us = 1700000000000000LL;
  const size_t replan_tick = traj.size() / 2;
  const double e_entry = traj.front().E_Jpkg;
  RunSummary summary;
  for (size_t k = 0; k < traj.size(); ++k) {
    const Sample& s = traj[k];
    const int64_t wall = wall0_us + std::llround(s.t_s * 1e6) + 137;  // logger receive time, a little later
    summary.maxima.qdot_Wpm2 = std::max(summary.maxima.qdot_Wpm2, s.qdot_Wpm2);
    summary.maxima.n_g = std::max(summary.maxima.n_g, s.n_g);
    summary.maxima.q_Pa = std::max(summary.maxima.q_Pa, s.q_Pa);
    write(log, "NAV_STATE", nav_of(s, static_cast<int64_t>(k), k + 1 == traj.size()), wall);
    reentry::truth_telemetry_t tr{};
    reentry::stamp(tr, s.t_s, static_cast<int64_t>(k));
    reentry::fill(tr, s);
    write(log, "TRUTH", tr, wall + 5);
    if (foreign) write_foreign(log, k, tr, wall);
    if (k == 0 || k == replan_tick) {
      const reentry::plan_t plan = k == 0 ? plan_from(traj, 0, 1, 201, e_entry, 1.03)
                                          : plan_from(traj, replan_tick, 2, 120, e_entry, 0.99);
      write(log, "PLAN", plan, wall + 10);
    }
    write_guidance(log, traj, k, replan_tick, wall);
  }
  summary.final_state = traj.back();
  reentry::run_control_t rc{};
  reentry::stamp(rc, summary.final_state.t_s, static_cast<int64_t>(traj.size()));  // as the simulator: the end tick has no sample
  reentry::fill(rc, summary, EndOfRun{});
  write(log, "RUN_CONTROL", rc, wall0_us + rc.utime + 1000);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Write a synthetic reentry run log (for the log tool tests only)"};
  std::string out_path;
  int ticks = 400;
  double dt_s = 2.0;
  app.add_option("out", out_path, "log file to write")->required();
  app.add_option("--ticks", ticks, "number of GNC ticks")->check(CLI::Range(10, 100000));
  app.add_option("--dt", dt_s, "tick period [s]")->check(CLI::Range(0.01, 10.0));
  bool foreign = false;
  app.add_flag("--foreign", foreign,
               "also write 3 events of an unknown type (channel FOREIGN) and 2 undecodable TRUTH events");
  CLI11_PARSE(app, argc, argv);

  const std::vector<Sample> traj = fly(Vehicle{}, ticks, dt_s);
  lcm::LogFile log(out_path, "w");
  if (!log.good()) {
    std::fprintf(stderr, "synth_log: cannot write '%s'\n", out_path.c_str());
    return 1;
  }
  write_run(log, traj, foreign);
  const Sample& last = traj.back();
  std::printf("synth_log: %zu ticks, final h %.1f km, V %.0f m/s -> %s\n", traj.size(), last.h_m * 1e-3, last.V_mps,
              out_path.c_str());
  return 0;
}
