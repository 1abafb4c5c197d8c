// On-board environment and vehicle models used by the planner and the tracker.
//
// Simpler than the truth models on purpose (DESIGN §5): central gravity, exponential or
// tabulated atmosphere, the vehicle's basic aero tables. All data is copied into
// fixed-capacity arrays at initialisation (the process layer reads the files and hands the
// arrays over); after that nothing allocates and nothing does I/O. Independent code from
// sim_truth.
#pragma once

#include "guidance_types.hpp"
#include "mission_data.hpp"
#include "models/onboard_trim.hpp"
#include "physics/earth_constants.hpp"

namespace reentry::fsw {

// The Earth's constants (common/physics); the models built on them below are the flight's own.
inline constexpr double kMuEarth_m3ps2 = physics::kMuEarth_m3ps2;
inline constexpr double kEarthRadius_m = physics::kEarthEquatorialRadius_m;  // R_eq, reference radius of (7.8)
inline constexpr double kEarthRate_radps = physics::kEarthRate_radps;
inline constexpr double kG0_mps2 = physics::kStandardGravity_mps2;
inline constexpr double kEarthFlattening = physics::kEarthFlattening;

/// Radius of the reference ellipsoid at a latitude, first order in the flattening:
/// R_eq (1 - f sin^2(lat)). Altitudes at the edges (the mission's TAEM altitude, the air's
/// stratification) are heights above it, while the on-board models work with r - R_eq: at
/// 33 deg latitude the two differ by 6.4 km.
double surface_radius_m(double latitude_rad);
/// The same from sin(latitude) (a caller that has it already).
inline double surface_radius_from_sine_m(double sin_latitude) {
  return kEarthRadius_m * (1.0 - kEarthFlattening * sin_latitude * sin_latitude);
}

/// Central gravity g = mu / r^2.
double gravity_mps2(double radius_m);

/// Vertical acceleration lift must supply to hold level flight, (2.33) with gamma' = 0 (the
/// omega^2 terms dropped; in energy form the Earth-rate term is C_gamma of (7.18)):
/// g - V_h^2 / r - 2 omega V_h cos(lat) sin(chi) (an eastbound vehicle is held up by the
/// Earth-rate term). V_h: horizontal Earth-relative speed, chi: heading from north.
double level_flight_lift_need_mps2(double radius_m, double horizontal_speed_mps, double latitude_rad,
                                   double heading_rad);

/// Specific energy E = V^2/2 - mu/r + mu/R (7.8), R = R_eq.
double specific_energy_Jpkg(double radius_m, double velocity_mps);

/// The mission gives a Mach band at TAEM (target and a finite tolerance).
bool has_mach_band(const TaemTarget& taem);

/// V from (E, r) through (7.8); returns a negative value when the energy is too low
/// for the radius (V^2 < 0), so callers can detect an impossible point.
double velocity_from_energy_mps(double energy_Jpkg, double radius_m);

/// Radius at which (7.8) gives the speed velocity_mps for the energy (V^2 >= 0 above it fails).
double radius_for_speed_m(double energy_Jpkg, double velocity_mps);

enum class AtmosphereKind { kExponential, kTable };

/// rho(h), d(ln rho)/dr and speed of sound. Exponential (2.20): rho0 = 1.225, beta = 1/7050,
/// d(ln rho)/dr = -beta (7.15)-(7.16);
/// table: ln(rho) and T linear in altitude between the rows of a US76 table.
class OnboardAtmosphere {
 public:
  static constexpr int kCapacity = 2048;
  static constexpr double kRho0_kgpm3 = 1.225;
  static constexpr double kBeta_pm = 1.0 / 7050.0;
  static constexpr double kScaleHeight_m = 7050.0;  // 1 / beta (2.20): the gain rule's and the TAEM altitude's H

  Status init_exponential();
  /// Rows of geometric altitude (strictly increasing), density (> 0) and temperature (> 0).
  Status init_table(const double* altitude_m, const double* density_kgpm3, const double* temperature_K, int n);

  double density_kgpm3(double altitude_m) const;
  double dlnrho_dr_pm(double altitude_m) const;   // (1/rho) d rho / dr
  double speed_of_sound_mps(double altitude_m) const;
  AtmosphereKind kind() const { return kind_; }
  int size() const { return n_; }

 private:
  int segment(double altitude_m) const;
  mutable int hint_segment_ = -1;  // last altitude interval (search hint only, see OnboardAero)
  AtmosphereKind kind_ = AtmosphereKind::kExponential;
  int n_ = 0;
  double h_m_[kCapacity] = {};
  double ln_rho_[kCapacity] = {};
  double temperature_K_[kCapacity] = {};
};

/// CL and CD over (alpha, Mach), bilinear, clamped at the table edges: the basic tables, or
/// the trimmed ones solved at start-up (onboard_trim.hpp).
class OnboardAero {
 public:
  static constexpr int kMaxAlpha = 64;
  static constexpr int kMaxMach = 64;

  /// The tables along alpha at one Mach number, for searches in alpha at a fixed flight
  /// condition: the Mach interval and weight are found once (at_mach), each look-up then
  /// brackets alpha alone. Its values are those of cl() and cd() at that Mach bit for bit: the
  /// same clamping and the same bilinear expression, evaluated in the same order. Refers to
  /// the OnboardAero it came from: use it while that object, its tables and its lift scale
  /// stay as they are (within one cycle or one plan step). Copies are independent searches
  /// (each keeps its own hint); a default-constructed slice has no table and gives 0.
  class MachSlice {
   public:
    double cl(double alpha_rad) const {
      return aero_ == nullptr ? 0.0 : aero_->lift_scale_ * interpolate(aero_->cl_, alpha_rad);
    }
    double cd(double alpha_rad) const { return aero_ == nullptr ? 0.0 : interpolate(aero_->cd_, alpha_rad); }

   private:
    friend class OnboardAero;
    double interpolate(const double* table, double alpha_rad) const {
      const OnboardAero& a = *aero_;
      const double* x = a.alpha_rad_;
      const int i = hint_alpha_;
      // Inside the last interval (most steps of a search are): the interval and the weight
      // numerics::bilinear finds there (at x[0] the general path's literal 0 applies).
      if (i >= 0 && i + 1 < a.n_alpha_ && alpha_rad < x[i + 1] && (i > 0 ? x[i] <= alpha_rad : x[0] < alpha_rad)) {
        return combine(table, i, i + 1, (alpha_rad - x[i]) / (x[i + 1] - x[i]));
      }
      return interpolate_general(table, alpha_rad);
    }
    double interpolate_general(const double* table, double alpha_rad) const;
    /// numerics::bilinear's expression, Mach weight w_.
    double combine(const double* v, int i, int i1, double wx) const {
      const int ny = aero_->n_mach_;
      const double wy = w_;
      const double v00 = v[i * ny + j_];
      const double v01 = v[i * ny + j1_];
      const double v10 = v[i1 * ny + j_];
      const double v11 = v[i1 * ny + j1_];
      return (1.0 - wx) * ((1.0 - wy) * v00 + wy * v01) + wx * ((1.0 - wy) * v10 + wy * v11);
    }
    const OnboardAero* aero_ = nullptr;
    int j_ = 0;              // Mach interval [mach_j, mach_j1]
    int j1_ = 0;             // j + 1, or j with a single Mach
    double w_ = 0.0;         // weight of Mach node j1
    mutable int hint_alpha_ = -1;  // search hint only (numerics::bracket_index)
  };
  MachSlice at_mach(double mach) const;

  /// Trimmed C_L, C_D on the data's grid (solve_trimmed_coefficients). Start-up only.
  Status init_trimmed(const TrimAeroData& data);
  /// Tables over (alpha, Mach), row-major: values[i_alpha * n_mach + i_mach].
  Status init(const double* alpha_rad, int n_alpha, const double* mach, int n_mach,
              const double* cl, const double* cd);
  void coefficients(double alpha_rad, double mach, double& cl, double& cd) const;
  /// Scale on C_L (the in-flight L/D estimate over the table's; 1 = table).
  void set_lift_scale(double scale) { lift_scale_ = scale; }
  double lift_scale() const { return lift_scale_; }
  double cl(double alpha_rad, double mach) const;
  double cd(double alpha_rad, double mach) const;

 private:
  double interpolate(const double* table, double alpha_rad, double mach) const;
  // Last intervals found: successive lookups (the planner's grid, the tracker's bisections
  // at one Mach) mostly fall in the same or a neighbouring interval. A hint changes only the
  // search, never the interval found (numerics::bracket_index), so results are identical;
  // each instance belongs to one thread (planner worker or GNC cycle).
  mutable int hint_alpha_ = -1;
  mutable int hint_mach_ = -1;
  int n_alpha_ = 0;
  int n_mach_ = 0;
  double alpha_rad_[kMaxAlpha] = {};
  double mach_[kMaxMach] = {};
  double cl_[kMaxAlpha * kMaxMach] = {};
  double cd_[kMaxAlpha * kMaxMach] = {};
  double lift_scale_ = 1.0;
};

/// alpha over normalised energy E / E_entry, linear, clamped (mission.alpha_profile).
class AlphaProfile {
 public:
  static constexpr int kCapacity = 64;
  Status init(const double* e_norm, const double* alpha_rad, int n);
  double alpha_rad(double e_norm) const;

 private:
  int n_ = 0;
  double x_[kCapacity] = {};
  double alpha_rad_[kCapacity] = {};
};

/// Heat-flux model of the constrained point, q = C(alpha) sqrt(rho) V^c2 in both cases.
enum class HeatFluxModel {
  kChapmanStagnation,  // (3.5)/(3.6): C = c1 / (sqrt(RN) sqrt(rho0) Vc^c2), c2 = 3
  kBettsLeadingEdge,   // Betts 2010 sec. 6.1 Shuttle wing leading edge: C = qa(alpha) K, c2 = 3.07
};

/// Everything the planner needs about the vehicle and its environment.
class OnboardModels {
 public:
  /// Vehicle mass, reference area and nose radius (all > 0); the atmosphere and the aero
  /// tables are initialised through atmosphere() and aero().
  Status init_vehicle(double mass_kg, double reference_area_m2, double nose_radius_m,
                      HeatFluxModel heating = HeatFluxModel::kChapmanStagnation);

  const OnboardAtmosphere& atmosphere() const { return atmosphere_; }
  const OnboardAero& aero() const { return aero_; }
  OnboardAtmosphere& atmosphere() { return atmosphere_; }
  OnboardAero& aero() { return aero_; }

  /// Mass, area and the heat-flux model (nose_radius_m is used by kChapmanStagnation only).
  void set_vehicle(double mass_kg, double reference_area_m2, double nose_radius_m,
                   HeatFluxModel heating = HeatFluxModel::kChapmanStagnation);
  /// The aero tables are the start-up trim solution (moment and surface data, guidance.onboard_trim).
  bool aero_trimmed() const { return aero_trimmed_; }
  void set_aero_trimmed(bool trimmed) { aero_trimmed_ = trimmed; }
  double mass_kg() const { return mass_kg_; }
  double area_over_mass() const { return area_over_mass_m2pkg_; }
  /// The air a sensed drag implies through the on-board C_D S/m (D.1, D = q C_D S/m): the
  /// dynamic pressure q = D / (C_D S/m) and the density rho = 2 q / V^2. An error of the
  /// on-board C_D S/m moves both as it moves q itself. 0 without a positive C_D (or speed).
  double sensed_dynamic_pressure_Pa(double drag_mps2, double cd) const;
  double sensed_density_kgpm3(double drag_mps2, double velocity_mps, double cd) const;
  /// rho = 2 q / V^2 (0 without a speed): the density of a dynamic pressure already in hand.
  static double density_of_dynamic_pressure_kgpm3(double dynamic_pressure_Pa, double velocity_mps);

  double mach(double altitude_m, double velocity_mps) const;
  /// How deep a TAEM state at this altitude and the TAEM energy lies inside the mission's TAEM
  /// bands: min over {altitude, Mach} of 1 - |x - x_target| / tol (1: on target, 0: on an
  /// edge, < 0: outside); the altitude band alone when no Mach band is given (has_mach_band).
  /// Needs altitude_tol_m > 0.
  double taem_band_depth(const TaemTarget& taem, double taem_energy_Jpkg, double altitude_m) const;
  /// Speed at the TAEM energy at a height above the ellipsoid over the aim point (the energy
  /// (7.8) is taken at the radius surface_radius_m(aim latitude) + height).
  static double taem_speed_mps(double aim_latitude_rad, double taem_energy_Jpkg, double altitude_m);
  /// The altitude term of taem_band_depth alone. Needs altitude_tol_m > 0.
  static double taem_altitude_depth(const TaemTarget& taem, double altitude_m);
  /// Drag acceleration D = rho V^2 CD S / (2 m)  (D.1).
  double drag_mps2(double alpha_rad, double altitude_m, double velocity_mps) const;
  double lift_mps2(double alpha_rad, double altitude_m, double velocity_mps) const;
  /// C_D at (alpha, E, h): V from (7.8), Mach from the on-board speed of sound (7.9).
  double drag_coefficient(double alpha_rad, double energy_Jpkg, double altitude_m) const;
  /// dC_D/dE between two points of an (alpha(E), h(E)) path, central difference (7.14).
  double drag_coefficient_slope(double alpha_a_rad, double energy_a_Jpkg, double altitude_a_m, double alpha_b_rad,
                                double energy_b_Jpkg, double altitude_b_m) const;
  /// (1/rho) d rho / dr by a central difference of ln rho over +-step_m (7.14-7.16).
  double dlnrho_dr_fd(double altitude_m, double step_m) const;
  /// Heat flux of the vehicle's model, q = C(alpha) sqrt(rho) V^c2: Chapman stagnation point
  /// (3.5)/(3.6), c1/sqrt(RN) sqrt(rho/rho0) (V/Vc)^3, alpha-free; or Betts's leading edge.
  double heat_flux_Wpm2(double density_kgpm3, double velocity_mps, double alpha_rad) const;
  /// The flow's factors sqrt(rho) and V^c2 of q = C(alpha) sqrt(rho) V^c2, for the heat flux at
  /// many alphas in one flow (heat_flux_Wpm2 below).
  struct HeatFluxFlow {
    double sqrt_density = 0.0;
    double velocity_power = 0.0;
  };
  HeatFluxFlow heat_flux_flow(double density_kgpm3, double velocity_mps) const;
  double heat_flux_Wpm2(const HeatFluxFlow& flow, double alpha_rad) const;
  /// C(alpha) of q = C sqrt(rho) V^c2, SI (W/m^2 per sqrt(kg/m^3) (m/s)^c2).
  double heat_flux_coefficient(double alpha_rad) const;
  /// c2 of q = C sqrt(rho) V^c2.
  double heat_flux_velocity_exponent() const { return heat_exponent_; }
  static constexpr double kHeatC1 = 1.06584e8;  // (3.5), W/m^(3/2)
  static constexpr double kBettsHeatC2 = 3.07;  // Betts 2010, 6.1
  static constexpr double kHeatC2 = 3.0;

 private:
  OnboardAtmosphere atmosphere_;
  OnboardAero aero_;
  double mass_kg_ = 1.0;
  double area_over_mass_m2pkg_ = 0.0;
  double nose_radius_m_ = 1.0;
  HeatFluxModel heating_ = HeatFluxModel::kChapmanStagnation;
  double heat_constant_ = 0.0;  // Chapman: C; Betts: K, C = qa(alpha) K
  double heat_exponent_ = kHeatC2;
  bool aero_trimmed_ = false;
};

}  // namespace reentry::fsw
