// The tracker's phases and the transitions between them, in one place.
//
//   kInitialDescent --captured--> kPlanned --E < E_corridor--> kHeadingCorridor
//       --E < E_terminal--> kTerminalRange <--final-reversal window--> kFinalReversal
//
//  - kInitialDescent: profile alpha, wings level, until a plan is adopted and the drag is
//    captured (flight practice: hold attitude until the drag is measurable, DESIGN §6);
//  - kPlanned: drag tracking with the bank sign of the plan (its one planned reversal);
//  - kHeadingCorridor: drag tracking, bank sign from the heading corridor about the arrival
//    line (the last lateral_corridor_span_fraction of the energy span);
//  - kTerminalRange: in addition, the range control of the drag reference (the last
//    terminal_span_fraction of the span, inside the corridor phase; no replans);
//  - kFinalReversal: the last final_reversal_window reversal durations before TAEM, judged
//    every cycle on the bank averaged up to the last cycle (a change of bank moves the
//    window, so this transition goes both ways): no lift down from here.
// The energy transitions are one way: after capture the energy falls monotonically (E' = -D V).
#pragma once

#include <cstdint>

namespace reentry::fsw {

enum class TrackerPhase : std::int8_t {
  kInitialDescent = 0,
  kPlanned = 1,
  kHeadingCorridor = 2,
  kTerminalRange = 3,
  kFinalReversal = 4,
};

const char* to_string(TrackerPhase phase);

class TrackerPhaseMachine {
 public:
  /// Normalised energies E / E_entry of the corridor and terminal phase starts
  /// (e_terminal_norm <= e_corridor_norm).
  void init(double e_corridor_norm, double e_terminal_norm) {
    e_corridor_norm_ = e_corridor_norm;
    e_terminal_norm_ = e_terminal_norm;
    reset();
  }
  void reset() { phase_ = TrackerPhase::kInitialDescent; }
  /// The drag is captured: tracking starts.
  void capture() {
    if (phase_ == TrackerPhase::kInitialDescent) phase_ = TrackerPhase::kPlanned;
  }
  /// The energy transitions at e_norm and the final-reversal window, once per tracking cycle.
  TrackerPhase advance(double e_norm, bool in_final_reversal_window);

  TrackerPhase phase() const { return phase_; }
  bool captured() const { return phase_ != TrackerPhase::kInitialDescent; }
  bool heading_corridor() const { return phase_ >= TrackerPhase::kHeadingCorridor; }
  bool terminal() const { return phase_ >= TrackerPhase::kTerminalRange; }
  bool final_reversal_window() const { return phase_ == TrackerPhase::kFinalReversal; }

 private:
  TrackerPhase phase_ = TrackerPhase::kInitialDescent;
  double e_corridor_norm_ = 0.0;
  double e_terminal_norm_ = 0.0;
};

}  // namespace reentry::fsw
