// On-board point-mass equations of motion of the predictor (Vinh's Earth-relative variables over
// a rotating spherical Earth, as in Lu 2014 eq. (1)-(6) in SI): radius, longitude, latitude,
// speed, flight-path angle and heading (from North, clockwise) with the Coriolis and centripetal
// terms; central gravity; the on-board atmosphere taken at the height above the WGS-84 ellipsoid
// (the air's stratification, models/onboard_models.hpp) scaled by the sensed density ratio K;
// the on-board aero tables at the mission's alpha profile with the in-flight L/D estimate.
// No heap, no exceptions; the caller bounds every loop.
#pragma once

#include <array>

#include "guidance_types.hpp"
#include "models/onboard_models.hpp"

namespace reentry::fsw {

/// Earth-relative state of the point mass (SI, radians).
struct PointMassState {
  double radius_m = 0.0;
  double longitude_rad = 0.0;
  double latitude_rad = 0.0;
  double velocity_mps = 0.0;
  double flight_path_rad = 0.0;
  double heading_rad = 0.0;
};

/// The air and the aerodynamic accelerations at one state and alpha.
struct AeroSample {
  double altitude_m = 0.0;     // above the ellipsoid
  double density_kgpm3 = 0.0;  // K times the model's
  double mach = 0.0;
  double alpha_rad = 0.0;
  double cl = 0.0, cd = 0.0;   // lift scaled by the L/D estimate
  double drag_mps2 = 0.0;
  double lift_mps2 = 0.0;
};

/// Height above the ellipsoid of a radius at a latitude (surface_radius_m, first order in f).
inline double height_above_ellipsoid_m(double radius_m, double latitude_rad) {
  return radius_m - surface_radius_m(latitude_rad);
}

class PointMassModel {
 public:
  /// The models and the alpha profile are referenced (they outlive the model); alpha is the
  /// profile's at E / entry_energy, within [0, alpha_max]. earth_rate_radps: kEarthRate_radps
  /// on board (0 in analytic tests).
  void init(const OnboardModels* models, const AlphaProfile* alpha_profile, double entry_energy_Jpkg,
            double alpha_max_rad, double earth_rate_radps = kEarthRate_radps);
  /// Sensed density ratio K (density = K rho_model) of the prediction.
  void set_density_ratio(double k) { density_ratio_ = k; }
  double density_ratio() const { return density_ratio_; }
  /// Alpha of the prediction: the profile's (within [0, alpha_max]) plus the shift, ramped
  /// linearly from full at e_full to zero at e_zero (and below). A negative (ranging) shift
  /// stops at the alpha of maximum L/D at the state's Mach (alpha_at(e, mach)): below it the
  /// shift would lose L/D, not gain it, and raise q for the drag flown.
  void set_alpha_shift(double shift_rad, double e_full_Jpkg, double e_zero_Jpkg) {
    alpha_shift_rad_ = shift_rad;
    shift_e_full_Jpkg_ = e_full_Jpkg;
    shift_e_zero_Jpkg_ = e_zero_Jpkg;
  }
  /// An offset on top (the reversal's lift modulation of one guidance step; 0 outside).
  void set_alpha_modulation(double offset_rad) { alpha_modulation_rad_ = offset_rad; }
  double alpha_at(double energy_Jpkg) const;
  double alpha_at(double energy_Jpkg, double mach) const;
  /// Air and aerodynamics of a state at its alpha of the prediction (alpha_at(e, Mach)).
  AeroSample aero_at(const PointMassState& x) const;
  /// The same with the energy of the alpha schedule given (a point sampled on an energy).
  AeroSample aero_at(const PointMassState& x, double energy_Jpkg) const;
  /// Alpha of maximum L/D at a Mach number (the start-up scan, linear in Mach between samples).
  double alpha_max_lift_over_drag_rad(double mach) const;
  double profile_alpha_at(double energy_Jpkg) const;
  AeroSample aero(const PointMassState& x, double alpha_rad) const;
  /// State derivative at bank sigma (signed, > 0 turns right); aux, if given, gets the air.
  void derivatives(const PointMassState& x, double sigma_rad, PointMassState& dx, AeroSample* aux) const;
  /// One RK4 step of h seconds with the bank linear from sigma_a to sigma_b over the step.
  /// air_of_x, if given, is air(x) (altitude, density, Mach of x: any AeroSample of x from this
  /// model, e.g. aero_at(x)); the first stage then uses it instead of evaluating it again.
  void rk4(const PointMassState& x, double sigma_a_rad, double sigma_b_rad, double h_s, PointMassState& out,
           const AeroSample* air_of_x = nullptr) const;
  const OnboardModels& models() const { return *models_; }
  double earth_rate_radps() const { return earth_rate_radps_; }
  double entry_energy_Jpkg() const { return entry_energy_Jpkg_; }

 private:
  /// The profile's alpha plus the modulation offset at an energy (unclamped, unshifted).
  double scheduled_alpha_rad(double energy_Jpkg) const;
  /// The scheduled alpha with the shift's ramp at that energy, within [0, alpha_max].
  double shifted_alpha_rad(double scheduled_rad, double energy_Jpkg) const;
  /// aero_at(x, e) on the air sample `a` of x (its altitude, density and Mach are kept).
  AeroSample aero_in_air(const PointMassState& x, double energy_Jpkg, AeroSample a) const;
  /// derivatives() on the air sample of x (evaluated here when null).
  void derivatives_in_air(const PointMassState& x, const AeroSample* air_of_x, double sigma_rad, PointMassState& dx,
                          AeroSample* aux) const;
  /// Altitude, density and Mach of a state (the air part of an AeroSample).
  AeroSample air(const PointMassState& x) const;
  /// The same with sin(latitude) given.
  AeroSample air(const PointMassState& x, double sin_latitude) const;
  /// Alpha, coefficients, drag and lift at alpha onto the air sample of the same state.
  void add_aero(const PointMassState& x, double alpha_rad, AeroSample& a) const;

  const OnboardModels* models_ = nullptr;
  const AlphaProfile* alpha_profile_ = nullptr;
  double entry_energy_Jpkg_ = 1.0;
  double alpha_max_rad_ = 0.0;
  double earth_rate_radps_ = kEarthRate_radps;
  double density_ratio_ = 1.0;
  double alpha_shift_rad_ = 0.0;
  double alpha_modulation_rad_ = 0.0;
  double shift_e_full_Jpkg_ = 0.0;
  double shift_e_zero_Jpkg_ = 0.0;
  // Alpha of maximum L/D scanned at start-up on kLdMachSamples Mach numbers 0..kLdMachMax.
  static constexpr int kLdMachSamples = 48;
  static constexpr double kLdMachMax = 40.0;
  static constexpr int kLdAlphaSteps = 400;  // scan of [0, alpha_max]
  double alpha_ld_rad_[kLdMachSamples] = {};
};

/// E = V^2/2 - mu/r + mu/R_eq (7.8) of a state.
inline double energy_of(const PointMassState& x) { return specific_energy_Jpkg(x.radius_m, x.velocity_mps); }

/// x_a + w (x_b - x_a), componentwise (angles are continuous along a prediction).
PointMassState interpolate(const PointMassState& a, const PointMassState& b, double w);

/// The navigated state as a point-mass state, and back (t, drag and lift of `like` kept).
PointMassState point_mass_from(const RelativeState& s);

}  // namespace reentry::fsw
