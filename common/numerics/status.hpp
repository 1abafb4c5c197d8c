#pragma once
// Status codes shared by all numerical routines (thesis ch. 4). Flight style: no exceptions.

namespace reentry::numerics {

enum class NumStatus {
  kOk,             // converged / fitted / integrated
  kInvalidInput,   // bad size, non-increasing abscissae, non-positive tolerance, ...
  kNoBracket,      // f(a) f(b) > 0 for a bracketing root finder
  kMaxIterations,  // iteration or step budget exhausted before convergence
  kNonFinite,      // NaN/Inf met in a function value or a computed quantity
  kStepTooSmall    // adaptive integrator step collapsed below the minimum step
};

inline const char* to_string(NumStatus s) {
  switch (s) {
    case NumStatus::kOk: return "ok";
    case NumStatus::kInvalidInput: return "invalid_input";
    case NumStatus::kNoBracket: return "no_bracket";
    case NumStatus::kMaxIterations: return "max_iterations";
    case NumStatus::kNonFinite: return "non_finite";
    case NumStatus::kStepTooSmall: return "step_too_small";
  }
  return "unknown";
}

}  // namespace reentry::numerics
