#include "tracker/reversal_execution.hpp"

#include <cmath>

namespace reentry::fsw {

void ReversalExecution::init(const OnboardModels& models, const TrackerParams& params, double sigma_rate_max_radps) {
  bind(models, params);
  sigma_rate_max_radps_ = sigma_rate_max_radps;
  reset();
}

void ReversalExecution::reset() {
  until_t_s_ = -1.0;
  start_t_s_ = -1.0;
  sigma0_rad_ = 0.0;
  ends_in_final_window_ = false;
}

void ReversalExecution::begin(double t_s, double t_rev_s, double dt_s, double sigma0_rad, bool ends_in_final_window) {
  until_t_s_ = t_s + t_rev_s + dt_s;
  start_t_s_ = t_s;
  sigma0_rad_ = sigma0_rad;
  ends_in_final_window_ = ends_in_final_window;
}

bool ReversalExecution::modulation_allowed(double drag_ref, double drag_max, double drag_ratio) const {
  return !(drag_max > 0.0) || drag_ref < params_->modulation_bound_margin * drag_max * drag_ratio;
}

double ReversalExecution::lift_ratio(double sigma0_rad, double t_rel_s) const {
  const double sigma_now = std::fabs(sigma0_rad - sigma_rate_max_radps_ * t_rel_s);
  const double c_now = std::cos(std::fmin(sigma_now, 0.5 * M_PI));
  return c_now > 0.0 ? clamp(std::cos(sigma0_rad) / c_now, params_->modulation_min_lift_ratio, 1.0) : 1.0;
}

double ReversalExecution::modulated_alpha(double alpha_rad, double mach, double lift_ratio, double max_rad) const {
  const OnboardAero& aero = models_->aero();
  const double cl_ref = aero.cl(alpha_rad, mach);
  if (!(lift_ratio < 1.0) || !(cl_ref > 0.0)) return alpha_rad;
  double lo = std::fmax(0.0, alpha_rad - max_rad), hi = alpha_rad;
  // Only where lowering alpha lowers the lift (below alpha(C_L max)) and can reach the ratio;
  // elsewhere a lower alpha would only cost drag.
  constexpr double kDegree_rad = M_PI / 180.0;
  if (!(aero.cl(alpha_rad - kDegree_rad, mach) < cl_ref) || !(aero.cl(lo, mach) < lift_ratio * cl_ref)) return alpha_rad;
  for (int i = 0; i < kAlphaBisectionSteps; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (aero.cl(mid, mach) > lift_ratio * cl_ref) hi = mid; else lo = mid;
  }
  return 0.5 * (lo + hi);
}

double ReversalExecution::range_extension_m(const RelativeState& s, double mach, double alpha_rad,
                                            double sigma0_rad) const {
  // Over the reversal time T the vehicle covers V T whatever its drag, but dissipates only
  // int D_mod V dt; the energy saved, int (D - D_mod) V dt, is dissipated afterwards at the
  // drag D over a distance dS = V int (1 - C_D(alpha_mod(t)) / C_D(alpha)) dt (S = -int dE / D).
  if (!(sigma0_rad > 0.0)) return 0.0;
  const OnboardAero& aero = models_->aero();
  const double cd_ref = aero.cd(alpha_rad, mach);
  const double t_rev = 2.0 * sigma0_rad / sigma_rate_max_radps_;
  constexpr int kSamples = 20;  // midpoint quadrature of the modulated reversal
  double extension = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double t = (i + 0.5) * t_rev / kSamples;
    const double cd =
        aero.cd(modulated_alpha(alpha_rad, mach, lift_ratio(sigma0_rad, t), params_->final_modulation_max_rad), mach);
    if (cd_ref > 0.0) extension += (1.0 - cd / cd_ref) * s.velocity_mps * t_rev / kSamples;
  }
  return extension;
}

double ReversalExecution::alpha_command(double t_s, double alpha_rad, double mach, double sigma_cmd_rad,
                                        double sigma_flown_rad, double u_over_lod, bool final_reversal_done) const {
  // The roll from the bank flown now towards the command, at the maximum rate for the lead.
  const TrackerParams& p = *params_;
  const double max_roll_rad = sigma_rate_max_radps_ * p.modulation_lead_s;
  const double cos_lead = std::cos(sigma_flown_rad + clamp(sigma_cmd_rad - sigma_flown_rad, -max_roll_rad, max_roll_rad));
  // The modulation removes vertical lift the drag loop has not asked for: only while the
  // rolling bank gives more than the loop's demand u / (L/D).
  const bool lift_unwanted = cos_lead > 0.0 && cos_lead > u_over_lod;
  if (!(active(t_s) && started() && lift_unwanted)) return alpha_rad;
  // sigma(t) is the rate-limited roll, led by the filter lag. The final reversal (its climb
  // would set the TAEM altitude) keeps the full modulation; corridor reversals get less,
  // since their drag deficit is what the range control corrects late. So does a corridor
  // reversal that ends inside the final-reversal window: the climb it leaves would still be
  // recovered there, under the lift-down limit, when the final reversal starts.
  const double t_rel = t_s - start_t_s_ + p.modulation_lead_s;
  const bool deep = final_reversal_done || ends_in_final_window_;
  const double max_rad = deep ? p.final_modulation_max_rad : p.corridor_modulation_max_rad;
  return modulated_alpha(alpha_rad, mach, lift_ratio(sigma0_rad_, t_rel), max_rad);
}

}  // namespace reentry::fsw
