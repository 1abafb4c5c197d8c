// The mission file, as loaded by config/, turned into what the flight-software core is
// initialised from: plain mission data, the guidance parameters (defaults, overridden by the
// mission's [guidance] tunables and validated against their documented ranges), the on-board
// models with their tables (the on-board atmosphere table file is read here) and the alpha
// profile. Start-up only: allocates and does I/O; the core components never see the loader.
#pragma once

#include <string>
#include <vector>

#include "alpha_planner/alpha_planner.hpp"
#include "guidance_params.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "planner/entry_planner.hpp"
#include "predictor_corrector/pc_params.hpp"
#include "predictor_corrector/pc_planner.hpp"
#include "reentry/config/mission.hpp"
#include "tracker/entry_tracker.hpp"

namespace reentry::fsw {

/// The guidance law a mission flies ([guidance] law).
enum class GuidanceLaw { kDragTracking, kPredictorCorrector };

struct GuidanceSetup {
  GuidanceMission mission;
  GuidanceLaw law = GuidanceLaw::kDragTracking;
  GuidanceLawParams params;
  PredictorCorrectorParams pc_params;  // [guidance.predictor_corrector]
  OnboardModels models;
  AlphaProfile alpha_profile;
};

GuidanceMission to_guidance_mission(const config::Mission& mission);
/// params from their defaults and the mission's [guidance] values ("" or an error naming the
/// file, the key and the value).
std::string guidance_params_from_mission(const config::Mission& mission, GuidanceLawParams& params);
/// The law and the predictor-corrector's parameters from their defaults and the mission's
/// [guidance] law and [guidance.predictor_corrector] values ("" or an error naming the file,
/// the key and the value).
std::string pc_params_from_mission(const config::Mission& mission, GuidanceLaw& law, PredictorCorrectorParams& params);
/// Vehicle, aero tables and on-board atmosphere ("" or an error naming the file or table).
std::string onboard_models_from_mission(const config::Mission& mission, OnboardModels& models);
/// The loader's aero model as on-board trim data (start-up): the base tables and the first body
/// flap and elevon surface, in that trim order; tables on another grid than C_L's are refused.
Status trim_data_from_aero(const config::AeroModel& aero, TrimAeroData& data);
std::string alpha_profile_from_mission(const config::Mission& mission, AlphaProfile& profile);
/// All of the above. The mission's alpha profile must be resolved (see alpha_profile_source).
std::string make_guidance_setup(const config::Mission& mission, GuidanceSetup& out);

/// Rows "altitude_m density_kgpm3 pressure_Pa temperature_K" of a US76 table file ('%' or '#'
/// comment lines, other unparsable lines skipped): "" or an error naming the file.
std::string read_atmosphere_table(const std::string& path, std::vector<double>& altitude_m,
                                  std::vector<double>& density_kgpm3, std::vector<double>& temperature_K);

/// One line per tunable: key (with the unit of the file), value, documented range, meaning.
std::string describe_guidance_params(const GuidanceLawParams& params);
/// The same for the predictor-corrector's tunables (guidance.predictor_corrector.*).
std::string describe_pc_params(const PredictorCorrectorParams& params);

/// A core component initialised from a mission (tests and tools; allocates a setup). Any
/// failure of the setup comes back as kInvalidInput.
Status init_from_mission(EntryPlanner& planner, const config::Mission& mission);
/// The predictor-corrector plan with the mission's timing (latency ticks at the GNC rate).
Status init_from_mission(PredictorCorrectorPlanner& planner, const config::Mission& mission);
Status init_from_mission(EntryTracker& tracker, const config::Mission& mission);
Status init_from_mission(AlphaPlanner& planner, const config::Mission& mission);
Status init_from_mission(OnboardModels& models, const config::Mission& mission);
Status init_from_mission(AlphaProfile& profile, const config::Mission& mission);

}  // namespace reentry::fsw
