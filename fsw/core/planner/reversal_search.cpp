#include "planner/reversal_search.hpp"

#include <cmath>

#include "numerics/root_finding.hpp"
#include "planner/mission_geometry.hpp"

namespace reentry::fsw {
namespace {

// The search aims at this share of the crossrange tolerance, so that the length iteration's
// acceptance test has margin.
constexpr double kCrossrangeTargetShare = 0.25;
// Bracket ends and range resolution of the search, as shares of the total flown range.
constexpr double kSearchRangeShare = 1e-9;
constexpr int kSearchIterations = 60;
// A reversal range this many times the total range: no reversal.
constexpr double kNoReversalRangeFactor = 2.0;

TrackErrors end_errors(const ReversalSearchInput& in, const RopState& end) {
  return track_errors(in.start.lat, in.start.lon, in.azimuth_mission_rad, end.lat, end.lon);  // §7.4 steps 1-4
}

// Flies the reversal at s_rev and reports the end point's errors.
Status fly_and_measure(const ReversalSearchInput& in, int first_sign, double s_rev, RopTrack& base,
                       ReversalSearchResult& out) {
  RopFlight flight;
  const Status s = fly_reduced_order(in.sys, in.start, first_sign, s_rev, base, nullptr, flight);
  if (s != Status::kOk) return s;
  const TrackErrors te = end_errors(in, flight.end);
  out.crossrange_rad = te.crossrange_rad;
  out.downrange_rad = te.downrange_rad;
  return Status::kOk;
}

// No single reversal nulls the crossrange (typically just after a flown reversal, when the
// remaining turn is short). Best effort: the smallest crossrange of no reversal and the
// interval ends; accepted when it is a small fraction of the range to go, which the lateral
// corridor phase steers out, since a stale plan would be worse.
template <class Crossrange>
Status best_effort_reversal(const ReversalSearchInput& in, Crossrange& crossrange, double base_crossrange_rad,
                            double s_lo, double s_hi, int first_sign, double& s_rev_m, RopTrack& base,
                            ReversalSearchResult& out) {
  double best_s = kNoReversalRangeFactor * in.sys.range.s_total_m, best_abs = std::fabs(base_crossrange_rad);
  const double ends[2] = {s_lo, s_hi};
  for (double s_end : ends) {
    const double c = crossrange(s_end);
    if (std::isfinite(c) && std::fabs(c) < best_abs) {
      best_abs = std::fabs(c);
      best_s = s_end;
    }
  }
  if (!(best_abs < in.best_effort_crossrange_fraction * in.b_mission_rad)) {
    out.lateral_unreachable = true;
    return Status::kNoBracket;
  }
  s_rev_m = best_s;
  const Status s = fly_and_measure(in, first_sign, s_rev_m, base, out);
  if (s == Status::kOk) out.best_effort = true;
  return s;
}

}  // namespace

Status bank_reversal_search(const ReversalSearchInput& in, int& first_sign, double& s_rev_m, RopTrack& base,
                            ReversalSearchResult& out) {
  out.best_effort = false;
  out.lateral_unreachable = false;
  out.evaluations = 0;
  const double s_total = in.sys.range.s_total_m;
  if (!(s_total > 0.0) || !std::isfinite(s_total)) return Status::kNonFinite;
  RopFlight flight;
  Status s = fly_reduced_order(in.sys, in.start, first_sign, kNoReversalRangeFactor * s_total, base, nullptr, flight);
  if (s != Status::kOk) return s;
  int evaluations = 1;
  const double f_tol = kCrossrangeTargetShare * in.crossrange_tol_m / in.r_mean_m;
  const TrackErrors no_reversal = end_errors(in, flight.end);
  if (in.planning_energy_Jpkg <= in.sys.corridor_energy_Jpkg || std::fabs(no_reversal.crossrange_rad) < f_tol) {
    // Planning inside the corridor phase, where the tracker steers laterally and a planned
    // reversal has no effect (or already on target): no reversal to search.
    s_rev_m = kNoReversalRangeFactor * s_total;
    out.crossrange_rad = no_reversal.crossrange_rad;
    out.downrange_rad = no_reversal.downrange_rad;
    out.evaluations = evaluations;
    return Status::kOk;
  }
  auto crossrange = [&](double s_trial) {  // a2 at the end for a reversal at s_trial
    ++evaluations;
    RopFlight f;
    if (fly_reduced_order(in.sys, in.start, first_sign, s_trial, base, nullptr, f) != Status::kOk) return std::nan("");
    return end_errors(in, f.end).crossrange_rad;
  };
  // Reversal range from (just after) the planning point to the end.
  const double s_lo = kSearchRangeShare * s_total, s_hi = s_total * (1.0 - kSearchRangeShare);
  const double s_tol = kSearchRangeShare * s_total;
  numerics::RootResult root = numerics::brent(crossrange, s_lo, s_hi, s_tol, kSearchIterations, f_tol);
  Status st = to_status(root.status);
  if (st == Status::kNoBracket) {
    // The quadrant rule (fig. 7.20) picks the first turn from the heading offset alone; after
    // a long wings-level descent (or with a large offset) the one-reversal solution may need
    // the opposite first turn. Try it once before reporting that no reversal exists.
    first_sign = -first_sign;
    root = numerics::brent(crossrange, s_lo, s_hi, s_tol, kSearchIterations, f_tol);
    st = to_status(root.status);
    if (st != Status::kOk) first_sign = -first_sign;
  }
  out.evaluations = evaluations;
  if (st == Status::kNoBracket) {
    return best_effort_reversal(in, crossrange, no_reversal.crossrange_rad, s_lo, s_hi, first_sign, s_rev_m, base, out);
  }
  if (st != Status::kOk) return st;
  s_rev_m = root.x;
  return fly_and_measure(in, first_sign, s_rev_m, base, out);
}

}  // namespace reentry::fsw
