// Route planning through doorways on a synthetic A-Graph; paths inside non-convex rooms.
#include <gtest/gtest.h>

#include "is_graphs/sim/room_geometry.h"
#include "is_graphs/sim/route_planner.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

TEST(SimRoutePlanner, CrossesEachDoorwayStraightAlongTheWallNormal) {
  const agraph::AGraph g = testing::ThreeRoomsInARow();
  TrajectoryConfig c;
  c.rooms = {"A", "C"};
  c.doorway_clearance = 0.8;
  const Result<Route> r = PlanRoute(g, 0, c);
  ASSERT_TRUE(r.ok()) << r.error();
  const Route& route = r.value();
  EXPECT_TRUE(route.start.head<2>().isApprox(Eigen::Vector2d(2.0, 2.0)));
  // A centre -> in front of dAB -> behind dAB -> B centre -> in front of dBC -> behind -> C.
  ASSERT_EQ(route.waypoints.size(), 6u);
  const double offset = 0.1 + 0.8;  // half the wall + clearance
  EXPECT_TRUE(route.waypoints[0].position.isApprox(Eigen::Vector2d(4.1 - offset, 2.0)));
  EXPECT_TRUE(route.waypoints[1].position.isApprox(Eigen::Vector2d(4.1 + offset, 2.0)));
  EXPECT_TRUE(route.waypoints[2].position.isApprox(Eigen::Vector2d(6.2, 2.0)));
  EXPECT_TRUE(route.waypoints[3].position.isApprox(Eigen::Vector2d(8.3 - offset, 1.0)));
  EXPECT_TRUE(route.waypoints[4].position.isApprox(Eigen::Vector2d(8.3 + offset, 1.0)));
  EXPECT_TRUE(route.waypoints[5].position.isApprox(Eigen::Vector2d(10.4, 2.0)));
  EXPECT_FALSE(route.waypoints[0].pause);
  EXPECT_TRUE(route.waypoints[5].pause);    // a room to visit
  EXPECT_NEAR(route.start.z(), 0.0, 1e-9);  // facing the first waypoint
}

TEST(SimRoutePlanner, UnreachableAndUnknownRoomsNameTheField) {
  const agraph::AGraph g = testing::ThreeRoomsInARow();
  TrajectoryConfig c;
  c.rooms = {"A", "B", "D"};
  Result<Route> r = PlanRoute(g, 0, c);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("trajectory.rooms[2] ('D'): not reachable from 'B'"), std::string::npos)
      << r.error();
  c.rooms = {"A", "Lobby"};
  r = PlanRoute(g, 0, c);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("trajectory.rooms[1]: no room named 'Lobby'"), std::string::npos)
      << r.error();
}

TEST(SimRoutePlanner, ExplicitWaypointsAreKept) {
  const agraph::AGraph g = testing::ThreeRoomsInARow();
  TrajectoryConfig c;
  c.waypoints = {{{1.0, 1.0}, std::nullopt}, {{3.0, 1.0}, std::nullopt}, {{3.0, 3.0}, 0.5}};
  const Result<Route> r = PlanRoute(g, 0, c);
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_TRUE(r.value().start.isApprox(Eigen::Vector3d(1.0, 1.0, 0.0)));
  ASSERT_EQ(r.value().waypoints.size(), 2u);
  EXPECT_DOUBLE_EQ(*r.value().waypoints[1].yaw, 0.5);
}

TEST(SimRoutePlanner, GoesAroundTheCornerOfAnLShapedRoom) {
  // L: the 6 x 2 bottom bar and the 2 x 6 left bar.
  const std::vector<Eigen::Vector2d> l{{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 6}, {0, 6}};
  const Eigen::Vector2d a(5.0, 1.0), b(1.0, 5.0);
  const std::vector<Eigen::Vector2d> path = PathInsideRoom(l, a, b, 0.3);
  ASSERT_GE(path.size(), 2u);
  EXPECT_TRUE(path.back().isApprox(b));
  Eigen::Vector2d from = a;
  for (const Eigen::Vector2d& to : path) {  // every leg stays inside the L
    for (int i = 0; i <= 50; ++i) {
      EXPECT_TRUE(PointInPolygon(l, from + (to - from) * (i / 50.0)));
    }
    from = to;
  }
  // An interior point of the L is inside it, away from the walls.
  agraph::Room room;
  room.polygon = l;
  room.center = Eigen::Vector3d(2.2, 2.2, 0.0);  // (its area centroid is near the inner corner)
  const Eigen::Vector2d inner = RoomInteriorPoint(room);
  EXPECT_TRUE(PointInPolygon(l, inner));
  EXPECT_GT(DistanceToPolygonEdges(l, inner), 0.6);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
