#include "run_oracle.hpp"

namespace reentry::optimal {

const char* to_string(Feasibility f) {
  switch (f) {
    case Feasibility::kFlown: return "flown";
    case Feasibility::kProvenOpenLoop: return "proven_open_loop";
    case Feasibility::kOptimizerOnly: return "optimizer_only";
    case Feasibility::kInfeasible: return "infeasible";
    case Feasibility::kPulloutBound: return "infeasible_pullout_bound";
    case Feasibility::kUndecided: return "undecided";
  }
  return "unknown";
}

namespace {
void classify(OracleResult& r, bool flown_success) {
  const bool conv = converged(r.entry.solution.status);
  if (flown_success) r.feasibility = Feasibility::kFlown;
  else if (r.replayed && r.replay.verdict.success) r.feasibility = Feasibility::kProvenOpenLoop;
  else if (r.optimizer_feasible) r.feasibility = Feasibility::kOptimizerOnly;
  else if (conv) r.feasibility = Feasibility::kInfeasible;
  else r.feasibility = Feasibility::kUndecided;
  r.feasible = r.feasibility == Feasibility::kFlown || r.feasibility == Feasibility::kProvenOpenLoop;
}
}  // namespace

std::unique_ptr<truth::Simulator> make_run_simulator(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                                                     std::string* error) {
  truth::SimOverrides ov;
  if (dispersed) ov.dispersion = truth::draw_dispersions(mission.dispersions, seed);
  auto sim = truth::Simulator::create(mission, ov, error);
  if (!sim && error) *error = "simulator: " + *error;
  return sim;
}

OracleResult solve_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed,
                          const std::vector<FlownSample>& flown, bool flown_success, const OracleOptions& options) {
  OracleResult out;
  if (flown.size() < 2) {
    out.error = "no flown trajectory to start from";
    return out;
  }
  auto sim = make_run_simulator(mission, seed, dispersed, &out.error);
  if (!sim) return out;
  const Mesh mesh = Mesh::uniform(options.solve.segments);
  const Trajectory guess = guess_from_flown(flown, mesh);
  out.entry = solve_entry(*sim, options.mode, guess, options.solve);
  if (!out.entry.error.empty()) {
    out.error = out.entry.error;
    return out;
  }
  out.optimizer_feasible = converged(out.entry.solution.status) && out.entry.figures.all_satisfied;
  if (options.replay) {
    auto replay_sim = make_run_simulator(mission, seed, dispersed, &out.error);
    if (!replay_sim) return out;
    const EntryProblem pb(*sim, options.mode, guess.p[0], 0.0, options.solve.alpha_band_rad);
    out.replay = replay_open_loop(*replay_sim, pb, out.entry.solution.trajectory);
    out.replayed = true;
  }
  classify(out, flown_success);
  return out;
}

OracleResult run_oracle(const config::Mission& mission, std::uint64_t seed, bool dispersed, const OracleOptions& options) {
  std::vector<FlownSample> flown;
  auto record = [&](const truth::Simulator& sim, double alpha, double sigma) {
    FlownSample s;
    s.t_s = sim.time_s();
    for (size_t i = 0; i < 6; ++i) s.y[i] = sim.state()[i];
    s.alpha_rad = alpha;
    s.sigma_rad = sigma;
    if (!flown.empty() && s.t_s <= flown.back().t_s) flown.back() = s;  // the end sample repeats the last tick
    else flown.push_back(s);
  };
  tools::ClosedLoopResult cl = tools::run_closed_loop(mission, seed, dispersed, {}, false, record);
  tools::PulloutBound pullout = tools::wings_level_pullout_bound(mission, seed, dispersed);
  OracleResult out;
  const bool bound_exceeded = pullout.error.empty() && !pullout.exceeded.empty();
  if (!cl.error.empty() || !pullout.error.empty()) {
    out.error = !cl.error.empty() ? cl.error : "pull-out bound: " + pullout.error;
  } else if (options.solve_decided || !(cl.verdict.success || bound_exceeded)) {
    out = solve_oracle(mission, seed, dispersed, flown, cl.verdict.success, options);
    out.solved = out.error.empty();
  }
  // A flight is the proof of feasibility, the pull-out bound a proof of infeasibility that
  // stands over the optimizer's "infeasible" (the best it found). A run both proven feasible and
  // beyond the bound keeps its proof: the campaign report names it as a bug to explain.
  if (out.error.empty() && cl.verdict.success) {
    out.feasibility = Feasibility::kFlown;
  } else if (out.error.empty() && bound_exceeded && out.feasibility != Feasibility::kProvenOpenLoop) {
    out.feasibility = Feasibility::kPulloutBound;
  }
  out.feasible = out.error.empty() && (out.feasibility == Feasibility::kFlown || out.feasibility == Feasibility::kProvenOpenLoop);
  out.flown = std::move(cl);
  out.pullout = std::move(pullout);
  return out;
}

}  // namespace reentry::optimal
