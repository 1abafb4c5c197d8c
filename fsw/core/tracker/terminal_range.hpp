// Terminal range control (drag reference update, as the Shuttle's): over the terminal phase the
// range the plan still flies from here, S = -int dE / D_ref (C.2), is matched to the distance
// to the aim point along the arrival line by a drag increment that vanishes at the TAEM energy,
//   dD(E) = c w(E),  w = 1 - (1 - u)^2,  u = (E - E_f) / (E_t - E_f),
// with c from the linearised range dS/dc = -int w / D_ref^2 dE, re-solved every cycle and
// bounded. The final drag, which sets the TAEM altitude, is multiplied by the final-drag factor
// k (blended in over the phase): the part of the sensed drag ratio K that keeps the TAEM state
// inside its bands; the rest of K moves the TAEM altitude.
#pragma once

#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_models.hpp"
#include "tracker/reference_track.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

/// Weight of the terminal drag increment over u in [0, 1]: 1 at the phase start with zero
/// slope, 0 at TAEM. Quadratic rather than linear, so that late errors (the last corridor
/// reversals) still meet some authority.
inline double terminal_weight(double u) { return 1.0 - (1.0 - u) * (1.0 - u); }

struct TerminalRange {
  double range_m = -1.0;     // range to the end of the profile (C.2); < 0: undefined
  double sensitivity = 0.0;  // d range / d c of the terminal drag increment [m per m/s^2]
};

class TerminalRangeControl {
 public:
  void init(const OnboardModels& models, const TrackerParams& params, const TaemTarget& taem, double terminal_energy_Jpkg,
            double taem_energy_Jpkg);
  /// Points at the models and parameters (init, and again after the owner is copied).
  void bind(const OnboardModels& models, const TrackerParams& params) {
    models_ = &models;
    params_ = &params;
  }
  double terminal_energy_Jpkg() const { return terminal_energy_Jpkg_; }
  /// Of the sensed drag ratio K, the factor on the planned final drag that keeps the predicted
  /// TAEM state inside its bands (the value closest to 1 between 1 and K).
  double final_drag_factor(double drag_ratio, const ReferenceTrack& reference) const;
  /// Trapezoidal quadrature of S and dS/dc from `energy` (in the reference's present cell) to
  /// the profile end, with the final-drag factor applied.
  TerminalRange range_to_profile_end(const ReferenceTrack& reference, double energy, double drag_here,
                                     double final_factor) const;

  /// The drag reference at the present energy with the increment and the final-drag factor:
  /// ref.drag and its two energy derivatives change. along_track_m: distance to go along the
  /// arrival line; extension_m(): the range a final reversal still to come adds (called only
  /// when the increment is solved for); plan_bound_mps2: the plan's path-constraint bound,
  /// never exceeded by the increment. Returns the increment c.
  template <class Extension>
  double shape_reference(RefPoint& ref, double energy_Jpkg, double along_track_m, double drag_ratio,
                         const ReferenceTrack& reference, double plan_bound_mps2, Extension&& extension_m) const;

 private:
  const OnboardModels* models_ = nullptr;
  const TrackerParams* params_ = nullptr;
  TaemTarget taem_{};
  double terminal_energy_Jpkg_ = 0.0;
  double taem_energy_Jpkg_ = 0.0;
};

template <class Extension>
double TerminalRangeControl::shape_reference(RefPoint& ref, double energy, double along_track_m, double drag_ratio,
                                             const ReferenceTrack& reference, double plan_bound,
                                             Extension&& extension_m) const {
  const TrackerParams& p = *params_;
  const double e_t = terminal_energy_Jpkg_;
  const double span = e_t - taem_energy_Jpkg_;
  const double u = clamp((energy - taem_energy_Jpkg_) / span, 0.0, 1.0);
  const double w_here = terminal_weight(u);
  const double dw_dE = 2.0 * (1.0 - u) / span, d2w_dE2 = -2.0 / (span * span);
  const double k = final_drag_factor(drag_ratio, reference);
  const double k_f = 1.0 + (k - 1.0) * (1.0 - w_here);
  const TerminalRange tr = range_to_profile_end(reference, energy, ref.drag, k);
  double c = 0.0;
  if (along_track_m > p.terminal_min_range_m && tr.range_m > 0.0 && tr.sensitivity < 0.0) {
    const double c_max = p.terminal_increment_max_fraction * ref.drag;
    c = clamp((along_track_m - tr.range_m - extension_m()) / tr.sensitivity, -c_max, c_max);
  }
  const double d0 = ref.drag, d0p = ref.drag_prime;
  // The increment never takes the reference past the plan's path-constraint bound.
  if (d0 * k_f + c * w_here > plan_bound && w_here > 0.0) c = (plan_bound - d0 * k_f) / w_here;
  ref.drag = d0 * k_f + c * w_here;
  ref.drag_prime = d0p * k_f + (c - (k - 1.0) * d0) * dw_dE;
  ref.drag_second = ref.drag_second * k_f - 2.0 * (k - 1.0) * d0p * dw_dE + (c - (k - 1.0) * d0) * d2w_dE2;
  return c;
}

}  // namespace reentry::fsw
