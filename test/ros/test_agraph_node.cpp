// rostest of agraph_node: its latched topics against an independent load of the same building,
// the robot description's tf, and the real node binary on bad inputs.
#include <gtest/gtest.h>
#include <is_graphs/AGraph.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <sys/wait.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "../../src/ros/agraph_conversions.h"
#include "../../src/ros/cloud_conversions.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/geometry/triangle_mesh.h"
#include "node_runner.h"

namespace is_graphs {
namespace {

const std::string kOffice = std::string(IS_GRAPHS_SOURCE_DIR) + "/bim/office.ifc";

template <typename M>
boost::shared_ptr<const M> WaitFor(const std::string& topic, double seconds) {
  ros::NodeHandle nh;
  return ros::topic::waitForMessage<M>(topic, nh, ros::Duration(seconds));
}

agraph::AGraph LoadOfficeIndependently() {
  ros::NodeHandle nh;
  agraph::IfcConversionConfig config;
  nh.getParam("test_cache_dir", config.cache_dir);
  auto loaded = agraph::LoadBim(kOffice, config);
  EXPECT_TRUE(loaded.ok()) << loaded.error();
  return loaded.ok() ? loaded.value() : agraph::AGraph{};
}

TEST(AGraphNode, PublishesTheBuildingsAGraphLatched) {
  const auto msg = WaitFor<is_graphs::AGraph>("a_graph", 180.0);
  ASSERT_TRUE(msg) << "no a_graph message within 180 s";
  const agraph::AGraph expected = LoadOfficeIndependently();
  ASSERT_FALSE(expected.rooms.empty());
  EXPECT_EQ(msg->header.frame_id, "bim");
  EXPECT_EQ(msg->source_sha256, expected.source.sha256);
  EXPECT_EQ(msg->surfaces.size(), expected.surfaces.size());
  EXPECT_EQ(msg->walls.size(), expected.walls.size());
  EXPECT_EQ(msg->rooms.size(), expected.rooms.size());
  EXPECT_EQ(msg->doorways.size(), expected.doorways.size());

  const agraph::AGraph got = ros_conversions::FromMsg(*msg);
  for (size_t i = 0; i < std::min(got.surfaces.size(), expected.surfaces.size()); ++i) {
    const auto& g = got.surfaces[i].plane;
    const auto& e = expected.surfaces[i].plane;
    EXPECT_NEAR(g.normal.norm(), 1.0, 1e-9) << "surface " << i;
    EXPECT_LT((g.normal - e.normal).norm(), 1e-3) << "surface " << i;
    EXPECT_NEAR(g.d, e.d, 1e-3) << "surface " << i;
  }
  for (size_t i = 0; i < std::min(got.rooms.size(), expected.rooms.size()); ++i) {
    EXPECT_EQ(got.rooms[i].name, expected.rooms[i].name);
    EXPECT_LT((got.rooms[i].center - expected.rooms[i].center).norm(), 1e-3) << got.rooms[i].name;
    // Every surface a room lists names the room back, and faces into it.
    for (int sid : got.rooms[i].surfaces) {
      const auto& s = got.surfaces.at(sid);
      EXPECT_NE(std::find(s.rooms.begin(), s.rooms.end(), static_cast<int>(i)), s.rooms.end());
      const Eigen::Vector3d c(got.rooms[i].center.x(), got.rooms[i].center.y(), s.z_min);
      EXPECT_GT(s.plane.SignedDistance(c), 0.0)
          << "surface " << sid << " faces away from room " << got.rooms[i].name;
    }
  }
  for (const auto& d : got.doorways) {
    ASSERT_FALSE(d.rooms.empty());
    for (int rid : d.rooms) {
      const auto& doors = got.rooms.at(rid).doorways;
      EXPECT_NE(std::find(doors.begin(), doors.end(), d.id), doors.end()) << d.name;
    }
  }
  // A late subscriber still gets it: the topic is latched.
  EXPECT_TRUE(WaitFor<is_graphs::AGraph>("a_graph", 5.0));
}

TEST(AGraphNode, PublishesMarkersForEveryLayer) {
  const auto graph = WaitFor<is_graphs::AGraph>("a_graph", 180.0);
  const auto markers = WaitFor<visualization_msgs::MarkerArray>("a_graph/markers", 10.0);
  ASSERT_TRUE(graph && markers);
  std::map<std::string, size_t> points_by_ns;
  for (const auto& m : markers->markers) {
    EXPECT_EQ(m.header.frame_id, "bim");
    points_by_ns[m.ns] += m.points.size();
  }
  EXPECT_EQ(points_by_ns["wall_surfaces"], 6 * graph->surfaces.size());
  EXPECT_EQ(points_by_ns["walls"], graph->walls.size());
  EXPECT_EQ(points_by_ns["wall_edges"], 4 * graph->walls.size());
  EXPECT_EQ(points_by_ns["rooms"], graph->rooms.size());
  EXPECT_EQ(points_by_ns["doorways"], graph->doorways.size());
  EXPECT_GT(points_by_ns["room_edges"], 0u);
  EXPECT_GT(points_by_ns["doorway_edges"], 0u);
}

TEST(AGraphNode, CloudLiesOnTheBuildingMesh) {
  const auto cloud = WaitFor<sensor_msgs::PointCloud2>("a_graph/cloud", 180.0);
  ASSERT_TRUE(cloud);
  EXPECT_EQ(cloud->header.frame_id, "bim");
  const auto points = ros_conversions::FromCloudMsg(*cloud);
  ASSERT_GT(points.size(), 1000u);
  const agraph::AGraph graph = LoadOfficeIndependently();
  const auto mesh = geometry::LoadObj(graph.mesh);
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  // Every 97th point (a spread-out subset): distance to the nearest mesh triangle's plane,
  // among triangles whose bounding box (grown by 1 cm) contains the point.
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); i += 97) {
    const Eigen::Vector3d& p = points[i];
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.value().triangles) {
      const Eigen::Vector3d& a = mesh.value().vertices[t[0]];
      const Eigen::Vector3d& b = mesh.value().vertices[t[1]];
      const Eigen::Vector3d& c = mesh.value().vertices[t[2]];
      const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c).array() - 0.01;
      const Eigen::Vector3d hi = a.cwiseMax(b).cwiseMax(c).array() + 0.01;
      if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
      const Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.norm() < 1e-12) continue;
      best = std::min(best, std::abs(n.normalized().dot(p - a)));
    }
    worst = std::max(worst, best);
  }
  EXPECT_LT(worst, 1e-3) << "a cloud point is off the building mesh";
}

TEST(RobotDescription, GivesBaseLinkToVelodyne) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  std::string error;
  ASSERT_TRUE(
      buffer.canTransform("base_link", "velodyne", ros::Time(0), ros::Duration(20.0), &error))
      << error;
  const auto t = buffer.lookupTransform("base_link", "velodyne", ros::Time(0));
  EXPECT_NEAR(t.transform.translation.x, 0.1, 1e-6);
  EXPECT_NEAR(t.transform.translation.y, 0.0, 1e-6);
  EXPECT_NEAR(t.transform.translation.z, 0.1877, 1e-6);
  EXPECT_NEAR(t.transform.rotation.w, 1.0, 1e-9);
}

std::pair<int, std::string> RunNode(const std::string& args) {
  return testing_support::RunNode(IS_GRAPHS_AGRAPH_NODE, "bad_input_agraph_node", args);
}

TEST(AGraphNodeBadInput, MissingFileIsAClearErrorAndExit) {
  const auto [code, out] = RunNode("_bim_file:=/nonexistent/building.ifc");
  EXPECT_NE(code, 0) << out;
  EXPECT_NE(out.find("/nonexistent/building.ifc"), std::string::npos) << out;
}

TEST(AGraphNodeBadInput, MissingParameterIsNamed) {
  const auto [code, out] = RunNode("");
  EXPECT_NE(code, 0) << out;
  EXPECT_NE(out.find("bim_file"), std::string::npos) << out;
}

TEST(AGraphNodeBadInput, NotAnIfcFileIsAClearErrorAndExit) {
  const std::string path = std::string(IS_GRAPHS_TEST_TMP_DIR) + "/not_a_building.ifc";
  std::system(("mkdir -p " + std::string(IS_GRAPHS_TEST_TMP_DIR)).c_str());
  std::ofstream(path) << "this is a shopping list, not a building\n";
  const auto [code, out] = RunNode("_bim_file:=" + path);
  EXPECT_NE(code, 0) << out;
  EXPECT_NE(out.find("not_a_building.ifc"), std::string::npos) << out;
}

TEST(AGraphNodeBadInput, UnknownStoreyIsNamed) {
  ros::NodeHandle nh;
  std::string cache;
  nh.getParam("test_cache_dir", cache);
  const auto [code, out] =
      RunNode("_bim_file:=" + kOffice + " _cache_dir:=" + cache + " _storey:=Penthouse");
  EXPECT_NE(code, 0) << out;
  EXPECT_NE(out.find("Penthouse"), std::string::npos) << out;
}

TEST(AGraphNodeBadInput, NegativeCloudDensityIsNamed) {
  const auto [code, out] = RunNode("_bim_file:=" + kOffice + " _cloud_density:=-3.0");
  EXPECT_NE(code, 0) << out;
  EXPECT_NE(out.find("cloud_density"), std::string::npos) << out;
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_agraph_node");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
