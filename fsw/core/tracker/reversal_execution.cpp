#include "tracker/reversal_execution.hpp"

#include <cmath>

#include "physics/earth_constants.hpp"

namespace reentry::fsw {
namespace {

// A modulation below alpha_ref at one Mach number and depth. What does not depend on the lift
// ratio (the table along alpha at that Mach, C_L at the reference and at the depth, whether a
// lower alpha lowers the lift) is looked up once, so that a quadrature over the roll repeats
// only the bisections; these run side by side (bisect). Each alpha comes from the same
// look-ups and comparisons as one modulation alone.
class AlphaModulation {
 public:
  static constexpr int kMaxBatch = 20;  // bisections run side by side

  AlphaModulation(const OnboardAero& aero, double alpha_rad, double mach, double max_rad)
      : aero_(aero.at_mach(mach)), alpha_rad_(alpha_rad), lo_rad_(std::fmax(0.0, alpha_rad - max_rad)),
        cl_ref_(aero_.cl(alpha_rad)) {
    if (cl_ref_ > 0.0) {
      lift_falls_ = aero_.cl(alpha_rad - physics::kRadPerDeg) < cl_ref_;
      cl_lo_ = aero_.cl(lo_rad_);
    }
  }
  const OnboardAero::MachSlice& aero() const { return aero_; }

  /// For k < n: alpha_out[k], the alpha with C_L(alpha) = lift_ratio[k] C_L(alpha_ref)
  /// (ReversalExecution::modulated_alpha), and cd_out[k] = C_D(alpha_out[k]) if cd_out is given.
  void solve(const double* lift_ratio, int n, double* alpha_out, double* cd_out) const {
    for (int k0 = 0; k0 < n; k0 += kMaxBatch) {
      const int m = n - k0 < kMaxBatch ? n - k0 : kMaxBatch;
      batch(lift_ratio + k0, m, alpha_out + k0, cd_out != nullptr ? cd_out + k0 : nullptr);
    }
  }

 private:
  // The bisections still to run: one chain per distinct C_L target, in increasing order.
  struct Chains {
    int n = 0;
    double target[kMaxBatch];
    int of_sample[kMaxBatch];  // chain of each sample, -1: alpha stays at alpha_ref
    double alpha[kMaxBatch];
    OnboardAero::MachSlice aero[kMaxBatch];  // each with its own search hint
  };

  void batch(const double* lift_ratio, int n, double* alpha_out, double* cd_out) const {
    Chains c;
    double target[kMaxBatch];
    int sample[kMaxBatch];
    int m = 0;
    for (int k = 0; k < n; ++k) {
      c.of_sample[k] = -1;
      if (!(lift_ratio[k] < 1.0) || !(cl_ref_ > 0.0)) continue;
      // Only where lowering alpha lowers the lift (below alpha(C_L max)) and can reach the
      // ratio; elsewhere a lower alpha would only cost drag.
      const double cl_target = lift_ratio[k] * cl_ref_;
      if (!lift_falls_ || !(cl_lo_ < cl_target)) continue;
      int q = m++;  // insertion by target
      for (; q > 0 && target[q - 1] > cl_target; --q) {
        target[q] = target[q - 1];
        sample[q] = sample[q - 1];
      }
      target[q] = cl_target;
      sample[q] = k;
    }
    for (int q = 0; q < m; ++q) {
      if (c.n == 0 || target[q] != c.target[c.n - 1]) c.target[c.n++] = target[q];
      c.of_sample[sample[q]] = c.n - 1;
    }
    bisect(c);
    const double cd_ref = cd_out != nullptr ? aero_.cd(alpha_rad_) : 0.0;
    for (int k = 0; k < n; ++k) {
      const int q = c.of_sample[k];
      alpha_out[k] = q < 0 ? alpha_rad_ : c.alpha[q];
      if (cd_out != nullptr) cd_out[k] = q < 0 ? cd_ref : c.aero[q].cd(c.alpha[q]);  // the chain's hint is there
    }
  }

  // The chains' bisections in lockstep: independent, so the processor overlaps their table
  // look-ups. Chains in target order share a bracket until they part (at each bracket the
  // targets part at one C_L value), and a shared midpoint is looked up once; the chain's slice
  // then takes its neighbour's search hint.
  void bisect(Chains& c) const {
    double lo[kMaxBatch], hi[kMaxBatch], mid[kMaxBatch], cl[kMaxBatch];
    for (int q = 0; q < c.n; ++q) {
      c.aero[q] = aero_;
      lo[q] = lo_rad_;
      hi[q] = alpha_rad_;
    }
    for (int i = 0; i < kAlphaBisectionSteps; ++i) {
      for (int q = 0; q < c.n; ++q) {
        mid[q] = 0.5 * (lo[q] + hi[q]);
        if (q > 0 && mid[q] == mid[q - 1]) {
          cl[q] = cl[q - 1];
          c.aero[q] = c.aero[q - 1];
        } else {
          cl[q] = c.aero[q].cl(mid[q]);
        }
      }
      for (int q = 0; q < c.n; ++q) (cl[q] > c.target[q] ? hi[q] : lo[q]) = mid[q];
    }
    for (int q = 0; q < c.n; ++q) c.alpha[q] = 0.5 * (lo[q] + hi[q]);
  }

  OnboardAero::MachSlice aero_;
  double alpha_rad_;
  double lo_rad_;            // the deepest alpha, alpha_ref - max (not below 0)
  double cl_ref_;
  double cl_lo_ = 0.0;       // C_L at lo_rad_
  bool lift_falls_ = false;  // C_L falls 1 deg below alpha_ref
};

}  // namespace

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
  return lift_ratio(sigma0_rad, std::cos(sigma0_rad), t_rel_s);
}

double ReversalExecution::lift_ratio(double sigma0_rad, double cos_sigma0, double t_rel_s) const {
  const double sigma_now = std::fabs(sigma0_rad - sigma_rate_max_radps_ * t_rel_s);
  const double c_now = std::cos(std::fmin(sigma_now, 0.5 * M_PI));
  return c_now > 0.0 ? clamp(cos_sigma0 / c_now, params_->modulation_min_lift_ratio, 1.0) : 1.0;
}

double ReversalExecution::modulated_alpha(double alpha_rad, double mach, double lift_ratio, double max_rad) const {
  double alpha_out = alpha_rad;
  AlphaModulation(models_->aero(), alpha_rad, mach, max_rad).solve(&lift_ratio, 1, &alpha_out, nullptr);
  return alpha_out;
}

double ReversalExecution::range_extension_m(const RelativeState& s, double mach, double alpha_rad,
                                            double sigma0_rad) const {
  // Over the reversal time T the vehicle covers V T whatever its drag, but dissipates only
  // int D_mod V dt; the energy saved, int (D - D_mod) V dt, is dissipated afterwards at the
  // drag D over a distance dS = V int (1 - C_D(alpha_mod(t)) / C_D(alpha)) dt (S = -int dE / D).
  if (!(sigma0_rad > 0.0)) return 0.0;
  const AlphaModulation modulation(models_->aero(), alpha_rad, mach, params_->final_modulation_max_rad);
  const double cd_ref = modulation.aero().cd(alpha_rad);
  const double t_rev = 2.0 * sigma0_rad / sigma_rate_max_radps_;
  constexpr int kSamples = 20;  // midpoint quadrature of the modulated reversal
  const double cos_sigma0 = std::cos(sigma0_rad);
  double ratio[kSamples], alpha_mod[kSamples], cd[kSamples];
  for (int i = 0; i < kSamples; ++i) ratio[i] = lift_ratio(sigma0_rad, cos_sigma0, (i + 0.5) * t_rev / kSamples);
  modulation.solve(ratio, kSamples, alpha_mod, cd);
  double extension = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    if (cd_ref > 0.0) extension += (1.0 - cd[i] / cd_ref) * s.velocity_mps * t_rev / kSamples;
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
