// Types shared by the flight-software core components (planner, tracker, filter,
// executive). Plain fixed-size data: no heap, trivially copyable, so a plan can be
// handed between threads by value through a preallocated slot.
#pragma once

#include <cstdint>

#include "numerics/status.hpp"
#include "telemetry/core_telemetry.hpp"  // TrackerTelemetry: generated from interfaces/tracker_status_t.lcm
#include "tracker/tracker_phase.hpp"

namespace reentry::fsw {

/// Capacity of a reference profile over energy (matches interfaces/plan_t.lcm MAX_POINTS).
inline constexpr int kProfileCapacity = 201;

/// Explicit status codes; every failure is returned, never thrown.
enum class Status : std::int8_t {
  kOk = 0,
  kInvalidInput = 1,
  kNoBracket = 2,           // root finder / reversal search: no sign change in the interval
  kMaxIterations = 3,
  kNonFinite = 4,           // NaN or inf encountered
  kCorridorClosed = 5,      // no feasible drag between the corridor limits
  kExtractionFailed = 6,    // r(E) / gamma(E) / bank extraction impossible
  kNotConverged = 7,        // trajectory-length iteration did not meet tolerances
  kCapacityExceeded = 8,
  kRangeTooLong = 9,        // even the maximum-drag profile flies past the aim point (best effort given)
  kRangeTooShort = 10,      // even the longest-flying profile ends short of the aim point (best effort given)
};

const char* to_string(Status s);

/// A numerics status as a guidance status (kStepTooSmall, an integrator failure, as kNonFinite).
inline Status to_status(numerics::NumStatus s) {
  switch (s) {
    case numerics::NumStatus::kOk: return Status::kOk;
    case numerics::NumStatus::kInvalidInput: return Status::kInvalidInput;
    case numerics::NumStatus::kNoBracket: return Status::kNoBracket;
    case numerics::NumStatus::kMaxIterations: return Status::kMaxIterations;
    default: return Status::kNonFinite;
  }
}

/// Guidance phase, published in the command/status messages.
enum class Phase : std::int8_t {
  kInitialDescent = 0,      // hold attitude until the sensed drag passes a threshold
  kTracking = 1,            // drag/heading tracking of the plan
  kReversal = 2,            // open-loop bank reversal at maximum bank rate
  kTerminal = 3,            // close to TAEM
  kSafe = 4,                // link loss / invalid data: safe command held
};

/// Navigation-derived state relative to the rotating Earth (what guidance works with).
struct RelativeState {
  double t_s = 0.0;
  double radius_m = 0.0;
  double altitude_m = 0.0;            // above the spherical reference radius
  double longitude_rad = 0.0;
  double latitude_rad = 0.0;
  double velocity_mps = 0.0;          // Earth-relative
  double flight_path_rad = 0.0;
  double heading_rad = 0.0;
  double energy_Jpkg = 0.0;           // E = V^2/2 - mu/r + mu/R (7.8)
  double drag_mps2 = 0.0;             // sensed (IMU) drag acceleration
  double lift_mps2 = 0.0;             // sensed lift acceleration magnitude
  double lift_over_drag_scale = 1.0;  // sensed L/D over the on-board model's, filtered (1: model)
  double bank_rad = 0.0;              // bank flown (the law's filtered command, signed; planner input)
  double alpha_rad = 0.0;             // alpha flown (the law's filtered command; planner input, 0: not given)
};

/// x bounded to [lo, hi] (lo <= hi); a NaN passes through (the callers check finiteness).
inline double clamp(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

/// A planned reference over energy, produced by the planner, consumed by the tracker.
/// Points are ordered by decreasing energy (index 0 = planning state, last = TAEM).
struct ReferenceProfile {
  int n_points = 0;
  int seq = 0;                            // plan sequence number
  double energy_Jpkg[kProfileCapacity] = {};
  double e_norm[kProfileCapacity] = {};   // E / E_entry
  double drag_mps2[kProfileCapacity] = {};
  double drag_prime[kProfileCapacity] = {};    // dD/dE [1/m]
  double drag_second[kProfileCapacity] = {};   // d2D/dE2
  double a_coef[kProfileCapacity] = {};        // D'' = a + b (L/D) cos(sigma)  (7.17-7.20)
  double b_coef[kProfileCapacity] = {};
  double radius_m[kProfileCapacity] = {};
  double velocity_mps[kProfileCapacity] = {};
  double gamma_rad[kProfileCapacity] = {};
  double alpha_rad[kProfileCapacity] = {};
  double lift_over_drag[kProfileCapacity] = {};
  double sigma_rad[kProfileCapacity] = {};     // signed bank angle including the reversal
  double heading_rad[kProfileCapacity] = {};   // chi(E) from the reduced-order integration
  double dynamic_pressure_Pa[kProfileCapacity] = {};
  double drag_max_mps2[kProfileCapacity] = {};  // active path-constraint bound (7.3)-(7.6)
  double reversal_energy_Jpkg = 0.0;
  int initial_bank_sign = 1;                   // +1 right, -1 left (quadrant rule, fig. 7.20)
  double entry_energy_Jpkg = 0.0;              // normalisation energy
  double taem_energy_Jpkg = 0.0;
  double taem_altitude_m = 0.0;                // height above the ellipsoid the final drag is planned for
  double reversal_hold_energy_Jpkg = 0.0;      // predictor-corrector: the bank side held above it (0: none)
  // Planner diagnostics
  double dc_mps2 = 0.0;
  double e1_Jpkg = 0.0;
  double e2_Jpkg = 0.0;
  double trajectory_length_m = 0.0;
  double ranging_blend = 0.0;          // alpha moved this fraction towards alpha(L/D max) (ranging)
  double crossrange_err_m = 0.0;
  double downrange_err_m = 0.0;
  int iterations = 0;
  Status status = Status::kInvalidInput;
  bool converged = false;
};

}  // namespace reentry::fsw
