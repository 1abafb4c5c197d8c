// Earth frames/shape and gravity models against analytic truths.
#include "environment/earth.hpp"
#include "environment/gravity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace rt = reentry::truth;
using rt::EarthConstants;

namespace {
const std::string kEgm96 = std::string(REENTRY_CONFIG_DIR) + "/environment/egm96_deg20.txt";

Eigen::Vector3d position(double lat_deg, double lon_deg, double radius_m) {
  const double lat = lat_deg * M_PI / 180.0, lon = lon_deg * M_PI / 180.0;
  return radius_m * Eigen::Vector3d(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
}

const std::vector<Eigen::Vector3d>& test_points() {
  static const std::vector<Eigen::Vector3d> pts = {
      position(0.0, 0.0, 6378137.0),        position(28.5, -80.6, 6378137.0 + 120e3),
      position(-45.0, 170.0, 6.5e6),        position(89.0, 33.0, 6356752.0 + 50e3),
      position(-89.9, -120.0, 6.4e6),       position(60.0, 10.0, 7.0e6),
      position(15.0, 250.0, 6378137.0 + 80e3), Eigen::Vector3d(0.0, 0.0, 6.4e6)};
  return pts;
}
}  // namespace

TEST(Earth, AltitudeSphereAndOblate) {
  const double re = EarthConstants::kEquatorialRadius_m;
  const double rp = re * (1.0 - EarthConstants::kFlattening);  // polar radius 6356752.314 m
  EXPECT_NEAR(rt::altitude_m(position(0, 30, re + 1000.0), rt::ShapeModel::kSphere), 1000.0, 1e-6);
  EXPECT_NEAR(rt::altitude_m(position(0, 30, re + 1000.0), rt::ShapeModel::kOblate), 1000.0, 1e-6);
  // (2.13) at the pole: surface point r = Rp has zero altitude
  EXPECT_NEAR(rt::altitude_m(Eigen::Vector3d(0, 0, rp + 500.0), rt::ShapeModel::kOblate), 500.0, 1e-6);
  EXPECT_NEAR(rp, 6356752.314245, 1e-5);
  // 45 deg: h = r - Re (1 - f / 2)
  EXPECT_NEAR(rt::altitude_m(position(45, 0, re), rt::ShapeModel::kOblate), re * EarthConstants::kFlattening / 2.0, 1e-6);
}

TEST(Earth, LatitudeLongitudeAndFrames) {
  const Eigen::Vector3d r = position(-33.0, 151.0, 6.4e6);
  EXPECT_NEAR(rt::geocentric_latitude_rad(r), -33.0 * M_PI / 180.0, 1e-14);
  EXPECT_NEAR(rt::longitude_rad(r), 151.0 * M_PI / 180.0, 1e-14);
  // V frame at (lon 0, lat 0): north = +Z, east = +Y, down = -X
  const Eigen::Matrix3d c0 = rt::dcm_R_to_V(0.0, 0.0);
  EXPECT_NEAR((c0 * Eigen::Vector3d(0, 0, 1) - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c0 * Eigen::Vector3d(0, 1, 0) - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c0 * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, 1e-15);
  // Down axis points to the centre anywhere; DCM orthonormal
  const double lon = 2.1, lat = -0.7;
  const Eigen::Matrix3d c = rt::dcm_R_to_V(lon, lat);
  EXPECT_NEAR((c * c.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(c.determinant(), 1.0, 1e-14);
  const Eigen::Vector3d rr = position(lat * 180.0 / M_PI, lon * 180.0 / M_PI, 1.0);
  EXPECT_NEAR((c * rr - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, 1e-14);
  // A point fixed on the rotating Earth at lon 0 is at inertial angle omega t.
  const double t = 1234.5, a = EarthConstants::kOmega_radps * t;
  const Eigen::Vector3d r_i(std::cos(a), std::sin(a), 0.0);
  EXPECT_NEAR((rt::rotation_I_to_R(t) * r_i - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
}

TEST(Gravity, CentralIsMuOverR2) {
  auto g = rt::Gravity::create(rt::GravityModel::kCentral, "");
  ASSERT_TRUE(g.has_value());
  for (const auto& r : test_points()) {
    const Eigen::Vector3d a = g->acceleration_R(r);
    const double expected = EarthConstants::kMu_m3ps2 / r.squaredNorm();  // (2.19)
    EXPECT_NEAR(a.norm() / expected - 1.0, 0.0, 1e-15);
    EXPECT_NEAR(a.normalized().dot(-r.normalized()), 1.0, 1e-15);
  }
}

TEST(Gravity, ZonalHarmonicsMatchAnalyticJ2J4) {
  // Spherical-harmonic code with only C20, C30, C40 (C_n0 = -J_n / sqrt(2n+1)) vs (2.16)-(2.17).
  std::vector<std::vector<double>> c(5), s(5);
  for (int n = 0; n <= 4; ++n) { c[n].assign(n + 1, 0.0); s[n].assign(n + 1, 0.0); }
  c[2][0] = -rt::Gravity::kJ2 / std::sqrt(5.0);
  c[3][0] = -rt::Gravity::kJ3 / std::sqrt(7.0);
  c[4][0] = -rt::Gravity::kJ4 / std::sqrt(9.0);
  std::string err;
  auto sh = rt::Gravity::from_coefficients(EarthConstants::kMu_m3ps2, EarthConstants::kEquatorialRadius_m, 4, c, s, &err);
  ASSERT_TRUE(sh.has_value()) << err;
  auto j = rt::Gravity::create(rt::GravityModel::kJ2J4, "");
  ASSERT_TRUE(j.has_value());
  double worst = 0.0;
  for (const auto& r : test_points()) {
    const Eigen::Vector3d a_sh = sh->acceleration_R(r), a_j = j->acceleration_R(r);
    worst = std::fmax(worst, (a_sh - a_j).norm() / a_j.norm());
    EXPECT_NEAR(sh->potential(r) / j->potential(r) - 1.0, 0.0, 1e-13);
  }
  EXPECT_LT(worst, 1e-12);
  std::printf("[figure] J2J4 analytic vs zonal SH: max relative difference %.3e\n", worst);
}

TEST(Gravity, SectoralTermMatchesClosedForm) {
  // Only Cbar22: U = mu/r (R/r)^2 C22 P22(sin d) cos(2 lon), P22 = 3 cos^2 d, C22 = sqrt(5/12) Cbar22.
  const double cbar22 = 2.43914352398e-6;
  std::vector<std::vector<double>> c(3), s(3);
  for (int n = 0; n <= 2; ++n) { c[n].assign(n + 1, 0.0); s[n].assign(n + 1, 0.0); }
  c[2][2] = cbar22;
  auto g = rt::Gravity::from_coefficients(EarthConstants::kMu_m3ps2, EarthConstants::kEquatorialRadius_m, 2, c, s);
  ASSERT_TRUE(g.has_value());
  const double re = EarthConstants::kEquatorialRadius_m, mu = EarthConstants::kMu_m3ps2;
  for (const auto& r : test_points()) {
    const double rn = r.norm(), cd = std::hypot(r.x(), r.y()) / rn, lon = std::atan2(r.y(), r.x());
    const double u = mu / rn * (1.0 + (re / rn) * (re / rn) * std::sqrt(5.0 / 12.0) * cbar22 * 3.0 * cd * cd * std::cos(2 * lon));
    EXPECT_NEAR(g->potential(r) / u - 1.0, 0.0, 1e-14);
  }
}

TEST(Gravity, AccelerationIsGradientOfPotential) {
  std::string err;
  auto sh = rt::Gravity::create(rt::GravityModel::kSphericalHarmonics, kEgm96, 20, &err);
  ASSERT_TRUE(sh.has_value()) << err;
  auto j = rt::Gravity::create(rt::GravityModel::kJ2J4, "");
  double worst = 0.0;
  for (const rt::Gravity* g : {&*sh, &*j}) {
    for (const auto& r : test_points()) {
      const double h = 2.0;
      Eigen::Vector3d grad;
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d rp = r, rm = r;
        rp[k] += h; rm[k] -= h;
        grad[k] = (g->potential(rp) - g->potential(rm)) / (2.0 * h);
      }
      const Eigen::Vector3d a = g->acceleration_R(r);
      // compare the non-central part too: subtract mu r / r^3 from both
      const Eigen::Vector3d central = -EarthConstants::kMu_m3ps2 / std::pow(r.norm(), 3) * r;
      worst = std::fmax(worst, (a - grad).norm() / (a - central).norm());
      EXPECT_LT((a - grad).norm() / a.norm(), 1e-8);
    }
  }
  EXPECT_LT(worst, 1e-5);
  std::printf("[figure] |a - grad U| / |a - a_central| worst %.3e\n", worst);
}

TEST(Gravity, Egm96Degree20DiffersFromJ2J4BySmallAmount) {
  std::string err;
  auto sh = rt::Gravity::create(rt::GravityModel::kSphericalHarmonics, kEgm96, 20, &err);
  ASSERT_TRUE(sh.has_value()) << err;
  auto j = rt::Gravity::create(rt::GravityModel::kJ2J4, "");
  double worst = 0.0;
  for (const auto& r : test_points()) {
    const double d = (sh->acceleration_R(r) - j->acceleration_R(r)).norm() / j->acceleration_R(r).norm();
    worst = std::fmax(worst, d);
    EXPECT_LT(d, 1e-4);
  }
  EXPECT_GT(worst, 1e-7);  // tesseral terms are present
  std::printf("[figure] SH20 vs J2J4 max relative difference %.3e\n", worst);
  // Surface gravity magnitude near the equator ~ 9.814 m/s^2 (no centrifugal term)
  EXPECT_NEAR(sh->acceleration_R(position(0, 0, EarthConstants::kEquatorialRadius_m)).norm(), 9.814, 0.01);
}

TEST(Gravity, BadFileReportsFileAndLine) {
  const std::string path = ::testing::TempDir() + "bad_egm.txt";
  FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fprintf(f, "3.986004418e14 6378137.0\n2 0 -0.48e-3 0\n2 1 nan 0\n");
  std::fclose(f);
  std::string err;
  EXPECT_FALSE(rt::Gravity::create(rt::GravityModel::kSphericalHarmonics, path, 2, &err).has_value());
  EXPECT_NE(err.find(path + ":3"), std::string::npos) << err;
  EXPECT_FALSE(rt::Gravity::create(rt::GravityModel::kSphericalHarmonics, "/nonexistent/x.txt", 20, &err).has_value());
  EXPECT_NE(err.find("/nonexistent/x.txt"), std::string::npos);
}
