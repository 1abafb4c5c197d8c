// One closed-loop mission flown in process: the truth simulator and the guidance stack of the
// guidance process (same executive, planner, tracker and filters, synchronous plan mode, which
// gives the same commands as lockstep over LCM), tick for tick in the order of the LCM
// simulator: nav of tick k -> command of tick k -> integrate to tick k+1.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"
#include "exec/executive.hpp"
#include "evaluation/mission_verdict.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::tools {

struct ClosedLoopResult {
  std::uint64_t seed = 0;
  bool dispersed = false;
  std::string error;                      // set when the run could not be started
  truth::RunSummary summary;
  truth::MissionVerdict verdict;
  truth::CommandRateMaxima rates;
  truth::DispersionDraw dispersion;
  fsw::exec::ExecCounters counters;     // the executive's at the end of the run
  std::string trace_error;                // the trace log could not be written whole (file and reason)
  double wall_s = 0.0;
};

/// Physics bound of one run: the maxima of the entry descent flown wings level at alpha_max
/// with the same dispersions (truth::wings_level_pullout_maxima), and the path constraints
/// they already exceed; no guidance can do better at the first pull-out.
struct PulloutBound {
  std::string error;
  truth::RunMaxima maxima;
  std::vector<std::string> exceeded;
};
PulloutBound wings_level_pullout_bound(const config::Mission& mission, std::uint64_t seed, bool dispersed);

/// Flies the mission; dispersed runs draw their dispersions from `seed` (draw_dispersions).
/// A non-empty `trace_log` receives the run once per second as an LCM log of the SIL's channels
/// (TRUTH, GUIDANCE_CMD, TRACKER_STATUS; PLAN at each adoption; RUN_CONTROL at the end), the
/// same messages as a SIL run's log: tools/log2csv and tools/plot read it. With `guidance_knows_vehicle`
/// the guidance is given the run's drawn C_L, C_D and mass (a diagnosis, not a flight mode:
/// no sensor tells a C_D error from a density error; it measures what that ignorance costs).
/// A non-empty `on_sample` sees the simulator at every tick right after the command (with the
/// command now in effect) and once more at the end of the run (the event state, last command):
/// the flown trajectory, e.g. to warm-start the trajectory optimizer.
using FlownSampleHandler = std::function<void(const truth::Simulator& sim, double alpha_rad, double sigma_rad)>;
ClosedLoopResult run_closed_loop(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                                 const std::string& trace_log = {}, bool guidance_knows_vehicle = false,
                                 const FlownSampleHandler& on_sample = {});

}  // namespace reentry::tools
