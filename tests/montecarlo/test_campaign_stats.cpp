// Campaign statistics against published/hand-computed values.
#include <gtest/gtest.h>

#include "campaign_stats.hpp"

namespace reentry::tools {
namespace {

TEST(CampaignStats, WilsonIntervalKnownValues) {
  // 99/100 at 95 %: [0.9455, 0.9982] (Wilson 1927; e.g. Brown, Cai & DasGupta 2001 tables).
  const Interval a = wilson_interval(99, 100);
  EXPECT_NEAR(a.low, 0.9455, 5e-5);
  EXPECT_NEAR(a.high, 0.9982, 5e-5);
  // 500/500: lower bound 1 - z^2/(n + z^2) = 0.99238, upper 1.
  const Interval b = wilson_interval(500, 500);
  EXPECT_NEAR(b.low, 500.0 / (500.0 + 1.959963984540054 * 1.959963984540054), 1e-12);
  EXPECT_DOUBLE_EQ(b.high, 1.0);
  // 0/10: [0, 0.2775].
  const Interval c = wilson_interval(0, 10);
  EXPECT_DOUBLE_EQ(c.low, 0.0);
  EXPECT_NEAR(c.high, 0.2775, 5e-5);
}

TEST(CampaignStats, PercentileInterpolatesBetweenRanks) {
  const std::vector<double> v = {5.0, 1.0, 4.0, 2.0, 3.0};
  EXPECT_DOUBLE_EQ(percentile(v, 0), 1.0);
  EXPECT_DOUBLE_EQ(percentile(v, 50), 3.0);
  EXPECT_DOUBLE_EQ(percentile(v, 100), 5.0);
  EXPECT_DOUBLE_EQ(percentile(v, 95), 4.8);   // rank 3.8 -> 4 + 0.8 (5 - 4)
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0}, 25), 1.25);
  EXPECT_TRUE(std::isnan(percentile({}, 50)));
}

}  // namespace
}  // namespace reentry::tools
