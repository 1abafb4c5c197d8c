// The tracker's phase machine (tracker_phase.hpp) against hand-written expectations of the
// energy schedule and the final-reversal window.
#include <gtest/gtest.h>

#include "tracker/tracker_phase.hpp"

namespace reentry::fsw {
namespace {

TEST(TrackerPhase, TransitionsFollowTheEnergyScheduleAndTheWindow) {
  // Corridor from E/E_entry = 0.30, terminal range from 0.25 (hand-written expectations).
  TrackerPhaseMachine m;
  m.init(0.30, 0.25);
  EXPECT_EQ(m.advance(0.10, true), TrackerPhase::kInitialDescent);  // nothing before capture
  m.capture();
  EXPECT_EQ(m.phase(), TrackerPhase::kPlanned);
  EXPECT_EQ(m.advance(0.50, true), TrackerPhase::kPlanned);          // the window alone does not move it
  EXPECT_EQ(m.advance(0.30, false), TrackerPhase::kPlanned);         // strictly below the start
  EXPECT_EQ(m.advance(0.29, false), TrackerPhase::kHeadingCorridor);
  EXPECT_TRUE(m.heading_corridor() && !m.terminal());
  EXPECT_EQ(m.advance(0.35, false), TrackerPhase::kHeadingCorridor);  // energy transitions are one way
  EXPECT_EQ(m.advance(0.20, false), TrackerPhase::kTerminalRange);
  EXPECT_EQ(m.advance(0.10, true), TrackerPhase::kFinalReversal);
  EXPECT_TRUE(m.final_reversal_window() && m.terminal());
  EXPECT_EQ(m.advance(0.09, false), TrackerPhase::kTerminalRange);    // the window is re-judged
  EXPECT_EQ(m.advance(0.08, true), TrackerPhase::kFinalReversal);
  m.reset();
  EXPECT_EQ(m.phase(), TrackerPhase::kInitialDescent);
  // Captured late in the flight: every phase due is entered at once.
  m.capture();
  EXPECT_EQ(m.advance(0.05, true), TrackerPhase::kFinalReversal);
  EXPECT_STREQ(to_string(TrackerPhase::kHeadingCorridor), "heading_corridor");
}

}  // namespace
}  // namespace reentry::fsw
