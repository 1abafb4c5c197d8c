// The adopted plan as the tracker reads it: the reference over energy, interpolated at the
// vehicle's energy (profile points are ordered by decreasing energy, index 0 = planning state).
#pragma once

#include "guidance_types.hpp"

namespace reentry::fsw {

/// The reference at one energy, linear in the plan's arrays (alpha' is the cell's slope): what
/// the tracker uses of the plan.
struct RefPoint {
  double drag = 0, drag_prime = 0, drag_second = 0;  // D, dD/dE, d2D/dE2
  double b = 0;                                      // b of D'' = a + b (L/D) cos(sigma) (7.20)
  double alpha = 0, alpha_prime = 0;                 // alpha and d alpha / dE
  double lod = 0, sigma = 0, heading = 0, q = 0;     // L/D, signed bank, heading, dynamic pressure
  double drag_max = 0;                               // active path-constraint bound (7.3)-(7.6)
};

class ReferenceTrack {
 public:
  /// q_ref of (3.13) is q_ref_fraction times the plan's largest dynamic pressure.
  void init(double q_ref_fraction) {
    q_ref_fraction_ = q_ref_fraction;
    has_profile_ = false;
  }
  /// Copies a trackable plan (no allocation): an ok plan, or the range-too-long maximum-drag
  /// best effort (see the executive). Returns false, keeping the old one, for any other.
  bool adopt(const ReferenceProfile& profile);
  bool has_profile() const { return has_profile_; }
  const ReferenceProfile& profile() const { return profile_; }
  /// Reference at `energy`; the cell found is kept as the start of the next search (and of
  /// the terminal range quadrature, cell()).
  RefPoint at(double energy_Jpkg);
  int cell() const { return hint_; }
  double q_ref_Pa() const { return q_ref_Pa_; }

 private:
  ReferenceProfile profile_;
  bool has_profile_ = false;
  int hint_ = 0;
  double q_ref_fraction_ = 0.3;
  double q_ref_Pa_ = 1.0;
};

}  // namespace reentry::fsw
