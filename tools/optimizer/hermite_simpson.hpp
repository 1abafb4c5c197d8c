// Direct collocation of an optimal-control problem by the separated Hermite-Simpson rule
// (Betts 2010, sec. 4.6.6), solved with IPOPT. Derivatives come from forward-mode automatic
// differentiation (Eigen AutoDiff, ad.hpp) of the problem's own templated functions: exact
// sparse Jacobians, and either the exact sparse Hessian of the Lagrangian (AD nested once, the
// default) or IPOPT's limited-memory quasi-Newton approximation. Nothing is finite-differenced.
//
// Transcription. Time t = t0 + tau tf, tau in [0, 1] over a mesh of N segments
// (tau_0 = 0 < ... < tau_N = 1); tf = p[0] is free. Each segment k has its two nodes and a
// midpoint, so there are 2N + 1 points j (even: nodes, odd: midpoints), each carrying the state
// x_j and the control u_j. With h_k = (tau_{k+1} - tau_k) tf and f_j = f(t_j, x_j, u_j):
//   x_m - (x_k + x_{k+1}) / 2 - h_k / 8 (f_k - f_{k+1}) = 0        (Hermite interpolant)
//   x_{k+1} - x_k - h_k / 6 (f_k + 4 f_m + f_{k+1}) = 0             (Simpson quadrature)
// Path constraints hold at every point (nodes and midpoints), with an optional constant
// linear term in the parameters (p enters e.g. as a common margin); control rates are bounded
// between successive points, |u_{j+1} - u_j| <= rate (t_{j+1} - t_j) (linear); the initial
// state is fixed; terminal constraints and a Mayer objective act on (x_f, u_f, p).
//
// A Problem provides (all sizes but the states, controls and parameters are run-time):
//   static constexpr int kStates, kControls, kParams;   // p[0] = tf
//   int n_path() const; int n_terminal() const; double t0() const;
//   bool time_invariant() const;                        // point() does not depend on t (its
//                                                       // derivatives in t are then not taken)
//   void initial_state(double* x0) const;
//   void state_bounds(double* lo, double* hi) const;   control_bounds(...); param_bounds(...);
//   void path_bounds(double* lo, double* hi) const;    terminal_bounds(...);
//   void path_param_coupling(double* a) const;          // n_path x kParams, row-major, constant
//   void control_rate_limits(double* rate) const;       // per control; +inf: unlimited
//   void state_scales(double*) const; control_scales; param_scales; path_scales; terminal_scales;
//   void defect_scales(double*) const;                  // per state: the size of a defect that
//                                                       // matters (not the size of the state)
//   double objective_scale() const;                     // typical magnitude of the objective
//   template <class T> void point(const T& t, const T* x, const T* u, T* xdot, T* path) const;
//   template <class T> void terminal(const T* x, const T* u, const T* p, T* psi) const;
//   template <class T> T objective(const T* x, const T* u, const T* p) const;
#pragma once

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "ad.hpp"

namespace reentry::optimal {

enum class SolveStatus { kOptimal, kAcceptable, kInfeasible, kIterationLimit, kTimeLimit, kFailure };
const char* to_string(SolveStatus s);
/// Optimal or acceptable (IPOPT's reduced tolerances): a usable solution.
inline bool converged(SolveStatus s) { return s == SolveStatus::kOptimal || s == SolveStatus::kAcceptable; }

struct SolverOptions {
  int max_iterations = 500;        // IPOPT iterations (bounded)
  double max_wall_s = 120.0;       // wall-clock limit of one solve (checked every iteration)
  double tol = 1e-7;               // IPOPT tol (scaled NLP)
  double constr_viol_tol = 1e-6;   // unscaled constraint violation
  double acceptable_tol = 1e-4;
  bool exact_hessian = true;       // false: limited-memory quasi-Newton
  int print_level = 0;             // IPOPT's console output (0: none)
  double bound_push = 1e-8;        // keep a warm start where it is (IPOPT: 1e-2)
  double mu_init = 1e-3;           // barrier start (IPOPT: 0.1); small for warm starts
  // Transcription: with linear_controls the midpoint control is tied to the mean of its
  // segment's node controls (piecewise-linear controls, as a flight computer's command history
  // is interpolated); otherwise it is free (classic Hermite-Simpson, quadratic control).
  bool linear_controls = false;
  bool monotone_mu = true;         // Fiacco-McCormick barrier from mu_init (a warm start stays close)
  double theta_max_fact = 1e4;     // IPOPT's filter cap on the constraint violation, x max(1, initial)
  /// Weight w of the control smoothing term added to the objective, w sum_j sum_c
  /// ((u_{j+1,c} - u_{j,c}) / scale_c)^2 / (tau_{j+1} - tau_j), the integral of (du/dtau)^2 in
  /// control scales: it picks the smoothest of the many control histories that share an
  /// optimum of a max-min objective (without it the Hessian is singular along them and Newton
  /// wanders). 0: none.
  double control_smoothing = 0.0;
  /// Weight w of the control proximity term added to the objective, w sum_j sum_c
  /// ((u_{j,c} - u0_{j,c}) / scale_c)^2 dtau_j (u0: the initial guess, dtau_j the point's share
  /// of tau): of the control histories sharing an optimum, the one closest to the start. 0: none.
  double control_proximity = 0.0;
  /// Further IPOPT options as (name, value): a value that parses as a number is set as an
  /// integer when it has no '.', 'e' or 'E', else as a number; anything else as a string.
  std::vector<std::pair<std::string, std::string>> ipopt_options;
  /// IPOPT's derivative checker: "first-order" or "second-order" (empty: off).
  std::string derivative_test;
  /// Largest least-squares estimate of the initial constraint multipliers IPOPT accepts
  /// (IPOPT: 1000); 0 starts them at zero.
  double constr_mult_init_max = 1000.0;
};

/// Mesh: tau of the N + 1 nodes, tau_0 = 0 < ... < tau_N = 1.
struct Mesh {
  std::vector<double> tau;
  static Mesh uniform(int segments);
  int segments() const { return static_cast<int>(tau.size()) - 1; }
  /// tau of the 2N + 1 collocation points (nodes and midpoints).
  std::vector<double> point_tau() const;
  /// The mesh of a trajectory's points (every other point is a node).
  static Mesh of_points(const std::vector<double>& point_tau);
};

/// Values at the 2N + 1 points, row-major (x[j * kStates + i]), and the parameters.
struct Trajectory {
  std::vector<double> tau, x, u, p;
  double t0 = 0.0;
  int points() const { return static_cast<int>(tau.size()); }
  double time(int j) const { return t0 + tau[static_cast<size_t>(j)] * p[0]; }
};

/// Constant offsets added to the values of the point functions at every collocation point
/// (their derivatives unchanged): f (n_points x kStates) and path (n_points x n_path), each
/// empty for none. A model correction: the solve then meets the collocation equations of
/// f + bias, i.e. of a reference model whose values at the points are f + bias.
struct PointBias {
  std::vector<double> f, path;
};

/// IPOPT's multipliers of a solve, in its order of variables and rows (hermite_simpson_nlp.hpp):
/// the dual start of a warm re-solve.
struct Multipliers {
  std::vector<double> z_lower, z_upper, lambda;
  bool empty() const { return lambda.empty(); }
};

struct Solution {
  SolveStatus status = SolveStatus::kFailure;
  std::string ipopt_status;        // IPOPT's return code name
  int iterations = 0;
  double wall_s = 0.0;
  double objective = 0.0;          // unscaled
  double max_violation = 0.0;      // largest constraint violation (unscaled units of each row)
  Trajectory trajectory;
  Multipliers multipliers;
};

namespace detail {
const char* ipopt_status_name(Ipopt::SolverReturn s);
SolveStatus map_status(Ipopt::SolverReturn s);
/// Sets the IPOPT options of one solve (no output files, MUMPS, bounded iterations); false when
/// an option of SolverOptions::ipopt_options is unknown or its value of the wrong kind.
bool configure(Ipopt::IpoptApplication& app, const SolverOptions& o, bool warm_duals = false);
}  // namespace detail

}  // namespace reentry::optimal

#include "hermite_simpson_nlp.hpp"

namespace reentry::optimal {

/// Transcribes and solves. `guess` holds the 2N + 1 points of `mesh` (Mesh::point_tau).
/// `duals`: the multipliers of a solve of the same problem on the same mesh, the dual start of a
/// warm re-solve (ignored when their sizes do not match).
template <class Problem>
Solution solve(const Problem& problem, const Mesh& mesh, const Trajectory& guess, const SolverOptions& options,
               const PointBias* bias = nullptr, const Multipliers* duals = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  Ipopt::SmartPtr<HermiteSimpsonNlp<Problem>> nlp = new HermiteSimpsonNlp<Problem>(problem, mesh, guess, options, bias, duals);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Solution out;
  if (!detail::configure(*app, options, nlp->warm_duals())) {
    out.ipopt_status = "invalid_option";
    return out;
  }
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    out.ipopt_status = "initialize_failed";
    return out;
  }
  app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(nlp)));
  out = nlp->solution();
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

/// Controls of a trajectory at tau inside segment k: the quadratic through the segment's node,
/// midpoint and node controls (linear when the midpoint is their mean).
template <int kU>
void segment_control(const Trajectory& tr, int k, double tau, double* u) {
  const size_t j0 = static_cast<size_t>(2 * k);
  const double a = tr.tau[j0], b = tr.tau[j0 + 2];
  const double s = (tau - a) / (b - a);
  const double l0 = 2.0 * (s - 0.5) * (s - 1.0), lm = -4.0 * s * (s - 1.0), l1 = 2.0 * s * (s - 0.5);
  for (int c = 0; c < kU; ++c)
    u[c] = l0 * tr.u[j0 * kU + c] + lm * tr.u[(j0 + 1) * kU + c] + l1 * tr.u[(j0 + 2) * kU + c];
}

/// One RK4 integration of dx/dtau = tf f(t, x, u(tau)) over segment k of a trajectory, from x
/// (in place), with `substeps` steps and the segment's own controls; `f(t, x, u, xdot)`.
template <int kX, int kU, class F>
void integrate_segment(const Trajectory& tr, int k, int substeps, const F& f, double* x) {
  auto rhs = [&](double tau, const double* y, double* dy) {
    double u[kU];
    segment_control<kU>(tr, k, tau, u);
    f(tr.t0 + tau * tr.p[0], y, u, dy);
    for (int i = 0; i < kX; ++i) dy[i] *= tr.p[0];
  };
  const double a = tr.tau[static_cast<size_t>(2 * k)], b = tr.tau[static_cast<size_t>(2 * k + 2)];
  const double d = (b - a) / substeps;
  for (int s = 0; s < substeps; ++s) {
    double k1[kX], k2[kX], k3[kX], k4[kX], y[kX];
    const double ts = a + s * d;
    rhs(ts, x, k1);
    for (int i = 0; i < kX; ++i) y[i] = x[i] + 0.5 * d * k1[i];
    rhs(ts + 0.5 * d, y, k2);
    for (int i = 0; i < kX; ++i) y[i] = x[i] + 0.5 * d * k2[i];
    rhs(ts + 0.5 * d, y, k3);
    for (int i = 0; i < kX; ++i) y[i] = x[i] + d * k3[i];
    rhs(ts + d, y, k4);
    for (int i = 0; i < kX; ++i) x[i] += d / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

/// The local error of each segment: the state at the segment's end integrated accurately (RK4,
/// `substeps` steps, the segment's own controls) from the collocated state at its start, minus
/// the collocated end state (n_segments x kX). `f(t, x, u, xdot)` is the model integrated: the
/// problem's own (the discretisation error, O(h^5) for Hermite-Simpson) or a reference model.
template <int kX, int kU, class F>
std::vector<double> segment_errors(const Trajectory& tr, int substeps, const F& f) {
  const int n_seg = (tr.points() - 1) / 2;
  std::vector<double> err(static_cast<size_t>(n_seg * kX), 0.0);
  for (int k = 0; k < n_seg; ++k) {
    double x[kX];
    std::copy(&tr.x[static_cast<size_t>(2 * k * kX)], &tr.x[static_cast<size_t>(2 * k * kX + kX)], x);
    integrate_segment<kX, kU>(tr, k, substeps, f, x);
    for (int i = 0; i < kX; ++i)
      err[static_cast<size_t>(k * kX + i)] = x[i] - tr.x[static_cast<size_t>((2 * k + 2) * kX + i)];
  }
  return err;
}

/// The trajectory's controls flown from its initial state over its whole time by RK4 of `f`
/// (`substeps` steps per segment): the final state.
template <int kX, int kU, class F>
std::vector<double> fly_controls(const Trajectory& tr, int substeps, const F& f) {
  std::vector<double> x(tr.x.begin(), tr.x.begin() + kX);
  for (int k = 0; k < (tr.points() - 1) / 2; ++k) integrate_segment<kX, kU>(tr, k, substeps, f, x.data());
  return x;
}

/// A trajectory carried onto another mesh: states on each old segment's Hermite cubic (the
/// node states and the node slopes f), controls on its quadratic, the parameters kept.
template <class Problem>
Trajectory interpolate(const Problem& pb, const Trajectory& tr, const Mesh& mesh) {
  constexpr int kX = Problem::kStates, kU = Problem::kControls;
  Trajectory out;
  out.t0 = tr.t0;
  out.p = tr.p;
  out.tau = mesh.point_tau();
  const int n_old = (tr.points() - 1) / 2;
  std::vector<double> path(static_cast<size_t>(std::max(1, pb.n_path())));
  int k = 0;
  for (double tau : out.tau) {
    while (k + 1 < n_old && tau > tr.tau[static_cast<size_t>(2 * k + 2)]) ++k;
    const size_t j0 = static_cast<size_t>(2 * k), j1 = j0 + 2;
    const double a = tr.tau[j0], b = tr.tau[j1], h = (b - a) * tr.p[0];
    const double s = std::clamp((tau - a) / (b - a), 0.0, 1.0);
    double f0[kX], f1[kX];
    pb.point(tr.time(static_cast<int>(j0)), &tr.x[j0 * kX], &tr.u[j0 * kU], f0, path.data());
    pb.point(tr.time(static_cast<int>(j1)), &tr.x[j1 * kX], &tr.u[j1 * kU], f1, path.data());
    const double h00 = 1.0 + s * s * (2.0 * s - 3.0), h01 = s * s * (3.0 - 2.0 * s);
    const double h10 = s * (1.0 + s * (s - 2.0)), h11 = s * s * (s - 1.0);
    for (int i = 0; i < kX; ++i)
      out.x.push_back(h00 * tr.x[j0 * kX + i] + h01 * tr.x[j1 * kX + i] + h * (h10 * f0[i] + h11 * f1[i]));
    double u[kU];
    segment_control<kU>(tr, k, tau, u);
    for (int c = 0; c < kU; ++c) out.u.push_back(u[c]);
  }
  return out;
}

}  // namespace reentry::optimal
