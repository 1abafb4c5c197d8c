#include "predictor_corrector/corrector.hpp"

#include <cmath>

namespace reentry::fsw {
namespace {

constexpr double kFarTooLong_m = -1e7;           // z of a prediction that skips out or times out
constexpr double kMaxStep_rad = 45.0 * M_PI / 180.0;

}  // namespace

Corrector::Point Corrector::evaluate(double x) {
  bank_.control = x;
  const Prediction pr = predictor_->run(*start_, bank_, scratch_);
  ++result_.predictions;
  Point pt;
  pt.x = x;
  if (pr.usable()) {
    pt.z = pr.along_m;
    pt.valid = true;
    if (!have_best_ || std::fabs(pr.along_m) < std::fabs(result_.best.along_m)) {
      result_.best = pr;
      result_.control = x;
      result_.sigma0_rad = bank_.sigma0_rad();
      result_.alpha_shift_rad = bank_.alpha_shift_rad();
      have_best_ = true;
      if (best_profile_ != nullptr && scratch_ != nullptr) *best_profile_ = *scratch_;
    }
  } else if (pr.end == PredictionEnd::kSkipOut || pr.end == PredictionEnd::kTimeOut) {
    pt.z = kFarTooLong_m;
    pt.valid = true;
  }
  if (pt.valid && pt.z < 0.0 && (!have_neg_ || pt.x > neg_.x)) {
    neg_ = pt;
    have_neg_ = true;
    illinois_side_ = illinois_side_ == -1 ? -2 : -1;
  } else if (pt.valid && pt.z > 0.0 && (!have_pos_ || pt.x < pos_.x)) {
    pos_ = pt;
    have_pos_ = true;
    illinois_side_ = illinois_side_ == 1 ? 2 : 1;
  }
  return pt;
}

double Corrector::next_guess(const Point& prev, const Point& cur) const {
  const PredictorCorrectorParams& p = *params_;
  if (have_neg_ && have_pos_ && neg_.x < pos_.x) {
    // Illinois regula falsi inside the bracket: the end not replaced twice has its z halved.
    double zn = neg_.z, zp = pos_.z;
    if (illinois_side_ == 2) zn *= 0.5;
    if (illinois_side_ == -2) zp *= 0.5;
    const double x = neg_.x - zn * (pos_.x - neg_.x) / (zp - zn);
    const double lo = neg_.x + 0.02 * (pos_.x - neg_.x), hi = pos_.x - 0.02 * (pos_.x - neg_.x);
    return std::isfinite(x) ? clamp(x, lo, hi) : 0.5 * (neg_.x + pos_.x);
  }
  // Secant while the slope has the expected sign (z rises with sigma_0), else a fixed step
  // towards the root; the step is bounded.
  double dx = cur.z > 0.0 ? -p.first_step_rad : p.first_step_rad;
  if (prev.valid && cur.valid && cur.x != prev.x) {
    const double slope = (cur.z - prev.z) / (cur.x - prev.x);
    if (slope > 0.0 && std::isfinite(slope)) dx = -cur.z / slope;
  }
  dx = std::copysign(clamp(std::fabs(dx), 1e-4, kMaxStep_rad), dx);
  return cur.x + dx;
}

CorrectorResult Corrector::solve(const Predictor& predictor, const PredictionStart& start, BankProfile bank,
                                 const PredictorCorrectorParams& params, int max_predictions,
                                 ReferenceProfile* best_profile, ReferenceProfile* scratch) {
  predictor_ = &predictor;
  start_ = &start;
  params_ = &params;
  bank_ = bank;
  best_profile_ = best_profile;
  scratch_ = scratch;
  result_ = CorrectorResult{};
  have_best_ = have_neg_ = have_pos_ = false;
  illinois_side_ = 0;
  const double lo = 0.0, hi = bank.control_max();
  Point prev;
  Point cur = evaluate(clamp(bank.control, lo, hi));
  Status status = Status::kNotConverged;
  while (result_.predictions < max_predictions) {
    if (have_best_ && std::fabs(result_.best.along_m) <= params.miss_tol_m) {
      status = Status::kOk;
      break;
    }
    // A bracket narrower than the control tolerance holds a jump of z (a reversal more or
    // less), not a root the predictions can refine: the best side is the answer.
    if (have_neg_ && have_pos_ && std::fabs(pos_.x - neg_.x) < params.control_tol_rad) break;
    // Out of reach: the bound that flies farthest (0) is still short, or the shortest
    // (bank_max) still long; z is monotonic in sigma_0 there.
    if (cur.valid && cur.x <= lo && cur.z > 0.0) {
      status = Status::kRangeTooShort;
      break;
    }
    if (cur.valid && cur.x >= hi && cur.z < 0.0) {
      status = Status::kRangeTooLong;
      break;
    }
    double x = cur.valid ? next_guess(prev, cur) : 0.5 * (cur.x + result_.control);
    x = clamp(x, lo, hi);
    Point next = evaluate(x);
    // Step halving (Lu 2014): a step that made |z| worse without crossing the root is halved
    // back towards the point it started from.
    for (int i = 0; i < 4 && result_.predictions < max_predictions && next.valid && cur.valid &&
                    next.z * cur.z > 0.0 && std::fabs(next.z) > std::fabs(cur.z);
         ++i) {
      next = evaluate(cur.x + 0.5 * (next.x - cur.x));
    }
    prev = cur;
    cur = next;
  }
  if (!have_best_) {
    status = Status::kNonFinite;
  } else if (status == Status::kNotConverged && std::fabs(result_.best.along_m) <= params.miss_tol_m) {
    status = Status::kOk;
  } else if (status == Status::kNotConverged && have_neg_ != have_pos_) {
    // Out of predictions and never across the root: the least miss found, and which way.
    status = have_pos_ ? Status::kRangeTooShort : Status::kRangeTooLong;
  }
  result_.status = status;
  result_.converged = status == Status::kOk;
  return result_;
}

}  // namespace reentry::fsw
