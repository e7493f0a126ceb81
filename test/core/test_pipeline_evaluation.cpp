// The evaluation measures of `make evaluate` on known inputs: the wrong-match classification of
// a B_x_M against the truth, and the point-cloud error against the BIM's wall-surfaces on a
// synthetic cloud with known offsets.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/pipeline/evaluation.h"

namespace is_graphs {
namespace pipeline {
namespace {

constexpr double kDeg = M_PI / 180.0;

// One 4 x 3 m room, walls 0..2.5 m high; surface normals point into the room.
agraph::AGraph OneRoom() {
  agraph::AGraph g;
  auto add = [&](Eigen::Vector3d n, double d, Eigen::Vector2d a, Eigen::Vector2d b) {
    agraph::WallSurface s;
    s.id = static_cast<int>(g.surfaces.size());
    s.plane = geometry::Plane(n, d);
    s.start = a;
    s.end = b;
    s.z_min = 0.0;
    s.z_max = 2.5;
    g.surfaces.push_back(s);
  };
  add({0, 1, 0}, 0.0, {0, 0}, {4, 0});    // south, y = 0
  add({0, -1, 0}, -3.0, {4, 3}, {0, 3});  // north, y = 3
  add({1, 0, 0}, 0.0, {0, 3}, {0, 0});    // west, x = 0
  add({-1, 0, 0}, -4.0, {4, 0}, {4, 3});  // east, x = 4
  return g;
}

TEST(PipelineEvaluation, TransformErrorIsTheWorstDisplacementOnTheMap) {
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(5.0, -2.0, 30 * kDeg);
  // 1 degree off about M's origin: 0 m there, 20 m * 1 deg = 0.35 m at a keyframe 20 m away.
  const Eigen::Isometry3d turned = truth * geometry::IsometryFromXYYaw(0.0, 0.0, 1.0 * kDeg);
  const std::vector<Eigen::Vector3d> keyframes{{0, 0, 0}, {20, 0, 0}};
  auto e = CompareTransforms(turned, truth, keyframes);
  EXPECT_NEAR(e.yaw_deg, 1.0, 1e-9);
  EXPECT_NEAR(e.xy_m, 2 * 20.0 * std::sin(0.5 * kDeg), 1e-9);
  EXPECT_FALSE(IsWrongMatch(e));
  // 2 degrees at 20 m: 0.70 m, wrong although the yaw is within 5 degrees.
  e = CompareTransforms(truth * geometry::IsometryFromXYYaw(0.0, 0.0, 2.0 * kDeg), truth,
                        keyframes);
  EXPECT_TRUE(IsWrongMatch(e));
  // A mirror-like answer: 180 degrees off.
  e = CompareTransforms(truth * geometry::IsometryFromXYYaw(0.0, 0.0, M_PI), truth, {});
  EXPECT_NEAR(e.yaw_deg, 180.0, 1e-9);
  EXPECT_TRUE(IsWrongMatch(e));
  // Shifted 0.4 m: fine; 0.6 m: wrong. No keyframes: measured at M's origin.
  const Eigen::Isometry3d shift = geometry::IsometryFromXYYaw(0.4, 0.0, 0.0);
  e = CompareTransforms(shift * truth, truth, {});
  EXPECT_NEAR(e.xy_m, 0.4, 1e-9);
  EXPECT_FALSE(IsWrongMatch(e));
  EXPECT_TRUE(IsWrongMatch(
      CompareTransforms(geometry::IsometryFromXYYaw(0.0, 0.6, 0.0) * truth, truth, {})));
  EXPECT_TRUE(IsWrongMatch({0.1, 5.5}));
}

TEST(PipelineEvaluation, CloudErrorOnKnownOffsets) {
  const agraph::AGraph room = OneRoom();
  std::vector<Eigen::Vector3f> cloud;
  // 100 points 2 cm in front of the south wall, 100 points 4 cm behind the west wall's face.
  for (int i = 0; i < 100; ++i) {
    const float s = 0.5f + 0.03f * i;  // 0.5 .. 3.47 along x (south), 0.5..2.9 along y (west)
    cloud.emplace_back(s, 0.02f, 1.2f);
    cloud.emplace_back(-0.04f, std::min(s, 2.8f), 1.0f);
  }
  // Left out: floor points near a wall, ceiling points, a point 0.5 m off every wall, a point
  // beyond the wall's end, a point in the middle of the room.
  cloud.emplace_back(1.0f, 0.05f, 0.02f);
  cloud.emplace_back(1.0f, 0.05f, 2.49f);
  cloud.emplace_back(2.0f, 0.5f, 1.0f);
  cloud.emplace_back(4.2f, 0.05f, 1.0f);
  cloud.emplace_back(2.0f, 1.5f, 1.0f);
  const CloudError e = CloudAgainstWallSurfaces(cloud, room);
  EXPECT_EQ(e.points, 205);
  EXPECT_EQ(e.used, 200);
  EXPECT_NEAR(e.rmse, std::sqrt((0.02 * 0.02 + 0.04 * 0.04) / 2), 1e-6);
  EXPECT_NEAR(e.max, 0.04, 1e-6);
  EXPECT_NEAR(e.UsedShare(), 200.0 / 205.0, 1e-12);
  // The nearest surface counts: a point 0.15 m from the south wall and 0.25 m from the west.
  const CloudError corner = CloudAgainstWallSurfaces({Eigen::Vector3f(0.25f, 0.15f, 1.0f)}, room);
  EXPECT_EQ(corner.used, 1);
  EXPECT_NEAR(corner.rmse, 0.15, 1e-6);
  // Tighter cut: 4 cm points are out at 3 cm.
  CloudErrorConfig tight;
  tight.max_distance = 0.03;
  EXPECT_EQ(CloudAgainstWallSurfaces(cloud, room, tight).used, 100);
  EXPECT_EQ(CloudAgainstWallSurfaces({}, room).used, 0);
}

// Issue 22: the storey a robot stands on, from its height (the evaluation's wrong-storey check).
TEST(PipelineEvaluation, StoreyAtHeightIsTheHighestFloorBelow) {
  agraph::AGraph building;
  for (const auto& [id, elevation] : {std::pair<int, double>{0, 0.0}, {1, -3.0}, {2, 3.55}}) {
    agraph::Storey s;
    s.id = id;
    s.elevation = elevation;
    building.storeys.push_back(s);
  }
  EXPECT_EQ(agraph::StoreyAtHeight(building, 0.5), 0);
  EXPECT_EQ(agraph::StoreyAtHeight(building, -2.5), 1);
  EXPECT_EQ(agraph::StoreyAtHeight(building, 4.05), 2);
  EXPECT_EQ(agraph::StoreyAtHeight(building, 3.52), 2);  // within 5 cm below its floor: rounding
  EXPECT_EQ(agraph::StoreyAtHeight(building, 3.40), 0);
  EXPECT_EQ(agraph::StoreyAtHeight(building, -4.0), -1);
}

// A split level: a storey whose rooms stand up to 0.6 m below its elevation begins at their
// floor (the robot there is on it, not below every storey); a room further down does not count.
TEST(PipelineEvaluation, StoreyAtHeightCountsASplitLevelsLowerFloor) {
  agraph::AGraph building;
  for (const auto& [id, elevation] : {std::pair<int, double>{0, 0.0}, {1, 3.0}}) {
    agraph::Storey s;
    s.id = id;
    s.elevation = elevation;
    s.height = 3.0;
    building.storeys.push_back(s);
  }
  EXPECT_EQ(agraph::StoreyAtHeight(building, -0.2), -1);
  agraph::Room lower;
  lower.storey = 0;
  lower.floor_z = -0.45;
  building.rooms.push_back(lower);
  agraph::Room sunk;  // on the upper storey, 1 m below it: not a split level (a bad floor)
  sunk.storey = 1;
  sunk.floor_z = 2.0;
  building.rooms.push_back(sunk);
  EXPECT_DOUBLE_EQ(agraph::StoreyFloor(building, 0), -0.45);
  EXPECT_DOUBLE_EQ(agraph::StoreyFloor(building, 1), 3.0);
  EXPECT_EQ(agraph::StoreyAtHeight(building, -0.2), 0);
  EXPECT_EQ(agraph::StoreyAtHeight(building, 2.5), 0);
  EXPECT_EQ(agraph::HeightOutsideStoreys(building, -1.4), "");  // 1 m margin
  EXPECT_NE(agraph::HeightOutsideStoreys(building, -1.5), "");
}

// Issue 22: a robot beyond every storey's height is named (the merger warns with it).
TEST(PipelineEvaluation, AHeightOutsideEveryStoreyIsNamed) {
  agraph::AGraph building;
  EXPECT_EQ(agraph::HeightOutsideStoreys(building, 100.0), "") << "no storeys: nothing to say";
  for (const auto& [elevation, height] : {std::pair<double, double>{0.0, 3.0},
                                          {-3.0, 3.0},
                                          {3.0, 0.0}}) {  // the top one without a height: 3 m
    agraph::Storey s;
    s.id = static_cast<int>(building.storeys.size());
    s.elevation = elevation;
    s.height = height;
    building.storeys.push_back(s);
  }
  for (double z : {-3.9, -2.5, 0.5, 3.5, 6.9})
    EXPECT_EQ(agraph::HeightOutsideStoreys(building, z), "") << z;
  const std::string above = agraph::HeightOutsideStoreys(building, 7.2);
  EXPECT_NE(above.find("above every storey"), std::string::npos) << above;
  EXPECT_NE(above.find("7.2"), std::string::npos) << above;
  const std::string below = agraph::HeightOutsideStoreys(building, -4.2);
  EXPECT_NE(below.find("below every storey (-3 to 6 m)"), std::string::npos) << below;
  EXPECT_EQ(agraph::HeightOutsideStoreys(building, -4.2, 1.5), "");  // the margin given
}

}  // namespace
}  // namespace pipeline
}  // namespace is_graphs
