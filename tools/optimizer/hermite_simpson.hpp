// Direct collocation of an optimal-control problem by the separated Hermite-Simpson rule
// (Betts 2010, sec. 4.6.6), solved with IPOPT. Derivatives come from forward-mode automatic
// differentiation (Eigen AutoDiff, ad.hpp) of the problem's own templated functions: exact
// sparse Jacobians, and either the exact sparse Hessian of the Lagrangian (AD nested once) or
// IPOPT's limited-memory quasi-Newton approximation. Nothing is finite-differenced.
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
#include <map>
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
};

/// Mesh: tau of the N + 1 nodes, tau_0 = 0 < ... < tau_N = 1.
struct Mesh {
  std::vector<double> tau;
  static Mesh uniform(int segments);
  int segments() const { return static_cast<int>(tau.size()) - 1; }
  /// tau of the 2N + 1 collocation points (nodes and midpoints).
  std::vector<double> point_tau() const;
};

/// Values at the 2N + 1 points, row-major (x[j * kStates + i]), and the parameters.
struct Trajectory {
  std::vector<double> tau, x, u, p;
  double t0 = 0.0;
  int points() const { return static_cast<int>(tau.size()); }
  double time(int j) const { return t0 + tau[static_cast<size_t>(j)] * p[0]; }
};

struct Solution {
  SolveStatus status = SolveStatus::kFailure;
  std::string ipopt_status;        // IPOPT's return code name
  int iterations = 0;
  double wall_s = 0.0;
  double objective = 0.0;          // unscaled
  double max_violation = 0.0;      // largest constraint violation (unscaled units of each row)
  Trajectory trajectory;
};

namespace detail {
const char* ipopt_status_name(Ipopt::SolverReturn s);
SolveStatus map_status(Ipopt::SolverReturn s);
}  // namespace detail

template <class Problem>
class HermiteSimpsonNlp : public Ipopt::TNLP {
 public:
  static constexpr int kX = Problem::kStates;
  static constexpr int kU = Problem::kControls;
  static constexpr int kP = Problem::kParams;
  static constexpr int kZ = kX + kU;     // variables of one point
  static constexpr int kW = 1 + kZ;      // arguments of the point function: t, x, u
  static constexpr int kV = kZ + kP;     // arguments of the terminal functions: x_f, u_f, p

  HermiteSimpsonNlp(const Problem& problem, const Mesh& mesh, const Trajectory& guess, const SolverOptions& options)
      : pb_(problem), mesh_(mesh), guess_(guess), opt_(options) {
    n_seg_ = mesh.segments();
    n_pts_ = 2 * n_seg_ + 1;
    tau_ = mesh.point_tau();
    n_path_ = pb_.n_path();
    n_term_ = pb_.n_terminal();
    rate_.assign(kU, 0.0);
    pb_.control_rate_limits(rate_.data());
    for (int c = 0; c < kU; ++c)
      if (std::isfinite(rate_[c])) limited_.push_back(c);
    path_a_.assign(static_cast<size_t>(std::max(1, n_path_ * kP)), 0.0);
    if (n_path_ > 0) pb_.path_param_coupling(path_a_.data());
    n_var_ = n_pts_ * kZ + kP;
    row_defect_ = 0;
    row_path_ = 2 * kX * n_seg_;
    row_rate_ = row_path_ + n_pts_ * n_path_;
    row_lin_ = row_rate_ + 2 * static_cast<int>(limited_.size()) * (n_pts_ - 1);
    row_term_ = row_lin_ + (opt_.linear_controls ? n_seg_ * kU : 0);
    n_con_ = row_term_ + n_term_;
    cache_f_.assign(static_cast<size_t>(n_pts_ * kX), 0.0);
    cache_g_.assign(static_cast<size_t>(std::max(1, n_pts_ * n_path_)), 0.0);
    cache_jf_.assign(static_cast<size_t>(n_pts_ * kX * kW), 0.0);
    cache_jg_.assign(static_cast<size_t>(std::max(1, n_pts_ * n_path_ * kW)), 0.0);
    build_hessian_structure();
    t_start_ = std::chrono::steady_clock::now();
  }

  const Solution& solution() const { return sol_; }

  // ---- IPOPT interface ---------------------------------------------------------------------
  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g, Ipopt::Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = n_var_;
    m = n_con_;
    nnz_jac_g = jacobian_nonzeros();
    nnz_h_lag = static_cast<Ipopt::Index>(hess_rows_.size());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Ipopt::Index, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index, Ipopt::Number* g_l,
                       Ipopt::Number* g_u) override {
    double xl[kX], xu[kX], ul[kU], uu[kU], pl[kP], pu[kP], x0[kX];
    pb_.state_bounds(xl, xu);
    pb_.control_bounds(ul, uu);
    pb_.param_bounds(pl, pu);
    pb_.initial_state(x0);
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < kX; ++i) {
        x_l[zi(j, i)] = j == 0 ? x0[i] : xl[i];
        x_u[zi(j, i)] = j == 0 ? x0[i] : xu[i];
      }
      for (int c = 0; c < kU; ++c) {
        x_l[zi(j, kX + c)] = ul[c];
        x_u[zi(j, kX + c)] = uu[c];
      }
    }
    for (int l = 0; l < kP; ++l) {
      x_l[pi(l)] = pl[l];
      x_u[pi(l)] = pu[l];
    }
    for (int r = 0; r < row_path_; ++r) g_l[r] = g_u[r] = 0.0;
    std::vector<double> lo(static_cast<size_t>(std::max(1, n_path_))), hi(lo.size());
    if (n_path_ > 0) pb_.path_bounds(lo.data(), hi.data());
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < n_path_; ++i) {
        g_l[row_path_ + j * n_path_ + i] = to_ipopt(lo[i]);
        g_u[row_path_ + j * n_path_ + i] = to_ipopt(hi[i]);
      }
    }
    int r = row_rate_;
    for (size_t c = 0; c < limited_.size(); ++c) {
      for (int j = 0; j + 1 < n_pts_; ++j) {
        g_l[r] = -kIpoptInf;  // u_{j+1} - u_j - rate dt <= 0
        g_u[r] = 0.0;
        ++r;
        g_l[r] = 0.0;  // u_{j+1} - u_j + rate dt >= 0
        g_u[r] = kIpoptInf;
        ++r;
      }
    }
    for (int r2 = row_lin_; r2 < row_term_; ++r2) g_l[r2] = g_u[r2] = 0.0;
    std::vector<double> tl(static_cast<size_t>(std::max(1, n_term_))), tu(tl.size());
    if (n_term_ > 0) pb_.terminal_bounds(tl.data(), tu.data());
    for (int k = 0; k < n_term_; ++k) {
      g_l[row_term_ + k] = to_ipopt(tl[k]);
      g_u[row_term_ + k] = to_ipopt(tu[k]);
    }
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool init_x, Ipopt::Number* x, bool, Ipopt::Number*, Ipopt::Number*,
                          Ipopt::Index, bool, Ipopt::Number*) override {
    if (!init_x) return false;
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < kX; ++i) x[zi(j, i)] = guess_.x[static_cast<size_t>(j * kX + i)];
      for (int c = 0; c < kU; ++c) x[zi(j, kX + c)] = guess_.u[static_cast<size_t>(j * kU + c)];
    }
    for (int l = 0; l < kP; ++l) x[pi(l)] = guess_.p[static_cast<size_t>(l)];
    return true;
  }

  bool get_scaling_parameters(Ipopt::Number& obj_scaling, bool& use_x_scaling, Ipopt::Index, Ipopt::Number* x_scaling,
                              bool& use_g_scaling, Ipopt::Index, Ipopt::Number* g_scaling) override {
    double xs[kX], us[kU], ps[kP], ds[kX];
    pb_.state_scales(xs);
    pb_.control_scales(us);
    pb_.param_scales(ps);
    pb_.defect_scales(ds);
    obj_scaling = 1.0 / pb_.objective_scale();
    use_x_scaling = true;
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < kX; ++i) x_scaling[zi(j, i)] = 1.0 / xs[i];
      for (int c = 0; c < kU; ++c) x_scaling[zi(j, kX + c)] = 1.0 / us[c];
    }
    for (int l = 0; l < kP; ++l) x_scaling[pi(l)] = 1.0 / ps[l];
    use_g_scaling = true;
    for (int k = 0; k < n_seg_; ++k) {
      for (int i = 0; i < kX; ++i) {
        g_scaling[row_defect_ + k * 2 * kX + i] = 1.0 / ds[i];
        g_scaling[row_defect_ + k * 2 * kX + kX + i] = 1.0 / ds[i];
      }
    }
    std::vector<double> gs(static_cast<size_t>(std::max(1, n_path_)), 1.0);
    if (n_path_ > 0) pb_.path_scales(gs.data());
    for (int j = 0; j < n_pts_; ++j)
      for (int i = 0; i < n_path_; ++i) g_scaling[row_path_ + j * n_path_ + i] = 1.0 / gs[i];
    int r = row_rate_;
    for (int c : limited_) {
      for (int j = 0; j + 1 < n_pts_; ++j) {
        g_scaling[r++] = 1.0 / us[c];
        g_scaling[r++] = 1.0 / us[c];
      }
    }
    for (int k = 0; k < n_seg_ && opt_.linear_controls; ++k)
      for (int c = 0; c < kU; ++c) g_scaling[row_lin_ + k * kU + c] = 1.0 / us[c];
    std::vector<double> ts(static_cast<size_t>(std::max(1, n_term_)), 1.0);
    if (n_term_ > 0) pb_.terminal_scales(ts.data());
    for (int k = 0; k < n_term_; ++k) g_scaling[row_term_ + k] = 1.0 / ts[k];
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number& obj_value) override {
    double v[kV];
    terminal_args(x, v);
    obj_value = pb_.objective(v, v + kX, v + kZ);
    return std::isfinite(obj_value);
  }

  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Number* grad_f) override {
    std::fill(grad_f, grad_f + n, 0.0);
    double v[kV];
    terminal_args(x, v);
    Ad1<kV> a[kV];
    seed<kV>(v, a);
    const Ad1<kV> o = pb_.objective(a, a + kX, a + kZ);
    for (int k = 0; k < kV; ++k) grad_f[terminal_index(k)] += o.derivatives()[k];
    return std::isfinite(o.value());
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Index, Ipopt::Number* g) override {
    refresh(x, new_x);
    if (!cache_ok_) return false;
    const double tf = x[pi(0)];
    for (int k = 0; k < n_seg_; ++k) {
      const int j0 = 2 * k, jm = j0 + 1, j1 = j0 + 2;
      const double h = (mesh_.tau[k + 1] - mesh_.tau[k]) * tf;
      for (int i = 0; i < kX; ++i) {
        const double f0 = fv(j0, i), fm = fv(jm, i), f1 = fv(j1, i);
        g[row_defect_ + k * 2 * kX + i] = x[zi(jm, i)] - 0.5 * (x[zi(j0, i)] + x[zi(j1, i)]) - h / 8.0 * (f0 - f1);
        g[row_defect_ + k * 2 * kX + kX + i] = x[zi(j1, i)] - x[zi(j0, i)] - h / 6.0 * (f0 + 4.0 * fm + f1);
      }
    }
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < n_path_; ++i) {
        double v = gv(j, i);
        for (int l = 0; l < kP; ++l) v += path_a_[static_cast<size_t>(i * kP + l)] * x[pi(l)];
        g[row_path_ + j * n_path_ + i] = v;
      }
    }
    int r = row_rate_;
    for (int c : limited_) {
      for (int j = 0; j + 1 < n_pts_; ++j) {
        const double du = x[zi(j + 1, kX + c)] - x[zi(j, kX + c)];
        const double dt = (tau_[j + 1] - tau_[j]) * tf;
        g[r++] = du - rate_[c] * dt;
        g[r++] = du + rate_[c] * dt;
      }
    }
    for (int k = 0; k < n_seg_ && opt_.linear_controls; ++k)
      for (int c = 0; c < kU; ++c)
        g[row_lin_ + k * kU + c] = x[zi(2 * k + 1, kX + c)] - 0.5 * (x[zi(2 * k, kX + c)] + x[zi(2 * k + 2, kX + c)]);
    if (n_term_ > 0) {
      double v[kV];
      terminal_args(x, v);
      std::vector<double> psi(static_cast<size_t>(n_term_));
      pb_.terminal(v, v + kX, v + kZ, psi.data());
      for (int k = 0; k < n_term_; ++k) {
        if (!std::isfinite(psi[k])) return false;
        g[row_term_ + k] = psi[k];
      }
    }
    return true;
  }

  bool eval_jac_g(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Index, Ipopt::Index, Ipopt::Index* iRow,
                  Ipopt::Index* jCol, Ipopt::Number* values) override {
    if (values == nullptr) {
      int e = 0;
      auto put = [&](int row, int col) {
        iRow[e] = row;
        jCol[e] = col;
        ++e;
      };
      jacobian_pattern(put);
      return true;
    }
    refresh(x, new_x);
    if (!cache_ok_) return false;
    int e = 0;
    auto put = [&](double v) { values[e++] = v; };
    jacobian_values(x, put);
    return true;
  }

  bool eval_h(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number obj_factor, Ipopt::Index,
              const Ipopt::Number* lambda, bool, Ipopt::Index nele_hess, Ipopt::Index* iRow, Ipopt::Index* jCol,
              Ipopt::Number* values) override {
    if (values == nullptr) {
      for (Ipopt::Index e = 0; e < nele_hess; ++e) {
        iRow[e] = hess_rows_[static_cast<size_t>(e)];
        jCol[e] = hess_cols_[static_cast<size_t>(e)];
      }
      return true;
    }
    std::fill(values, values + nele_hess, 0.0);
    const double tf = x[pi(0)];
    // Weights of f_j in the Lagrangian (multiplying tf) and of the path constraints.
    std::vector<double> a(static_cast<size_t>(n_pts_ * kX), 0.0);
    for (int k = 0; k < n_seg_; ++k) {
      const int j0 = 2 * k, jm = j0 + 1, j1 = j0 + 2;
      const double dtau = mesh_.tau[k + 1] - mesh_.tau[k];
      for (int i = 0; i < kX; ++i) {
        const double l1 = lambda[row_defect_ + k * 2 * kX + i];
        const double l2 = lambda[row_defect_ + k * 2 * kX + kX + i];
        a[static_cast<size_t>(j0 * kX + i)] += -dtau / 8.0 * l1 - dtau / 6.0 * l2;
        a[static_cast<size_t>(j1 * kX + i)] += dtau / 8.0 * l1 - dtau / 6.0 * l2;
        a[static_cast<size_t>(jm * kX + i)] += -4.0 * dtau / 6.0 * l2;
      }
    }
    using A2 = Ad2<kW>;
    for (int j = 0; j < n_pts_; ++j) {
      const double* aj = &a[static_cast<size_t>(j * kX)];
      const double* bj = n_path_ > 0 ? &lambda[row_path_ + j * n_path_] : nullptr;
      bool any = false;
      for (int i = 0; i < kX; ++i) any = any || aj[i] != 0.0;
      for (int i = 0; i < n_path_; ++i) any = any || bj[i] != 0.0;
      if (!any) continue;
      double w[kW];
      point_args(x, j, w);
      A2 aw[kW];
      seed<kW>(w, aw);
      A2 f[kX];
      std::vector<A2> g(static_cast<size_t>(std::max(1, n_path_)));
      pb_.point(aw[0], aw + 1, aw + 1 + kX, f, g.data());
      A2 s = A2(0.0);
      for (int i = 0; i < kX; ++i)
        if (aj[i] != 0.0) s += (tf * aj[i]) * f[i];
      for (int i = 0; i < n_path_; ++i)
        if (bj[i] != 0.0) s += bj[i] * g[static_cast<size_t>(i)];
      // Gradient of a^T f (for the tf cross terms), from the first-order part of f.
      double af_grad[kW] = {};
      for (int i = 0; i < kX; ++i) {
        if (aj[i] == 0.0) continue;
        for (int q = 0; q < kW; ++q) af_grad[q] += aj[i] * f[i].value().derivatives()[q];
      }
      const double tj = tau_[j];
      const int* idx = &hess_point_[static_cast<size_t>(j) * kHessPoint];
      int e = 0;
      for (int p = 0; p < kZ; ++p) {
        for (int q = 0; q <= p; ++q) values[idx[e++]] += s.derivatives()[1 + p].derivatives()[1 + q];
      }
      for (int q = 0; q < kZ; ++q)
        values[idx[e++]] += af_grad[1 + q] + tj * s.derivatives()[0].derivatives()[1 + q];
      values[idx[e++]] += 2.0 * tj * af_grad[0] + tj * tj * s.derivatives()[0].derivatives()[0];
    }
    // Terminal constraints and the objective.
    {
      using B2 = Ad2<kV>;
      double v[kV];
      terminal_args(x, v);
      B2 av[kV];
      seed<kV>(v, av);
      B2 s = obj_factor * pb_.objective(av, av + kX, av + kZ);
      if (n_term_ > 0) {
        std::vector<B2> psi(static_cast<size_t>(n_term_));
        pb_.terminal(av, av + kX, av + kZ, psi.data());
        for (int k = 0; k < n_term_; ++k) {
          const double mu = lambda[row_term_ + k];
          if (mu != 0.0) s += mu * psi[static_cast<size_t>(k)];
        }
      }
      int e = 0;
      for (int p = 0; p < kV; ++p)
        for (int q = 0; q <= p; ++q) values[hess_term_[static_cast<size_t>(e++)]] += s.derivatives()[p].derivatives()[q];
    }
    return true;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Ipopt::Index iter, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                             Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Number, Ipopt::Index,
                             const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    iterations_ = iter;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start_).count();
    if (wall > opt_.max_wall_s) {
      timed_out_ = true;
      return false;
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index, const Ipopt::Number* x, const Ipopt::Number*,
                         const Ipopt::Number*, Ipopt::Index m, const Ipopt::Number* g, const Ipopt::Number*,
                         Ipopt::Number obj_value, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    sol_.status = timed_out_ && status == Ipopt::USER_REQUESTED_STOP ? SolveStatus::kTimeLimit : detail::map_status(status);
    sol_.ipopt_status = detail::ipopt_status_name(status);
    sol_.objective = obj_value;
    sol_.iterations = iterations_;
    Trajectory& tr = sol_.trajectory;
    tr.t0 = pb_.t0();
    tr.tau = tau_;
    tr.x.assign(static_cast<size_t>(n_pts_ * kX), 0.0);
    tr.u.assign(static_cast<size_t>(n_pts_ * kU), 0.0);
    tr.p.assign(kP, 0.0);
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < kX; ++i) tr.x[static_cast<size_t>(j * kX + i)] = x[zi(j, i)];
      for (int c = 0; c < kU; ++c) tr.u[static_cast<size_t>(j * kU + c)] = x[zi(j, kX + c)];
    }
    for (int l = 0; l < kP; ++l) tr.p[static_cast<size_t>(l)] = x[pi(l)];
    // Largest violation of the constraint bounds (unscaled).
    std::vector<Ipopt::Number> gl(static_cast<size_t>(m)), gu(static_cast<size_t>(m)), xl(static_cast<size_t>(n_var_)),
        xu(static_cast<size_t>(n_var_));
    get_bounds_info(n_var_, xl.data(), xu.data(), m, gl.data(), gu.data());
    double viol = 0.0;
    for (Ipopt::Index r = 0; r < m && g; ++r) {
      if (g[r] < gl[static_cast<size_t>(r)]) viol = std::max(viol, gl[static_cast<size_t>(r)] - g[r]);
      if (g[r] > gu[static_cast<size_t>(r)]) viol = std::max(viol, g[r] - gu[static_cast<size_t>(r)]);
    }
    sol_.max_violation = viol;
  }

 private:
  static constexpr double kIpoptInf = 1e20;
  static constexpr int kHessPoint = kZ * (kZ + 1) / 2 + kZ + 1;  // z-z lower triangle, tf-z, tf-tf

  static double to_ipopt(double v) { return std::isfinite(v) ? v : (v > 0 ? kIpoptInf : -kIpoptInf); }
  int zi(int j, int k) const { return j * kZ + k; }
  int pi(int l) const { return n_pts_ * kZ + l; }
  double fv(int j, int i) const { return cache_f_[static_cast<size_t>(j * kX + i)]; }
  double gv(int j, int i) const { return cache_g_[static_cast<size_t>(j * n_path_ + i)]; }
  double jf(int j, int i, int w) const { return cache_jf_[static_cast<size_t>((j * kX + i) * kW + w)]; }
  double jg(int j, int i, int w) const { return cache_jg_[static_cast<size_t>((j * n_path_ + i) * kW + w)]; }
  int terminal_index(int k) const { return k < kZ ? zi(n_pts_ - 1, k) : pi(k - kZ); }

  void point_args(const double* x, int j, double* w) const {
    w[0] = pb_.t0() + tau_[j] * x[pi(0)];
    for (int k = 0; k < kZ; ++k) w[1 + k] = x[zi(j, k)];
  }
  void terminal_args(const double* x, double* v) const {
    for (int k = 0; k < kV; ++k) v[k] = x[terminal_index(k)];
  }

  // The point evaluations are cached per iterate; new_x is not trusted alone (IPOPT's
  // derivative checker perturbs x without it), the cached x is compared.
  void refresh(const double* x, bool new_x) {
    if (!new_x && cache_valid_ && std::equal(x, x + n_var_, cache_x_.begin())) return;
    cache_x_.assign(x, x + n_var_);
    update_cache(x);
  }

  void update_cache(const double* x) {
    cache_ok_ = true;
    using A1 = Ad1<kW>;
    std::vector<A1> g(static_cast<size_t>(std::max(1, n_path_)));
    for (int j = 0; j < n_pts_; ++j) {
      double w[kW];
      point_args(x, j, w);
      A1 aw[kW];
      seed<kW>(w, aw);
      A1 f[kX];
      pb_.point(aw[0], aw + 1, aw + 1 + kX, f, g.data());
      for (int i = 0; i < kX; ++i) {
        cache_f_[static_cast<size_t>(j * kX + i)] = f[i].value();
        for (int q = 0; q < kW; ++q) cache_jf_[static_cast<size_t>((j * kX + i) * kW + q)] = f[i].derivatives()[q];
        cache_ok_ = cache_ok_ && std::isfinite(f[i].value()) && f[i].derivatives().allFinite();
      }
      for (int i = 0; i < n_path_; ++i) {
        const A1& gi = g[static_cast<size_t>(i)];
        cache_g_[static_cast<size_t>(j * n_path_ + i)] = gi.value();
        for (int q = 0; q < kW; ++q) cache_jg_[static_cast<size_t>((j * n_path_ + i) * kW + q)] = gi.derivatives()[q];
        cache_ok_ = cache_ok_ && std::isfinite(gi.value()) && gi.derivatives().allFinite();
      }
    }
    cache_valid_ = true;
  }

  int jacobian_nonzeros() const {
    int nnz = n_seg_ * kX * ((2 * kZ + 2) + (3 * kZ + 1));
    nnz += n_pts_ * n_path_ * (kZ + kP);
    nnz += 2 * static_cast<int>(limited_.size()) * (n_pts_ - 1) * 3;
    nnz += opt_.linear_controls ? n_seg_ * kU * 3 : 0;
    nnz += n_term_ * kV;
    return nnz;
  }

  // The same traversal for the pattern and the values (so they cannot disagree).
  template <class Put>
  void jacobian_pattern(Put&& put) const {
    const int tf = pi(0);
    for (int k = 0; k < n_seg_; ++k) {
      const int j0 = 2 * k, jm = j0 + 1, j1 = j0 + 2;
      for (int i = 0; i < kX; ++i) {  // Hermite rows
        const int row = row_defect_ + k * 2 * kX + i;
        for (int q = 0; q < kZ; ++q) put(row, zi(j0, q));
        for (int q = 0; q < kZ; ++q) put(row, zi(j1, q));
        put(row, zi(jm, i));
        put(row, tf);
      }
      for (int i = 0; i < kX; ++i) {  // Simpson rows
        const int row = row_defect_ + k * 2 * kX + kX + i;
        for (int q = 0; q < kZ; ++q) put(row, zi(j0, q));
        for (int q = 0; q < kZ; ++q) put(row, zi(jm, q));
        for (int q = 0; q < kZ; ++q) put(row, zi(j1, q));
        put(row, tf);
      }
    }
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < n_path_; ++i) {
        const int row = row_path_ + j * n_path_ + i;
        for (int q = 0; q < kZ; ++q) put(row, zi(j, q));
        for (int l = 0; l < kP; ++l) put(row, pi(l));
      }
    }
    int r = row_rate_;
    for (int c : limited_) {
      for (int j = 0; j + 1 < n_pts_; ++j) {
        for (int s = 0; s < 2; ++s) {
          put(r, zi(j, kX + c));
          put(r, zi(j + 1, kX + c));
          put(r, tf);
          ++r;
        }
      }
    }
    for (int k = 0; k < n_seg_ && opt_.linear_controls; ++k) {
      for (int c = 0; c < kU; ++c) {
        put(row_lin_ + k * kU + c, zi(2 * k, kX + c));
        put(row_lin_ + k * kU + c, zi(2 * k + 1, kX + c));
        put(row_lin_ + k * kU + c, zi(2 * k + 2, kX + c));
      }
    }
    for (int k = 0; k < n_term_; ++k)
      for (int q = 0; q < kV; ++q) put(row_term_ + k, terminal_index(q));
  }

  template <class Put>
  void jacobian_values(const double* x, Put&& put) const {
    const double tf = x[pi(0)];
    for (int k = 0; k < n_seg_; ++k) {
      const int j0 = 2 * k, jm = j0 + 1, j1 = j0 + 2;
      const double dtau = mesh_.tau[k + 1] - mesh_.tau[k];
      const double h = dtau * tf;
      const double t0 = tau_[j0], tm = tau_[jm], t1 = tau_[j1];
      for (int i = 0; i < kX; ++i) {  // x_m - (x0 + x1)/2 - h/8 (f0 - f1)
        for (int q = 0; q < kZ; ++q) put((q == i ? -0.5 : 0.0) - h / 8.0 * jf(j0, i, 1 + q));
        for (int q = 0; q < kZ; ++q) put((q == i ? -0.5 : 0.0) + h / 8.0 * jf(j1, i, 1 + q));
        put(1.0);
        put(-dtau / 8.0 * (fv(j0, i) - fv(j1, i)) - h / 8.0 * (t0 * jf(j0, i, 0) - t1 * jf(j1, i, 0)));
      }
      for (int i = 0; i < kX; ++i) {  // x1 - x0 - h/6 (f0 + 4 fm + f1)
        for (int q = 0; q < kZ; ++q) put((q == i ? -1.0 : 0.0) - h / 6.0 * jf(j0, i, 1 + q));
        for (int q = 0; q < kZ; ++q) put(-4.0 * h / 6.0 * jf(jm, i, 1 + q));
        for (int q = 0; q < kZ; ++q) put((q == i ? 1.0 : 0.0) - h / 6.0 * jf(j1, i, 1 + q));
        put(-dtau / 6.0 * (fv(j0, i) + 4.0 * fv(jm, i) + fv(j1, i)) -
            h / 6.0 * (t0 * jf(j0, i, 0) + 4.0 * tm * jf(jm, i, 0) + t1 * jf(j1, i, 0)));
      }
    }
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < n_path_; ++i) {
        for (int q = 0; q < kZ; ++q) put(jg(j, i, 1 + q));
        for (int l = 0; l < kP; ++l) {
          double v = path_a_[static_cast<size_t>(i * kP + l)];
          if (l == 0) v += tau_[j] * jg(j, i, 0);
          put(v);
        }
      }
    }
    for (int c : limited_) {
      for (int j = 0; j + 1 < n_pts_; ++j) {
        const double dtau = tau_[j + 1] - tau_[j];
        for (int s = 0; s < 2; ++s) {
          put(-1.0);
          put(1.0);
          put((s == 0 ? -1.0 : 1.0) * rate_[c] * dtau);
        }
      }
    }
    for (int k = 0; k < n_seg_ && opt_.linear_controls; ++k) {
      for (int c = 0; c < kU; ++c) {
        put(-0.5);
        put(1.0);
        put(-0.5);
      }
    }
    if (n_term_ > 0) {
      double v[kV];
      terminal_args(x, v);
      Ad1<kV> av[kV];
      seed<kV>(v, av);
      std::vector<Ad1<kV>> psi(static_cast<size_t>(n_term_));
      pb_.terminal(av, av + kX, av + kZ, psi.data());
      for (int k = 0; k < n_term_; ++k)
        for (int q = 0; q < kV; ++q) put(psi[static_cast<size_t>(k)].derivatives()[q]);
    }
  }

  void build_hessian_structure() {
    std::map<std::pair<int, int>, int> index;
    auto entry = [&](int a, int b) {
      const int row = std::max(a, b), col = std::min(a, b);
      const auto key = std::make_pair(row, col);
      auto it = index.find(key);
      if (it != index.end()) return it->second;
      const int e = static_cast<int>(hess_rows_.size());
      hess_rows_.push_back(row);
      hess_cols_.push_back(col);
      index.emplace(key, e);
      return e;
    };
    hess_point_.assign(static_cast<size_t>(n_pts_) * kHessPoint, 0);
    for (int j = 0; j < n_pts_; ++j) {
      int* idx = &hess_point_[static_cast<size_t>(j) * kHessPoint];
      int e = 0;
      for (int p = 0; p < kZ; ++p)
        for (int q = 0; q <= p; ++q) idx[e++] = entry(zi(j, p), zi(j, q));
      for (int q = 0; q < kZ; ++q) idx[e++] = entry(pi(0), zi(j, q));
      idx[e++] = entry(pi(0), pi(0));
    }
    for (int p = 0; p < kV; ++p)
      for (int q = 0; q <= p; ++q) hess_term_.push_back(entry(terminal_index(p), terminal_index(q)));
  }

  const Problem& pb_;
  Mesh mesh_;
  Trajectory guess_;
  SolverOptions opt_;
  int n_seg_ = 0, n_pts_ = 0, n_path_ = 0, n_term_ = 0, n_var_ = 0, n_con_ = 0;
  int row_defect_ = 0, row_path_ = 0, row_rate_ = 0, row_lin_ = 0, row_term_ = 0;
  std::vector<double> tau_, rate_, path_a_;
  std::vector<int> limited_;
  std::vector<double> cache_f_, cache_g_, cache_jf_, cache_jg_;
  std::vector<double> cache_x_;
  bool cache_valid_ = false, cache_ok_ = false;
  std::vector<int> hess_rows_, hess_cols_, hess_point_, hess_term_;
  std::chrono::steady_clock::time_point t_start_;
  int iterations_ = 0;
  bool timed_out_ = false;
  Solution sol_;
};

namespace detail {
/// Sets the IPOPT options of one solve (no output files, MUMPS, bounded iterations).
void configure(Ipopt::IpoptApplication& app, const SolverOptions& o);
}  // namespace detail

/// Transcribes and solves. `guess` holds the 2N + 1 points of `mesh` (Mesh::point_tau).
template <class Problem>
Solution solve(const Problem& problem, const Mesh& mesh, const Trajectory& guess, const SolverOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  Ipopt::SmartPtr<HermiteSimpsonNlp<Problem>> nlp = new HermiteSimpsonNlp<Problem>(problem, mesh, guess, options);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  detail::configure(*app, options);
  Solution out;
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    out.ipopt_status = "initialize_failed";
    return out;
  }
  app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(nlp)));
  out = nlp->solution();
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace reentry::optimal
