// Guidance parameters shared by the planner and the tracker, with the tunables of each: the
// values the guidance is initialised with (defaults = the values the reference missions fly).
// A mission sets them in [guidance] (the shared ones), [guidance.planner] and
// [guidance.tracker]; fsw/guidance validates them against the ranges the visitors document.
#pragma once

#include "params/param_visitor.hpp"
#include "planner/planner_params.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

struct GuidanceLawParams {
  /// Planned fraction of every path-constraint limit (3 % design margin): the planner's
  /// corridor bounds and the tracker's sensed-constraint drag limiter use the same fraction.
  double constraint_margin = 0.97;
  /// Lateral corridor phase: over the last fraction of the entry-to-TAEM energy span the
  /// tracker keeps the vehicle on the arrival great circle with a heading corridor instead of
  /// the planned reversal; the planner's reduced-order trajectory flies that circle there too,
  /// so that planned and flown path lengths agree.
  double lateral_corridor_span_fraction = 0.30;
  /// Terminal phase: over the last fraction of the energy span the tracker controls the range
  /// to go with a drag increment and no replans are made (DESIGN §6); the planner's ranging
  /// alpha ends there. Not above lateral_corridor_span_fraction.
  double terminal_span_fraction = 0.25;
  PlannerParams planner;
  TrackerParams tracker;
};

template <class Params, class Visitor>
void visit_shared_guidance_params(Params& p, Visitor&& v) {
  using U = ParamUnit;
  v("constraint_margin", p.constraint_margin, U::kNone, 0.5, 1.0, "planned fraction of every path-constraint limit");
  v("lateral_corridor_span_fraction", p.lateral_corridor_span_fraction, U::kNone, 0.0, 1.0,
    "heading-corridor phase: last fraction of the energy span");
  v("terminal_span_fraction", p.terminal_span_fraction, U::kNone, 0.0, 1.0,
    "terminal range control: last fraction of the energy span (<= lateral_corridor_span_fraction)");
}

/// The first key whose value breaks a relation between fields (nullptr: consistent).
const char* guidance_params_inconsistency(const GuidanceLawParams& p);

}  // namespace reentry::fsw
