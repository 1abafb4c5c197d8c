#include "guidance_types.hpp"

namespace reentry::fsw {

const char* to_string(Status s) {
  switch (s) {
    case Status::kOk: return "ok";
    case Status::kInvalidInput: return "invalid_input";
    case Status::kNoBracket: return "no_bracket";
    case Status::kMaxIterations: return "max_iterations";
    case Status::kNonFinite: return "non_finite";
    case Status::kCorridorClosed: return "corridor_closed";
    case Status::kExtractionFailed: return "extraction_failed";
    case Status::kNotConverged: return "not_converged";
    case Status::kCapacityExceeded: return "capacity_exceeded";
    case Status::kRangeTooLong: return "range_too_long";
    case Status::kRangeTooShort: return "range_too_short";
  }
  return "unknown";
}

}  // namespace reentry::fsw
