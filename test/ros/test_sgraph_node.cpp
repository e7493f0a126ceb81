// rostest of sgraph_node: a short office bag played with simulated time; the published S-Graph
// (keyframes, planes on the building's true walls after aligning with ground truth, a room, the
// floor), tf map -> odom, and the real node binary on bad parameters.
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <is_graphs/SGraph.h>
#include <ros/ros.h>
#include <sys/wait.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <array>
#include <cstdio>
#include <mutex>
#include <set>

#include "../../src/ros/pose_conversions.h"
#include "../../src/ros/sgraph_conversions.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/sgraph/evaluation.h"
#include "node_runner.h"

namespace is_graphs {
namespace {

class SGraphNodeTest : public ::testing::Test {
 protected:
  // Collects s_graph and ground truth until the bag has played (the graph stops growing).
  static void SetUpTestSuite() {
    ros::NodeHandle nh;
    ros::Subscriber gs =
        nh.subscribe<is_graphs::SGraph>("s_graph", 10,
                                        boost::function<void(const is_graphs::SGraph::ConstPtr&)>(
                                            [](const is_graphs::SGraph::ConstPtr& m) {
                                              std::lock_guard<std::mutex> lock(mutex_);
                                              last_ = m;
                                              ++count_;
                                            }));
    ros::Subscriber ts = nh.subscribe<geometry_msgs::PoseStamped>(
        "ground_truth/pose", 1000,
        boost::function<void(const geometry_msgs::PoseStamped::ConstPtr&)>(
            [](const geometry_msgs::PoseStamped::ConstPtr& m) {
              std::lock_guard<std::mutex> lock(mutex_);
              truth_.push_back({m->header.stamp.toSec(), ros_conversions::FromPose(m->pose)});
            }));
    tf_ = new tf2_ros::Buffer(ros::Duration(60.0));
    listener_ = new tf2_ros::TransformListener(*tf_);
    const ros::WallTime start = ros::WallTime::now();
    ros::WallTime last_change = start;
    size_t last_keyframes = 0;
    while (ros::ok() && (ros::WallTime::now() - start).toSec() < 150.0) {
      ros::WallDuration(0.2).sleep();
      std::lock_guard<std::mutex> lock(mutex_);
      const size_t k = last_ ? last_->keyframes.size() : 0;
      if (k != last_keyframes) last_keyframes = k, last_change = ros::WallTime::now();
      if (k > 0 && (ros::WallTime::now() - last_change).toSec() > 8.0) break;  // bag over
    }
  }
  static inline std::mutex mutex_;
  static inline is_graphs::SGraph::ConstPtr last_;
  static inline int count_ = 0;
  static inline std::vector<sgraph::StampedPose> truth_;
  static inline tf2_ros::Buffer* tf_ = nullptr;
  static inline tf2_ros::TransformListener* listener_ = nullptr;
};

TEST_F(SGraphNodeTest, PublishesAGraphOnTheBuildingsWalls) {
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_TRUE(last_) << "no s_graph message";
  EXPECT_GT(count_, 1);
  EXPECT_EQ(last_->header.frame_id, "map");
  const sgraph::SGraph graph = ros_conversions::FromMsg(*last_);
  ASSERT_GE(graph.keyframes.size(), 5u);
  ASSERT_GE(graph.planes.size(), 4u);
  EXPECT_FALSE(graph.observations.empty());
  // Plane ids are stable but not dense (a duplicate plane merged away leaves its id unused):
  // every observation and room member must name a published plane.
  std::set<int> plane_ids;
  for (const auto& p : graph.planes) EXPECT_TRUE(plane_ids.insert(p.id).second) << "plane " << p.id;
  for (const auto& o : graph.observations) {
    EXPECT_LT(o.keyframe, static_cast<int>(graph.keyframes.size()));
    EXPECT_EQ(plane_ids.count(o.plane), 1u) << "observation of an unpublished plane " << o.plane;
  }
  for (const auto& r : graph.rooms)
    for (int p : r.planes) EXPECT_EQ(plane_ids.count(p), 1u) << "room " << r.id << " plane " << p;
  // The newest slice_keyframes (3) keyframes carry their slice, the older ones none.
  for (size_t i = 0; i < graph.keyframes.size(); ++i) {
    const bool newest = i + 3 >= graph.keyframes.size();
    if (newest)
      EXPECT_GT(graph.keyframes[i].slice.size(), 200u) << "keyframe " << i;
    else
      EXPECT_TRUE(graph.keyframes[i].slice.empty()) << "keyframe " << i;
  }
  ASSERT_GT(truth_.size(), 100u);
  const auto trajectory = sgraph::EvaluateTrajectory(graph, truth_);
  EXPECT_LT(trajectory.sgraph_rmse, 0.1);
  EXPECT_LE(trajectory.sgraph_rmse, trajectory.odom_rmse + 0.01);

  agraph::IfcConversionConfig config;
  ros::NodeHandle nh;
  nh.getParam("test_cache_dir", config.cache_dir);
  const auto office =
      agraph::LoadBim(std::string(IS_GRAPHS_SOURCE_DIR) + "/bim/office.ifc", config);
  ASSERT_TRUE(office.ok()) << office.error();
  const auto planes = sgraph::EvaluatePlanes(graph, office.value(), trajectory.bim_T_map, 200);
  ASSERT_GE(planes.size(), 3u);
  int on_wall = 0;
  for (const auto& p : planes) {
    if (p.surface < 0) continue;
    ++on_wall;
    EXPECT_LT(p.distance, 0.05) << "plane " << p.plane;
    EXPECT_LT(p.angle_deg, 1.5) << "plane " << p.plane;
  }
  EXPECT_GE(on_wall, static_cast<int>(planes.size()) - 1) << "planes off every BIM wall";
  ASSERT_GE(graph.rooms.size(), 1u) << "no room found";
  const auto rooms = sgraph::EvaluateRooms(graph, office.value(), truth_, trajectory.bim_T_map);
  EXPECT_EQ(rooms.false_rooms, 0);
  EXPECT_EQ(graph.floors.size(), 1u);
}

TEST_F(SGraphNodeTest, BroadcastsMapToOdom) {
  std::string error;
  ASSERT_TRUE(tf_->canTransform("map", "odom", ros::Time(0), ros::Duration(5.0), &error)) << error;
}

std::pair<int, std::string> RunNode(const std::string& args) {
  return testing_support::RunNode(IS_GRAPHS_SGRAPH_NODE, "bad_sgraph_node", args);
}

TEST(SGraphNodeBadInput, BadParameterIsNamedAndTheNodeExits) {
  auto [code, out] = RunNode("_voxel_size:=-1.0");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("voxel_size"), std::string::npos) << out;
  std::tie(code, out) = RunNode("_keyframe_distance:=fast");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("keyframe_distance"), std::string::npos) << out;
  // The cloud layout: an unknown driver names the parameter and the choices.
  std::tie(code, out) = RunNode("_cloud_layout:=livox");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("cloud_layout"), std::string::npos) << out;
  EXPECT_NE(out.find("ouster"), std::string::npos) << out;
  std::tie(code, out) = RunNode("_cloud_max_sweep_period:=0.0");
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("cloud_max_sweep_period"), std::string::npos) << out;
}

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_sgraph_node");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
