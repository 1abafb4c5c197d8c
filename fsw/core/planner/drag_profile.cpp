#include "planner/drag_profile.hpp"

#include <cmath>

#include "numerics/root_finding.hpp"

namespace reentry::fsw {
namespace {

// Below |Db/Da - 1| of this, (C.9) is evaluated by its series (ln(1+x)/x to x^3).
constexpr double kSegmentSeriesLimit = 1e-5;
// Level solve (7.12): Brent in ln(Dc), resolution in ln(Dc), iteration bound, length tolerance.
constexpr double kLevelLogTol = 1e-12;
constexpr int kLevelIterations = 100;
constexpr double kLevelLengthTol_m = 1e-6;

// Dc such that profile.length_m() == s_m (7.12), in ln(Dc) for a well-scaled bracket.
template <class Profile>
Status solve_level_for_length(Profile& profile, double s_m, double dc_min, double dc_max) {
  Profile trial = profile;
  auto residual = [&](double log_dc) {
    trial.d_c = std::exp(log_dc);
    return s_m - trial.length_m();
  };
  const numerics::RootResult root =
      numerics::brent(residual, std::log(dc_min), std::log(dc_max), kLevelLogTol, kLevelIterations, kLevelLengthTol_m);
  if (root.status != numerics::NumStatus::kOk) return to_status(root.status);
  profile.d_c = std::exp(root.x);
  return profile.valid() ? Status::kOk : Status::kNonFinite;
}

}  // namespace

double linear_segment_length(double delta_energy, double d_a, double d_b) {
  // int dE / (Da + (Db - Da) u) = dE ln(Db / Da) / (Db - Da)  (C.9)
  const double x = d_b / d_a - 1.0;
  if (std::fabs(x) < kSegmentSeriesLimit) return delta_energy / d_a * (1.0 - x / 2.0 + x * x / 3.0 - x * x * x / 4.0);
  return delta_energy * std::log(d_b / d_a) / (d_b - d_a);
}

bool ThreeSegmentProfile::valid() const {
  return e_i > e_1 && e_1 >= e_2 && e_2 > e_f && d_i > 0.0 && d_c > 0.0 && d_f > 0.0 &&
         std::isfinite(e_i + e_1 + e_2 + e_f + d_i + d_c + d_f);
}

double ThreeSegmentProfile::drag(double energy) const {
  if (energy >= e_1) return d_c + (d_i - d_c) / (e_i - e_1) * (energy - e_1);   // (C.4)
  if (energy >= e_2) return d_c;                                             // (C.5)
  return d_f + (d_c - d_f) / (e_2 - e_f) * (energy - e_f);                   // (C.6)
}

double ThreeSegmentProfile::slope(double energy) const {
  if (energy >= e_1) return (d_i - d_c) / (e_i - e_1);
  if (energy >= e_2) return 0.0;
  return (d_c - d_f) / (e_2 - e_f);
}

double ThreeSegmentProfile::length_m() const {
  // (7.11): (E1-Ei)/(Di-Dc) ln(Dc/Di) + (E1-E2)/Dc + (Ef-E2)/(Dc-Df) ln(Df/Dc)
  return linear_segment_length(e_i - e_1, d_i, d_c) + (e_1 - e_2) / d_c + linear_segment_length(e_2 - e_f, d_c, d_f);
}

Status ThreeSegmentProfile::solve_constant_drag(double s_m, double dc_min, double dc_max) {
  return solve_level_for_length(*this, s_m, dc_min, dc_max);  // (7.12)
}

bool SmoothProfile::valid() const {
  return e_i > e_f && d_i > 0.0 && d_c > 0.0 && d_f > 0.0 && std::isfinite(e_i + e_f + d_i + d_c + d_f);
}

namespace {
// Value, d/dx and d2/dx2 of the quartic Bernstein profile.
void bernstein(double di, double dc, double df, double x, double& v, double& v1, double& v2) {
  const double y = 1.0 - x;
  const double b0 = y * y * y * y, b4 = x * x * x * x;
  const double inner = 1.0 - b0 - b4;  // B1 + B2 + B3
  v = di * b0 + dc * inner + df * b4;
  const double db0 = -4.0 * y * y * y, db4 = 4.0 * x * x * x;
  v1 = di * db0 - dc * (db0 + db4) + df * db4;
  const double ddb0 = 12.0 * y * y, ddb4 = 12.0 * x * x;
  v2 = di * ddb0 - dc * (ddb0 + ddb4) + df * ddb4;
}
}  // namespace

double SmoothProfile::drag(double energy) const {
  double v, v1, v2;
  bernstein(d_i, d_c, d_f, (e_i - energy) / (e_i - e_f), v, v1, v2);
  return v;
}

double SmoothProfile::slope(double energy) const {
  double v, v1, v2;
  bernstein(d_i, d_c, d_f, (e_i - energy) / (e_i - e_f), v, v1, v2);
  return -v1 / (e_i - e_f);
}

double SmoothProfile::curvature(double energy) const {
  double v, v1, v2;
  const double de = e_i - e_f;
  bernstein(d_i, d_c, d_f, (e_i - energy) / de, v, v1, v2);
  return v2 / (de * de);
}

double SmoothProfile::length_m() const {
  static constexpr double kNode[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  static constexpr double kWeight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
  const double h = 1.0 / kPanels;
  double sum = 0.0;
  for (int p = 0; p < kPanels; ++p) {
    const double mid = (p + 0.5) * h;
    for (int q = 0; q < 5; ++q) {
      double v, v1, v2;
      bernstein(d_i, d_c, d_f, mid + 0.5 * h * kNode[q], v, v1, v2);
      sum += kWeight[q] * 0.5 * h / v;
    }
  }
  return (e_i - e_f) * sum;  // S = -int_Ei^Ef dE / D (7.10)
}

Status SmoothProfile::solve_level(double s_m, double dc_min, double dc_max) {
  return solve_level_for_length(*this, s_m, dc_min, dc_max);
}

}  // namespace reentry::fsw
