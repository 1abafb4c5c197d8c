// The AD derivatives the optimizer takes of the truth models, checked against central finite
// differences of the same models in double (an independent evaluation path: the double
// instantiation the simulator runs), on dispersed runs with wind, the density perturbation and
// (HORUS) trim; and the optimizer's arrival-line frame against the referee's.
#include <gtest/gtest.h>

#include <cmath>

#include "ad.hpp"
#include "entry_problem.hpp"
#include "evaluation/mission_verdict.hpp"
#include "run_oracle.hpp"

namespace reentry::optimal {
namespace {

config::Mission load(const std::string& name) {
  const config::LoadResult r = config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

// A mid-flight state of run `seed`: the entry flown open loop at the profile's entry alpha
// and a 60 deg bank for t_s seconds.
std::unique_ptr<truth::Simulator> advanced(const config::Mission& m, std::uint64_t seed, double t_s) {
  std::string err;
  auto sim = make_run_simulator(m, seed, true, &err);
  EXPECT_TRUE(sim) << err;
  sim->set_command(m.alpha_profile.y.back(), 60.0 * M_PI / 180.0);
  sim->advance_to(t_s);
  return sim;
}

constexpr int kW = 9;  // t, r_I, v_I, alpha, sigma

void check_point_derivatives(const std::string& mission, std::uint64_t run_seed, double t_s, double alpha_deg) {
  const config::Mission m = load(mission);
  auto sim = advanced(m, run_seed, t_s);
  auto fresh = make_run_simulator(m, run_seed, true, nullptr);
  const EntryProblem pb(*fresh, EntryMode::kMaxMargin, 2000.0);
  const int np = pb.n_path();
  double w[kW] = {sim->time_s()};
  for (int i = 0; i < 6; ++i) w[1 + i] = sim->state()[static_cast<size_t>(i)];
  w[7] = alpha_deg * M_PI / 180.0;
  w[8] = 0.7;
  auto eval = [&](const double* v, double* out) {
    double xdot[6];
    std::vector<double> g(static_cast<size_t>(np));
    pb.point(v[0], v + 1, v + 7, xdot, g.data());
    for (int i = 0; i < 6; ++i) out[i] = xdot[i];
    for (int i = 0; i < np; ++i) out[6 + i] = g[static_cast<size_t>(i)];
  };
  const int nout = 6 + np;
  // First derivatives.
  Ad1<kW> a[kW];
  seed<kW>(w, a);
  Ad1<kW> xdot[6];
  std::vector<Ad1<kW>> g(static_cast<size_t>(np));
  pb.point(a[0], a + 1, a + 7, xdot, g.data());
  // t: the models are invariant under the Earth's rotation about its axis (J2-J4, oblate shape, wind and
  // atmosphere by altitude), so d/dt is zero; a 10 s step keeps the altitude round-off out.
  const double step[kW] = {10.0, 0.1, 0.1, 0.1, 1e-4, 1e-4, 1e-4, 1e-6, 1e-6};
  for (int q = 0; q < kW; ++q) {
    double wp[kW], wm[kW], fp[16], fm[16];
    std::copy(w, w + kW, wp);
    std::copy(w, w + kW, wm);
    wp[q] += step[q];
    wm[q] -= step[q];
    eval(wp, fp);
    eval(wm, fm);
    for (int i = 0; i < nout; ++i) {
      const Ad1<kW>& ad = i < 6 ? xdot[i] : g[static_cast<size_t>(i - 6)];
      // Compared as the change of the output over one step, against the round-off of the
      // output (the altitude row carries the radius, 6.4e6 m, inside).
      const double change_fd = 0.5 * (fp[i] - fm[i]);
      const double change_ad = ad.derivatives()[q] * step[q];
      const double magnitude = i == nout - 1 ? 1e7 : std::max(std::fabs(fp[i]), std::fabs(fm[i]));
      EXPECT_NEAR(change_ad, change_fd, 1e-4 * std::fabs(change_fd) + 1e-12 * magnitude)
          << mission << " output " << i << " wrt " << q;
    }
  }
  // Second derivatives of a weighted sum of the outputs (what the Lagrangian needs), against
  // differences of the first derivatives.
  std::vector<double> weight(static_cast<size_t>(nout));
  for (int i = 0; i < nout; ++i) weight[static_cast<size_t>(i)] = 1.0 / (1.0 + i);
  Ad2<kW> b[kW];
  seed<kW>(w, b);
  Ad2<kW> xdot2[6];
  std::vector<Ad2<kW>> g2(static_cast<size_t>(np));
  pb.point(b[0], b + 1, b + 7, xdot2, g2.data());
  Ad2<kW> s = Ad2<kW>(0.0);
  for (int i = 0; i < nout; ++i) s += weight[static_cast<size_t>(i)] * (i < 6 ? xdot2[i] : g2[static_cast<size_t>(i - 6)]);
  auto grad = [&](const double* v, double* out) {
    Ad1<kW> c[kW];
    seed<kW>(v, c);
    Ad1<kW> f[6];
    std::vector<Ad1<kW>> gg(static_cast<size_t>(np));
    pb.point(c[0], c + 1, c + 7, f, gg.data());
    Gradient<kW> acc = Gradient<kW>::Zero();
    for (int i = 0; i < nout; ++i) acc += weight[static_cast<size_t>(i)] * (i < 6 ? f[i] : gg[static_cast<size_t>(i - 6)]).derivatives();
    for (int k = 0; k < kW; ++k) out[k] = acc[k];
  };
  for (int q = 0; q < kW; ++q) {
    double wp[kW], wm[kW], gp[kW], gm[kW];
    std::copy(w, w + kW, wp);
    std::copy(w, w + kW, wm);
    wp[q] += step[q];
    wm[q] -= step[q];
    grad(wp, gp);
    grad(wm, gm);
    for (int k = 0; k < kW; ++k) {
      const double change_fd = 0.5 * (gp[k] - gm[k]);
      const double change_ad = s.derivatives()[q].derivatives()[k] * step[q];
      // Round-off floor: of the largest gradient change over a step, and of this component
      // (HORUS: the trim root is solved to 1e-14 rad).
      double magnitude = 0.0;
      for (int j = 0; j < kW; ++j) magnitude = std::max(magnitude, std::fabs(gp[j]) * step[j]);
      const double floor = 1e-12 * magnitude + 1e-10 * std::max(std::fabs(gp[k]), std::fabs(gm[k]));
      EXPECT_NEAR(change_ad, change_fd, 1e-3 * std::fabs(change_fd) + floor)
          << mission << " d2/d" << q << "d" << k;
    }
  }
}

TEST(TruthModelAD, X33DispersedDerivativesMatchFiniteDifferences) { check_point_derivatives("x33", 11, 400.0, 40.3); }

TEST(TruthModelAD, HorusTrimmedDerivativesMatchFiniteDifferences) { check_point_derivatives("horus", 12, 500.0, 38.4); }

TEST(TruthModelAD, X38DerivativesMatchFiniteDifferencesLateInFlight) { check_point_derivatives("x38", 13, 1200.0, 30.2); }

// The Orbiter's heating is Betts's leading-edge fit, which depends on alpha: its AD derivatives
// (d qdot / d alpha included) against finite differences, and the optimizer's heat-flux row
// against the heat flux the simulator reports for the same state and attitude.
TEST(TruthModelAD, OrbiterLeadingEdgeHeatingDerivativesMatchFiniteDifferences) {
  check_point_derivatives("orbiter", 14, 600.0, 38.0);
}

TEST(EntryProblem, HeatFluxRowIsTheVehicleHeatingModelOfTheSimulator) {
  for (const char* name : {"orbiter", "horus"}) {
    const config::Mission m = load(name);
    auto sim = advanced(m, 3, 500.0);
    auto fresh = make_run_simulator(m, 3, true, nullptr);
    const EntryProblem pb(*fresh, EntryMode::kMaxMargin, 2000.0);
    ASSERT_EQ(pb.path_rows().front(), PathRow::kHeatFlux) << name;
    const truth::TruthSample ts = sim->sample();
    double x[6], xdot[6], u[2] = {ts.alpha_rad, ts.sigma_rad};
    for (int i = 0; i < 6; ++i) x[i] = sim->state()[static_cast<size_t>(i)];
    std::vector<double> g(static_cast<size_t>(pb.n_path()));
    pb.point(sim->time_s(), x, u, xdot, g.data());
    EXPECT_NEAR(g[0] * m.constraints.heat_flux_max_Wpm2, ts.qdot_Wpm2, 1e-9 * ts.qdot_Wpm2) << name;
    const double expected = m.vehicle.heating_model == config::HeatingModel::kBettsLeadingEdge
                                ? truth::betts_leading_edge_heat_flux_Wpm2(ts.rho_kgpm3, ts.airspeed_mps, ts.alpha_rad)
                                : truth::chapman_heat_flux_Wpm2(ts.rho_kgpm3, ts.airspeed_mps, m.vehicle.nose_radius_m);
    EXPECT_NEAR(ts.qdot_Wpm2, expected, 1e-9 * expected) << name;
  }
}

TEST(EntryProblem, ArrivalLineFrameMatchesTheReferee) {
  const config::Mission m = load("x33");
  auto sim = make_run_simulator(m, 0, false, nullptr);
  const EntryProblem pb(*sim, EntryMode::kMaxDownrange, 1500.0);
  // Points around the aim point: place them with r_I at t = 0 (R = I) on the R_eq sphere.
  const double re = truth::EarthConstants::kEquatorialRadius_m;
  for (double dlat : {-1.0, 0.3, 2.0}) {
    for (double dlon : {-2.5, 0.1, 1.7}) {
      const double lat = m.taem.latitude_rad + dlat * M_PI / 180.0, lon = m.taem.longitude_rad + dlon * M_PI / 180.0;
      const double x[6] = {re * std::cos(lat) * std::cos(lon), re * std::cos(lat) * std::sin(lon), re * std::sin(lat),
                           100.0, 200.0, -10.0};
      const double u[2] = {0.5, 0.0};
      const auto f = pb.final_quantities(0.0, x, u);
      const truth::ArrivalLineOffset ref =
          truth::arrival_line_offset(lat, lon, m.taem.latitude_rad, m.taem.longitude_rad, m.taem.heading_rad);
      EXPECT_NEAR(f.along, ref.along_m, 1e-3);
      EXPECT_NEAR(f.cross, ref.cross_m, 1e-3);
      const double arc = 2.0 * std::asin(0.5 * std::sqrt(f.chord2));
      EXPECT_NEAR(arc * re, truth::great_circle_leg(lat, lon, m.taem.latitude_rad, m.taem.longitude_rad).arc_rad * re, 1e-3);
    }
  }
}

}  // namespace
}  // namespace reentry::optimal
