// Mission data as the flight-software core sees it (temporary bridge to the loader's types).
#pragma once

#include "reentry/config/mission.hpp"

namespace reentry::fsw {
using TaemTarget = config::TaemInterface;
}  // namespace reentry::fsw
