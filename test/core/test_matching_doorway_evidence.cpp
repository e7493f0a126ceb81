// Doorways as evidence: DoorwayEvidence on a hand-made A-Graph (position, width, rooms, storey,
// one pair per A-doorway), the S-Graph's doorways that cannot be weighed (warned about, left
// out, never a crash or a claimed match), and the matcher pairing the doorways of a walk through
// the office with the BIM's under the true motion.
#include <gtest/gtest.h>

#include <limits>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/doorway_evidence.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

agraph::Doorway Door(int id, Eigen::Vector2d at, double width, std::vector<int> rooms,
                     int storey = 0) {
  agraph::Doorway d;
  d.id = id;
  d.position = Eigen::Vector3d(at.x(), at.y(), 0.0);
  d.width = width;
  d.rooms = std::move(rooms);
  d.storey = storey;
  return d;
}

// Doors between rooms 0|1 at (4, 2.5), 1|2 at (4, 7), and one of storey 1 at (4, 2.5).
agraph::AGraph Doors() {
  agraph::AGraph g;
  g.doorways = {Door(0, {4.0, 2.5}, 0.9, {0, 1}), Door(1, {4.0, 7.0}, 0.9, {1, 2}),
                Door(2, {4.0, 2.5}, 0.9, {5, 6}, 1)};
  return g;
}

SDoorwayView SDoor(int id, Eigen::Vector2d at, double width, std::vector<int> rooms) {
  return {id, at, width, std::move(rooms)};
}

TEST(DoorwayEvidence, PairsByPositionWidthRoomsAndStorey) {
  const DoorwayEvidence evidence(Doors(), MatcherConfig{});
  const Pose2 identity;
  const std::map<int, int> rooms{{10, 0}, {11, 1}};
  // 0.1414 m off door 0, width unknown: paired, score exp(-0.5 (0.1414 / 0.25)^2).
  auto pairs = evidence.Pairs({SDoor(3, {4.1, 2.6}, 0.0, {10, 11})}, identity, 0, rooms);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].a_id, 0);
  EXPECT_EQ(pairs[0].s_id, 3);
  EXPECT_NEAR(pairs[0].score, std::exp(-0.5 * 0.02 / 0.0625), 1e-9);
  // Its room paired with an A-room the door does not open into: no pair.
  EXPECT_TRUE(evidence.Pairs({SDoor(3, {4.1, 2.6}, 0.0, {10})}, identity, 0, {{10, 2}}).empty());
  // An unpaired S-room does not constrain.
  EXPECT_EQ(evidence.Pairs({SDoor(3, {4.1, 2.6}, 0.0, {12})}, identity, 0, rooms).size(), 1u);
  // Too wide, too far, another storey, or moved by the motion: none.
  EXPECT_TRUE(evidence.Pairs({SDoor(3, {4.0, 2.5}, 1.5, {10})}, identity, 0, rooms).empty());
  EXPECT_EQ(evidence.Pairs({SDoor(3, {4.0, 2.5}, 1.1, {10})}, identity, 0, rooms).size(), 1u);
  EXPECT_TRUE(evidence.Pairs({SDoor(3, {4.0, 3.1}, 0.0, {10})}, identity, 0, rooms).empty());
  EXPECT_TRUE(evidence.Pairs({SDoor(3, {4.0, 2.5}, 0.0, {10})}, identity, 3, rooms).empty());
  EXPECT_TRUE(
      evidence.Pairs({SDoor(3, {4.0, 2.5}, 0.0, {10})}, Pose2{0.0, {0.0, 1.0}}, 0, rooms).empty());
  // A half turn about (4, 4.75) takes door 0 onto door 1 (if the rooms allow it).
  const Pose2 half_turn{M_PI, {8.0, 9.5}};
  pairs = evidence.Pairs({SDoor(3, {4.0, 2.5}, 0.0, {})}, half_turn, 0, {});
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].a_id, 1);
  EXPECT_NEAR(pairs[0].score, 1.0, 1e-9);
}

TEST(DoorwayEvidence, EachADoorwayPairsOnceNearestFirst) {
  const DoorwayEvidence evidence(Doors(), MatcherConfig{});
  const auto pairs = evidence.Pairs(
      {SDoor(1, {4.3, 2.5}, 0.0, {}), SDoor(2, {4.05, 2.5}, 0.0, {}), SDoor(3, {4.0, 7.0}, 0, {})},
      Pose2{}, 0, {});
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].s_id, 3);  // in order of distance: 0 m, then 0.05 m
  EXPECT_EQ(pairs[1].s_id, 2);
  EXPECT_EQ(pairs[1].a_id, 0);
  EXPECT_NEAR(evidence.Explained({SDoor(1, {4.3, 2.5}, 0.0, {}), SDoor(2, {4.05, 2.5}, 0.0, {})},
                                 Pose2{}, 0, {}),
              std::exp(-0.5 * 0.04), 1e-9);
}

TEST(DoorwayEvidence, DoorwaysThatCannotBeWeighedAreNamedAndLeftOut) {
  sgraph::SGraph s;
  s.revision = 4;
  sgraph::Room r;
  r.id = 2;
  s.rooms = {r};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  sgraph::Doorway good, at_nan, wide_nan, unknown_room, no_room;
  good.id = 1, good.rooms = {2};
  at_nan = good, at_nan.id = 2, at_nan.position.x() = nan;
  wide_nan = good, wide_nan.id = 3, wide_nan.width = nan;
  unknown_room = good, unknown_room.id = 4, unknown_room.rooms = {2, 9};
  no_room = good, no_room.id = 5, no_room.rooms.clear();
  s.doorways = {good, at_nan, wide_nan, unknown_room, no_room};
  std::vector<std::string> warnings;
  const auto usable = UsableDoorways(s, &warnings);
  ASSERT_EQ(usable.size(), 1u);
  EXPECT_EQ(usable[0].id, 1);
  ASSERT_EQ(warnings.size(), 4u);
  EXPECT_EQ(warnings[0], "S-Graph rev 4: doorway 2: non-finite position or width (ignored)");
  EXPECT_EQ(warnings[1], "S-Graph rev 4: doorway 3: non-finite position or width (ignored)");
  EXPECT_EQ(warnings[2], "S-Graph rev 4: doorway 4: names room 9 which does not exist (ignored)");
  EXPECT_EQ(warnings[3], "S-Graph rev 4: doorway 5: between no rooms (ignored)");
  s.rooms.clear();
  warnings.clear();
  EXPECT_TRUE(UsableDoorways(s, &warnings).empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "S-Graph rev 4: 5 doorways but no rooms (doorways ignored)");
}

SyntheticSGraphConfig OfficeWalk(const agraph::AGraph& g) {
  SyntheticSGraphConfig c;
  c.rooms = {testing::RoomByName(g, "Corridor"), testing::RoomByName(g, "112"),
             testing::RoomByName(g, "113"), testing::RoomByName(g, "Meeting")};
  c.bim_T_map = geometry::IsometryFromXYYaw(-3.0, 14.0, 0.7);
  c.normal_noise_deg = 0.5;
  c.offset_noise = 0.02;
  c.walk = true;
  c.walk_noise = 0.05;
  c.doorways = true;
  c.seed = 11;
  return c;
}

// The walk's doorways, found as the S-Graph node finds them, pair with the BIM's doorways they
// went through: each S-doorway's pair is the A-doorway nearest its true place.
TEST(MatchingDoorways, TheWalkedDoorwaysPairWithTheBimsUnderTheTruth) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, testing::ProjectBim("office.ifc"));
  const SyntheticSGraph s = MakeSyntheticSGraph(*g, OfficeWalk(*g));
  ASSERT_GE(s.graph.doorways.size(), 3u) << "the walk goes through three doors at least";
  GraphMatcher matcher;
  matcher.SetAGraph(*g);
  const GraphMatch m = matcher.Match(s.graph);
  std::string why;
  ASSERT_EQ(m.status, MatchStatus::kUnique);
  ASSERT_TRUE(testing::MatchIsCorrect(m, s, &why)) << why;
  EXPECT_EQ(m.doorway_pairs.size(), s.graph.doorways.size());
  for (const auto& p : m.doorway_pairs) {
    const auto d = std::find_if(s.graph.doorways.begin(), s.graph.doorways.end(),
                                [&](const sgraph::Doorway& x) { return x.id == p.s_id; });
    ASSERT_NE(d, s.graph.doorways.end());
    const Eigen::Vector2d truth = (s.bim_T_map * d->position).head<2>();
    int nearest = -1;
    for (const auto& a : g->doorways)
      if (nearest < 0 || (a.position.head<2>() - truth).norm() <
                             (g->doorways[nearest].position.head<2>() - truth).norm())
        nearest = a.id;
    EXPECT_EQ(p.a_id, nearest) << "S-doorway " << p.s_id;
    EXPECT_GT(p.score, 0.5);
  }
  // Weighed at 0, the doorways still pair (reported for rviz and the merger), but score nothing.
  MatcherConfig off;
  off.doorway_evidence_weight = 0.0;
  GraphMatcher plain(off);
  plain.SetAGraph(*g);
  const GraphMatch unweighed = plain.Match(s.graph);
  EXPECT_EQ(unweighed.doorway_pairs.size(), m.doorway_pairs.size());
  double sum = 0.0;
  for (const auto& p : m.doorway_pairs) sum += p.score;
  EXPECT_NEAR(m.score - unweighed.score, MatcherConfig{}.doorway_evidence_weight * sum, 1e-9);
}

// Spoiled doorways are warned about and left out: the answer is the one without them.
TEST(MatchingDoorways, SpoiledDoorwaysChangeNothingButTheWarnings) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, testing::ProjectBim("office.ifc"));
  const SyntheticSGraph s = MakeSyntheticSGraph(*g, OfficeWalk(*g));
  sgraph::SGraph without = s.graph;
  without.doorways.clear();
  sgraph::SGraph spoiled = without;
  for (auto d : s.graph.doorways) {
    d.position.y() = std::numeric_limits<double>::quiet_NaN();
    spoiled.doorways.push_back(d);
    d.position = s.graph.doorways.front().position;
    d.rooms = {4242};
    spoiled.doorways.push_back(d);
  }
  GraphMatcher a, b;
  a.SetAGraph(*g);
  b.SetAGraph(*g);
  const GraphMatch ma = a.Match(without), mb = b.Match(spoiled);
  EXPECT_EQ(ma.status, mb.status);
  EXPECT_DOUBLE_EQ(ma.score, mb.score);
  EXPECT_TRUE(mb.doorway_pairs.empty());
  EXPECT_EQ(mb.warnings.size(), ma.warnings.size() + 2 * s.graph.doorways.size());
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
