// The tools' statistics: one definition each, NaN on empty input.
#include "shared/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace antcd::shared {
namespace {

TEST(Statistics, EmptyInputIsNaN) {
  EXPECT_TRUE(std::isnan(mean({})));
  EXPECT_TRUE(std::isnan(median({})));
  EXPECT_TRUE(std::isnan(quantile({}, 0.99)));
}

TEST(Statistics, MeanAndMedian) {
  EXPECT_DOUBLE_EQ(mean({1, 2, 6}), 3);
  EXPECT_DOUBLE_EQ(median({5, 1, 3}), 3);
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);  // mean of the two middle values
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(median({1, inf}), inf);  // runs that never finished sort last
}

TEST(Statistics, QuantileIsNearestRank) {
  const std::vector<double> v{10, 20, 30, 40, 50, 60, 70, 80, 90, 100};
  EXPECT_DOUBLE_EQ(quantile(v, 0), 10);
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 50);  // nearest rank, not interpolated
  EXPECT_DOUBLE_EQ(quantile(v, 0.99), 100);
  EXPECT_DOUBLE_EQ(quantile(v, 1), 100);
  EXPECT_DOUBLE_EQ(quantile({7}, 0.99), 7);
}

}  // namespace
}  // namespace antcd::shared
