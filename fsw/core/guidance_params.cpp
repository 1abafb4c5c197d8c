#include "guidance_params.hpp"

namespace reentry::fsw {

const char* guidance_params_inconsistency(const GuidanceLawParams& p) {
  if (!(p.terminal_span_fraction <= p.lateral_corridor_span_fraction)) return "terminal_span_fraction";
  if (!(p.planner.lift_scale_min < p.planner.lift_scale_max)) return "planner.lift_scale_min";
  if (const char* planner = planner_params_inconsistency(p.planner)) return planner;
  const char* tracker = tracker_params_inconsistency(p.tracker);
  return tracker;
}

}  // namespace reentry::fsw
