// The truth models of one run at one instant: environment (shape, gravity, atmosphere with its
// dispersion, wind) and vehicle (aerodynamics with trim, mass, heating), and the translational
// dynamics (2.23)-(2.31) they drive, for a given state and attitude.
//
// One implementation, two users: the Simulator integrates it in double (the referee), and the
// trajectory optimizer (tools/optimal) differentiates it with Eigen AutoDiff scalars, so the
// optimal trajectories it finds obey exactly the physics the referee judges. Built only by
// Simulator::create (which resolves the mission, its [sim] section and a dispersion draw);
// read through Simulator::point_model().
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <optional>

#include "environment/atmosphere.hpp"
#include "environment/earth.hpp"
#include "environment/gravity.hpp"
#include "environment/scalar.hpp"
#include "environment/wind.hpp"
#include "vehicle/aerodynamics.hpp"
#include "vehicle/heating.hpp"

namespace reentry::truth {

/// Everything computed from (t, r_I, v_I, alpha, sigma) in one evaluation.
template <class T>
struct PointOutputs {
  scalar::Vec3<T> accel_I = scalar::Vec3<T>::Zero();  // total (gravity + aerodynamic), inertial
  scalar::Vec3<T> aero_I = scalar::Vec3<T>::Zero();   // aerodynamic (what an IMU senses)
  T h_m = T(0.0), r_m = T(0.0), lat = T(0.0), lon = T(0.0);
  T V = T(0.0), gamma = T(0.0), chi = T(0.0), airspeed = T(0.0), mach = T(0.0);
  T rho = T(0.0), q = T(0.0), qdot = T(0.0), n_g = T(0.0), D = T(0.0), L = T(0.0), E = T(0.0);
  T alpha = T(0.0), sigma = T(0.0), flap = T(0.0), elevon = T(0.0);
};

class PointModel {
 public:
  ShapeModel shape = ShapeModel::kSphere;
  std::optional<Gravity> gravity;
  std::optional<Atmosphere> atmosphere;
  std::optional<Wind> wind;  // empty: no wind
  std::optional<Aerodynamics> aero;
  double mass_kg = 0.0, area_m2 = 0.0, nose_radius_m = 0.0;
  config::HeatingModel heating = config::HeatingModel::kChapmanStagnation;  // vehicle.heating_model
  double cl_scale = 1.0, cd_scale = 1.0;
  bool trim = false;

  /// Dynamics and outputs at time t (the R-frame has turned by omega t) for the inertial state
  /// (r_I, v_I) and the attitude (alpha, sigma). `full` adds the Earth-relative V, gamma, chi,
  /// the energy (7.8), latitude/longitude and the load factor (3.7).
  template <class T>
  PointOutputs<T> evaluate(const T& t, const scalar::Vec3<T>& r_I, const scalar::Vec3<T>& v_I, const T& alpha,
                           const T& sigma, bool full) const {
    const auto tables = [this](const T& a, const T& m, const T& q) {
      return aero->coefficients(a, m, q, trim, cl_scale, cd_scale);
    };
    return evaluate_with(tables, t, r_I, v_I, alpha, sigma, full);
  }

  /// evaluate() with the aerodynamic coefficients from `aero_at(alpha, mach, q)` (returning
  /// AeroCoefficientsT<T>, scales included) instead of this model's tables; everything else is
  /// this model. The trajectory optimizer passes its C2 fits of these very tables
  /// (tools/optimizer/smooth_models.hpp); the simulator always flies the tables.
  template <class T, class AeroAt>
  PointOutputs<T> evaluate_with(const AeroAt& aero_at, const T& t, const scalar::Vec3<T>& r_I,
                                const scalar::Vec3<T>& v_I, const T& alpha, const T& sigma, bool full) const;

  /// Energy (7.8) with the Earth-relative speed, E = |v_I - omega x r_I|^2 / 2 - mu / r + mu / R_eq:
  /// the TAEM event's variable.
  template <class T>
  static T specific_energy(const scalar::Vec3<T>& r_I, const scalar::Vec3<T>& v_I) {
    const scalar::Vec3<T> omega(T(0.0), T(0.0), T(EarthConstants::kOmega_radps));
    const scalar::Vec3<T> v_rel_I = v_I - omega.cross(r_I);
    const T r = r_I.norm();
    const double mu = EarthConstants::kMu_m3ps2;
    return 0.5 * v_rel_I.squaredNorm() - mu / r + mu / EarthConstants::kEquatorialRadius_m;
  }

  /// Altitude above the configured shape of an inertial position at time t.
  template <class T>
  T altitude(const T& t, const scalar::Vec3<T>& r_I) const {
    return altitude_m(scalar::Vec3<T>(rotation_I_to_R(t) * r_I), shape);
  }
};

template <class T, class AeroAt>
PointOutputs<T> PointModel::evaluate_with(const AeroAt& aero_at, const T& t, const scalar::Vec3<T>& r_I,
                                          const scalar::Vec3<T>& v_I, const T& alpha, const T& sigma, bool full) const {
  using Vec3 = scalar::Vec3<T>;
  using Mat3 = scalar::Mat3<T>;
  using std::atan2;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Vec3 omega_vec(T(0.0), T(0.0), T(EarthConstants::kOmega_radps));
  PointOutputs<T> d;
  const Mat3 C_RI = rotation_I_to_R(t);
  const Mat3 C_IR = C_RI.transpose();
  const Vec3 r_R = C_RI * r_I;
  const Vec3 v_rel_I = v_I - omega_vec.cross(r_I);  // Earth-relative velocity, I components

  d.r_m = r_I.norm();
  d.h_m = altitude_m(r_R, shape);
  const Vec3 up_I = r_I / d.r_m;  // -Z of the V-frame (geocentric vertical)
  Vec3 air_I = v_rel_I;
  const bool need_v_frame = full || wind;
  Mat3 C_VR = Mat3::Identity();
  if (need_v_frame) {
    d.lat = geocentric_latitude_rad(r_R);
    d.lon = longitude_rad(r_R);
    C_VR = dcm_R_to_V(d.lon, d.lat);
  }
  const auto atm = atmosphere->at(d.h_m);
  d.rho = atm.density_kgpm3;
  if (wind) {
    const Vec3 wind_V(wind->velocity_V(d.h_m));  // north, east, down
    air_I -= C_IR * (C_VR.transpose() * wind_V);  // V_A = V_G - V_wind (2.29)
  }
  d.airspeed = air_I.norm();
  d.mach = scalar::value(atm.speed_of_sound_mps) > 0.0 ? T(d.airspeed / atm.speed_of_sound_mps) : T(0.0);
  d.q = 0.5 * d.rho * d.airspeed * d.airspeed;
  d.alpha = alpha;
  d.sigma = sigma;

  const auto c = aero_at(d.alpha, d.mach, d.q);
  d.flap = c.flap_rad;
  d.elevon = c.elevon_rad;
  const T lift_N = d.q * area_m2 * c.cl;  // (2.21)
  const T drag_N = d.q * area_m2 * c.cd;
  d.L = lift_N / mass_kg;
  d.D = drag_N / mass_kg;

  // Aerodynamic force in the airspeed frames (2.27)/(2.29), assembled directly in I: drag along
  // -V_A; lift normal to V_A, in the vertical plane through V_A for sigma = 0 (upward), rotated
  // by sigma about V_A, positive sigma towards the right of V_A (+Y of the trajectory frame).
  // Side-slip is zero.
  d.aero_I = Vec3::Zero();
  if (scalar::value(d.airspeed) > 0.0) {
    const Vec3 u = air_I / d.airspeed;
    Vec3 lift_up = up_I - up_I.dot(u) * u;  // -Z of the trajectory frame
    const T n = lift_up.norm();
    if (scalar::value(n) > 1e-12) {
      lift_up /= n;
    } else {  // vertical flight: bank reference undefined, use the Earth's polar axis
      lift_up = C_IR * Vec3(T(0.0), T(0.0), T(1.0));
      lift_up = (lift_up - lift_up.dot(u) * u).normalized();
    }
    const Vec3 right = u.cross(lift_up);  // +Y of the trajectory frame
    d.aero_I = -d.D * u + d.L * (cos(d.sigma) * lift_up + sin(d.sigma) * right);
  }
  const Vec3 g_I = C_IR * Vec3(gravity->acceleration_R(r_R));  // (2.28)
  d.accel_I = g_I + d.aero_I;                                  // (2.25)
  d.qdot = heat_flux_Wpm2(heating, d.rho, d.airspeed, d.alpha, nose_radius_m);  // (3.5) or Betts

  if (full) {
    const Vec3 v_V = C_VR * (C_RI * v_rel_I);  // north, east, down
    d.V = v_V.norm();
    d.gamma = atan2(-v_V.z(), scalar::hypot(v_V.x(), v_V.y()));
    d.chi = atan2(v_V.y(), v_V.x());
    const double mu = EarthConstants::kMu_m3ps2;
    d.E = 0.5 * d.V * d.V - mu / d.r_m + mu / EarthConstants::kEquatorialRadius_m;  // (7.8)
    d.n_g = body_normal_load_factor(lift_N, drag_N, d.alpha, mass_kg);              // (3.7)
  }
  return d;
}

}  // namespace reentry::truth
