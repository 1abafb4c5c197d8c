// Reversal execution: a bank sign change is flown open loop at the maximum bank rate (the rate
// filter after the tracker limits the rate), t_rev = 2 |sigma| / sigma_rate_max, with the drag
// integrator frozen. Meanwhile alpha is lowered so that C_L cos(sigma(t)) stays C_L cos(sigma0):
// the roll through wings level would otherwise leave a climb that the drag loop cannot remove
// before TAEM.
#pragma once

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

class ReversalExecution {
 public:
  void init(const OnboardModels& models, const TrackerParams& params, double sigma_rate_max_radps);
  /// Points at the models and parameters (init, and again after the owner is copied).
  void bind(const OnboardModels& models, const TrackerParams& params) {
    models_ = &models;
    params_ = &params;
  }
  void reset();
  /// A reversal from bank magnitude sigma0 starts at t_s and lasts t_rev (plus one cycle);
  /// `ends_in_final_window`: judged at its start on the time to go.
  void begin(double t_s, double t_rev_s, double dt_s, double sigma0_rad, bool ends_in_final_window);
  bool active(double t_s) const { return t_s < until_t_s_; }
  bool started() const { return start_t_s_ >= 0.0; }

  /// The modulation is allowed only while the drag reference is below modulation_bound_margin
  /// of the path-constraint bound (times the sensed drag ratio K), so that the range control
  /// can still add the drag it costs.
  bool modulation_allowed(double drag_ref_mps2, double drag_max_mps2, double drag_ratio) const;
  /// cos(sigma0) / cos(sigma(t)) for the rate-limited roll sigma(t) = sigma0 - rate t, bounded.
  double lift_ratio(double sigma0_rad, double t_rel_s) const;
  /// alpha with C_L(alpha) = lift_ratio C_L(alpha_ref), by bisection below alpha_ref (bounded),
  /// at most max_rad below it; only where a lower alpha lowers the lift.
  double modulated_alpha(double alpha_rad, double mach, double lift_ratio, double max_rad) const;
  /// Range added by one modulated reversal flown now from sigma0 (final-reversal depth).
  double range_extension_m(const RelativeState& s, double mach, double alpha_rad, double sigma0_rad) const;

  /// The modulated alpha command this cycle (alpha_rad when no modulation applies).
  /// sigma_cmd_rad: the signed bank commanded now; sigma_flown_rad: the bank flown now;
  /// u_over_lod: the drag loop's demand u / (L/D). The full depth applies after the final
  /// reversal started and to a corridor reversal that ends inside the final-reversal window.
  double alpha_command(double t_s, double alpha_rad, double mach, double sigma_cmd_rad, double sigma_flown_rad,
                       double u_over_lod, bool final_reversal_done) const;

 private:
  /// lift_ratio with cos(sigma0) given (a quadrature over the roll computes it once).
  double lift_ratio(double sigma0_rad, double cos_sigma0, double t_rel_s) const;

  const OnboardModels* models_ = nullptr;
  const TrackerParams* params_ = nullptr;
  double sigma_rate_max_radps_ = 0.0;
  double until_t_s_ = -1.0;
  double start_t_s_ = -1.0;   // start of the last reversal
  double sigma0_rad_ = 0.0;   // bank magnitude at its start
  bool ends_in_final_window_ = false;
};

}  // namespace reentry::fsw
