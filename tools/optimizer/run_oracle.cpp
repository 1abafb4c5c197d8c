#include "run_oracle.hpp"

namespace reentry::optimal {

const char* to_string(Feasibility f) {
  switch (f) {
    case Feasibility::kFlown: return "flown";
    case Feasibility::kProvenOpenLoop: return "proven_open_loop";
    case Feasibility::kOptimizerOnly: return "optimizer_only";
    case Feasibility::kInfeasible: return "infeasible";
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
  auto guess_sim = make_run_simulator(mission, seed, dispersed, &out.error);
  if (!guess_sim) return out;
  const Trajectory guess = consistent_guess_from_flown(*guess_sim, flown, mesh);
  out.entry = solve_entry(*sim, options.mode, guess, options.solve);
  if (!out.entry.error.empty()) {
    out.error = out.entry.error;
    return out;
  }
  out.optimizer_feasible = converged(out.entry.solution.status) && out.entry.figures.all_satisfied;
  if (options.replay) {
    auto replay_sim = make_run_simulator(mission, seed, dispersed, &out.error);
    if (!replay_sim) return out;
    const EntryProblem pb(*sim, options.mode, guess.p[0]);
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
  OracleResult out;
  if (!cl.error.empty()) {
    out.error = cl.error;
    out.flown = std::move(cl);
    return out;
  }
  out = solve_oracle(mission, seed, dispersed, flown, cl.verdict.success, options);
  out.flown = std::move(cl);
  return out;
}

}  // namespace reentry::optimal
