// The predictor and the corrector of the predictor-corrector law against independent truths:
//   - the truth simulator (sim_truth: Cartesian inertial dynamics, its own atmosphere, aero and
//     event location) flying open loop the bank and alpha schedule a prediction flew ends where
//     the prediction says;
//   - an equilibrium glide over a non-rotating Earth with constant L/D and bank covers the
//     analytic range s = (r/2)(L/D) cos(sigma) ln[(1 - V_f^2/(g r)) / (1 - V_0^2/(g r))];
//   - a lower terminal aim flies a shorter flight (denser air, ds/dE = -1/D), and where the
//     bank is out of reach late in the flight the plan takes the range with it;
//   - the corrector reaches a reachable target (a root: the neighbouring sigma_0 straddle it)
//     and, for targets out of reach, returns the bound that misses least (brute-force scan).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "dynamics/open_loop.hpp"
#include "dynamics/simulator.hpp"
#include "guidance/mission_adapter.hpp"
#include "nav/relative_state.hpp"
#include "planner/mission_geometry.hpp"
#include "predictor_corrector/pc_planner.hpp"
#include "reentry/config/mission.hpp"

namespace reentry::fsw {
namespace {

constexpr double kDeg = M_PI / 180.0;

config::Mission load(const char* name) {
  const auto r = config::load_mission(name);
  EXPECT_TRUE(r.ok) << r.error;
  return r.mission;
}

RelativeState state_of(const truth::Simulator& sim) {
  const truth::NavSample n = sim.nav_sample();
  const double r[3] = {n.r_I_m.x(), n.r_I_m.y(), n.r_I_m.z()};
  const double v[3] = {n.v_I_mps.x(), n.v_I_mps.y(), n.v_I_mps.z()};
  const double a[3] = {n.aero_accel_I_mps2.x(), n.aero_accel_I_mps2.y(), n.aero_accel_I_mps2.z()};
  RelativeState s;
  EXPECT_EQ(relative_state_from_nav(n.t_s, r, v, a, n.earth_rotation_angle_rad, s), Status::kOk);
  return s;
}

// The truth with the on-board models' physics (central gravity, US76 without wind, the air over
// the ellipsoid) but its own equations, atmosphere interpolation, aero lookup and events.
std::unique_ptr<truth::Simulator> truth_like_onboard(const config::Mission& m) {
  truth::SimOverrides ov;
  ov.gravity = truth::GravityChoice::kCentral;
  ov.atmosphere = truth::AtmosphereChoice::kUS76;
  ov.wind = truth::WindChoice::kOff;
  ov.shape = truth::ShapeChoice::kOblate;
  ov.attitude = truth::AttitudeChoice::kIdeal;
  std::string err;
  auto sim = truth::Simulator::create(m, ov, &err);
  EXPECT_NE(sim, nullptr) << err;
  return sim;
}

TEST(PcPredictor, EndsWhereTheTruthSimulatorFlyingTheSameScheduleOpenLoopEnds) {
  // Tolerance: 0.1 % of the distance flown in position and 300 m in altitude, from the step
  // (2 s RK4 against the truth's RKF5(6) at 1e-10), the first-order ellipsoid of the on-board
  // air and the linear ln(rho) of the on-board table against the truth's spline.
  for (const char* name : {"x33", "x38"}) {
    const config::Mission m = load(name);
    auto planner = std::make_unique<PredictorCorrectorPlanner>();
    ASSERT_EQ(init_from_mission(*planner, m), Status::kOk) << name;
    auto sim = truth_like_onboard(m);
    ASSERT_NE(sim, nullptr);
    const RelativeState s0 = state_of(*sim);
    auto trace = std::make_unique<PredictionTrace>();
    const Prediction p = planner->predict(s0, 50.0 * kDeg, 1.0, nullptr, -1.0, trace.get());
    ASSERT_EQ(p.end, PredictionEnd::kTaem) << name;
    ASSERT_GT(p.reversals, 0) << name << ": the schedule must include the lateral logic's reversals";
    truth::OpenLoopProfile schedule;
    for (int i = 0; i < trace->n; ++i) {
      schedule.x.push_back(trace->t_s[i]);
      schedule.alpha_rad.push_back(trace->alpha_rad[i]);
      schedule.sigma_rad.push_back(trace->sigma_rad[i]);
    }
    const truth::RunSummary r = truth::run_open_loop(*sim, schedule, 1e9, nullptr);
    ASSERT_EQ(r.event, truth::SimEvent::kTaemEnergy) << name;
    const truth::TruthSample& f = r.final_state;
    const double miss_m =
        kEarthRadius_m * great_circle(f.lat_rad, f.lon_rad, p.final_state.latitude_rad, p.final_state.longitude_rad).arc_rad;
    EXPECT_LT(miss_m, 1e-3 * p.range_flown_m) << name << ": predicted and flown TAEM points " << miss_m << " m apart over "
                                              << p.range_flown_m << " m";
    EXPECT_NEAR(f.h_m, p.altitude_m, 300.0) << name;
    EXPECT_NEAR(f.t_s, p.time_s, 5.0) << name;
    EXPECT_NEAR(wrap_pi(f.chi_rad - p.final_state.heading_rad), 0.0, 0.5 * kDeg) << name;
  }
}

// A vehicle with constant C_L, C_D in an exponential atmosphere over a non-rotating Earth.
struct GlideCase {
  OnboardModels models;
  AlphaProfile alpha;
  PredictorCorrectorParams params;
  PointMassModel model;
  PcLateral lateral;
  Predictor predictor;
};

// A ranging (negative) alpha shift stops at the alpha of maximum L/D: the X-38 model's, as its
// vehicle file states it from the generator's 0.1 deg scan (25.0 deg at Mach 5.5 and 10, 25.1 at
// Mach 20, 23.0 at Mach 3; the on-board table, bilinear on a 1 deg alpha grid, has its maximum
// at a node: within 0.6 deg); a shift that stays above it, and a positive one, are flown as given.
TEST(PcPointMass, RangingShiftStopsAtTheAlphaOfMaximumLiftOverDrag) {
  auto setup = std::make_unique<GuidanceSetup>();
  ASSERT_TRUE(make_guidance_setup(load("x38"), *setup).empty());
  const double e0 = specific_energy_Jpkg(kEarthRadius_m + setup->mission.entry.altitude_m, setup->mission.entry.velocity_mps);
  auto model = std::make_unique<PointMassModel>();
  model->init(&setup->models, &setup->alpha_profile, e0, setup->mission.limits.alpha_max_rad);
  const double e = 0.8 * e0;  // the profile's 40 deg, the shift in full above 0.5 e0
  const double profile = model->profile_alpha_at(e);
  ASSERT_NEAR(profile, 40.0 * kDeg, 1e-9);
  const struct { double mach, alpha_ld_deg; } published[] = {{3.0, 23.0}, {5.5, 25.0}, {10.0, 25.0}, {20.0, 25.1}};
  model->set_alpha_shift(-30.0 * kDeg, 0.5 * e0, 0.4 * e0);
  for (const auto& p : published) {
    EXPECT_NEAR(model->alpha_at(e, p.mach) / kDeg, p.alpha_ld_deg, 0.6) << "Mach " << p.mach;
  }
  model->set_alpha_shift(-5.0 * kDeg, 0.5 * e0, 0.4 * e0);
  EXPECT_NEAR(model->alpha_at(e, 10.0), profile - 5.0 * kDeg, 1e-12);
  model->set_alpha_shift(3.0 * kDeg, 0.5 * e0, 0.4 * e0);
  EXPECT_NEAR(model->alpha_at(e, 10.0), profile + 3.0 * kDeg, 1e-12);
}

TEST(PcPointMass, AStepGivenTheAirOfItsStartEqualsTheStepThatEvaluatesIt) {
  // The predictor hands each RK4 step the air it already sampled at the step's start (the first
  // stage is evaluated there, numerics::rk4_step); the step must be the one that evaluates it
  // itself, bit for bit, with or without a ranging shift and a modulation offset.
  auto setup = std::make_unique<GuidanceSetup>();
  ASSERT_TRUE(make_guidance_setup(load("orbiter"), *setup).empty());
  const double e0 = specific_energy_Jpkg(kEarthRadius_m + setup->mission.entry.altitude_m, setup->mission.entry.velocity_mps);
  auto model = std::make_unique<PointMassModel>();
  model->init(&setup->models, &setup->alpha_profile, e0, setup->mission.limits.alpha_max_rad);
  model->set_density_ratio(1.07);
  PointMassState x{kEarthRadius_m + 62000.0, -1.9, 0.31, 6300.0, -0.6 * kDeg, 48.0 * kDeg};
  auto bits_equal = [](const PointMassState& a, const PointMassState& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
  };
  for (const double shift : {0.0, -4.0 * kDeg}) {
    model->set_alpha_shift(shift, 0.6 * e0, 0.2 * e0);
    model->set_alpha_modulation(shift == 0.0 ? 0.0 : -2.5 * kDeg);
    const AeroSample air = model->aero_at(x);
    PointMassState given, evaluated;
    model->rk4(x, 70.0 * kDeg, 68.0 * kDeg, 2.0, given, &air);
    model->rk4(x, 70.0 * kDeg, 68.0 * kDeg, 2.0, evaluated);
    EXPECT_TRUE(bits_equal(given, evaluated)) << "shift " << shift;
    EXPECT_GT(std::fabs(given.velocity_mps - x.velocity_mps), 1.0);  // a step that flew
  }
}

TEST(PcPredictor, EquilibriumGlideCoversTheAnalyticRange) {
  auto c = std::make_unique<GlideCase>();
  const double cl = 0.6, cd = 0.5, mass = 10000.0, area = 20.0, sigma = 30.0 * kDeg;
  const double alpha_grid[2] = {0.0, 1.0}, mach_grid[1] = {1.0}, cls[2] = {cl, cl}, cds[2] = {cd, cd};
  ASSERT_EQ(c->models.init_vehicle(mass, area, 1.0), Status::kOk);
  c->models.atmosphere().init_exponential();
  ASSERT_EQ(c->models.aero().init(alpha_grid, 2, mach_grid, 1, cls, cds), Status::kOk);
  const double e_norm[1] = {0.0}, alpha[1] = {0.5};
  ASSERT_EQ(c->alpha.init(e_norm, alpha, 1), Status::kOk);
  c->params.terminal_span_fraction = 0.0;  // the glide alone: no terminal altitude law
  c->params.glide_position_factor = 0.0;
  // The glide's state at speed v on the equator, heading east: L cos(sigma) = g - V^2 / r.
  const double lod = cl / cd;
  auto glide_state = [&](double v) {
    PointMassState x;
    double r = kEarthRadius_m + 50000.0;
    for (int i = 0; i < 50; ++i) {
      const double rho = 2.0 * (gravity_mps2(r) - v * v / r) / (v * v * cl * area / mass * std::cos(sigma));
      r = kEarthRadius_m - std::log(rho / OnboardAtmosphere::kRho0_kgpm3) / OnboardAtmosphere::kBeta_pm;
    }
    x.radius_m = r;
    x.velocity_mps = v;
    x.heading_rad = 0.5 * M_PI;
    return x;
  };
  const PointMassState x0 = glide_state(6500.0), xf = glide_state(2500.0);
  const double e0 = energy_of(x0), ef = energy_of(xf);
  c->model.init(&c->models, &c->alpha, e0, 1.0, 0.0);
  TaemTarget taem;
  taem.longitude_rad = 1.5;  // far east on the equator: the lateral logic keeps the bank's side
  taem.heading_rad = 0.5 * M_PI;
  c->lateral.init(c->params, taem, 1.0, e0, ef);
  PredictorConfig cfg;
  cfg.sigma_rate_max_radps = 1.0;
  cfg.sigma_accel_max_radps2 = 10.0;
  cfg.skip_out_altitude_m = 200000.0;
  cfg.terminal = TerminalAltitude{ef, e0 - ef, 0.0};
  ASSERT_EQ(c->predictor.init(&c->model, &c->lateral, &c->params, cfg), Status::kOk);
  PredictionStart start;
  start.x = x0;
  start.x.flight_path_rad = qeg_altitude_rate_mps(6500.0, x0.radius_m, 0.0, 0.5 * M_PI, 0.0, 7050.0) / 6500.0;
  start.sigma_flown_rad = sigma;
  start.lateral.sign = 1;
  start.captured = true;
  BankProfile bank;
  bank.bank_max_rad = bank.bank_far_rad = 85.0 * kDeg;
  bank.control = bank.sigma_glide_rad = sigma;
  bank.e0_Jpkg = e0;
  bank.ef_Jpkg = ef;
  const Prediction p = c->predictor.run(start, bank, nullptr);
  ASSERT_EQ(p.end, PredictionEnd::kTaem);
  const double r_mean = 0.5 * (x0.radius_m + xf.radius_m), g = gravity_mps2(r_mean);
  const double v0 = 6500.0, vf = 2500.0;
  const double path_m = 0.5 * r_mean * lod * std::cos(sigma) *
                        std::log((1.0 - vf * vf / (g * r_mean)) / (1.0 - v0 * v0 / (g * r_mean)));
  const double ground_m = path_m * kEarthRadius_m / r_mean;
  EXPECT_NEAR(p.range_flown_m, ground_m, 0.01 * ground_m) << "predicted " << p.range_flown_m << " m, analytic " << ground_m;
  EXPECT_NEAR(p.final_state.velocity_mps, vf, 25.0);
}

// A plan without latency and without the terminal-aim iterations: plan() then solves exactly the
// predictions predict() makes from the same state.
struct CorrectorCase {
  std::unique_ptr<PredictorCorrectorPlanner> planner = std::make_unique<PredictorCorrectorPlanner>();
  std::unique_ptr<ReferenceProfile> out = std::make_unique<ReferenceProfile>();
  PathLimits setup_limits;
  Status init(const config::Mission& m) {
    auto setup = std::make_unique<GuidanceSetup>();
    if (!make_guidance_setup(m, *setup).empty()) return Status::kInvalidInput;
    setup->pc_params.altitude_iterations = 0;
    setup_limits = setup->mission.limits;
    return planner->init(setup->models, setup->alpha_profile, setup->mission, setup->pc_params,
                         setup->params.tracker.initial_descent_drag_mps2, PcPlanTiming{0, 0.1});
  }
};

// The mission with its aim point moved along the arrival great circle by `shift_rad`
// (> 0: farther), the arrival heading kept that of the circle there.
config::Mission shifted(const config::Mission& m, double shift_rad) {
  config::Mission s = m;
  const TrackPoint p = great_circle_point(m.taem.latitude_rad, m.taem.longitude_rad, m.entry.latitude_rad,
                                          m.entry.longitude_rad, 0.0);
  const double back = p.azimuth_rad;  // from the aim point towards the entry
  const double d = -shift_rad, lat1 = m.taem.latitude_rad, lon1 = m.taem.longitude_rad;
  const double lat2 = std::asin(std::sin(lat1) * std::cos(d) + std::cos(lat1) * std::sin(d) * std::cos(back));
  const double lon2 = lon1 + std::atan2(std::sin(back) * std::sin(d) * std::cos(lat1), std::cos(d) - std::sin(lat1) * std::sin(lat2));
  s.taem.latitude_rad = lat2;
  s.taem.longitude_rad = lon2;
  s.taem.heading_rad = wrap_pi(great_circle(lat2, lon2, m.entry.latitude_rad, m.entry.longitude_rad).azimuth_rad + M_PI);
  return s;
}

TEST(PcCorrector, ReachesAReachableTargetAtARootOfTheMiss) {
  CorrectorCase c;
  ASSERT_EQ(c.init(load("x33")), Status::kOk);
  const RelativeState s = c.planner->entry_state();
  ASSERT_EQ(c.planner->plan(s, *c.out), Status::kOk);
  // The miss is a step function at the scale of the lateral logic's discrete reversal times
  // (jumps of a few km over 8000 km), so the root is reached within the plan's acceptance.
  const PcPlanDiagnostics& d = c.planner->diagnostics();
  EXPECT_LE(std::fabs(d.miss_along_m), c.planner->params().accept_miss_m);
  EXPECT_LE(d.predictions, c.planner->params().max_predictions);
  EXPECT_EQ(c.out->n_points, kProfileCapacity);
  // A root of a miss that rises with sigma_0: the neighbours straddle zero.
  const double k = d.density_ratio;
  BankProfile bank = c.planner->bank_family();
  bank.sigma_glide_rad = c.planner->final_bank_rad(k);
  bank.control = d.control - 2.0 * kDeg;
  const Prediction lo = c.planner->predict_profile(s, bank, k, nullptr);
  bank.control = d.control + 2.0 * kDeg;
  const Prediction hi = c.planner->predict_profile(s, bank, k, nullptr);
  EXPECT_LT(lo.along_m, 0.0);
  EXPECT_GT(hi.along_m, 0.0);
}

TEST(PcCorrector, OutOfReachReturnsTheBoundThatMissesLeastAndSaysWhichWay) {
  const config::Mission x33 = load("x33");
  for (const double shift : {+6000e3 / kEarthRadius_m, -5000e3 / kEarthRadius_m}) {
    CorrectorCase c;
    ASSERT_EQ(c.init(shifted(x33, shift)), Status::kOk);
    const RelativeState s = c.planner->entry_state();
    const Status st = c.planner->plan(s, *c.out);
    const PcPlanDiagnostics& d = c.planner->diagnostics();
    const bool too_short = shift > 0.0;
    EXPECT_EQ(st, too_short ? Status::kRangeTooShort : Status::kRangeTooLong) << to_string(st);
    EXPECT_EQ(c.out->n_points, kProfileCapacity);  // flown as a best effort
    if (too_short) EXPECT_DOUBLE_EQ(d.sigma0_rad, 0.0);                              // the longest flight
    else EXPECT_GT(d.sigma0_rad, c.planner->params().bank_max_rad);                       // lift down
    EXPECT_DOUBLE_EQ(d.alpha_shift_rad, (too_short ? -1.0 : 1.0) * c.planner->params().alpha_band_rad);
    // Brute force over the whole family (bank, alpha shift, final bank): nothing reaches, and the
    // bound misses least to within 2 % (z is monotonic only up to the lateral logic's jumps).
    double least = 1e300;
    BankProfile bank = c.planner->bank_family();
    bank.sigma_glide_rad = c.planner->final_bank_rad(d.density_ratio);
    const int n = 40;
    for (int i = 0; i <= n; ++i) {
      bank.control = bank.control_max() * i / n;
      const Prediction p = c.planner->predict_profile(s, bank, d.density_ratio, nullptr);
      if (!p.usable()) continue;
      EXPECT_EQ(p.along_m > 0.0, too_short) << bank.control;
      least = std::fmin(least, std::fabs(p.along_m));
    }
    EXPECT_LE(std::fabs(d.miss_along_m), 1.02 * least);
  }
}

// A state late in the flight, inside the terminal phase (the terminal altitude law flies the
// bank): on the arrival great circle `distance_m` before the aim point, heading along it.
RelativeState late_state(const config::Mission& m, double distance_m, double altitude_m, double velocity_mps) {
  const double aim_to_entry_rad = great_circle(m.taem.latitude_rad, m.taem.longitude_rad, m.entry.latitude_rad,
                                               m.entry.longitude_rad).arc_rad;
  const TrackPoint p = great_circle_point(m.taem.latitude_rad, m.taem.longitude_rad, m.entry.latitude_rad,
                                          m.entry.longitude_rad, distance_m / kEarthRadius_m / aim_to_entry_rad);
  RelativeState s;
  s.latitude_rad = p.lat_rad;
  s.longitude_rad = p.lon_rad;
  s.radius_m = surface_radius_m(s.latitude_rad) + altitude_m;
  s.altitude_m = s.radius_m - kEarthRadius_m;
  s.velocity_mps = velocity_mps;
  s.flight_path_rad = -1.0 * kDeg;
  s.heading_rad = wrap_pi(p.azimuth_rad + M_PI);  // along the circle, towards the aim point
  s.energy_Jpkg = specific_energy_Jpkg(s.radius_m, s.velocity_mps);
  s.drag_mps2 = 5.0;  // sensed: captured (the plan's K from it)
  return s;
}

// The X-33 late in its flight (165 km before the aim point, 45 km, 2000 m/s, captured), the family
// at the glide's final bank.
class PcLateTerminalPhase : public ::testing::Test {
 protected:
  void SetUp() override {
    m = load("x33");
    ASSERT_EQ(c.init(m), Status::kOk);
    s = late_state(m, 165e3, 45000.0, 2000.0);
    bank = c.planner->bank_family();
    bank.sigma_glide_rad = c.planner->final_bank_rad(1.0);
  }
  config::Mission m;
  CorrectorCase c;
  RelativeState s;
  BankProfile bank;
};

// The terminal line's aim moves the range: a lower line flies denser air, more drag per unit
// energy (ds/dE = -1/D), so the flight ends shorter (more still to go) and lower.
TEST_F(PcLateTerminalPhase, ALowerTerminalAimFliesAShorterFlight) {
  bank.control = 0.0;
  Prediction p[3];
  for (int i = 0; i < 3; ++i) {
    bank.terminal_altitude_m = c.planner->taem_target_altitude_m() + 1000.0 * (i - 1);
    p[i] = c.planner->predict_profile(s, bank, 1.0, nullptr);
    ASSERT_TRUE(p[i].usable());
  }
  EXPECT_GT(p[0].along_m, p[1].along_m + 2000.0);
  EXPECT_GT(p[1].along_m, p[2].along_m + 2000.0);
  EXPECT_LT(p[0].altitude_m, p[2].altitude_m);
}

// There sigma_0 has lost the range (every member of the family at the target aim ends long, by a
// brute-force scan): the plan takes the range with the terminal aim, below the target and within
// the TAEM band, its path maxima within the planned limits, and misses less than the bank can.
TEST_F(PcLateTerminalPhase, OutOfTheBanksReachTheTerminalAimTakesTheRange) {
  const Status st = c.planner->plan(s, *c.out);
  const PcPlanDiagnostics& d = c.planner->diagnostics();
  const double k = d.density_ratio;  // the plan's sensed density ratio, for the scan
  bank.sigma_glide_rad = c.planner->final_bank_rad(k);
  double least = 1e300;
  for (int i = 0; i <= 40; ++i) {
    bank.control = bank.control_max() * i / 40;
    const Prediction p = c.planner->predict_profile(s, bank, k, nullptr);
    ASSERT_TRUE(p.usable());
    ASSERT_LT(p.along_m, 0.0) << bank.control;  // long whatever the bank
    least = std::fmin(least, -p.along_m);
  }
  EXPECT_TRUE(st == Status::kRangeTooLong || st == Status::kOk) << to_string(st);
  EXPECT_LT(std::fabs(d.miss_along_m), least - 2000.0) << "the bank's least miss " << least << " m";
  EXPECT_LT(c.out->taem_altitude_m, c.planner->taem_target_altitude_m());
  EXPECT_GE(c.out->taem_altitude_m, m.taem.altitude_m - m.taem.altitude_tol_m);
  EXPECT_NEAR(d.final_altitude_m, m.taem.altitude_m, m.taem.altitude_tol_m);
  const PcLimits lim = pc_limits_from(c.setup_limits, c.planner->params().constraint_margin,
                                      c.planner->params().drag_model_uncertainty);
  EXPECT_LE(d.best.q_max_Pa, lim.q_max_Pa);
  EXPECT_LE(d.best.q_alpha_max_Pa_rad, lim.q_alpha_max_Pa_rad);
  EXPECT_LE(d.best.heat_flux_max_Wpm2, lim.heat_flux_max_Wpm2);
}

// The Orbiter captured early, 3550 km before the aim point at 7215 m/s and 68.5 km: closer than
// any member of the family can end (the constraint bound, not the bank, holds it up), so every
// flight along the line of sight ends long.
class PcReversalHold : public ::testing::Test {
 protected:
  void SetUp() override {
    m = load("orbiter");
    // At the default heading corridor: the mission's wider one (its file says why) lets the
    // bank's side alone turn the track off the line, which is what the hold is tested for here.
    auto& tuning = m.guidance.tuning;
    tuning.erase(std::remove_if(tuning.begin(), tuning.end(),
                                [](const auto& t) { return t.key.rfind("predictor_corrector.corridor_", 0) == 0; }),
                 tuning.end());
    ASSERT_EQ(c.init(m), Status::kOk);
    s = late_state(m, kDistance_m, 68500.0, 7215.0);
    s.flight_path_rad = -0.2 * kDeg;
    s.drag_mps2 = 5.2;  // the on-board model's drag there (density ratio 1)
    s.bank_rad = 35.0 * kDeg;
    bank = c.planner->bank_family();
    bank.sigma_glide_rad = c.planner->final_bank_rad(1.0);
    e_taem = c.planner->taem_energy_Jpkg();
  }
  static constexpr double kDistance_m = 3550e3;
  config::Mission m;
  CorrectorCase c;
  RelativeState s;
  BankProfile bank;
  double e_taem = 0.0;
};

// Holding the bank's side turns the heading off the line of sight: the ground track grows
// longer than the along-track progress, and the flight ends shorter along the line.
TEST_F(PcReversalHold, HoldingTheSideTurnsTheTrackOffTheLineAndShortensTheRange) {
  bank.control = bank.control_max();
  const Prediction none = c.planner->predict_profile(s, bank, 1.0, nullptr);
  bank.reversal_hold_Jpkg = s.energy_Jpkg - 0.3 * (s.energy_Jpkg - e_taem);
  const Prediction hold = c.planner->predict_profile(s, bank, 1.0, nullptr);
  ASSERT_TRUE(none.usable());
  ASSERT_TRUE(hold.usable());
  EXPECT_LT(none.along_m, 0.0);                    // long along the line of sight
  EXPECT_GT(hold.along_m, none.along_m + 100e3);   // the hold ends 100+ km shorter
  const double progress_none = kDistance_m - none.along_m, progress_hold = kDistance_m - hold.along_m;
  EXPECT_LT(progress_hold, hold.range_flown_m - 50e3);  // the track turned off the line
  EXPECT_NEAR(progress_none, none.range_flown_m, 0.02 * none.range_flown_m);
}

// The plan finds the hold: every member of the family without it ends long by a brute-force
// scan; the replan recovers nine tenths of the least of those misses (along the line and across
// it) with a hold energy between the TAEM energy and now, its TAEM heading within the
// tolerance and its path maxima within the mission's limits or no worse than the family's.
TEST_F(PcReversalHold, OutOfTheFamilysReachTheHoldTakesTheRange) {
  // The replan from the same state starts from the first plan's hold (its miss is a step
  // function of the hold at the lateral logic's reversals).
  ASSERT_NE(c.planner->plan(s, *c.out), Status::kNonFinite);
  const Status st = c.planner->plan(s, *c.out);
  const PcPlanDiagnostics& d = c.planner->diagnostics();
  const double k = d.density_ratio;
  bank.sigma_glide_rad = c.planner->final_bank_rad(k);
  double least = 1e300;
  for (int i = 0; i <= 20; ++i) {
    bank.control = bank.control_max() * i / 20;
    const Prediction p = c.planner->predict_profile(s, bank, k, nullptr);
    ASSERT_TRUE(p.usable());
    ASSERT_LT(p.along_m, 0.0) << bank.control;  // long whatever the bank
    least = std::fmin(least, -p.along_m);
  }
  EXPECT_GT(least, 100e3);
  EXPECT_TRUE(st == Status::kOk || st == Status::kRangeTooLong) << to_string(st);
  EXPECT_GT(c.out->reversal_hold_energy_Jpkg, e_taem);
  EXPECT_LT(c.out->reversal_hold_energy_Jpkg, s.energy_Jpkg);
  EXPECT_LT(std::hypot(d.miss_along_m, d.miss_cross_m), 0.1 * least);
  EXPECT_LE(std::fabs(d.final_heading_err_rad), m.taem.heading_tol_rad);
  bank.control = d.control;  // the plan's member without the hold
  const Prediction family = c.planner->predict_profile(s, bank, k, nullptr);
  const PcLimits lim = pc_limits_from(c.setup_limits, 1.0, c.planner->params().drag_model_uncertainty);
  EXPECT_LE(d.best.q_max_Pa, std::fmax(lim.q_max_Pa, family.q_max_Pa));
  EXPECT_LE(d.best.heat_flux_max_Wpm2, std::fmax(lim.heat_flux_max_Wpm2, family.heat_flux_max_Wpm2));
  EXPECT_LE(d.best.aero_accel_max_mps2, std::fmax(lim.load_factor_max_mps2, family.aero_accel_max_mps2));
}

}  // namespace
}  // namespace reentry::fsw
