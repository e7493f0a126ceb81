// The height of M in B from the floors of the rooms the robot stood in (split levels).
#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/merging/room_floors.h"

namespace is_graphs {
namespace merging {
namespace {

// Two rooms side by side on storey 0: west (x 0..5) at 0.0, east (x 5..10) at -0.45.
agraph::AGraph SplitLevel() {
  agraph::AGraph g;
  agraph::Storey s;
  g.storeys.push_back(s);
  for (int i = 0; i < 2; ++i) {
    agraph::Room r;
    r.id = i;
    r.storey = 0;
    const double x0 = 5.0 * i;
    r.polygon = {{x0, 0}, {x0 + 5, 0}, {x0 + 5, 4}, {x0, 4}};
    r.floor_z = i == 0 ? 0.0 : -0.45;
    g.rooms.push_back(r);
  }
  return g;
}

constexpr double kStanding = 0.5;  // base above the floor
constexpr double Z = -1.0;         // M's height in B from the storey's elevation

// Keyframes (in M = B shifted by `shift` in x, z of M 1.0 above B's) at (x, 2) with base z.
sgraph::SGraph Walk(const std::vector<std::pair<double, double>>& xz, double shift = 0.0) {
  sgraph::SGraph s;
  for (size_t i = 0; i < xz.size(); ++i) {
    sgraph::Keyframe k;
    k.id = static_cast<int>(i);
    k.stamp = static_cast<double>(i);
    k.pose.translation() = Eigen::Vector3d(xz[i].first - shift, 2.0, xz[i].second + 1.0);
    s.keyframes.push_back(k);
  }
  return s;
}

// Each keyframe observes a floor plane at `floor` (in M), one plane per height.
void ObserveFloors(sgraph::SGraph* s, const std::vector<double>& floor) {
  for (size_t i = 0; i < floor.size(); ++i) {
    int id = -1;
    for (const auto& p : s->planes)
      if (std::abs(p.plane.d - floor[i]) < 1e-9) id = p.id;
    if (id < 0) {
      sgraph::Plane p;
      p.id = id = static_cast<int>(s->planes.size());
      p.plane = geometry::Plane(Eigen::Vector3d::UnitZ(), floor[i]);
      s->planes.push_back(p);
    }
    sgraph::PlaneObservation o;
    o.keyframe = static_cast<int>(i);
    o.plane = id;
    s->observations.push_back(o);
  }
}

TEST(RoomFloors, TheFloorSeenUnderAKeyframeBeatsItsHeight) {
  // The keyframes' heights bob 1 cm (gait: flat within 3 cm); the floor planes are exact.
  sgraph::SGraph s = Walk({{9, -0.45 + kStanding + 0.01},
                           {8, -0.45 + kStanding - 0.01},
                           {7, -0.45 + kStanding + 0.01}});
  ObserveFloors(&s, {0.55, 0.55, 0.55});  // -0.45 in B, 1 m higher in M
  const auto z = HeightOfMapFromRoomFloors(SplitLevel(), 0, s, -1, {0, 0, 0}, kStanding, Z);
  ASSERT_TRUE(z);
  EXPECT_NEAR(*z, -1.0, 1e-9);
  // A floor further than 0.2 m from the keyframe's height less standing is not its floor.
  sgraph::SGraph far = Walk({{9, 0.05}, {8, 0.05}});
  ObserveFloors(&far, {0.8, 0.8});
  const auto from_height =
      HeightOfMapFromRoomFloors(SplitLevel(), 0, far, -1, {0, 0, 0}, kStanding, Z);
  ASSERT_TRUE(from_height);
  EXPECT_NEAR(*from_height, -0.45 - (1.05 - kStanding), 1e-9);
}

TEST(RoomFloors, TheNewestFlatKeyframesGiveTheirRoomsFloor) {
  // Started in the east room (lower), walked up a ramp into the west room.
  const sgraph::SGraph s = Walk({{9, -0.45 + kStanding},
                                 {8, -0.45 + kStanding},
                                 {6.5, -0.30 + kStanding},  // on the ramp
                                 {5.5, -0.15 + kStanding},
                                 {4, 0.0 + kStanding},
                                 {3, 0.0 + kStanding},
                                 {2, 0.0 + kStanding}},
                                1.5);
  const auto z = HeightOfMapFromRoomFloors(SplitLevel(), 0, s, -1, {1.5, 0.0, 0.0}, kStanding, Z);
  ASSERT_TRUE(z);
  EXPECT_NEAR(*z, -1.0, 1e-9);  // z_B = z_M - 1
}

TEST(RoomFloors, OdometryHeightDriftIsTakenFromTheRoomsFloorNotCarried) {
  // The odometry rose 2 cm too much on the step: the west room's keyframes say M is 2 cm lower.
  const sgraph::SGraph s =
      Walk({{9, -0.45 + kStanding}, {4, 0.02 + kStanding}, {3, 0.02 + kStanding}});
  const auto z = HeightOfMapFromRoomFloors(SplitLevel(), 0, s, -1, {0, 0, 0}, kStanding, Z);
  ASSERT_TRUE(z);
  EXPECT_NEAR(*z, -1.02, 1e-9);
}

TEST(RoomFloors, KeyframesOnARampOutsideEveryRoomOrOnAnotherLevelGiveNothing) {
  const agraph::AGraph g = SplitLevel();
  // Every keyframe rising: all on the ramp.
  EXPECT_FALSE(HeightOfMapFromRoomFloors(g, 0, Walk({{9, 0.5}, {8, 0.6}, {7, 0.7}}), -1, {0, 0, 0},
                                         kStanding, Z));
  // Outside both rooms (y 2 + 10 in B).
  EXPECT_FALSE(
      HeightOfMapFromRoomFloors(g, 0, Walk({{9, 0.5}, {8, 0.5}}), -1, {0, 10, 0}, kStanding, Z));
  // Rooms of another storey.
  EXPECT_FALSE(
      HeightOfMapFromRoomFloors(g, 1, Walk({{9, 0.5}, {8, 0.5}}), -1, {0, 0, 0}, kStanding, Z));
  // Keyframes of another level.
  sgraph::SGraph s = Walk({{9, 0.5}, {8, 0.5}});
  for (auto& k : s.keyframes) k.level = 1;
  EXPECT_FALSE(HeightOfMapFromRoomFloors(g, 0, s, 0, {0, 0, 0}, kStanding, Z));
  EXPECT_TRUE(HeightOfMapFromRoomFloors(g, 0, s, 1, {0, 0, 0}, kStanding, Z));
}

TEST(RoomFloors, TheMapsYawTakesKeyframesIntoB) {
  // M turned 90 deg: a keyframe at M (2, -9) is at B (9, 2), in the east room.
  sgraph::SGraph s = Walk({{0, 0.05}, {0, 0.05}});
  for (auto& k : s.keyframes) k.pose.translation().head<2>() = Eigen::Vector2d(2, -9);
  const auto z = HeightOfMapFromRoomFloors(SplitLevel(), 0, s, -1, {0, 0, M_PI / 2}, kStanding, Z);
  ASSERT_TRUE(z);
  EXPECT_NEAR(*z, -0.45 - (1.05 - kStanding), 1e-9);
}

TEST(RoomFloors, AKeyframeHigherThanASplitLevelAboveItsRoomIsNotOnItsFloor) {
  // A stair's landing 1.2 m up, flat, above the east room: not that room's floor.
  const sgraph::SGraph s = Walk({{9, 1.2 + kStanding}, {8, 1.2 + kStanding}});
  EXPECT_FALSE(HeightOfMapFromRoomFloors(SplitLevel(), 0, s, -1, {0, 0, 0}, kStanding, Z));
  // 0.5 m below the storey's estimate: a split level, taken.
  const sgraph::SGraph step = Walk({{9, -0.95 + kStanding}, {8, -0.95 + kStanding}});
  EXPECT_TRUE(HeightOfMapFromRoomFloors(SplitLevel(), 0, step, -1, {0, 0, 0}, kStanding, Z));
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
