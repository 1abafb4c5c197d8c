// The oracle of one Monte Carlo run: fly the run closed loop (the guidance's trajectory is the
// warm start), then solve the run's entry problem on its own truth models, and optionally fly
// the optimal control history open loop in the truth simulator (the independent check).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

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
};

/// What the oracle can say about a run, strongest first. A run is feasible when a flight in
/// the truth simulator proves it: the guidance's own (a success), or the optimal control
/// history flown open loop and judged a success by the referee. The optimizer's word alone
/// (its collocated trajectory satisfies every constraint, but the open-loop flight does not:
/// discretisation error near a boundary) does not count; nor does its "infeasible", which is
/// the converged maximum common margin below zero (a local optimum of a discretised problem:
/// the best found, not a proof that none exists).
/// kPulloutBound: infeasible by the wings-level pull-out bound (tools::wings_level_pullout_bound).
enum class Feasibility { kFlown, kProvenOpenLoop, kOptimizerOnly, kInfeasible, kPulloutBound, kUndecided };
const char* to_string(Feasibility f);

struct OracleResult {
  std::string error;
  tools::ClosedLoopResult flown;   // the guidance's flight of the run
  tools::PulloutBound pullout;     // the cheap physics bound of the first pull-out
  bool solved = false;             // the optimizer ran (else a cheap verdict decided)
  EntryResult entry;
  bool optimizer_feasible = false; // converged, every constraint of the collocated trajectory met
  bool replayed = false;
  ReplayResult replay;
  Feasibility feasibility = Feasibility::kUndecided;
  bool feasible = false;           // kFlown or kProvenOpenLoop
};

/// The truth simulator of a run (the draw of run `seed` when dispersed), as every run tool makes it.
std::unique_ptr<truth::Simulator> make_run_simulator(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                                                     std::string* error);

/// Flies run `seed` closed loop and its wings-level pull-out bound, and solves its entry problem
/// warm-started from that flight unless a cheap verdict decides (OracleOptions::solve_decided).
OracleResult run_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed, const OracleOptions& options);

/// The same from a given flown trajectory (ending at the TAEM event) and its verdict.
OracleResult solve_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                          const std::vector<FlownSample>& flown, bool flown_success, const OracleOptions& options);

}  // namespace reentry::optimal
