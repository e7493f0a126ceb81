// The synthetic S-Graph's harsh options, checked against the BIM they come from: a walk through
// doorways crosses no BIM wall under the truth and one through a plan wall does; moved, turned
// and missing walls are built as drawn; the plain options give the same graph with them off.
#include <gtest/gtest.h>

#include <random>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "is_graphs/matching/wall_crossings.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

using testing::ProjectBim;

Pose2 Truth(const SyntheticSGraph& s) {
  return {geometry::Yaw(s.bim_T_map), s.bim_T_map.translation().head<2>()};
}

SyntheticSGraphConfig Walked(const agraph::AGraph& g, std::mt19937_64& rng) {
  SyntheticSGraphConfig c;
  c.seed = rng();
  c.bim_T_map = RandomPlanarMotion(rng, 50.0);
  c.rooms = RandomConnectedRooms(g, 2 + static_cast<int>(rng() % 5), rng);
  c.walk = true;
  return c;
}

TEST(SyntheticHarsh, AWalkThroughDoorwaysCrossesNoPlanWallUnderTheTruth) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("office.ifc"));
  const WallCrossings crossings(*g, 0.4);
  std::mt19937_64 rng(7);
  int steps = 0, through = 0;
  for (int trial = 0; trial < 30; ++trial) {
    SyntheticSGraphConfig c = Walked(*g, rng);
    const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
    const auto path = WalkedPath(s.graph, 1.5);
    steps += static_cast<int>(path.size());
    const int storey = g->rooms[c.rooms.front()].storey;
    EXPECT_EQ(crossings.Count(path, Truth(s), storey), 0) << "trial " << trial;
    c.through_walls = 1;
    const SyntheticSGraph opened = MakeSyntheticSGraph(*g, c);
    const int n = crossings.Count(WalkedPath(opened.graph, 1.5), Truth(opened), storey);
    through += n > 0;
    EXPECT_LE(n, 3) << "trial " << trial;
  }
  EXPECT_GT(steps, 30 * 5);
  EXPECT_GT(through, 5) << "room sets sharing a plan wall to walk through";
}

TEST(SyntheticHarsh, MovedTurnedAndMissingWallsAreBuiltAsDrawn) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("office.ifc"));
  std::mt19937_64 rng(11);
  SyntheticSGraphConfig c = Walked(*g, rng);
  c.corridor_aspect = 0.0;  // every surface of a room is a plane
  c.moved_walls = 2;
  c.turned_walls = 1;
  c.missing_walls = 1;
  c.turned_wall_deg = 15.0;
  const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
  ASSERT_EQ(s.moved.size(), 2u);
  ASSERT_EQ(s.turned.size(), 1u);
  ASSERT_EQ(s.missing.size(), 1u);
  for (const auto& [sid, offset] : s.moved) {
    EXPECT_GE(std::abs(offset), 0.25);
    EXPECT_LE(std::abs(offset), 0.35);
  }
  int checked = 0;
  for (const auto& p : s.graph.planes) {
    const auto truth = s.plane_truth.find(p.id);
    if (truth == s.plane_truth.end()) continue;
    const agraph::WallSurface& a = g->surfaces[truth->second];
    EXPECT_NE(truth->second, s.missing.front()) << "a missing wall has no plane";
    const geometry::Plane in_bim = p.plane.Transformed(s.bim_T_map);
    const Eigen::Vector2d mid = 0.5 * (a.start + a.end);
    const double angle = std::atan2(a.plane.normal.head<2>().x() * in_bim.normal.y() -
                                        a.plane.normal.head<2>().y() * in_bim.normal.x(),
                                    a.plane.normal.head<2>().dot(in_bim.normal.head<2>()));
    const double offset = in_bim.normal.head<2>().dot(mid) - in_bim.d;
    if (s.moved.count(a.id)) {
      EXPECT_NEAR(-offset, s.moved.at(a.id), 1e-6);
      ++checked;
    } else if (s.turned.count(a.id)) {
      EXPECT_NEAR(angle, s.turned.at(a.id), 1e-9);
      ++checked;
      EXPECT_NEAR(offset, 0.0, 1e-6) << "turned about its middle";
    } else {
      EXPECT_NEAR(angle, 0.0, 1e-9);
      EXPECT_NEAR(offset, 0.0, 1e-6);
    }
  }
  EXPECT_EQ(checked, 3);
}

TEST(SyntheticHarsh, PlainOptionsGiveTheSameGraphWithTheHarshOnesOff) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("large.ifc"));
  std::mt19937_64 rng(3);
  SyntheticSGraphConfig c = Walked(*g, rng);
  c.walk = false;
  c.normal_noise_deg = 1.0;
  c.offset_noise = 0.03;
  c.extra_planes = 2;
  const SyntheticSGraph plain = MakeSyntheticSGraph(*g, c);
  c.walk = true;
  c.walk_noise = 0.1;
  const SyntheticSGraph walked = MakeSyntheticSGraph(*g, c);
  ASSERT_EQ(plain.graph.planes.size(), walked.graph.planes.size());
  for (size_t i = 0; i < plain.graph.planes.size(); ++i) {
    EXPECT_EQ(plain.graph.planes[i].plane.normal, walked.graph.planes[i].plane.normal);
    EXPECT_EQ(plain.graph.planes[i].plane.d, walked.graph.planes[i].plane.d);
  }
  EXPECT_TRUE(plain.graph.keyframes.empty());
  EXPECT_FALSE(walked.graph.keyframes.empty());
  const SyntheticSGraph again = MakeSyntheticSGraph(*g, c);
  ASSERT_EQ(again.graph.keyframes.size(), walked.graph.keyframes.size());
  for (size_t i = 0; i < again.graph.keyframes.size(); ++i)
    EXPECT_TRUE(again.graph.keyframes[i].pose.isApprox(walked.graph.keyframes[i].pose, 0.0));
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
