// The BIM as a navigation map (docs/navigation.md), on every storey of the project's buildings
// and of ../shared/bim: wall faces occupied, doorway-joined rooms connected (A*), outside
// unknown; the as-built grid of H6's deviations; map_server's files.
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/navigation/grid_path.h"
#include "is_graphs/navigation/map_files.h"
#include "is_graphs/navigation/places.h"
#include "navigation_test_helpers.h"

namespace is_graphs {
namespace navigation {
namespace {

using testing::NavigationBuildings;

/// Whether `p` lies in the passage of one of the storey's doorways (a cell of slack).
bool InDoorway(const agraph::AGraph& g, const Eigen::Vector2d& p, double slack) {
  for (const auto& d : g.doorways) {
    if (!d.InWall()) continue;
    const double half = 0.5 * (d.width > 0 ? d.width : 0.9) + slack;
    if (d.wall < 0) {  // its wall on another storey: the passage across the nearest outline
      if ((p - d.position.head<2>()).norm() <= std::hypot(half, 0.3 + slack)) return true;
      continue;
    }
    const auto& wall = g.walls[d.wall];
    const Eigen::Vector2d n = g.surfaces[wall.surface_a].plane.normal.head<2>().normalized();
    const Eigen::Vector2d t(-n.y(), n.x());
    const Eigen::Vector2d r = p - d.position.head<2>();
    if (std::abs(r.dot(t)) <= half && std::abs(r.dot(n)) <= wall.thickness + 0.2) return true;
  }
  return false;
}

/// The free cell of room `r` nearest to the doorway `d` (its centre 20 cm inside the room's
/// outline, within 2 m of the doorway); (-1, -1) when there is none.
Eigen::Vector2i CellBy(const OccupancyGrid& grid, const agraph::Room& r, const agraph::Doorway& d) {
  const Eigen::Vector2i c = grid.CellOf(d.position.head<2>());
  const int n = static_cast<int>(2.0 / grid.resolution);
  Eigen::Vector2i best(-1, -1);
  double best_distance = 1e9;
  for (int dy = -n; dy <= n; ++dy)
    for (int dx = -n; dx <= n; ++dx) {
      const int x = c.x() + dx, y = c.y() + dy;
      if (!grid.Contains(x, y) || grid.At(x, y) != OccupancyGrid::kFree) continue;
      const double distance = std::hypot(dx, dy);
      if (distance >= best_distance ||
          SignedDistanceToPolygon(r.polygon, grid.CentreOf(x, y)) < 0.2)
        continue;
      best = {x, y}, best_distance = distance;
    }
  return best;
}

/// Whether `p` lies in one of the storey's rooms or doorway passages (`slack` m outside too).
bool InRoomOrDoorway(const agraph::AGraph& g, const Eigen::Vector2d& p, double slack) {
  for (const auto& r : g.rooms)
    if (r.polygon.size() >= 3 && SignedDistanceToPolygon(r.polygon, p) > -slack) return true;
  return InDoorway(g, p, slack);
}

TEST(NavigationGrid, EveryStoreyOfEveryBuilding) {
  const auto buildings = NavigationBuildings();
  if (buildings.empty()) GTEST_SKIP() << "no building converts here (make setup)";
  const GridConfig config;
  int storeys = 0, surfaces = 0, joined = 0;
  for (const auto& b : buildings) {
    for (size_t s = 0; s < b.graph->storeys.size(); ++s) {
      const auto one = agraph::SelectStorey(*b.graph, static_cast<int>(s));
      ASSERT_TRUE(one.ok()) << one.error();
      const agraph::AGraph& g = one.value();
      const std::string where = b.name + " storey '" + g.storeys[0].name + "'";
      const auto built = BuildStoreyGrid(g, b.mesh, config);
      if (g.rooms.empty() && g.walls.empty()) {
        EXPECT_FALSE(built.ok()) << where;
        continue;
      }
      ASSERT_TRUE(built.ok()) << where << ": " << built.error();
      const OccupancyGrid& grid = built.value();
      ++storeys;
      // Every wall face reaching into the robot's band: within one cell of an occupied cell
      // (where no doorway passes through it).
      const double z0 = grid.elevation + config.slice_min, z1 = grid.elevation + config.slice_max;
      for (const auto& f : g.surfaces) {
        if (f.z_max < z0 || f.z_min > z1) continue;
        ++surfaces;
        const int n = 1 + static_cast<int>(f.Length() / config.resolution);
        int missed = 0;
        for (int i = 0; i <= n; ++i) {
          const Eigen::Vector2d p = f.start + (f.end - f.start) * (double(i) / n);
          if (!InDoorway(g, p, config.resolution) && !grid.OccupiedNear(p, 1)) ++missed;
        }
        EXPECT_EQ(missed, 0) << where << ": surface " << f.id << " of wall " << f.wall;
      }
      // Outside the building: never free (unknown, or an element built there); free cells lie in
      // rooms and doorways (every 5th cell each way checked, a cell of slack).
      int free_outside = 0, free_sampled = 0;
      for (int iy = 0; iy < grid.height; iy += 5)
        for (int ix = 0; ix < grid.width; ix += 5) {
          if (grid.At(ix, iy) != OccupancyGrid::kFree) continue;
          ++free_sampled;
          free_outside += !InRoomOrDoorway(g, grid.CentreOf(ix, iy), config.resolution);
        }
      EXPECT_EQ(free_outside, 0) << where << ": of " << free_sampled << " free cells sampled";
      for (int ix = 0; ix < grid.width; ++ix)
        EXPECT_NE(grid.At(ix, 0), OccupancyGrid::kFree) << where << " cell " << ix << ", 0";
      // A path between every two rooms a doorway joins.
      for (const auto& d : g.doorways) {
        if (d.rooms.size() != 2) continue;
        ++joined;
        const auto a = CellBy(grid, g.rooms[d.rooms[0]], d);
        const auto c = CellBy(grid, g.rooms[d.rooms[1]], d);
        EXPECT_FALSE(FindPath(grid, a, c).empty())
            << where << ": no path through doorway '" << d.name << "' (" << d.guid << ") from "
            << g.rooms[d.rooms[0]].name << " to " << g.rooms[d.rooms[1]].name;
      }
    }
  }
  RecordProperty("storeys", storeys);
  RecordProperty("surfaces", surfaces);
  RecordProperty("doorways", joined);
  std::printf(
      "[ grid     ] %d storeys of %zu buildings: %d wall faces, %d doorways joining two rooms\n",
      storeys, buildings.size(), surfaces, joined);
}

TEST(NavigationGrid, AStarGoesAroundWallsAndFailsThroughThem) {
  OccupancyGrid grid;
  grid.width = 10, grid.height = 5;
  grid.cells.assign(50, OccupancyGrid::kFree);
  for (int iy = 0; iy < 4; ++iy) grid.At(5, iy) = OccupancyGrid::kOccupied;
  const auto path = FindPath(grid, {0, 0}, {9, 0});
  ASSERT_FALSE(path.empty());
  for (const auto& c : path) EXPECT_NE(grid.At(c.x(), c.y()), OccupancyGrid::kOccupied);
  grid.At(5, 4) = OccupancyGrid::kUnknown;  // unknown is no way through either
  EXPECT_TRUE(FindPath(grid, {0, 0}, {9, 0}).empty());
  EXPECT_TRUE(FindPath(grid, {5, 0}, {9, 0}).empty());  // start on a wall
}

TEST(NavigationGrid, BadConfigAndStoreysAreErrors) {
  std::string why;
  const agraph::AGraph* g = testing::LoadBuildingOnce(testing::ProjectBim("tower.ifc"), &why);
  if (!g) GTEST_SKIP() << why;
  GridConfig bad;
  bad.resolution = 0.0;
  const auto one = agraph::SelectStorey(*g, 0);
  ASSERT_TRUE(one.ok());
  EXPECT_NE(BuildStoreyGrid(one.value(), nullptr, bad).error().find("resolution"),
            std::string::npos);
  EXPECT_NE(BuildStoreyGrid(*g, nullptr, GridConfig{}).error().find("per storey"),
            std::string::npos);
}

TEST(NavigationGrid, MapServerFilesRoundTrip) {
  std::string why;
  const agraph::AGraph* g = testing::LoadBuildingOnce(testing::ProjectBim("office.ifc"), &why);
  if (!g) GTEST_SKIP() << why;
  const auto grid = BuildStoreyGrid(agraph::SelectStorey(*g, 0).value(), nullptr, GridConfig{});
  ASSERT_TRUE(grid.ok()) << grid.error();
  const std::string dir = testing::ScratchDir("navigation_map_files");
  ASSERT_EQ(WriteMapFiles(grid.value(), dir + "/office.yaml"), "");
  const std::string yaml = testing::ReadFile(dir + "/office.yaml");
  EXPECT_NE(yaml.find("image: office.pgm\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("resolution: 0.05\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"), std::string::npos);
  OccupancyGrid back = grid.value();
  std::fill(back.cells.begin(), back.cells.end(), OccupancyGrid::kFree);
  ASSERT_EQ(ReadMapImage(dir + "/office.pgm", back), "");
  EXPECT_EQ(back.cells, grid.value().cells);
}

}  // namespace
}  // namespace navigation
}  // namespace is_graphs
