#include "vehicle/heating.hpp"

#include "environment/earth.hpp"

#include <cmath>

namespace reentry::truth {

double chapman_circular_velocity_mps() {
  return std::sqrt(EarthConstants::kMu_m3ps2 / EarthConstants::kEquatorialRadius_m);
}

}  // namespace reentry::truth
