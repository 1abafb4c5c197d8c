#include "tracker/tracker_phase.hpp"

namespace reentry::fsw {

const char* to_string(TrackerPhase phase) {
  switch (phase) {
    case TrackerPhase::kInitialDescent: return "initial_descent";
    case TrackerPhase::kPlanned: return "planned";
    case TrackerPhase::kHeadingCorridor: return "heading_corridor";
    case TrackerPhase::kTerminalRange: return "terminal_range";
    case TrackerPhase::kFinalReversal: return "final_reversal";
  }
  return "unknown";
}

TrackerPhase TrackerPhaseMachine::advance(double e_norm, bool in_window) {
  // Bounded: each pass moves one phase forward; a state may pass several at once (a tracker
  // started late in the flight).
  for (int i = 0; i < 4; ++i) {
    switch (phase_) {
      case TrackerPhase::kInitialDescent: return phase_;
      case TrackerPhase::kPlanned:
        if (!(e_norm < e_corridor_norm_)) return phase_;
        phase_ = TrackerPhase::kHeadingCorridor;
        break;
      case TrackerPhase::kHeadingCorridor:
        if (!(e_norm < e_terminal_norm_)) return phase_;
        phase_ = TrackerPhase::kTerminalRange;
        break;
      case TrackerPhase::kTerminalRange:
        if (in_window) phase_ = TrackerPhase::kFinalReversal;
        return phase_;
      case TrackerPhase::kFinalReversal:
        if (!in_window) phase_ = TrackerPhase::kTerminalRange;
        return phase_;
    }
  }
  return phase_;
}

}  // namespace reentry::fsw
