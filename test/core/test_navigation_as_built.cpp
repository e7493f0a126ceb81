// The as-built grid (bim_map/as_built) of scenario H6 (bags/H6_office_as_built.yaml): the
// office with p_n3 not built, p_s2 built 35 cm off and two extra partitions, as the
// `deviations` topic reports them (statuses, GlobalIds, plan extents).
#include <gtest/gtest.h>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/navigation/occupancy_grid.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace navigation {
namespace {

const agraph::Wall* WallNamed(const agraph::AGraph& g, const std::string& name) {
  for (const auto& w : g.walls)
    if (w.name == name) return &w;
  return nullptr;
}

merging::WallDeviation Reported(const agraph::AGraph& g, const agraph::Wall& w,
                                merging::WallStatus status, double offset = 0.0) {
  merging::WallDeviation d;
  d.wall_id = 1000 + w.id;  // the merger's storey graph numbers walls its own way: unused
  d.guid = w.guid;
  d.status = status;
  d.offset = offset;
  const auto footprint = WallFootprint(g, w);
  d.start = 0.5 * (footprint[0] + footprint[3]);  // the mid-line's ends
  d.end = 0.5 * (footprint[1] + footprint[2]);
  return d;
}

merging::WallDeviation Extra(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  merging::WallDeviation d;
  d.status = merging::WallStatus::kExtra;
  d.start = a, d.end = b;
  return d;
}

std::int8_t At(const OccupancyGrid& grid, const Eigen::Vector2d& p) {
  const auto c = grid.CellOf(p);
  return grid.Contains(c.x(), c.y()) ? grid.At(c.x(), c.y()) : OccupancyGrid::kUnknown;
}

TEST(NavigationAsBuilt, H6FreesItsNotBuiltWallMovesOneAndBlocksItsExtraOnes) {
  std::string why;
  const agraph::AGraph* office = testing::LoadBuildingOnce(testing::ProjectBim("office.ifc"), &why);
  if (!office) GTEST_SKIP() << why;
  const agraph::AGraph g = agraph::SelectStorey(*office, 0).value();
  const agraph::Wall* n3 = WallNamed(g, "p_n3");
  const agraph::Wall* s2 = WallNamed(g, "p_s2");
  ASSERT_TRUE(n3 && s2);
  const std::vector<merging::WallDeviation> deviations = {
      Reported(g, *n3, merging::WallStatus::kNotBuilt),
      Reported(g, *s2, merging::WallStatus::kMoved, 0.35),
      Reported(g, *WallNamed(g, "p_n1"), merging::WallStatus::kAsPlanned),
      Extra({16.8, 12.0}, {16.8, 10.5}), Extra({0.8, 3.2}, {0.8, 4.7})};
  const GridConfig config;
  const auto planned = BuildStoreyGrid(g, nullptr, config);
  const auto built = BuildStoreyGrid(g, nullptr, config, &deviations);
  ASSERT_TRUE(planned.ok() && built.ok());
  const OccupancyGrid& p = planned.value();
  const OccupancyGrid& b = built.value();
  ASSERT_EQ(p.width, b.width);
  ASSERT_EQ(p.origin, b.origin);

  // NOT_BUILT: p_n3's footprint (away from its ends, where other walls meet it) freed.
  const auto n3_foot = WallFootprint(g, *n3);
  const Eigen::Vector2d n3_a = 0.5 * (n3_foot[0] + n3_foot[3]),
                        n3_b = 0.5 * (n3_foot[1] + n3_foot[2]);
  for (double t = 0.2; t <= 0.8; t += 0.05) {
    const Eigen::Vector2d q = n3_a + t * (n3_b - n3_a);
    EXPECT_EQ(At(p, q), OccupancyGrid::kOccupied) << "planned p_n3 at t " << t;
    EXPECT_EQ(At(b, q), OccupancyGrid::kFree) << "as built p_n3 at t " << t;
  }
  // MOVED 35 cm along its first face's normal: the plan's place free, the built one occupied.
  const auto s2_foot = WallFootprint(g, *s2);
  const Eigen::Vector2d s2_mid = 0.25 * (s2_foot[0] + s2_foot[1] + s2_foot[2] + s2_foot[3]);
  const Eigen::Vector2d normal = g.surfaces[s2->surface_a].plane.normal.head<2>().normalized();
  const Eigen::Vector2d along = (s2_foot[1] - s2_foot[0]).normalized();
  for (double s : {-1.0, 0.0, 1.0}) {
    EXPECT_EQ(At(p, s2_mid + s * along), OccupancyGrid::kOccupied);
    EXPECT_EQ(At(b, s2_mid + s * along), OccupancyGrid::kFree) << "plan place of p_s2, " << s;
    EXPECT_EQ(At(b, s2_mid + s * along + 0.35 * normal), OccupancyGrid::kOccupied) << s;
  }
  // EXTRA: blocked along their length (free in the plan).
  for (const auto& [a, c] :
       {std::pair<Eigen::Vector2d, Eigen::Vector2d>{{16.8, 12.0}, {16.8, 10.5}},
        {{0.8, 3.2}, {0.8, 4.7}}})
    for (double t = 0.1; t <= 0.91; t += 0.1) {  // (16.8, 12) touches the corridor's wall
      EXPECT_EQ(At(p, a + t * (c - a)), OccupancyGrid::kFree) << a.transpose() << " t " << t;
      EXPECT_EQ(At(b, a + t * (c - a)), OccupancyGrid::kOccupied) << a.transpose() << " t " << t;
    }
  // A wall AS_PLANNED stays put: the grids differ only near the deviations.
  const auto n1_foot = WallFootprint(g, *WallNamed(g, "p_n1"));
  const Eigen::Vector2d n1_mid = 0.25 * (n1_foot[0] + n1_foot[1] + n1_foot[2] + n1_foot[3]);
  EXPECT_EQ(At(b, n1_mid), OccupancyGrid::kOccupied);
}

TEST(NavigationAsBuilt, DeviationsOfAnotherWallChangeNothing) {
  std::string why;
  const agraph::AGraph* office = testing::LoadBuildingOnce(testing::ProjectBim("office.ifc"), &why);
  if (!office) GTEST_SKIP() << why;
  const agraph::AGraph g = agraph::SelectStorey(*office, 0).value();
  merging::WallDeviation unknown;
  unknown.guid = "0000000000000000000000";  // no wall of this building
  unknown.status = merging::WallStatus::kNotBuilt;
  const std::vector<merging::WallDeviation> deviations = {unknown};
  const auto planned = BuildStoreyGrid(g, nullptr, GridConfig{});
  const auto built = BuildStoreyGrid(g, nullptr, GridConfig{}, &deviations);
  ASSERT_TRUE(planned.ok() && built.ok());
  EXPECT_EQ(planned.value().cells, built.value().cells);
}

}  // namespace
}  // namespace navigation
}  // namespace is_graphs
