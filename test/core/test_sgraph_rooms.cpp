#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "is_graphs/sgraph/corridor_detection.h"
#include "is_graphs/sgraph/floor_node.h"
#include "is_graphs/sgraph/room_detection.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector2d;

// The walls of a counter-clockwise polygon, normals into it.
std::vector<Wall2D> PolygonWalls(const std::vector<Vector2d>& corners, int first_id = 0) {
  std::vector<Wall2D> walls;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vector2d a = corners[i];
    const Vector2d b = corners[(i + 1) % corners.size()];
    const Vector2d dir = (b - a).normalized();
    Wall2D w;
    w.id = first_id + static_cast<int>(i);
    w.normal = Vector2d(-dir.y(), dir.x());  // left of a -> b: inside a CCW polygon
    w.d = w.normal.dot(a);
    w.start = a;
    w.end = b;
    walls.push_back(w);
  }
  return walls;
}

std::optional<RoomCandidate> Detect(const std::vector<Wall2D>& walls, const Vector2d& at) {
  FrontendConfig config;
  const RayFan fan = CastRays(walls, at, config);
  auto room = DetectRoom(walls, at, fan, config);
  return room ? room : DetectCorridor(walls, at, fan, config);
}

TEST(RoomDetection, RectangularRoomIsAFourWallRoomAtItsCentre) {
  const auto walls = PolygonWalls({{0, 0}, {6, 0}, {6, 4}, {0, 4}});
  const auto room = Detect(walls, Vector2d(1.0, 3.0));  // off-centre keyframe
  ASSERT_TRUE(room);
  EXPECT_EQ(room->type, RoomType::kRoom);
  EXPECT_TRUE(room->rectangular);
  EXPECT_LT((room->center - Vector2d(3, 2)).norm(), 1e-9);
  ASSERT_EQ(room->walls.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    const int id = room->walls[i];
    EXPECT_NEAR(room->distances[i], id % 2 == 0 ? 2.0 : 3.0, 1e-9) << "wall " << id;
  }
}

TEST(RoomDetection, RotatedRoomWithADoorway) {
  // 5 x 4 m rotated 30°, a 0.9 m doorway in one wall (two coplanar segments, one plane each).
  const Eigen::Rotation2Dd r(M_PI / 6);
  std::vector<Vector2d> c = {r * Vector2d(0, 0), r * Vector2d(5, 0), r * Vector2d(5, 4),
                             r * Vector2d(0, 4)};
  auto walls = PolygonWalls(c);
  Wall2D second = walls[0];
  second.id = 10;
  walls[0].end = r * Vector2d(2.0, 0);
  second.start = r * Vector2d(2.9, 0);
  walls.push_back(second);
  const auto room = Detect(walls, r * Vector2d(4, 1));
  ASSERT_TRUE(room);
  EXPECT_EQ(room->type, RoomType::kRoom);
  EXPECT_LT((room->center - r * Vector2d(2.5, 2)).norm(), 0.1);
}

// A wall along y = y0 from x0 to x1 facing +y (into a room above it).
Wall2D SouthWall(int id, double y0, double x0, double x1) {
  Wall2D w;
  w.id = id;
  w.normal = Vector2d(0, 1);
  w.d = y0;
  w.start = Vector2d(x1, y0);
  w.end = Vector2d(x0, y0);
  return w;
}

TEST(RoomDetection, SeenThroughOpeningIsWhatIsSetInAWallsDepth) {
  const Wall2D face = SouthWall(0, 0.0, 2.5, 6.0);
  EXPECT_TRUE(SeenThroughOpening(face, SouthWall(1, -0.37, 0.0, 2.4)));   // a pane at its end
  EXPECT_TRUE(SeenThroughOpening(face, SouthWall(1, -0.2, 3.0, 4.0)));    // a door leaf in it
  EXPECT_FALSE(SeenThroughOpening(face, SouthWall(1, -1.2, 0.0, 2.4)));   // a room beyond
  EXPECT_FALSE(SeenThroughOpening(face, SouthWall(1, 0.37, 0.0, 2.4)));   // in front of it
  EXPECT_FALSE(SeenThroughOpening(face, SouthWall(1, -0.05, 0.0, 2.4)));  // the same face
  // A cupboard's front (2.5-6) before a wall seen on both sides of it (0-8): the wall is no
  // opening of the cupboard.
  EXPECT_FALSE(SeenThroughOpening(face, SouthWall(1, -0.4, 0.0, 8.0)));
  Wall2D facing_away = SouthWall(1, -0.37, 0.0, 2.4);
  facing_away.normal = -facing_away.normal;
  facing_away.d = -facing_away.d;
  EXPECT_FALSE(SeenThroughOpening(face, facing_away));
}

TEST(RoomDetection, APaneSetInTheWallsDepthDoesNotBoundTheRoom) {
  // A 6 x 4 m room whose south wall (y = 0) is glazed from its west corner to x = 2.4: the pane
  // stands 0.37 m deep in the wall (as Revit's duplex living room). The room is bounded by the
  // wall's face, not by the pane: its centre at y = 2, not 1.815.
  std::vector<Wall2D> walls = PolygonWalls({{0, 0}, {6, 0}, {6, 4}, {0, 4}});
  walls[0].end = Vector2d(6, 0);
  walls[0].start = Vector2d(2.5, 0);
  walls[3].end = Vector2d(0, -0.37);  // the west wall runs on to the pane
  walls.push_back(SouthWall(10, -0.37, 0.0, 2.4));
  const auto room = Detect(walls, Vector2d(1.5, 2.5));
  ASSERT_TRUE(room);
  EXPECT_TRUE(room->rectangular);
  EXPECT_NEAR(room->center.y(), 2.0, 1e-6);
  EXPECT_NE(std::find(room->walls.begin(), room->walls.end(), 0), room->walls.end());
  EXPECT_EQ(std::find(room->walls.begin(), room->walls.end(), 10), room->walls.end());
}

TEST(RoomDetection, CorridorIsTwoOpposedWalls) {
  // 2 m wide, 20 m long, open ends beyond the range of the fan.
  FrontendConfig config;
  std::vector<Wall2D> walls = PolygonWalls({{-10, 0}, {10, 0}, {10, 2}, {-10, 2}});
  walls.erase(walls.begin() + 3);
  walls.erase(walls.begin() + 1);
  const auto corridor = Detect(walls, Vector2d(3, 0.7));
  ASSERT_TRUE(corridor);
  EXPECT_EQ(corridor->type, RoomType::kCorridor);
  EXPECT_NEAR(corridor->center.y(), 1.0, 1e-9);
  EXPECT_NEAR(corridor->center.x(), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(corridor->axis.x()), 1.0, 1e-9);
  EXPECT_NEAR(corridor->distances[0], 1.0, 1e-9);
}

TEST(RoomDetection, CorridorBetweenOfficeWallsIsNoRoom) {
  // A 2 m corridor (y 0..2), 40 m long (its ends beyond the fan's range), crossed at x = -2 and
  // x = 8 by the lines of offices' side walls that stop 0.15 m short of it on both sides. Their
  // doorway margins bridge the corridor, but no ray sees them where they are: they bound
  // offices, not this space. A corridor, not a 10 m four-wall room (D3's false rooms).
  std::vector<Wall2D> walls = PolygonWalls({{-20, 0}, {20, 0}, {20, 2}, {-20, 2}});
  walls.erase(walls.begin() + 3);
  walls.erase(walls.begin() + 1);
  int id = 10;
  for (const double x : {-2.0, 8.0}) {
    for (const auto& [y0, y1] : {std::pair<double, double>{-5.0, -0.15}, {2.15, 7.0}}) {
      Wall2D w;
      w.id = id++;
      w.normal = Vector2d(x < 0 ? 1.0 : -1.0, 0.0);  // facing the corridor's middle
      w.d = w.normal.x() * x;
      w.start = Vector2d(x, y0);
      w.end = Vector2d(x, y1);
      walls.push_back(w);
    }
  }
  const auto found = Detect(walls, Vector2d(3, 1.1));
  ASSERT_TRUE(found);
  EXPECT_EQ(found->type, RoomType::kCorridor) << found->walls.size() << " walls";
  EXPECT_NEAR(found->center.y(), 1.0, 1e-9);
}

Wall2D VerticalWall(int id, double x, double facing, double y0, double y1) {
  Wall2D w;
  w.id = id;
  w.normal = Vector2d(facing, 0.0);
  w.d = facing * x;
  w.start = Vector2d(x, y0);
  w.end = Vector2d(x, y1);
  return w;
}

TEST(RoomDetection, OneCorridorClosedAtTwoPlacesIsOneSpace) {
  // D6: a corridor (x 0..20, y 0..2; walls 0 south, 1 east end, 2 north with a doorway in it,
  // 3 west end) and, through the doorway, a link corridor going north (walls 10 at x = 8 and
  // 11 at x = 10, from y = 2.2). Seen from its west part the corridor is closed by wall 11's
  // doorway margin; seen from further on, by its own east end. One space, not two rooms.
  std::vector<Wall2D> walls = PolygonWalls({{0, 0}, {20, 0}, {20, 2}, {0, 2}});
  walls.push_back(VerticalWall(10, 8.0, 1.0, 2.2, 7.0));
  walls.push_back(VerticalWall(11, 10.0, -1.0, 2.2, 7.0));
  EXPECT_TRUE(SameSpace(walls, {3, 0, 2, 11}, Vector2d(5, 1), {3, 0, 2, 1}, Vector2d(10, 1)));
  EXPECT_TRUE(SameSpace(walls, {3, 0, 2, 1}, Vector2d(10, 1), {3, 0, 2, 11}, Vector2d(5, 1)));
  // Sharing only one side (0) and an end wall: no opposed pair, nothing to say they are one.
  EXPECT_FALSE(SameSpace(walls, {3, 0, 11}, Vector2d(5, 1), {3, 0, 1}, Vector2d(10, 1)));
  // A centre outside the shared pair (1 m beyond the north wall, in the link corridor).
  EXPECT_FALSE(SameSpace(walls, {3, 0, 2, 11}, Vector2d(5, 1), {0, 2, 10, 11}, Vector2d(9, 3)));
}

TEST(RoomDetection, TwoOfficesAlongOneCorridorAreTwoSpaces) {
  // Offices A (x 0..4) and B (x 4.12..8) between a corridor-side wall (y = 2.2) and the façade
  // (y = 6), each one plane across both; a 12 cm partition between them. They share an opposed
  // pair, but the partition lies across the segment joining their centres.
  std::vector<Wall2D> walls;
  Wall2D corridor_side;
  corridor_side.id = 0;
  corridor_side.normal = Vector2d(0, 1);
  corridor_side.d = 2.2;
  corridor_side.start = Vector2d(0, 2.2);
  corridor_side.end = Vector2d(8, 2.2);
  Wall2D facade = corridor_side;
  facade.id = 1;
  facade.normal = Vector2d(0, -1);
  facade.d = -6.0;
  facade.start = Vector2d(0, 6);
  facade.end = Vector2d(8, 6);
  walls = {corridor_side,
           facade,
           VerticalWall(2, 0.0, 1.0, 2.2, 6.0),
           VerticalWall(3, 4.0, -1.0, 2.2, 6.0),
           VerticalWall(4, 4.12, 1.0, 2.2, 6.0),
           VerticalWall(5, 8.0, -1.0, 2.2, 6.0)};
  EXPECT_FALSE(SameSpace(walls, {0, 1, 2, 3}, Vector2d(2, 4.1), {0, 1, 4, 5}, Vector2d(6.06, 4.1)));
  // Without the partition mapped they would be one (what the rule rests on).
  walls.erase(walls.begin() + 3, walls.begin() + 5);
  EXPECT_TRUE(SameSpace(walls, {0, 1, 2}, Vector2d(2, 4.1), {0, 1, 5}, Vector2d(6.06, 4.1)));
}

TEST(RoomDetection, LShapedRoomIsAPolygonalRoom) {
  const std::vector<Vector2d> corners = {{0, 0}, {6, 0}, {6, 3}, {3, 3}, {3, 6}, {0, 6}};
  const auto room = Detect(PolygonWalls(corners), Vector2d(1.5, 1.5));
  ASSERT_TRUE(room);
  EXPECT_EQ(room->type, RoomType::kRoom);
  EXPECT_FALSE(room->rectangular);
  EXPECT_EQ(room->walls.size(), 6u);
  // The L's area centroid is (2.5, 2.5); seen from one corner part of it is hidden, so the
  // visibility polygon's centroid lies nearby, inside the room.
  EXPECT_LT((room->center - Vector2d(2.5, 2.5)).norm(), 0.8);
  for (double d : room->distances) EXPECT_GT(d, 0.0);
}

TEST(RoomDetection, RoomSeenOnlyInPartIsNoRoom) {
  // Two adjacent walls of a room: no closure, no opposed pair.
  auto walls = PolygonWalls({{0, 0}, {6, 0}, {6, 4}, {0, 4}});
  walls.resize(2);
  EXPECT_FALSE(Detect(walls, Vector2d(3, 2)));
  // Three walls: still open on one side, and the one pair is too wide for a corridor.
  walls = PolygonWalls({{0, 0}, {6, 0}, {6, 4}, {0, 4}});
  walls.resize(3);
  EXPECT_FALSE(Detect(walls, Vector2d(3, 2)));
}

TEST(RoomDetection, NoWallsNoRoom) { EXPECT_FALSE(Detect({}, Vector2d(0, 0))); }

TEST(FloorNode, CentreIsTheMeanOfTheRooms) {
  Room a, b;
  a.id = 3;
  a.center = Eigen::Vector3d(0, 0, 0);
  b.id = 5;
  b.center = Eigen::Vector3d(4, 2, 0);
  const Floor f = MakeFloor({a, b}, -0.5);
  EXPECT_LT((f.center - Eigen::Vector3d(2, 1, -0.5)).norm(), 1e-12);
  EXPECT_EQ(f.rooms, (std::vector<int>{3, 5}));
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
