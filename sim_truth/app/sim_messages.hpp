// The simulator process's messages, shared by the SIL simulator (sim_lcm_main.cpp) and the
// in-process runs that record the same channels (tools/montecarlo/closed_loop.cpp). The field
// copies are generated from interfaces/*.lcm (<reentry/telemetry_fill.hpp>, interfaces/README.md).
#pragma once

#include <cstdint>
#include <reentry/nav_state_t.hpp>
#include <reentry/run_control_t.hpp>
#include <reentry/truth_telemetry_t.hpp>

#include "dynamics/simulator.hpp"

namespace reentry::truth {

/// NAV_STATE of tick k.
void fill_nav(const NavSample& ns, std::int64_t k, nav_state_t& nav);

/// TRUTH of tick k, stamped utime [us].
void fill_truth(const TruthSample& ts, std::int64_t utime, std::int64_t k, truth_telemetry_t& tel);

/// The run_control_t::EVENT_* code of a simulator event.
std::int8_t end_event_code(SimEvent e);

/// RUN_CONTROL END_OF_RUN: the run's final state and maxima, its event (run_control_t::EVENT_*)
/// and the final heading error from the TAEM heading [rad].
void fill_end_of_run(const RunSummary& summary, std::int64_t tick, std::int8_t event, double taem_heading_rad,
                     run_control_t& rc);

}  // namespace reentry::truth
