#include "entry_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace reentry::optimal {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Margins below this (a fraction of each limit) are polished without the smoothing term.
constexpr double kPolishMargin = 0.01;

// Index of the sample interval containing t (samples increasing in time).
size_t interval(const std::vector<double>& t, double tq, size_t hint) {
  size_t i = std::min(hint, t.size() - 2);
  while (i > 0 && t[i] > tq) --i;
  while (i + 2 < t.size() && t[i + 1] < tq) ++i;
  return i;
}
// The flown commands (held between samples) averaged over each point's share of the time line,
// [t_{j-1/2}, t_{j+1/2}], then made piecewise linear (a midpoint the mean of its nodes).
std::vector<double> mean_commands(const std::vector<FlownSample>& flown, const std::vector<double>& tau, double tf) {
  const int n = static_cast<int>(tau.size());
  std::vector<double> u(static_cast<size_t>(2 * n), 0.0);
  for (int j = 0; j < n; ++j) {
    const double a = j == 0 ? 0.0 : 0.5 * (tau[static_cast<size_t>(j - 1)] + tau[static_cast<size_t>(j)]) * tf;
    const double b = j == n - 1 ? tf : 0.5 * (tau[static_cast<size_t>(j)] + tau[static_cast<size_t>(j + 1)]) * tf;
    double sum_a = 0.0, sum_s = 0.0, w = 0.0;
    for (size_t i = 0; i + 1 < flown.size(); ++i) {
      const double lo = std::max(a, flown[i].t_s), hi = std::min(b, flown[i + 1].t_s);
      if (hi <= lo) continue;
      sum_a += (hi - lo) * flown[i].alpha_rad;
      sum_s += (hi - lo) * flown[i].sigma_rad;
      w += hi - lo;
    }
    u[static_cast<size_t>(2 * j)] = w > 0.0 ? sum_a / w : flown.back().alpha_rad;
    u[static_cast<size_t>(2 * j + 1)] = w > 0.0 ? sum_s / w : flown.back().sigma_rad;
  }
  for (int j = 1; j + 1 < n; j += 2)
    for (int c = 0; c < 2; ++c)
      u[static_cast<size_t>(2 * j + c)] = 0.5 * (u[static_cast<size_t>(2 * (j - 1) + c)] + u[static_cast<size_t>(2 * (j + 1) + c)]);
  return u;
}
}  // namespace

Trajectory guess_from_flown(const std::vector<FlownSample>& flown, const Mesh& mesh) {
  Trajectory g;
  g.tau = mesh.point_tau();
  const double tf = flown.back().t_s;
  g.p = {tf, 0.0};
  std::vector<double> t(flown.size());
  for (size_t i = 0; i < flown.size(); ++i) t[i] = flown[i].t_s;
  size_t hint = 0;
  for (double s : g.tau) {
    const double tq = s * tf;
    if (flown.size() < 2) {
      g.x.insert(g.x.end(), flown.front().y.begin(), flown.front().y.end());
      continue;
    }
    hint = interval(t, tq, hint);
    const FlownSample& a = flown[hint];
    const FlownSample& b = flown[hint + 1];
    const double w = b.t_s > a.t_s ? std::clamp((tq - a.t_s) / (b.t_s - a.t_s), 0.0, 1.0) : 0.0;
    for (size_t i = 0; i < 6; ++i) g.x.push_back(a.y[i] + w * (b.y[i] - a.y[i]));
  }
  g.u = mean_commands(flown, g.tau, tf);
  return g;
}

EntryFigures evaluate_figures(const EntryProblem& pb, const Trajectory& tr) {
  EntryFigures f;
  const int n = tr.points();
  if (n == 0) return f;
  f.tf_s = tr.p[0];
  f.margin = pb.mode() == EntryMode::kMaxMargin ? -tr.p[1] : kNaN;
  const config::PathConstraints& c = pb.mission().constraints;
  const config::TaemInterface& tm = pb.mission().taem;
  f.max_altitude_m = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    const double* x = &tr.x[static_cast<size_t>(j * 6)];
    const double* u = &tr.u[static_cast<size_t>(j * 2)];
    const truth::PointOutputs<double> o = pb.model().evaluate(tr.time(j), truth::scalar::Vec3<double>(x[0], x[1], x[2]),
                                                              truth::scalar::Vec3<double>(x[3], x[4], x[5]), u[0], u[1], true);
    f.max_heat_flux_Wpm2 = std::max(f.max_heat_flux_Wpm2, o.qdot);
    f.max_load_g = std::max(f.max_load_g, o.n_g);
    f.max_q_Pa = std::max(f.max_q_Pa, o.q);
    f.max_q_alpha_Pa_rad = std::max(f.max_q_alpha_Pa_rad, std::fabs(o.q * o.alpha));
    f.max_altitude_m = std::max(f.max_altitude_m, o.h_m);
  }
  const double* xf = &tr.x[static_cast<size_t>((n - 1) * 6)];
  const double* uf = &tr.u[static_cast<size_t>((n - 1) * 2)];
  const auto fin = pb.final_quantities(tr.time(n - 1), xf, uf);
  const double re = truth::EarthConstants::kEquatorialRadius_m;
  f.miss_m = 2.0 * re * std::asin(std::min(1.0, 0.5 * std::sqrt(fin.chord2)));
  f.along_m = fin.along;
  f.cross_m = fin.cross;
  f.altitude_err_m = fin.h - tm.altitude_m;
  f.mach = fin.mach;
  f.gamma_rad = fin.gamma;
  f.heading_err_rad = std::atan2(fin.heading_sin, fin.heading_cos);
  {
    const truth::PointOutputs<double> o = pb.model().evaluate(tr.time(n - 1), truth::scalar::Vec3<double>(xf[0], xf[1], xf[2]),
                                                              truth::scalar::Vec3<double>(xf[3], xf[4], xf[5]), uf[0], uf[1], true);
    f.final_lat_rad = o.lat;
    f.final_lon_rad = o.lon;
  }
  auto path_margin = [](double v, double lim) { return std::isfinite(lim) && lim > 0.0 ? 1.0 - v / lim : kNaN; };
  f.margin_heat_flux = path_margin(f.max_heat_flux_Wpm2, c.heat_flux_max_Wpm2);
  f.margin_load = path_margin(f.max_load_g, c.load_factor_max_g);
  f.margin_q = path_margin(f.max_q_Pa, c.dynamic_pressure_max_Pa);
  f.margin_q_alpha = path_margin(f.max_q_alpha_Pa_rad, c.q_alpha_max_Pa_rad);
  auto band_margin = [](double err, double tol) { return std::isfinite(tol) && tol > 0.0 ? 1.0 - std::fabs(err) / tol : kNaN; };
  f.margin_range = band_margin(f.miss_m, tm.range_tol_m);
  f.margin_altitude = band_margin(f.altitude_err_m, tm.altitude_tol_m);
  f.margin_mach = tm.mach_target > 0.0 ? band_margin(f.mach - tm.mach_target, tm.mach_tol) : kNaN;
  f.margin_gamma = band_margin(f.gamma_rad - tm.flight_path_rad, tm.flight_path_tol_rad);
  f.margin_heading = band_margin(f.heading_err_rad, tm.heading_tol_rad);
  constexpr double kSlack = 1e-6;
  bool ok = true;
  for (double m : {f.margin_heat_flux, f.margin_load, f.margin_q, f.margin_q_alpha})
    if (std::isfinite(m)) ok = ok && m >= -kSlack;
  for (double m : {f.margin_range, f.margin_altitude, f.margin_mach, f.margin_gamma, f.margin_heading})
    if (std::isfinite(m)) ok = ok && m >= -kSlack;
  f.all_satisfied = ok;
  return f;
}

namespace {
// The margin (or miss) parameter of the start: the guess's largest normalised violation plus a
// little, so every margin row starts feasible.
Trajectory with_margin_start(const EntryProblem& pb, const Trajectory& guess) {
  Trajectory start = guess;
  const EntryFigures g = evaluate_figures(pb, guess);
  if (pb.mode() == EntryMode::kMaxMargin) {
    double worst = -1.0;
    for (double m : {g.margin_heat_flux, g.margin_load, g.margin_q, g.margin_q_alpha, g.margin_altitude, g.margin_mach,
                     g.margin_gamma, g.margin_heading, g.margin_range})
      if (std::isfinite(m)) worst = std::max(worst, -m);
    start.p[1] = std::clamp(worst + 0.05, -0.95, 99.0);
  } else {
    start.p[1] = 0.0;
  }
  return start;
}

// A warm re-solve on a refined mesh or with a new model correction starts at the last solution:
// a smaller barrier keeps it there.
SolverOptions warm(SolverOptions o) {
  o.mu_init = std::min(o.mu_init, 1e-6);
  return o;
}
}  // namespace

EntryResult solve_entry(const truth::Simulator& sim, EntryMode mode, const Trajectory& guess,
                        const EntrySolveOptions& options, double downrange_m) {
  const auto t0 = std::chrono::steady_clock::now();
  EntryResult r;
  r.mode = mode;
  if (guess.points() < 3 || guess.points() % 2 == 0 || guess.p.size() != 2) {
    r.error = "initial guess does not match a mesh";
    return r;
  }
  const EntryProblem pb(sim, mode, guess.p[0], downrange_m, options.alpha_band_rad, options.extent_limit_m);
  const RefinementOptions& ro = options.refinement;
  Mesh mesh = Mesh::of_points(guess.tau);
  Trajectory start = with_margin_start(pb, guess);
  for (int k = 0; k < ro.a_priori_passes; ++k) {  // where the start's own local errors are largest
    mesh = refine_mesh(mesh, local_errors_m(pb, start, ro.substeps), ro.a_priori_reduction, ro.max_segments);
    start = interpolate(pb, start, mesh);
  }
  // The model correction of the first solve is taken at the start (the optimum lies near it).
  PointBias bias = ro.model_correction ? model_bias(pb, start) : PointBias{};
  for (int pass = 0; pass <= ro.max_passes; ++pass) {
    const Solution s = solve(pb, mesh, start, pass == 0 ? options.solver : warm(options.solver), bias.f.empty() ? nullptr : &bias);
    MeshPass mp{mesh.segments(), s.status, s.iterations, s.wall_s, 0.0, !bias.f.empty()};
    const bool ok = converged(s.status);
    if (ok || pass == 0) r.solution = s;
    if (ok) mp.end_error_m = table_flight_end_error_m(pb, s.trajectory, ro.substeps);
    r.passes.push_back(mp);
    if (!ok || pass == ro.max_passes || mp.end_error_m <= ro.end_error_target_m) break;
    const double reduction = mp.end_error_m / ro.end_error_target_m;
    mesh = refine_mesh(mesh, local_errors_m(pb, s.trajectory, ro.substeps), reduction, ro.max_segments);
    start = interpolate(pb, s.trajectory, mesh);
    if (ro.model_correction) bias = model_bias(pb, start);
  }
  // A warm re-solve of the last pass's solution (the kept one once that pass converged) on its
  // mesh and model correction, kept as a pass of its own when `keep` accepts its status.
  auto resolve_warm = [&](const SolverOptions& o, bool (*keep)(SolveStatus)) {
    if (!converged(r.passes.back().status)) return;
    const Solution s = solve(pb, mesh, r.solution.trajectory, o, bias.f.empty() ? nullptr : &bias);
    if (!keep(s.status)) return;
    r.passes.push_back({mesh.segments(), s.status, s.iterations, s.wall_s,
                        table_flight_end_error_m(pb, s.trajectory, ro.substeps), !bias.f.empty()});
    r.solution = s;
  };
  // IPOPT's acceptable point (its relaxed tolerances held for acceptable_iter iterations) is
  // resumed once, warm, on the same mesh and model correction: Newton from there usually meets
  // the full tolerances in a few iterations. Kept only if it does.
  if (r.passes.back().status == SolveStatus::kAcceptable)
    resolve_warm(warm(options.solver), [](SolveStatus st) { return st == SolveStatus::kOptimal; });
  auto regularisation = [&](const Solution& s) {
    return mode == EntryMode::kMaxMargin && s.trajectory.p.size() == 2 ? s.objective - s.trajectory.p[1] : kNaN;
  };
  // The smoothing term speeds Newton up but may cost margin; where the margin is near zero (a
  // sign and an open-loop replay the caller decides on) or not clearly larger than what the
  // regularisation terms are worth, the solution is polished warm without it, on the same mesh
  // and model correction.
  if (mode == EntryMode::kMaxMargin && options.solver.control_smoothing > 0.0 &&
      -r.solution.trajectory.p[1] < std::max(kPolishMargin, regularisation(r.solution))) {
    SolverOptions plain = warm(options.solver);
    plain.control_smoothing = 0.0;
    resolve_warm(plain, converged);
  }
  r.figures = evaluate_figures(pb, r.solution.trajectory);
  r.figures.regularisation = regularisation(r.solution);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

nlohmann::json result_json(const EntryResult& r) {
  using nlohmann::json;
  constexpr double kDeg = 180.0 / M_PI;
  const EntryFigures& f = r.figures;
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json passes = json::array();
  for (const MeshPass& p : r.passes)
    passes.push_back({{"segments", p.segments}, {"status", to_string(p.status)}, {"iterations", p.iterations},
                      {"wall_s", p.wall_s}, {"end_error_m", p.end_error_m}, {"model_corrected", p.corrected}});
  return {{"status", to_string(r.solution.status)}, {"ipopt_status", r.solution.ipopt_status},
          {"iterations", r.solution.iterations}, {"wall_s", r.wall_s}, {"segments", r.segments()}, {"passes", passes},
          {"tf_s", f.tf_s}, {"margin", num(f.margin)}, {"regularisation", num(f.regularisation)},
          {"miss_km", f.miss_m * 1e-3}, {"along_km", f.along_m * 1e-3}, {"cross_km", f.cross_m * 1e-3},
          {"altitude_err_km", f.altitude_err_m * 1e-3}, {"mach", f.mach}, {"gamma_deg", f.gamma_rad * kDeg},
          {"heading_err_deg", f.heading_err_rad * kDeg}, {"final_lat_deg", f.final_lat_rad * kDeg},
          {"final_lon_deg", f.final_lon_rad * kDeg}, {"max_heat_flux_kW_m2", f.max_heat_flux_Wpm2 * 1e-3},
          {"max_g", f.max_load_g}, {"max_q_kPa", f.max_q_Pa * 1e-3},
          {"max_q_alpha_kPa_deg", f.max_q_alpha_Pa_rad * 1e-3 * kDeg},
          {"margins",
           {{"heat_flux", num(f.margin_heat_flux)}, {"load_factor", num(f.margin_load)},
            {"dynamic_pressure", num(f.margin_q)}, {"q_alpha", num(f.margin_q_alpha)}, {"range", num(f.margin_range)},
            {"altitude", num(f.margin_altitude)}, {"mach", num(f.margin_mach)}, {"flight_path", num(f.margin_gamma)},
            {"heading", num(f.margin_heading)}}},
          {"all_satisfied", f.all_satisfied}};
}

std::vector<TrackPoint> track(const EntryProblem& pb, const Trajectory& tr) {
  std::vector<TrackPoint> out;
  for (int j = 0; j < tr.points(); ++j) {
    const double* x = &tr.x[static_cast<size_t>(j * 6)];
    const double* u = &tr.u[static_cast<size_t>(j * 2)];
    const truth::PointOutputs<double> o = pb.model().evaluate(tr.time(j), truth::scalar::Vec3<double>(x[0], x[1], x[2]),
                                                              truth::scalar::Vec3<double>(x[3], x[4], x[5]), u[0], u[1], true);
    out.push_back({tr.time(j), o.lat, o.lon, o.h_m, o.V, o.gamma, o.chi, o.mach, o.qdot, o.n_g, o.q, u[0], u[1]});
  }
  return out;
}

void control_at(const Trajectory& tr, double t, double* alpha, double* sigma) {
  const int n = tr.points();
  if (t <= tr.time(0)) {
    *alpha = tr.u[0];
    *sigma = tr.u[1];
    return;
  }
  if (t >= tr.time(n - 1)) {
    *alpha = tr.u[static_cast<size_t>(2 * (n - 1))];
    *sigma = tr.u[static_cast<size_t>(2 * (n - 1) + 1)];
    return;
  }
  int lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (tr.time(mid) <= t) lo = mid; else hi = mid;
  }
  const double w = (t - tr.time(lo)) / (tr.time(hi) - tr.time(lo));
  *alpha = tr.u[static_cast<size_t>(2 * lo)] + w * (tr.u[static_cast<size_t>(2 * hi)] - tr.u[static_cast<size_t>(2 * lo)]);
  *sigma = tr.u[static_cast<size_t>(2 * lo + 1)] + w * (tr.u[static_cast<size_t>(2 * hi + 1)] - tr.u[static_cast<size_t>(2 * lo + 1)]);
}

ReplayResult replay_open_loop(truth::Simulator& sim, const EntryProblem& pb, const Trajectory& tr) {
  ReplayResult out;
  const double rate = sim.mission().guidance.gnc_rate_hz > 0.0 ? sim.mission().guidance.gnc_rate_hz : 10.0;
  const double dt = 1.0 / rate;
  truth::CommandRateMaxima rates;
  double a_prev = 0.0, s_prev = 0.0;
  const auto max_ticks = static_cast<long long>(std::ceil(sim.settings().time_limit_s / dt)) + 2;
  for (long long k = 0; k < max_ticks && !sim.finished(); ++k) {
    double a = 0.0, s = 0.0;
    control_at(tr, (static_cast<double>(k) + 0.5) * dt, &a, &s);
    if (k > 0) {
      rates.alpha_rate_radps = std::max(rates.alpha_rate_radps, std::fabs(a - a_prev) / dt);
      rates.sigma_rate_radps = std::max(rates.sigma_rate_radps, std::fabs(s - s_prev) / dt);
    }
    a_prev = a;
    s_prev = s;
    sim.set_command(a, s);
    sim.advance_to(static_cast<double>(k + 1) * dt);
  }
  out.summary = sim.summary();
  out.verdict = truth::judge_mission(sim.mission(), out.summary, rates);
  const int n = tr.points();
  const double* xf = &tr.x[static_cast<size_t>((n - 1) * 6)];
  const truth::scalar::Vec3<double> r_sol = truth::rotation_I_to_R(tr.time(n - 1)) * truth::scalar::Vec3<double>(xf[0], xf[1], xf[2]);
  const auto& y = sim.state();
  const truth::scalar::Vec3<double> r_rep = truth::rotation_I_to_R(sim.time_s()) * truth::scalar::Vec3<double>(y[0], y[1], y[2]);
  out.final_position_diff_m = (r_rep - r_sol).norm();
  out.final_time_diff_s = sim.time_s() - tr.time(n - 1);
  const EntryFigures f = evaluate_figures(pb, tr);
  const auto& fs = out.summary.final_state;
  out.final_altitude_diff_m = fs.h_m - (f.altitude_err_m + sim.mission().taem.altitude_m);
  out.final_mach_diff = fs.mach - f.mach;
  out.final_heading_diff_rad = truth::wrap_pi(fs.chi_rad - (sim.mission().taem.heading_rad + f.heading_err_rad));
  return out;
}

}  // namespace reentry::optimal
