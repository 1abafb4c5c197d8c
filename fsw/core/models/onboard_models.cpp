#include "models/onboard_models.hpp"

#include <cmath>
#include <cstring>

#include "numerics/table_lookup.hpp"

namespace reentry::fsw {
namespace {

constexpr double kGammaAir = 1.4;
constexpr double kGasConstantAir = 287.05287;

// US 1976 temperature layers (geometric altitude approximation), used for the speed of
// sound when the exponential density model is selected.
double us76_temperature_K(double altitude_m) {
  static constexpr double kBase_m[] = {0.0, 11000.0, 20000.0, 32000.0, 47000.0, 51000.0, 71000.0, 84852.0};
  static constexpr double kBaseT_K[] = {288.15, 216.65, 216.65, 228.65, 270.65, 270.65, 214.65, 186.946};
  static constexpr double kLapse_Kpm[] = {-6.5e-3, 0.0, 1.0e-3, 2.8e-3, 0.0, -2.8e-3, -2.0e-3, 0.0};
  const double h = altitude_m < 0.0 ? 0.0 : altitude_m;
  int layer = 0;
  for (int i = 0; i < 8; ++i) {
    if (h >= kBase_m[i]) layer = i;
  }
  return kBaseT_K[layer] + kLapse_Kpm[layer] * (h - kBase_m[layer]);
}

// Interval j and weight w of the upper node of the grid g at q, clamped at the edges: the rules
// and the expression of numerics::bilinear's axes, which OnboardAero::MachSlice must equal bit
// for bit.
void clamped_interval(const double* g, int n, double q, int hint, int& j, double& w) {
  if (n < 2) {
    j = 0;
    w = 0.0;
    return;
  }
  j = numerics::bracket_index(g, n, q, hint);
  if (!(q > g[0])) {
    w = 0.0;
  } else if (q >= g[n - 1]) {
    w = 1.0;
  } else {
    w = (q - g[j]) / (g[j + 1] - g[j]);
  }
}

bool strictly_increasing(const double* x, int n) {
  for (int i = 1; i < n; ++i) {
    if (!(x[i] > x[i - 1])) return false;
  }
  return true;
}

}  // namespace

double gravity_mps2(double radius_m) { return kMuEarth_m3ps2 / (radius_m * radius_m); }

double level_flight_lift_need_mps2(double radius_m, double horizontal_speed_mps, double latitude_rad,
                                   double heading_rad) {
  const double v = horizontal_speed_mps;
  return gravity_mps2(radius_m) - v * v / radius_m -
         2.0 * kEarthRate_radps * v * std::cos(latitude_rad) * std::sin(heading_rad);
}

double specific_energy_Jpkg(double radius_m, double velocity_mps) {
  return 0.5 * velocity_mps * velocity_mps - kMuEarth_m3ps2 / radius_m + kMuEarth_m3ps2 / kEarthRadius_m;  // (7.8)
}

double surface_radius_m(double latitude_rad) { return surface_radius_from_sine_m(std::sin(latitude_rad)); }

double velocity_from_energy_mps(double energy_Jpkg, double radius_m) {
  const double v2 = 2.0 * (energy_Jpkg + kMuEarth_m3ps2 / radius_m - kMuEarth_m3ps2 / kEarthRadius_m);
  if (!(v2 >= 0.0)) return -1.0;
  return std::sqrt(v2);
}

double radius_for_speed_m(double energy_Jpkg, double velocity_mps) {
  // mu/r = mu/R - E + V^2/2
  const double mu_over_r = kMuEarth_m3ps2 / kEarthRadius_m - energy_Jpkg + 0.5 * velocity_mps * velocity_mps;
  if (!(mu_over_r > 0.0)) return -1.0;
  return kMuEarth_m3ps2 / mu_over_r;
}

// ---------------------------------------------------------------- atmosphere
Status OnboardAtmosphere::init_exponential() {
  kind_ = AtmosphereKind::kExponential;
  n_ = 0;
  return Status::kOk;
}

Status OnboardAtmosphere::init_table(const double* altitude_m, const double* density_kgpm3,
                                     const double* temperature_K, int n) {
  if (n > kCapacity) return Status::kCapacityExceeded;
  if (n < 2) return Status::kInvalidInput;
  for (int i = 0; i < n; ++i) {
    const double h = altitude_m[i], rho = density_kgpm3[i], t = temperature_K[i];
    if (!std::isfinite(h) || !(rho > 0.0) || !(t > 0.0) || !std::isfinite(rho) || !std::isfinite(t) ||
        (i > 0 && !(h > h_m_[i - 1]))) {
      return Status::kInvalidInput;
    }
    h_m_[i] = h;
    ln_rho_[i] = std::log(rho);
    temperature_K_[i] = t;
  }
  n_ = n;
  kind_ = AtmosphereKind::kTable;
  return Status::kOk;
}

int OnboardAtmosphere::segment(double altitude_m) const {
  hint_segment_ = numerics::bracket_index(h_m_, n_, altitude_m, hint_segment_);
  return hint_segment_;
}

double OnboardAtmosphere::density_kgpm3(double altitude_m) const {
  if (kind_ == AtmosphereKind::kExponential) return kRho0_kgpm3 * std::exp(-kBeta_pm * altitude_m);
  const int j = segment(altitude_m);
  const double slope = (ln_rho_[j + 1] - ln_rho_[j]) / (h_m_[j + 1] - h_m_[j]);
  return std::exp(ln_rho_[j] + slope * (altitude_m - h_m_[j]));  // linear extrapolation of ln rho outside
}

double OnboardAtmosphere::dlnrho_dr_pm(double altitude_m) const {
  if (kind_ == AtmosphereKind::kExponential) return -kBeta_pm;  // (7.16)
  const int j = segment(altitude_m);
  return (ln_rho_[j + 1] - ln_rho_[j]) / (h_m_[j + 1] - h_m_[j]);
}

double OnboardAtmosphere::speed_of_sound_mps(double altitude_m) const {
  double t_K = 0.0;
  if (kind_ == AtmosphereKind::kExponential) {
    t_K = us76_temperature_K(altitude_m);
  } else {
    const int j = segment(altitude_m);
    double w = (altitude_m - h_m_[j]) / (h_m_[j + 1] - h_m_[j]);
    w = w < 0.0 ? 0.0 : (w > 1.0 ? 1.0 : w);
    t_K = temperature_K_[j] + w * (temperature_K_[j + 1] - temperature_K_[j]);
  }
  return std::sqrt(kGammaAir * kGasConstantAir * t_K);
}

// ---------------------------------------------------------------- aero
Status OnboardAero::init(const double* alpha_rad, int n_alpha, const double* mach, int n_mach,
                         const double* cl, const double* cd) {
  if (n_alpha < 2 || n_mach < 1 || n_alpha > kMaxAlpha || n_mach > kMaxMach) return Status::kCapacityExceeded;
  if (!strictly_increasing(alpha_rad, n_alpha) || !strictly_increasing(mach, n_mach)) return Status::kInvalidInput;
  for (int i = 0; i < n_alpha * n_mach; ++i) {
    if (!std::isfinite(cl[i]) || !std::isfinite(cd[i]) || !(cd[i] > 0.0)) return Status::kInvalidInput;
  }
  n_alpha_ = n_alpha;
  n_mach_ = n_mach;
  std::memcpy(alpha_rad_, alpha_rad, sizeof(double) * static_cast<unsigned>(n_alpha));
  std::memcpy(mach_, mach, sizeof(double) * static_cast<unsigned>(n_mach));
  std::memcpy(cl_, cl, sizeof(double) * static_cast<unsigned>(n_alpha * n_mach));
  std::memcpy(cd_, cd, sizeof(double) * static_cast<unsigned>(n_alpha * n_mach));
  return Status::kOk;
}

Status OnboardAero::init_trimmed(const TrimAeroData& data) {
  double cl[TrimSurfaceData::kMaxNodes];
  double cd[TrimSurfaceData::kMaxNodes];
  const Status s = solve_trimmed_coefficients(data, cl, cd);
  if (s != Status::kOk) return s;
  return init(data.alpha_rad, data.n_alpha, data.mach, data.n_mach, cl, cd);
}

double OnboardAero::interpolate(const double* table, double alpha_rad, double mach) const {
  return numerics::bilinear(alpha_rad_, n_alpha_, mach_, n_mach_, table, alpha_rad, mach, &hint_alpha_,
                            &hint_mach_);  // clamped at the edges
}

void OnboardAero::coefficients(double alpha_rad, double mach, double& cl, double& cd) const {
  // Both tables share the grid: the Mach interval and the alpha interval are found once (the
  // slice's values are cl() and cd()'s bit for bit).
  const MachSlice slice = at_mach(mach);
  cl = slice.cl(alpha_rad);
  cd = slice.cd(alpha_rad);
  hint_alpha_ = slice.hint_alpha_;
}
double OnboardAero::cl(double alpha_rad, double mach) const { return lift_scale_ * interpolate(cl_, alpha_rad, mach); }
double OnboardAero::cd(double alpha_rad, double mach) const { return interpolate(cd_, alpha_rad, mach); }

OnboardAero::MachSlice OnboardAero::at_mach(double mach) const {
  MachSlice slice;
  slice.aero_ = this;
  clamped_interval(mach_, n_mach_, mach, hint_mach_, slice.j_, slice.w_);
  slice.j1_ = n_mach_ >= 2 ? slice.j_ + 1 : slice.j_;
  slice.hint_alpha_ = hint_alpha_;
  return slice;
}

double OnboardAero::MachSlice::interpolate_general(const double* v, double alpha_rad) const {
  const OnboardAero& a = *aero_;
  if (a.n_alpha_ < 1 || a.n_mach_ < 1) return 0.0;
  int i = 0;
  double wx = 0.0;
  clamped_interval(a.alpha_rad_, a.n_alpha_, alpha_rad, hint_alpha_, i, wx);
  if (a.n_alpha_ >= 2) hint_alpha_ = i;
  return combine(v, i, a.n_alpha_ >= 2 ? i + 1 : i, wx);
}

// ---------------------------------------------------------------- alpha profile
Status AlphaProfile::init(const double* e_norm, const double* alpha_rad, int n) {
  if (n < 1 || n > kCapacity) return Status::kCapacityExceeded;
  if (!strictly_increasing(e_norm, n)) return Status::kInvalidInput;
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(alpha_rad[i])) return Status::kInvalidInput;
    x_[i] = e_norm[i];
    alpha_rad_[i] = alpha_rad[i];
  }
  n_ = n;
  return Status::kOk;
}

double AlphaProfile::alpha_rad(double e_norm) const {
  return numerics::linear(x_, alpha_rad_, n_, e_norm);  // clamped
}

// ---------------------------------------------------------------- aggregate
void OnboardModels::set_vehicle(double mass_kg, double reference_area_m2, double nose_radius_m, HeatFluxModel heating) {
  mass_kg_ = mass_kg;
  area_over_mass_m2pkg_ = reference_area_m2 / mass_kg;
  nose_radius_m_ = nose_radius_m;
  heating_ = heating;
  if (heating == HeatFluxModel::kBettsLeadingEdge) {
    // Betts's fit q[BTU/(ft^2 s)] = qa(alpha) 17700 sqrt(rho[slug/ft^3]) (1e-4 v[ft/s])^3.07 with
    // the unit conversions folded into K: q[W/m^2] = qa(alpha) K sqrt(rho[kg/m^3]) V[m/s]^3.07.
    constexpr double kFoot_m = 0.3048;
    constexpr double kSlug_kg = 14.59390293720636;
    constexpr double kBtu_J = 1055.05585262;
    const double btu_per_ft2s_in_Wpm2 = kBtu_J / (kFoot_m * kFoot_m);
    const double slug_per_ft3_in_kgpm3 = kSlug_kg / (kFoot_m * kFoot_m * kFoot_m);
    heat_exponent_ = kBettsHeatC2;
    heat_constant_ = btu_per_ft2s_in_Wpm2 * 17700.0 / std::sqrt(slug_per_ft3_in_kgpm3) *
                     std::pow(1e-4 / kFoot_m, kBettsHeatC2);
  } else {
    // C of (3.6) from (3.5): c1 / (sqrt(RN) sqrt(rho0) Vc^c2), Vc = sqrt(mu / R).
    const double vc = std::sqrt(kMuEarth_m3ps2 / kEarthRadius_m);
    heat_exponent_ = kHeatC2;
    heat_constant_ =
        kHeatC1 / (std::sqrt(nose_radius_m_) * std::sqrt(OnboardAtmosphere::kRho0_kgpm3) * std::pow(vc, kHeatC2));
  }
}

Status OnboardModels::init_vehicle(double mass_kg, double reference_area_m2, double nose_radius_m,
                                   HeatFluxModel heating) {
  if (!(mass_kg > 0.0) || !(reference_area_m2 > 0.0) || !(nose_radius_m > 0.0) || !std::isfinite(mass_kg) ||
      !std::isfinite(reference_area_m2) || !std::isfinite(nose_radius_m)) {
    return Status::kInvalidInput;
  }
  set_vehicle(mass_kg, reference_area_m2, nose_radius_m, heating);
  return Status::kOk;
}

double OnboardModels::mach(double altitude_m, double velocity_mps) const {
  return velocity_mps / atmosphere_.speed_of_sound_mps(altitude_m);
}

bool has_mach_band(const TaemTarget& taem) {
  return taem.mach_target > 0.0 && taem.mach_tol > 0.0 && taem.mach_tol < kUnconstrained;
}

double OnboardModels::taem_altitude_depth(const TaemTarget& taem, double altitude_m) {
  return 1.0 - std::fabs(altitude_m - taem.altitude_m) / taem.altitude_tol_m;
}

double OnboardModels::taem_band_depth(const TaemTarget& taem, double taem_energy_Jpkg,
                                      double altitude_m) const {
  double depth = taem_altitude_depth(taem, altitude_m);
  if (has_mach_band(taem)) {
    const double v = taem_speed_mps(taem.latitude_rad, taem_energy_Jpkg, altitude_m);
    depth = std::fmin(depth, 1.0 - std::fabs(mach(altitude_m, v) - taem.mach_target) / taem.mach_tol);
  }
  return depth;
}

double OnboardModels::taem_speed_mps(double aim_latitude_rad, double taem_energy_Jpkg, double altitude_m) {
  return velocity_from_energy_mps(taem_energy_Jpkg, surface_radius_m(aim_latitude_rad) + altitude_m);
}

double OnboardModels::drag_mps2(double alpha_rad, double altitude_m, double velocity_mps) const {
  const double rho = atmosphere_.density_kgpm3(altitude_m);
  const double cd = aero_.cd(alpha_rad, mach(altitude_m, velocity_mps));
  return 0.5 * rho * velocity_mps * velocity_mps * cd * area_over_mass_m2pkg_;  // (D.1)
}

double OnboardModels::lift_mps2(double alpha_rad, double altitude_m, double velocity_mps) const {
  const double rho = atmosphere_.density_kgpm3(altitude_m);
  const double cl = aero_.cl(alpha_rad, mach(altitude_m, velocity_mps));
  return 0.5 * rho * velocity_mps * velocity_mps * cl * area_over_mass_m2pkg_;
}

double OnboardModels::drag_coefficient(double alpha_rad, double energy_Jpkg, double altitude_m) const {
  const double v = velocity_from_energy_mps(energy_Jpkg, kEarthRadius_m + altitude_m);
  return aero_.cd(alpha_rad, mach(altitude_m, v < 0.0 ? 0.0 : v));
}

double OnboardModels::drag_coefficient_slope(double alpha_a_rad, double energy_a_Jpkg, double altitude_a_m,
                                             double alpha_b_rad, double energy_b_Jpkg, double altitude_b_m) const {
  if (energy_a_Jpkg == energy_b_Jpkg) return 0.0;
  return (drag_coefficient(alpha_b_rad, energy_b_Jpkg, altitude_b_m) - drag_coefficient(alpha_a_rad, energy_a_Jpkg, altitude_a_m)) /
         (energy_b_Jpkg - energy_a_Jpkg);
}

double OnboardModels::dlnrho_dr_fd(double altitude_m, double step_m) const {
  return (std::log(atmosphere_.density_kgpm3(altitude_m + step_m)) - std::log(atmosphere_.density_kgpm3(altitude_m - step_m))) /
         (2.0 * step_m);
}

double OnboardModels::heat_flux_coefficient(double alpha_rad) const {
  if (heating_ == HeatFluxModel::kChapmanStagnation) return heat_constant_;  // (3.6)
  // Betts's alpha factor qa, alpha in degrees as published (Betts 2010, 6.1).
  const double a = alpha_rad * physics::kDegPerRad;
  const double qa = ((-1.0117249e-6 * a + 2.1286289e-4) * a - 1.9213774e-2) * a + 1.0672181;
  return qa * heat_constant_;
}

OnboardModels::HeatFluxFlow OnboardModels::heat_flux_flow(double density_kgpm3, double velocity_mps) const {
  return {std::sqrt(density_kgpm3), std::pow(velocity_mps, heat_exponent_)};
}

double OnboardModels::heat_flux_Wpm2(const HeatFluxFlow& flow, double alpha_rad) const {
  return heat_flux_coefficient(alpha_rad) * flow.sqrt_density * flow.velocity_power;  // (3.6)
}

double OnboardModels::sensed_dynamic_pressure_Pa(double drag_mps2, double cd) const {
  return cd > 0.0 ? drag_mps2 / (cd * area_over_mass_m2pkg_) : 0.0;
}

double OnboardModels::sensed_density_kgpm3(double drag_mps2, double velocity_mps, double cd) const {
  return density_of_dynamic_pressure_kgpm3(sensed_dynamic_pressure_Pa(drag_mps2, cd), velocity_mps);
}

double OnboardModels::density_of_dynamic_pressure_kgpm3(double dynamic_pressure_Pa, double velocity_mps) {
  const double v2 = velocity_mps * velocity_mps;
  return v2 > 0.0 ? 2.0 * dynamic_pressure_Pa / v2 : 0.0;
}

double OnboardModels::heat_flux_Wpm2(double density_kgpm3, double velocity_mps, double alpha_rad) const {
  return heat_flux_Wpm2(heat_flux_flow(density_kgpm3, velocity_mps), alpha_rad);
}

}  // namespace reentry::fsw
