// Proposals from the first scans (issue 25): corners of wall planes (FindCorners), the motions
// corner pairs propose (ProposeMotions), and the matcher deciding on them before any room is
// closed: right where the walls seen are unique in the building, never a wrong UNIQUE where they
// are not (a randomized campaign of S-Graphs without rooms, printed seed).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/corner_proposals.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

FacingSegment Seg(Eigen::Vector2d a, Eigen::Vector2d b, Eigen::Vector2d n, int storey = 0) {
  return {a, b, n.normalized(), storey};
}

// The inside of a 4 m x 3 m room, normals into the room.
std::vector<FacingSegment> Room(int storey = 0) {
  return {Seg({0, 0}, {4, 0}, {0, 1}, storey), Seg({4, 0}, {4, 3}, {-1, 0}, storey),
          Seg({4, 3}, {0, 3}, {0, -1}, storey), Seg({0, 3}, {0, 0}, {1, 0}, storey)};
}

TEST(CornerProposals, CornersAreWhereAPlaneEndsAtAnother) {
  // Each wall ends at two corners: eight (one per wall end).
  const auto corners = FindCorners(Room(), 0.5);
  ASSERT_EQ(corners.size(), 8u);
  for (const Corner& c : corners) {
    const bool at_corner = (c.point - Eigen::Vector2d(0, 0)).norm() < 1e-9 ||
                           (c.point - Eigen::Vector2d(4, 0)).norm() < 1e-9 ||
                           (c.point - Eigen::Vector2d(4, 3)).norm() < 1e-9 ||
                           (c.point - Eigen::Vector2d(0, 3)).norm() < 1e-9;
    EXPECT_TRUE(at_corner) << c.point.transpose();
    // Inside a room, each wall's normal points along the other wall from the corner.
    EXPECT_NEAR(c.normal.dot(c.along), 0.0, 1e-9);
    EXPECT_GT(c.other.dot(c.along), 0.9);
  }
  // Seen with gaps (a plane ending 0.4 m short of the corner) it is still a corner; 0.8 m short
  // it is not; parallel planes and planes on another storey meet nowhere.
  EXPECT_EQ(FindCorners({Seg({0.4, 0}, {4, 0}, {0, 1}), Seg({0, 0.3}, {0, 3}, {1, 0})}, 0.5).size(),
            2u);
  EXPECT_EQ(FindCorners({Seg({0.8, 0}, {4, 0}, {0, 1}), Seg({0, 0.9}, {0, 3}, {1, 0})}, 0.5).size(),
            0u);
  EXPECT_EQ(FindCorners({Seg({0, 0}, {4, 0}, {0, 1}), Seg({0, 1}, {4, 1}, {0, -1})}, 0.5).size(),
            0u);
  EXPECT_EQ(
      FindCorners({Seg({0, 0}, {4, 0}, {0, 1}, 0), Seg({0, 0}, {0, 3}, {1, 0}, 1)}, 0.5).size(),
      0u);
  // A partition meeting a long wall in its middle (a T): only the partition ends there.
  const auto t = FindCorners({Seg({0, 0}, {8, 0}, {0, 1}), Seg({4, 0}, {4, 3}, {-1, 0})}, 0.5);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_TRUE(t[0].point.isApprox(Eigen::Vector2d(4, 0)));
  EXPECT_TRUE(t[0].normal.isApprox(Eigen::Vector2d(-1, 0)));
}

TEST(CornerProposals, CornerPairsProposeTheMotion) {
  // The room seen from M, where bim_T_map is a turn by 0.7 rad and a shift.
  const Pose2 truth{0.7, {12.0, -3.0}};
  const Pose2 inverse{-truth.yaw, -(truth.R().transpose() * truth.t)};
  std::vector<FacingSegment> seen;
  for (const auto& s : Room())
    seen.push_back({inverse.Apply(s.a), inverse.Apply(s.b), inverse.Rotate(s.normal), -1});
  const auto bim = FindCorners(Room(), 0.5);
  const auto proposals = ProposeMotions(FindCorners(seen, 0.5), bim, 8.0);
  // A 4 x 3 room fits itself twice: as it is and turned half round. Every corner votes for both.
  ASSERT_GE(proposals.size(), 2u);
  EXPECT_EQ(proposals[0].votes, 8);
  EXPECT_EQ(proposals[1].votes, 8);
  int found = 0;
  for (int k = 0; k < 2; ++k) {
    const Pose2& p = proposals[k].pose;
    if (AngleDistance(p.yaw, truth.yaw) < 1e-6 && (p.t - truth.t).norm() < 1e-6) ++found;
    if (AngleDistance(p.yaw, truth.yaw + M_PI) < 1e-6) ++found;
  }
  EXPECT_EQ(found, 2);
  // More distinct motions than allowed: none, and said so.
  bool too_many = false;
  EXPECT_TRUE(ProposeMotions(FindCorners(seen, 0.5), bim, 8.0, 1, &too_many).empty());
  EXPECT_TRUE(too_many);
  const int all = static_cast<int>(proposals.size());  // the two above and single-corner fits
  EXPECT_EQ(ProposeMotions(FindCorners(seen, 0.5), bim, 8.0, all, &too_many).size(),
            proposals.size());
  EXPECT_FALSE(too_many);
  // A convex corner (the outside of the room) never pairs with an inside one.
  std::vector<FacingSegment> outside;
  for (const auto& s : seen) outside.push_back({s.a, s.b, -s.normal, -1});
  EXPECT_TRUE(ProposeMotions(FindCorners(outside, 0.5), bim, 8.0).empty());
}

/// The S-Graph of `c` before any room is closed: its planes, keyframes, observations, no rooms.
SyntheticSGraph WithoutRooms(const agraph::AGraph& g, const SyntheticSGraphConfig& c);

// Before any room: the walls of the office's hall and the rooms seen through its doorways decide
// by themselves; planes with NaNs, a plane of zero length and doorways of rooms that do not
// exist are left out (warnings), the answer the same as without them.
TEST(CornerProposals, WallsAloneLocalizeAndBadPlanesAreLeftOut) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, testing::ProjectBim("rotated.ifc"));
  int hall = 0;
  for (const auto& r : g->rooms)
    if (r.doorways.size() > g->rooms[hall].doorways.size()) hall = r.id;
  SyntheticSGraphConfig c;
  c.rooms = {hall};
  c.bim_T_map = geometry::IsometryFromXYYaw(4.0, -9.0, 2.1);
  c.normal_noise_deg = 0.5;
  c.offset_noise = 0.02;
  c.walk = true;
  c.observations = true;
  for (int d : g->rooms[hall].doorways)
    for (int r : g->doorways[d].rooms)
      if (r != hall) c.seen_rooms.push_back(r);
  c.seed = 11;
  SyntheticSGraph s = WithoutRooms(*g, c);
  ASSERT_TRUE(s.graph.rooms.empty());
  GraphMatcher matcher;
  matcher.SetAGraph(*g);
  const GraphMatch clean = matcher.Match(s.graph);
  std::string why;
  ASSERT_EQ(clean.status, MatchStatus::kUnique) << clean.hypotheses << " hypotheses";
  EXPECT_TRUE(testing::MatchIsCorrect(clean, s, &why)) << why;
  EXPECT_TRUE(clean.room_pairs.empty());
  EXPECT_GE(clean.surface_pairs.size(), 6u);
  // Bad input added.
  sgraph::Plane nan_plane = s.graph.planes.front();
  nan_plane.id = 9001;
  nan_plane.start.x() = std::nan("");
  sgraph::Plane zero = s.graph.planes.front();
  zero.id = 9002;
  zero.end = zero.start;
  s.graph.planes.push_back(nan_plane);
  s.graph.planes.push_back(zero);
  sgraph::Doorway door;
  door.id = 77;
  door.position = Eigen::Vector3d(1.0, 2.0, 0.0);
  door.rooms = {5, 6};
  s.graph.doorways.push_back(door);
  matcher.ForgetHistory();
  const GraphMatch bad = matcher.Match(s.graph);
  EXPECT_EQ(bad.status, MatchStatus::kUnique);
  EXPECT_TRUE(bad.bim_T_map.isApprox(clean.bim_T_map, 1e-12));
  EXPECT_FALSE(bad.warnings.empty());
  // With the proposals off, the same walls without rooms give no answer.
  MatcherConfig rooms_only;
  rooms_only.proposals = false;
  GraphMatcher without(rooms_only);
  without.SetAGraph(*g);
  EXPECT_EQ(without.Match(s.graph).status, MatchStatus::kNone);
}

/// The S-Graph of `c` before any room is closed: its planes, keyframes, observations, no rooms.
SyntheticSGraph WithoutRooms(const agraph::AGraph& g, const SyntheticSGraphConfig& c) {
  SyntheticSGraph s = MakeSyntheticSGraph(g, c);
  s.graph.rooms.clear();
  s.graph.doorways.clear();
  s.room_truth.clear();
  return s;
}

// Walls seen from a walk, before any room is closed: 1-3 rooms walked, their walls and those of
// rooms seen through their doorways, noise, deviations, clutter, missing walls, all as in the
// harsh campaign. Never a wrong UNIQUE; the share decided is printed.
TEST(CornerProposals, ThousandRoomlessTrialsWithoutAWrongUniqueMatch) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.empty()) GTEST_SKIP() << "no building could be loaded (converter missing?)";
  const std::uint64_t seed = testing::CampaignSeed(20261125ull);
  std::cout << "[ roomless ] seed " << seed << " (set IS_GRAPHS_SEED to change)" << std::endl;
  RecordProperty("seed", std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int kTrials = 1000;
  std::vector<GraphMatcher> matchers(buildings.size());
  for (size_t b = 0; b < buildings.size(); ++b) matchers[b].SetAGraph(*buildings[b].second);
  testing::CampaignTally tally;
  const auto t0 = std::chrono::steady_clock::now();
  for (int trial = 0; trial < kTrials; ++trial) {
    const size_t b = std::uniform_int_distribution<size_t>(0, buildings.size() - 1)(rng);
    const agraph::AGraph& g = *buildings[b].second;
    SyntheticSGraphConfig c;
    c.seed = rng();
    c.bim_T_map = RandomPlanarMotion(rng, 100.0);
    const int max_rooms = std::min<int>(3, static_cast<int>(g.rooms.size()));
    c.rooms = RandomConnectedRooms(g, std::uniform_int_distribution<int>(1, max_rooms)(rng), rng);
    // (No mirror images here: a few rooms mirrored are often rooms the building has, mirrored
    // twins about a corridor; MatchingBuildings.MirrorImagesAreNeverUnique mirrors it whole.)
    c.normal_noise_deg = 3.0 * unit(rng);
    c.offset_noise = 0.05 * unit(rng);
    c.bim_deviation = 0.15 * unit(rng);
    c.moved_walls = unit(rng) < 0.4 ? 1 + static_cast<int>(2 * unit(rng)) : 0;
    c.turned_walls = unit(rng) < 0.3 ? 1 : 0;
    c.missing_walls = unit(rng) < 0.3 ? 1 + static_cast<int>(2 * unit(rng)) : 0;
    c.extra_planes = unit(rng) < 0.6 ? 1 + static_cast<int>(6 * unit(rng)) : 0;
    c.extra_rooms = unit(rng) < 0.3 ? 1 : 0;
    c.walk = true;
    c.walk_noise = 0.1 * unit(rng);
    for (int r : c.rooms)
      for (int d : g.rooms[r].doorways)
        if (d >= 0 && d < static_cast<int>(g.doorways.size()))
          for (int other : g.doorways[d].rooms)
            if (other >= 0 && unit(rng) < 0.5) c.seen_rooms.push_back(other);
    c.observations = true;
    const SyntheticSGraph s = WithoutRooms(g, c);
    const GraphMatch m = matchers[b].Match(s.graph);
    matchers[b].ForgetHistory();
    tally.Add(buildings[b].first, m, s,
              "trial " + std::to_string(trial) + " (" + buildings[b].first + ", " +
                  std::to_string(c.rooms.size()) + " rooms, S-Graph seed " +
                  std::to_string(c.seed) + ")");
  }
  tally.Print("roomless",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  RecordProperty("unique_share", std::to_string(static_cast<double>(tally.unique) / tally.trials));
  EXPECT_EQ(tally.wrong, 0);
  EXPECT_GT(tally.unique, tally.trials / 10) << "the proposals decide some";
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
