// reentry_synth_log: writes a short synthetic but physically consistent run.lcm for the tool tests
// (used only by tests/tools; the SIL writes the real logs). A point mass with constant L/D flies
// through an exponential atmosphere over a spherical, non-rotating Earth; all channels the SIL
// publishes are written with lcm::LogFile, the messages encoded by the generated types.
#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <reentry/guidance_cmd_t.hpp>
#include <reentry/guidance_status_t.hpp>
#include <reentry/tracker_status_t.hpp>
#include <reentry/nav_state_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/run_control_t.hpp>
#include <reentry/truth_telemetry_t.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

constexpr double kMu_m3ps2 = 3.986004418e14;
constexpr double kEarthRadius_m = 6378137.0;
constexpr double kOmegaEarth_radps = 7.292115e-5;
constexpr double kRho0_kgpm3 = 1.225;
constexpr double kScaleHeight_m = 7050.0;
constexpr double kG0_mps2 = 9.80665;
constexpr double kPi = 3.14159265358979323846;

struct Vehicle {
  double mass_kg = 37000.0;
  double ref_area_m2 = 149.0;
  double cd = 0.55;
  double lift_over_drag = 1.1;
  double nose_radius_m = 0.8;
};

struct Sample {
  double t_s, r_m, lon_rad, lat_rad, v_mps, gamma_rad, chi_rad;
  double sigma_rad, alpha_rad, drag_mps2, lift_mps2, q_Pa, heat_Wpm2, heat_load_Jpm2, g_load, energy_Jpkg;
};

// Planar-Earth-free 3-DOF point-mass equations over a spherical non-rotating Earth.
void derivatives(const Vehicle& veh, const double* y, double sigma, double* dy) {
  const double r = y[0], lat = y[2], v = y[3], gam = y[4], chi = y[5];
  const double rho = kRho0_kgpm3 * std::exp(-(r - kEarthRadius_m) / kScaleHeight_m);
  const double drag = 0.5 * rho * v * v * veh.ref_area_m2 * veh.cd / veh.mass_kg;
  const double lift = drag * veh.lift_over_drag;
  const double g = kMu_m3ps2 / (r * r);
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
  s.lon_rad = y[1];
  s.lat_rad = y[2];
  s.v_mps = y[3];
  s.gamma_rad = y[4];
  s.chi_rad = y[5];
  s.sigma_rad = sigma;
  s.alpha_rad = alpha;
  const double rho = kRho0_kgpm3 * std::exp(-(y[0] - kEarthRadius_m) / kScaleHeight_m);
  s.q_Pa = 0.5 * rho * y[3] * y[3];
  s.drag_mps2 = s.q_Pa * veh.ref_area_m2 * veh.cd / veh.mass_kg;
  s.lift_mps2 = s.drag_mps2 * veh.lift_over_drag;
  s.heat_Wpm2 = 1.7415e-4 * std::sqrt(rho / veh.nose_radius_m) * std::pow(y[3], 3.0);  // Sutton-Graves
  s.heat_load_Jpm2 = heat_load;
  s.g_load = std::hypot(s.drag_mps2, s.lift_mps2) / kG0_mps2;
  s.energy_Jpkg = 0.5 * y[3] * y[3] - kMu_m3ps2 / y[0] + kMu_m3ps2 / kEarthRadius_m;
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
  const double e0 = traj[from].energy_Jpkg, e1 = traj.back().energy_Jpkg;
  size_t j = from;
  for (int i = 0; i < reentry::plan_t::MAX_POINTS; ++i) {
    if (i >= n_points) continue;  // unused tail stays zero
    const double e = e0 + (e1 - e0) * i / (n_points - 1);
    while (j + 1 < traj.size() - 1 && traj[j + 1].energy_Jpkg > e) ++j;
    const Sample& a = traj[j];
    const Sample& b = traj[std::min(j + 1, traj.size() - 1)];
    const double w = (a.energy_Jpkg == b.energy_Jpkg) ? 0.0 : (a.energy_Jpkg - e) / (a.energy_Jpkg - b.energy_Jpkg);
    auto lerp = [w](double x, double y) { return x + w * (y - x); };
    p.e_norm[i] = e / e_entry;
    p.drag_mps2[i] = drag_scale * lerp(a.drag_mps2, b.drag_mps2);
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

  const Vehicle veh;
  const double alpha_rad = 40.0 * kPi / 180.0;
  // Entry interface: 121.9 km, 7400 m/s, -1.2 deg, heading 60 deg, near Vandenberg.
  double y[6] = {kEarthRadius_m + 121.9e3, -120.6 * kPi / 180.0, 34.7 * kPi / 180.0, 7400.0, -1.2 * kPi / 180.0,
                 60.0 * kPi / 180.0};
  std::vector<Sample> traj;
  double heat_load = 0.0;
  for (int k = 0; k < ticks; ++k) {
    const double t = k * dt_s;
    // Bank 65 deg right, reversal to the left at 40% of the run: a typical lateral profile.
    const double sigma = (k < (ticks * 2) / 5 ? 1.0 : -1.0) * 65.0 * kPi / 180.0;
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
      heat_load += h * sample_of(veh, y, t, sigma, alpha_rad, 0.0).heat_Wpm2;
    }
    if (y[0] - kEarthRadius_m < 20e3 || y[3] < 760.0) break;  // about TAEM
  }
  const double e_entry = traj.front().energy_Jpkg;

  lcm::LogFile log(out_path, "w");
  if (!log.good()) {
    std::fprintf(stderr, "synth_log: cannot write '%s'\n", out_path.c_str());
    return 1;
  }
  const int64_t wall0_us = 1700000000000000LL;
  const size_t replan_tick = traj.size() / 2;
  double max_heat = 0, max_g = 0, max_q = 0;
  for (size_t k = 0; k < traj.size(); ++k) {
    const Sample& s = traj[k];
    const int64_t utime = static_cast<int64_t>(std::llround(s.t_s * 1e6));
    const int64_t wall = wall0_us + utime + 137;  // logger receive time, a little later
    const int plan_seq = k < replan_tick ? 1 : 2;
    max_heat = std::max(max_heat, s.heat_Wpm2);
    max_g = std::max(max_g, s.g_load);
    max_q = std::max(max_q, s.q_Pa);

    reentry::nav_state_t nav{};
    nav.utime = utime;
    nav.tick = static_cast<int64_t>(k);
    nav.t_s = s.t_s;
    const double theta = kOmegaEarth_radps * s.t_s;
    const double lon_i = s.lon_rad + theta;
    const double cl = std::cos(s.lat_rad);
    nav.position_I_m[0] = s.r_m * cl * std::cos(lon_i);
    nav.position_I_m[1] = s.r_m * cl * std::sin(lon_i);
    nav.position_I_m[2] = s.r_m * std::sin(s.lat_rad);
    // Local north-east-down to inertial for the velocity direction.
    const double vn = s.v_mps * std::cos(s.gamma_rad) * std::cos(s.chi_rad);
    const double ve = s.v_mps * std::cos(s.gamma_rad) * std::sin(s.chi_rad);
    const double vu = s.v_mps * std::sin(s.gamma_rad);
    const double sl = std::sin(s.lat_rad), so = std::sin(lon_i), co = std::cos(lon_i);
    nav.velocity_I_mps[0] = vu * cl * co - vn * sl * co - ve * so;
    nav.velocity_I_mps[1] = vu * cl * so - vn * sl * so + ve * co;
    nav.velocity_I_mps[2] = vu * sl + vn * cl;
    for (int i = 0; i < 3; ++i) nav.aero_accel_I_mps2[i] = -s.drag_mps2 * nav.velocity_I_mps[i] / s.v_mps;
    nav.earth_rotation_angle_rad = theta;
    nav.sim_flags = (k + 1 == traj.size()) ? 1 : 0;
    write(log, "NAV_STATE", nav, wall);

    reentry::truth_telemetry_t tr{};
    tr.utime = utime;
    tr.tick = static_cast<int64_t>(k);
    tr.t_s = s.t_s;
    tr.altitude_m = s.r_m - kEarthRadius_m;
    tr.latitude_rad = s.lat_rad;
    tr.longitude_rad = s.lon_rad;
    tr.velocity_mps = s.v_mps;
    tr.gamma_rad = s.gamma_rad;
    tr.heading_rad = s.chi_rad;
    tr.mach = s.v_mps / 295.0;
    tr.q_Pa = s.q_Pa;
    tr.heat_flux_Wpm2 = s.heat_Wpm2;
    tr.heat_load_Jpm2 = s.heat_load_Jpm2;
    tr.load_factor_g = s.g_load;
    tr.drag_mps2 = s.drag_mps2;
    tr.lift_mps2 = s.lift_mps2;
    tr.energy_Jpkg = s.energy_Jpkg;
    tr.alpha_rad = s.alpha_rad;
    tr.sigma_rad = s.sigma_rad;
    tr.range_to_taem_m = std::max(0.0, 4.0e6 - 6.0e6 * (1.0 - s.energy_Jpkg / e_entry));
    tr.heading_to_taem_rad = 0.02 * std::sin(0.01 * s.t_s);
    write(log, "TRUTH", tr, wall + 5);

    if (foreign && k >= 10 && k < 13) {
      // A message type that is not ours: an arbitrary fingerprint and payload.
      std::vector<uint8_t> junk(40 + k);
      for (size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<uint8_t>(0x5A ^ (i * 37 + k));
      lcm::LogEvent ev{};
      ev.timestamp = wall + 7;
      ev.channel = "FOREIGN";
      ev.datalen = static_cast<int32_t>(junk.size());
      ev.data = junk.data();
      log.writeEvent(&ev);
    }
    if (foreign && (k == 20 || k == 21)) {
      // Our TRUTH fingerprint but the payload cut short: decode() must fail.
      std::vector<uint8_t> buf(static_cast<size_t>(tr.getEncodedSize()));
      tr.encode(buf.data(), 0, static_cast<int>(buf.size()));
      lcm::LogEvent ev{};
      ev.timestamp = wall + 8;
      ev.channel = "TRUTH";
      ev.datalen = static_cast<int32_t>(buf.size() / 2);
      ev.data = buf.data();
      log.writeEvent(&ev);
    }

    if (k == 0 || k == replan_tick) {
      const reentry::plan_t plan = k == 0 ? plan_from(traj, 0, 1, 201, e_entry, 1.03)
                                          : plan_from(traj, replan_tick, 2, 120, e_entry, 0.99);
      write(log, "PLAN", plan, wall + 10);
    }

    reentry::guidance_cmd_t cmd{};
    cmd.utime = utime;
    cmd.tick = static_cast<int64_t>(k);
    cmd.alpha_rad = s.alpha_rad;
    cmd.beta_rad = 0.0;
    cmd.sigma_rad = s.sigma_rad + 0.03 * std::sin(0.05 * s.t_s);
    cmd.mode = 2;
    cmd.plan_seq = plan_seq;
    cmd.health_flags = 0;
    write(log, "GUIDANCE_CMD", cmd, wall + 20);

    reentry::guidance_status_t st{};
    st.utime = utime;
    st.tick = static_cast<int64_t>(k);
    st.phase = 2;
    st.mode = 0;
    st.cycle_us_last = 40.0 + (k % 7);
    st.cycle_us_max = 46.0;
    st.planner_runs = plan_seq;
    st.planner_ms_last = 12.5 * plan_seq;
    st.planner_ms_max = 25.0;
    st.plan_age_s = s.t_s - traj[k < replan_tick ? 0 : replan_tick].t_s;
    st.plan_seq = plan_seq;
    st.drag_err_mps2 = 0.01 * s.drag_mps2;
    write(log, "GUIDANCE_STATUS", st, wall + 25);

    reentry::tracker_status_t ts{};
    ts.utime = utime;
    ts.tick = static_cast<int64_t>(k);
    ts.phase = static_cast<int8_t>(k < replan_tick ? 1 : 2);
    ts.drag_ref_mps2 = 0.99 * s.drag_mps2;
    ts.drag_err_mps2 = 0.01 * s.drag_mps2;
    ts.drag_ratio = 1.0;
    ts.lift_over_drag_ratio = 1.0;
    ts.corridor_half_width_rad = k < replan_tick ? 0.0 : 0.1;
    write(log, "TRACKER_STATUS", ts, wall + 27);
  }
  const Sample& last = traj.back();
  reentry::run_control_t rc{};
  rc.utime = static_cast<int64_t>(std::llround(last.t_s * 1e6));
  rc.tick = static_cast<int64_t>(traj.size());  // as the simulator: the end tick has no sample
  rc.command = reentry::run_control_t::END_OF_RUN;
  rc.event = reentry::run_control_t::EVENT_TAEM;
  rc.final_altitude_m = last.r_m - kEarthRadius_m;
  rc.final_velocity_mps = last.v_mps;
  rc.final_mach = last.v_mps / 295.0;
  rc.final_gamma_rad = last.gamma_rad;
  rc.final_heading_rad = last.chi_rad;
  rc.final_latitude_rad = last.lat_rad;
  rc.final_longitude_rad = last.lon_rad;
  rc.max_heat_flux_Wpm2 = max_heat;
  rc.heat_load_Jpm2 = last.heat_load_Jpm2;
  rc.max_load_factor_g = max_g;
  rc.max_q_Pa = max_q;
  rc.flight_time_s = last.t_s;
  write(log, "RUN_CONTROL", rc, wall0_us + rc.utime + 1000);
  std::printf("synth_log: %zu ticks, final h %.1f km, V %.0f m/s -> %s\n", traj.size(),
              (last.r_m - kEarthRadius_m) * 1e-3, last.v_mps, out_path.c_str());
  return 0;
}
