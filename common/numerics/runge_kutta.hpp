#pragma once
// Runge-Kutta integrators, thesis sec. 4.3: classical RK4 and embedded Runge-Kutta-Fehlberg pairs
// RKF5(6)-8 and RKF7(8)-13 (Fehlberg 1968, NASA TR R-287) in the general form (4.10), truncation
// error (4.11), per-component scaling (4.12), scaled RMS error (4.13) and step-size factor (4.14).
// Thesis convention: the order-p solution is propagated; the order-(p+1) one only estimates the error.
// Header-only, allocation-free, no exceptions; derivative functor: void f(double t, const State<N>& y,
// State<N>& dydt).

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "numerics/status.hpp"

namespace reentry::numerics {

template <int N>
using State = std::array<double, N>;

// Classical fourth-order Runge-Kutta step.
template <int N, class F>
void rk4_step(F&& f, double t, const State<N>& y, double h, State<N>& y_out) {
  State<N> k1{};
  State<N> k2{};
  State<N> k3{};
  State<N> k4{};
  State<N> tmp{};
  f(t, y, k1);
  for (int i = 0; i < N; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
  f(t + 0.5 * h, tmp, k2);
  for (int i = 0; i < N; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
  f(t + 0.5 * h, tmp, k3);
  for (int i = 0; i < N; ++i) tmp[i] = y[i] + h * k3[i];
  f(t + h, tmp, k4);
  for (int i = 0; i < N; ++i) y_out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

// Same, with N deduced from the state (std::array's extent is a std::size_t).
template <class F, std::size_t M>
void rk4_step(F&& f, double t, const std::array<double, M>& y, double h, std::array<double, M>& y_out) {
  rk4_step<static_cast<int>(M)>(f, t, y, h, y_out);
}

enum class RkfMethod { kRkf56, kRkf78 };

// Per-component tolerances of (4.12): s_i = abs_i + |y_i| rel_i.
template <int N>
struct RkfTolerances {
  State<N> abs;
  State<N> rel;

  static RkfTolerances uniform(double abs_tol, double rel_tol) {
    RkfTolerances t{};
    t.abs.fill(abs_tol);
    t.rel.fill(rel_tol);
    return t;
  }
};

// Result of one attempted step.
template <int N>
struct RkfStep {
  bool accepted;       // scaled error (4.13) <= 1 and everything finite
  double error_norm;   // epsilon of (4.13)
  double h_next;       // suggested next step (4.14), growth <= 5x, shrink >= 0.1x
  State<N> y;          // propagated order-p solution at t + h (meaningful if accepted)
  NumStatus status;    // kOk, kNonFinite (NaN/Inf in stages or error), kInvalidInput (h == 0 or non-finite)
  int evaluations;     // derivative evaluations spent (number of stages)
};

// Result of integrate().
template <int N>
struct RkfIntegration {
  State<N> y;          // state at t
  double t;            // reached time (== t1 exactly on success when stopping at t1)
  double h_next;       // step suggested for continuing
  int evaluations;     // derivative evaluations
  int accepted_steps;
  int rejected_steps;
  NumStatus status;    // kOk, kMaxIterations (step budget), kStepTooSmall, kNonFinite, kInvalidInput
};

namespace detail {

constexpr int kMaxStages = 13;

// Butcher tableau of an embedded pair: alpha (nodes), beta (stage matrix), c (order p, propagated),
// e = c_hat - c (error weights of (4.11)).
struct RkfTableau {
  int stages;
  int order;  // p
  double alpha[kMaxStages];
  double beta[kMaxStages][kMaxStages];
  double c[kMaxStages];
  double e[kMaxStages];
};

// Fehlberg RK5(6)-8 (NASA TR R-287, 1968, table for the 5th/6th-order pair).
inline constexpr RkfTableau kFehlberg56 = {
    8,
    5,
    {0.0, 1.0 / 6.0, 4.0 / 15.0, 2.0 / 3.0, 4.0 / 5.0, 1.0, 0.0, 1.0},
    {
        {},
        {1.0 / 6.0},
        {4.0 / 75.0, 16.0 / 75.0},
        {5.0 / 6.0, -8.0 / 3.0, 5.0 / 2.0},
        {-8.0 / 5.0, 144.0 / 25.0, -4.0, 16.0 / 25.0},
        {361.0 / 320.0, -18.0 / 5.0, 407.0 / 128.0, -11.0 / 80.0, 55.0 / 128.0},
        {-11.0 / 640.0, 0.0, 11.0 / 256.0, -11.0 / 160.0, 11.0 / 256.0, 0.0},
        {93.0 / 640.0, -18.0 / 5.0, 803.0 / 256.0, -11.0 / 160.0, 99.0 / 256.0, 0.0, 1.0},
    },
    // 5th order weights (propagated)
    {31.0 / 384.0, 0.0, 1125.0 / 2816.0, 9.0 / 32.0, 125.0 / 768.0, 5.0 / 66.0, 0.0, 0.0},
    // c_hat - c with 6th order weights {7/1408, 0, 1125/2816, 9/32, 125/768, 0, 5/66, 5/66}
    {-5.0 / 66.0, 0.0, 0.0, 0.0, 0.0, -5.0 / 66.0, 5.0 / 66.0, 5.0 / 66.0},
};

// Fehlberg RK7(8)-13 (NASA TR R-287, 1968).
inline constexpr RkfTableau kFehlberg78 = {
    13,
    7,
    {0.0, 2.0 / 27.0, 1.0 / 9.0, 1.0 / 6.0, 5.0 / 12.0, 1.0 / 2.0, 5.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0, 1.0 / 3.0, 1.0, 0.0,
     1.0},
    {
        {},
        {2.0 / 27.0},
        {1.0 / 36.0, 1.0 / 12.0},
        {1.0 / 24.0, 0.0, 1.0 / 8.0},
        {5.0 / 12.0, 0.0, -25.0 / 16.0, 25.0 / 16.0},
        {1.0 / 20.0, 0.0, 0.0, 1.0 / 4.0, 1.0 / 5.0},
        {-25.0 / 108.0, 0.0, 0.0, 125.0 / 108.0, -65.0 / 27.0, 125.0 / 54.0},
        {31.0 / 300.0, 0.0, 0.0, 0.0, 61.0 / 225.0, -2.0 / 9.0, 13.0 / 900.0},
        {2.0, 0.0, 0.0, -53.0 / 6.0, 704.0 / 45.0, -107.0 / 9.0, 67.0 / 90.0, 3.0},
        {-91.0 / 108.0, 0.0, 0.0, 23.0 / 108.0, -976.0 / 135.0, 311.0 / 54.0, -19.0 / 60.0, 17.0 / 6.0, -1.0 / 12.0},
        {2383.0 / 4100.0, 0.0, 0.0, -341.0 / 164.0, 4496.0 / 1025.0, -301.0 / 82.0, 2133.0 / 4100.0, 45.0 / 82.0,
         45.0 / 164.0, 18.0 / 41.0},
        {3.0 / 205.0, 0.0, 0.0, 0.0, 0.0, -6.0 / 41.0, -3.0 / 205.0, -3.0 / 41.0, 3.0 / 41.0, 6.0 / 41.0, 0.0},
        {-1777.0 / 4100.0, 0.0, 0.0, -341.0 / 164.0, 4496.0 / 1025.0, -289.0 / 82.0, 2193.0 / 4100.0, 51.0 / 82.0,
         33.0 / 164.0, 12.0 / 41.0, 0.0, 1.0},
    },
    // 7th order weights (propagated)
    {41.0 / 840.0, 0.0, 0.0, 0.0, 0.0, 34.0 / 105.0, 9.0 / 35.0, 9.0 / 35.0, 9.0 / 280.0, 9.0 / 280.0, 41.0 / 840.0,
     0.0, 0.0},
    // c_hat - c with 8th order weights {0,0,0,0,0,34/105,9/35,9/35,9/280,9/280,0,41/840,41/840}
    {-41.0 / 840.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -41.0 / 840.0, 41.0 / 840.0, 41.0 / 840.0},
};

inline const RkfTableau& tableau(RkfMethod m) { return m == RkfMethod::kRkf78 ? kFehlberg78 : kFehlberg56; }

}  // namespace detail

template <int N>
class EmbeddedRungeKutta {
 public:
  static constexpr double kSafety = 0.9;      // (4.14)
  static constexpr double kMaxGrowth = 5.0;   // step may grow at most 5x per step
  static constexpr double kMaxShrink = 0.1;   // and shrink to no less than 0.1x

  explicit EmbeddedRungeKutta(RkfMethod m) : method_(m), tab_(&detail::tableau(m)) {}

  RkfMethod method() const { return method_; }
  int order() const { return tab_->order; }
  int stages() const { return tab_->stages; }

  // One attempted step of size h (may be negative) from (t, y): (4.10)-(4.14).
  template <class F>
  RkfStep<N> step(F&& f, double t, const State<N>& y, double h, const RkfTolerances<N>& tol) const {
    RkfStep<N> out{};
    out.y = y;
    out.accepted = false;
    out.h_next = h;
    out.error_norm = std::numeric_limits<double>::infinity();
    out.evaluations = 0;
    if (!(h != 0.0) || !std::isfinite(h) || !std::isfinite(t)) {
      out.status = NumStatus::kInvalidInput;
      return out;
    }
    const detail::RkfTableau& tb = *tab_;
    State<N> k[detail::kMaxStages];
    State<N> tmp{};
    for (int s = 0; s < tb.stages; ++s) {  // (4.10): f_k = f(x0 + alpha_k h, y0 + h sum beta_k,l f_l)
      for (int i = 0; i < N; ++i) {
        double acc = 0.0;
        for (int l = 0; l < s; ++l) acc += tb.beta[s][l] * k[l][i];
        tmp[i] = y[i] + h * acc;
      }
      f(t + tb.alpha[s] * h, tmp, k[s]);
      ++out.evaluations;
    }
    double sum_sq = 0.0;
    bool finite = true;
    for (int i = 0; i < N; ++i) {
      double incr = 0.0;
      double err = 0.0;
      for (int s = 0; s < tb.stages; ++s) {
        incr += tb.c[s] * k[s][i];
        err += tb.e[s] * k[s][i];
      }
      const double y_new = y[i] + h * incr;      // order-p solution (4.10)
      const double delta = h * err;              // (4.11)
      const double y_mag = std::fmax(std::fabs(y[i]), std::fabs(y_new));
      const double scale = tol.abs[i] + y_mag * tol.rel[i];  // (4.12)
      if (!std::isfinite(y_new) || !std::isfinite(delta)) finite = false;
      out.y[i] = y_new;
      // A component with zero scale (zero tolerances and zero state) must have zero error.
      const double r = (scale > 0.0) ? delta / scale : (delta == 0.0 ? 0.0 : 1e300);
      sum_sq += r * r;
    }
    if (!finite || !std::isfinite(sum_sq)) {
      out.status = NumStatus::kNonFinite;
      out.h_next = kMaxShrink * h;
      out.y = y;
      return out;
    }
    const double eps = std::sqrt(sum_sq / static_cast<double>(N));  // (4.13)
    out.error_norm = eps;
    out.status = NumStatus::kOk;
    out.accepted = eps <= 1.0;
    out.h_next = h * step_factor(eps);
    if (!out.accepted) out.y = y;
    return out;
  }

  // Step-size factor (4.14): delta = 0.9 (1/eps)^(1/(p+1)), limited to [0.1, 5].
  double step_factor(double eps) const {
    if (!(eps > 0.0)) return kMaxGrowth;
    const double delta = kSafety * std::pow(1.0 / eps, 1.0 / (tab_->order + 1));
    return std::fmin(kMaxGrowth, std::fmax(kMaxShrink, delta));
  }

  // Integrates from (t0, y0) to t1 (either direction) starting with step h0 (its sign is ignored).
  // At most max_steps attempted steps (accepted + rejected). h_min (> 0) is the smallest step
  // magnitude allowed before kStepTooSmall; 0 selects 1e-14 * max(|t0|, |t1|, |t1 - t0|).
  // With stop_at_t1 the last step is shortened so that the result lands exactly on t1; otherwise
  // the final accepted step may overshoot t1 (useful for continuing beyond).
  template <class F>
  RkfIntegration<N> integrate(F&& f, double t0, const State<N>& y0, double t1, double h0,
                              const RkfTolerances<N>& tol, int max_steps, double h_min = 0.0,
                              bool stop_at_t1 = true) const {
    RkfIntegration<N> r{};
    r.y = y0;
    r.t = t0;
    r.h_next = h0;
    r.status = NumStatus::kOk;
    if (!std::isfinite(t0) || !std::isfinite(t1) || !std::isfinite(h0) || h0 == 0.0 || max_steps < 1 ||
        h_min < 0.0) {
      r.status = NumStatus::kInvalidInput;
      return r;
    }
    if (t1 == t0) return r;
    const double dir = (t1 > t0) ? 1.0 : -1.0;
    const double span = std::fabs(t1 - t0);
    const double h_floor =
        (h_min > 0.0) ? h_min : 1e-14 * std::fmax(span, std::fmax(std::fabs(t0), std::fabs(t1)));
    double h = dir * std::fmin(std::fabs(h0), span);
    for (int attempt = 0; attempt < max_steps; ++attempt) {
      const double remaining = t1 - r.t;
      bool last = false;
      double h_try = h;
      if (stop_at_t1 && std::fabs(h_try) >= std::fabs(remaining)) {
        h_try = remaining;
        last = true;
      }
      const RkfStep<N> s = step(f, r.t, r.y, h_try, tol);
      r.evaluations += s.evaluations;
      if (s.status == NumStatus::kInvalidInput) {
        r.status = s.status;
        return r;
      }
      if (s.accepted) {
        ++r.accepted_steps;
        r.y = s.y;
        r.t = last ? t1 : r.t + h_try;
        // Do not let a shortened final step shrink the suggestion for continuing.
        r.h_next = last ? dir * std::fmax(std::fabs(h), std::fabs(s.h_next)) : s.h_next;
        if (last || (!stop_at_t1 && dir * (r.t - t1) >= 0.0)) return r;
        h = s.h_next;
      } else {
        ++r.rejected_steps;
        h = s.h_next;  // already limited to >= 0.1x
        r.h_next = h;
        if (std::fabs(h) < h_floor) {
          r.status = (s.status == NumStatus::kNonFinite) ? NumStatus::kNonFinite : NumStatus::kStepTooSmall;
          return r;
        }
      }
    }
    r.status = NumStatus::kMaxIterations;
    return r;
  }

 private:
  RkfMethod method_;
  const detail::RkfTableau* tab_;
};

// Convenience wrapper: integrate with a freshly constructed integrator of the given method.
// (Templated on the std::array extent so that N is deduced from y0.)
template <class F, std::size_t M>
RkfIntegration<static_cast<int>(M)> integrate(RkfMethod method, F&& f, double t0, const std::array<double, M>& y0,
                                               double t1, double h0, const RkfTolerances<static_cast<int>(M)>& tol,
                                               int max_steps, double h_min = 0.0, bool stop_at_t1 = true) {
  const EmbeddedRungeKutta<static_cast<int>(M)> rk(method);
  return rk.integrate(f, t0, y0, t1, h0, tol, max_steps, h_min, stop_at_t1);
}

}  // namespace reentry::numerics
