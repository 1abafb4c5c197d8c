// Truth dynamics checked against independent references: a separate integration of the
// spherical rotating-frame equations (2.32)-(2.37), Kepler invariants, the equilibrium glide,
// the bank-angle sign convention, event location and seeded dispersions.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <utility>
#include <vector>

#include "dynamics/dispersions.hpp"
#include "dynamics/open_loop.hpp"
#include "dynamics/simulator.hpp"
#include "environment/earth.hpp"
#include "environment/wind.hpp"
#include "physics/angles.hpp"
#include "test_mission.hpp"

using namespace reentry;
using namespace reentry::truth;
using truth_test::kDeg;

namespace {

constexpr double kMu = EarthConstants::kMu_m3ps2;
constexpr double kOmega = EarthConstants::kOmega_radps;
constexpr double kRe = EarthConstants::kEquatorialRadius_m;

SimOverrides simple_models() {
  SimOverrides ov;
  ov.gravity = GravityChoice::kCentral;
  ov.atmosphere = AtmosphereChoice::kExponential;
  ov.wind = WindChoice::kOff;
  ov.shape = ShapeChoice::kSphere;
  ov.trim = 0;
  return ov;
}

std::unique_ptr<Simulator> make(const config::Mission& m, const SimOverrides& ov) {
  std::string err;
  auto sim = Simulator::create(m, ov, &err);
  EXPECT_NE(sim, nullptr) << err;
  return sim;
}

std::unique_ptr<Simulator> make_on_shape(const config::Mission& m, ShapeChoice shape) {
  SimOverrides ov = simple_models();
  ov.shape = shape;
  return make(m, ov);
}

// ---- independent reference: spherical equations (2.32)-(2.37), central gravity, no wind -------
// y = {r, tau (lon), delta (lat), V, gamma, chi}
using Sph = std::array<double, 6>;
struct SphericalModel {
  double mass_kg, area_m2, alpha_rad, sigma_rad;
  Sph rate(const Sph& y) const {
    const double r = y[0], dl = y[2], V = y[3], g = y[4], c = y[5];
    const double rho = 1.225 * std::exp(-(r - kRe) / 7050.0);  // exponential atmosphere (2.20)
    const double q = 0.5 * rho * V * V;
    const double D = q * area_m2 * truth_test::cd_of(alpha_rad) / mass_kg;
    const double L = q * area_m2 * truth_test::cl_of(alpha_rad) / mass_kg;
    const double gr = kMu / (r * r);
    const double w = kOmega;
    Sph d;
    d[0] = V * std::sin(g);                                                   // (2.35)
    d[1] = V * std::sin(c) * std::cos(g) / (r * std::cos(dl));                // (2.36)
    d[2] = V * std::cos(c) * std::cos(g) / r;                                 // (2.37)
    d[3] = -D - gr * std::sin(g) +
           w * w * r * std::cos(dl) * (std::sin(g) * std::cos(dl) - std::cos(g) * std::sin(dl) * std::cos(c));  // (2.32)
    d[4] = (L * std::cos(sigma_rad) - gr * std::cos(g) + 2.0 * w * V * std::cos(dl) * std::sin(c) +
            V * V / r * std::cos(g) +
            w * w * r * std::cos(dl) * (std::cos(dl) * std::cos(g) + std::sin(g) * std::sin(dl) * std::cos(c))) / V;  // (2.33)
    d[5] = (L * std::sin(sigma_rad) + 2.0 * w * V * (std::sin(dl) * std::cos(g) - std::cos(dl) * std::sin(g) * std::cos(c)) +
            V * V / r * std::cos(g) * std::cos(g) * std::tan(dl) * std::sin(c) +
            w * w * r * std::cos(dl) * std::sin(dl) * std::sin(c)) / (V * std::cos(g));  // (2.34)
    return d;
  }
};

Sph rk4(const SphericalModel& m, Sph y, double t_end, double dt) {
  const int n = static_cast<int>(std::ceil(t_end / dt));
  const double h = t_end / n;
  for (int i = 0; i < n; ++i) {
    auto add = [](const Sph& a, const Sph& b, double s) {
      Sph o;
      for (int k = 0; k < 6; ++k) o[k] = a[k] + s * b[k];
      return o;
    };
    const Sph k1 = m.rate(y), k2 = m.rate(add(y, k1, h / 2)), k3 = m.rate(add(y, k2, h / 2)), k4 = m.rate(add(y, k3, h));
    for (int k = 0; k < 6; ++k) y[k] += h / 6.0 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
  }
  return y;
}

// Spherical Earth-relative state at time t -> inertial position and velocity (own geometry).
void spherical_to_inertial(const Sph& y, double t, Eigen::Vector3d* r_I, Eigen::Vector3d* v_I) {
  const double r = y[0], lon = y[1], lat = y[2], V = y[3], g = y[4], c = y[5];
  const Eigen::Vector3d up(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  const Eigen::Vector3d north(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
  const Eigen::Vector3d east(-std::sin(lon), std::cos(lon), 0.0);
  const Eigen::Vector3d r_R = r * up;
  const Eigen::Vector3d v_R = V * std::cos(g) * (std::cos(c) * north + std::sin(c) * east) + V * std::sin(g) * up;
  const Eigen::Vector3d v_in_R = v_R + Eigen::Vector3d(0, 0, kOmega).cross(r_R);
  const double th = kOmega * t;
  Eigen::Matrix3d C_IR;
  C_IR << std::cos(th), -std::sin(th), 0, std::sin(th), std::cos(th), 0, 0, 0, 1;
  *r_I = C_IR * r_R;
  *v_I = C_IR * v_in_R;
}

}  // namespace

// Open-loop X-33 entry, alpha 40 deg, sigma 60 deg, 1500 s: the nominal entry (gamma -1.249 deg,
// a shallow skip with q below 300 Pa, 1500 s) and a steeper one (-2.5 deg, 600 s) that flies through q > 1 kPa.
class SphericalReference : public ::testing::TestWithParam<std::pair<double, double>> {};  // gamma_e deg, t_end s

TEST_P(SphericalReference, CartesianMatchesIndependentSphericalIntegration) {
  config::Mission m = truth_test::x33_test_mission();
  m.entry.flight_path_rad = GetParam().first * kDeg;
  SimOverrides ov = simple_models();
  ov.rel_tol = 1e-11;
  auto sim = make(m, ov);
  ASSERT_TRUE(sim);
  const double alpha = 40.0 * kDeg, sigma = 60.0 * kDeg, t_end = GetParam().second;
  sim->set_command(alpha, sigma);
  ASSERT_EQ(sim->advance_to(t_end), SimEvent::kNone) << to_string(sim->event()) << " at " << sim->time_s();

  const SphericalModel ref{m.vehicle.mass_kg, m.vehicle.reference_area_m2, alpha, sigma};
  Sph y0{kRe + m.entry.altitude_m, m.entry.longitude_rad, m.entry.latitude_rad,
         m.entry.velocity_mps,     m.entry.flight_path_rad, m.entry.heading_rad};
  const Sph y = rk4(ref, y0, t_end, 0.02);
  Eigen::Vector3d r_ref, v_ref;
  spherical_to_inertial(y, t_end, &r_ref, &v_ref);
  const NavSample nav = sim->nav_sample();
  const double dr = (nav.r_I_m - r_ref).norm(), dv = (nav.v_I_mps - v_ref).norm();
  const TruthSample s = sim->sample();
  const RunMaxima mx = sim->summary().maxima;
  std::printf("[ spherical ] gamma_e %.3f deg, t=%.0f s: h=%.1f km V=%.1f m/s, max q %.0f Pa: |dr| = %.3e m, |dv| = %.3e m/s\n",
              GetParam().first, t_end, s.h_m / 1e3, s.V_mps, mx.q_Pa, dr, dv);
  EXPECT_LT(dr, 50.0);
  EXPECT_LT(dv, 0.05);
  EXPECT_NEAR(s.V_mps, y[3], 0.05);
  EXPECT_NEAR(s.chi_rad, y[5], 1e-5);
  EXPECT_GT(mx.q_Pa, 200.0);  // the atmosphere shaped the trajectory
}

INSTANTIATE_TEST_SUITE_P(X33OpenLoop, SphericalReference,
                         ::testing::Values(std::make_pair(-1.249, 1500.0), std::make_pair(-2.5, 600.0)),
                         [](const ::testing::TestParamInfo<std::pair<double, double>>& i) {
                           return i.param.first > -2.0 ? std::string("nominal_entry") : std::string("steep_entry");
                         });

class KeplerOrbit : public ::testing::TestWithParam<IntegratorChoice> {};

TEST_P(KeplerOrbit, ConservesEnergyAndAngularMomentum) {
  config::Mission m = truth_test::x33_test_mission();
  m.entry.altitude_m = 2000e3;  // apoapsis; perigee near 1150 km: exponential density < 1e-70
  m.entry.latitude_rad = 10.0 * kDeg;
  m.entry.longitude_rad = 0.0;
  m.entry.flight_path_rad = 0.0;
  m.entry.heading_rad = 80.0 * kDeg;
  m.entry.velocity_mps = 6100.0;
  SimOverrides ov = simple_models();
  ov.rel_tol = 1e-13;  // the absolute tolerances dominate at 8000 km: tighten them too
  ov.abs_tol_position_m = 1e-6;
  ov.abs_tol_velocity_mps = 1e-9;
  ov.time_limit_s = 1e6;
  ov.integrator = GetParam();
  auto sim = make(m, ov);
  ASSERT_TRUE(sim);
  auto invariants = [&](double* energy, double* ang) {
    const NavSample n = sim->nav_sample();
    *energy = 0.5 * n.v_I_mps.squaredNorm() - kMu / n.r_I_m.norm();
    *ang = n.r_I_m.cross(n.v_I_mps).norm();
  };
  double e0, h0;
  invariants(&e0, &h0);
  const double a = -kMu / (2.0 * e0);
  const double period = 2.0 * M_PI * std::sqrt(a * a * a / kMu);
  sim->set_command(0.0, 0.0);
  double worst_e = 0.0, worst_h = 0.0;
  for (int k = 1; k <= 10; ++k) {
    ASSERT_EQ(sim->advance_to(k * period), SimEvent::kNone) << to_string(sim->event());
    double e, h;
    invariants(&e, &h);
    worst_e = std::max(worst_e, std::fabs(e / e0 - 1.0));
    worst_h = std::max(worst_h, std::fabs(h / h0 - 1.0));
  }
  std::printf("[ kepler %s ] 10 orbits (T = %.0f s): max |dE/E| = %.2e, max |dH/H| = %.2e, evaluations %lld\n", sim->settings().integrator.c_str(), period, worst_e,
              worst_h, static_cast<long long>(sim->summary().derivative_evaluations));
  EXPECT_LT(worst_e, 1e-9);
  EXPECT_LT(worst_h, 1e-9);
  // After whole periods the vehicle is back at apoapsis radius.
  EXPECT_NEAR(sim->sample().r_m, kRe + m.entry.altitude_m, 1.0);
}

INSTANTIATE_TEST_SUITE_P(Integrators, KeplerOrbit, ::testing::Values(IntegratorChoice::kRkf56, IntegratorChoice::kRkf78),
                         [](const ::testing::TestParamInfo<IntegratorChoice>& i) {
                           return std::string(i.param == IntegratorChoice::kRkf56 ? "rkf56" : "rkf78");
                         });

TEST(TruthDynamics, EquilibriumGlideBankKeepsFlightPathAngle) {
  // Bank of (6.15), sigma = acos(m (g - V^2/r) / L), extended with the Earth-rotation terms of
  // (2.33) because the truth model always rotates: vertical lift L cos(sigma) / m =
  // (g - V^2/r) cos(gamma) - 2 omega V cos(delta) sin(chi) - omega^2 r cos(delta) (cos(delta)
  // cos(gamma) + sin(gamma) sin(delta) cos(chi)). Recomputed every 0.1 s from the truth outputs.
  config::Mission m = truth_test::x33_test_mission();
  m.entry.altitude_m = 62e3;
  m.entry.longitude_rad = 0.0;
  m.entry.latitude_rad = 5.0 * kDeg;
  m.entry.velocity_mps = 6500.0;
  m.entry.flight_path_rad = -0.25 * kDeg;
  m.entry.heading_rad = 60.0 * kDeg;
  auto sim = make(m, simple_models());
  ASSERT_TRUE(sim);
  const double alpha = 40.0 * kDeg, gamma0 = m.entry.flight_path_rad;
  double worst = 0.0, max_ratio = 0.0;
  for (int k = 0; k < 3000; ++k) {
    sim->set_command(alpha, 0.0);  // lift needed at the current state, evaluated at sigma = 0
    const TruthSample s = sim->sample();
    const double g = kMu / (s.r_m * s.r_m), V = s.V_mps, r = s.r_m, dl = s.lat_rad, ga = s.gamma_rad, c = s.chi_rad;
    const double vertical = (g - V * V / r) * std::cos(ga) - 2.0 * kOmega * V * std::cos(dl) * std::sin(c) -
                            kOmega * kOmega * r * std::cos(dl) * (std::cos(dl) * std::cos(ga) + std::sin(ga) * std::sin(dl) * std::cos(c));
    const double ratio = vertical / s.L_mps2;
    max_ratio = std::max(max_ratio, ratio);
    ASSERT_LT(ratio, 1.0) << "equilibrium glide infeasible at t = " << s.t_s;
    sim->set_command(alpha, std::acos(ratio));  // (6.15)
    ASSERT_EQ(sim->advance_to(0.1 * (k + 1)), SimEvent::kNone);
    worst = std::max(worst, std::fabs(sim->sample().gamma_rad - gamma0));
  }
  const TruthSample f = sim->sample();
  std::printf("[ glide ] 300 s: max |gamma - gamma0| = %.4f deg, h %.1f -> %.1f km, V %.0f -> %.0f m/s, max cos(sigma) %.3f\n",
              worst / kDeg, m.entry.altitude_m / 1e3, f.h_m / 1e3, m.entry.velocity_mps, f.V_mps, max_ratio);
  EXPECT_LT(worst, 0.1 * kDeg);
}

TEST(TruthDynamics, PositiveBankTurnsHeadingClockwise) {
  config::Mission m = truth_test::x33_test_mission();
  m.entry.altitude_m = 60e3;
  m.entry.longitude_rad = 0.0;
  m.entry.latitude_rad = 0.0;
  m.entry.velocity_mps = 6000.0;
  m.entry.flight_path_rad = 0.0;
  m.entry.heading_rad = 0.0;  // flying north
  double chi[3];
  const double sigmas[3] = {-45.0 * kDeg, 0.0, 45.0 * kDeg};
  for (int i = 0; i < 3; ++i) {
    auto sim = make(m, simple_models());
    ASSERT_TRUE(sim);
    sim->set_command(40.0 * kDeg, sigmas[i]);
    ASSERT_EQ(sim->advance_to(20.0), SimEvent::kNone);
    chi[i] = sim->sample().chi_rad;
  }
  std::printf("[ bank ] chi after 20 s: sigma -45: %.3f deg, 0: %.3f deg, +45: %.3f deg\n", chi[0] / kDeg, chi[1] / kDeg,
              chi[2] / kDeg);
  EXPECT_GT(chi[2], 0.5 * kDeg);   // turned right (towards east)
  EXPECT_LT(chi[0], -0.5 * kDeg);  // turned left
  EXPECT_GT(chi[2], chi[1]);
  EXPECT_LT(chi[0], chi[1]);

  // sigma = 0: lift has a positive component along the local vertical and none sideways.
  auto sim = make(m, simple_models());
  sim->set_command(40.0 * kDeg, 0.0);
  const NavSample n = sim->nav_sample();
  const TruthSample s = sim->sample();
  const Eigen::Vector3d up = n.r_I_m.normalized();
  EXPECT_GT(n.aero_accel_I_mps2.dot(up), 0.9 * s.L_mps2);
}

TEST(TruthDynamics, AerodynamicForceFollowsTheAirspeedWithWind) {
  // Rebuild the airspeed vector from the navigation sample and the wind model with the test's own
  // frame geometry: drag must be exactly along -V_A and, at sigma = 0, there is no side force.
  config::Mission m = truth_test::x33_test_mission();
  m.entry.flight_path_rad = -2.0 * kDeg;
  SimOverrides ov = simple_models();
  ov.wind = WindChoice::kOn;
  auto sim = make(m, ov);
  ASSERT_TRUE(sim);
  std::string err;
  auto wind = Wind::create(m.environment.wind_profile, &err);
  ASSERT_TRUE(wind) << err;
  sim->set_command(40.0 * kDeg, 0.0);
  ASSERT_EQ(sim->advance_to(300.0), SimEvent::kNone);
  const NavSample n = sim->nav_sample();
  const TruthSample s = sim->sample();
  const double th = kOmega * n.t_s;
  Eigen::Matrix3d C_IR;
  C_IR << std::cos(th), -std::sin(th), 0, std::sin(th), std::cos(th), 0, 0, 0, 1;
  const Eigen::Vector3d r_R = C_IR.transpose() * n.r_I_m;
  const double lat = std::asin(r_R.z() / r_R.norm()), lon = std::atan2(r_R.y(), r_R.x());
  const Eigen::Vector3d up(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  const Eigen::Vector3d north(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
  const Eigen::Vector3d east(-std::sin(lon), std::cos(lon), 0.0);
  const Eigen::Vector3d w_V(wind->velocity_V(r_R.norm() - kRe));
  ASSERT_GT(w_V.norm(), 1.0) << "no wind at " << (r_R.norm() - kRe) / 1e3 << " km: test would not test anything";
  const Eigen::Vector3d w_I = C_IR * (w_V.x() * north + w_V.y() * east - w_V.z() * up);
  const Eigen::Vector3d v_air = n.v_I_mps - Eigen::Vector3d(0, 0, kOmega).cross(n.r_I_m) - w_I;
  const Eigen::Vector3d u = v_air.normalized();
  const Eigen::Vector3d side = u.cross(n.r_I_m).normalized();
  std::printf("[ wind ] h %.1f km, wind N %.2f E %.2f D %.2f m/s: a.u = %.9f, -D = %.9f, side %.2e m/s2\n", s.h_m / 1e3,
              w_V.x(), w_V.y(), w_V.z(), n.aero_accel_I_mps2.dot(u), -s.D_mps2, n.aero_accel_I_mps2.dot(side));
  EXPECT_NEAR(v_air.norm(), s.airspeed_mps, 1e-6);
  EXPECT_NEAR(n.aero_accel_I_mps2.dot(u), -s.D_mps2, 1e-9 * s.D_mps2);
  EXPECT_NEAR(n.aero_accel_I_mps2.dot(side), 0.0, 1e-9 * s.L_mps2);
  EXPECT_GT(std::fabs(s.airspeed_mps - s.V_mps), 0.1);  // the wind changed the airspeed
}

TEST(TruthDynamics, EntryStateIsReproducedOnBothShapes) {
  const config::Mission m = truth_test::x33_test_mission();
  for (ShapeChoice shape : {ShapeChoice::kSphere, ShapeChoice::kOblate}) {
    auto sim = make_on_shape(m, shape);
    ASSERT_TRUE(sim);
    const TruthSample s = sim->sample();
    EXPECT_NEAR(s.h_m, m.entry.altitude_m, 1e-6);
    EXPECT_NEAR(s.lat_rad, m.entry.latitude_rad, 1e-12);
    EXPECT_NEAR(std::remainder(s.lon_rad - m.entry.longitude_rad, 2.0 * M_PI), 0.0, 1e-12);
    EXPECT_NEAR(s.V_mps, m.entry.velocity_mps, 1e-9);
    EXPECT_NEAR(s.gamma_rad, m.entry.flight_path_rad, 1e-12);
    EXPECT_NEAR(s.chi_rad, m.entry.heading_rad, 1e-12);
    // Inertial speed = ground speed + Earth rotation (independent geometry).
    const NavSample n = sim->nav_sample();
    const double lat = m.entry.latitude_rad, chi = m.entry.heading_rad, ga = m.entry.flight_path_rad;
    const double v_east = m.entry.velocity_mps * std::cos(ga) * std::sin(chi) + kOmega * n.r_I_m.norm() * std::cos(lat);
    const double v_north = m.entry.velocity_mps * std::cos(ga) * std::cos(chi);
    const double v_up = m.entry.velocity_mps * std::sin(ga);
    EXPECT_NEAR(n.v_I_mps.norm(), std::sqrt(v_east * v_east + v_north * v_north + v_up * v_up), 1e-8);
  }
  // The oblate surface lies below the sphere away from the equator: larger entry radius on the sphere.
  SimOverrides a = simple_models(), b = simple_models();
  b.shape = ShapeChoice::kOblate;
  EXPECT_GT(make(m, a)->sample().r_m, make(m, b)->sample().r_m);
}

TEST(TruthDynamics, TaemEnergyIsTheEnergyOfTheTaemStateOnBothShapes) {
  // A vehicle placed exactly at the mission's TAEM state (its altitude above the shape over
  // the aim point, at its speed) has the TAEM energy: the event ends the run with zero
  // altitude error and the mission's own speed. Independent truth: the simulator's entry
  // placement (tested above) puts the state there and its sample gives the energy.
  config::Mission m = truth_test::x33_test_mission();
  m.taem.latitude_rad = 33.2 * kDeg;  // far from the equator: the shapes differ by 6.4 km here
  m.entry.altitude_m = m.taem.altitude_m;
  m.entry.latitude_rad = m.taem.latitude_rad;
  m.entry.longitude_rad = m.taem.longitude_rad;
  m.entry.velocity_mps = m.taem.velocity_mps;
  for (ShapeChoice shape : {ShapeChoice::kSphere, ShapeChoice::kOblate}) {
    auto sim = make_on_shape(m, shape);
    ASSERT_TRUE(sim);
    const TruthSample s = sim->sample();
    EXPECT_NEAR(s.h_m, m.taem.altitude_m, 1e-6);
    EXPECT_NEAR(s.E_Jpkg, sim->taem_energy_Jpkg(), 1e-9 * std::fabs(s.E_Jpkg)) << "shape " << static_cast<int>(shape);
  }
}

TEST(TruthDynamics, EventsAreLocatedPrecisely) {
  const config::Mission base = truth_test::x33_test_mission();
  {  // TAEM energy
    auto sim = make(base, simple_models());
    sim->set_command(40.0 * kDeg, 60.0 * kDeg);
    ASSERT_EQ(sim->advance_to(4000.0), SimEvent::kTaemEnergy);
    const double E = sim->sample().E_Jpkg, Et = sim->taem_energy_Jpkg();
    std::printf("[ events ] TAEM at t = %.3f s, h = %.2f km: |E - E_taem| / E_taem = %.2e\n", sim->time_s(),
                sim->sample().h_m / 1e3, std::fabs(E - Et) / Et);
    EXPECT_LT(std::fabs(E - Et) / Et, 1e-6);
  }
  {  // ground impact: TAEM energy below anything reachable
    config::Mission m = base;
    m.taem.velocity_mps = 0.0;
    m.taem.altitude_m = -1000e3;
    auto sim = make(m, simple_models());
    sim->set_command(40.0 * kDeg, 80.0 * kDeg);
    ASSERT_EQ(sim->advance_to(4000.0), SimEvent::kGroundImpact);
    EXPECT_LT(std::fabs(sim->sample().h_m), 1e-3);
  }
  {  // skip-out
    config::Mission m = base;
    m.entry.flight_path_rad = 3.0 * kDeg;
    auto sim = make(m, simple_models());
    sim->set_command(40.0 * kDeg, 0.0);
    ASSERT_EQ(sim->advance_to(4000.0), SimEvent::kSkipOut);
    const double h_skip = m.entry.altitude_m + 10e3;
    EXPECT_LT(std::fabs(sim->sample().h_m - h_skip) / h_skip, 1e-6);
  }
  {  // time-out exactly at the limit
    SimOverrides ov = simple_models();
    ov.time_limit_s = 123.45;
    auto sim = make(base, ov);
    sim->set_command(40.0 * kDeg, 0.0);
    ASSERT_EQ(sim->advance_to(500.0), SimEvent::kTimeOut);
    EXPECT_EQ(sim->time_s(), 123.45);
    EXPECT_EQ(sim->advance_to(600.0), SimEvent::kTimeOut);  // finished runs stay put
    EXPECT_EQ(sim->time_s(), 123.45);
  }
}

TEST(TruthDynamics, AttitudeLagRespectsRateLimitAndConverges) {
  const config::Mission m = truth_test::x33_test_mission();
  SimOverrides ov = simple_models();
  ov.attitude = AttitudeChoice::kLag;
  auto sim = make(m, ov);
  sim->set_command(30.0 * kDeg, 0.0);
  ASSERT_EQ(sim->advance_to(30.0), SimEvent::kNone);
  EXPECT_NEAR(sim->sample().alpha_rad, 30.0 * kDeg, 1e-6);
  sim->set_command(30.0 * kDeg, 60.0 * kDeg);
  double prev = sim->sample().sigma_rad;
  const double rate = m.constraints.sigma_rate_max_radps;
  for (int k = 1; k <= 300; ++k) {
    ASSERT_EQ(sim->advance_to(30.0 + 0.1 * k), SimEvent::kNone);
    const double now = sim->sample().sigma_rad;
    EXPECT_LE(now - prev, rate * 0.1 * (1 + 1e-12));
    EXPECT_GE(now - prev, 0.0);
    prev = now;
  }
  EXPECT_NEAR(prev, 60.0 * kDeg, 1e-6);  // 12 s of ramp + many time constants later
}

TEST(TruthDynamics, BankCommandAcrossPiRollsTheShorterWay) {
  // +170 deg -> -170 deg is a 20 deg roll through pi, not 340 deg through wings level: at the
  // rate limit the bank stays past 170 deg all the way, and the referee's wrapped rate holds.
  const config::Mission m = truth_test::x33_test_mission();
  SimOverrides ov = simple_models();
  ov.attitude = AttitudeChoice::kLag;
  auto sim = make(m, ov);
  sim->set_command(30.0 * kDeg, 170.0 * kDeg);
  ASSERT_EQ(sim->advance_to(80.0), SimEvent::kNone);
  ASSERT_NEAR(sim->sample().sigma_rad, 170.0 * kDeg, 1e-6);
  sim->set_command(30.0 * kDeg, -170.0 * kDeg);
  const double t0 = sim->time_s();
  double prev = sim->sample().sigma_rad;
  for (int k = 1; k <= 600; ++k) {
    ASSERT_EQ(sim->advance_to(t0 + 0.1 * k), SimEvent::kNone);
    const double now = sim->sample().sigma_rad;
    EXPECT_GE(std::fabs(now), 170.0 * kDeg - 1e-9) << "t " << 0.1 * k;
    EXPECT_LE(std::fabs(physics::wrap_pi(now - prev)), m.constraints.sigma_rate_max_radps * 0.1 * (1 + 1e-12));
    EXPECT_LE(std::fabs(now), M_PI);
    prev = now;
  }
  EXPECT_NEAR(prev, -170.0 * kDeg, 1e-6);  // 60 s: the 20 deg ramp and many time constants
}

TEST(Dispersions, MappingIsExplicitAndReproducible) {
  // The standard fixes mt19937_64: the 10000th output of a default-constructed engine.
  std::mt19937_64 ref;
  ref.discard(9999);
  ASSERT_EQ(ref(), 9981545732273789042ULL);
  const config::Dispersions w = truth_test::x33_test_mission().dispersions;
  const DispersionDraw d = draw_dispersions(w, 42);
  std::mt19937_64 e(42);
  const double u0 = static_cast<double>(e() >> 11) / 9007199254740992.0;
  EXPECT_EQ(d.entry_flight_path_rad, w.entry_flight_path_rad.value * (2.0 * u0 - 1.0));
  const DispersionDraw d2 = draw_dispersions(w, 42);
  EXPECT_EQ(d.cl_scale, d2.cl_scale);
  EXPECT_EQ(d.density_seed, d2.density_seed);
  EXPECT_LE(std::fabs(d.density_scale - 1.0), w.density_scale.value);
  EXPECT_LE(std::fabs(d.mass_scale - 1.0), w.mass_scale.value);
  EXPECT_GE(d.wind_scale, w.wind_scale_min);
  EXPECT_LE(d.wind_scale, w.wind_scale_max);
  // Over many seeds the draws fill the interval and stay inside it.
  double lo = 1.0, hi = -1.0;
  for (std::uint64_t s = 0; s < 2000; ++s) {
    const double x = draw_dispersions(w, s).cd_scale - 1.0;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  EXPECT_GE(lo, -w.cd_scale.value);
  EXPECT_LE(hi, w.cd_scale.value);
  EXPECT_LT(lo, -0.95 * w.cd_scale.value);
  EXPECT_GT(hi, 0.95 * w.cd_scale.value);
}

TEST(Dispersions, TruncatedNormalQuantilesMatchTheNormalTable) {
  // Independent truth: standard normal table values. Quantile u of N(0,1) truncated at +-3:
  // Phi(z) = Phi(-3) + u (Phi(3) - Phi(-3)), Phi(-3) = 0.0013498980, Phi(3) - Phi(-3) = 0.9973002039.
  EXPECT_EQ(truncated_standard_normal(0.5), 0.0);
  EXPECT_NEAR(truncated_standard_normal((0.8413447461 - 0.0013498980) / 0.9973002039), 1.0, 1e-8);   // Phi(1)
  EXPECT_NEAR(truncated_standard_normal((0.0227501319 - 0.0013498980) / 0.9973002039), -2.0, 1e-8);  // Phi(-2)
  EXPECT_NEAR(truncated_standard_normal(0.0), -3.0, 1e-9);
  EXPECT_NEAR(truncated_standard_normal(1.0 - 1e-16), 3.0, 1e-6);
  EXPECT_NEAR(truncated_standard_normal(0.3), -truncated_standard_normal(0.7), 1e-14);
}

TEST(Dispersions, GaussianSetIsThreeSigmaTruncatedAndShareTheUniformSetsQuantiles) {
  config::Dispersions uni = truth_test::x33_test_mission().dispersions;
  config::Dispersions gauss = uni;
  for (config::Dispersion* q : {&gauss.entry_flight_path_rad, &gauss.entry_heading_rad, &gauss.entry_velocity_mps,
                                &gauss.entry_position_rad, &gauss.density_scale, &gauss.cl_scale, &gauss.cd_scale,
                                &gauss.mass_scale}) {
    q->distribution = config::Distribution::kGaussian;
  }
  gauss.wind_scale_distribution = config::Distribution::kGaussian;
  constexpr int kSeeds = 20000;
  double sum = 0.0, sum2 = 0.0, inside_1sigma = 0.0, wind_sum = 0.0, max_abs = 0.0;
  const double w = gauss.cl_scale.value;  // 3 sigma
  for (std::uint64_t s = 0; s < kSeeds; ++s) {
    const DispersionDraw g = draw_dispersions(gauss, s);
    const DispersionDraw u = draw_dispersions(uni, s);
    const double x = g.cl_scale - 1.0;
    sum += x;
    sum2 += x * x;
    inside_1sigma += std::fabs(x) <= w / 3.0 ? 1.0 : 0.0;
    max_abs = std::max(max_abs, std::fabs(x));
    wind_sum += g.wind_scale;
    // Same engine output per quantity: the same sign (quantile above or below the median).
    EXPECT_EQ(x > 0.0, u.cl_scale - 1.0 > 0.0) << s;
    EXPECT_EQ(g.density_seed, u.density_seed) << s;
  }
  // Truncated at 3 sigma: sigma of the truncated normal is 0.98658 sigma; 68.27 % within 1 sigma
  // of the untruncated one becomes 68.45 %.
  const double mean = sum / kSeeds, sd = std::sqrt(sum2 / kSeeds - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * (w / 3.0) / std::sqrt(kSeeds));
  EXPECT_NEAR(sd / (w / 3.0), 0.98658, 0.015);
  EXPECT_NEAR(inside_1sigma / kSeeds, 0.6845, 0.01);
  EXPECT_LE(max_abs, w);
  EXPECT_GT(max_abs, 0.9 * w);  // the tail is reached
  EXPECT_NEAR(wind_sum / kSeeds, 0.5 * (gauss.wind_scale_min + gauss.wind_scale_max), 0.01);
}

TEST(Dispersions, SameSeedSameRunDifferentSeedDifferentRun) {
  const config::Mission m = truth_test::x33_test_mission();
  auto run = [&](std::uint64_t seed) {
    SimOverrides ov = simple_models();
    ov.dispersion = draw_dispersions(m.dispersions, seed);
    auto sim = make(m, ov);
    sim->set_command(40.0 * kDeg, 50.0 * kDeg);
    sim->advance_to(400.0);
    return sim->state();
  };
  const Simulator::State a = run(7), b = run(7), c = run(8);
  for (int i = 0; i < Simulator::kStates; ++i) EXPECT_EQ(a[i], b[i]) << "component " << i;
  double diff = 0.0;
  for (int i = 0; i < 3; ++i) diff += std::fabs(a[i] - c[i]);
  EXPECT_GT(diff, 100.0);
}

TEST(OpenLoop, ProfileCsvIsValidatedWithFileAndLine) {
  const std::string path = ::testing::TempDir() + "/truth_dyn_profile.csv";
  {
    std::ofstream f(path);
    f << "# test\nt_s,alpha_deg,sigma_deg\n0,40,0\n100,40,60\n50,40,x\n";
  }
  OpenLoopProfile p;
  std::string err;
  EXPECT_FALSE(load_open_loop_profile(path, &p, &err));
  EXPECT_NE(err.find(path + ":5"), std::string::npos) << err;
  {
    std::ofstream f(path);
    f << "E_norm,alpha_deg,sigma_deg\n1.0,40,10\n0.5,30,20\n0.1,20,30\n";
  }
  ASSERT_TRUE(load_open_loop_profile(path, &p, &err)) << err;
  EXPECT_EQ(p.variable, OpenLoopProfile::Variable::kEnergyNorm);
  double a, s;
  p.command_at(0.75, &a, &s);
  EXPECT_NEAR(a, 35.0 * kDeg, 1e-12);
  EXPECT_NEAR(s, 15.0 * kDeg, 1e-12);
}

TEST(OpenLoop, RunnerSamplesEveryOutputIntervalAndTheEvent) {
  const config::Mission m = truth_test::x33_test_mission();
  auto sim = make(m, simple_models());
  OpenLoopProfile p;
  p.variable = OpenLoopProfile::Variable::kEnergyNorm;
  p.x = {0.0, 1.0};
  p.alpha_rad = {30.0 * kDeg, 40.0 * kDeg};
  p.sigma_rad = {50.0 * kDeg, 75.0 * kDeg};
  std::vector<TruthSample> rows;
  const RunSummary r = run_open_loop(*sim, p, 2.5, [&](const TruthSample& s) { rows.push_back(s); });
  ASSERT_EQ(r.event, SimEvent::kTaemEnergy);
  ASSERT_GT(rows.size(), 100u);
  for (std::size_t k = 0; k + 1 < rows.size(); ++k) EXPECT_NEAR(rows[k].t_s, 2.5 * k, 1e-9);
  EXPECT_EQ(rows.back().t_s, r.final_state.t_s);
  // Commands follow E/E_entry (held over each 0.1 s tick): alpha within the profile's range.
  const TruthSample& mid = rows[rows.size() / 2];
  const double x = mid.E_Jpkg / sim->entry_energy_Jpkg();
  EXPECT_NEAR(mid.alpha_rad, (30.0 + 10.0 * x) * kDeg, 0.05 * kDeg);
}

TEST(OpenLoop, WingsLevelPulloutBoundsEveryBankedDescent) {
  // The wings-level pull-out stops at the bottom (first gamma >= 0) and its heat-flux, q and
  // load peaks are below those of the same descent flown with any constant bank: less
  // vertical lift takes the vehicle deeper before it levels off (the bound reentry_mc
  // --pullout-bound reports). A steeper entry raises the bound.
  const config::Mission m = truth_test::x33_test_mission();
  const double alpha = 40.0 * kDeg;
  auto level = make(m, simple_models());
  const RunMaxima bound = wings_level_pullout_maxima(*level, alpha);
  ASSERT_FALSE(level->finished());
  EXPECT_GE(level->sample().gamma_rad, 0.0);
  EXPECT_GT(bound.qdot_Wpm2, 0.0);
  for (double sigma_deg : {20.0, 45.0, 70.0}) {
    SCOPED_TRACE(sigma_deg);
    auto banked = make(m, simple_models());
    OpenLoopProfile p;
    p.x = {0.0};
    p.alpha_rad = {alpha};
    p.sigma_rad = {sigma_deg * kDeg};
    double qdot = 0.0, q = 0.0, n = 0.0;
    bool bottom = false;
    run_open_loop(*banked, p, 0.1, [&](const TruthSample& s) {
      if (bottom || s.t_s == 0.0) return;
      bottom = s.gamma_rad >= 0.0;
      qdot = std::max(qdot, s.qdot_Wpm2);
      q = std::max(q, s.q_Pa);
      n = std::max(n, s.n_g);
    });
    EXPECT_GT(qdot, bound.qdot_Wpm2);
    EXPECT_GT(q, bound.q_Pa);
    EXPECT_GT(n, bound.n_g);
  }
  config::Mission steep = m;
  steep.entry.flight_path_rad -= 0.3 * kDeg;
  auto deeper = make(steep, simple_models());
  EXPECT_GT(wings_level_pullout_maxima(*deeper, alpha).qdot_Wpm2, bound.qdot_Wpm2);
}

TEST(Performance, FullOpenLoopEntryReport) {
  // Reported, not asserted (timing belongs in benchmarks): a full open-loop entry (alpha 40 deg,
  // sigma 60 deg, 10 Hz command ticks) at rel tol 1e-10, with the simple models and with the
  // full ones (J2-J4, US76, oblate Earth, wind), on the X-33 mission file.
  config::LoadResult loaded = config::load_mission(std::string(REENTRY_CONFIG_DIR) + "/missions/x33.toml");
  ASSERT_TRUE(loaded.ok) << loaded.error;
  const config::Mission& m = loaded.mission;
  for (int full = 0; full < 2; ++full) {
    SimOverrides ov = simple_models();
    if (full) {
      ov.gravity = GravityChoice::kJ2J4;
      ov.atmosphere = AtmosphereChoice::kUS76;
      ov.shape = ShapeChoice::kOblate;
      ov.wind = WindChoice::kOn;
      ov.trim = -1;
    }
    ov.rel_tol = 1e-10;
    std::string err;
    auto sim = Simulator::create(m, ov, &err);
    ASSERT_TRUE(sim) << err;
    OpenLoopProfile p;
    p.x = {0.0};
    p.alpha_rad = {40.0 * kDeg};
    p.sigma_rad = {60.0 * kDeg};
    const RunSummary r = run_open_loop(*sim, p, 0.0, nullptr);
    std::printf("[ perf ] %s (%s, %s, %s, wind %d, trim %d): event %s at t = %.1f s, wall %.4f s, %lld derivative evaluations, "
                "%lld/%lld steps\n",
                "x33.toml", sim->settings().gravity.c_str(), sim->settings().atmosphere.c_str(),
                sim->settings().shape.c_str(), sim->settings().wind ? 1 : 0, sim->settings().trim ? 1 : 0, to_string(r.event),
                r.final_state.t_s, r.wall_s, static_cast<long long>(r.derivative_evaluations),
                static_cast<long long>(r.steps_accepted), static_cast<long long>(r.steps_rejected));
    EXPECT_NE(r.event, SimEvent::kFailure) << r.message;
  }
}
