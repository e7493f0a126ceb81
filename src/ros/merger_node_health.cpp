// merger_node: odometry (guarded) and the pose it extrapolates, the watchdog over the inputs,
// localization_status and /diagnostics (the class: merger_node.h).
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <is_graphs/ISGraph.h>
#include <is_graphs/LocalizationStatus.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>

#include "is_graphs/merging/pose_covariance.h"
#include "merger_node.h"
#include "pose_conversions.h"

namespace is_graphs {
namespace ros_merger {

void MergerNode::OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  odometry_rate_.Tick();
  const ros::Time stamp = msg->header.stamp;
  const Eigen::Isometry3d reading = ros_conversions::FromPose(msg->pose.pose);
  std::unique_lock<std::mutex> lock(mutex_);
  ++odometry_received_;
  const common::OdometryGuard::Result checked = guard_.Check(stamp.toSec(), reading);
  if (!checked.usable()) {
    ++odometry_skipped_;
    last_odometry_problem_ =
        std::string(common::ToString(checked.verdict)) + ": " + checked.message;
    ROS_WARN_THROTTLE(2.0, "merger_node: %s: %s (%s): skipped, no pose extrapolated through it",
                      odom_sub_.getTopic().c_str(), common::ToString(checked.verdict),
                      checked.message.c_str());
    return;
  }
  if (checked.verdict == common::OdometryGuard::Verdict::kBridged) {
    ++odometry_bridged_;
    ROS_WARN("merger_node: %s: %s", odom_sub_.getTopic().c_str(), checked.message.c_str());
  }
  const bool went_back = checked.verdict == common::OdometryGuard::Verdict::kTimeBack;
  if (went_back) {
    ROS_WARN("merger_node: odometry went back in time by %.1f s (bag restarted?): merge reset",
             (last_odom_stamp_ - stamp).toSec());
    ResetLocked("time went back");
    last_bim_T_odom_.reset();  // the odometry started over: nothing to carry
    carry_.reset();
    tf_buffer_.clear();
    latest_s_.reset();
    latest_s_graph_.reset();
    session_revision_ = 0;
  }
  last_odom_stamp_ = stamp;
  // odom_T_base: the reading as the S-Graph uses it (the guard's bridge of a lasting step).
  const Eigen::Isometry3d odom_T_base = checked.odom_T_base;
  state_.AddOdometry(stamp.toSec(), odom_T_base.translation());
  watchdog_.OnOdometry(stamp.toSec(), state_.distance_walked());
  if (!localized_) {
    lock.unlock();
    if (went_back) PublishStatus();  // the change at once, not at the next status tick
    return;
  }
  const merging::OdometryAnchor anchor = anchor_;
  const Eigen::Isometry3d bim_T_map = bim_T_map_;
  const Eigen::Matrix3d covariance = covariance_;
  const bool degraded = state_.state() == merging::LocalizationState::kDegraded;
  const double since_sgraph = watchdog_.Check(stamp.toSec()).distance_since_sgraph;
  lock.unlock();

  // The pose: the merged revision's newest keyframe and the odometry since, calibrated (no tf
  // needed).
  const Eigen::Isometry3d bim_T_base = anchor.Pose(odom_T_base);
  if (!bim_T_base.matrix().allFinite()) {  // the last line: never a NaN pose
    ++nonfinite_poses_;
    ROS_ERROR_THROTTLE(2.0,
                       "merger_node: a non-finite pose from odometry at %.3f s and the merge: "
                       "not published",
                       stamp.toSec());
    return;
  }
  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header.stamp = stamp;
  pose.header.frame_id = params_.bim_frame;
  pose.pose.pose = ros_conversions::ToPose(bim_T_base);
  Eigen::Matrix<double, 6, 6> pose_covariance = merging::RobotPoseCovariance(
      covariance, bim_T_map, bim_T_map.inverse() * bim_T_base.translation(), params_.merger);
  if (degraded)
    pose_covariance = merging::GrowWithOdometry(pose_covariance, since_sgraph, params_.watchdog);
  ros_conversions::ToArray(pose_covariance, pose.pose.covariance);
  pose_pub_.publish(pose);
  ++poses_;
  // tf bim -> map, such that bim -> map -> odom (the S-Graph's newest) -> base_link is that pose;
  // map -> odom and odom -> base_link are both in the readings' frame (sgraph_node's map -> odom
  // carries the guard's bridge).
  if (stamp <= last_tf_stamp_) return;  // tf2 rejects repeated stamps
  auto map_T_odom = tf_.Lookup(params_.map_frame, params_.odom_frame, stamp);
  if (!map_T_odom.ok())
    map_T_odom = tf_.Lookup(params_.map_frame, params_.odom_frame, ros::Time(0));
  if (!map_T_odom.ok()) {  // a tf gap: the pose holds, the tf waits
    ROS_WARN_THROTTLE(2.0, "merger_node: %s: tf %s -> %s not published", map_T_odom.error().c_str(),
                      params_.bim_frame.c_str(), params_.map_frame.c_str());
    return;
  }
  last_tf_stamp_ = stamp;
  geometry_msgs::TransformStamped t =
      tf2::eigenToTransform(bim_T_base * (map_T_odom.value() * reading).inverse());
  t.header.stamp = stamp;
  t.header.frame_id = params_.bim_frame;
  t.child_frame_id = params_.map_frame;
  tf_broadcaster_.sendTransform(t);
}

void MergerNode::OnWatchdogTimer() {
  const auto heartbeat = tf_.LatestStamp(params_.map_frame, params_.odom_frame);
  const ros::Time now = ros::Time::now();
  bool changed = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (heartbeat.ok()) watchdog_.OnMapToOdom(heartbeat.value().toSec());
    changed = ApplyWatchdogLocked(watchdog_.Check(now.toSec()));
  }
  if (changed) PublishStatus();
}

bool MergerNode::ApplyWatchdogLocked(const merging::InputWatchdog::Report& report) {
  last_report_ = report;
  using Health = merging::InputWatchdog::Health;
  if (!localized_) return false;
  if (report.health == Health::kFresh) {
    // Every input is back in time and the merge was never contradicted: the pose is as good as
    // between any two revisions.
    if (state_.state() != merging::LocalizationState::kDegraded) return false;
    ROS_INFO("merger_node: LOCALIZED again: every input fresh");
    state_.SetLocalized(ros::Time::now().toSec(), "localized: inputs fresh again");
    return true;
  }
  if (report.health == Health::kStopped) {
    ROS_WARN("merger_node: LOST: %s; matching again", report.message.c_str());
    localized_ = false;
    reset_merger_ = true;
    state_.SetLost("lost: " + report.message + "; matching again");
    wake_.notify_all();
    return true;
  }
  const bool was_localized = state_.localized();
  state_.SetDegraded("degraded: " + report.message);
  if (was_localized)
    ROS_WARN("merger_node: DEGRADED: %s; the pose goes on with odometry alone",
             report.message.c_str());
  return was_localized;
}

void MergerNode::ResetLocked(const std::string& why) {
  reset_merger_ = true;
  localized_ = false;
  state_.Reset("reset: " + why + "; waiting for a unique match");
  status_dirty_ = true;
}

void MergerNode::PublishStatus() {
  is_graphs::LocalizationStatus msg;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    msg.header.stamp = ros::Time::now();
    msg.header.frame_id = params_.bim_frame;
    msg.state = static_cast<uint8_t>(state_.state());
    if (state_.has_pose()) msg.localized_since = ros::Time(std::max(state_.localized_since(), 0.0));
    msg.seconds_to_localize = state_.seconds_to_localize();
    msg.distance_to_localize = state_.distance_to_localize();
    msg.message = state_.message();
    msg.hint = hint_;
    msg.hint_in_force = hint_.rfind("in force", 0) == 0;
    if (state_.has_pose()) {
      Eigen::Matrix<double, 6, 6> covariance = merging::RobotPoseCovariance(
          covariance_, bim_T_map_, Eigen::Vector3d::Zero(), params_.merger);
      if (state_.state() == merging::LocalizationState::kDegraded)
        covariance = merging::GrowWithOdometry(covariance, last_report_.distance_since_sgraph,
                                               params_.watchdog);
      ros_conversions::ToArray(covariance, msg.covariance);
    }
    status_dirty_ = false;
  }
  status_pub_.publish(msg);
}

MergerHealthSnapshot MergerNode::Snapshot() {
  ros_merger::MergerHealthSnapshot h;
  h.odometry_rate = odometry_rate_.Rate(ros::Time::now());
  std::lock_guard<std::mutex> lock(mutex_);
  h.state = state_.state();
  h.message = state_.message();
  h.armed = localized_;
  h.watchdog = last_report_;
  h.odometry_received = odometry_received_;
  h.odometry_skipped = odometry_skipped_;
  h.odometry_bridged = odometry_bridged_;
  h.last_odometry_problem = last_odometry_problem_;
  h.sgraph_revisions = sgraph_revisions_;
  h.sgraph_rejected = sgraph_rejected_;
  h.matches = matches_;
  h.poses = poses_;
  h.nonfinite_poses = nonfinite_poses_;
  h.last_merge_ms = last_merge_ms_;
  h.max_merge_ms = max_merge_ms_;
  return h;
}

void MergerNode::DiagnoseLocalization(diagnostic_updater::DiagnosticStatusWrapper& d) {
  snapshot_ = Snapshot();
  ros_merger::FillLocalization(snapshot_, d);
}

void MergerNode::DiagnoseInputs(diagnostic_updater::DiagnosticStatusWrapper& d) {
  // Runs right after DiagnoseLocalization (the order added): the same snapshot.
  ros_merger::FillInputs(snapshot_, snapshot_.odometry_skipped - skipped_reported_, d);
  skipped_reported_ = snapshot_.odometry_skipped;
}

}  // namespace ros_merger
}  // namespace is_graphs
