#pragma once
// The fixture of the merger_node rostests (test_merger_node.cpp, test_merger_node_mid_run.cpp):
// the test plays the S-Graph node against real agraph_node, matcher_node and merger_node.
// Synthetic S-Graphs made from the published A-Graph under a known B_T_M (one keyframe per room
// observing its planes, odometry drifted by a known map <- odom D) on `s_graph`, odometry on
// `odom` and tf map -> odom = D at 20 Hz (the tf can be paused: a tf gap).
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <is_graphs/AGraph.h>
#include <is_graphs/GraphMatch.h>
#include <is_graphs/LocalizationStatus.h>
#include <is_graphs/SGraph.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>

#include "../../src/ros/agraph_conversions.h"
#include "../../src/ros/graph_match_conversions.h"
#include "../../src/ros/pose_conversions.h"
#include "../../src/ros/sgraph_conversions.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/synthetic_sgraph.h"

namespace is_graphs {
namespace merger_test {

using Status = is_graphs::LocalizationStatus;
using Pose = geometry_msgs::PoseWithCovarianceStamped;
constexpr double kDeg = M_PI / 180.0;
const Eigen::Isometry3d kMapTOdom = geometry::IsometryFromXYYaw(0.4, -0.3, 3.0 * kDeg);  // D
constexpr double kMaxError = 0.05;       // m, x-y of pose_bim
constexpr double kMaxYawErrorDeg = 1.0;  // of pose_bim

class MergerNodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    s_pub_ = nh_.advertise<is_graphs::SGraph>("s_graph", 10);
    match_pub_ = nh_.advertise<is_graphs::GraphMatch>("graph_match", 10);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("odom", 100);
    match_sub_ = nh_.subscribe("graph_match", 10, &MergerNodeTest::OnMatch, this);
    status_sub_ = Record<Status>("localization_status", &statuses_);
    pose_sub_ = Record<Pose>("pose_bim", &poses_);
    const auto a =
        ros::topic::waitForMessage<is_graphs::AGraph>("a_graph", nh_, ros::Duration(180));
    ASSERT_TRUE(a) << "no a_graph within 180 s";
    a_graph_ = ros_conversions::FromMsg(*a);
    // The merger subscribes to odom last (after a_graph, s_graph and graph_match).
    ASSERT_TRUE(Poll(20.0, [this] {
      return s_pub_.getNumSubscribers() >= 2 && odom_pub_.getNumSubscribers() >= 1;
    })) << "matcher_node and merger_node not on s_graph, or merger_node not on odom";
    ros::WallDuration(1.0).sleep();  // the latched A-Graph reaches the merger
    odom_thread_ = std::thread([this] {
      while (!stop_) {
        PublishOdometry(ros::Time::now());
        ros::WallDuration(0.05).sleep();
      }
    });
  }

  void TearDown() override {
    stop_ = true;
    if (odom_thread_.joinable()) odom_thread_.join();
  }

  void OnMatch(const ros::MessageEvent<is_graphs::GraphMatch const>& event) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (event.getPublisherName() == "/matcher_node") matches_.push_back(event.getMessage());
  }
  template <typename M>
  ros::Subscriber Record(const std::string& topic, std::vector<typename M::ConstPtr>* into) {
    return nh_.subscribe<M>(topic, 100, [this, into](const typename M::ConstPtr& msg) {
      std::lock_guard<std::mutex> lock(mutex_);
      into->push_back(msg);
    });
  }

  /// Odometry (odom <- base_link: the current reading) and tf map -> odom = D at `stamp`.
  /// (The tf is left out while tf_paused_: a tf gap.)
  void PublishOdometry(const ros::Time& stamp) {
    if (!tf_paused_) {
      geometry_msgs::TransformStamped t = tf2::eigenToTransform(kMapTOdom);
      t.header.stamp = stamp;
      t.header.frame_id = "map";
      t.child_frame_id = "odom";
      tf_pub_.sendTransform(t);
    }
    nav_msgs::Odometry odom;
    odom.header.stamp = stamp;
    odom.header.frame_id = "odom";
    odom.child_frame_id = "base_link";
    {
      std::lock_guard<std::mutex> lock(mutex_);
      odom.pose.pose = ros_conversions::ToPose(odom_T_base_);
    }
    odom_pub_.publish(odom);
  }
  void SetOdometry(const Eigen::Isometry3d& odom_T_base) {
    std::lock_guard<std::mutex> lock(mutex_);
    odom_T_base_ = odom_T_base;
  }

  /// The rooms `names` (all when empty) under B_T_M, with a keyframe per room from stamp t0 on
  /// (odometry drifted by D), observing the room's planes, and a floor at the storey's elevation.
  matching::SyntheticSGraph Session(const std::vector<std::string>& names,
                                    const Eigen::Isometry3d& bim_T_map, double t0, int seed) {
    matching::SyntheticSGraphConfig c;
    for (const auto& r : a_graph_.rooms)
      if (names.empty() || std::find(names.begin(), names.end(), r.name) != names.end())
        c.rooms.push_back(r.id);
    c.bim_T_map = bim_T_map;
    c.normal_noise_deg = 0.3;
    c.offset_noise = 0.01;
    c.centre_noise = 0.03;
    c.seed = seed;
    matching::SyntheticSGraph s = matching::MakeSyntheticSGraph(a_graph_, c);
    sgraph::SGraph& g = s.graph;
    sgraph::Floor floor;
    floor.height = a_graph_.storeys.front().elevation - bim_T_map.translation().z();
    for (const auto& room : g.rooms) {
      sgraph::Keyframe k;
      k.id = static_cast<int>(g.keyframes.size());
      k.stamp = t0 + k.id;
      k.pose = geometry::IsometryFromXYYaw(room.center.x(), room.center.y(), 0.3 * k.id);
      k.odom_pose = kMapTOdom.inverse() * k.pose;
      if (!g.keyframes.empty()) {
        k.previous = g.keyframes.back().id;
        k.relative_odom = g.keyframes.back().odom_pose.inverse() * k.odom_pose;
      }
      k.odom_information *= 1e4;
      for (int id : room.planes)
        for (const auto& p : g.planes)
          if (p.id == id)
            g.observations.push_back({k.id, p.id, p.plane.Transformed(k.pose.inverse()),
                                      Eigen::Matrix3d::Identity() * 1e4});
      g.keyframes.push_back(k);
      floor.rooms.push_back(room.id);
    }
    g.floors.push_back(floor);
    return s;
  }

  /// A UNIQUE match of `s` with its true pairs, the motion off by 0.2 m and 2 deg.
  is_graphs::GraphMatch Forged(const matching::SyntheticSGraph& s, unsigned revision,
                               const std::string& sha256) {
    matching::GraphMatch m;
    m.status = matching::MatchStatus::kUnique;
    m.a_graph_sha256 = sha256;
    m.s_graph_revision = revision;
    m.hypotheses = 1;
    for (const auto& [s_id, a_id] : s.room_truth) m.room_pairs.push_back({a_id, s_id, 1.0});
    for (const auto& [s_id, a_id] : s.plane_truth) m.surface_pairs.push_back({a_id, s_id, 1.0});
    const Eigen::Vector3d xi = geometry::ToXYYaw(s.bim_T_map);
    m.bim_T_map = geometry::IsometryFromXYYaw(xi.x() + 0.2, xi.y() - 0.1, xi.z() + 2.0 * kDeg);
    is_graphs::GraphMatch msg = ros_conversions::ToMsg(m);
    msg.header.frame_id = "bim";
    msg.header.stamp = ros::Time::now();
    return msg;
  }

  /// With the robot at the newest keyframe (odometry), publishes `s` as `revision`: the
  /// matcher's graph_match for it is UNIQUE or not, as `unique`.
  ::testing::AssertionResult Matched(const matching::SyntheticSGraph& s, unsigned revision,
                                     bool unique) {
    SetOdometry(s.graph.keyframes.back().odom_pose);
    {  // an earlier answer for this revision number was for another S-Graph
      std::lock_guard<std::mutex> lock(mutex_);
      matches_.erase(std::remove_if(matches_.begin(), matches_.end(),
                                    [&](const auto& m) { return m->s_graph_revision == revision; }),
                     matches_.end());
    }
    is_graphs::SGraph msg = ros_conversions::ToMsg(s.graph);
    msg.revision = revision;
    msg.header.frame_id = "map";
    msg.header.stamp = ros::Time::now();
    s_pub_.publish(msg);
    const auto m = Poll(30.0, [&]() -> is_graphs::GraphMatch::ConstPtr {
      for (const auto& answer : matches_)
        if (answer->s_graph_revision == revision) return answer;
      return nullptr;
    });
    if (!m) return ::testing::AssertionFailure() << "no graph_match for revision " << revision;
    if ((m->status == is_graphs::GraphMatch::UNIQUE) != unique)
      return ::testing::AssertionFailure() << "graph_match for revision " << revision << " is "
                                           << int(m->status) << ", not as the test expects";
    return ::testing::AssertionSuccess();
  }

  /// `found()` (called under the lock) once it is true, or false after `timeout` s.
  template <typename F>
  auto Poll(double timeout, F found) -> decltype(found()) {
    for (const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(timeout);;
         ros::WallDuration(0.02).sleep()) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (auto result = found()) return result;
      }
      if (ros::WallTime::now() > until) return {};
    }
  }
  /// The newest localization_status once it has `state` (null after `timeout` s).
  Status::ConstPtr WaitForState(uint8_t state, double timeout) {
    return Poll(timeout, [&]() -> Status::ConstPtr {
      return !statuses_.empty() && statuses_.back()->state == state ? statuses_.back() : nullptr;
    });
  }
  /// The pose_bim for odometry stamped after `t`.
  std::vector<Pose::ConstPtr> PosesAfter(const ros::Time& t) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Pose::ConstPtr> out;
    std::copy_if(poses_.begin(), poses_.end(), std::back_inserter(out),
                 [&](const auto& p) { return p->header.stamp > t; });
    return out;
  }

  static void ExpectNear(const Eigen::Isometry3d& p, const Eigen::Isometry3d& truth,
                         const std::string& what) {
    const double dxy = (p.translation() - truth.translation()).head<2>().norm();
    const double dz = std::abs(p.translation().z() - truth.translation().z());
    const double dyaw =
        std::abs(geometry::NormalizeAngle(geometry::Yaw(p) - geometry::Yaw(truth))) / kDeg;
    std::printf("%s: off by %.4f m (x-y), %.4f m (z), %.3f deg\n", what.c_str(), dxy, dz, dyaw);
    EXPECT_LT(dxy, kMaxError) << what;
    EXPECT_LT(dz, kMaxError) << what;
    EXPECT_LT(dyaw, kMaxYawErrorDeg) << what;
  }
  /// The first pose_bim for odometry stamped after LOCALIZED (at `at`) puts the robot (at the
  /// newest keyframe of `s`) where B_T_M does.
  void ExpectPoseAfter(const ros::Time& at, const matching::SyntheticSGraph& s,
                       const std::string& what) {
    const Pose::ConstPtr msg = Poll(3.0, [&]() -> Pose::ConstPtr {
      for (const auto& p : poses_)
        if (p->header.stamp > at) return p;
      return nullptr;
    });
    ASSERT_TRUE(msg) << what << ": no pose_bim after LOCALIZED";
    EXPECT_EQ(msg->header.frame_id, "bim") << what;
    ExpectNear(ros_conversions::FromPose(msg->pose.pose),
               s.bim_T_map * s.graph.keyframes.back().pose, what + ": pose_bim");
    EXPECT_GT(msg->pose.covariance[0], 0.0) << what;
    EXPECT_LT(msg->pose.covariance[0], 0.01) << what;  // sigma x < 10 cm
  }

  ros::NodeHandle nh_;
  ros::Publisher s_pub_, match_pub_, odom_pub_;
  ros::Subscriber match_sub_, status_sub_, pose_sub_;
  tf2_ros::TransformBroadcaster tf_pub_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_{tf_buffer_};
  agraph::AGraph a_graph_;
  std::mutex mutex_;
  std::vector<is_graphs::GraphMatch::ConstPtr> matches_;  // the matcher's
  std::vector<Status::ConstPtr> statuses_;
  std::vector<Pose::ConstPtr> poses_;
  Eigen::Isometry3d odom_T_base_{Eigen::Isometry3d::Identity()};
  std::atomic<bool> stop_{false};
  std::atomic<bool> tf_paused_{false};
  std::thread odom_thread_;
};

}  // namespace merger_test
}  // namespace is_graphs
