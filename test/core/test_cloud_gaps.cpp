// CloudGapCounter: a 10 Hz sensor with jittered stamps; clouds left out are counted from the gaps
// once the period is learnt, a restarted bag starts over.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "is_graphs/sgraph/cloud_gaps.h"

namespace is_graphs {
namespace sgraph {
namespace {

TEST(CloudGapCounter, CountsTheCloudsLeftOut) {
  const unsigned seed = 7;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  CloudGapCounter gaps;
  int left_out = 0;
  for (int k = 0; k < 600; ++k) {
    // Every 7th of the clouds after the first 20 dropped, and 3 in a row at k = 300.
    const bool dropped = (k > 20 && k % 7 == 0) || (k >= 300 && k < 303);
    if (dropped) {
      ++left_out;
      continue;
    }
    gaps.Add(1000.0 + 0.1 * k + jitter(rng));
  }
  EXPECT_EQ(gaps.missing(), left_out);
  EXPECT_NEAR(gaps.period(), 0.1, 0.005);
}

TEST(CloudGapCounter, NothingMissingOnAFullStreamAndTimeGoingBackStartsOver) {
  CloudGapCounter gaps;
  for (int k = 0; k < 100; ++k) EXPECT_EQ(gaps.Add(10.0 + 0.1 * k), 0) << k;
  EXPECT_EQ(gaps.Add(5.0), 0);  // the bag restarted
  EXPECT_DOUBLE_EQ(gaps.period(), 0.0);
  EXPECT_EQ(gaps.Add(5.3), 0);  // no period yet: nothing counted
  EXPECT_EQ(gaps.missing(), 0);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
