// The Hermite-Simpson transcription as IPOPT's TNLP (hermite_simpson.hpp says what it solves).
// Point functions are evaluated in double at trial points (constraint values), with first-order
// AD at accepted points (the Jacobian) and second-order AD for the Hessian of the Lagrangian.
#pragma once

#include <IpTNLP.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "ad.hpp"
#include "hermite_simpson.hpp"

namespace reentry::optimal {

template <class Problem>
class HermiteSimpsonNlp : public Ipopt::TNLP {
 public:
  static constexpr int kX = Problem::kStates;
  static constexpr int kU = Problem::kControls;
  static constexpr int kP = Problem::kParams;
  static constexpr int kZ = kX + kU;     // variables of one point
  static constexpr int kW = 1 + kZ;      // arguments of the point function: t, x, u
  static constexpr int kV = kZ + kP;     // arguments of the terminal functions: x_f, u_f, p

  HermiteSimpsonNlp(const Problem& problem, const Mesh& mesh, const Trajectory& guess, const SolverOptions& options,
                    const PointBias* bias, const Multipliers* duals)
      : pb_(problem), mesh_(mesh), guess_(guess), opt_(options) {
    n_seg_ = mesh.segments();
    n_pts_ = 2 * n_seg_ + 1;
    tau_ = mesh.point_tau();
    n_path_ = pb_.n_path();
    n_term_ = pb_.n_terminal();
    time_invariant_ = pb_.time_invariant();
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
    bias_f_.assign(cache_f_.size(), 0.0);
    bias_g_.assign(cache_g_.size(), 0.0);
    if (bias && bias->f.size() == bias_f_.size()) bias_f_ = bias->f;
    if (bias && n_path_ > 0 && bias->path.size() == bias_g_.size()) bias_g_ = bias->path;
    build_hessian_structure();
    if (duals && duals->lambda.size() == static_cast<size_t>(n_con_) && duals->z_lower.size() == static_cast<size_t>(n_var_) &&
        duals->z_upper.size() == static_cast<size_t>(n_var_))
      duals_ = *duals;
    t_start_ = std::chrono::steady_clock::now();
  }

  const Solution& solution() const { return sol_; }
  bool warm_duals() const { return !duals_.empty(); }

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
    variable_bounds(x_l, x_u);
    constraint_bounds(g_l, g_u);
    return true;
  }

  bool get_starting_point(Ipopt::Index, bool init_x, Ipopt::Number* x, bool init_z, Ipopt::Number* z_l,
                          Ipopt::Number* z_u, Ipopt::Index, bool init_lambda, Ipopt::Number* lambda) override {
    if ((init_z || init_lambda) && duals_.empty()) return false;
    if (init_z) {
      std::copy(duals_.z_lower.begin(), duals_.z_lower.end(), z_l);
      std::copy(duals_.z_upper.begin(), duals_.z_upper.end(), z_u);
    }
    if (init_lambda) std::copy(duals_.lambda.begin(), duals_.lambda.end(), lambda);
    if (!init_x) return true;
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < kX; ++i) x[zi(j, i)] = guess_.x[static_cast<size_t>(j * kX + i)];
      for (int c = 0; c < kU; ++c) x[zi(j, kX + c)] = guess_.u[static_cast<size_t>(j * kU + c)];
    }
    for (int l = 0; l < kP; ++l) x[pi(l)] = guess_.p[static_cast<size_t>(l)];
    return true;
  }

  bool get_scaling_parameters(Ipopt::Number& obj_scaling, bool& use_x_scaling, Ipopt::Index, Ipopt::Number* x_scaling,
                              bool& use_g_scaling, Ipopt::Index, Ipopt::Number* g_scaling) override {
    obj_scaling = 1.0 / pb_.objective_scale();
    use_x_scaling = true;
    variable_scaling(x_scaling);
    use_g_scaling = true;
    constraint_scaling(g_scaling);
    return true;
  }

  bool eval_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number& obj_value) override {
    double v[kV];
    terminal_args(x, v);
    obj_value = pb_.objective(v, v + kX, v + kZ) + smoothing(x, nullptr);
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
    smoothing(x, grad_f);
    return std::isfinite(o.value());
  }

  bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Index, Ipopt::Number* g) override {
    if (!refresh_values(x, new_x)) return false;
    defect_values(x, g);
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < n_path_; ++i) {
        double v = gv(j, i);
        for (int l = 0; l < kP; ++l) v += path_a_[static_cast<size_t>(i * kP + l)] * x[pi(l)];
        g[row_path_ + j * n_path_ + i] = v;
      }
    }
    control_row_values(x, g);
    if (n_term_ > 0) {
      double v[kV];
      terminal_args(x, v);
      std::vector<double> psi(static_cast<size_t>(n_term_));
      pb_.terminal(v, v + kX, v + kZ, psi.data());
      for (int k = 0; k < n_term_; ++k) {
        if (!std::isfinite(psi[static_cast<size_t>(k)])) return false;
        g[row_term_ + k] = psi[static_cast<size_t>(k)];
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
    if (!refresh_jacobian(x, new_x)) return false;
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
    const std::vector<double> a = dynamics_weights(lambda);
    for (int j = 0; j < n_pts_; ++j) point_hessian(x, j, &a[static_cast<size_t>(j * kX)], lambda, values);
    terminal_hessian(x, obj_factor, lambda, values);
    smoothing_hessian(obj_factor, values);
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

  void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index, const Ipopt::Number* x, const Ipopt::Number* z_l,
                         const Ipopt::Number* z_u, Ipopt::Index m, const Ipopt::Number* g, const Ipopt::Number* lambda,
                         Ipopt::Number obj_value, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    if (z_l && z_u && lambda) {
      sol_.multipliers.z_lower.assign(z_l, z_l + n_var_);
      sol_.multipliers.z_upper.assign(z_u, z_u + n_var_);
      sol_.multipliers.lambda.assign(lambda, lambda + m);
    }
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
    sol_.max_violation = largest_violation(m, g);
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

  void variable_bounds(double* x_l, double* x_u) const {
    double xl[kX], xu[kX], ul[kU], uu[kU], pl[kP], pu[kP], x0[kX];
    pb_.state_bounds(xl, xu);
    pb_.control_bounds(ul, uu);
    pb_.param_bounds(pl, pu);
    pb_.initial_state(x0);
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < kX; ++i) {
        x_l[zi(j, i)] = j == 0 ? x0[i] : to_ipopt(xl[i]);
        x_u[zi(j, i)] = j == 0 ? x0[i] : to_ipopt(xu[i]);
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
  }

  void constraint_bounds(double* g_l, double* g_u) const {
    for (int r = 0; r < row_path_; ++r) g_l[r] = g_u[r] = 0.0;
    std::vector<double> lo(static_cast<size_t>(std::max(1, n_path_))), hi(lo.size());
    if (n_path_ > 0) pb_.path_bounds(lo.data(), hi.data());
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < n_path_; ++i) {
        g_l[row_path_ + j * n_path_ + i] = to_ipopt(lo[static_cast<size_t>(i)]);
        g_u[row_path_ + j * n_path_ + i] = to_ipopt(hi[static_cast<size_t>(i)]);
      }
    }
    for (int r = row_rate_; r < row_lin_; r += 2) {
      g_l[r] = -kIpoptInf;  // u_{j+1} - u_j - rate dt <= 0
      g_u[r] = 0.0;
      g_l[r + 1] = 0.0;  // u_{j+1} - u_j + rate dt >= 0
      g_u[r + 1] = kIpoptInf;
    }
    for (int r = row_lin_; r < row_term_; ++r) g_l[r] = g_u[r] = 0.0;
    std::vector<double> tl(static_cast<size_t>(std::max(1, n_term_))), tu(tl.size());
    if (n_term_ > 0) pb_.terminal_bounds(tl.data(), tu.data());
    for (int k = 0; k < n_term_; ++k) {
      g_l[row_term_ + k] = to_ipopt(tl[static_cast<size_t>(k)]);
      g_u[row_term_ + k] = to_ipopt(tu[static_cast<size_t>(k)]);
    }
  }

  void variable_scaling(double* x_scaling) const {
    double xs[kX], us[kU], ps[kP];
    pb_.state_scales(xs);
    pb_.control_scales(us);
    pb_.param_scales(ps);
    for (int j = 0; j < n_pts_; ++j) {
      for (int i = 0; i < kX; ++i) x_scaling[zi(j, i)] = 1.0 / xs[i];
      for (int c = 0; c < kU; ++c) x_scaling[zi(j, kX + c)] = 1.0 / us[c];
    }
    for (int l = 0; l < kP; ++l) x_scaling[pi(l)] = 1.0 / ps[l];
  }

  void constraint_scaling(double* g_scaling) const {
    double us[kU], ds[kX];
    pb_.control_scales(us);
    pb_.defect_scales(ds);
    for (int k = 0; k < n_seg_; ++k) {
      for (int i = 0; i < kX; ++i) {
        g_scaling[row_defect_ + k * 2 * kX + i] = 1.0 / ds[i];
        g_scaling[row_defect_ + k * 2 * kX + kX + i] = 1.0 / ds[i];
      }
    }
    std::vector<double> gs(static_cast<size_t>(std::max(1, n_path_)), 1.0);
    if (n_path_ > 0) pb_.path_scales(gs.data());
    for (int j = 0; j < n_pts_; ++j)
      for (int i = 0; i < n_path_; ++i) g_scaling[row_path_ + j * n_path_ + i] = 1.0 / gs[static_cast<size_t>(i)];
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
    for (int k = 0; k < n_term_; ++k) g_scaling[row_term_ + k] = 1.0 / ts[static_cast<size_t>(k)];
  }

  // The control regularisation terms (SolverOptions::control_smoothing, control_proximity);
  // adds their gradient to grad.
  double smoothing(const double* x, double* grad) const {
    double us[kU], sum = 0.0, prox = 0.0;
    pb_.control_scales(us);
    for (int j = 0; j < n_pts_ && opt_.control_proximity > 0.0; ++j) {
      const double share = point_share(j);
      for (int c = 0; c < kU; ++c) {
        const double d = (x[zi(j, kX + c)] - guess_.u[static_cast<size_t>(j * kU + c)]) / us[c];
        prox += d * d * share;
        if (grad) grad[zi(j, kX + c)] += 2.0 * opt_.control_proximity * d * share / us[c];
      }
    }
    if (opt_.control_smoothing <= 0.0) return opt_.control_proximity * prox;
    for (int j = 0; j + 1 < n_pts_; ++j) {
      const double dtau = tau_[j + 1] - tau_[j];
      for (int c = 0; c < kU; ++c) {
        const double d = (x[zi(j + 1, kX + c)] - x[zi(j, kX + c)]) / us[c];
        sum += d * d / dtau;
        if (grad == nullptr) continue;
        const double gr = 2.0 * opt_.control_smoothing * d / (dtau * us[c]);
        grad[zi(j + 1, kX + c)] += gr;
        grad[zi(j, kX + c)] -= gr;
      }
    }
    return opt_.control_smoothing * sum + opt_.control_proximity * prox;
  }

  double point_share(int j) const {
    return 0.5 * (tau_[std::min(j + 1, n_pts_ - 1)] - tau_[std::max(j - 1, 0)]);
  }

  void smoothing_hessian(double obj_factor, double* values) const {
    double us[kU];
    pb_.control_scales(us);
    for (int j = 0; j < n_pts_ && opt_.control_proximity > 0.0; ++j) {
      const int* idx = &hess_point_[static_cast<size_t>(j) * kHessPoint];
      for (int c = 0; c < kU; ++c) {
        const int p = kX + c;  // diagonal entry (p, p) of the point block: index p (p + 1) / 2 + p
        values[idx[p * (p + 1) / 2 + p]] += 2.0 * obj_factor * opt_.control_proximity * point_share(j) / (us[c] * us[c]);
      }
    }
    if (opt_.control_smoothing <= 0.0) return;
    int e = 0;
    for (int j = 0; j + 1 < n_pts_; ++j) {
      const double dtau = tau_[j + 1] - tau_[j];
      for (int c = 0; c < kU; ++c) {
        const double h = 2.0 * obj_factor * opt_.control_smoothing / (dtau * us[c] * us[c]);
        values[hess_smooth_[static_cast<size_t>(e++)]] += h;   // (j+1, j+1)
        values[hess_smooth_[static_cast<size_t>(e++)]] += h;   // (j, j)
        values[hess_smooth_[static_cast<size_t>(e++)]] -= h;   // (j+1, j)
      }
    }
  }

  void defect_values(const double* x, double* g) const {
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
  }

  void control_row_values(const double* x, double* g) const {
    const double tf = x[pi(0)];
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
  }

  double largest_violation(Ipopt::Index m, const double* g) const {
    std::vector<double> gl(static_cast<size_t>(m)), gu(static_cast<size_t>(m));
    constraint_bounds(gl.data(), gu.data());
    double viol = 0.0;
    for (Ipopt::Index r = 0; r < m && g; ++r) {
      if (g[r] < gl[static_cast<size_t>(r)]) viol = std::max(viol, gl[static_cast<size_t>(r)] - g[r]);
      if (g[r] > gu[static_cast<size_t>(r)]) viol = std::max(viol, g[r] - gu[static_cast<size_t>(r)]);
    }
    return viol;
  }

  // The point functions' values (double) at x, cached per iterate. new_x is not trusted alone
  // (IPOPT's derivative checker perturbs x without it): the cached x is compared.
  bool refresh_values(const double* x, bool new_x) {
    if (!new_x && values_valid_ && std::equal(x, x + n_var_, values_x_.begin())) return values_ok_;
    values_x_.assign(x, x + n_var_);
    values_valid_ = true;
    values_ok_ = true;
    std::vector<double> g(static_cast<size_t>(std::max(1, n_path_)));
    for (int j = 0; j < n_pts_; ++j) {
      double w[kW], f[kX];
      point_args(x, j, w);
      pb_.point(w[0], w + 1, w + 1 + kX, f, g.data());
      for (int i = 0; i < kX; ++i) {
        cache_f_[static_cast<size_t>(j * kX + i)] = f[i] + bias_f_[static_cast<size_t>(j * kX + i)];
        values_ok_ = values_ok_ && std::isfinite(f[i]);
      }
      for (int i = 0; i < n_path_; ++i) {
        cache_g_[static_cast<size_t>(j * n_path_ + i)] = g[static_cast<size_t>(i)] + bias_g_[static_cast<size_t>(j * n_path_ + i)];
        values_ok_ = values_ok_ && std::isfinite(g[static_cast<size_t>(i)]);
      }
    }
    return values_ok_;
  }

  // The point functions' first derivatives (AD) at x, with their values.
  bool refresh_jacobian(const double* x, bool new_x) {
    if (!new_x && jac_valid_ && std::equal(x, x + n_var_, jac_x_.begin())) return jac_ok_;
    if (!refresh_values(x, new_x)) return false;
    jac_x_.assign(x, x + n_var_);
    jac_valid_ = true;
    jac_ok_ = true;
    for (int j = 0; j < n_pts_; ++j) jac_ok_ = (time_invariant_ ? point_jacobian<0>(x, j) : point_jacobian<1>(x, j)) && jac_ok_;
    return jac_ok_;
  }

  // First derivatives of point j with respect to (t, z) (kT = 1) or to z alone (kT = 0: a
  // time-invariant problem, whose t column is zero).
  template <int kT>
  bool point_jacobian(const double* x, int j) {
    constexpr int kN = kZ + kT;
    using A1 = Ad1<kN>;
    std::vector<A1> g(static_cast<size_t>(std::max(1, n_path_)));
    double w[kW];
    point_args(x, j, w);
    A1 aw[kN];
    seed<kN>(w + 1 - kT, aw);
    const A1 t = kT ? aw[0] : A1(w[0]);
    A1 f[kX];
    pb_.point(t, aw + kT, aw + kT + kX, f, g.data());
    bool ok = true;
    auto store = [&](const A1& v, double* out) {
      out[0] = kT ? v.derivatives()[0] : 0.0;
      for (int q = 0; q < kZ; ++q) out[1 + q] = v.derivatives()[kT + q];
      ok = ok && v.derivatives().allFinite();
    };
    for (int i = 0; i < kX; ++i) store(f[i], &cache_jf_[static_cast<size_t>((j * kX + i) * kW)]);
    for (int i = 0; i < n_path_; ++i) store(g[static_cast<size_t>(i)], &cache_jg_[static_cast<size_t>((j * n_path_ + i) * kW)]);
    return ok;
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
    control_rows_pattern(put);
    for (int k = 0; k < n_term_; ++k)
      for (int q = 0; q < kV; ++q) put(row_term_ + k, terminal_index(q));
  }

  template <class Put>
  void control_rows_pattern(Put&& put) const {
    int r = row_rate_;
    for (int c : limited_) {
      for (int j = 0; j + 1 < n_pts_; ++j) {
        for (int s = 0; s < 2; ++s) {
          put(r, zi(j, kX + c));
          put(r, zi(j + 1, kX + c));
          put(r, pi(0));
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
  }

  template <class Put>
  void jacobian_values(const double* x, Put&& put) const {
    defect_jacobian(x[pi(0)], put);
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

  template <class Put>
  void defect_jacobian(double tf, Put&& put) const {
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
  }

  // Weights a_j of f_j in the Lagrangian (each multiplying tf): -sum lambda dh/df over the
  // defects of the point's segments, per unit tf.
  std::vector<double> dynamics_weights(const double* lambda) const {
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
    return a;
  }

  // Hessian block of point j: tf a^T f(t, z) + b^T g(t, z), t = t0 + tau_j tf, with respect to
  // (z, tf) (second-order AD in (t, z), or in z alone for a time-invariant problem; the tf terms
  // by the chain rule).
  void point_hessian(const double* x, int j, const double* aj, const double* lambda, double* values) const {
    const double* bj = n_path_ > 0 ? &lambda[row_path_ + j * n_path_] : nullptr;
    bool any = false;
    for (int i = 0; i < kX; ++i) any = any || aj[i] != 0.0;
    for (int i = 0; i < n_path_; ++i) any = any || bj[i] != 0.0;
    if (!any) return;
    if (time_invariant_) point_hessian_in<0>(x, j, aj, bj, values);
    else point_hessian_in<1>(x, j, aj, bj, values);
  }

  template <int kT>
  void point_hessian_in(const double* x, int j, const double* aj, const double* bj, double* values) const {
    constexpr int kN = kZ + kT;
    using A2 = Ad2<kN>;
    const double tf = x[pi(0)];
    double w[kW];
    point_args(x, j, w);
    A2 aw[kN];
    seed<kN>(w + 1 - kT, aw);
    const A2 t = kT ? aw[0] : A2(w[0]);
    A2 f[kX];
    std::vector<A2> g(static_cast<size_t>(std::max(1, n_path_)));
    pb_.point(t, aw + kT, aw + kT + kX, f, g.data());
    A2 s = A2(0.0);
    for (int i = 0; i < kX; ++i)
      if (aj[i] != 0.0) s += (tf * aj[i]) * f[i];
    for (int i = 0; i < n_path_; ++i)
      if (bj[i] != 0.0) s += bj[i] * g[static_cast<size_t>(i)];
    // Gradient of a^T f (for the tf cross terms), from the first-order part of f.
    double af_grad[kN] = {};
    for (int i = 0; i < kX; ++i) {
      if (aj[i] == 0.0) continue;
      for (int q = 0; q < kN; ++q) af_grad[q] += aj[i] * f[i].value().derivatives()[q];
    }
    const double tj = tau_[j];
    const int* idx = &hess_point_[static_cast<size_t>(j) * kHessPoint];
    int e = 0;
    for (int p = 0; p < kZ; ++p)
      for (int q = 0; q <= p; ++q) values[idx[e++]] += s.derivatives()[kT + p].derivatives()[kT + q];
    for (int q = 0; q < kZ; ++q) {
      values[idx[e++]] += af_grad[kT + q] + (kT ? tj * s.derivatives()[0].derivatives()[kT + q] : 0.0);
    }
    values[idx[e++]] += kT ? 2.0 * tj * af_grad[0] + tj * tj * s.derivatives()[0].derivatives()[0] : 0.0;
  }

  void terminal_hessian(const double* x, double obj_factor, const double* lambda, double* values) const {
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
    for (int j = 0; j + 1 < n_pts_ && opt_.control_smoothing > 0.0; ++j) {
      for (int c = 0; c < kU; ++c) {
        hess_smooth_.push_back(entry(zi(j + 1, kX + c), zi(j + 1, kX + c)));
        hess_smooth_.push_back(entry(zi(j, kX + c), zi(j, kX + c)));
        hess_smooth_.push_back(entry(zi(j + 1, kX + c), zi(j, kX + c)));
      }
    }
  }

  const Problem& pb_;
  Mesh mesh_;
  Trajectory guess_;
  SolverOptions opt_;
  int n_seg_ = 0, n_pts_ = 0, n_path_ = 0, n_term_ = 0, n_var_ = 0, n_con_ = 0;
  bool time_invariant_ = false;
  int row_defect_ = 0, row_path_ = 0, row_rate_ = 0, row_lin_ = 0, row_term_ = 0;
  std::vector<double> tau_, rate_, path_a_;
  std::vector<int> limited_;
  std::vector<double> cache_f_, cache_g_, cache_jf_, cache_jg_, bias_f_, bias_g_;
  std::vector<double> values_x_, jac_x_;
  bool values_valid_ = false, values_ok_ = false, jac_valid_ = false, jac_ok_ = false;
  std::vector<int> hess_rows_, hess_cols_, hess_point_, hess_term_, hess_smooth_;
  std::chrono::steady_clock::time_point t_start_;
  int iterations_ = 0;
  bool timed_out_ = false;
  Multipliers duals_;
  Solution sol_;
};

}  // namespace reentry::optimal
