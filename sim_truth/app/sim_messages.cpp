#include "sim_messages.hpp"

#include <reentry/telemetry_fill.hpp>

#include "evaluation/mission_verdict.hpp"

namespace reentry::truth {
namespace {

/// nav_state_t's field beyond the navigation sample: no flag (the end of a run is announced
/// by RUN_CONTROL END_OF_RUN).
struct NavFlags {
  std::int32_t sim_flags = 0;
};

/// run_control_t's fields beyond the run summary.
struct EndOfRun {
  std::int8_t command = run_control_t::END_OF_RUN;
  std::int8_t event_code = run_control_t::EVENT_NONE;
  double heading_err_rad = 0.0;
};

}  // namespace

void fill_nav(const NavSample& ns, std::int64_t k, nav_state_t& nav) {
  reentry::stamp(nav, ns.t_s, k);
  reentry::fill(nav, ns, NavFlags{});
}

void fill_truth(const TruthSample& ts, std::int64_t utime, std::int64_t k, truth_telemetry_t& tel) {
  tel.utime = utime;
  tel.tick = k;
  reentry::fill(tel, ts);
}

std::int8_t end_event_code(SimEvent e) {
  switch (e) {
    case SimEvent::kTaemEnergy: return run_control_t::EVENT_TAEM;
    case SimEvent::kGroundImpact: return run_control_t::EVENT_GROUND;
    case SimEvent::kSkipOut: return run_control_t::EVENT_SKIP_OUT;
    case SimEvent::kTimeOut: return run_control_t::EVENT_TIMEOUT;
    default: return run_control_t::EVENT_ABORT;
  }
}

void fill_end_of_run(const RunSummary& summary, std::int64_t tick, std::int8_t event, double taem_heading_rad,
                     run_control_t& rc) {
  EndOfRun end;
  end.event_code = event;
  end.heading_err_rad = wrap_pi(summary.final_state.chi_rad - taem_heading_rad);
  reentry::stamp(rc, summary.final_state.t_s, tick);
  reentry::fill(rc, summary, end);
}

}  // namespace reentry::truth
