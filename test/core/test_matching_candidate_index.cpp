// CandidateIndex must return every candidate RoomPairConsistency can accept (a superset), in
// list order, so that a grow through the index joins the same rooms as a scan of the list.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <random>

#include "is_graphs/matching/candidate_graph.h"
#include "is_graphs/matching/candidate_index.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/pairwise_consistency.h"

namespace is_graphs {
namespace matching {
namespace {

TEST(CandidateIndex, ConsistencyRadiusBoundsTheTest) {
  // At the radius the test's own tolerance (2c + k·|da|, |da| = |ds| + radius) is met exactly.
  const double c = 0.6, k = 0.035, ds = 12.0;
  const double r = ConsistencyRadius(ds, c, k);
  EXPECT_NEAR(r, 2.0 * c + k * (ds + r), 1e-6);
  EXPECT_TRUE(std::isinf(ConsistencyRadius(ds, c, 1.0)));
}

TEST(CandidateIndex, NearHoldsEveryConsistentCandidateInListOrder) {
  const char* env = std::getenv("IS_GRAPHS_SEED");
  const std::uint64_t seed = env && *env ? std::strtoull(env, nullptr, 10) : 4242ull;
  std::cout << "[ index ] seed " << seed << " (set IS_GRAPHS_SEED to change)" << std::endl;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coord(-60.0, 60.0), yaw(-M_PI, M_PI), unit(0.0, 1.0);
  MatcherConfig config;
  int checked = 0, accepted = 0, accepted_off = 0, returned = 0;
  for (int trial = 0; trial < 40; ++trial) {
    config.centre_tolerance = trial % 2 ? 0.6 : 1.2;  // the matcher's and the doubter's gate
    std::vector<RoomDescriptor> a_rooms(150 + trial);
    for (auto& a : a_rooms) a.centre = {coord(rng), 0.3 * coord(rng)};
    std::vector<RoomDescriptor> s_rooms(6);
    std::vector<std::vector<RoomCandidate>> candidates(s_rooms.size());
    for (size_t i = 0; i < s_rooms.size(); ++i) {
      s_rooms[i].centre = {0.2 * coord(rng), 0.2 * coord(rng)};
      for (int n = 0; n < 120; ++n) {
        RoomCandidate c;
        c.s_room = static_cast<int>(i);
        c.a_room = static_cast<int>(rng() % a_rooms.size());
        c.pose.yaw = yaw(rng);
        c.full_rank = unit(rng) < 0.97;  // a few corridor (axis-free) candidates
        // Rooms paired through their walls: indexed where their S-centre goes, on the grid of
        // the A-centres or beyond it (y out to ±27 m, the A-centres to ±18).
        c.centre_off = c.full_rank && unit(rng) < 0.25;
        c.at = {coord(rng), 0.45 * coord(rng)};
        candidates[i].push_back(c);
      }
    }
    const CandidateIndex index(candidates, a_rooms);
    std::vector<int> near;
    for (size_t si = 0; si < s_rooms.size(); ++si)
      for (const RoomCandidate& seed_c : candidates[si]) {
        if (!seed_c.full_rank) continue;
        const RoomCorrespondence seed_corr =
            ToCorrespondence(seed_c, s_rooms[si], a_rooms[seed_c.a_room]);
        for (size_t sj = 0; sj < s_rooms.size(); ++sj) {
          if (sj == si) continue;
          const Eigen::Vector2d ds = s_rooms[sj].centre - seed_corr.s_centre;
          const Eigen::Vector2d predicted =
              seed_corr.a_centre + Pose2{seed_corr.yaw, Eigen::Vector2d::Zero()}.Rotate(ds);
          index.Near(static_cast<int>(sj), predicted,
                     ConsistencyRadius(ds.norm(), config.centre_tolerance, config.lever_arm_slack),
                     &near);
          ASSERT_TRUE(std::is_sorted(near.begin(), near.end()));
          ASSERT_EQ(std::adjacent_find(near.begin(), near.end()), near.end()) << "a duplicate";
          for (size_t k = 0; k < candidates[sj].size(); ++k) {
            const RoomCandidate& c = candidates[sj][k];
            const double w = RoomPairConsistency(
                seed_corr, ToCorrespondence(c, s_rooms[sj], a_rooms[c.a_room]), config);
            ++checked;
            if (w == 0.0) continue;
            ++accepted;
            accepted_off += c.centre_off;
            ASSERT_TRUE(std::binary_search(near.begin(), near.end(), static_cast<int>(k)))
                << "seed " << seed << " trial " << trial << ": candidate " << k
                << " is consistent but not returned";
          }
          returned += static_cast<int>(near.size());
        }
      }
  }
  std::cout << "[ index ] " << checked << " pairs checked, " << accepted << " consistent ("
            << accepted_off << " through their walls), " << returned << " returned" << std::endl;
  EXPECT_GT(accepted, 100);          // the property was exercised
  EXPECT_GT(accepted_off, 20);       // for rooms paired through their walls too
  EXPECT_LT(returned, checked / 5);  // and the index prunes
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
