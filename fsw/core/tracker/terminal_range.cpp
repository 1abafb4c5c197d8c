#include "tracker/terminal_range.hpp"

#include <cmath>

namespace reentry::fsw {

void TerminalRangeControl::init(const OnboardModels& models, const TrackerParams& params, const TaemTarget& taem,
                                double terminal_energy_Jpkg, double taem_energy_Jpkg) {
  bind(models, params);
  taem_ = taem;
  terminal_energy_Jpkg_ = terminal_energy_Jpkg;
  taem_energy_Jpkg_ = taem_energy_Jpkg;
}

TerminalRange TerminalRangeControl::range_to_profile_end(const ReferenceTrack& reference, double energy,
                                                         double drag_here, double final_factor) const {
  // S = -int dE / D (C.2) and dS/dc = -int w / D^2 dE, D = k_f(E) D_ref with the final-drag
  // factor k_f = 1 + (k - 1)(1 - w).
  const ReferenceProfile& p = reference.profile();
  TerminalRange t;
  const double span = terminal_energy_Jpkg_ - taem_energy_Jpkg_;
  if (!(span > 0.0) || !(drag_here > 0.0)) return t;
  auto weight = [&](double e) { return terminal_weight(clamp((e - taem_energy_Jpkg_) / span, 0.0, 1.0)); };
  auto scaled = [&](double e, double d) { return d * (1.0 + (final_factor - 1.0) * (1.0 - weight(e))); };
  double e_prev = energy, inv_prev = 1.0 / scaled(energy, drag_here);
  double sens_prev = weight(energy) * inv_prev * inv_prev;
  t.range_m = 0.0;
  for (int j = reference.cell() + 1; j < p.n_points; ++j) {
    if (!(p.drag_mps2[j] > 0.0)) return TerminalRange{};
    const double inv = 1.0 / scaled(p.energy_Jpkg[j], p.drag_mps2[j]);
    const double sens = weight(p.energy_Jpkg[j]) * inv * inv;
    const double de = e_prev - p.energy_Jpkg[j];
    t.range_m += 0.5 * (inv_prev + inv) * de;
    t.sensitivity -= 0.5 * (sens_prev + sens) * de;
    e_prev = p.energy_Jpkg[j];
    inv_prev = inv;
    sens_prev = sens;
  }
  return t;
}

double TerminalRangeControl::final_drag_factor(double K, const ReferenceTrack& reference) const {
  // Flying the planned final drag D_f in air K times the model's meets the TAEM energy
  // H ln(K / k) above the planned altitude when the final drag is k D_f. Scaling by the whole
  // K (holding the planned altitude) makes the drag ramp by K - 1 over the terminal phase,
  // which costs range and heading; k = 1 leaves a too-dense or too-thin dispersion outside
  // the TAEM bands. So k is the value closest to 1 between 1 and K whose TAEM state stays in
  // the Mach band and within final_altitude_band_depth of the altitude band (K keeps moving
  // after k is chosen: the altitude keeps a margin, the Mach band none).
  const TrackerParams& p = *params_;
  if (!(taem_.altitude_tol_m > 0.0) || !reference.has_profile()) return K;
  const double planned_altitude_m = reference.profile().taem_altitude_m;
  for (int i = 0; i <= p.final_factor_samples; ++i) {
    const double k = 1.0 + (K - 1.0) * i / p.final_factor_samples;
    const double altitude_m = planned_altitude_m + OnboardAtmosphere::kScaleHeight_m * std::log(K / k);
    if (models_->taem_band_depth(taem_, taem_energy_Jpkg_, altitude_m) >= 0.0 &&
        OnboardModels::taem_altitude_depth(taem_, altitude_m) >= p.final_altitude_band_depth) {
      return k;
    }
  }
  return K;
}

}  // namespace reentry::fsw
