// Drag loop of the tracker (thesis 3.10-3.18): second-order drag-error dynamics with integral,
//   e'' + c_E e' + k_E e + k_I int e dt = 0,   e = D - D_ref  (derivatives in energy),
// the time-domain damping and frequency converted to energy by (3.14)-(3.18) with E' = -D V,
// the natural frequency scheduled on dynamic pressure (3.13), and D'' = a + b u (3.10)
// solved for the vertical L/D command u = (L/D) cos(sigma).
#pragma once

#include "guidance_types.hpp"
#include "tracker/reference_track.hpp"
#include "tracker/tracker_params.hpp"

namespace reentry::fsw {

struct TrackerGains {
  double zeta = 0.7071067811865476;  // time-domain damping ratio of the drag loop
  double omega0_radps = 0.0;         // time-domain natural frequency at q = q_ref
  double k_integral = 0.0;           // time-domain integral gain [1/s^3]
};

/// The documented gain rule (no per-vehicle tuning):
///  - omega0 = gain_frequency_factor sqrt(g0 / H) (factor 2: twice the natural frequency of
///    the altitude mode of a glide in an atmosphere of scale height H = 7050 m, about
///    0.075 rad/s, period 85 s: fast enough to reject density errors, slow against the GNC
///    rate and the bank-rate limit);
///  - zeta = 1/sqrt(2) (no resonance peak, thesis §8.3);
///  - integral gain omega0^3 / gain_integral_pole_ratio (20: integral pole a decade below);
///  - scheduled by (3.13) with q_ref = q_ref_fraction of the plan's largest q.
/// Non-zero params.omega0_radps / k_integral_ps3 override the rule; params.zeta is used as is.
TrackerGains derive_gains(const TrackerParams& params);

/// omega(q) of (3.13): omega0 [2 (q/q_ref) - (q/q_ref)^2] below q_ref, omega0 above.
double scheduled_omega(double omega0, double q_Pa, double q_ref_Pa);

/// Lower bound on the drag loop's natural frequency in the terminal phase: settling / t_go,
/// so that the loop's time constant 1 / (zeta omega) stays within the time to go, at most
/// omega_max_factor omega0 (the bank-rate limit bounds what a faster loop can fly).
double terminal_omega_floor_radps(double omega0_radps, double t_go_s, double settling, double omega_max_factor);

/// What the loop needs of the present cycle.
struct DragLoopInput {
  RefPoint ref;                 // reference at the vehicle's energy (terminal-shaped, limited)
  double drag_mps2 = 0.0;       // sensed drag referred to the reference alpha
  double drag_prime = 0.0;      // dD/dE of the flown state (7.14)
  double b = 0.0;               // (7.20) at the flown state
  double e_dot = 0.0;           // E' = -D V
  double e_ddot = 0.0;          // (3.18)
  double omega_radps = 0.0;     // scheduled (3.13), terminal floor applied
  double lift_over_drag = 0.0;  // available L/D (sensed)
};

struct DragLoopCommand {
  double u_drag = 0.0;    // vertical L/D command, before the limits on it
  double error = 0.0;     // D - D_ref
  bool saturated = false; // |u| beyond the available L/D
};

class DragLoop {
 public:
  void init(const TrackerGains& gains, const TrackerParams& params) {
    gains_ = gains;
    integral_bias_max_fraction_ = params.integral_bias_max_fraction;
    reset();
  }
  void reset() { integral_ = 0.0; }
  /// (3.12) through (3.14)-(3.18) and (3.10).
  DragLoopCommand command(const DragLoopInput& in) const;
  /// int e dt with anti-windup: frozen in reversals and while saturated in the direction of
  /// the integral, bounded to a drag bias of integral_bias_max_fraction of the reference.
  void update_integral(const DragLoopCommand& c, bool reversing, double drag_ref_mps2, double dt_s);
  double integral() const { return integral_; }
  const TrackerGains& gains() const { return gains_; }

 private:
  TrackerGains gains_;
  double integral_bias_max_fraction_ = 0.2;
  double integral_ = 0.0;  // int (D - D_ref) dt
};

}  // namespace reentry::fsw
