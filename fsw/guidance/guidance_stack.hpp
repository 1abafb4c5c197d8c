// The guidance stack: the core components of the mission's guidance law wired into the
// executive's two interfaces, shared by the guidance process (fsw/app) and in-process runs
// (Monte Carlo, tests), so both fly exactly the same code. Two laws ([guidance] law):
//   - drag tracking: the entry planner (PlanComputer) and the tracker + rate filters (CommandLaw);
//   - predictor-corrector: its plan (PlanComputer) and its cycle + the same rate filters.
// All allocation happens in create(); cycles and plans allocate nothing.
#pragma once

#include <memory>
#include <string>

#include "exec/executive.hpp"
#include "filter/rate_filter.hpp"
#include "planner/entry_planner.hpp"
#include "predictor_corrector/pc_cycle.hpp"
#include "predictor_corrector/pc_planner.hpp"
#include "tracker/entry_tracker.hpp"

namespace reentry::config {
struct Mission;
}

namespace reentry::fsw {

/// PlanComputer backed by the entry planner.
class PlannerAdapter : public exec::PlanComputer {
 public:
  EntryPlanner planner;
  Status compute(const RelativeState& from, ReferenceProfile& out) override { return planner.plan(from, out); }
};

/// CommandLaw: tracker followed by the alpha and sigma rate filters. The filters start at
/// the first tracker command (no artificial ramp from zero at the entry interface).
class TrackerLaw : public exec::CommandLaw {
 public:
  EntryTracker tracker;
  RateFilter alpha_filter;
  RateFilter sigma_filter;
  TrackerOutput last;
  void set_profile(const ReferenceProfile& profile) override { tracker.set_profile(profile); }
  Status step(const RelativeState& s, double dt_s, bool has_profile, exec::LawOutput& out) override;

 private:
  bool started_ = false;
};

/// PlanComputer backed by the predictor-corrector plan.
class PcPlannerAdapter : public exec::PlanComputer {
 public:
  PredictorCorrectorPlanner planner;
  Status compute(const RelativeState& from, ReferenceProfile& out) override { return planner.plan(from, out); }
};

/// CommandLaw: the predictor-corrector cycle followed by the same alpha and sigma rate filters.
class PcLaw : public exec::CommandLaw {
 public:
  PredictorCorrectorCycle cycle;
  RateFilter alpha_filter;
  RateFilter sigma_filter;
  PcCycleOutput last;
  void set_profile(const ReferenceProfile& profile) override { cycle.set_profile(profile); }
  Status step(const RelativeState& s, double dt_s, bool has_profile, exec::LawOutput& out) override;

 private:
  bool started_ = false;
};

struct GuidanceStack {
  // The drag-tracking law's components (null when the mission flies the predictor-corrector).
  std::unique_ptr<PlannerAdapter> planner;
  std::unique_ptr<TrackerLaw> law;
  // The predictor-corrector's (null when the mission flies drag tracking).
  std::unique_ptr<PcPlannerAdapter> pc_planner;
  std::unique_ptr<PcLaw> pc_law;
  std::unique_ptr<exec::Executive> executive;
  exec::ExecConfig config;

  /// Initialises every component of the mission's law and starts the executive in `mode`.
  /// Returns an empty string on success, otherwise what failed.
  std::string create(const config::Mission& mission, exec::PlanMode mode);
  /// The components of the law in use (valid after a successful create()).
  exec::PlanComputer& plan_computer();
  exec::CommandLaw& command_law();
};

}  // namespace reentry::fsw
