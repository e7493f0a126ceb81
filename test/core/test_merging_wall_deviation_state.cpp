// The merge's as-built wall deviation states (issue 21): a wall built off the plan moves, not
// the robot's pose; walls built as planned stay on the plan.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "is_graphs/merging/is_graph_problem.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Built {
  agraph::AGraph plan;
  matching::SyntheticSGraph s;
  int moved_wall{-1};
};

// The two-room plan, the S-Graph of it as built (exact planes) with the one wall whose both
// faces bound a room shifted `shift` along its plan normal, seen from M under `truth`.
Built MakeBuilt(double shift, const Eigen::Isometry3d& truth) {
  Built b;
  auto loaded = agraph::LoadAGraph(testing::TwoRoomsPath());
  EXPECT_TRUE(loaded.ok()) << loaded.error();
  b.plan = loaded.value();
  agraph::AGraph built = b.plan;
  for (const agraph::Wall& w : b.plan.walls) {
    int bounding = 0;
    for (const agraph::Room& r : b.plan.rooms)
      for (int s : r.surfaces) bounding += s == w.surface_a || s == w.surface_b;
    if (bounding == 2) b.moved_wall = w.id;
  }
  EXPECT_GE(b.moved_wall, 0) << "two_rooms has no wall between its rooms";
  const agraph::Wall& w = b.plan.walls[b.moved_wall];
  const Eigen::Vector3d m = b.plan.surfaces[w.surface_a].plane.normal;
  for (int id : {w.surface_a, w.surface_b}) {
    agraph::WallSurface& f = built.surfaces[id];
    f.plane.d += shift * f.plane.normal.dot(m);
    f.start += shift * m.head<2>();
    f.end += shift * m.head<2>();
  }
  matching::SyntheticSGraphConfig config;
  config.bim_T_map = truth;
  b.s = matching::MakeSyntheticSGraph(built, config);
  return b;
}

MergeSolution Solve(const Built& b, const Eigen::Isometry3d& truth, bool deviations,
                    const std::map<int, Eigen::Vector2d>& initial = {}) {
  MatchPairs pairs;
  for (const auto& [s, a] : b.s.room_truth) pairs.rooms[s] = a;
  for (const auto& [s, a] : b.s.plane_truth) pairs.surfaces[s].push_back(a);
  MergerConfig config;
  config.optimize_sgraph = false;
  config.estimate_wall_deviations = deviations;
  Eigen::Vector3d guess = geometry::ToXYYaw(truth);
  guess += Eigen::Vector3d(0.1, -0.1, 1.0 * kDeg);  // the matcher's guess, off
  return SolveMerge(b.plan, b.s.graph, pairs, guess, guess, truth.translation().z(), config,
                    initial);
}

double PositionError(const MergeSolution& out, const Eigen::Isometry3d& truth) {
  return (out.bim_x_map.head<2>() - truth.translation().head<2>()).norm();
}

const WallDeviationEstimate* Find(const MergeSolution& out, int wall) {
  for (const auto& w : out.walls)
    if (w.wall_id == wall) return &w;
  return nullptr;
}

TEST(WallDeviationState, AWallBuiltOffThePlanMovesInsteadOfThePose) {
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  const Built b = MakeBuilt(0.30, truth);
  ASSERT_GE(b.moved_wall, 0);
  const MergeSolution held = Solve(b, truth, false);
  const MergeSolution free = Solve(b, truth, true);
  ASSERT_TRUE(held.usable && free.usable);
  std::printf("B_x_M error with the walls held to the plan %.4f m, with deviation states %.4f m\n",
              PositionError(held, truth), PositionError(free, truth));
  EXPECT_TRUE(held.walls.empty());
  // (4.9 cm held, 0.5 cm free when written: the prior's tail and the rooms' centres still pull.)
  EXPECT_LT(PositionError(free, truth), 0.01);
  EXPECT_LT(PositionError(free, truth), 0.25 * PositionError(held, truth));
  const WallDeviationEstimate* moved = Find(free, b.moved_wall);
  ASSERT_NE(moved, nullptr) << "no deviation state for the moved wall";
  EXPECT_NEAR(moved->offset, 0.30, 0.02);
  EXPECT_LT(std::abs(moved->angle), 0.1 * kDeg);
  EXPECT_GT(moved->offset_sigma, 0.0);
  EXPECT_LT(moved->offset_sigma, 0.1);
  EXPECT_GE(moved->pairs, 2);  // both faces
  for (const auto& w : free.walls) {
    if (w.wall_id == b.moved_wall) continue;
    EXPECT_LT(std::abs(w.offset), 0.01) << "wall " << w.wall_id << " was built as planned";
  }
}

// The Merger starts each revision's states where the last solve left them: a wall built off
// the plan is not searched for again from the plan (H6's merges: 40 -> 17 ms median).
TEST(WallDeviationState, StartedFromTheLastSolveItConvergesSoonerToTheSame) {
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  const Built b = MakeBuilt(0.30, truth);
  const MergeSolution cold = Solve(b, truth, true);
  std::map<int, Eigen::Vector2d> last;
  for (const auto& w : cold.walls) last[w.wall_id] = {w.offset, w.angle};
  const MergeSolution warm = Solve(b, truth, true, last);
  ASSERT_TRUE(cold.usable && warm.usable);
  std::printf("iterations from the plan %d, from the last solve %d\n", cold.iterations,
              warm.iterations);
  EXPECT_LT(warm.iterations, cold.iterations);
  EXPECT_LT(PositionError(warm, truth), 0.01);
  const WallDeviationEstimate* moved = Find(warm, b.moved_wall);
  ASSERT_NE(moved, nullptr);
  EXPECT_NEAR(moved->offset, Find(cold, b.moved_wall)->offset, 1e-3);
}

TEST(WallDeviationState, WallsBuiltAsPlannedStayOnThePlan) {
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(-7.0, 1.5, -120.0 * kDeg, 0.5);
  const Built b = MakeBuilt(0.0, truth);
  const MergeSolution out = Solve(b, truth, true);
  ASSERT_TRUE(out.usable);
  EXPECT_FALSE(out.walls.empty());
  EXPECT_LT(PositionError(out, truth), 0.002);
  for (const auto& w : out.walls) {
    EXPECT_LT(std::abs(w.offset), 0.002) << "wall " << w.wall_id;
    EXPECT_LT(std::abs(w.angle), 0.01 * kDeg) << "wall " << w.wall_id;
  }
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
