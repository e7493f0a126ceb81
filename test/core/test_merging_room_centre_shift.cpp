// How an A-room's centre moves with its walls' as-built offsets (issue 21): RoomCentreShifts
// against the centroid of the polygon moved by hand, and DeviatedRoomMatchCost on known values.
#include <ceres/dynamic_numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "cost_test_util.h"
#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/merging/cost/deviated_room_match_cost.h"
#include "is_graphs/merging/cost/room_match_cost.h"
#include "is_graphs/merging/room_centre_shift.h"

namespace is_graphs {
namespace merging {
namespace {

using Eigen::Vector2d;
constexpr double kDeg = M_PI / 180.0;

Vector2d Centroid(const std::vector<Vector2d>& p) {
  double twice_area = 0.0;
  Vector2d c = Vector2d::Zero();
  for (size_t i = 0; i < p.size(); ++i) {
    const Vector2d& a = p[i];
    const Vector2d& b = p[(i + 1) % p.size()];
    const double cross = a.x() * b.y() - b.x() * a.y();
    twice_area += cross;
    c += cross * (a + b);
  }
  return c / (3.0 * twice_area);
}

// An L-shaped room, counter-clockwise, one 0.2 m wall per edge. Its room faces are surface_a of
// the even walls and surface_b of the odd ones (the shift must not depend on which face is
// first).
agraph::AGraph LShapedRoom() {
  const std::vector<Vector2d> p = {{0, 0}, {6, 0}, {6, 3}, {3, 3}, {3, 5}, {0, 5}};
  agraph::AGraph g;
  agraph::Room room;
  room.polygon = p;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vector2d a = p[i], b = p[(i + 1) % p.size()];
    const Vector2d t = (b - a).normalized();
    const Vector2d in(-t.y(), t.x());  // left of a counter-clockwise edge
    agraph::Wall w;
    w.id = static_cast<int>(i);
    w.thickness = 0.2;
    const Vector2d mid = 0.5 * (a + b);
    w.center = Eigen::Vector3d(mid.x() - 0.1 * in.x(), mid.y() - 0.1 * in.y(), 1.5);
    for (int face = 0; face < 2; ++face) {
      agraph::WallSurface s;
      s.id = static_cast<int>(g.surfaces.size());
      s.wall = w.id;
      const Vector2d n = face == 0 ? in : Vector2d(-in);
      const Vector2d on = face == 0 ? a : Vector2d(a - 0.2 * in);
      s.plane = geometry::Plane::FromPointNormal(Eigen::Vector3d(on.x(), on.y(), 0.0),
                                                 Eigen::Vector3d(n.x(), n.y(), 0.0));
      s.start = face == 0 ? a : Vector2d(b - 0.2 * in);
      s.end = face == 0 ? b : Vector2d(a - 0.2 * in);
      if (face == 0) room.surfaces.push_back(s.id);
      g.surfaces.push_back(s);
    }
    w.surface_a = i % 2 == 0 ? 2 * w.id : 2 * w.id + 1;
    w.surface_b = i % 2 == 0 ? 2 * w.id + 1 : 2 * w.id;
    g.walls.push_back(w);
  }
  g.rooms.push_back(room);
  return g;
}

// The room's polygon with wall `wall` built δ off along its plan normal n_w: each vertex on that
// wall's room face moved along the face's normal n_s by δ (n_w · n_s) (its neighbours run along
// n_s, so they only lengthen or shorten).
std::vector<Vector2d> Moved(const agraph::AGraph& g, int wall, double delta) {
  const agraph::Wall& w = g.walls[wall];
  const Vector2d n_w = g.surfaces[w.surface_a].plane.normal.head<2>();
  int face = -1;
  for (int s : g.rooms[0].surfaces)
    if (g.surfaces[s].wall == wall) face = s;
  const Vector2d n_s = g.surfaces[face].plane.normal.head<2>();
  std::vector<Vector2d> p = g.rooms[0].polygon;
  for (Vector2d& v : p) {
    if (std::abs((v - g.surfaces[face].start).dot(n_s)) > 1e-9) continue;
    v += delta * n_w.dot(n_s) * n_s;
  }
  return p;
}

TEST(RoomCentreShifts, MatchTheMovedPolygonsCentroid) {
  const agraph::AGraph g = LShapedRoom();
  const std::vector<RoomCentreShift> shifts = RoomCentreShifts(g, g.rooms[0]);
  ASSERT_EQ(shifts.size(), g.walls.size()) << "one entry per wall bounding the room";
  const Vector2d c0 = Centroid(g.rooms[0].polygon);
  for (const RoomCentreShift& s : shifts) {
    for (const double delta : {0.01, -0.01}) {
      const Vector2d moved = Centroid(Moved(g, s.wall, delta)) - c0;
      const Vector2d predicted = s.per_offset * delta;
      EXPECT_GT(moved.norm(), 1e-4) << "wall " << s.wall;
      EXPECT_LT((moved - predicted).norm(), 0.02 * moved.norm())
          << "wall " << s.wall << " δ " << delta << ": centroid moved " << moved.transpose()
          << ", predicted " << predicted.transpose();
    }
  }
}

TEST(RoomCentreShifts, ARectanglesWallMovedMovesItsCentreHalfAsFar) {
  auto loaded = agraph::LoadAGraph(testing::TwoRoomsPath());
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const agraph::AGraph& g = loaded.value();
  const agraph::Room& room = g.rooms[0];  // 3.9 m x 4.0 m
  for (const RoomCentreShift& s : RoomCentreShifts(g, room)) {
    const Vector2d n_w = g.surfaces[g.walls[s.wall].surface_a].plane.normal.head<2>();
    // The wall's whole face bounds the room: 10 cm along n_w moves the centre 5 cm along n_w.
    EXPECT_LT((s.per_offset * 0.1 - 0.05 * n_w).norm(), 1e-9) << "wall " << s.wall;
  }
  EXPECT_EQ(RoomCentreShifts(g, room).size(), room.walls.size());
  agraph::Room no_polygon = room;
  no_polygon.polygon.resize(2);
  EXPECT_TRUE(RoomCentreShifts(g, no_polygon).empty());
}

TEST(DeviatedRoomMatchCost, WithoutDeviationsItIsRoomMatchCost) {
  const double xi[3] = {1.0, -2.0, 30.0 * kDeg}, rho[2] = {2.0, 0.5}, alpha[3] = {3.1, -0.2, 1.4};
  std::unique_ptr<ceres::CostFunction> plain(RoomMatchCost::Create(0.15));
  std::unique_ptr<ceres::CostFunction> deviated(
      DeviatedRoomMatchCost::Create({}, Vector2d::Zero(), 0.15));
  const double* blocks[] = {xi, rho, alpha};
  double r1[2], r2[2];
  ASSERT_TRUE(plain->Evaluate(blocks, r1, nullptr));
  ASSERT_TRUE(deviated->Evaluate(blocks, r2, nullptr));
  EXPECT_NEAR(r1[0], r2[0], 1e-12);
  EXPECT_NEAR(r1[1], r2[1], 1e-12);
}

TEST(DeviatedRoomMatchCost, HandComputed) {
  // ξ identity; ρ = (2, 1); α = (2.05, 1); one wall, g = (0.5, 0) (a rectangle's east wall),
  // built δ = 0.1 along x (and turned, which does not count): the centre matched is
  // 2.05 + 0.05 = 2.10, e = (−0.1, 0).
  const double xi[3] = {0.0, 0.0, 0.0}, rho[2] = {2.0, 1.0}, alpha[3] = {2.05, 1.0, 0.0};
  const double dev[2] = {0.1, 3.0 * kDeg};
  const Vector2d j(0.5, 0.0);
  const double* blocks[] = {xi, rho, alpha, dev};
  std::unique_ptr<ceres::CostFunction> room(
      DeviatedRoomMatchCost::Create({j}, Vector2d::Zero(), 0.2));
  ASSERT_EQ(room->num_residuals(), 2);
  double r[2];
  ASSERT_TRUE(room->Evaluate(blocks, r, nullptr));
  EXPECT_NEAR(r[0], -0.1 / 0.2, 1e-12);
  EXPECT_NEAR(r[1], 0.0, 1e-12);
  // A corridor across x: only that component; across y: nothing.
  std::unique_ptr<ceres::CostFunction> across_x(
      DeviatedRoomMatchCost::Create({j}, Vector2d::UnitX(), 0.2));
  std::unique_ptr<ceres::CostFunction> across_y(
      DeviatedRoomMatchCost::Create({j}, Vector2d::UnitY(), 0.2));
  ASSERT_EQ(across_x->num_residuals(), 1);
  ASSERT_TRUE(across_x->Evaluate(blocks, r, nullptr));
  EXPECT_NEAR(r[0], -0.5, 1e-12);
  ASSERT_TRUE(across_y->Evaluate(blocks, r, nullptr));
  EXPECT_NEAR(r[0], 0.0, 1e-12);
}

TEST(DeviatedRoomMatchCost, AutodiffMatchesNumericJacobian) {
  const Vector2d j1(0.5, -0.1), j2(-0.2, 0.4);
  for (const Vector2d& across : {Vector2d::Zero().eval(), Vector2d(0.6, 0.8)}) {
    DeviatedRoomMatchCost functor({j1, j2}, across, 0.15);
    ceres::DynamicNumericDiffCostFunction<DeviatedRoomMatchCost, ceres::CENTRAL> numeric(
        &functor, ceres::DO_NOT_TAKE_OWNERSHIP);
    for (int size : {3, 2, 3, 2, 2}) numeric.AddParameterBlock(size);
    numeric.SetNumResiduals(across.norm() > 0 ? 1 : 2);
    std::unique_ptr<ceres::CostFunction> autodiff(
        DeviatedRoomMatchCost::Create({j1, j2}, across, 0.15));
    const double xi[3] = {0.4, -1.0, 25.0 * kDeg}, rho[2] = {1.5, 2.5}, alpha[3] = {1.0, 2.0, 0.5};
    const double d1[2] = {0.08, 2.0 * kDeg}, d2[2] = {-0.2, -1.0 * kDeg};
    testing::ExpectSameEvaluation(*autodiff, numeric, {xi, rho, alpha, d1, d2});
  }
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
