// matcher_node's run-time requests (docs/localization_services.md): a pose hint on the
// `initialpose` topic (rviz's "2D Pose Estimate") or the `set_pose_hint` service, `relocalize`
// and `set_storey`. Each is checked here, on the ROS thread (tf for the hint's frames, the
// storey's name against the A-Graph); a bad one is answered with a message naming what is
// wrong and changes nothing, a good one is handed to the node's worker as a Request.
#pragma once

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <is_graphs/SetPoseHint.h>
#include <is_graphs/SetStorey.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_listener.h>

#include <functional>
#include <mutex>
#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/pose_hint.h"
#include "pose_hint_conversions.h"
#include "tf_lookup.h"

namespace is_graphs {
namespace ros_matcher {

struct Request {
  enum class Kind { kHint, kRelocalize, kStorey };
  Kind kind{Kind::kRelocalize};
  matching::PoseHint hint;  // kHint
  int storey{-1};           // kStorey: A-Graph storey id, -1: the whole building
  std::string storey_name;  // kStorey, for messages
};

class LocalizationServices {
 public:
  /// `submit` is called (on the ROS thread) with each request that passed its checks.
  LocalizationServices(ros::NodeHandle& nh, const ros_conversions::HintFrames& frames,
                       std::function<void(const Request&)> submit);
  /// The building's storeys, for the names requests give (any thread).
  void SetBuilding(const agraph::AGraph& building);

 private:
  void OnInitialPose(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg);
  bool OnSetPoseHint(is_graphs::SetPoseHint::Request& req, is_graphs::SetPoseHint::Response& res);
  bool OnRelocalize(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool OnSetStorey(is_graphs::SetStorey::Request& req, is_graphs::SetStorey::Response& res);
  /// The hint of `msg` on `storey` ("" any), or why not.
  Result<matching::PoseHint> Hint(const geometry_msgs::PoseWithCovarianceStamped& msg,
                                  const std::string& storey);
  Result<int> Storey(const std::string& storey);

  ros_conversions::HintFrames frames_;
  std::function<void(const Request&)> submit_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  ros_tf::TfLookup tf_;
  std::mutex mutex_;
  agraph::AGraph storeys_;  // the building's storeys only (mutex_)
  bool has_building_{false};
  ros::Subscriber initialpose_sub_;
  ros::ServiceServer hint_srv_, relocalize_srv_, storey_srv_;
};

}  // namespace ros_matcher
}  // namespace is_graphs
