// Open-loop flight of a tabulated alpha/sigma schedule with the truth simulator: the logic of
// `reentry_sim --open-loop`, kept in the library so Monte Carlo and tests reuse it.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "dynamics/simulator.hpp"

namespace reentry::truth {

/// alpha(x), sigma(x) with x = time [s] or normalised energy E/E_entry; linear interpolation,
/// held constant outside the table.
struct OpenLoopProfile {
  enum class Variable { kTime, kEnergyNorm };
  Variable variable = Variable::kTime;
  std::vector<double> x;          // strictly increasing
  std::vector<double> alpha_rad;
  std::vector<double> sigma_rad;
  void command_at(double x_query, double* alpha_rad_out, double* sigma_rad_out) const;
};

/// Reads a CSV with header `t_s,alpha_deg,sigma_deg` or `E_norm,alpha_deg,sigma_deg` (blank
/// lines and lines starting with '#' are skipped). Rows may be given in increasing or decreasing
/// x but must be strictly monotonic. Errors name the file, line and offending value.
bool load_open_loop_profile(const std::string& path, OpenLoopProfile* profile, std::string* error);

/// Flies the schedule: the command is sampled at every GNC tick (mission.guidance.gnc_rate_hz)
/// and held until the next; `on_sample` receives t = 0, every multiple of out_dt_s, and the final
/// (event) state. Runs until an event (TAEM energy, ground, skip-out, time-out).
RunSummary run_open_loop(Simulator& sim, const OpenLoopProfile& profile, double out_dt_s,
                         const std::function<void(const TruthSample&)>& on_sample);

/// The entry descent flown wings level at the constant alpha `alpha_rad` (sigma = 0, the most
/// vertical lift the vehicle has when C_L rises up to that alpha) from the simulator's present
/// state until the Earth-relative flight-path angle first reaches zero (the bottom of the first
/// pull-out) or an event ends the flight. A bank only lowers the vertical lift and so deepens
/// the pull-out: the maxima returned (heat flux, q, q alpha, load factor at every accepted
/// integrator step) are the least any guidance can reach at the bottom of the entry descent.
/// Bounded by the simulator's time limit.
RunMaxima wings_level_pullout_maxima(Simulator& sim, double alpha_rad);

/// Trajectory CSV: header line, and one row per sample, SI units except angles in degrees.
void write_trajectory_header(std::ostream& out);
void write_trajectory_row(std::ostream& out, const TruthSample& s);

/// One line of JSON (no newline): event, final state, maxima, wall time, evaluations, settings.
std::string summary_json(const RunSummary& summary, const Simulator& sim);

}  // namespace reentry::truth
