// Storeys walked (issue 22): keyframe levels from the height walked, the part of an S-Graph on
// one level, and what the matcher and the merger make of an S-Graph over two levels.
#include <gtest/gtest.h>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/sgraph/levels.h"

namespace is_graphs {
namespace sgraph {
namespace {

TEST(SGraphLevels, AStairClimbEndsOnANewLevelOnceSettled) {
  LevelTracker t;
  EXPECT_EQ(t.Add(0.50), 0);
  EXPECT_EQ(t.Add(0.52), 0);  // the gait's bob
  EXPECT_EQ(t.Add(0.48), 0);
  for (double z : {0.9, 1.5, 2.2, 3.0, 3.5}) EXPECT_EQ(t.Add(z), 0) << "on the flight: " << z;
  EXPECT_EQ(t.Add(3.52), 1);  // settled 3 m up
  EXPECT_EQ(t.size(), 2);
  EXPECT_DOUBLE_EQ(t.Height(1), 3.52);
  EXPECT_EQ(t.Add(3.49), 1);
  EXPECT_EQ(t.Add(2.0), 1);   // going down: still the level it left
  EXPECT_EQ(t.Add(0.51), 0);  // back on the ground floor
  EXPECT_EQ(t.size(), 2);
  t.Reset();
  EXPECT_EQ(t.Add(7.0), 0);
}

TEST(SGraphLevels, StepsAndRampsInsideAStoreyAreNoNewLevel) {
  // A split level: down three 0.15 m steps (0.45 m), along, down a ramp to 0.6 m below, back up.
  LevelTracker t;
  EXPECT_EQ(t.Add(0.50), 0);
  for (double z : {0.35, 0.20, 0.05, 0.05, 0.04, 0.0, -0.05, -0.10, -0.10, -0.09, 0.2, 0.5, 0.5})
    EXPECT_EQ(t.Add(z), 0) << z;
  EXPECT_EQ(t.size(), 1);
  EXPECT_DOUBLE_EQ(t.Height(0), 0.50);
}

TEST(SGraphLevels, AHalfStoreyLandingIsNotALevel) {
  LevelTracker t;
  t.Add(0.5);
  EXPECT_EQ(t.Add(1.55), 0);  // a landing 1.05 m up, stood on for two keyframes
  EXPECT_EQ(t.Add(1.56), 0);
  EXPECT_EQ(t.size(), 1);
}

TEST(SGraphLevels, ALandingTwoThirdsUpMovesToTheFloorTheClimbEndsOn) {
  // AC11's stair: three flights of a 3 m storey, the second landing 2 m up (beyond min_rise:
  // taken for a level when stood on), then the last flight to the floor 3 m up.
  LevelTracker t;
  t.Add(0.5);
  t.Add(0.51);
  for (double z : {1.0, 1.5, 2.0}) EXPECT_EQ(t.Add(z), 0) << "on the flight: " << z;
  EXPECT_EQ(t.Add(2.5), 0);
  EXPECT_EQ(t.Add(2.52), 1);  // settled on the landing: a level for now
  EXPECT_DOUBLE_EQ(t.Height(1), 2.52);
  EXPECT_EQ(t.Add(3.0), 1);  // the last flight
  EXPECT_EQ(t.Add(3.5), 1);
  EXPECT_EQ(t.Add(3.51), 1);  // settled on the floor: the level moves there
  EXPECT_DOUBLE_EQ(t.Height(1), 3.51);
  EXPECT_EQ(t.size(), 2);
  EXPECT_EQ(t.Add(3.49), 1);
  EXPECT_EQ(t.Add(0.52), 0);  // back down

  // Stood on long enough, a level stays where it is (a mezzanine, then a half flight up).
  LevelTracker m;
  m.Add(0.5);
  m.Add(2.5);
  EXPECT_EQ(m.Add(2.52), 1);
  for (int i = 1; i <= 9; ++i) m.Add(Eigen::Vector3d(0.5 * i, 0.0, 2.5));  // 4.5 m walked on it
  EXPECT_EQ(m.Add(3.5), 1);
  EXPECT_EQ(m.Add(3.51), 1);
  EXPECT_DOUBLE_EQ(m.Height(1), 2.52);
  // Off (landing_length 0): the landing stays the level, as before.
  LevelConfig off;
  off.landing_length = 0.0;
  LevelTracker o(off);
  o.Add(0.5);
  o.Add(2.5);
  o.Add(2.52);
  o.Add(3.5);
  o.Add(3.51);
  EXPECT_DOUBLE_EQ(o.Height(1), 2.52);
}

TEST(SGraphLevels, ValidateNamesTheField) {
  LevelConfig c;
  EXPECT_EQ(c.Validate(), "");
  c.min_rise = 0.3;
  EXPECT_NE(c.Validate().find("level_min_rise"), std::string::npos);
  c = LevelConfig();
  c.settle = 0.0;
  EXPECT_NE(c.Validate().find("level_settle"), std::string::npos);
}

// Two keyframes on level 0 and two on level 1, each pair observing its own plane; a room per
// level; a doorway on level 0; a floor per level.
SGraph TwoLevels() {
  SGraph g;
  for (int i = 0; i < 4; ++i) {
    Keyframe k;
    k.id = 10 + i;
    k.previous = i > 0 ? 9 + i : -1;
    k.level = i < 2 ? 0 : 1;
    g.keyframes.push_back(k);
  }
  for (int i = 0; i < 2; ++i) {
    Plane p;
    p.id = 100 + i;
    g.planes.push_back(p);
    Room r;
    r.id = 200 + i;
    r.keyframes = {10 + 2 * i};
    g.rooms.push_back(r);
    Floor f;
    f.id = i;
    f.height = 3.0 * i;
    f.rooms = {200 + i};
    g.floors.push_back(f);
  }
  for (int k = 0; k < 4; ++k) {
    PlaneObservation o;
    o.keyframe = 10 + k;
    o.plane = k < 2 ? 100 : 101;
    g.observations.push_back(o);
  }
  Doorway d;
  d.id = 160;
  d.keyframes = {10};
  g.doorways.push_back(d);
  return g;
}

TEST(SGraphLevels, TheSubgraphOfALevelKeepsItsOwnPartsAndIds) {
  const SGraph g = TwoLevels();
  EXPECT_TRUE(HasLevels(g));
  EXPECT_EQ(CurrentLevel(g), 1);
  EXPECT_EQ(LevelOfRoom(g, g.rooms[1]), 1);
  EXPECT_EQ(LevelOfPlane(g, 100), 0);
  const SGraph up = LevelSubgraph(g, 1);
  ASSERT_EQ(up.keyframes.size(), 2u);
  EXPECT_EQ(up.keyframes[0].id, 12);
  EXPECT_EQ(up.keyframes[0].previous, -1) << "its walk starts on the level";
  EXPECT_EQ(up.keyframes[1].previous, 12);
  ASSERT_EQ(up.planes.size(), 1u);
  EXPECT_EQ(up.planes[0].id, 101);
  ASSERT_EQ(up.rooms.size(), 1u);
  EXPECT_EQ(up.rooms[0].id, 201);
  ASSERT_EQ(up.floors.size(), 1u);
  EXPECT_DOUBLE_EQ(up.floors[0].height, 3.0);
  EXPECT_TRUE(up.doorways.empty());
  EXPECT_EQ(up.observations.size(), 2u);
  const SGraph down = LevelSubgraph(g, 0);
  EXPECT_EQ(down.doorways.size(), 1u);
  EXPECT_FALSE(HasLevels(down));
}

TEST(SGraphLevels, WithOneStoreyLoadedOtherLevelsAreNotMatched) {
  // The robot climbed away from the storey given: nothing there can be matched against it.
  const auto building = agraph::LoadAGraph(testing::TwoRoomsPath());
  ASSERT_TRUE(building.ok()) << building.error();
  ASSERT_EQ(building.value().storeys.size(), 1u);
  matching::GraphMatcher matcher;
  matcher.SetAGraph(building.value());
  const matching::GraphMatch m = matcher.Match(TwoLevels());
  EXPECT_EQ(m.status, matching::MatchStatus::kNone);
  bool said = false;
  for (const auto& w : m.warnings) said = said || w.find("another level") != std::string::npos;
  EXPECT_TRUE(said) << "a warning names the level";
}

TEST(SGraphLevels, OnAStairTheRobotIsNotMatched) {
  // At the top of a flight the newest keyframe is still counted on the level it left (it has
  // not settled): matched there, the answer named the storey below (M4). Not matched at all.
  const auto building = agraph::LoadAGraph(testing::TwoRoomsPath());
  ASSERT_TRUE(building.ok()) << building.error();
  SGraph g = TwoLevels();
  for (auto& k : g.keyframes) k.pose.translation().z() = 3.0 * k.level;
  g.keyframes.resize(2);  // both on level 0, at z = 0
  EXPECT_DOUBLE_EQ(HeightOffLevel(g), 0.0);
  Keyframe top = g.keyframes.back();
  top.id = 20, top.previous = top.id - 1;
  top.pose.translation().z() = 2.6;  // up the flight, level 0 still
  g.keyframes.push_back(top);
  EXPECT_DOUBLE_EQ(HeightOffLevel(g), 2.6);
  matching::GraphMatcher matcher;
  matcher.SetAGraph(building.value());
  matching::GraphMatch m = matcher.Match(g);
  EXPECT_EQ(m.status, matching::MatchStatus::kNone);
  bool said = false;
  for (const auto& w : m.warnings)
    said = said || w.find("2.6 m above the level") != std::string::npos;
  EXPECT_TRUE(said) << (m.warnings.empty() ? "no warning" : m.warnings.front());
  // Settled on it (a new level whose first keyframe is this one): matched again.
  g.keyframes.back().level = 1;
  EXPECT_DOUBLE_EQ(HeightOffLevel(g), 0.0);
  m = matcher.Match(g);
  for (const auto& w : m.warnings) EXPECT_EQ(w.find("above the level"), std::string::npos) << w;
  // Settled up there on level 0 still (a long landing the tracker took for the level, a
  // plateau): the level's map is matched again.
  g.keyframes.back().level = 0;
  for (int i = 0; i < 2; ++i) {
    Keyframe more = g.keyframes.back();
    more.id += 1, more.previous = more.id - 1;
    g.keyframes.push_back(more);
  }
  EXPECT_DOUBLE_EQ(HeightOffLevel(g), 2.6);
  EXPECT_FALSE(OnStair(g, 0.5));
  m = matcher.Match(g);
  for (const auto& w : m.warnings) EXPECT_EQ(w.find("above the level"), std::string::npos) << w;
  g.keyframes.resize(3);
  // Down a flight: below the level.
  g.keyframes.back().level = 0;
  g.keyframes.back().pose.translation().z() = -0.8;
  EXPECT_DOUBLE_EQ(HeightOffLevel(g), -0.8);
  EXPECT_EQ(matcher.Match(g).status, matching::MatchStatus::kNone);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
