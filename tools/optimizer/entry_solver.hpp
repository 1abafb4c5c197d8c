// Solving a run's entry problem: warm start from a flown trajectory, the figures of a solution
// (constraint maxima and margins, the TAEM miss as the referee computes it), and the
// independent check of the optimizer's dynamics: the optimal control history flown open loop
// in the truth simulator.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dynamics/simulator.hpp"
#include "entry_problem.hpp"
#include "evaluation/mission_verdict.hpp"
#include "hermite_simpson.hpp"
#include "mesh_refinement.hpp"

namespace reentry::optimal {

/// One sample of a flown trajectory: the simulator state and the command in effect after t.
struct FlownSample {
  double t_s = 0.0;
  std::array<double, 6> y{};  // r_I [m], v_I [m/s]
  double alpha_rad = 0.0, sigma_rad = 0.0;
};

/// Settings of an entry solve.
struct EntrySolveOptions {
  // Hermite-Simpson segments of the first solve, uniform in time; refinement adds segments
  // where the local error is largest (mesh_refinement.hpp).
  int segments = 80;
  /// > 0: alpha within this band of the mission's alpha profile (EntryProblem); 0: free.
  double alpha_band_rad = 0.0;
  SolverOptions solver = default_solver();
  RefinementOptions refinement;
  /// Footprint modes: EntryProblem's extent limit (a step of the footprint's homotopy).
  double extent_limit_m = std::numeric_limits<double>::infinity();
  /// Newton on the exact Hessian of the Lagrangian (second-order AD of the smooth models),
  /// piecewise-linear controls (the free Hermite-Simpson midpoint control zig-zags and its
  /// open-loop replay missed by 150-350 km). A warm start sits next to the optimum, so the
  /// barrier starts small (with IPOPT's 0.1, or 1e-3, the barrier terms of the ~600 path rows
  /// coupled to the margin outweigh the objective and push the margin the wrong way for tens of
  /// iterations). The max-min objective has many optima (every control history that keeps the
  /// binding constraints where they are): a small proximity term picks the one closest to the
  /// start, and a small smoothing term (the integral of (du/dtau)^2 in control scales) the
  /// smoothest of those near it. The proximity term alone leaves the Hessian nearly singular
  /// along control histories that trade one reversal's timing against another's: IPOPT then
  /// regularises every iteration and creeps to the optimum in tens of short steps. The smoothing
  /// weight is small against the margin (a fraction of each limit; the value of both terms at
  /// the solution is reported as its "regularisation") and large enough to give Newton a regular
  /// Hessian along those directions.
  static SolverOptions default_solver() {
    SolverOptions s;
    s.exact_hessian = true;
    s.linear_controls = true;
    s.mu_init = 1e-5;
    s.control_proximity = 3e-2;
    s.control_smoothing = 3e-5;
    s.constr_mult_init_max = 0.0;
    s.max_iterations = 1500;  // bounded by max_wall_s too; far-downrange footprint homotopy steps need more than 500
    s.max_wall_s = 60.0;
    return s;
  }
};

/// A solution's figures, in the referee's terms.
struct EntryFigures {
  double tf_s = 0.0;
  double margin = 0.0;                    // -s (kMaxMargin): common margin, fraction of each limit/tolerance; NaN otherwise
  /// kMaxMargin: the objective's secondary terms at the solution (control proximity, the miss):
  /// what they may have cost the margin. NaN otherwise.
  double regularisation = 0.0;
  double miss_m = 0.0, along_m = 0.0, cross_m = 0.0;
  double altitude_err_m = 0.0, mach = 0.0, gamma_rad = 0.0, heading_err_rad = 0.0;
  double final_lat_rad = 0.0, final_lon_rad = 0.0;  // geocentric, of the final point
  double max_heat_flux_Wpm2 = 0.0, max_load_g = 0.0, max_q_Pa = 0.0, max_q_alpha_Pa_rad = 0.0;
  double max_altitude_m = 0.0;
  /// Margins as fractions (1 - value / limit, or 1 - |error| / tolerance); NaN: not constrained.
  double margin_heat_flux = 0.0, margin_load = 0.0, margin_q = 0.0, margin_q_alpha = 0.0;
  double margin_range = 0.0, margin_altitude = 0.0, margin_mach = 0.0, margin_gamma = 0.0, margin_heading = 0.0;
  /// Every constraint within its limit (with 1e-6 relative slack on the path constraints) at the
  /// collocation points.
  bool all_satisfied = false;
};

struct EntryResult {
  std::string error;           // set when the problem could not be set up
  EntryMode mode = EntryMode::kMinMiss;
  Solution solution;           // the last converged solve (or the first solve when none converged)
  EntryFigures figures;
  std::vector<MeshPass> passes;  // every solve of the refinement sequence
  double wall_s = 0.0;           // all of them, with the error estimates
  int segments() const { return (solution.trajectory.points() - 1) / 2; }
};

/// The initial guess on `mesh` interpolated (linearly in time) from a flown trajectory that
/// ends at the TAEM event: t_f = the last sample's time.
Trajectory guess_from_flown(const std::vector<FlownSample>& flown, const Mesh& mesh);

/// Solves one run's problem from `guess` (its mesh: every other point a node), then corrects the
/// models and refines the mesh (mesh_refinement.hpp). `sim` is the run's simulator right after
/// create().
EntryResult solve_entry(const truth::Simulator& sim, EntryMode mode, const Trajectory& guess,
                        const EntrySolveOptions& options, double downrange_m = 0.0);

/// Figures of a trajectory of `problem` (double evaluation of the same functions).
EntryFigures evaluate_figures(const EntryProblem& problem, const Trajectory& trajectory);

/// A solve for the record: status, iterations, wall time, its mesh passes and the figures.
nlohmann::json result_json(const EntryResult& r);

/// The trajectory's points in the referee's terms (one per collocation point).
struct TrackPoint {
  double t_s, lat_rad, lon_rad, h_m, V_mps, gamma_rad, chi_rad, mach, qdot_Wpm2, n_g, q_Pa, alpha_rad, sigma_rad;
};
std::vector<TrackPoint> track(const EntryProblem& problem, const Trajectory& trajectory);

/// The control history of a solution at time t: linear between the collocation points (which
/// keeps the rate limits), held outside.
void control_at(const Trajectory& trajectory, double t_s, double* alpha_rad, double* sigma_rad);

/// The optimal control history flown open loop in a fresh truth simulator of the same run
/// (`sim` right after create()): commands at the mission's GNC rate, each the mean of the
/// solution's control over its tick.
struct ReplayResult {
  truth::RunSummary summary;
  truth::MissionVerdict verdict;
  double final_position_diff_m = 0.0;  // |r_R(replay) - r_R(solution)| at the TAEM energy
  double final_time_diff_s = 0.0;
  double final_altitude_diff_m = 0.0, final_mach_diff = 0.0, final_heading_diff_rad = 0.0;
};
ReplayResult replay_open_loop(truth::Simulator& sim, const EntryProblem& problem, const Trajectory& solution);

}  // namespace reentry::optimal
