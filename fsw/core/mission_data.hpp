// The mission as the flight-software core sees it: the shared interface types
// (common/mission) gathered into one struct. The process layer (fsw/guidance) fills it from the
// loaded mission at start-up; the core never sees the loader.
#pragma once

#include "mission/mission_interface.hpp"

namespace reentry::fsw {

using mission::EntryInterface;
using mission::kUnconstrained;
using mission::PathLimits;
using mission::TaemTarget;

struct GuidanceMission {
  EntryInterface entry;
  TaemTarget taem;
  PathLimits limits;
};

}  // namespace reentry::fsw
