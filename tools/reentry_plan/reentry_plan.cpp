// reentry_plan --mission <name|file> [--profile-out plan.csv] [--drag-profile three_segment|smooth]
//              [--initial-drag actual|lmin]
// Plans from the mission's entry state (drag from the on-board models) and prints ONE JSON line.
#include "guidance/mission_adapter.hpp"
#include "guidance/alpha_profile_source.hpp"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <reentry/nav_state_t.hpp>

#include "nav/relative_state.hpp"
#include "physics/earth_constants.hpp"
#include <nlohmann/json.hpp>

#include <reentry/config/mission.hpp>

#include "planner/entry_planner.hpp"

namespace {
using reentry::physics::kDegPerRad;

bool write_profile_csv(const std::string& path, const reentry::fsw::ReferenceProfile& p) {
  std::ofstream out(path);
  if (!out) return false;
  out << "energy_Jpkg,e_norm,drag_mps2,drag_prime,drag_second,a_coef,b_coef,altitude_m,velocity_mps,"
         "gamma_deg,alpha_deg,lift_over_drag,sigma_deg,heading_deg,q_Pa\n";
  out.precision(10);
  for (int k = 0; k < p.n_points; ++k) {
    out << p.energy_Jpkg[k] << ',' << p.e_norm[k] << ',' << p.drag_mps2[k] << ',' << p.drag_prime[k] << ','
        << p.drag_second[k] << ',' << p.a_coef[k] << ',' << p.b_coef[k] << ','
        << p.radius_m[k] - reentry::fsw::kEarthRadius_m << ',' << p.velocity_mps[k] << ','
        << p.gamma_rad[k] * kDegPerRad << ',' << p.alpha_rad[k] * kDegPerRad << ',' << p.lift_over_drag[k] << ','
        << p.sigma_rad[k] * kDegPerRad << ',' << p.heading_rad[k] * kDegPerRad << ',' << p.dynamic_pressure_Pa[k] << '\n';
  }
  return static_cast<bool>(out);
}
struct Options {
  std::string mission_arg, profile_out, drag_profile, initial_drag, from_log;
  long long from_tick = -1;
};

/// The mission with the command line's overrides and its alpha profile resolved; "" or the error.
std::string load_mission(const Options& o, reentry::config::Mission& mission) {
  reentry::config::LoadResult loaded = reentry::config::load_mission(o.mission_arg);
  if (!loaded.ok) return loaded.error;
  mission = std::move(loaded.mission);
  if (!o.drag_profile.empty()) mission.guidance.drag_profile = o.drag_profile;
  if (!o.initial_drag.empty()) mission.guidance.initial_drag = o.initial_drag;
  return reentry::fsw::resolve_alpha_profile(mission);
}

/// The state of the logged NAV_STATE at the given tick; "" or the error.
std::string state_from_log(const std::string& path, long long tick, reentry::fsw::RelativeState& state) {
  lcm::LogFile log(path, "r");
  bool found = false;
  reentry::nav_state_t nav{};
  for (const lcm::LogEvent* ev = log.good() ? log.readNextEvent() : nullptr; ev != nullptr && !found;
       ev = log.readNextEvent()) {
    if (ev->channel != "NAV_STATE" || nav.decode(ev->data, 0, ev->datalen) < 0) continue;
    found = nav.tick == tick;
  }
  if (!found) return "no NAV_STATE with tick " + std::to_string(tick) + " in " + path;
  if (reentry::fsw::relative_state_from_nav(nav.t_s, nav.position_I_m, nav.velocity_I_mps, nav.aero_accel_I_mps2,
                                            nav.earth_rotation_angle_rad, state) != reentry::fsw::Status::kOk)
    return "invalid NAV_STATE at tick " + std::to_string(tick) + " in " + path;
  return "";
}

/// The one JSON line: the planner's diagnostics (thesis ch. 7 quantities) in degrees and km.
nlohmann::json plan_summary(const reentry::config::Mission& mission, reentry::fsw::Status status,
                            const reentry::fsw::PlannerDiagnostics& d, double e_entry_Jpkg, double plan_ms) {
  nlohmann::json j;
  j["mission"] = mission.name;
  j["drag_profile"] = mission.guidance.drag_profile;
  j["initial_drag"] = mission.guidance.initial_drag;
  j["converged"] = d.converged;
  j["iterations"] = d.iterations;
  j["status"] = reentry::fsw::to_string(status);
  j["b_mission_deg"] = d.b_mission_rad * kDegPerRad;
  j["A_mission_deg"] = d.a_mission_rad * kDegPerRad;
  j["chi_minus_A_deg"] = d.chi_minus_a_rad * kDegPerRad;
  j["initial_bank_sign"] = d.initial_bank_sign;
  j["S_initial_km"] = d.s_initial_m / 1e3;
  j["S_final_km"] = d.s_final_m / 1e3;
  j["Di_mps2"] = d.di_mps2;
  j["Dc_mps2"] = d.dc_mps2;
  j["Df_mps2"] = d.df_mps2;
  j["E1_norm"] = d.e1_Jpkg / e_entry_Jpkg;
  j["E2_norm"] = d.e2_Jpkg / e_entry_Jpkg;
  j["reversal_E_norm"] = d.reversal_energy_Jpkg / e_entry_Jpkg;
  j["crossrange_err_km"] = d.crossrange_err_m / 1e3;
  j["downrange_err_km"] = d.downrange_err_m / 1e3;
  j["clipped_points"] = d.clipped_points;
  j["bank_saturated_points"] = d.bank_saturated_points;
  j["ranging_blend"] = d.ranging_blend;
  j["reversal_evaluations"] = d.reversal_evaluations;
  j["plan_ms"] = plan_ms;
  return j;
}

int fail(const std::string& message) {
  std::cerr << "reentry_plan: " << message << '\n';
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Plan a reference drag/bank profile from the mission's entry interface (thesis ch. 7)"};
  Options o;
  app.add_option("--mission", o.mission_arg, "mission name (x33, horus, ...) or path to a .toml file")->required();
  app.add_option("--profile-out", o.profile_out, "write the planned profile as CSV");
  app.add_option("--from-log", o.from_log, "plan from a logged NAV_STATE instead of the entry interface (with --tick)");
  app.add_option("--tick", o.from_tick, "tick of the NAV_STATE in --from-log");
  app.add_option("--drag-profile", o.drag_profile, "three_segment or smooth (default: mission file)")
      ->check(CLI::IsMember({"three_segment", "smooth"}));
  app.add_option("--initial-drag", o.initial_drag, "actual or lmin (default: mission file)")
      ->check(CLI::IsMember({"actual", "lmin"}));
  CLI11_PARSE(app, argc, argv);

  reentry::config::Mission mission;
  if (const std::string error = load_mission(o, mission); !error.empty()) return fail(error);
  auto planner = std::make_unique<reentry::fsw::EntryPlanner>();  // large fixed arrays: not on the stack
  const reentry::fsw::Status init_status = init_from_mission(*planner, mission);
  if (init_status != reentry::fsw::Status::kOk)
    return fail(std::string("planner init failed: ") + reentry::fsw::to_string(init_status));
  reentry::fsw::RelativeState entry = planner->entry_state();
  if (!o.from_log.empty()) {
    if (const std::string error = state_from_log(o.from_log, o.from_tick, entry); !error.empty()) return fail(error);
  }

  auto profile = std::make_unique<reentry::fsw::ReferenceProfile>();
  const auto t0 = std::chrono::steady_clock::now();
  const reentry::fsw::Status status = planner->plan(entry, *profile);
  const auto t1 = std::chrono::steady_clock::now();
  nlohmann::json j = plan_summary(mission, status, planner->diagnostics(), planner->entry_energy_Jpkg(),
                                  std::chrono::duration<double, std::milli>(t1 - t0).count());
  if (!o.profile_out.empty()) {
    j["profile_out"] = o.profile_out;
    if (!write_profile_csv(o.profile_out, *profile)) {
      std::cout << j.dump() << std::endl;
      return fail("cannot write " + o.profile_out);
    }
  }
  std::cout << j.dump() << std::endl;
  return status == reentry::fsw::Status::kOk ? 0 : 1;
}
