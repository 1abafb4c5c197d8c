// Truth-model translational dynamics (thesis §2.6.1): Cartesian position and velocity in the
// inertial I-frame (2.23)-(2.31) plus the integrated stagnation-point heat load, propagated by
// an adaptive embedded Runge-Kutta method with events located by root finding.
//
// The I-frame coincides with the Earth-fixed R-frame at t = 0; the R-frame rotates about +Z
// at omega. Commands (alpha, sigma) are piecewise constant between calls of set_command();
// advance_to() restarts the integrator exactly at every command change.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "dynamics/dispersions.hpp"
#include "dynamics/point_model.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::truth {

enum class GravityChoice { kFromConfig, kCentral, kJ2J4, kSphericalHarmonics20 };
enum class AtmosphereChoice { kFromConfig, kUS76, kExponential };
enum class ShapeChoice { kFromConfig, kSphere, kOblate };
enum class IntegratorChoice { kFromConfig, kRkf56, kRkf78 };
enum class AttitudeChoice { kFromConfig, kIdeal, kLag };
enum class WindChoice { kFromConfig, kOn, kOff };

/// Overrides of the mission's [sim] section; kFromConfig / negative values keep the config.
struct SimOverrides {
  GravityChoice gravity = GravityChoice::kFromConfig;
  AtmosphereChoice atmosphere = AtmosphereChoice::kFromConfig;
  WindChoice wind = WindChoice::kFromConfig;
  ShapeChoice shape = ShapeChoice::kFromConfig;
  IntegratorChoice integrator = IntegratorChoice::kFromConfig;
  AttitudeChoice attitude = AttitudeChoice::kFromConfig;
  double rel_tol = -1.0;
  double abs_tol_position_m = -1.0;
  double abs_tol_velocity_mps = -1.0;
  double time_limit_s = -1.0;
  int trim = -1;                          // -1: config, 0: off, 1: on (when moment data exist)
  DispersionDraw dispersion;              // default: nominal
};

enum class SimEvent { kNone, kTaemEnergy, kGroundImpact, kSkipOut, kTimeOut, kFailure };
const char* to_string(SimEvent e);

/// Everything a plot, a test or the telemetry message needs at one instant.
struct TruthSample {
  double t_s = 0.0;
  double h_m = 0.0;               // above the configured shape (sphere: R_eq)
  double r_m = 0.0;
  double lat_rad = 0.0;           // geocentric latitude
  double lon_rad = 0.0;
  double V_mps = 0.0;             // Earth-relative
  double gamma_rad = 0.0;         // Earth-relative flight-path angle
  double chi_rad = 0.0;           // heading from North, clockwise, in (-pi, pi]
  double airspeed_mps = 0.0;
  double mach = 0.0;
  double rho_kgpm3 = 0.0;
  double q_Pa = 0.0;
  double qdot_Wpm2 = 0.0;         // the vehicle's heating model: Chapman (3.5) or Betts's leading edge
  double Q_Jpm2 = 0.0;            // integrated heat load
  double n_g = 0.0;               // body-normal load factor (3.7), in g
  double D_mps2 = 0.0;            // drag acceleration
  double L_mps2 = 0.0;            // lift acceleration
  double E_Jpkg = 0.0;            // V^2/2 - mu/r + mu/R_eq, Earth-relative V (7.8)
  double alpha_rad = 0.0;         // achieved attitude
  double sigma_rad = 0.0;
  double flap_rad = 0.0;
  double elevon_rad = 0.0;
  double q_alpha_Pa_rad = 0.0;
  double range_to_taem_m = 0.0;   // great-circle arc to the TAEM aim point on the R_eq sphere
  double heading_to_taem_rad = 0.0;  // initial great-circle bearing to the aim point
};

/// What an ideal navigation system would deliver (inertial, plus the IMU's aero acceleration).
struct NavSample {
  double t_s = 0.0;
  Eigen::Vector3d r_I_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_I_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d aero_accel_I_mps2 = Eigen::Vector3d::Zero();
  double earth_rotation_angle_rad = 0.0;  // omega * t
};

struct RunMaxima {
  double qdot_Wpm2 = 0.0, qdot_t_s = 0.0;
  double n_g = 0.0, n_g_t_s = 0.0;
  double q_Pa = 0.0, q_t_s = 0.0;
  double q_alpha_Pa_rad = 0.0, q_alpha_t_s = 0.0;
};

struct RunSummary {
  SimEvent event = SimEvent::kNone;
  TruthSample final_state;
  RunMaxima maxima;
  std::int64_t derivative_evaluations = 0;
  std::int64_t steps_accepted = 0;
  std::int64_t steps_rejected = 0;
  double wall_s = 0.0;            // wall time spent inside advance_to()
  std::string message;            // failure reason, if any
};

/// Resolved settings (config plus overrides) the simulator runs with.
struct ResolvedSimSettings {
  std::string gravity, atmosphere, shape, integrator, attitude;
  bool wind = false;
  bool trim = false;
  double rel_tol = 0.0, abs_tol_position_m = 0.0, abs_tol_velocity_mps = 0.0, abs_tol_heat_Jpm2 = 0.0;
  double time_limit_s = 0.0;
  double attitude_time_constant_s = 0.0;
  double alpha_rate_max_radps = 0.0, sigma_rate_max_radps = 0.0;  // 0: unlimited
  double mass_kg = 0.0;
  double E_taem_Jpkg = 0.0;
  double skip_out_altitude_m = 0.0;
  DispersionDraw dispersion;  // applied draw (nominal when !dispersion.dispersed)
};

class Simulator {
 public:
  static constexpr int kStates = 7;  // r_I (3), V_I (3), heat load Q
  using State = std::array<double, kStates>;

  /// Builds the environment and vehicle models and the entry state. nullptr and *error set on
  /// failure (missing data file, unknown option, invalid entry state).
  static std::unique_ptr<Simulator> create(const config::Mission& mission, const SimOverrides& overrides,
                                           std::string* error);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// Commanded attitude from now on (held until the next call).
  void set_command(double alpha_rad, double sigma_rad);
  /// Integrates to t_s, or to the first event before it. Returns the event (kNone: reached t_s).
  SimEvent advance_to(double t_s);

  double time_s() const { return t_s_; }
  bool finished() const { return event_ != SimEvent::kNone; }
  SimEvent event() const { return event_; }
  const State& state() const { return y_; }
  TruthSample sample() const;
  NavSample nav_sample() const;
  RunSummary summary() const;
  const ResolvedSimSettings& settings() const { return settings_; }
  const config::Mission& mission() const { return mission_; }
  /// Energy (7.8) of the TAEM interface: V_taem^2/2 - mu/r_taem + mu/R_eq, r_taem the radius at
  /// the TAEM altitude above the run's shape model at the TAEM latitude (radius_at_altitude_m:
  /// R_eq + h_taem on the sphere, (2.13) on the oblate Earth).
  double taem_energy_Jpkg() const { return settings_.E_taem_Jpkg; }
  /// Energy of the entry state (for schedules in normalised energy E/E_entry).
  double entry_energy_Jpkg() const { return E_entry_Jpkg_; }
  /// The run's truth models at one instant (dispersions applied), as the integrator sees them;
  /// the trajectory optimizer evaluates the same object with AD scalars.
  const PointModel& point_model() const;

 private:
  struct Models;
  struct Attitude;  // achieved attitude model of one command segment

  Simulator();
  void derivatives(double t, const State& y, State& dydt) const;
  PointOutputs<double> evaluate(double t, const State& y, bool full) const;  // full: also the outputs
  void attitude_at(double t, double* alpha_rad, double* sigma_rad) const;
  double next_attitude_breakpoint(double after_t) const;
  void start_segment();
  // Steps of create(): "" or what is wrong.
  std::string resolve_settings(const SimOverrides& ov);
  std::string build_models(const SimOverrides& ov);
  std::string set_entry_state(const DispersionDraw& disp);
  void update_maxima(const TruthSample& s);
  // Event functions: negative when the event has happened.
  std::array<double, 4> event_functions(double t, const State& y) const;
  /// The earliest event whose function is <= 0 at the end of the accepted step of length h
  /// from (t_s_, y_): -1 when none, else its index with its time offset and state.
  int earliest_event(double h, const std::array<double, 4>& g_new, double* tau_fired, State* y_fired) const;

  config::Mission mission_;
  ResolvedSimSettings settings_;
  std::unique_ptr<Models> models_;
  std::unique_ptr<Attitude> attitude_;

  double t_s_ = 0.0;
  State y_{};
  double h_next_s_ = 1.0;
  double E_entry_Jpkg_ = 0.0;
  SimEvent event_ = SimEvent::kNone;
  std::string failure_;
  RunMaxima maxima_;
  mutable std::int64_t evaluations_ = 0;
  std::int64_t accepted_ = 0, rejected_ = 0;
  double wall_s_ = 0.0;
};

/// Parse "central"/"j2j4"/"sh20" etc. (command line and config spellings). false if unknown.
bool parse_gravity(const std::string& s, GravityChoice* out);
bool parse_atmosphere(const std::string& s, AtmosphereChoice* out);
bool parse_shape(const std::string& s, ShapeChoice* out);
bool parse_integrator(const std::string& s, IntegratorChoice* out);
bool parse_attitude(const std::string& s, AttitudeChoice* out);

}  // namespace reentry::truth
