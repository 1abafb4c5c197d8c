// The generated fill functions (<reentry/telemetry_fill.hpp>, from interfaces/*.lcm) against the
// interface as documented: every field lands in its own place, flags at the bit positions the
// messages have always used (tracker_status_t: bit 0 reversing, 1 final reversal done,
// 2 correction reversal done, 3 pull-out arrested, 4 saturated), enums by value, stamps in us.
#include <gtest/gtest.h>

#include <cmath>
#include <reentry/telemetry_fill.hpp>

#include "app/guidance_messages.hpp"
#include "app/guidance_node.hpp"
#include "sim_messages.hpp"

namespace reentry {
namespace {

using fsw::Phase;
using fsw::TrackerPhase;

fsw::TrackerTelemetry distinct_tracker_telemetry() {
  fsw::TrackerTelemetry t;
  t.phase = TrackerPhase::kTerminalRange;
  t.drag_ref_mps2 = 11.0;
  t.drag_err_mps2 = 12.0;
  t.drag_integral_mps = 13.0;
  t.omega_radps = 14.0;
  t.drag_ratio = 15.0;
  t.lift_over_drag_ratio = 16.0;
  t.corridor_half_width_rad = 17.0;
  t.heading_err_rad = 18.0;
  t.terminal_increment_mps2 = 19.0;
  t.time_to_go_s = 20.0;
  t.mean_bank_rad = 21.0;
  t.cross_track_m = 22.0;
  t.along_track_m = 23.0;
  return t;
}

TEST(TelemetryFill, TrackerStatusCarriesEveryFieldAndPacksTheFlagsAtTheirBits) {
  fsw::exec::CycleOutput out;
  out.t_s = 123.4567891;
  out.tick = 1234;
  out.tracker = distinct_tracker_telemetry();
  tracker_status_t m{};
  fsw::app::fill_tracker_status(out, m);
  EXPECT_EQ(m.utime, 123456789);
  EXPECT_EQ(m.tick, 1234);
  EXPECT_EQ(m.phase, 3);
  EXPECT_EQ(m.flags, 0);
  const double got[] = {m.drag_ref_mps2,     m.drag_err_mps2,   m.drag_integral_mps,       m.omega_radps,
                        m.drag_ratio,        m.lift_over_drag_ratio, m.corridor_half_width_rad, m.heading_err_rad,
                        m.terminal_increment_mps2, m.time_to_go_s, m.mean_bank_rad,          m.cross_track_m,
                        m.along_track_m};
  for (int i = 0; i < 13; ++i) EXPECT_EQ(got[i], 11.0 + i) << "field " << i << " in .lcm order";
  const struct {
    bool fsw::TrackerTelemetry::*flag;
    int bit;
  } bits[] = {{&fsw::TrackerTelemetry::reversing, 0},        {&fsw::TrackerTelemetry::final_reversal_done, 1},
              {&fsw::TrackerTelemetry::final_correction_done, 2}, {&fsw::TrackerTelemetry::pullout_arrested, 3},
              {&fsw::TrackerTelemetry::saturated, 4}};
  int all = 0;
  const fsw::exec::CycleOutput none = out;
  for (const auto& b : bits) {
    fsw::exec::CycleOutput one = none;
    one.tracker.*(b.flag) = true;
    fsw::app::fill_tracker_status(one, m);
    EXPECT_EQ(m.flags, 1 << b.bit) << "bit " << b.bit;
    out.tracker.*(b.flag) = true;
    all |= 1 << b.bit;
  }
  fsw::app::fill_tracker_status(out, m);
  EXPECT_EQ(m.flags, all);
}

TEST(TelemetryFill, CoreStructStartsAtTheDocumentedDefaults) {
  const fsw::TrackerTelemetry t;
  EXPECT_EQ(t.phase, TrackerPhase::kInitialDescent);
  EXPECT_EQ(t.drag_ratio, 1.0);  // @default: no estimate yet is the model itself
  EXPECT_EQ(t.lift_over_drag_ratio, 1.0);
  EXPECT_EQ(t.drag_err_mps2, 0.0);
  EXPECT_FALSE(t.reversing || t.final_reversal_done || t.final_correction_done || t.pullout_arrested || t.saturated);
}

TEST(TelemetryFill, CommandTakesTheCycleOutputAndThePhaseAsMode) {
  fsw::exec::CycleOutput out;
  out.t_s = 0.1;
  out.tick = 1;
  out.alpha_rad = 0.7;
  out.sigma_rad = -1.1;
  out.phase = Phase::kReversal;
  out.plan_seq = 7;
  out.health_flags = fsw::exec::kHealthNoPlan | fsw::exec::kHealthPlanWait;
  guidance_cmd_t c{};
  c.beta_rad = 9.0;
  fsw::app::fill_command(out, c);
  EXPECT_EQ(c.utime, 100000);
  EXPECT_EQ(c.tick, 1);
  EXPECT_EQ(c.alpha_rad, 0.7);
  EXPECT_EQ(c.sigma_rad, -1.1);
  EXPECT_EQ(c.beta_rad, 0.0);
  EXPECT_EQ(c.mode, 2);
  EXPECT_EQ(c.plan_seq, 7);
  EXPECT_EQ(c.health_flags, (1 << 4) | (1 << 7));
}

TEST(TelemetryFill, StatusTakesEachFieldFromItsOwner) {
  fsw::exec::CycleOutput out;
  out.phase = Phase::kTracking;
  out.plan_seq = 3;
  out.health_flags = 5;
  out.tracker.drag_err_mps2 = -0.25;
  out.tracker.heading_err_rad = 0.125;
  fsw::exec::ExecCounters c;
  c.cycle_us_last = 1.0;
  c.cycle_us_max = 2.0;
  c.plan_overruns = 3;
  c.planner_runs = 4;
  c.planner_ms_last = 5.0;
  c.planner_ms_max = 6.0;
  c.plan_latency_ms = 7.0;
  c.invalid_nav = 8;
  c.duplicate_ticks = 9;
  c.skipped_ticks = 10;
  c.plan_waits = 11;
  c.plan_wait_ms_last = 12.0;
  c.plan_wait_ms_max = 13.0;
  c.nav_rejected_tick = 14;
  fsw::app::AdapterStatus a;
  a.mode = fsw::app::RunMode::kReplay;
  a.jitter_us_last = 21.0;
  a.jitter_us_max = 22.0;
  a.cycle_overruns = 23;
  a.plan_age_s = 24.0;
  a.bad_messages = 25;
  a.bad_datagrams = 26;
  a.rx_kernel_drops = 27;
  a.log_dropped = 28;
  a.link_silent_ms = 29.0;
  guidance_status_t s{};
  reentry::fill(s, out, c, a);
  EXPECT_EQ(s.phase, 1);
  EXPECT_EQ(s.mode, 2);
  EXPECT_EQ(s.health_flags, 5);
  EXPECT_EQ(s.plan_seq, 3);
  EXPECT_EQ(s.drag_err_mps2, -0.25);
  EXPECT_EQ(s.heading_err_rad, 0.125);
  const double exec_fields[] = {s.cycle_us_last,   s.cycle_us_max,      static_cast<double>(s.plan_overruns),
                                static_cast<double>(s.planner_runs),  s.planner_ms_last, s.planner_ms_max,
                                s.plan_latency_ms, static_cast<double>(s.invalid_nav), static_cast<double>(s.duplicate_ticks),
                                static_cast<double>(s.skipped_ticks), static_cast<double>(s.plan_waits),
                                s.plan_wait_ms_last, s.plan_wait_ms_max, static_cast<double>(s.nav_rejected_tick)};
  for (int i = 0; i < 14; ++i) EXPECT_EQ(exec_fields[i], 1.0 + i) << "executive field " << i;
  const double own_fields[] = {s.jitter_us_last, s.jitter_us_max, static_cast<double>(s.cycle_overruns), s.plan_age_s,
                               static_cast<double>(s.bad_messages), static_cast<double>(s.bad_datagrams),
                               static_cast<double>(s.rx_kernel_drops), static_cast<double>(s.log_dropped),
                               s.link_silent_ms};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(own_fields[i], 21.0 + i) << "process field " << i;
}

truth::TruthSample distinct_truth_sample() {
  truth::TruthSample t;
  double* const fields[] = {&t.t_s,    &t.h_m,       &t.r_m,        &t.lat_rad,       &t.lon_rad,    &t.V_mps,
                            &t.gamma_rad, &t.chi_rad, &t.airspeed_mps, &t.mach,        &t.rho_kgpm3,  &t.q_Pa,
                            &t.qdot_Wpm2, &t.Q_Jpm2,  &t.n_g,        &t.D_mps2,        &t.L_mps2,     &t.E_Jpkg,
                            &t.alpha_rad, &t.sigma_rad, &t.flap_rad, &t.elevon_rad,    &t.q_alpha_Pa_rad,
                            &t.range_to_taem_m, &t.heading_to_taem_rad};
  double v = 100.0;
  for (double* f : fields) *f = v++;
  return t;
}

TEST(TelemetryFill, TruthTelemetryMapsTheSimulatorSample) {
  const truth::TruthSample t = distinct_truth_sample();
  truth_telemetry_t m{};
  truth::fill_truth(t, 42, 7, m);
  EXPECT_EQ(m.utime, 42);
  EXPECT_EQ(m.tick, 7);
  const std::pair<double, double> pairs[] = {
      {m.t_s, t.t_s},           {m.altitude_m, t.h_m},           {m.latitude_rad, t.lat_rad},
      {m.longitude_rad, t.lon_rad}, {m.velocity_mps, t.V_mps},    {m.gamma_rad, t.gamma_rad},
      {m.heading_rad, t.chi_rad}, {m.mach, t.mach},               {m.q_Pa, t.q_Pa},
      {m.heat_flux_Wpm2, t.qdot_Wpm2}, {m.heat_load_Jpm2, t.Q_Jpm2}, {m.load_factor_g, t.n_g},
      {m.drag_mps2, t.D_mps2},   {m.lift_mps2, t.L_mps2},         {m.energy_Jpkg, t.E_Jpkg},
      {m.alpha_rad, t.alpha_rad}, {m.sigma_rad, t.sigma_rad},     {m.range_to_taem_m, t.range_to_taem_m},
      {m.heading_to_taem_rad, t.heading_to_taem_rad}};
  for (const auto& [got, want] : pairs) EXPECT_EQ(got, want);
}

TEST(TelemetryFill, NavStateCarriesTheInertialState) {
  truth::NavSample n;
  n.t_s = 2.5;
  n.r_I_m = {1.0, 2.0, 3.0};
  n.v_I_mps = {4.0, 5.0, 6.0};
  n.aero_accel_I_mps2 = {7.0, 8.0, 9.0};
  n.earth_rotation_angle_rad = 0.5;
  nav_state_t m{};
  m.sim_flags = 3;
  truth::fill_nav(n, 25, m);
  EXPECT_EQ(m.utime, 2500000);
  EXPECT_EQ(m.tick, 25);
  EXPECT_EQ(m.t_s, 2.5);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m.position_I_m[i], 1.0 + i);
    EXPECT_EQ(m.velocity_I_mps[i], 4.0 + i);
    EXPECT_EQ(m.aero_accel_I_mps2[i], 7.0 + i);
  }
  EXPECT_EQ(m.earth_rotation_angle_rad, 0.5);
  EXPECT_EQ(m.sim_flags, 0);
}

TEST(TelemetryFill, EndOfRunSummarisesTheRun) {
  truth::RunSummary s;
  s.event = truth::SimEvent::kGroundImpact;
  s.final_state = distinct_truth_sample();
  s.final_state.chi_rad = 3.0;
  s.maxima.qdot_Wpm2 = 1.0e6;
  s.maxima.n_g = 2.5;
  s.maxima.q_Pa = 1.2e4;
  s.maxima.q_alpha_Pa_rad = 9.0e3;
  run_control_t rc{};
  truth::fill_end_of_run(s, 99, truth::end_event_code(s.event), -3.0, rc);
  const truth::TruthSample& f = s.final_state;
  EXPECT_EQ(rc.utime, std::llround(f.t_s * 1e6));
  EXPECT_EQ(rc.tick, 99);
  EXPECT_EQ(rc.command, +run_control_t::END_OF_RUN);  // + : a value (lcm-gen constants have no definition)
  EXPECT_EQ(rc.event, +run_control_t::EVENT_GROUND);
  EXPECT_EQ(rc.final_altitude_m, f.h_m);
  EXPECT_EQ(rc.final_velocity_mps, f.V_mps);
  EXPECT_EQ(rc.final_mach, f.mach);
  EXPECT_EQ(rc.final_gamma_rad, f.gamma_rad);
  EXPECT_EQ(rc.final_heading_rad, 3.0);
  EXPECT_EQ(rc.final_latitude_rad, f.lat_rad);
  EXPECT_EQ(rc.final_longitude_rad, f.lon_rad);
  EXPECT_EQ(rc.taem_miss_m, f.range_to_taem_m);
  EXPECT_NEAR(rc.heading_err_rad, 6.0 - 2.0 * M_PI, 1e-12);  // 3 - (-3) wrapped into (-pi, pi]
  EXPECT_EQ(rc.max_heat_flux_Wpm2, 1.0e6);
  EXPECT_EQ(rc.heat_load_Jpm2, f.Q_Jpm2);
  EXPECT_EQ(rc.max_load_factor_g, 2.5);
  EXPECT_EQ(rc.max_q_Pa, 1.2e4);
  EXPECT_EQ(rc.max_q_alpha_Pa_rad, 9.0e3);
  EXPECT_EQ(rc.flight_time_s, f.t_s);
}

}  // namespace
}  // namespace reentry
