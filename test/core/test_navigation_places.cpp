// Places as goals (agraph_node's `locate`, docs/navigation.md) on every room, door and wall of
// the project's buildings and of ../shared/bim: inside the room, facing the door, in front of
// the wall; ambiguous and unknown names; the time per call.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/navigation/occupancy_grid.h"
#include "is_graphs/navigation/places.h"
#include "navigation_test_helpers.h"

namespace is_graphs {
namespace navigation {
namespace {

using testing::NavigationBuildings;

Eigen::Vector2d Heading(double yaw) { return {std::cos(yaw), std::sin(yaw)}; }

TEST(NavigationPlaces, EveryRoomsGoalIsInsideItAndFarthestFromItsWalls) {
  const auto buildings = NavigationBuildings();
  if (buildings.empty()) GTEST_SKIP() << "no building converts here (make setup)";
  int rooms = 0, calls = 0, split_rooms = 0;
  double worst_ms = 0.0, total_ms = 0.0;
  for (const auto& b : buildings) {
    const PlaceIndex index(*b.graph, PlaceConfig{});
    for (const auto& r : b.graph->rooms) {
      if (r.polygon.size() < 3) continue;
      ++rooms;
      const auto t0 = std::chrono::steady_clock::now();
      const auto found = index.Locate(r.guid.empty() ? r.name : r.guid);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      ++calls, total_ms += ms, worst_ms = std::max(worst_ms, ms);
      ASSERT_TRUE(found.ok()) << b.name << " " << r.name << ": " << found.error();
      const Place* place = nullptr;
      for (const auto& p : found.value())
        if (p.kind == Place::Kind::kRoom && p.id == r.id) place = &p;
      ASSERT_TRUE(place) << b.name << " " << r.name;
      const Eigen::Vector2d q = place->position.head<2>();
      const double inside = SignedDistanceToPolygon(r.polygon, q);
      EXPECT_GT(inside, 0.0) << b.name << " room " << r.name << " at " << q.transpose();
      // The farthest point: no vertex-free sample of the room lies deeper (1 cm of slack).
      const double centre = SignedDistanceToPolygon(r.polygon, r.center.head<2>());
      EXPECT_GE(inside + 0.01, centre) << b.name << " room " << r.name;
      EXPECT_EQ(place->storey, r.storey);
      EXPECT_EQ(place->storey_name, b.graph->storeys[r.storey].name);
      EXPECT_DOUBLE_EQ(place->position.z(), r.floor_z) << b.name << " room " << r.name;
      if (b.name == "split.ifc" && r.name == "Workshop") {  // the lower of its two levels
        EXPECT_NEAR(place->position.z(), -0.45, 0.001);
        ++split_rooms;
      }
    }
  }
  if (std::any_of(buildings.begin(), buildings.end(),
                  [](const auto& b) { return b.name == "split.ifc"; })) {
    EXPECT_EQ(split_rooms, 1) << "split.ifc's workshop not located";
  }
  std::printf("[ locate   ] %d rooms of %zu buildings, all inside; %.3f ms per call (worst %.3f)\n",
              rooms, buildings.size(), total_ms / std::max(calls, 1), worst_ms);
  EXPECT_LT(worst_ms, 10.0);
}

TEST(NavigationPlaces, DoorsAreFacedFromTheirFirstRoomAndWallsFromTheirRoomSide) {
  std::string why;
  const agraph::AGraph* g = testing::LoadBuildingOnce(testing::ProjectBim("tower.ifc"), &why);
  if (!g) GTEST_SKIP() << why;
  const PlaceConfig config;
  const PlaceIndex index(*g, config);
  int doors = 0;
  for (const auto& d : g->doorways) {
    const auto found = index.Locate(d.guid);
    ASSERT_TRUE(found.ok()) << found.error();
    ASSERT_EQ(found.value().size(), 1u) << d.guid;
    const Place& p = found.value()[0];
    EXPECT_EQ(p.kind, Place::Kind::kDoor);
    const Eigen::Vector2d to_door = d.position.head<2>() - p.position.head<2>();
    // Facing the door: the heading points at it (the door's position may sit off the wall's
    // mid-plane by half the wall: a few degrees).
    EXPECT_GT(Heading(p.yaw).dot(to_door.normalized()), std::cos(0.2)) << d.name;
    EXPECT_NEAR(to_door.norm(), config.door_standoff, 0.2) << d.name;
    EXPECT_GT(SignedDistanceToPolygon(g->rooms[d.rooms[0]].polygon, p.position.head<2>()), 0.0)
        << d.name << " not in front of it in " << g->rooms[d.rooms[0]].name;
    ++doors;
  }
  EXPECT_GT(doors, 10);
  for (const auto& w : g->walls) {
    const auto found = index.Locate(w.guid);
    ASSERT_TRUE(found.ok()) << found.error();
    for (const auto& p : found.value()) {
      if (p.id != w.id) continue;
      bool in_a_room = false;
      for (const auto& r : g->rooms)
        in_a_room |= SignedDistanceToPolygon(r.polygon, p.position.head<2>()) > 0.0;
      EXPECT_TRUE(in_a_room) << "wall " << w.name << " seen from outside every room";
      const Eigen::Vector2d to_centre = w.center.head<2>() - p.position.head<2>();
      EXPECT_GT(Heading(p.yaw).dot(to_centre.normalized()), std::cos(0.2)) << w.name;
    }
  }
}

TEST(NavigationPlaces, NamesLongNamesCaseAndStoreys) {
  std::string why;
  const agraph::AGraph* g = testing::LoadBuildingOnce(testing::ProjectBim("tower.ifc"), &why);
  if (!g) GTEST_SKIP() << why;
  const PlaceIndex index(*g, PlaceConfig{});
  auto found = index.Locate("Canteen");  // a long name
  ASSERT_TRUE(found.ok()) << found.error();
  ASSERT_EQ(found.value().size(), 1u);
  EXPECT_EQ(found.value()[0].name, "0.04");
  EXPECT_EQ(found.value()[0].storey_name, "Ground floor");
  found = index.Locate("library 2.07");  // case ignored when nothing matches exactly
  ASSERT_TRUE(found.ok()) << found.error();
  EXPECT_EQ(found.value()[0].name, "2.07");
  EXPECT_EQ(found.value()[0].storey, 2);
  found = index.Locate("1.03", "First floor");
  ASSERT_TRUE(found.ok()) << found.error();
  found = index.Locate("1.03", "Second floor");
  ASSERT_FALSE(found.ok());
  EXPECT_NE(found.error().find("on storey 'Second floor'"), std::string::npos) << found.error();
  found = index.Locate("1.03", "Roof");
  ASSERT_FALSE(found.ok());
  EXPECT_NE(found.error().find("Ground floor"), std::string::npos) << found.error();
}

TEST(NavigationPlaces, AnAmbiguousNameReturnsEveryMatchWithItsStorey) {
  std::string why;
  const agraph::AGraph* tower = testing::LoadBuildingOnce(testing::ProjectBim("tower.ifc"), &why);
  if (!tower) GTEST_SKIP() << why;
  agraph::AGraph g = *tower;  // every storey's corridor called "Corridor"
  int corridors = 0;
  for (auto& r : g.rooms)
    if (r.long_name.rfind("Corridor", 0) == 0) r.long_name = "Corridor", ++corridors;
  ASSERT_EQ(corridors, 3);
  const PlaceIndex index(g, PlaceConfig{});
  const auto found = index.Locate("Corridor");
  ASSERT_TRUE(found.ok()) << found.error();
  ASSERT_EQ(found.value().size(), 3u);
  std::set<std::string> storeys;
  for (const auto& p : found.value()) storeys.insert(p.storey_name);
  EXPECT_EQ(storeys, (std::set<std::string>{"Ground floor", "First floor", "Second floor"}));
  const auto one = index.Locate("Corridor", "1");  // the storey by index
  ASSERT_TRUE(one.ok()) << one.error();
  ASSERT_EQ(one.value().size(), 1u);
  EXPECT_EQ(one.value()[0].name, "1.C");
}

TEST(NavigationPlaces, AnUnknownNameNamesTheClosestOnes) {
  std::string why;
  const agraph::AGraph* g = testing::LoadBuildingOnce(testing::ProjectBim("office.ifc"), &why);
  if (!g) GTEST_SKIP() << why;
  const PlaceIndex index(*g, PlaceConfig{});
  auto found = index.Locate("Meetng room");
  ASSERT_FALSE(found.ok());
  EXPECT_NE(found.error().find("no room, door or wall named 'Meetng room'"), std::string::npos);
  EXPECT_NE(found.error().find("'Meeting room'"), std::string::npos) << found.error();
  found = index.Locate("03ISH2Axx0AakK$DuPbqG3");  // a GlobalId one character off a door's
  ASSERT_FALSE(found.ok());
  EXPECT_NE(found.error().find("03ISH2Axx0AakK$DuPbqG2"), std::string::npos) << found.error();
}

TEST(NavigationPlaces, SnappedGoalsLieOnFreeCellsOfTheStoreysMap) {
  const auto buildings = NavigationBuildings();
  if (buildings.empty()) GTEST_SKIP() << "no building converts here (make setup)";
  int moved = 0, stuck = 0, rooms = 0, places = 0, not_free = 0;
  for (const auto& b : buildings) {
    PlaceIndex index(*b.graph, PlaceConfig{});
    for (size_t s = 0; s < b.graph->storeys.size(); ++s) {
      const auto grid = BuildStoreyGrid(agraph::SelectStorey(*b.graph, static_cast<int>(s)).value(),
                                        b.mesh, GridConfig{});
      if (!grid.ok()) continue;
      const Eigen::Vector2i counts = index.SnapToFree(static_cast<int>(s), grid.value(), *b.graph);
      moved += counts[0], stuck += counts[1];
      for (const auto& p : index.places()) {
        if (p.storey != static_cast<int>(s)) continue;
        ++places;
        const auto c = grid.value().CellOf(p.position.head<2>());
        const bool free = grid.value().Contains(c.x(), c.y()) &&
                          grid.value().At(c.x(), c.y()) == OccupancyGrid::kFree;
        not_free += !free;
        EXPECT_EQ(p.on_free_cell, free) << b.name << " " << ToString(p.kind) << " " << p.name;
        if (!free && p.kind != Place::Kind::kRoom)
          std::printf("[ locate   ] %s %s %s: no free cell\n", b.name.c_str(), ToString(p.kind),
                      p.name.c_str());
        if (p.kind != Place::Kind::kRoom) continue;
        ++rooms;
        // A real IFC may fill a room at the robot's height (duplex's R301 under its roof).
        if (!free)
          std::printf("[ locate   ] %s room %s: no free cell\n", b.name.c_str(), p.name.c_str());
        EXPECT_TRUE(free || !b.project) << b.name << " room " << p.name;
        EXPECT_GT(SignedDistanceToPolygon(b.graph->rooms[p.id].polygon, p.position.head<2>()), 0.0)
            << b.name << " room " << p.name;
      }
    }
  }
  std::printf("[ locate   ] %d goals (%d rooms): %d moved onto a free cell, %d not free\n", places,
              rooms, moved, not_free);
  EXPECT_EQ(not_free, stuck);
}

TEST(NavigationPlaces, FarthestFromEdgesOfAnLShape) {
  // An L of two 4 x 2 arms: the deepest point (1 m from the walls) is in the corner square.
  const std::vector<Eigen::Vector2d> l = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
  double d = 0.0;
  const Eigen::Vector2d p = FarthestFromEdges(l, 0.001, &d);
  // On the diagonal (a, a), as far from x = 0 as from the inner corner (2, 2).
  EXPECT_NEAR(d, 2.0 * std::sqrt(2.0) / (1.0 + std::sqrt(2.0)), 0.005);
  EXPECT_GT(SignedDistanceToPolygon(l, p), 0.99);
  EXPECT_LT(p.x(), 2.5);
  EXPECT_LT(p.y(), 2.5);
}

}  // namespace
}  // namespace navigation
}  // namespace is_graphs
