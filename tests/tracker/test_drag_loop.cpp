// Drag loop (drag_loop.hpp, thesis 3.10-3.18) against independent truths: the closed forms of
// (3.13) and the documented gain rule, the closed-form response of the linear error dynamics
// (3.12) flown on an independently integrated plant D'' = a + b u (3.10), and the anti-windup
// rule of the integral written out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "models/onboard_models.hpp"
#include "tracker/drag_loop.hpp"

namespace reentry::fsw {
namespace {

TEST(DragLoop, ScheduledFrequencyFollows313) {
  const double w0 = 0.08, q_ref = 4000.0;
  EXPECT_DOUBLE_EQ(scheduled_omega(w0, 0.0, q_ref), 0.0);
  EXPECT_DOUBLE_EQ(scheduled_omega(w0, 1000.0, q_ref), w0 * (2.0 * 0.25 - 0.0625));
  EXPECT_DOUBLE_EQ(scheduled_omega(w0, 2000.0, q_ref), w0 * 0.75);
  EXPECT_DOUBLE_EQ(scheduled_omega(w0, 4000.0, q_ref), w0);
  EXPECT_DOUBLE_EQ(scheduled_omega(w0, 9000.0, q_ref), w0);  // held above q_ref
}

TEST(DragLoop, GainsFollowTheDocumentedRuleUnlessTheMissionOverrides) {
  TrackerParams m;
  TrackerGains g = derive_gains(m);
  const double w0 = 2.0 * std::sqrt(9.80665 / 7050.0);
  EXPECT_NEAR(g.omega0_radps, w0, 1e-15);
  EXPECT_NEAR(g.omega0_radps, 0.0746, 1e-4);
  EXPECT_NEAR(g.zeta, 1.0 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(g.k_integral, w0 * w0 * w0 / 20.0, 1e-18);
  m.omega0_radps = 0.05;
  m.zeta = 0.9;
  g = derive_gains(m);
  EXPECT_DOUBLE_EQ(g.omega0_radps, 0.05);
  EXPECT_DOUBLE_EQ(g.zeta, 0.9);
  m.k_integral_ps3 = 2e-5;
  EXPECT_DOUBLE_EQ(derive_gains(m).k_integral, 2e-5);
}

TEST(DragLoop, TerminalDragLoopSettlesWithinTheTimeToGo) {
  // The floor on the loop's natural frequency keeps its time constant 1 / (zeta omega)
  // (zeta = 1/sqrt(2)) within the time to go, up to three times omega0 (bank-rate limit).
  const double omega0 = 2.0 * std::sqrt(kG0_mps2 / 7050.0);
  const double zeta = 1.0 / std::sqrt(2.0);
  const TrackerParams p;
  for (double t_go : {2.0, 5.0, 10.0, 20.0, 60.0, 300.0}) {
    const double w = terminal_omega_floor_radps(omega0, t_go, p.terminal_settling, p.terminal_omega_max_factor);
    EXPECT_LE(w, 3.0 * omega0 * (1.0 + 1e-12)) << t_go;
    if (w < 3.0 * omega0) {
      EXPECT_LE(1.0 / (zeta * w), t_go) << t_go;
    }
  }
  EXPECT_LT(terminal_omega_floor_radps(omega0, 60.0, p.terminal_settling, p.terminal_omega_max_factor), omega0);
  EXPECT_DOUBLE_EQ(terminal_omega_floor_radps(omega0, 0.0, p.terminal_settling, p.terminal_omega_max_factor),
                   3.0 * omega0);
}

// ------------------------------------------------------------------ closed-loop error response
// The truth plant: a point in (E, D, D' = dD/dE, V) flown in time with E' = -D V, D-dot = D' E',
// D'-dot = D'' E' where D'' = a + b u + d_t / E'^2 (3.10; d_t: a disturbance that is constant in
// the time domain) and V-dot = -D (level flight, (2.48) with gamma = 0). The loop is run every
// dt_cycle with u held, its E-dot and E-dotdot from the chain rule of the plant state
// ((3.16)-(3.18) derived here, not the tracker's expression). The reference is a quadratic in E.
struct Plant {
  double energy, drag, drag_prime, speed;
};

struct Reference {
  double e0, d0, k1, k2;  // D_ref = d0 + k1 x + k2 x^2, x = e0 - E
  double drag(double e) const { return d0 + k1 * (e0 - e) + k2 * (e0 - e) * (e0 - e); }
  double prime(double e) const { return -(k1 + 2.0 * k2 * (e0 - e)); }
  double second() const { return 2.0 * k2; }
};

struct LoopRun {
  double max_error_deviation = 0.0;  // largest |e(t) - e_closed(t)| over the run
  double final_error = 0.0;
  double final_integral = 0.0;
};

constexpr double kB = -3e-12;       // b of (3.10) [per (m/s^2)]: the vertical L/D's effect on D''
constexpr double kLodRef = 0.8;     // reference vertical L/D u_ref = L/D cos(sigma_ref) ...
constexpr double kSigmaRef = 0.9;   // ... at this reference bank

Plant plant_rate(const Plant& y, double u, double a, double disturbance_t) {
  const double e_dot = -y.drag * y.speed;
  const double d2 = a + kB * u + disturbance_t / (e_dot * e_dot);
  return {e_dot, y.drag_prime * e_dot, d2 * e_dot, -y.drag};
}

Plant advance(const Plant& y, const Plant& k, double h) {
  return {y.energy + h * k.energy, y.drag + h * k.drag, y.drag_prime + h * k.drag_prime, y.speed + h * k.speed};
}

// Flies the loop for t_end seconds; closed(t) is the expected error response.
template <class Closed>
LoopRun fly_loop(const TrackerGains& gains, double omega, double e0_mps2, double disturbance_t, double t_end,
                 Closed closed) {
  const Reference ref{3.0e7, 10.0, 2e-7, 5e-15};
  TrackerParams params;
  DragLoop loop;
  loop.init(gains, params);
  const double u_ref = kLodRef * std::cos(kSigmaRef);
  const double a = ref.second() - kB * u_ref;  // the plant flies the reference at u = u_ref
  Plant y{ref.e0, ref.drag(ref.e0) + e0_mps2, ref.prime(ref.e0), 7000.0};
  const double dt = 0.01;
  LoopRun run;
  const int n = static_cast<int>(std::lround(t_end / dt));
  for (int i = 0; i <= n; ++i) {
    const double t = i * dt;
    const double error = y.drag - ref.drag(y.energy);
    run.max_error_deviation = std::fmax(run.max_error_deviation, std::fabs(error - closed(t)));
    run.final_error = error;
    run.final_integral = loop.integral();
    DragLoopInput in;
    in.ref.drag = ref.drag(y.energy);
    in.ref.drag_prime = ref.prime(y.energy);
    in.ref.drag_second = ref.second();
    in.ref.b = kB;
    in.ref.lod = kLodRef;
    in.ref.sigma = kSigmaRef;
    in.drag_mps2 = y.drag;
    in.drag_prime = y.drag_prime;
    in.b = kB;
    in.e_dot = -y.drag * y.speed;
    const double d_dot = y.drag_prime * in.e_dot, v_dot = -y.drag;
    in.e_ddot = -(d_dot * y.speed + y.drag * v_dot);  // d/dt (-D V)
    in.omega_radps = omega;
    in.lift_over_drag = 100.0;  // never saturated
    const DragLoopCommand c = loop.command(in);
    loop.update_integral(c, false, in.ref.drag, dt);
    // RK4 over the cycle, u held.
    const Plant k1 = plant_rate(y, c.u_drag, a, disturbance_t);
    const Plant k2 = plant_rate(advance(y, k1, 0.5 * dt), c.u_drag, a, disturbance_t);
    const Plant k3 = plant_rate(advance(y, k2, 0.5 * dt), c.u_drag, a, disturbance_t);
    const Plant k4 = plant_rate(advance(y, k3, dt), c.u_drag, a, disturbance_t);
    y = {y.energy + dt / 6.0 * (k1.energy + 2.0 * k2.energy + 2.0 * k3.energy + k4.energy),
         y.drag + dt / 6.0 * (k1.drag + 2.0 * k2.drag + 2.0 * k3.drag + k4.drag),
         y.drag_prime + dt / 6.0 * (k1.drag_prime + 2.0 * k2.drag_prime + 2.0 * k3.drag_prime + k4.drag_prime),
         y.speed + dt / 6.0 * (k1.speed + 2.0 * k2.speed + 2.0 * k3.speed + k4.speed)};
  }
  return run;
}

// Solution of J''' + A J'' + B J' + C J = 0 (C > 0, one real root and a complex pair) from
// J(0), J'(0), J''(0): the roots by bisection and synthetic division, the modal amplitudes by
// Cramer's rule. Returns J'(t).
struct ThirdOrder {
  double r = 0.0, alpha = 0.0, beta = 0.0, c1 = 0.0, c2 = 0.0, c3 = 0.0;
  ThirdOrder(double A, double B, double C, double j0, double j1, double j2) {
    auto f = [&](double s) { return ((s + A) * s + B) * s + C; };
    double lo = -A - 1.0, hi = 0.0;  // f(lo) < 0 < f(0) = C
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (f(mid) < 0.0 ? lo : hi) = mid;
    }
    r = 0.5 * (lo + hi);
    const double p = A + r, q = B + r * p;  // s^3 + A s^2 + B s + C = (s - r)(s^2 + p s + q)
    alpha = -0.5 * p;
    beta = std::sqrt(q - 0.25 * p * p);
    // Rows: J(0), J'(0), J''(0) of c1 e^{rt} + e^{alpha t}(c2 cos + c3 sin).
    const double m[3][3] = {{1.0, 1.0, 0.0}, {r, alpha, beta}, {r * r, alpha * alpha - beta * beta, 2.0 * alpha * beta}};
    const double rhs[3] = {j0, j1, j2};
    auto det = [](const double a[3][3]) {
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double d = det(m);
    double c[3];
    for (int col = 0; col < 3; ++col) {
      double mc[3][3];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) mc[i][j] = j == col ? rhs[i] : m[i][j];
      }
      c[col] = det(mc) / d;
    }
    c1 = c[0];
    c2 = c[1];
    c3 = c[2];
  }
  double derivative(double t) const {
    const double ea = std::exp(alpha * t), cb = std::cos(beta * t), sb = std::sin(beta * t);
    return r * c1 * std::exp(r * t) + ea * ((alpha * c2 + beta * c3) * cb + (alpha * c3 - beta * c2) * sb);
  }
  double value(double t) const {
    return c1 * std::exp(r * t) + std::exp(alpha * t) * (c2 * std::cos(beta * t) + c3 * std::sin(beta * t));
  }
};

TEST(DragLoop, ProportionalDerivativeLoopGivesTheClosedFormSecondOrderResponse) {
  // Without the integral, (3.12) with the energy-domain gains of (3.14)-(3.15) makes the drag
  // error a second-order system in time: e(t) = e0 exp(-zeta w t) (cos(w_d t) +
  // zeta w / w_d sin(w_d t)), w_d = w sqrt(1 - zeta^2), from e(0) = e0, e'(0) = 0.
  const double omega = 2.0 * std::sqrt(kG0_mps2 / 7050.0), zeta = 1.0 / std::sqrt(2.0);
  const double e0 = 0.5;
  const double wd = omega * std::sqrt(1.0 - zeta * zeta);
  auto closed = [&](double t) {
    return e0 * std::exp(-zeta * omega * t) * (std::cos(wd * t) + zeta * omega / wd * std::sin(wd * t));
  };
  const LoopRun run = fly_loop(TrackerGains{zeta, omega, 0.0}, omega, e0, 0.0, 150.0, closed);
  EXPECT_LT(run.max_error_deviation, 1e-3 * e0);
  // The response undershoots by exp(-pi zeta / sqrt(1 - zeta^2)) = 4.3 % (no resonance): seen.
  EXPECT_NEAR(closed(M_PI / wd), -e0 * std::exp(-M_PI * zeta / std::sqrt(1.0 - zeta * zeta)), 1e-12);
  // Another damping and frequency: the same closed form.
  const double zeta2 = 0.4, omega2 = 0.12, wd2 = omega2 * std::sqrt(1.0 - zeta2 * zeta2);
  auto closed2 = [&](double t) {
    return e0 * std::exp(-zeta2 * omega2 * t) * (std::cos(wd2 * t) + zeta2 * omega2 / wd2 * std::sin(wd2 * t));
  };
  EXPECT_LT(fly_loop(TrackerGains{zeta2, omega2, 0.0}, omega2, e0, 0.0, 150.0, closed2).max_error_deviation, 1e-3 * e0);
}

TEST(DragLoop, IntegralTermRemovesAConstantDisturbanceAlongTheThirdOrderResponse) {
  // With the integral, e'' + 2 zeta w e' + w^2 e + k_I int e dt = d_t in time. With
  // J = int e dt - d_t / k_I: J''' + 2 zeta w J'' + w^2 J' + k_I J = 0, J(0) = -d_t / k_I,
  // J'(0) = e0, J''(0) = 0, solved in closed form; e = J'. The steady error a proportional-
  // derivative loop would keep, d_t / w^2, is removed, and the integral settles at d_t / k_I.
  const TrackerGains gains = derive_gains(TrackerParams{});
  const double w = gains.omega0_radps, zeta = gains.zeta, k_i = gains.k_integral;
  const double e0 = 0.5, disturbance = 0.05 * 10.0 * w * w;  // a steady PD error of 5 % of D_ref
  const ThirdOrder j(2.0 * zeta * w, w * w, k_i, -disturbance / k_i, e0, 0.0);
  const double t_end = 400.0;
  const LoopRun run = fly_loop(gains, w, e0, disturbance, t_end, [&](double t) { return j.derivative(t); });
  EXPECT_LT(run.max_error_deviation, 2e-3 * e0);
  EXPECT_NEAR(run.final_integral, j.value(t_end) + disturbance / k_i, 2e-3 * disturbance / k_i);
  // The steady PD error would be d_t / w^2 = 0.5 m/s^2; the integral has removed most of it
  // (the slow real root, about -k_I / w^2, leaves exp(r t_end) of it).
  EXPECT_LT(std::fabs(run.final_error), 0.25 * disturbance / (w * w));
  // The same plant with the PD loop alone keeps the steady error (closed form of the
  // second-order step response to d_t).
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  auto pd = [&](double t) {
    const double ss = disturbance / (w * w);
    return ss + (e0 - ss) * std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
  };
  const LoopRun pd_run = fly_loop(TrackerGains{zeta, w, 0.0}, w, e0, disturbance, t_end, pd);
  EXPECT_LT(pd_run.max_error_deviation, 2e-3 * e0);
  EXPECT_NEAR(pd_run.final_error, disturbance / (w * w), 1e-3);
}

// ------------------------------------------------------------------ anti-windup
// The rule (drag_loop.hpp, docs): the integral term k_I int e dt of (3.12) acts as a drag bias
// of k_I int e dt / omega0^2 (the proportional term's w^2 e at q >= q_ref); that bias is bounded
// to integral_bias_max_fraction (0.2) of the reference drag, and the integral is frozen in
// reversals and while saturated in its own direction.
double drag_bias_mps2(const DragLoop& loop) {
  const TrackerGains& g = loop.gains();
  return g.k_integral * loop.integral() / (g.omega0_radps * g.omega0_radps);
}

DragLoopCommand error_of(double error_mps2, bool saturated) {
  DragLoopCommand c;
  c.error = error_mps2;
  c.saturated = saturated;
  return c;
}

TEST(DragLoop, AntiWindupBoundsTheIntegralBiasToAFifthOfTheReferenceDrag) {
  DragLoop loop;
  loop.init(derive_gains(TrackerParams{}), TrackerParams{});
  const double drag_ref = 10.0, dt = 0.1;
  // A persistent 1 m/s^2 error for 1000 s: unbounded, the bias would reach
  // k_I 1000 / w0^2 = w0 1000 / 20 = 3.7 m/s^2; it stops at 0.2 x 10 = 2 m/s^2.
  for (int i = 0; i < 10000; ++i) loop.update_integral(error_of(1.0, false), false, drag_ref, dt);
  EXPECT_NEAR(drag_bias_mps2(loop), 0.2 * drag_ref, 1e-12 * drag_ref);
  // At the bound, the first cycle of opposite error moves it straight back (nothing wound up).
  const double at_bound = loop.integral();
  loop.update_integral(error_of(-1.0, false), false, drag_ref, dt);
  EXPECT_NEAR(loop.integral(), at_bound - 0.1, 1e-12 * at_bound);
  // The other sign, and a bound that follows the reference drag down.
  for (int i = 0; i < 20000; ++i) loop.update_integral(error_of(-1.0, false), false, drag_ref, dt);
  EXPECT_NEAR(drag_bias_mps2(loop), -0.2 * drag_ref, 1e-12 * drag_ref);
  loop.update_integral(error_of(0.0, false), false, 0.5 * drag_ref, dt);
  EXPECT_NEAR(drag_bias_mps2(loop), -0.1 * drag_ref, 1e-12 * drag_ref);
  // Another fraction.
  TrackerParams p;
  p.integral_bias_max_fraction = 0.05;
  DragLoop tight;
  tight.init(derive_gains(p), p);
  for (int i = 0; i < 10000; ++i) tight.update_integral(error_of(1.0, false), false, drag_ref, dt);
  EXPECT_NEAR(drag_bias_mps2(tight), 0.05 * drag_ref, 1e-12 * drag_ref);
  tight.reset();
  EXPECT_EQ(tight.integral(), 0.0);
}

TEST(DragLoop, IntegralIsFrozenInReversalsAndWhileSaturatedInItsOwnDirection) {
  DragLoop loop;
  loop.init(derive_gains(TrackerParams{}), TrackerParams{});
  const double drag_ref = 10.0, dt = 0.1;
  loop.update_integral(error_of(0.5, false), false, drag_ref, dt);  // rectangle rule: e dt
  EXPECT_DOUBLE_EQ(loop.integral(), 0.05);
  loop.update_integral(error_of(0.5, false), true, drag_ref, dt);   // reversing: frozen
  EXPECT_DOUBLE_EQ(loop.integral(), 0.05);
  loop.update_integral(error_of(0.5, true), false, drag_ref, dt);   // saturated, same direction: frozen
  EXPECT_DOUBLE_EQ(loop.integral(), 0.05);
  loop.update_integral(error_of(-0.2, true), false, drag_ref, dt);  // saturated, unwinding: integrates
  EXPECT_DOUBLE_EQ(loop.integral(), 0.05 - 0.02);
  loop.update_integral(error_of(-0.2, true), true, drag_ref, dt);   // reversing beats everything
  EXPECT_DOUBLE_EQ(loop.integral(), 0.03);
}

TEST(DragLoop, CommandIsTheReferenceBankWhenOnTheReferenceAndFlagsSaturation) {
  // On the reference (no error, no error rate, no integral) (3.10) gives back u_ref =
  // (L/D) cos(sigma_ref); a command beyond the available L/D is flagged saturated.
  DragLoop loop;
  loop.init(derive_gains(TrackerParams{}), TrackerParams{});
  DragLoopInput in;
  in.ref.drag = 12.0;
  in.ref.drag_prime = -3e-7;
  in.ref.drag_second = 1e-14;
  in.ref.lod = 1.1;
  in.ref.sigma = 1.0;
  in.drag_mps2 = 12.0;
  in.drag_prime = -3e-7;
  in.b = kB;
  in.e_dot = -12.0 * 6000.0;
  in.e_ddot = 100.0;
  in.omega_radps = 0.07;
  in.lift_over_drag = 1.1;
  DragLoopCommand c = loop.command(in);
  EXPECT_NEAR(c.u_drag, 1.1 * std::cos(1.0), 1e-12);
  EXPECT_EQ(c.error, 0.0);
  EXPECT_FALSE(c.saturated);
  // 1 m/s^2 too much drag: u shifts by -w^2 e / (E'^2 b) (3.12 with 3.15 into 3.10): lift up.
  in.drag_mps2 = 13.0;
  c = loop.command(in);
  const double du = -(0.07 * 0.07 / (in.e_dot * in.e_dot)) * 1.0 / kB;
  EXPECT_NEAR(c.u_drag, 1.1 * std::cos(1.0) + du, 1e-9 * std::fabs(du));
  EXPECT_EQ(c.saturated, std::fabs(c.u_drag) > 1.1);
  EXPECT_GT(c.u_drag, 1.1 * std::cos(1.0));
}

}  // namespace
}  // namespace reentry::fsw
