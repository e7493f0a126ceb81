// Round trips of the message conversions: core graph -> message -> core graph keeps every field.
#include <gtest/gtest.h>

#include <limits>

#include "../../src/ros/agraph_conversions.h"
#include "../../src/ros/cloud_conversions.h"
#include "../../src/ros/graph_match_conversions.h"
#include "../../src/ros/graph_match_markers.h"
#include "../../src/ros/sgraph_conversions.h"
#include "is_graphs/agraph/agraph_io.h"

namespace is_graphs {
namespace {

TEST(AGraphConversions, RoundTripKeepsTheFixture) {
  const auto loaded =
      agraph::LoadAGraph(std::string(IS_GRAPHS_SOURCE_DIR) + "/test/data/two_rooms.agraph.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  const agraph::AGraph& a = loaded.value();
  const agraph::AGraph b = ros_conversions::FromMsg(ros_conversions::ToMsg(a));
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  ASSERT_EQ(a.walls.size(), b.walls.size());
  ASSERT_EQ(a.rooms.size(), b.rooms.size());
  ASSERT_EQ(a.doorways.size(), b.doorways.size());
  ASSERT_EQ(a.storeys.size(), b.storeys.size());
  EXPECT_EQ(a.source.sha256, b.source.sha256);
  for (size_t i = 0; i < a.surfaces.size(); ++i) {
    EXPECT_EQ(a.surfaces[i].ifc_id, b.surfaces[i].ifc_id);
    EXPECT_EQ(a.surfaces[i].wall, b.surfaces[i].wall);
    EXPECT_EQ(a.surfaces[i].orientation, b.surfaces[i].orientation);
    EXPECT_EQ(a.surfaces[i].rooms, b.surfaces[i].rooms);
    EXPECT_DOUBLE_EQ(a.surfaces[i].plane.d, b.surfaces[i].plane.d);
    EXPECT_TRUE(a.surfaces[i].plane.normal.isApprox(b.surfaces[i].plane.normal, 1e-12));
    EXPECT_TRUE(a.surfaces[i].start.isApprox(b.surfaces[i].start));
    EXPECT_TRUE(a.surfaces[i].end.isApprox(b.surfaces[i].end));
    EXPECT_DOUBLE_EQ(a.surfaces[i].z_max, b.surfaces[i].z_max);
  }
  for (size_t i = 0; i < a.walls.size(); ++i) {
    EXPECT_EQ(a.walls[i].surface_a, b.walls[i].surface_a);
    EXPECT_EQ(a.walls[i].surface_b, b.walls[i].surface_b);
    EXPECT_TRUE(a.walls[i].center.isApprox(b.walls[i].center));
    EXPECT_TRUE(a.walls[i].start.isApprox(b.walls[i].start));
    EXPECT_EQ(a.walls[i].external, b.walls[i].external);
  }
  for (size_t i = 0; i < a.rooms.size(); ++i) {
    EXPECT_EQ(a.rooms[i].name, b.rooms[i].name);
    EXPECT_EQ(a.rooms[i].surfaces, b.rooms[i].surfaces);
    EXPECT_EQ(a.rooms[i].doorways, b.rooms[i].doorways);
    EXPECT_DOUBLE_EQ(a.rooms[i].floor_z, b.rooms[i].floor_z);
    ASSERT_EQ(a.rooms[i].polygon.size(), b.rooms[i].polygon.size());
    for (size_t k = 0; k < a.rooms[i].polygon.size(); ++k)
      EXPECT_TRUE(a.rooms[i].polygon[k].isApprox(b.rooms[i].polygon[k]));
  }
  for (size_t i = 0; i < a.doorways.size(); ++i) {
    EXPECT_EQ(a.doorways[i].rooms, b.doorways[i].rooms);
    EXPECT_EQ(a.doorways[i].wall, b.doorways[i].wall);
    EXPECT_TRUE(a.doorways[i].position.isApprox(b.doorways[i].position));
  }
}

sgraph::SGraph MakeSGraph() {
  sgraph::SGraph g;
  g.revision = 7;
  g.odometry_scale = 1.04;
  for (int i = 0; i < 3; ++i) {
    sgraph::Keyframe k;
    k.id = 10 + i;
    k.stamp = 100.0 + i;
    k.pose = Eigen::Translation3d(i, 2.0 * i, 0.5) *
             Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d::UnitZ());
    k.odom_pose = Eigen::Translation3d(i + 0.1, 2.0 * i, 0.5) *
                  Eigen::AngleAxisd(0.31 * i, Eigen::Vector3d::UnitZ());
    k.previous = i == 0 ? -1 : 10 + i - 1;
    k.relative_odom =
        Eigen::Translation3d(1.0, 0.0, 0.0) * Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ());
    k.odom_information = Eigen::Matrix<double, 6, 6>::Identity() * (i + 1);
    k.odom_information(0, 5) = k.odom_information(5, 0) = 0.25;
    for (int j = 0; j < i; ++j) k.slice.emplace_back(0.5f * j, -1.25f, 0.75f + j);  // 0, 1, 2
    g.keyframes.push_back(k);
  }
  sgraph::Plane p;
  p.id = 4;
  p.plane = geometry::Plane(Eigen::Vector3d(0.6, 0.8, 0.0), -2.5);
  p.orientation = geometry::Orientation::kOther;
  p.covariance = Eigen::Matrix4d::Identity() * 1e-4;
  p.covariance(0, 3) = p.covariance(3, 0) = 2e-5;
  p.start = {1.0, 2.0};
  p.end = {3.0, 4.0};
  p.z_min = 0.1;
  p.z_max = 2.7;
  p.num_points = 1234;
  g.planes.push_back(p);
  g.observations.push_back(
      {11, 4, geometry::Plane(Eigen::Vector3d(0, 1, 0), 1.5), Eigen::Matrix3d::Identity() * 40.0});
  sgraph::Room r;
  r.id = 2;
  r.type = sgraph::RoomType::kCorridor;
  r.center = {1.0, -2.0, 0.0};
  r.planes = {4, 5};
  r.keyframes = {10, 11};
  r.information = Eigen::Matrix3d::Identity() * 9.0;
  g.rooms.push_back(r);
  g.floors.push_back({0, Eigen::Vector3d(1.0, 1.0, 0.0), 0.0, {2}});
  sgraph::Doorway d;
  d.id = 176;
  d.position = {2.0, 3.0, 0.1};
  d.width = 0.85;
  d.rooms = {2};
  d.planes = {4};
  d.keyframes = {11};
  g.doorways.push_back(d);
  return g;
}

TEST(SGraphConversions, AnOdometryScaleFromAnOlderNodeIsOne) {
  is_graphs::SGraph msg = ros_conversions::ToMsg(MakeSGraph());
  for (double bad : {0.0, -1.0, 5.0, std::numeric_limits<double>::quiet_NaN()}) {
    msg.odometry_scale = bad;
    EXPECT_EQ(ros_conversions::FromMsg(msg).odometry_scale, 1.0) << bad;
  }
}

TEST(SGraphConversions, RoundTripKeepsEveryField) {
  const sgraph::SGraph a = MakeSGraph();
  const sgraph::SGraph b = ros_conversions::FromMsg(ros_conversions::ToMsg(a));
  EXPECT_EQ(a.revision, b.revision);
  EXPECT_EQ(a.odometry_scale, b.odometry_scale);
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  for (size_t i = 0; i < a.keyframes.size(); ++i) {
    EXPECT_EQ(a.keyframes[i].id, b.keyframes[i].id);
    EXPECT_EQ(a.keyframes[i].previous, b.keyframes[i].previous);
    EXPECT_NEAR(a.keyframes[i].stamp, b.keyframes[i].stamp, 1e-9);
    EXPECT_TRUE(a.keyframes[i].pose.isApprox(b.keyframes[i].pose, 1e-12));
    EXPECT_TRUE(a.keyframes[i].odom_pose.isApprox(b.keyframes[i].odom_pose, 1e-12));
    EXPECT_TRUE(a.keyframes[i].relative_odom.isApprox(b.keyframes[i].relative_odom, 1e-12));
    EXPECT_TRUE(a.keyframes[i].odom_information.isApprox(b.keyframes[i].odom_information));
    EXPECT_EQ(a.keyframes[i].slice, b.keyframes[i].slice);
  }
  ASSERT_EQ(b.planes.size(), 1u);
  EXPECT_EQ(b.planes[0].id, 4);
  EXPECT_EQ(b.planes[0].orientation, geometry::Orientation::kOther);
  EXPECT_TRUE(b.planes[0].plane.normal.isApprox(a.planes[0].plane.normal));
  EXPECT_DOUBLE_EQ(b.planes[0].plane.d, -2.5);
  EXPECT_TRUE(b.planes[0].covariance.isApprox(a.planes[0].covariance));
  EXPECT_TRUE(b.planes[0].start.isApprox(a.planes[0].start));
  EXPECT_TRUE(b.planes[0].end.isApprox(a.planes[0].end));
  EXPECT_EQ(b.planes[0].num_points, 1234);
  ASSERT_EQ(b.observations.size(), 1u);
  EXPECT_EQ(b.observations[0].keyframe, 11);
  EXPECT_EQ(b.observations[0].plane, 4);
  EXPECT_TRUE(b.observations[0].information.isApprox(a.observations[0].information));
  ASSERT_EQ(b.rooms.size(), 1u);
  EXPECT_EQ(b.rooms[0].type, sgraph::RoomType::kCorridor);
  EXPECT_EQ(b.rooms[0].planes, a.rooms[0].planes);
  EXPECT_EQ(b.rooms[0].keyframes, a.rooms[0].keyframes);
  EXPECT_TRUE(b.rooms[0].center.isApprox(a.rooms[0].center));
  ASSERT_EQ(b.floors.size(), 1u);
  EXPECT_EQ(b.floors[0].rooms, std::vector<int>{2});
  ASSERT_EQ(b.doorways.size(), 1u);
  EXPECT_EQ(b.doorways[0].id, 176);
  EXPECT_TRUE(b.doorways[0].position.isApprox(a.doorways[0].position));
  EXPECT_DOUBLE_EQ(b.doorways[0].width, 0.85);
  EXPECT_EQ(b.doorways[0].rooms, std::vector<int>{2});
  EXPECT_EQ(b.doorways[0].planes, std::vector<int>{4});
  EXPECT_EQ(b.doorways[0].keyframes, std::vector<int>{11});
}

TEST(GraphMatchConversions, RoundTripKeepsPairsAndDeviations) {
  matching::GraphMatch a;
  a.status = matching::MatchStatus::kUnique;
  a.a_graph_sha256 = "abc";
  a.s_graph_revision = 7;
  a.room_pairs = {{1, 3, 0.9}};
  a.surface_pairs = {{4, 8, 0.8}, {5, 8, 0.8}};
  a.doorway_pairs = {{2, 1, 1.0}};
  a.deviations = {{4, 11, 0.31, -0.02, true}, {9, 14, -0.12, 0.2, false}};
  a.score = 2.5;
  a.hypotheses = 1;
  a.storey = 3;
  a.competing_storeys = {0, 2};
  a.hint = "in force: pose hint (1.00, 2.00, 3.0 deg)";
  a.scan_set = 2;
  a.scan_margin = 0.05;
  a.scan_search = "2 poses within 0.05 of the best 0.8";
  const matching::GraphMatch b = ros_conversions::FromMsg(ros_conversions::ToMsg(a));
  EXPECT_EQ(b.scan_set, 2);
  EXPECT_DOUBLE_EQ(b.scan_margin, 0.05);
  EXPECT_EQ(b.scan_search, a.scan_search);
  EXPECT_EQ(b.status, a.status);
  EXPECT_EQ(b.storey, 3);
  EXPECT_EQ(b.competing_storeys, (std::vector<int>{0, 2}));
  EXPECT_EQ(b.hint, a.hint);
  EXPECT_EQ(b.s_graph_revision, 7u);
  ASSERT_EQ(b.surface_pairs.size(), 2u);
  ASSERT_EQ(b.doorway_pairs.size(), 1u);
  ASSERT_EQ(b.deviations.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(b.deviations[i].a_id, a.deviations[i].a_id);
    EXPECT_EQ(b.deviations[i].s_id, a.deviations[i].s_id);
    EXPECT_DOUBLE_EQ(b.deviations[i].offset, a.deviations[i].offset);
    EXPECT_DOUBLE_EQ(b.deviations[i].angle, a.deviations[i].angle);
    EXPECT_EQ(b.deviations[i].paired, a.deviations[i].paired);
  }
}

// A wall off the plan is drawn in the BIM frame (not lifted): from the A-surface's middle to
// the S-plane, red, in its own namespace; surface pairs lifted by s_graph_lift.
TEST(GraphMatchMarkers, DeviationsFromThePlannedFaceToTheBuiltOne) {
  agraph::AGraph a;
  agraph::WallSurface face;
  face.plane = geometry::Plane(Eigen::Vector3d::UnitX(), 2.0);  // x = 2
  face.start = {2.0, 4.0};
  face.end = {2.0, 0.0};
  face.z_max = 2.0;
  a.surfaces.push_back(face);
  sgraph::SGraph s;
  sgraph::Plane built;
  built.id = 7;
  built.plane = geometry::Plane(Eigen::Vector3d::UnitX(), 2.3);  // built 0.3 m into the room
  s.planes.push_back(built);
  matching::GraphMatch m;
  m.status = matching::MatchStatus::kUnique;
  m.surface_pairs = {{0, 7, 0.1}};
  m.deviations = {{0, 7, 0.3, 0.0, true}, {5, 7, 0.3, 0.0, false}};  // the second: unknown face
  ros_markers::GraphMatchMarkerStyle style;
  const auto array = ros_markers::BuildGraphMatchMarkers(m, a, s, style);
  const visualization_msgs::Marker* deviations = nullptr;
  const visualization_msgs::Marker* surfaces = nullptr;
  for (const auto& marker : array.markers) {
    if (marker.ns == "deviations") deviations = &marker;
    if (marker.ns == "surface_pairs") surfaces = &marker;
  }
  ASSERT_NE(deviations, nullptr);
  ASSERT_EQ(deviations->points.size(), 2u);  // the unknown face is left out
  EXPECT_DOUBLE_EQ(deviations->points[0].x, 2.0);
  EXPECT_DOUBLE_EQ(deviations->points[0].y, 2.0);
  EXPECT_DOUBLE_EQ(deviations->points[1].x, 2.3);
  EXPECT_DOUBLE_EQ(deviations->points[1].z, 1.0);  // not lifted
  ASSERT_NE(surfaces, nullptr);
  ASSERT_EQ(surfaces->points.size(), 2u);
  EXPECT_DOUBLE_EQ(surfaces->points[1].z, 1.0 + style.s_graph_lift);
}

TEST(CloudConversions, RoundTripDropsNothingFinite) {
  const std::vector<Eigen::Vector3d> points = {{1, 2, 3}, {-4.5, 0.25, 1e3}, {0, 0, 0}};
  const auto back = ros_conversions::FromCloudMsg(ros_conversions::ToCloudMsg(points, "bim"));
  ASSERT_EQ(back.size(), points.size());
  for (size_t i = 0; i < points.size(); ++i) EXPECT_TRUE(back[i].isApprox(points[i], 1e-6));
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
