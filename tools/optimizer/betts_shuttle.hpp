// Betts's Space Shuttle maximum-crossrange re-entry (Betts 2010, Practical Methods for Optimal
// Control and Estimation Using Nonlinear Programming, sec. 6.1 and table 10.31): the published
// benchmark that validates the transcription, the AD derivatives and the NLP set-up of this
// optimizer before it runs on the truth models.
//
// The benchmark's own models, in its US units (ft, slug, s, BTU), not ours: non-rotating
// spherical Earth with inverse-square gravity, exponential atmosphere, the lift and drag fits
// C_L = a0 + a1 a, C_D = b0 + b1 a + b2 a^2 and the wing-leading-edge heating
// q = q_a q_r, q_a = c0 + c1 a + c2 a^2 + c3 a^3, q_r = 17700 sqrt(rho) (1e-4 v)^3.07 BTU/ft^2/s
// (a: angle of attack in degrees). The constants below were checked against three public
// implementations: OpenMDAO/dymos examples/shuttle_reentry, ferrolho/space-shuttle-reentry-
// trajectory (Julia/KNITRO) and trajectolab's shuttle example (citing Betts table 10.31).
// Published optimum: theta_f = 34.1412 deg at t_f = 2008.59 s unconstrained, 30.6255 deg at
// 2198.67 s with q <= 70 BTU/ft^2/s.
#pragma once

#include <cmath>
#include <limits>

#include "hermite_simpson.hpp"

namespace reentry::optimal {

struct BettsShuttle {
  static constexpr int kStates = 6;    // h [ft], phi (longitude), theta (latitude), v [ft/s], gamma, psi
  static constexpr int kControls = 2;  // alpha, beta (bank) [rad]
  static constexpr int kParams = 1;    // t_f
  static constexpr double kDeg = M_PI / 180.0;

  static constexpr double kWeight_lb = 203000.0;
  static constexpr double kG0_ftps2 = 32.174;
  static constexpr double kMass_slug = kWeight_lb / kG0_ftps2;
  static constexpr double kRho0_slugpft3 = 0.002378;
  static constexpr double kScaleHeight_ft = 23800.0;
  static constexpr double kRe_ft = 20902900.0;
  static constexpr double kMu_ft3ps2 = 0.14076539e17;
  static constexpr double kArea_ft2 = 2690.0;
  static constexpr double kA0 = -0.20704, kA1 = 0.029244;
  static constexpr double kB0 = 0.07854, kB1 = -0.61592e-2, kB2 = 0.621408e-3;
  static constexpr double kC0 = 1.0672181, kC1 = -0.19213774e-1, kC2 = 0.21286289e-3, kC3 = -0.10117249e-5;

  double heating_limit_BTU = std::numeric_limits<double>::infinity();  // q_U (70 in the constrained case)

  int n_path() const { return std::isfinite(heating_limit_BTU) ? 1 : 0; }
  int n_terminal() const { return 3; }  // h_f, v_f, gamma_f
  double t0() const { return 0.0; }
  bool time_invariant() const { return true; }  // non-rotating Earth
  void initial_state(double* x) const {
    x[0] = 260000.0;
    x[1] = 0.0;
    x[2] = 0.0;
    x[3] = 25600.0;
    x[4] = -1.0 * kDeg;
    x[5] = 90.0 * kDeg;
  }
  void state_bounds(double* lo, double* hi) const {
    const double inf = std::numeric_limits<double>::infinity();
    lo[0] = 0.0;          hi[0] = 300000.0;
    lo[1] = -inf;         hi[1] = inf;
    lo[2] = -89.0 * kDeg; hi[2] = 89.0 * kDeg;
    lo[3] = 1.0;          hi[3] = inf;
    lo[4] = -89.0 * kDeg; hi[4] = 89.0 * kDeg;
    lo[5] = -180.0 * kDeg; hi[5] = 180.0 * kDeg;
  }
  void control_bounds(double* lo, double* hi) const {
    lo[0] = -90.0 * kDeg; hi[0] = 90.0 * kDeg;
    lo[1] = -89.0 * kDeg; hi[1] = 1.0 * kDeg;
  }
  void param_bounds(double* lo, double* hi) const {
    lo[0] = 100.0;
    hi[0] = 5000.0;
  }
  void path_bounds(double* lo, double* hi) const {
    lo[0] = -std::numeric_limits<double>::infinity();
    hi[0] = heating_limit_BTU;
  }
  void path_param_coupling(double* a) const { a[0] = 0.0; }
  void control_rate_limits(double* rate) const {
    rate[0] = rate[1] = std::numeric_limits<double>::infinity();
  }
  void terminal_bounds(double* lo, double* hi) const {
    lo[0] = hi[0] = 80000.0;
    lo[1] = hi[1] = 2500.0;
    lo[2] = hi[2] = -5.0 * kDeg;
  }
  void state_scales(double* s) const {
    s[0] = 1e5;
    s[1] = s[2] = 1.0;
    s[3] = 1e4;
    s[4] = s[5] = 1.0;
  }
  void defect_scales(double* s) const { state_scales(s); }
  void control_scales(double* s) const { s[0] = s[1] = 1.0; }
  void param_scales(double* s) const { s[0] = 1e3; }
  void path_scales(double* s) const { s[0] = 70.0; }
  void terminal_scales(double* s) const {
    s[0] = 1e5;
    s[1] = 1e4;
    s[2] = 1.0;
  }
  double objective_scale() const { return 1.0; }

  /// Wing-leading-edge heating [BTU/ft^2/s] at altitude h [ft], speed v [ft/s], alpha [rad].
  template <class T>
  static T heating(const T& h, const T& v, const T& alpha) {
    using std::exp;
    using std::log;
    using std::sqrt;
    const T rho = kRho0_slugpft3 * exp(-h / kScaleHeight_ft);
    const T a = alpha / kDeg;
    const T qa = kC0 + kC1 * a + kC2 * a * a + kC3 * a * a * a;
    const T qr = 17700.0 * sqrt(rho) * exp(3.07 * log(1e-4 * v));
    return qa * qr;
  }

  template <class T>
  void point(const T&, const T* x, const T* u, T* xdot, T* path) const {
    using std::cos;
    using std::exp;
    using std::sin;
    const T& h = x[0];
    const T& theta = x[2];
    const T& v = x[3];
    const T& gamma = x[4];
    const T& psi = x[5];
    const T& alpha = u[0];
    const T& beta = u[1];
    const T a = alpha / kDeg;
    const T cl = kA0 + kA1 * a;
    const T cd = kB0 + kB1 * a + kB2 * a * a;
    const T rho = kRho0_slugpft3 * exp(-h / kScaleHeight_ft);
    const T q = 0.5 * rho * v * v;
    const T lift = q * kArea_ft2 * cl, drag = q * kArea_ft2 * cd;
    const T r = kRe_ft + h;
    const T g = kMu_ft3ps2 / (r * r);
    const T cg = cos(gamma), sg = sin(gamma);
    xdot[0] = v * sg;
    xdot[1] = v / r * cg * sin(psi) / cos(theta);
    xdot[2] = v / r * cg * cos(psi);
    xdot[3] = -drag / kMass_slug - g * sg;
    xdot[4] = lift / (kMass_slug * v) * cos(beta) + cg * (v / r - g / v);
    xdot[5] = lift * sin(beta) / (kMass_slug * v * cg) + v / (r * cos(theta)) * cg * sin(psi) * sin(theta);
    if (n_path() > 0) path[0] = heating(h, v, alpha);
  }

  template <class T>
  void terminal(const T* x, const T*, const T*, T* psi) const {
    psi[0] = x[0];
    psi[1] = x[3];
    psi[2] = x[4];
  }

  template <class T>
  T objective(const T* x, const T*, const T*) const {
    return -x[2];  // maximise the final latitude (crossrange)
  }

  /// The linear initial guess of the dymos example: states from the initial to plausible final
  /// values, alpha 17.4 deg, bank -75 deg to 0, t_f = 2000 s.
  Trajectory linear_guess(const Mesh& mesh) const;
};

}  // namespace reentry::optimal
