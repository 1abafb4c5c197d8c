// Statistics of a Monte Carlo campaign: the Wilson score interval of a success rate and
// percentiles with linear interpolation between order statistics (numpy's default).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace reentry::tools {

struct Interval {
  double low = 0.0;
  double high = 0.0;
};

/// Wilson score interval for `successes` out of `n` at the normal quantile z (1.96: 95 %).
inline Interval wilson_interval(int successes, int n, double z = 1.959963984540054) {
  if (n <= 0) return {0.0, 1.0};
  const double p = static_cast<double>(successes) / n;
  const double z2 = z * z;
  const double denom = 1.0 + z2 / n;
  const double centre = (p + z2 / (2.0 * n)) / denom;
  const double half = z * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n)) / denom;
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

/// p-th percentile (0..100) of the values, linear between closest ranks; NaN when empty.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double rank = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (rank - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace reentry::tools
