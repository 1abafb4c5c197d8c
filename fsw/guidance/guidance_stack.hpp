// The guidance stack: the core components (entry planner, tracker, rate filters) wired into
// the executive's two interfaces. Shared by the guidance process (fsw/app) and in-process
// runs (Monte Carlo, tests), so both fly exactly the same code. All allocation happens in
// create(); cycles and plans allocate nothing.
#pragma once

#include <memory>
#include <string>

#include "exec/executive.hpp"
#include "filter/rate_filter.hpp"
#include "planner/entry_planner.hpp"
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

struct GuidanceStack {
  std::unique_ptr<PlannerAdapter> planner;
  std::unique_ptr<TrackerLaw> law;
  std::unique_ptr<exec::Executive> executive;
  exec::ExecConfig config;

  /// Initialises every component from the mission and starts the executive in `mode`.
  /// Returns an empty string on success, otherwise what failed.
  std::string create(const config::Mission& mission, exec::PlanMode mode);
};

}  // namespace reentry::fsw
