// reentry_sim: fly an open-loop alpha/sigma schedule with the truth simulator.
// Writes the trajectory CSV (one row per --out-dt) and one line of JSON on stdout.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <fstream>
#include <iostream>

#include "dynamics/open_loop.hpp"
#include "dynamics/simulator.hpp"
#include "reentry/config/mission.hpp"

using namespace reentry;

int main(int argc, char** argv) {
  CLI::App app{"Truth-model re-entry simulator (open loop)"};
  std::string mission_name, profile_path, out_path, gravity, atmosphere, wind, shape, integrator;
  double out_dt = 1.0, rel_tol = -1.0;
  std::uint64_t seed = 0;
  app.add_option("--mission", mission_name, "mission name (x33, horus, orbiter, x38) or .toml file")->required();
  app.add_option("--open-loop", profile_path, "CSV t_s|E_norm,alpha_deg,sigma_deg")->required();
  app.add_option("--out", out_path, "trajectory CSV to write")->required();
  app.add_option("--out-dt", out_dt, "output interval [s]")->check(CLI::PositiveNumber);
  app.add_option("--gravity", gravity)->check(CLI::IsMember({"central", "j2j4", "sh20"}));
  app.add_option("--atmosphere", atmosphere)->check(CLI::IsMember({"exponential", "us76"}));
  app.add_option("--wind", wind)->check(CLI::IsMember({"on", "off"}));
  app.add_option("--shape", shape)->check(CLI::IsMember({"sphere", "oblate"}));
  app.add_option("--integrator", integrator)->check(CLI::IsMember({"rkf56", "rkf78"}));
  app.add_option("--rel-tol", rel_tol, "relative integration tolerance")->check(CLI::PositiveNumber);
  auto* seed_opt = app.add_option("--seed", seed, "draw dispersions from the mission's [dispersions] with this seed");
  CLI11_PARSE(app, argc, argv);

  const config::LoadResult loaded = config::load_mission(mission_name);
  if (!loaded.ok) {
    std::cerr << "reentry_sim: " << loaded.error << "\n";
    return 2;
  }
  truth::OpenLoopProfile profile;
  std::string error;
  if (!truth::load_open_loop_profile(profile_path, &profile, &error)) {
    std::cerr << "reentry_sim: " << error << "\n";
    return 2;
  }
  truth::SimOverrides ov;
  if (!gravity.empty()) truth::parse_gravity(gravity, &ov.gravity);
  if (!atmosphere.empty()) truth::parse_atmosphere(atmosphere, &ov.atmosphere);
  if (!shape.empty()) truth::parse_shape(shape, &ov.shape);
  if (!integrator.empty()) truth::parse_integrator(integrator, &ov.integrator);
  if (!wind.empty()) ov.wind = wind == "on" ? truth::WindChoice::kOn : truth::WindChoice::kOff;
  ov.rel_tol = rel_tol;
  if (seed_opt->count() > 0) ov.dispersion = truth::draw_dispersions(loaded.mission.dispersions, seed);

  auto sim = truth::Simulator::create(loaded.mission, ov, &error);
  if (!sim) {
    std::cerr << "reentry_sim: " << error << "\n";
    return 2;
  }
  std::ofstream out(out_path);
  if (!out) {
    std::cerr << "reentry_sim: cannot write " << out_path << "\n";
    return 2;
  }
  truth::write_trajectory_header(out);
  const truth::RunSummary summary = truth::run_open_loop(
      *sim, profile, out_dt, [&out](const truth::TruthSample& s) { truth::write_trajectory_row(out, s); });
  out.close();
  std::cout << truth::summary_json(summary, *sim) << std::endl;
  return summary.event == truth::SimEvent::kFailure ? 1 : 0;
}
