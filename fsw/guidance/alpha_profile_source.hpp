// Where the angle-of-attack profile comes from: the mission's table, or, with
// [alpha_profile] source = "planned", the angle-of-attack planner (thesis ch. 6) run at start-up.
#pragma once

#include <string>

#include "reentry/config/mission.hpp"

namespace reentry::fsw {

/// Start-up only (allocates). With mission.alpha_profile_planned and no table yet, plans the
/// profile in the 2D h-V corridor with the default shaping parameters (AlphaPlanParams{}: the
/// documented rule, no per-vehicle choice), holds its end values out to E/E_entry = 0 and 1,
/// and stores it in mission.alpha_profile. Returns "" or an error naming the failure.
std::string resolve_alpha_profile(config::Mission& mission);

}  // namespace reentry::fsw
