// Shared fixtures of the tracker tests: the X-33 plan, a tracker flying it mid-profile, states
// placed on the profile or around the TAEM aim point by independent spherical formulas, and an
// RK4 integration of the vertical motion as the independent truth for the pull-out predictors.
#pragma once

#include <memory>

#include "guidance/mission_adapter.hpp"
#include "models/onboard_models.hpp"
#include "reentry/config/mission.hpp"
#include "tracker/entry_tracker.hpp"

namespace reentry::fsw::test {

constexpr double kDeg = M_PI / 180.0;

/// The X-33 mission and its first plan from the entry state (planned once per process: the
/// planner is deterministic). nullptr when the mission does not load or plan.
struct X33Plan {
  config::Mission mission;
  ReferenceProfile profile;
};
const X33Plan* x33_plan();

/// The X-33 on-board models, default tracker parameters, and the level state, alpha and Mach of
/// point k of the plan.
struct X33Point {
  OnboardModels models;
  TrackerParams params;
  RelativeState state;
  double alpha_rad = 0.0, mach = 0.0;
};
std::unique_ptr<X33Point> x33_point(int k);
/// The same at the middle point of the plan.
std::unique_ptr<X33Point> x33_mid_plan();

/// Level flight at profile point k: its radius, speed, heading, energy, drag and lift.
RelativeState level_state_on_profile(const ReferenceProfile& p, int k);

/// A tracker flying mid-profile (captured, level) and the state it was given.
struct MidProfile {
  config::Mission mission;
  EntryTracker tracker;
  RelativeState state;
  const ReferenceProfile* profile = nullptr;
};
/// The X-33 tracker with the plan adopted, at the level state of profile point
/// profile_fraction (n_points - 1); nullptr when the mission does not load, plan or initialise.
std::unique_ptr<MidProfile> mid_profile_tracker(double profile_fraction);

/// A trackable synthetic plan (status ok) of n points evenly spaced in energy from e_first
/// down to e_last: drag(E) with its first two energy derivatives by central differences of
/// step de (exact for polynomials up to degree 2), the other arrays zero.
template <class Drag>
void synthetic_profile(ReferenceProfile& p, int n, double e_first, double e_last, Drag drag, double de = 1e3) {
  p = ReferenceProfile{};
  p.n_points = n;
  p.status = Status::kOk;
  p.converged = true;
  p.entry_energy_Jpkg = e_first;
  p.taem_energy_Jpkg = e_last;
  for (int k = 0; k < n; ++k) {
    const double e = e_first + (e_last - e_first) * k / (n - 1);
    p.energy_Jpkg[k] = e;
    p.drag_mps2[k] = drag(e);
    p.drag_prime[k] = (drag(e + de) - drag(e - de)) / (2.0 * de);
    p.drag_second[k] = (drag(e + de) - 2.0 * drag(e) + drag(e - de)) / (de * de);
  }
}

/// Time from profile point j to TAEM at its drag, the speed falling linearly to the TAEM speed
/// (E' = -D V), as the tracker estimates it.
double profile_time_to_go_s(const ReferenceProfile& p, int j);
/// Last profile point at least t_go_s before TAEM (by profile_time_to_go_s).
int profile_index_at_time_to_go(const ReferenceProfile& p, double t_go_s);
/// The plan's range to go from profile point k, S = -int dE / D (C.2), trapezoidal.
double profile_range_to_go_m(const ReferenceProfile& p, int k);

/// Places st at great-circle distance distance_m from the TAEM aim point, on the bearing (seen
/// from the aim point) offset_rad from the reversed arrival heading (spherical destination
/// formula); returns the azimuth from st to the aim point.
double place_from_aim_point(const config::TaemInterface& taem, double distance_m, double offset_rad, RelativeState& st);

/// RK4 (1 ms) of the vertical motion h'' = accel(t, h) from a sink rate h_dot0 at h = 0 until
/// h' = 0 after t_min; returns the lowest altitude (negative, below the start).
template <class Accel>
double rk4_pullout_bottom_m(Accel accel, double h_dot0, double t_min = 0.0) {
  double h = 0.0, v = h_dot0, t = 0.0;
  const double dt = 1e-3;
  for (int i = 0; i < 100000000 && (v < 0.0 || t < t_min); ++i) {
    const double k1h = v, k1v = accel(t, h);
    const double k2h = v + 0.5 * dt * k1v, k2v = accel(t + 0.5 * dt, h + 0.5 * dt * k1h);
    const double k3h = v + 0.5 * dt * k2v, k3v = accel(t + 0.5 * dt, h + 0.5 * dt * k2h);
    const double k4h = v + dt * k3v, k4v = accel(t + dt, h + dt * k3h);
    h += dt / 6.0 * (k1h + 2.0 * k2h + 2.0 * k3h + k4h);
    v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    t += dt;
    if (t >= t_min && v >= 0.0) break;
  }
  return h;
}

/// Mid-profile state below the reference: 0.8 of the planned drag at profile point k, the
/// planned L/D, sinking at gamma_rad.
RelativeState sinking_below_reference(const MidProfile& m, int k, double gamma_rad);
/// Heat-flux limit whose sensed drag bound, at 97 % of it, is drag_bound: the heat flux (3.5)
/// of the state at q = D / (C_D S/m) scales with sqrt(D).
double heat_limit_for_drag_bound(const OnboardModels& models, const RelativeState& s, double alpha_rad,
                                 double drag_bound_mps2);
/// Drag at the bottom of the pull-out from s, independently of the tracker's closed form:
/// RK4 of h'' = (L/D) D exp(-dh / H) cos(sigma(t)) - g_eff, sigma rolling from sigma0 to 0 at
/// sigma_rate (no filter lag); H the on-board scale height, g_eff gravity less the centrifugal
/// and Earth-rate terms (near circular speed the Earth-rate term is most of it).
double pullout_bottom_drag_mps2(const OnboardModels& models, const RelativeState& s, double sigma0_rad,
                                double sigma_rate_radps);

}  // namespace reentry::fsw::test
