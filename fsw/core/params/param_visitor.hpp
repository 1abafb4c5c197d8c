// Conventions shared by the parameter lists of the planner and the tracker
// (visit_planner_params, visit_tracker_params): each entry names the key a mission file uses,
// the unit of that key and the documented range in that unit; the field itself is SI.
#pragma once

#include <cmath>

namespace reentry::fsw {

/// Unit of a parameter's key in the mission file (the field is SI).
enum class ParamUnit { kNone, kDeg };

/// A file value in its key's unit, in SI. Degrees are converted as v * pi / 180, the order the
/// defaults are written in, so a key set to its default gives the default bit for bit.
inline double param_to_si(double file_value, ParamUnit unit) {
  return unit == ParamUnit::kDeg ? file_value * M_PI / 180.0 : file_value;
}
inline double param_from_si(double value_si, ParamUnit unit) {
  return unit == ParamUnit::kDeg ? value_si * 180.0 / M_PI : value_si;
}

}  // namespace reentry::fsw
