// Timings of the thesis ch. 4 numerics: spline evaluation with/without a warm hint, Brent root
// finding, one RKF5(6)/RKF7(8) step of a 6-state two-body problem.
#include <benchmark/benchmark.h>

#include <cmath>

#include "physics/earth_constants.hpp"
#include "numerics/cubic_spline.hpp"
#include "numerics/root_finding.hpp"
#include "numerics/runge_kutta.hpp"

namespace rn = reentry::numerics;

namespace {

constexpr int kKnots = 1001;

const rn::NaturalCubicSpline<kKnots>& atmosphere_like_spline() {
  static rn::NaturalCubicSpline<kKnots> s = [] {
    rn::NaturalCubicSpline<kKnots> sp;
    double h[kKnots];
    double ln_rho[kKnots];
    for (int i = 0; i < kKnots; ++i) {
      h[i] = 100.0 * i;  // altitude_m
      ln_rho[i] = std::log(1.225) - h[i] / 7200.0;
    }
    sp.fit(h, ln_rho, kKnots);
    return sp;
  }();
  return s;
}

void BM_SplineMonotoneSweep(benchmark::State& state) {
  const auto& s = atmosphere_like_spline();
  double altitude_m = 0.0;
  for (auto _ : state) {
    altitude_m += 7.3;
    if (altitude_m > 100000.0) altitude_m = 0.0;
    benchmark::DoNotOptimize(s.value(altitude_m));
  }
}
BENCHMARK(BM_SplineMonotoneSweep);

void BM_SplineRandomAccess(benchmark::State& state) {
  const auto& s = atmosphere_like_spline();
  unsigned long seed = 12345;
  for (auto _ : state) {
    seed = seed * 6364136223846793005UL + 1442695040888963407UL;
    const double altitude_m = 100000.0 * static_cast<double>(seed >> 11) / 9007199254740992.0;
    int hint = -1;
    benchmark::DoNotOptimize(s.value(altitude_m, &hint));
  }
}
BENCHMARK(BM_SplineRandomAccess);

void BM_BrentCosMinusCube(benchmark::State& state) {
  for (auto _ : state) {
    const auto r = rn::brent([](double x) { return std::cos(x) - x * x * x; }, 0.0, 1.0, 1e-14, 100);
    benchmark::DoNotOptimize(r.x);
  }
}
BENCHMARK(BM_BrentCosMinusCube);

struct TwoBody {
  void operator()(double, const rn::State<6>& s, rn::State<6>& d) const {
    const double r = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    const double k = -reentry::physics::kMuEarth_m3ps2 / (r * r * r);
    for (int i = 0; i < 3; ++i) {
      d[i] = s[i + 3];
      d[i + 3] = k * s[i];
    }
  }
};

void BM_RkfStep(benchmark::State& state) {
  const rn::EmbeddedRungeKutta<6> rk(state.range(0) == 56 ? rn::RkfMethod::kRkf56 : rn::RkfMethod::kRkf78);
  const auto tol = rn::RkfTolerances<6>::uniform(1e-6, 1e-12);
  const rn::State<6> y{6.3e6, 0.0, 0.0, 0.0, 8.2e3, 0.0};
  for (auto _ : state) {
    const auto s = rk.step(TwoBody{}, 0.0, y, 10.0, tol);
    benchmark::DoNotOptimize(s.y);
  }
}
BENCHMARK(BM_RkfStep)->Arg(56)->Arg(78);

}  // namespace

BENCHMARK_MAIN();
