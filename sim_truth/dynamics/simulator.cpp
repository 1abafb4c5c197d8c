#include "dynamics/simulator.hpp"

#include "reentry/config/environment_files.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "environment/atmosphere.hpp"
#include "environment/earth.hpp"
#include "environment/gravity.hpp"
#include "environment/wind.hpp"
#include "numerics/root_finding.hpp"
#include "physics/angles.hpp"
#include "numerics/runge_kutta.hpp"
#include "vehicle/aerodynamics.hpp"
#include "vehicle/heating.hpp"

namespace reentry::truth {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSkipOutMargin_m = 10000.0;

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

const Vec3 kOmegaVec(0.0, 0.0, EarthConstants::kOmega_radps);

bool equals(const std::string& a, const char* b) { return a == b; }
}  // namespace

const char* to_string(SimEvent e) {
  switch (e) {
    case SimEvent::kNone: return "none";
    case SimEvent::kTaemEnergy: return "taem_energy";
    case SimEvent::kGroundImpact: return "ground_impact";
    case SimEvent::kSkipOut: return "skip_out";
    case SimEvent::kTimeOut: return "time_out";
    case SimEvent::kFailure: return "failure";
  }
  return "unknown";
}

bool parse_gravity(const std::string& s, GravityChoice* out) {
  if (equals(s, "central")) *out = GravityChoice::kCentral;
  else if (equals(s, "j2j4")) *out = GravityChoice::kJ2J4;
  else if (equals(s, "sh20")) *out = GravityChoice::kSphericalHarmonics20;
  else return false;
  return true;
}
bool parse_atmosphere(const std::string& s, AtmosphereChoice* out) {
  if (equals(s, "us76")) *out = AtmosphereChoice::kUS76;
  else if (equals(s, "exponential")) *out = AtmosphereChoice::kExponential;
  else return false;
  return true;
}
bool parse_shape(const std::string& s, ShapeChoice* out) {
  if (equals(s, "sphere")) *out = ShapeChoice::kSphere;
  else if (equals(s, "oblate")) *out = ShapeChoice::kOblate;
  else return false;
  return true;
}
bool parse_integrator(const std::string& s, IntegratorChoice* out) {
  if (equals(s, "rkf56")) *out = IntegratorChoice::kRkf56;
  else if (equals(s, "rkf78")) *out = IntegratorChoice::kRkf78;
  else return false;
  return true;
}
bool parse_attitude(const std::string& s, AttitudeChoice* out) {
  if (equals(s, "ideal")) *out = AttitudeChoice::kIdeal;
  else if (equals(s, "lag")) *out = AttitudeChoice::kLag;
  else return false;
  return true;
}

// ---------------------------------------------------------------------------------------------
// The point model (environment, vehicle, dynamics at one instant) and the integrator settings.
struct Simulator::Models : PointModel {
  numerics::RkfMethod method = numerics::RkfMethod::kRkf56;
  numerics::RkfTolerances<kStates> tol{};
};

// Achieved attitude of one command segment: ideal (instant), or a first-order lag with time
// constant tau whose rate is limited to rate_max (0: unlimited). Solved in closed form, so the
// attitude adds no states and the integrator can stop exactly where the rate limit ends.
struct Simulator::Attitude {
  struct Channel {
    double x0 = 0.0, cmd = 0.0, tau = 0.0, rate_max = 0.0;
    bool ideal = true;
    double value(double dt) const {
      const double e0 = cmd - x0;
      if (ideal || e0 == 0.0) return cmd;
      const double s = e0 > 0.0 ? 1.0 : -1.0;
      const double a = std::fabs(e0);
      if (tau <= 0.0) {
        if (rate_max <= 0.0) return cmd;
        return dt * rate_max >= a ? cmd : x0 + s * rate_max * dt;
      }
      if (rate_max > 0.0 && a > rate_max * tau) {
        const double t_ramp = (a - rate_max * tau) / rate_max;  // rate-limited part
        if (dt <= t_ramp) return x0 + s * rate_max * dt;
        return cmd - s * rate_max * tau * std::exp(-(dt - t_ramp) / tau);
      }
      return cmd - e0 * std::exp(-dt / tau);
    }
    // End of the rate-limited ramp (a kink in the attitude history), or +inf.
    double breakpoint() const {
      const double a = std::fabs(cmd - x0);
      if (ideal || a == 0.0 || rate_max <= 0.0) return kInf;
      if (tau <= 0.0) return a / rate_max;
      if (a > rate_max * tau) return (a - rate_max * tau) / rate_max;
      return kInf;
    }
  };
  double t0 = 0.0;
  Channel alpha, sigma;
};

Simulator::Simulator() = default;
Simulator::~Simulator() = default;

std::unique_ptr<Simulator> Simulator::create(const config::Mission& mission, const SimOverrides& ov,
                                             std::string* error) {
  std::unique_ptr<Simulator> sim(new Simulator());
  sim->mission_ = mission;
  // The overridden integration settings are the mission's for this run: the loader's rules
  // (config::check_mission) judge the mission as flown, so both accept the same missions.
  config::SimParams& cfg = sim->mission_.sim;
  if (ov.rel_tol > 0.0) cfg.rel_tol = ov.rel_tol;
  if (ov.abs_tol_position_m > 0.0) cfg.abs_tol_position_m = ov.abs_tol_position_m;
  if (ov.abs_tol_velocity_mps > 0.0) cfg.abs_tol_velocity_mps = ov.abs_tol_velocity_mps;
  if (ov.time_limit_s > 0.0) cfg.time_limit_s = ov.time_limit_s;
  std::string err = config::check_mission(sim->mission_);
  if (err.empty()) err = sim->resolve_settings(ov);
  if (err.empty()) err = sim->build_models(ov);
  if (err.empty()) err = sim->set_entry_state(ov.dispersion);
  if (!err.empty()) {
    if (error) *error = err;
    return nullptr;
  }
  return sim;
}

std::string Simulator::resolve_settings(const SimOverrides& ov) {
  const config::SimParams& cfg = mission_.sim;
  const config::Mission& mission = mission_;
  ResolvedSimSettings& st = settings_;
  st.dispersion = ov.dispersion;
  GravityChoice g = ov.gravity;
  if (g == GravityChoice::kFromConfig && !parse_gravity(cfg.gravity, &g))
    return "unknown sim.gravity '" + cfg.gravity + "' (central, j2j4, sh20)";
  AtmosphereChoice a = ov.atmosphere;
  if (a == AtmosphereChoice::kFromConfig && !parse_atmosphere(cfg.atmosphere, &a))
    return "unknown sim.atmosphere '" + cfg.atmosphere + "' (us76, exponential)";
  ShapeChoice sh = ov.shape;
  if (sh == ShapeChoice::kFromConfig && !parse_shape(cfg.shape, &sh))
    return "unknown sim.shape '" + cfg.shape + "' (sphere, oblate)";
  IntegratorChoice in = ov.integrator;
  if (in == IntegratorChoice::kFromConfig && !parse_integrator(cfg.integrator, &in))
    return "unknown sim.integrator '" + cfg.integrator + "' (rkf56, rkf78)";
  AttitudeChoice at = ov.attitude;
  if (at == AttitudeChoice::kFromConfig && !parse_attitude(cfg.attitude, &at))
    return "unknown sim.attitude '" + cfg.attitude + "' (ideal, lag)";
  const bool wind_on = ov.wind == WindChoice::kFromConfig ? cfg.wind : ov.wind == WindChoice::kOn;

  st.gravity = g == GravityChoice::kCentral ? "central" : g == GravityChoice::kJ2J4 ? "j2j4" : "sh20";
  st.atmosphere = a == AtmosphereChoice::kUS76 ? "us76" : "exponential";
  st.shape = sh == ShapeChoice::kSphere ? "sphere" : "oblate";
  st.integrator = in == IntegratorChoice::kRkf56 ? "rkf56" : "rkf78";
  st.attitude = at == AttitudeChoice::kIdeal ? "ideal" : "lag";
  st.wind = wind_on;
  st.rel_tol = cfg.rel_tol;
  st.abs_tol_position_m = cfg.abs_tol_position_m;
  st.abs_tol_velocity_mps = cfg.abs_tol_velocity_mps;
  st.abs_tol_heat_Jpm2 = 1.0;
  st.time_limit_s = cfg.time_limit_s;
  st.attitude_time_constant_s = cfg.attitude_time_constant_s;
  st.alpha_rate_max_radps = mission.constraints.alpha_rate_max_radps;
  st.sigma_rate_max_radps = mission.constraints.sigma_rate_max_radps;
  if (!(st.rel_tol > 0.0) || !(st.abs_tol_position_m > 0.0) || !(st.abs_tol_velocity_mps > 0.0))
    return "integration tolerances must be positive";
  if (!(st.time_limit_s > 0.0)) return "sim.time_limit_s must be positive";

  return {};
}

std::string Simulator::build_models(const SimOverrides& ov) {
  const config::SimParams& cfg = mission_.sim;
  const config::Mission& mission = mission_;
  ResolvedSimSettings& st = settings_;
  const DispersionDraw& disp = ov.dispersion;
  models_ = std::make_unique<Models>();
  attitude_ = std::make_unique<Attitude>();
  Models& m = *models_;
  const bool wind_on = st.wind;
  std::string err;
  m.shape = st.shape == "sphere" ? ShapeModel::kSphere : ShapeModel::kOblate;
  const GravityModel gm = st.gravity == "central" ? GravityModel::kCentral
                          : st.gravity == "j2j4"  ? GravityModel::kJ2J4
                                                  : GravityModel::kSphericalHarmonics;
  m.gravity = Gravity::create(gm, mission.environment.gravity_coefficients, config::kGravityFileDegree, &err);
  if (!m.gravity) return "gravity: " + err;
  const AtmosphereModel am = st.atmosphere == "us76" ? AtmosphereModel::kUS76 : AtmosphereModel::kExponential;
  m.atmosphere = Atmosphere::create(am, mission.environment.us76_table, &err);
  if (!m.atmosphere) return "atmosphere: " + err;
  if (disp.dispersed)
    m.atmosphere->set_density_dispersion(disp.density_scale, disp.density_perturbation, disp.density_correlation_m,
                                         disp.density_seed);
  if (wind_on) {
    m.wind = Wind::create(mission.environment.wind_profile, &err);
    if (!m.wind) return "wind: " + err;
    m.wind->set_scale(disp.wind_scale);
  }
  m.aero = Aerodynamics::create(mission.vehicle.aero, &err);
  if (!m.aero) return "aerodynamics: " + err;
  st.trim = (ov.trim < 0 ? cfg.trim : ov.trim == 1) && !mission.vehicle.aero.cm.empty();
  m.trim = st.trim;
  m.cl_scale = disp.cl_scale;
  m.cd_scale = disp.cd_scale;
  m.mass_kg = mission.vehicle.mass_kg * disp.mass_scale;
  m.area_m2 = mission.vehicle.reference_area_m2;
  m.nose_radius_m = mission.vehicle.nose_radius_m;
  m.heating = mission.vehicle.heating_model;
  st.mass_kg = m.mass_kg;
  if (!(m.mass_kg > 0.0) || !(m.area_m2 > 0.0) || !(m.nose_radius_m > 0.0))
    return "vehicle mass, reference area and nose radius must be positive";

  m.method = st.integrator == "rkf56" ? numerics::RkfMethod::kRkf56 : numerics::RkfMethod::kRkf78;
  for (int i = 0; i < kStates; ++i) m.tol.rel[i] = st.rel_tol;
  for (int i = 0; i < 3; ++i) {
    m.tol.abs[i] = st.abs_tol_position_m;
    m.tol.abs[3 + i] = st.abs_tol_velocity_mps;
  }
  m.tol.abs[6] = st.abs_tol_heat_Jpm2;

  return {};
}

std::string Simulator::set_entry_state(const DispersionDraw& disp) {
  const config::Mission& mission = mission_;
  Models& m = *models_;
  ResolvedSimSettings& st = settings_;
  // Spherical, Earth-relative -> inertial Cartesian (I = R at t = 0).
  const config::SphericalState& e = mission.entry;
  const double lat = e.latitude_rad + disp.entry_latitude_rad;
  const double lon = e.longitude_rad + disp.entry_longitude_rad;
  const double V = e.velocity_mps + disp.entry_velocity_mps;
  const double gam = e.flight_path_rad + disp.entry_flight_path_rad;
  const double chi = e.heading_rad + disp.entry_heading_rad;
  if (!(e.altitude_m > 0.0) || !(V > 0.0) || std::fabs(lat) >= 0.5 * M_PI)
    return "entry state invalid (altitude and velocity must be positive, |latitude| < 90 deg)";
  const Vec3 u_r(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  double r = EarthConstants::kEquatorialRadius_m + e.altitude_m;
  for (int it = 0; it < 20; ++it) {  // radius whose altitude above the chosen shape is h_entry
    const double dh = e.altitude_m - altitude_m(Vec3(r * u_r), m.shape);
    r += dh;
    if (std::fabs(dh) < 1e-9) break;
  }
  const Vec3 r_R = r * u_r;
  const Mat3 C_VR = dcm_R_to_V(lon, lat);
  const Vec3 v_V(V * std::cos(gam) * std::cos(chi), V * std::cos(gam) * std::sin(chi), -V * std::sin(gam));
  const Vec3 v_R = C_VR.transpose() * v_V;
  const Vec3 v_I = v_R + kOmegaVec.cross(r_R);  // (transport theorem at t = 0)
  for (int i = 0; i < 3; ++i) {
    y_[i] = r_R[i];
    y_[3 + i] = v_I[i];
  }
  y_[6] = 0.0;
  t_s_ = 0.0;

  const double mu = EarthConstants::kMu_m3ps2, Re = EarthConstants::kEquatorialRadius_m;
  // Energy of the TAEM state itself: its speed at its altitude above the chosen shape over the
  // aim point (with Re + h instead, the oblate Earth put the X-38's zero-error TAEM state 6.4 km
  // lower, 80 m/s faster and above its q limit).
  const double r_taem = radius_at_altitude_m(mission.taem.latitude_rad, mission.taem.altitude_m, m.shape);
  st.E_taem_Jpkg = 0.5 * mission.taem.velocity_mps * mission.taem.velocity_mps - mu / r_taem + mu / Re;
  st.skip_out_altitude_m = e.altitude_m + kSkipOutMargin_m;
  E_entry_Jpkg_ = 0.5 * V * V - mu / r + mu / Re;

  // Hold the entry attitude of the mission's alpha profile until the first command.
  const double alpha0 = mission.alpha_profile.y.empty() ? 0.0 : mission.alpha_profile.y.back();
  Attitude& att = *attitude_;
  att.alpha.x0 = att.alpha.cmd = alpha0;
  att.sigma.x0 = att.sigma.cmd = 0.0;
  start_segment();

  // An entry state already beyond an event ends the run at once.
  const auto g0 = event_functions(0.0, y_);
  if (g0[0] <= 0.0) event_ = SimEvent::kTaemEnergy;
  else if (g0[1] <= 0.0) event_ = SimEvent::kGroundImpact;
  update_maxima(sample());
  return {};
}

void Simulator::start_segment() {
  Attitude& a = *attitude_;
  const bool ideal = settings_.attitude == "ideal";
  double alpha_now = a.alpha.cmd, sigma_now = a.sigma.cmd;
  if (!ideal) attitude_at(t_s_, &alpha_now, &sigma_now);
  a.t0 = t_s_;
  a.alpha.x0 = alpha_now;
  a.sigma.x0 = physics::wrap_pi(sigma_now);
  a.alpha.ideal = a.sigma.ideal = ideal;
  a.alpha.tau = a.sigma.tau = settings_.attitude_time_constant_s;
  a.alpha.rate_max = settings_.alpha_rate_max_radps;
  a.sigma.rate_max = settings_.sigma_rate_max_radps;
}

void Simulator::set_command(double alpha_rad, double sigma_rad) {
  start_segment();  // freeze the achieved attitude at the current time
  attitude_->alpha.cmd = alpha_rad;
  // The bank rolls the shorter way round: the command moved by whole turns to within pi of
  // the bank now (the flight software's filter makes the same choice on its smaller steps).
  attitude_->sigma.cmd = physics::unwrap_near(sigma_rad, attitude_->sigma.x0);
}

void Simulator::attitude_at(double t, double* alpha_rad, double* sigma_rad) const {
  const double dt = std::max(0.0, t - attitude_->t0);
  *alpha_rad = attitude_->alpha.value(dt);
  *sigma_rad = physics::wrap_pi(attitude_->sigma.value(dt));
}

double Simulator::next_attitude_breakpoint(double after_t) const {
  double best = kInf;
  for (double b : {attitude_->alpha.breakpoint(), attitude_->sigma.breakpoint()}) {
    const double tb = attitude_->t0 + b;
    if (tb > after_t && tb < best) best = tb;
  }
  return best;
}

PointOutputs<double> Simulator::evaluate(double t, const State& y, bool full) const {
  double alpha = 0.0, sigma = 0.0;
  attitude_at(t, &alpha, &sigma);
  return models_->evaluate(t, Vec3(y[0], y[1], y[2]), Vec3(y[3], y[4], y[5]), alpha, sigma, full);
}

const PointModel& Simulator::point_model() const { return *models_; }

void Simulator::derivatives(double t, const State& y, State& dydt) const {
  ++evaluations_;
  const PointOutputs<double> d = evaluate(t, y, false);
  dydt[0] = y[3];  // (2.26)
  dydt[1] = y[4];
  dydt[2] = y[5];
  dydt[3] = d.accel_I.x();  // (2.25)
  dydt[4] = d.accel_I.y();
  dydt[5] = d.accel_I.z();
  dydt[6] = d.qdot;  // heat load Q = integral of qdot dt
}

std::array<double, 4> Simulator::event_functions(double t, const State& y) const {
  const Vec3 r_I(y[0], y[1], y[2]);
  const double E = PointModel::specific_energy<double>(r_I, Vec3(y[3], y[4], y[5]));
  const double h = models_->altitude(t, r_I);
  return {E - settings_.E_taem_Jpkg, h, settings_.skip_out_altitude_m - h, settings_.time_limit_s - t};
}

int Simulator::earliest_event(double h, const std::array<double, 4>& g_new, double* tau_fired, State* y_fired) const {
  const numerics::EmbeddedRungeKutta<kStates> rk(models_->method);
  auto f = [this](double t, const State& y, State& dydt) { derivatives(t, y, dydt); };
  const Models& m = *models_;
  int fired = -1;
  // Re-integration from the last accepted state over tau in (0, h]: one step of length tau,
  // which is shorter than the accepted step (split further only if the error test fails).
  const double t0 = t_s_;
  const State y0 = y_;
  auto propagate = [&](double tau) {
    State y = y0;
    double done = 0.0, h_try = tau;
    for (int attempt = 0; attempt < 64 && done < tau; ++attempt) {
      const double h_use = std::min(h_try, tau - done);
      const auto sub = rk.step(f, t0 + done, y, h_use, m.tol);
      if (sub.accepted) {
        y = sub.y;
        done = (h_use == tau - done) ? tau : done + h_use;
      }
      h_try = sub.h_next;
    }
    return y;
  };
  for (int k = 0; k < 3; ++k) {  // 0: TAEM energy, 1: ground, 2: skip-out
    if (g_new[k] > 0.0) continue;
    auto g_of_tau = [&](double tau) { return event_functions(t0 + tau, propagate(tau))[k]; };
    const double x_tol = 1e-10 * std::max(1.0, std::fabs(t0));
    const auto root = numerics::brent(g_of_tau, 0.0, h, x_tol, 100);
    const double tau = root.status == numerics::NumStatus::kOk ? root.x : h;
    if (tau < *tau_fired) {
      *tau_fired = tau;
      fired = k;
      *y_fired = propagate(tau);
    }
  }
  return fired;
}

SimEvent Simulator::advance_to(double t_target) {
  if (event_ != SimEvent::kNone) return event_;
  const auto wall0 = std::chrono::steady_clock::now();
  const numerics::EmbeddedRungeKutta<kStates> rk(models_->method);
  auto f = [this](double t, const State& y, State& dydt) { derivatives(t, y, dydt); };
  const Models& m = *models_;
  const double t_end = std::min(t_target, settings_.time_limit_s);

  while (t_s_ < t_end && event_ == SimEvent::kNone) {
    const double t_stop = std::min(t_end, next_attitude_breakpoint(t_s_));
    double h = std::min(h_next_s_, t_stop - t_s_);
    bool lands = false;
    if (t_s_ + 1.01 * h >= t_stop) {  // never leave a sliver before a stop
      h = t_stop - t_s_;
      lands = true;
    }
    const auto step = rk.step(f, t_s_, y_, h, m.tol);
    if (!step.accepted) {
      ++rejected_;
      h_next_s_ = step.h_next;
      if (!(h_next_s_ > 1e-9 * std::max(1.0, std::fabs(t_s_)))) {
        event_ = SimEvent::kFailure;
        failure_ = "step size underflow at t = " + std::to_string(t_s_) + " s";
      }
      continue;
    }
    ++accepted_;
    const double t_new = lands ? t_stop : t_s_ + h;
    bool finite = true;
    for (double v : step.y) finite = finite && std::isfinite(v);
    if (!finite) {
      event_ = SimEvent::kFailure;
      failure_ = "non-finite state at t = " + std::to_string(t_new) + " s";
      break;
    }
    const auto g_new = event_functions(t_new, step.y);
    double tau_fired = kInf;
    State y_fired{};
    const int fired = earliest_event(h, g_new, &tau_fired, &y_fired);
    if (fired >= 0) {
      t_s_ = t_s_ + tau_fired;
      y_ = y_fired;
      event_ = fired == 0 ? SimEvent::kTaemEnergy : fired == 1 ? SimEvent::kGroundImpact : SimEvent::kSkipOut;
      update_maxima(sample());
      break;
    }
    t_s_ = t_new;
    y_ = step.y;
    if (!lands || step.h_next < h_next_s_) h_next_s_ = step.h_next;
    update_maxima(sample());
    if (t_s_ >= settings_.time_limit_s) event_ = SimEvent::kTimeOut;
  }
  wall_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return event_;
}

TruthSample Simulator::sample() const {
  const PointOutputs<double> d = evaluate(t_s_, y_, true);
  TruthSample s;
  s.t_s = t_s_;
  s.h_m = d.h_m;
  s.r_m = d.r_m;
  s.lat_rad = d.lat;
  s.lon_rad = d.lon;
  s.V_mps = d.V;
  s.gamma_rad = d.gamma;
  s.chi_rad = d.chi;
  s.airspeed_mps = d.airspeed;
  s.mach = d.mach;
  s.rho_kgpm3 = d.rho;
  s.q_Pa = d.q;
  s.qdot_Wpm2 = d.qdot;
  s.Q_Jpm2 = y_[6];
  s.n_g = d.n_g;
  s.D_mps2 = d.D;
  s.L_mps2 = d.L;
  s.E_Jpkg = d.E;
  s.alpha_rad = d.alpha;
  s.sigma_rad = d.sigma;
  s.flap_rad = d.flap;
  s.elevon_rad = d.elevon;
  s.q_alpha_Pa_rad = d.q * d.alpha;
  // Great circle to the aim point (geocentric latitudes on the R_eq sphere).
  const GreatCircleLeg to_aim = great_circle_leg(d.lat, d.lon, mission_.taem.latitude_rad, mission_.taem.longitude_rad);
  s.range_to_taem_m = to_aim.arc_rad * EarthConstants::kEquatorialRadius_m;
  s.heading_to_taem_rad = to_aim.initial_bearing_rad;
  return s;
}

NavSample Simulator::nav_sample() const {
  const PointOutputs<double> d = evaluate(t_s_, y_, false);
  NavSample n;
  n.t_s = t_s_;
  n.r_I_m = Vec3(y_[0], y_[1], y_[2]);
  n.v_I_mps = Vec3(y_[3], y_[4], y_[5]);
  n.aero_accel_I_mps2 = d.aero_I;
  n.earth_rotation_angle_rad = EarthConstants::kOmega_radps * t_s_;
  return n;
}

void Simulator::update_maxima(const TruthSample& s) {
  auto upd = [&](double v, double* max, double* t) {
    if (v > *max) {
      *max = v;
      *t = s.t_s;
    }
  };
  upd(s.qdot_Wpm2, &maxima_.qdot_Wpm2, &maxima_.qdot_t_s);
  upd(s.n_g, &maxima_.n_g, &maxima_.n_g_t_s);
  upd(s.q_Pa, &maxima_.q_Pa, &maxima_.q_t_s);
  upd(std::fabs(s.q_alpha_Pa_rad), &maxima_.q_alpha_Pa_rad, &maxima_.q_alpha_t_s);
}

RunSummary Simulator::summary() const {
  RunSummary r;
  r.event = event_;
  r.final_state = sample();
  r.maxima = maxima_;
  r.derivative_evaluations = evaluations_;
  r.steps_accepted = accepted_;
  r.steps_rejected = rejected_;
  r.wall_s = wall_s_;
  r.message = failure_;
  return r;
}

}  // namespace reentry::truth
