// What simulated objects stand on in a split level: the floor of their room.
#include <gtest/gtest.h>

#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace sim {
namespace {

// Storey 0: west room (x 0..5) at 0.0, east room (x 5..10) at -0.45, a north room at 0.013 (a
// finish modelled as its own slab); storey 1 above the west room.
agraph::AGraph SplitLevel() {
  agraph::AGraph g;
  const struct {
    int storey;
    double x0, y0, floor;
  } rooms[] = {{0, 0, 0, 0.0}, {0, 5, 0, -0.45}, {0, 0, 4, 0.013}, {1, 0, 0, 3.0}};
  for (const auto& r : rooms) {
    agraph::Room room;
    room.id = static_cast<int>(g.rooms.size());
    room.storey = r.storey;
    room.polygon = {{r.x0, r.y0}, {r.x0 + 5, r.y0}, {r.x0 + 5, r.y0 + 4}, {r.x0, r.y0 + 4}};
    room.floor_z = r.floor;
    g.rooms.push_back(room);
  }
  return g;
}

TEST(SimFloorUnder, AnObjectStandsOnItsRoomsFloorWhenThatIsAnotherLevel) {
  const agraph::AGraph g = SplitLevel();
  // Started on the lower floor: the west room's object stands 0.45 m higher.
  EXPECT_DOUBLE_EQ(FloorUnder(g, 0, {2, 2}, -0.45), 0.0);
  EXPECT_DOUBLE_EQ(FloorUnder(g, 0, {7, 2}, -0.45), -0.45);
  // Started on the upper floor.
  EXPECT_DOUBLE_EQ(FloorUnder(g, 0, {7, 2}, 0.0), -0.45);
  // A finish a few mm higher is the same floor; outside every room, the start's.
  EXPECT_DOUBLE_EQ(FloorUnder(g, 0, {2, 6}, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(FloorUnder(g, 0, {20, 2}, -0.45), -0.45);
  // Rooms of another storey do not count.
  EXPECT_DOUBLE_EQ(FloorUnder(g, 1, {7, 2}, 3.0), 3.0);
  EXPECT_DOUBLE_EQ(FloorUnder(g, 0, {2, 2}, 0.0), 0.0);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
