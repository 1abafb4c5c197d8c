// reentry_alpha_plan --mission <name|file> [--heating-pct 30] [--ranging-pct 50]
//   [--heating-switch-pct 0] [--taem-switch-pct 100] [--out alpha.csv] [--corridor-out corridor.csv]
//
// Plans an angle-of-attack profile (thesis ch. 6) and prints one JSON line:
//   {"mission","status","alpha_entry_deg","alpha_taem_deg","alpha_min_deg","alpha_max_deg",
//    "corridor_closed_points","extraction_clamped_points","path_violation_points","v_intersection_mps","v_heating_switch_mps",
//    "v_taem_switch_mps","dv_taem_mps","profile_points"}
// --out CSV columns:          energy_norm (E/E_entry, (7.8)), alpha_deg
//   (directly usable as [alpha_profile] energy / alpha_deg of a mission file)
// --corridor-out CSV columns: velocity_mps, h_glide_cl_max_m, h_glide_ld_max_m, h_heat_flux_m,
//   h_load_factor_cl_max_m, h_load_factor_ld_max_m, h_q_alpha_cl_max_m, h_q_alpha_ld_max_m,
//   h_dynamic_pressure_m, h_lower_m, closed (0/1), phase (0 heating, 1 ranging, 2 taem), h_path_m,
//   alpha_cl_max_deg, alpha_ld_max_deg, alpha_extracted_deg, alpha_deg, energy_norm,
//   heat_flux_Wpm2, load_factor_g, q_alpha_Pa_rad, dynamic_pressure_Pa (on the path), violation (0/1)
//   Heights in m; a constraint without limit or never violated shows 0.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "guidance/mission_adapter.hpp"
#include "alpha_planner/alpha_planner.hpp"
#include "physics/earth_constants.hpp"
#include "reentry/config/mission.hpp"

namespace {
using reentry::physics::kDegPerRad;
reentry::fsw::AlphaPlanner g_planner;   // large: static storage
reentry::fsw::AlphaPlanResult g_result;

/// fclose's verdict joined with the stream's: false when any byte was not written.
bool close_ok(std::FILE* f) {
  const bool wrote = std::ferror(f) == 0;
  return std::fclose(f) == 0 && wrote;
}

bool write_profile_csv(const std::string& path, const reentry::fsw::AlphaPlanResult& r) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  std::fprintf(f, "energy_norm,alpha_deg\n");
  for (int i = 0; i < r.n_profile; ++i)
    std::fprintf(f, "%.9f,%.6f\n", r.profile_energy_norm[i], r.profile_alpha_rad[i] * kDegPerRad);
  return close_ok(f);
}

bool write_corridor_csv(const std::string& path, const reentry::fsw::AlphaPlanResult& r) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  std::fprintf(f,
               "velocity_mps,h_glide_cl_max_m,h_glide_ld_max_m,h_heat_flux_m,h_load_factor_cl_max_m,"
               "h_load_factor_ld_max_m,h_q_alpha_cl_max_m,h_q_alpha_ld_max_m,h_dynamic_pressure_m,h_lower_m,"
               "closed,phase,h_path_m,alpha_cl_max_deg,alpha_ld_max_deg,alpha_extracted_deg,alpha_deg,"
               "energy_norm,heat_flux_Wpm2,load_factor_g,q_alpha_Pa_rad,dynamic_pressure_Pa,violation\n");
  for (int i = 0; i < r.n_corridor; ++i) {
    const reentry::fsw::AlphaCorridorPoint& p = r.corridor[i];
    std::fprintf(f,
                 "%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%d,%d,%.3f,%.6f,%.6f,%.6f,%.6f,%.9f,%.3f,%.6f,"
                 "%.3f,%.3f,%d\n",
                 p.velocity_mps, p.h_glide_cl_max_m, p.h_glide_ld_max_m, p.h_heat_flux_m, p.h_load_factor_cl_max_m,
                 p.h_load_factor_ld_max_m, p.h_q_alpha_cl_max_m, p.h_q_alpha_ld_max_m, p.h_dynamic_pressure_m,
                 p.h_lower_m, p.closed ? 1 : 0, static_cast<int>(p.phase), p.h_path_m, p.alpha_cl_max_rad * kDegPerRad,
                 p.alpha_ld_max_rad * kDegPerRad, p.alpha_extracted_rad * kDegPerRad, p.alpha_rad * kDegPerRad,
                 p.energy_norm, p.path_heat_flux_Wpm2, p.path_load_factor_g, p.path_q_alpha_Pa_rad,
                 p.path_dynamic_pressure_Pa, p.path_violation ? 1 : 0);
  }
  return close_ok(f);
}

void add_plan_summary(const reentry::fsw::AlphaPlanResult& r, nlohmann::json& j) {
  j["alpha_entry_deg"] = r.alpha_entry_rad * kDegPerRad;
  j["alpha_taem_deg"] = r.alpha_taem_rad * kDegPerRad;
  j["alpha_min_deg"] = r.alpha_min_rad * kDegPerRad;
  j["alpha_max_deg"] = r.alpha_max_rad * kDegPerRad;
  j["corridor_closed_points"] = r.closed_points;
  j["extraction_clamped_points"] = r.clamped_points;
  j["path_violation_points"] = r.violation_points;
  j["v_intersection_mps"] = r.v_intersection_mps;
  j["v_heating_switch_mps"] = r.v_heating_switch_mps;
  j["v_taem_switch_mps"] = r.v_taem_switch_mps;
  j["dv_taem_mps"] = r.dv_taem_mps;
  j["profile_points"] = r.n_profile;
}

/// Prints the JSON line and returns the exit status.
int report(nlohmann::json& j, int exit_status) {
  std::cout << j.dump() << std::endl;
  return exit_status;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Angle-of-attack planning in the 2D h-V corridor (thesis ch. 6)"};
  std::string mission_arg;
  reentry::fsw::AlphaPlanParams params;
  std::string out_csv;
  std::string corridor_csv;
  app.add_option("--mission", mission_arg, "mission name (x33, horus, orbiter, x38) or .toml path")->required();
  app.add_option("--heating-pct", params.heating_pct, "heating phase height percentage [0,100]");
  app.add_option("--ranging-pct", params.ranging_pct, "ranging phase alpha percentage [0,100]");
  app.add_option("--heating-switch-pct", params.heating_switch_pct, "heating->ranging switch velocity percentage");
  app.add_option("--taem-switch-pct", params.taem_switch_pct, "ranging->alpha(L/D max) switch velocity percentage");
  app.add_option("--out", out_csv, "alpha profile CSV (energy_norm, alpha_deg)");
  app.add_option("--corridor-out", corridor_csv, "corridor CSV");
  CLI11_PARSE(app, argc, argv);

  nlohmann::json j;
  j["mission"] = mission_arg;
  const reentry::config::LoadResult loaded = reentry::config::load_mission(mission_arg);
  if (!loaded.ok) {
    j["status"] = "load_error";
    j["error"] = loaded.error;
    return report(j, 2);
  }
  reentry::fsw::Status s = init_from_mission(g_planner, loaded.mission);
  if (s == reentry::fsw::Status::kOk) s = g_planner.plan(params, g_result);
  j["status"] = reentry::fsw::to_string(s);
  if (s != reentry::fsw::Status::kOk) return report(j, 1);
  add_plan_summary(g_result, j);
  for (const auto& [path, write] : {std::make_pair(out_csv, &write_profile_csv), std::make_pair(corridor_csv, &write_corridor_csv)}) {
    if (path.empty() || write(path, g_result)) continue;
    j["status"] = "write_error";
    j["error"] = "cannot write " + path;
    return report(j, 3);
  }
  return report(j, 0);
}
