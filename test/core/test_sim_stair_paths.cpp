// Stairs found in a building's mesh and routes across storeys by room name (issue 22): a
// hand-made flight, a spiral too tight to walk, the project's tower and ../shared/bim's IFC.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/sim/room_geometry.h"
#include "is_graphs/sim/route_planner.h"
#include "is_graphs/sim/stair_paths.h"
#include "matching_test_helpers.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

// A horizontal quad (two upward triangles) of object `object`.
void AddQuad(geometry::TriangleMesh* m, int object, const Eigen::Vector2d& lo,
             const Eigen::Vector2d& hi, double z) {
  const int v = static_cast<int>(m->vertices.size());
  m->vertices.push_back({lo.x(), lo.y(), z});
  m->vertices.push_back({hi.x(), lo.y(), z});
  m->vertices.push_back({hi.x(), hi.y(), z});
  m->vertices.push_back({lo.x(), hi.y(), z});
  m->triangles.push_back({v, v + 1, v + 2});
  m->triangles.push_back({v, v + 2, v + 3});
  m->triangle_object.push_back(object);
  m->triangle_object.push_back(object);
}

// Two storeys 1.5 m apart, one 10 x 4 m room on each ("Hall" below, "Gallery" above; "Store",
// with no doorway, below too), and the mesh of a straight flight up +x in the hall: 9 treads of
// 0.3 m (x 3.0 .. 5.7, y 2.6 .. 3.8), 10 risers of 0.15 m, the last onto the gallery's floor.
struct TwoStoreys {
  agraph::AGraph graph;
  geometry::TriangleMesh mesh;
  TwoStoreys() {
    graph.storeys.push_back({0, -1, "", "Ground", 0.0, 1.5});
    graph.storeys.push_back({1, -1, "", "Upper", 1.5, 1.5});
    graph.rooms = {testing::MakeRoom(0, "Hall", 0.0, 0.0, 10.0, 4.0),
                   testing::MakeRoom(1, "Gallery", 0.0, 0.0, 10.0, 4.0),
                   testing::MakeRoom(2, "Store", 0.0, 4.2, 4.0, 8.2)};
    graph.rooms[1].storey = 1;
    mesh.object_names = {"IfcSlab#1", "IfcStairFlight#7"};
    AddQuad(&mesh, 0, {0.0, 0.0}, {10.0, 4.0}, 0.0);  // a floor: not a stair
    for (int i = 0; i < 9; ++i)
      AddQuad(&mesh, 1, {3.0 + 0.3 * i, 2.6}, {3.3 + 0.3 * i, 3.8}, 0.15 * (i + 1));
  }
};

TEST(SimStairPaths, AStraightFlightJoinsTheRoomsAtItsFootAndHead) {
  const TwoStoreys b;
  std::vector<std::string> skipped;
  const std::vector<StairPath> paths = FindStairPaths(b.mesh, b.graph, StairPathConfig(), &skipped);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_TRUE(skipped.empty());
  const StairPath& p = paths[0];
  EXPECT_EQ(p.name, "IfcStairFlight#7");
  EXPECT_EQ(p.lower_storey, 0);
  EXPECT_EQ(p.upper_storey, 1);
  EXPECT_EQ(p.lower_room, 0);
  EXPECT_EQ(p.upper_room, 1);
  EXPECT_NEAR(p.width, 1.2, 1e-9);
  // Foot 0.8 m before the bottom tread's edge (x 3.0), head 0.8 m past the top one's (x 5.7);
  // a straight flight: no turn between.
  ASSERT_EQ(p.points.size(), 4u);
  EXPECT_TRUE(p.points.front().isApprox(Eigen::Vector3d(2.2, 3.2, 0.0), 1e-9));
  EXPECT_TRUE(p.points.back().head<2>().isApprox(Eigen::Vector2d(6.5, 3.2), 1e-9));
  EXPECT_NEAR(p.points.back().z(), 1.5, 1e-9);
  EXPECT_NEAR(p.Length(), 4.3, 1e-9);
  ASSERT_EQ(p.footprint.size(), 4u);  // the flight's outline
}

TEST(SimStairPaths, TooNarrowOrLeadingNowhereIsSkippedWithTheReason) {
  TwoStoreys narrow;
  for (std::size_t i = 0; i < narrow.mesh.vertices.size(); ++i) {
    if (std::abs(narrow.mesh.vertices[i].y() - 3.8) < 1e-9) narrow.mesh.vertices[i].y() = 3.2;
  }
  std::vector<std::string> skipped;
  EXPECT_TRUE(FindStairPaths(narrow.mesh, narrow.graph, StairPathConfig(), &skipped).empty());
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_NE(skipped[0].find("0.60 m wide, under min_width 0.90 m"), std::string::npos)
      << skipped[0];

  TwoStoreys high;  // its top one riser short of the upper storey: a storey 1.0 m higher
  high.graph.storeys[1].elevation = 2.5;
  skipped.clear();
  EXPECT_TRUE(FindStairPaths(high.mesh, high.graph, StairPathConfig(), &skipped).empty());
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_NE(skipped[0].find("not from one storey's floor to another's"), std::string::npos)
      << skipped[0];
}

TEST(SimStairPaths, ABadConfigIsNamed) {
  const TwoStoreys b;
  StairPathConfig c;
  c.max_rise = 0.0;
  std::vector<std::string> skipped;
  EXPECT_TRUE(FindStairPaths(b.mesh, b.graph, c, &skipped).empty());
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_NE(skipped[0].find("max_rise: must be in (0, 1] m"), std::string::npos) << skipped[0];
}

TEST(SimStairPaths, ASpiralIsTooTightToWalk) {
  TwoStoreys b;
  b.mesh.triangles.resize(2);  // the floor only
  b.mesh.triangle_object.resize(2);
  b.mesh.object_names[1] = "IfcStair#9";
  const Eigen::Vector2d c(5.0, 2.0);
  for (int i = 0; i < 9; ++i) {  // winders of 36° around a post, 0.8 m radius
    const double a0 = i * 0.2 * M_PI, a1 = (i + 1) * 0.2 * M_PI;
    const int v = static_cast<int>(b.mesh.vertices.size());
    b.mesh.vertices.push_back(
        {c.x() + 0.05 * std::cos(a0), c.y() + 0.05 * std::sin(a0), 0.15 * (i + 1)});
    b.mesh.vertices.push_back(
        {c.x() + 0.8 * std::cos(a0), c.y() + 0.8 * std::sin(a0), 0.15 * (i + 1)});
    b.mesh.vertices.push_back(
        {c.x() + 0.8 * std::cos(a1), c.y() + 0.8 * std::sin(a1), 0.15 * (i + 1)});
    b.mesh.triangles.push_back({v, v + 1, v + 2});
    b.mesh.triangle_object.push_back(1);
  }
  std::vector<std::string> skipped;
  EXPECT_TRUE(FindStairPaths(b.mesh, b.graph, StairPathConfig(), &skipped).empty());
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_NE(skipped[0].find("IfcStair#9"), std::string::npos) << skipped[0];
  EXPECT_NE(skipped[0].find("min_width"), std::string::npos) << skipped[0];
}

TEST(SimStairPaths, RoutesAcrossStoreysTakeTheStairByRoomName) {
  const TwoStoreys b;
  const std::vector<StairPath> stairs = FindStairPaths(b.mesh, b.graph);
  TrajectoryConfig c;
  c.rooms = {"Hall", "Gallery", "Hall"};
  Result<Route> r = PlanRoute(b.graph, 0, c, "trajectory", stairs);
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value().stairs_taken, 2);  // up and down again
  EXPECT_EQ(r.value().end_storey, 0);
  // Up: to the foot, over the flight to the head, into the gallery's centre; down the reverse.
  std::vector<Eigen::Vector2d> xy{r.value().start.head<2>()};
  for (const PlanarWaypoint& w : r.value().waypoints) xy.push_back(w.position);
  std::size_t foot = 0;
  while (foot < xy.size() && !xy[foot].isApprox(Eigen::Vector2d(2.2, 3.2), 1e-9)) ++foot;
  ASSERT_LT(foot + 3, xy.size());
  EXPECT_TRUE(xy[foot + 3].isApprox(Eigen::Vector2d(6.5, 3.2), 1e-9));  // bottom, top, head
  EXPECT_NE(r.value().description[0].find("[up IfcStairFlight#7] -> Gallery (Upper)"),
            std::string::npos)
      << r.value().description[0];
  EXPECT_NE(r.value().description[1].find("[down IfcStairFlight#7] -> Hall (Ground)"),
            std::string::npos)
      << r.value().description[1];
  // Off the stair, the walk on each floor keeps 0.3 m clear of the flight's footprint (the
  // straight way from the head to the gallery's centre (5, 2) would cut its corner).
  const std::vector<Eigen::Vector2d>& footprint = stairs[0].footprint;
  auto on_stair = [&](const Eigen::Vector2d& p) {
    for (const Eigen::Vector3d& q : stairs[0].points)
      if ((q.head<2>() - p).norm() < 1e-9) return true;
    return false;
  };
  int checked = 0;
  for (std::size_t i = 1; i < xy.size(); ++i) {
    if (on_stair(xy[i - 1]) && on_stair(xy[i])) continue;
    const double length = (xy[i] - xy[i - 1]).norm();
    for (double s = 0.3; s < length - 0.3; s += 0.05, ++checked) {
      const Eigen::Vector2d p = xy[i - 1] + (xy[i] - xy[i - 1]) * (s / length);
      EXPECT_FALSE(PointInPolygon(footprint, p)) << "segment " << i << " at " << p.transpose();
      EXPECT_GE(DistanceToPolygonEdges(footprint, p), 0.29)
          << "segment " << i << " at " << p.transpose();
    }
  }
  EXPECT_GT(checked, 20);

  // Without the stair the gallery is unreachable; a name on one storey only is found there.
  r = PlanRoute(b.graph, 0, c, "trajectory", {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("trajectory.rooms[1] ('Gallery'): not reachable from 'Hall'"),
            std::string::npos)
      << r.error();
  EXPECT_NE(r.error().find("no walkable stair was found in the building's mesh"), std::string::npos)
      << r.error();
  // One storey's rooms: the stairs are not used (the route is as before stairs were known).
  c.rooms = {"Hall", "Store"};
  r = PlanRoute(b.graph, 0, c, "trajectory", stairs);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("not reachable"), std::string::npos) << r.error();
}

TEST(SimStairPaths, RoomNamesOnSeveralStoreysArePickedWithAt) {
  agraph::AGraph g = TwoStoreys().graph;
  g.rooms[1].name = "Hall";  // the same name on both storeys
  Result<int> r = FindRoomInBuilding(g, 0, "Hall");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value(), 0);  // the preferred storey first
  r = FindRoomInBuilding(g, 0, "Hall @ Upper");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value(), 1);
  r = FindRoomInBuilding(g, 0, "Hall @ 1");  // the storey by index
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value(), 1);
  r = FindRoomInBuilding(g, 0, "Hall @ Roof");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("'Hall @ Roof'"), std::string::npos) << r.error();
  g.storeys.push_back({2, -1, "", "Top", 3.0, 1.5});
  g.rooms.push_back(testing::MakeRoom(3, "Hall", 0.0, 0.0, 10.0, 4.0));
  g.rooms[3].storey = 2;
  g.rooms[0].name = "Lobby";
  r = FindRoomInBuilding(g, 0, "Hall");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(
      r.error().find("room 'Hall' is on storeys 'Upper', 'Top': name one as 'Hall @ <storey>'"),
      std::string::npos)
      << r.error();
  r = FindRoomInBuilding(g, 0, "Attic");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("nor on any other storey"), std::string::npos) << r.error();
}

// The mesh of a building converted by the real converter (skips without it or the file).
const geometry::TriangleMesh* MeshOf(const std::string& path, const agraph::AGraph** graph) {
  static std::map<std::string, geometry::TriangleMesh> meshes;
  std::string why;
  *graph = is_graphs::testing::LoadBuildingOnce(path, &why);
  if (!*graph) return nullptr;
  auto it = meshes.find(path);
  if (it == meshes.end()) {
    auto mesh = geometry::LoadObj((*graph)->mesh);
    if (!mesh.ok()) return nullptr;
    it = meshes.emplace(path, std::move(mesh).value()).first;
  }
  return &it->second;
}

TEST(SimStairPaths, TheTowersTwoFlightsJoinItsStairwells) {
  const agraph::AGraph* g = nullptr;
  const geometry::TriangleMesh* mesh = MeshOf(is_graphs::testing::ProjectBim("tower.ifc"), &g);
  if (!mesh) GTEST_SKIP() << "tower.ifc not converted (run make setup)";
  std::vector<std::string> skipped;
  const std::vector<StairPath> paths = FindStairPaths(*mesh, *g, StairPathConfig(), &skipped);
  for (const std::string& s : skipped) ADD_FAILURE() << s;
  ASSERT_EQ(paths.size(), 2u);
  std::map<int, const StairPath*> by_lower;
  for (const StairPath& p : paths) by_lower[p.lower_storey] = &p;
  ASSERT_EQ(by_lower.size(), 2u);
  for (int s : {0, 1}) {
    const StairPath& p = *by_lower.at(s);
    EXPECT_EQ(p.upper_storey, s + 1);
    EXPECT_EQ(g->rooms[p.lower_room].name, std::to_string(s) + ".ST");
    EXPECT_EQ(g->rooms[p.upper_room].name, std::to_string(s + 1) + ".ST");
    EXPECT_NEAR(p.width, 1.1, 0.05) << p.name;
    // flight_0_1 climbs northward at x 20.75, flight_1_2 southward at x 23.0.
    EXPECT_NEAR(p.points.front().x(), s == 0 ? 20.75 : 23.0, 0.05) << p.name;
    EXPECT_NEAR(p.points.back().y() - p.points.front().y(), s == 0 ? 6.35 : -6.35, 0.2) << p.name;
  }
}

TEST(SimStairPaths, SharedBimStairs) {
  // The duplex: one straight flight in each unit from Level 1 to Level 2. FZK-Haus: the spiral,
  // too tight. AC11: the three-flight stair from the ground floor up.
  const std::string dir = IS_GRAPHS_SHARED_BIM_DIR;
  struct Case {
    const char* file;
    int walkable;
  };
  for (const Case& k : {Case{"duplex.ifc", 2}, Case{"AC20-FZK-Haus.ifc", 0},
                        Case{"AC11-Institute-Var-2-IFC.ifc", 4}, Case{"KIT-EDC_with_SB.ifc", 0},
                        Case{"OSH_Flat.ifc", 0}, Case{"Smiley-West-AC10.ifc", 0}}) {
    const agraph::AGraph* g = nullptr;
    const geometry::TriangleMesh* mesh = MeshOf(dir + "/" + k.file, &g);
    if (!mesh) {
      std::cout << "[ SKIPPED  ] " << k.file << " (not there or not converted)\n";
      continue;
    }
    std::vector<std::string> skipped;
    const std::vector<StairPath> paths = FindStairPaths(*mesh, *g, StairPathConfig(), &skipped);
    std::string all;
    for (const StairPath& p : paths) all += " walkable: " + p.name;
    for (const std::string& s : skipped) all += " skipped: " + s;
    std::cout << k.file << ":" << all << "\n";
    for (const StairPath& p : paths) {
      std::cout << "  " << p.name << " " << g->storeys[p.lower_storey].name << " '"
                << g->rooms[p.lower_room].name << "' -> " << g->storeys[p.upper_storey].name << " '"
                << g->rooms[p.upper_room].name << "' width " << p.width << " length " << p.Length()
                << " points " << p.points.size() << "\n";
    }
    EXPECT_EQ(static_cast<int>(paths.size()), k.walkable) << k.file << all;
    for (const StairPath& p : paths) {
      EXPECT_EQ(g->storeys[p.upper_storey].elevation > g->storeys[p.lower_storey].elevation, true);
    }
  }
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
