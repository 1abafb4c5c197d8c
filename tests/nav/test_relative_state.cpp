// Navigation adapter (nav/relative_state.hpp) against independent truths: inertial states built
// here from a spherical state with independent formulas, (7.8) written out by hand, and the
// Earth's rotation seen from an Earth-fixed point.
#include <gtest/gtest.h>

#include <cmath>

#include "nav/relative_state.hpp"

namespace reentry::fsw {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kOmega = 7.292115e-5;

struct Inertial {
  double r[3], v[3], a[3];
};

// Independent construction: Earth-fixed position from (lat, lon, h), Earth-relative velocity
// from (V, gamma, chi) in local north/east/up, rotation by theta about Z to the inertial
// frame, plus omega x r; aerodynamic acceleration = drag along -v_rel + lift along a unit
// vector perpendicular to v_rel.
Inertial build(double lat, double lon, double h, double V, double gamma, double chi, double theta, double D,
               double L) {
  const double r = 6378137.0 + h;
  const double up[3] = {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
  const double east[3] = {-std::sin(lon), std::cos(lon), 0.0};
  const double north[3] = {-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat)};
  double pR[3], vR[3];
  for (int i = 0; i < 3; ++i) {
    pR[i] = r * up[i];
    vR[i] = V * (std::cos(gamma) * std::cos(chi) * north[i] + std::cos(gamma) * std::sin(chi) * east[i] +
                 std::sin(gamma) * up[i]);
  }
  const double c = std::cos(theta), s = std::sin(theta);
  Inertial x{};
  x.r[0] = c * pR[0] - s * pR[1];
  x.r[1] = s * pR[0] + c * pR[1];
  x.r[2] = pR[2];
  const double vrel[3] = {c * vR[0] - s * vR[1], s * vR[0] + c * vR[1], vR[2]};
  x.v[0] = vrel[0] - kOmega * x.r[1];
  x.v[1] = vrel[1] + kOmega * x.r[0];
  x.v[2] = vrel[2];
  // A unit vector perpendicular to v_rel: (v_rel x r) normalised.
  double p[3] = {vrel[1] * x.r[2] - vrel[2] * x.r[1], vrel[2] * x.r[0] - vrel[0] * x.r[2],
                 vrel[0] * x.r[1] - vrel[1] * x.r[0]};
  const double pn = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  for (int i = 0; i < 3; ++i) x.a[i] = -D * vrel[i] / V + L * p[i] / pn;
  return x;
}

TEST(Navigation, RecoversTheSphericalStateOfAnIndependentlyBuiltInertialState) {
  const double lat = -23.75 * kDeg, lon = -134.5 * kDeg, h = 75000.0, V = 6500.0;
  const double gamma = -1.3 * kDeg, chi = 49.59 * kDeg, theta = 0.37, D = 4.2, L = 3.1;
  const Inertial x = build(lat, lon, h, V, gamma, chi, theta, D, L);
  RelativeState s;
  ASSERT_EQ(relative_state_from_nav(812.5, x.r, x.v, x.a, theta, s), Status::kOk);
  EXPECT_NEAR(s.latitude_rad, lat, 1e-12);
  EXPECT_NEAR(s.longitude_rad, lon, 1e-12);
  EXPECT_NEAR(s.altitude_m, h, 1e-6);
  EXPECT_NEAR(s.velocity_mps, V, 1e-8);
  EXPECT_NEAR(s.flight_path_rad, gamma, 1e-12);
  EXPECT_NEAR(s.heading_rad, chi, 1e-12);
  EXPECT_NEAR(s.drag_mps2, D, 1e-12);
  EXPECT_NEAR(s.lift_mps2, L, 1e-12);
  // (7.8) by hand: V^2/2 - mu/r + mu/R.
  const double mu = 3.986004418e14, R = 6378137.0;
  EXPECT_NEAR(s.energy_Jpkg, 0.5 * V * V - mu / (R + h) + mu / R, 1e-6);
  EXPECT_DOUBLE_EQ(s.t_s, 812.5);
}

TEST(Navigation, RejectsNonFiniteAndDegenerateInput) {
  const Inertial x = build(0.1, 0.2, 50000.0, 5000.0, -0.01, 0.5, 0.0, 1.0, 1.0);
  RelativeState s;
  double bad[3] = {x.r[0], NAN, x.r[2]};
  EXPECT_EQ(relative_state_from_nav(0.0, bad, x.v, x.a, 0.0, s), Status::kNonFinite);
  double inf_a[3] = {INFINITY, 0.0, 0.0};
  EXPECT_EQ(relative_state_from_nav(0.0, x.r, x.v, inf_a, 0.0, s), Status::kNonFinite);
  const double zero[3] = {0.0, 0.0, 0.0};
  EXPECT_EQ(relative_state_from_nav(0.0, zero, x.v, x.a, 0.0, s), Status::kInvalidInput);
}

TEST(Navigation, EarthRotationIsRemovedFromTheInertialVelocity) {
  // At the equator on the inertial X axis (rotation angle 0), a vehicle whose inertial velocity
  // is v_I due +Y (east) moves over the ground at v_I - omega r (the surface of the rotating
  // Earth under it moves east at omega r, 472 m/s at 100 km): heading 90 deg, level.
  const double r = 6378137.0 + 100000.0, v_inertial = 7500.0;
  const double r_I[3] = {r, 0.0, 0.0}, v_I[3] = {0.0, v_inertial, 0.0}, a_I[3] = {0.0, 0.0, 0.0};
  RelativeState s;
  ASSERT_EQ(relative_state_from_nav(0.0, r_I, v_I, a_I, 0.0, s), Status::kOk);
  EXPECT_NEAR(s.velocity_mps, v_inertial - kOmega * r, 1e-9);
  EXPECT_NEAR(kOmega * r, 472.4, 0.1);
  EXPECT_NEAR(s.heading_rad, 0.5 * M_PI, 1e-12);
  EXPECT_NEAR(s.flight_path_rad, 0.0, 1e-12);
  EXPECT_NEAR(s.latitude_rad, 0.0, 1e-12);
  EXPECT_NEAR(s.longitude_rad, 0.0, 1e-12);
  // A point at rest on the rotating Earth has no Earth-relative speed: refused, not a NaN heading.
  const double v_fixed[3] = {0.0, kOmega * r, 0.0};
  EXPECT_EQ(relative_state_from_nav(0.0, r_I, v_fixed, a_I, 0.0, s), Status::kInvalidInput);
}

TEST(Navigation, SensedAccelerationSplitsIntoDragAlongAndLiftAcrossTheRelativeVelocity) {
  // The same sensed acceleration rotated about the relative velocity keeps drag and lift;
  // an acceleration along +v_rel (thrust) reads as negative drag, and its lift is zero.
  const double lat = 0.4, lon = -2.0, h = 60000.0, V = 5000.0, gamma = -0.05, chi = 1.1, theta = 1.3;
  for (double L : {0.0, 2.0, 7.5}) {
    const Inertial x = build(lat, lon, h, V, gamma, chi, theta, 3.0, L);
    RelativeState s;
    ASSERT_EQ(relative_state_from_nav(10.0, x.r, x.v, x.a, theta, s), Status::kOk);
    EXPECT_NEAR(s.drag_mps2, 3.0, 1e-12) << L;
    EXPECT_NEAR(s.lift_mps2, L, 1e-7) << L;
  }
  const Inertial thrust = build(lat, lon, h, V, gamma, chi, theta, -1.5, 0.0);
  RelativeState s;
  ASSERT_EQ(relative_state_from_nav(10.0, thrust.r, thrust.v, thrust.a, theta, s), Status::kOk);
  EXPECT_NEAR(s.drag_mps2, -1.5, 1e-12);
  EXPECT_NEAR(s.lift_mps2, 0.0, 1e-6);
}

}  // namespace
}  // namespace reentry::fsw
