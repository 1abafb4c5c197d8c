#include "guidance/alpha_profile_source.hpp"

#include <memory>

#include "alpha_planner/alpha_planner.hpp"
#include "guidance/mission_adapter.hpp"

namespace reentry::fsw {

std::string resolve_alpha_profile(config::Mission& mission) {
  if (!mission.alpha_profile_planned || !mission.alpha_profile.x.empty()) return {};
  auto models = std::make_unique<OnboardModels>();
  const std::string err = onboard_models_from_mission(mission, *models);
  if (!err.empty()) return err;
  auto planner = std::make_unique<AlphaPlanner>();
  Status st = planner->init(*models, to_guidance_mission(mission));
  if (st != Status::kOk) return std::string("alpha planner init: ") + to_string(st);
  auto result = std::make_unique<AlphaPlanResult>();
  st = planner->plan(AlphaPlanParams{}, *result);
  if (st != Status::kOk) return std::string("alpha planning ([alpha_profile] source = \"planned\"): ") + to_string(st);
  if (result->n_profile < 2) return "alpha planning produced fewer than 2 profile points";
  config::Table1D& t = mission.alpha_profile;
  t.x.assign(result->profile_energy_norm, result->profile_energy_norm + result->n_profile);
  t.y.assign(result->profile_alpha_rad, result->profile_alpha_rad + result->n_profile);
  // The planned path spans the energies of its own corridor end points; the guidance needs
  // the whole [0, 1] range (entry and TAEM energies differ slightly): hold the end values.
  if (t.x.front() > 0.0) t.x.front() = 0.0;
  if (t.x.back() < 1.0) t.x.back() = 1.0;
  return {};
}

}  // namespace reentry::fsw
