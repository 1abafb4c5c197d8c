// Mission and vehicle configuration as loaded from config/*.toml.
//
// This is start-up data: std::vector and std::string are fine here. The flight
// software copies what it needs into fixed-capacity structures at initialisation;
// the truth simulator builds its own models from the same data. SI units inside,
// angles in radians; the TOML files use the units named in their keys (e.g.
// `heading_deg`) and the loader converts.
#pragma once

#include <limits>

#include "mission/mission_interface.hpp"
#include "physics/earth_constants.hpp"
#include <string>
#include <vector>

namespace reentry::config {

inline constexpr double kNotConstrained = mission::kUnconstrained;

/// Values over (alpha, Mach), row-major: values[i_alpha * mach.size() + i_mach].
struct Table2D {
  std::vector<double> alpha_rad;  // strictly increasing
  std::vector<double> mach;       // strictly increasing
  std::vector<double> values;     // alpha_rad.size() * mach.size()
  bool empty() const { return values.empty(); }
};

/// y(x) with x strictly increasing.
struct Table1D {
  std::vector<double> x;
  std::vector<double> y;
};

/// Aerodynamic increments of one control surface, one (alpha, Mach) table per deflection.
struct ControlSurface {
  std::string name;                     // "body_flap", "elevon"
  int count = 1;                        // number of identical surfaces (elevons: 2, thesis 3.24)
  double min_rad = 0.0;                 // deflection limits
  double max_rad = 0.0;
  std::vector<double> deflection_rad;   // strictly increasing, includes 0
  std::vector<Table2D> dcl, dcd, dcm;   // one per deflection, same grid as the base tables
};

/// Query outside the table range: clamp to the edge (default), or reject.
enum class OutOfRangePolicy { kClamp, kError };

struct AeroModel {
  std::string source;                   // public source or documented model, quoted in the file
  double reference_length_m = 0.0;      // pitching-moment reference length
  Table2D cl, cd;                       // basic (untrimmed, surfaces neutral)
  Table2D cm;                           // empty when no moment data exists (trim then unavailable)
  std::vector<ControlSurface> surfaces; // trim priority order: body flap first, then elevons (thesis 3.4)
  double flap_fixed_rad = 0.0;          // body-flap setting used below q_flap_fixed_Pa (thesis 5.5)
  double q_flap_fixed_Pa = 100.0;
  OutOfRangePolicy out_of_range = OutOfRangePolicy::kClamp;
};

/// Heat-flux model of the point whose limit the mission constrains (`vehicle.heating_model`).
enum class HeatingModel {
  kChapmanStagnation,  // "chapman_stagnation": stagnation point at the nose radius (thesis 3.5)
  kBettsLeadingEdge,   // "betts_leading_edge": Shuttle wing leading edge, alpha dependent (Betts 2010, 6.1)
};

struct Vehicle {
  std::string name;
  double mass_kg = 0.0;
  double reference_area_m2 = 0.0;
  double nose_radius_m = 0.0;     // used by chapman_stagnation
  HeatingModel heating_model = HeatingModel::kChapmanStagnation;
  AeroModel aero;
};

/// The interface types are shared with the flight software and the truth model
/// (common/mission/mission_interface.hpp): entry state relative to the rotating Earth, TAEM
/// interface with its tolerances (thesis 3.1.2 for X-33 / HORUS; adopted and justified in the
/// file otherwise), path and control limits.
using SphericalState = mission::EntryInterface;
using TaemInterface = mission::TaemTarget;
using PathConstraints = mission::PathLimits;

/// A number of the [guidance] section that the loader passes through uninterpreted: the
/// tunables of the planner and the tracker, which the flight software's own parameter lists
/// validate (fsw/guidance/mission_adapter). Keys of [guidance.planner] / [guidance.tracker]
/// come as "planner.<key>" / "tracker.<key>".
struct TuningValue {
  std::string key;
  double value = 0.0;
  bool integer = false;  // written as a TOML integer
};

struct GuidanceParams {
  double gnc_rate_hz = 10.0;
  int plan_latency_ticks = 5;            // lockstep: plan requested at k is adopted at k + L
  double replan_period_s = 50.0;
  double replan_drag_error_frac = 0.15;  // replan when |D - Dref| / Dref exceeds this
  double drag_error_replan_spacing_s = 5.0;  // ... at most once in this time (optional key)
  std::string drag_profile = "smooth";   // "three_segment" (thesis 7.2) or "smooth"
  std::string initial_drag = "actual";   // "actual" or "lmin" (thesis 7.6)
  std::string onboard_atmosphere = "exponential";  // "exponential" or "table"
  bool onboard_trim = true;              // trimmed on-board aero tables where moment data exist
  double initial_descent_drag_mps2 = 0.05 * physics::kStandardGravity_mps2;  // hold attitude until sensed drag exceeds this
  std::vector<TuningValue> tuning;       // planner / tracker tunables, in file order of their tables
  // Guidance law: "drag_tracking" (planner + tracker) or "predictor_corrector"
  // (fsw/core/predictor_corrector); the latter's tunables ([guidance.predictor_corrector]) come
  // through `tuning` as "predictor_corrector.<key>".
  std::string law = "drag_tracking";
};

struct SimParams {
  std::string integrator = "rkf56";      // "rkf56" or "rkf78"
  double rel_tol = 1e-10;
  double abs_tol_position_m = 1e-4;
  double abs_tol_velocity_mps = 1e-7;
  std::string gravity = "j2j4";          // "central", "j2j4", "sh20"
  std::string atmosphere = "us76";       // "us76", "exponential"
  bool wind = true;
  std::string shape = "oblate";          // "sphere", "oblate"
  bool trim = true;                      // when moment data exist
  std::string attitude = "ideal";        // "ideal" or "lag"
  double attitude_time_constant_s = 0.5;
  int transport_delay_ticks = 0;
  double time_limit_s = 4000.0;
};

/// Distribution of one dispersed quantity (`distribution`, `<quantity>_distribution`).
enum class Distribution {
  kGaussian,  // "gaussian": the number is 3 sigma; draws are truncated at 3 sigma
  kUniform,   // "uniform": the number is the half-width
};

/// One dispersed quantity: offsets and scale factors are centred on the nominal value.
struct Dispersion {
  double value = 0.0;  // 3 sigma (gaussian) or half-width (uniform), SI
  Distribution distribution = Distribution::kGaussian;
};

/// Monte Carlo dispersions of one campaign set ([dispersions] or [stress_dispersions]), SI.
struct Dispersions {
  Dispersion entry_flight_path_rad;
  Dispersion entry_heading_rad;
  Dispersion entry_velocity_mps;
  Dispersion entry_position_rad;         // lat/lon
  Dispersion density_scale;              // fraction
  double density_perturbation = 0.0;     // amplitude of the altitude-correlated part (a random shape)
  double density_correlation_m = 10000.0;
  Dispersion cl_scale;
  Dispersion cd_scale;
  Dispersion mass_scale;
  // Wind profile scale over [min, max]: uniform over it, or gaussian about its centre with
  // 3 sigma at its ends.
  double wind_scale_min = 1.0;
  double wind_scale_max = 1.0;
  Distribution wind_scale_distribution = Distribution::kGaussian;
};

/// Environment data files (paths resolved relative to the mission file).
struct EnvironmentData {
  std::string us76_table;
  std::string gravity_coefficients;
  std::string wind_profile;
};

struct Mission {
  std::string name;                      // e.g. "x33"
  std::string source_file;               // absolute path of the mission file
  // FNV-1a 64 of every file the mission was loaded from (mission, vehicle, environment), in
  // hex: two runs flew the same mission exactly when their digests are equal.
  std::string digest;
  std::string notes;                     // provenance of the numbers
  Vehicle vehicle;
  SphericalState entry;
  TaemInterface taem;
  PathConstraints constraints;
  Table1D alpha_profile;                 // alpha_rad over normalised energy E/E_entry (x increasing)
  // [alpha_profile] source = "planned": no table in the file; the guidance plans the profile at
  // start-up with the angle-of-attack planner (thesis ch. 6) and fills alpha_profile.
  bool alpha_profile_planned = false;
  GuidanceParams guidance;
  SimParams sim;
  Dispersions dispersions;               // reference campaigns (and seeded SIL runs)
  // [stress_dispersions]: a second, named set (tools/mc --dispersions stress); optional.
  bool has_stress_dispersions = false;
  Dispersions stress_dispersions;
  EnvironmentData environment;
};

/// Result of loading: ok, or an error message naming file, key and value.
struct LoadResult {
  bool ok = false;
  std::string error;
  Mission mission;
};

/// Load and validate a mission file. `name_or_path` is a path to a .toml file or a
/// mission name ("x33", "horus", "orbiter", "x38") looked up in the config directory.
LoadResult load_mission(const std::string& name_or_path);

/// The rules a mission's values and data files must meet to be flown: "" or an error naming
/// the file, the key and the value. load_mission applies them after reading a file, and the
/// truth simulator applies them again to the mission it is given (Simulator::create): the
/// loader and the simulator accept exactly the same missions.
std::string check_mission(const Mission& mission);

/// One-line human summary: vehicle, mass, S_ref, entry and TAEM state, limits in SI.
std::string summary_line(const Mission& mission);

}  // namespace reentry::config
