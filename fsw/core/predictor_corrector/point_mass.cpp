#include "predictor_corrector/point_mass.hpp"

#include <cmath>

#include "models/lift_over_drag.hpp"
#include "numerics/runge_kutta.hpp"

namespace reentry::fsw {
namespace {

using Vec6 = std::array<double, 6>;

Vec6 to_array(const PointMassState& x) {
  return {x.radius_m, x.longitude_rad, x.latitude_rad, x.velocity_mps, x.flight_path_rad, x.heading_rad};
}

PointMassState from_array(const Vec6& a) { return {a[0], a[1], a[2], a[3], a[4], a[5]}; }

}  // namespace

void PointMassModel::init(const OnboardModels* models, const AlphaProfile* alpha_profile, double entry_energy_Jpkg,
                          double alpha_max_rad, double earth_rate_radps) {
  models_ = models;
  alpha_profile_ = alpha_profile;
  entry_energy_Jpkg_ = entry_energy_Jpkg;
  alpha_max_rad_ = alpha_max_rad;
  earth_rate_radps_ = earth_rate_radps;
  density_ratio_ = 1.0;
  alpha_shift_rad_ = 0.0;
  alpha_modulation_rad_ = 0.0;
  for (int j = 0; j < kLdMachSamples; ++j) {
    const double mach = kLdMachMax * j / (kLdMachSamples - 1);
    alpha_ld_rad_[j] = alpha_of_max_lift_over_drag_rad(models->aero(), mach, alpha_max_rad, kLdAlphaSteps, alpha_max_rad);
  }
}

double PointMassModel::alpha_max_lift_over_drag_rad(double mach) const {
  const double u = clamp(mach / kLdMachMax, 0.0, 1.0) * (kLdMachSamples - 1);
  const int j = static_cast<int>(std::fmin(std::floor(u), kLdMachSamples - 2));
  return alpha_ld_rad_[j] + (u - j) * (alpha_ld_rad_[j + 1] - alpha_ld_rad_[j]);
}

double PointMassModel::profile_alpha_at(double energy_Jpkg) const {
  return clamp(alpha_profile_->alpha_rad(energy_Jpkg / entry_energy_Jpkg_), 0.0, alpha_max_rad_);
}

double PointMassModel::scheduled_alpha_rad(double energy_Jpkg) const {
  return alpha_profile_->alpha_rad(energy_Jpkg / entry_energy_Jpkg_) + alpha_modulation_rad_;
}

double PointMassModel::shifted_alpha_rad(double scheduled_rad, double energy_Jpkg) const {
  if (alpha_shift_rad_ == 0.0) return clamp(scheduled_rad, 0.0, alpha_max_rad_);
  const double span = shift_e_full_Jpkg_ - shift_e_zero_Jpkg_;
  const double w = span > 0.0 ? clamp((energy_Jpkg - shift_e_zero_Jpkg_) / span, 0.0, 1.0) : 1.0;
  return clamp(scheduled_rad + w * alpha_shift_rad_, 0.0, alpha_max_rad_);
}

double PointMassModel::alpha_at(double energy_Jpkg) const {
  return shifted_alpha_rad(scheduled_alpha_rad(energy_Jpkg), energy_Jpkg);
}

double PointMassModel::alpha_at(double energy_Jpkg, double mach) const {
  const double scheduled = scheduled_alpha_rad(energy_Jpkg);
  const double shifted = shifted_alpha_rad(scheduled, energy_Jpkg);
  if (!(alpha_shift_rad_ < 0.0)) return shifted;
  const double profile = clamp(scheduled, 0.0, alpha_max_rad_);
  return std::fmax(shifted, std::fmin(profile, alpha_max_lift_over_drag_rad(mach)));
}

AeroSample PointMassModel::aero_at(const PointMassState& x) const { return aero_at(x, energy_of(x)); }

AeroSample PointMassModel::aero_at(const PointMassState& x, double energy_Jpkg) const {
  return aero_in_air(x, energy_Jpkg, air(x));
}

AeroSample PointMassModel::aero_in_air(const PointMassState& x, double energy_Jpkg, AeroSample a) const {
  add_aero(x, alpha_shift_rad_ < 0.0 ? alpha_at(energy_Jpkg, a.mach) : alpha_at(energy_Jpkg), a);
  return a;
}

AeroSample PointMassModel::aero(const PointMassState& x, double alpha_rad) const {
  AeroSample a = air(x);
  add_aero(x, alpha_rad, a);
  return a;
}

AeroSample PointMassModel::air(const PointMassState& x) const { return air(x, std::sin(x.latitude_rad)); }

AeroSample PointMassModel::air(const PointMassState& x, double sin_latitude) const {
  AeroSample a;
  a.altitude_m = x.radius_m - surface_radius_from_sine_m(sin_latitude);  // height_above_ellipsoid_m
  const OnboardAtmosphere& atmosphere = models_->atmosphere();
  a.density_kgpm3 = density_ratio_ * atmosphere.density_kgpm3(a.altitude_m);
  a.mach = x.velocity_mps / atmosphere.speed_of_sound_mps(a.altitude_m);
  return a;
}

void PointMassModel::add_aero(const PointMassState& x, double alpha_rad, AeroSample& a) const {
  a.alpha_rad = alpha_rad;
  models_->aero().coefficients(alpha_rad, a.mach, a.cl, a.cd);
  const double q_over_m = 0.5 * a.density_kgpm3 * x.velocity_mps * x.velocity_mps * models_->area_over_mass();
  a.drag_mps2 = q_over_m * a.cd;  // (D.1)
  a.lift_mps2 = q_over_m * a.cl;
}

void PointMassModel::derivatives(const PointMassState& x, double sigma_rad, PointMassState& dx, AeroSample* aux) const {
  derivatives_in_air(x, nullptr, sigma_rad, dx, aux);
}

void PointMassModel::derivatives_in_air(const PointMassState& x, const AeroSample* air_of_x, double sigma_rad,
                                        PointMassState& dx, AeroSample* aux) const {
  // Lu 2014 eq. (1)-(6) in SI (heading psi from North, clockwise; Earth rate w):
  //   r' = V sin g,  lon' = V cos g sin psi / (r cos lat),  lat' = V cos g cos psi / r,
  //   V' = -D - g0(r) sin g + w^2 r cos lat (sin g cos lat - cos g sin lat cos psi),
  //   g' = [L cos s + (V^2/r - g0(r)) cos g] / V + 2 w cos lat sin psi
  //        + w^2 r cos lat (cos g cos lat + sin g sin lat cos psi) / V,
  //   psi' = [L sin s / cos g + V^2 cos g sin psi tan lat / r] / V - 2 w (tan g cos psi cos lat - sin lat)
  //        + w^2 r sin lat cos lat sin psi / (V cos g).
  const double r = x.radius_m, V = x.velocity_mps, w = earth_rate_radps_;
  const double sg = std::sin(x.flight_path_rad), cg = std::cos(x.flight_path_rad);
  const double sp = std::sin(x.heading_rad), cp = std::cos(x.heading_rad);
  const double sl = std::sin(x.latitude_rad), cl = std::cos(x.latitude_rad);
  const AeroSample a = aero_in_air(x, energy_of(x), air_of_x != nullptr ? *air_of_x : air(x, sl));
  if (aux != nullptr) *aux = a;
  const double g = gravity_mps2(r);
  const double w2r = w * w * r;
  dx.radius_m = V * sg;
  dx.longitude_rad = V * cg * sp / (r * cl);
  dx.latitude_rad = V * cg * cp / r;
  dx.velocity_mps = -a.drag_mps2 - g * sg + w2r * cl * (sg * cl - cg * sl * cp);
  dx.flight_path_rad = (a.lift_mps2 * std::cos(sigma_rad) + (V * V / r - g) * cg) / V + 2.0 * w * cl * sp +
                       w2r * cl * (cg * cl + sg * sl * cp) / V;
  dx.heading_rad = (a.lift_mps2 * std::sin(sigma_rad) / cg + V * V * cg * sp * sl / (cl * r)) / V -
                   2.0 * w * (sg / cg * cp * cl - sl) + w2r * sl * cl * sp / (V * cg);
}

void PointMassModel::rk4(const PointMassState& x, double sigma_a_rad, double sigma_b_rad, double h_s,
                         PointMassState& out, const AeroSample* air_of_x) const {
  const double rate = h_s > 0.0 ? (sigma_b_rad - sigma_a_rad) / h_s : 0.0;
  // The first stage is evaluated at x itself (numerics::rk4_step): its air may be given.
  bool first_stage = true;
  auto f = [&](double t, const Vec6& y, Vec6& dy) {
    PointMassState d;
    const PointMassState at = from_array(y);
    derivatives_in_air(at, first_stage ? air_of_x : nullptr, sigma_a_rad + rate * t, d, nullptr);
    first_stage = false;
    dy = to_array(d);
  };
  Vec6 y_out{};
  numerics::rk4_step(f, 0.0, to_array(x), h_s, y_out);
  out = from_array(y_out);
}

PointMassState interpolate(const PointMassState& a, const PointMassState& b, double w) {
  auto lerp = [w](double p, double q) { return p + w * (q - p); };
  return {lerp(a.radius_m, b.radius_m),       lerp(a.longitude_rad, b.longitude_rad),
          lerp(a.latitude_rad, b.latitude_rad), lerp(a.velocity_mps, b.velocity_mps),
          lerp(a.flight_path_rad, b.flight_path_rad), lerp(a.heading_rad, b.heading_rad)};
}

PointMassState point_mass_from(const RelativeState& s) {
  return {s.radius_m, s.longitude_rad, s.latitude_rad, s.velocity_mps, s.flight_path_rad, s.heading_rad};
}

}  // namespace reentry::fsw
