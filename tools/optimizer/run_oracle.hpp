// The oracle of one Monte Carlo run: fly the run closed loop (the guidance's trajectory is the
// warm start), then solve the run's entry problem on its own truth models, and fly the optimal
// control history open loop in the truth simulator (the independent check).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "closed_loop.hpp"
#include "entry_solver.hpp"

namespace reentry::optimal {

struct OracleOptions {
  EntryMode mode = EntryMode::kMaxMargin;
  EntrySolveOptions solve;
  bool replay = true;  // fly the solution open loop in the truth simulator
  /// Solve also the runs the cheap verdicts decide: a guidance success (feasible by its own
  /// flight) and a run whose wings-level pull-out at alpha_max already exceeds a path limit
  /// (infeasible: no guidance does better at the first pull-out). Off in campaigns, where the
  /// optimizer then judges only the runs nothing else decides; on, it checks both verdicts.
  bool solve_decided = false;
  /// A run is infeasible when the maximum common margin converges below -infeasible_margin
  /// (and below minus the solve's regularisation terms, EntryFigures::regularisation) from both
  /// starts: the guidance's flight and the neighbouring solution.
  double infeasible_margin = 1e-3;
  /// Second start: a solution of a neighbouring problem (the mission's nominal run); null: the
  /// nominal maximum-margin solution, solved once per process and mission.
  std::shared_ptr<const Trajectory> neighbour;
};

/// What the oracle can say about a run, strongest first. A run is feasible when a flight in the
/// truth simulator proves it: the guidance's own (a success), or the optimal control history
/// flown open loop and judged a success by the referee. It is infeasible when the maximum
/// common margin converges below zero from two different starts (a local optimum of a
/// discretised problem each time: the best found, twice), or by the wings-level pull-out bound
/// (kPulloutBound: tools::wings_level_pullout_bound). Anything else is undecided, with the
/// reason (OracleResult::reason).
enum class Feasibility { kFlown, kProvenOpenLoop, kInfeasible, kPulloutBound, kUndecided };
const char* to_string(Feasibility f);

/// One solve of the oracle and its open-loop flight.
struct OracleAttempt {
  std::string start;  // "guidance", "guidance_refined" (a tighter mesh from its solution), "neighbour"
  EntryResult entry;
  bool replayed = false;
  ReplayResult replay;
};

struct OracleResult {
  std::string error;
  tools::ClosedLoopResult flown;   // the guidance's flight of the run
  tools::PulloutBound pullout;     // the cheap physics bound of the first pull-out
  bool solved = false;             // the optimizer ran (else a cheap verdict decided)
  std::vector<OracleAttempt> attempts;
  EntryResult entry;               // the deciding attempt (the best margin when none decides)
  bool optimizer_feasible = false; // that attempt converged with every constraint of the collocated trajectory met
  bool replayed = false;
  ReplayResult replay;             // its open-loop flight
  Feasibility feasibility = Feasibility::kUndecided;
  bool feasible = false;           // kFlown or kProvenOpenLoop
  std::string reason;              // why undecided (or how infeasible was decided)
  double solve_s = 0.0;            // every attempt's solves
};

/// The guidance's closed-loop flight of a run, with its trajectory sampled at every GNC tick.
struct GuidanceFlight {
  tools::ClosedLoopResult result;
  std::vector<FlownSample> samples;  // ends at the run's end event
};
GuidanceFlight fly_guidance(const config::Mission& mission, std::uint64_t seed, bool dispersed);

/// The truth simulator of a run (the draw of run `seed` when dispersed), as every run tool makes it.
std::unique_ptr<truth::Simulator> make_run_simulator(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                                                     std::string* error);

/// Flies run `seed` closed loop and its wings-level pull-out bound, and solves its entry problem
/// warm-started from that flight unless a cheap verdict decides (OracleOptions::solve_decided).
OracleResult run_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed, const OracleOptions& options);

/// The same from a given flown trajectory (ending at the TAEM event) and its verdict.
OracleResult solve_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                          const std::vector<FlownSample>& flown, bool flown_success, const OracleOptions& options);

/// The mission's nominal maximum-margin solution (the neighbouring start of the dispersed runs),
/// solved once per process for each mission and alpha band; null when it did not converge.
std::shared_ptr<const Trajectory> nominal_solution(const config::Mission& mission, const OracleOptions& options);

/// The oracle's part of a campaign run record: its verdict, and the solves when the optimizer judged.
nlohmann::json oracle_record(const OracleResult& o);

}  // namespace reentry::optimal
