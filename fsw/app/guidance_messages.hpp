// The guidance process's messages from one executive cycle, shared by the guidance process
// (guidance_node.cpp) and the in-process runs that record the same channels
// (tools/montecarlo/closed_loop.cpp). The field copies are generated from interfaces/*.lcm
// (<reentry/telemetry_fill.hpp>, interfaces/README.md); only the plan, whose points are
// normalised and padded, is written here by hand. No allocation.
#pragma once

#include <cstdint>
#include <reentry/guidance_cmd_t.hpp>
#include <reentry/plan_t.hpp>
#include <reentry/telemetry_fill.hpp>
#include <reentry/tracker_status_t.hpp>

#include "exec/executive.hpp"

namespace reentry::fsw::app {

/// GUIDANCE_CMD of a cycle.
inline void fill_command(const exec::CycleOutput& out, guidance_cmd_t& cmd) {
  reentry::stamp(cmd, out.t_s, out.tick);
  reentry::fill(cmd, out);
}

/// TRACKER_STATUS of a cycle.
inline void fill_tracker_status(const exec::CycleOutput& out, tracker_status_t& m) {
  reentry::stamp(m, out.t_s, out.tick);
  reentry::fill(m, out.tracker);
}

/// PLAN of an adopted profile: points over energy (zero beyond n_points), the reversal and
/// breakpoint energies normalised by the entry energy, the compute time of the plan [ms].
void fill_plan(const ReferenceProfile& p, std::int64_t utime, std::int64_t tick, double compute_ms, plan_t& plan);

}  // namespace reentry::fsw::app
