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
// faces bound a room shifted `shift` along its plan normal and turned `turn` about the vertical
// through its centre, seen from M under `truth`.
Built MakeBuilt(double shift, const Eigen::Isometry3d& truth, double turn = 0.0) {
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
  const Eigen::Matrix3d r = geometry::RotationZ(turn);
  const Eigen::Vector2d c = w.center.head<2>();
  for (int id : {w.surface_a, w.surface_b}) {
    agraph::WallSurface& f = built.surfaces[id];
    f.plane.d += shift * f.plane.normal.dot(m);
    f.start += shift * m.head<2>();
    f.end += shift * m.head<2>();
    const Eigen::Vector3d on(f.start.x(), f.start.y(), 0.0);  // a point of the face
    f.plane.normal = r * f.plane.normal;
    f.start = c + r.topLeftCorner<2, 2>() * (f.start - c);
    f.end = c + r.topLeftCorner<2, 2>() * (f.end - c);
    const Eigen::Vector3d c3(c.x(), c.y(), 0.0);
    f.plane.d = f.plane.normal.dot(c3 + r * (on - c3));
  }
  matching::SyntheticSGraphConfig config;
  config.bim_T_map = truth;
  b.s = matching::MakeSyntheticSGraph(built, config);
  return b;
}

MergeSolution Solve(const Built& b, const Eigen::Isometry3d& truth, bool deviations,
                    const std::map<int, Eigen::Vector2d>& initial = {},
                    double turn_release_deg = MergerConfig().wall_turn_release_deg,
                    int unseen_surface = -1,
                    bool with_rooms = true) {
  MatchPairs pairs;
  if (with_rooms)
    for (const auto& [s, a] : b.s.room_truth) pairs.rooms[s] = a;
  for (const auto& [s, a] : b.s.plane_truth)
    if (a != unseen_surface) pairs.surfaces[s].push_back(a);
  MergerConfig config;
  config.optimize_sgraph = false;
  config.estimate_wall_deviations = deviations;
  config.wall_turn_release_deg = turn_release_deg;
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
  // (4.9 cm held, 0.24 cm free when written: the offset prior's Cauchy tail still pulls.)
  EXPECT_LT(PositionError(free, truth), 0.005);
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

// A wall 30 cm off makes both its rooms' centres stand 15 cm from the plan's. Matched to the
// planned centres they pulled the pose: 4.9 mm, against 5.6 mm with no room pairs at all. The
// room matches now move the A-rooms' centres with the walls' offsets: they help (2.4 mm).
TEST(WallDeviationState, TheRoomsOfAWallOffThePlanMoveWithIt) {
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  const Built b = MakeBuilt(0.30, truth);
  const MergeSolution rooms = Solve(b, truth, true);
  const MergeSolution no_rooms = Solve(b, truth, true, {}, 1.0, -1, false);
  ASSERT_TRUE(rooms.usable && no_rooms.usable);
  ASSERT_FALSE(rooms.rooms.empty());
  ASSERT_TRUE(no_rooms.rooms.empty());
  std::printf("wall built 0.30 m off: B_x_M %.4f m with the room matches, %.4f m without\n",
              PositionError(rooms, truth), PositionError(no_rooms, truth));
  EXPECT_LT(PositionError(rooms, truth), 0.6 * PositionError(no_rooms, truth));
  EXPECT_LT(PositionError(rooms, truth), 0.0035);
  EXPECT_NEAR(Find(rooms, b.moved_wall)->offset, 0.30, 0.02);
}

double YawError(const MergeSolution& out, const Eigen::Isometry3d& truth) {
  return std::abs(out.bim_x_map.z() - geometry::ToXYYaw(truth).z());
}

// H8: a partition turned 4° (the large floor's Lab) held at the plan by its turn's stiff prior
// pulled the pose's yaw, and the position with it far from M's origin. Released, it turns.
TEST(WallDeviationState, AWallTurnedFourDegreesTurnsInsteadOfThePose) {
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  const Built b = MakeBuilt(0.0, truth, 4.0 * kDeg);
  const int back = b.plan.walls[b.moved_wall].surface_b;  // seen from one room, as in H8
  const MergeSolution held = Solve(b, truth, true, {}, 90.0, back);
  const MergeSolution released = Solve(b, truth, true, {}, 1.0, back);
  ASSERT_TRUE(held.usable && released.usable);
  std::printf("yaw error with the turn held %.4f deg, released %.4f deg; B_x_M %.4f / %.4f m\n",
              YawError(held, truth) / kDeg, YawError(released, truth) / kDeg,
              PositionError(held, truth), PositionError(released, truth));
  // (0.25° and 2.8 cm held, 0.003° and 0.2 mm released when written: released, its turn has
  // no prior; with the prior's Cauchy tail kept it was 0.08° and 0.5 cm.)
  EXPECT_LT(YawError(released, truth), 0.5 * YawError(held, truth));
  EXPECT_LT(YawError(released, truth), 0.02 * kDeg);
  EXPECT_LT(PositionError(released, truth), 0.25 * PositionError(held, truth));
  EXPECT_LT(PositionError(released, truth), 0.002);
  const WallDeviationEstimate* turned = Find(released, b.moved_wall);
  ASSERT_NE(turned, nullptr);
  EXPECT_NEAR(turned->angle, 4.0 * kDeg, 0.1 * kDeg);
  EXPECT_LT(std::abs(Find(held, b.moved_wall)->angle), 1.0 * kDeg) << "held at the plan";
}

// A yaw error of B_x_M turns every wall alike: against the walls' median nothing is released.
TEST(WallDeviationState, TurnsAreReleasedAgainstTheMedianOfTheWalls) {
  const double release = 1.0 * kDeg;
  std::map<int, std::vector<double>> turns = {
      {0, {2.0 * kDeg}}, {1, {2.1 * kDeg, 1.9 * kDeg}}, {2, {2.0 * kDeg}}, {3, {6.0 * kDeg}}};
  const std::map<int, double> turned = TurnedWalls(turns, release);
  ASSERT_EQ(turned.size(), 1u);
  EXPECT_NEAR(turned.at(3), 4.0 * kDeg, 1e-12);  // 6° against the median's 2°
  const auto starts = ReleasedTurns(turned, {{0, {0.05, 0.0}}});
  ASSERT_EQ(starts.count(3), 1u);
  EXPECT_NEAR(starts.at(3).y(), 4.0 * kDeg, 1e-12);
  EXPECT_EQ(starts.count(1), 0u);
  EXPECT_EQ(starts.at(0), Eigen::Vector2d(0.05, 0.0));  // kept as it was
  // A state already half-way or more is left where the last solve put it.
  const auto again = ReleasedTurns(turned, {{3, {0.0, 3.0 * kDeg}}});
  EXPECT_NEAR(again.at(3).y(), 3.0 * kDeg, 1e-12);
  // Two walls give no median: nothing is released.
  turns.erase(0);
  turns.erase(1);
  EXPECT_TRUE(TurnedWalls(turns, release).empty());
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
