// sgraph_node: builds the Situational Graph online from `velodyne_points` (any LiDAR driver's
// PointCloud2: the layout is detected or set by `cloud_layout`, lidar_conversions.h) and `odom`
// (+ tf base_link <- sensor) and publishes `s_graph`, tf map -> odom, `s_graph/markers` and
// `s_graph/map_cloud`. Thin: the work is in is_graphs_core (sgraph::SGraphBuilder). A cloud is
// held until odometry covers its sweep (sgraph::ScanOdometrySync, at most odom_wait) and then
// processed in the callback; the optimization runs on a worker thread and never blocks them.
// Odometry passes the builder's guard (NaN, glitches, lasting steps bridged); clouds missing
// (stamp gaps: a full queue when processing is slower than the clouds come) and inputs that stop
// are warned about; health on /diagnostics; a restarted node says what its predecessor held.
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TransformStamped.h>
#include <is_graphs/SGraph.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <thread>
#include <utility>

#include "cloud_conversions.h"
#include "is_graphs/sgraph/scan_odometry_sync.h"
#include "is_graphs/sgraph/sgraph_builder.h"
#include "lidar_conversions.h"
#include "param_helpers.h"
#include "pose_conversions.h"
#include "run_marker.h"
#include "sgraph_conversions.h"
#include "sgraph_health.h"
#include "sgraph_markers.h"
#include "sgraph_params.h"
#include "tf_lookup.h"

namespace is_graphs {
namespace {

using ros_sgraph::SGraphNodeParams;

std::string RunId(const ros::NodeHandle& nh) {
  std::string id;
  nh.getParam("/run_id", id);
  return id;
}

class SGraphNode {
 public:
  SGraphNode(ros::NodeHandle& nh, const SGraphNodeParams& params)
      : params_(params),
        builder_(params.frontend, params.backend),
        sync_(params.frontend.odom_wait),
        reader_(params.cloud),
        tf_listener_(tf_buffer_),
        tf_lookup_(tf_buffer_),
        marker_(ros::this_node::getName(), RunId(nh)) {
    if (!marker_.Previous().empty()) {
      health_.OnRestart();
      ROS_WARN(
          "sgraph_node: restarted: a previous sgraph_node of this ROS run held an S-Graph (%s); "
          "that S-Graph is lost, a new one starts here (merger_node matches and localizes again)",
          marker_.Previous().c_str());
    }
    graph_pub_ = nh.advertise<is_graphs::SGraph>("s_graph", 2, /*latch=*/true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("s_graph/markers", 2);
    cloud_pub_ = nh.advertise<sensor_msgs::PointCloud2>("s_graph/map_cloud", 1);
    odom_sub_ = nh.subscribe("odom", 200, &SGraphNode::OnOdometry, this);
    cloud_sub_ = nh.subscribe("velodyne_points", params.cloud_queue, &SGraphNode::OnCloud, this);
    diagnostics_.setHardwareID("is_graphs");
    diagnostics_.add("inputs", [this](diagnostic_updater::DiagnosticStatusWrapper& d) {
      health_.FillInputs(ros::Time::now(), params_.input_timeout, d);
    });
    diagnostics_.add("processing", [this](diagnostic_updater::DiagnosticStatusWrapper& d) {
      health_.FillProcessing(params_.max_cloud_lag, d);
    });
    diagnostics_timer_ = nh.createTimer(ros::Duration(1.0),
                                        [this](const ros::TimerEvent&) { diagnostics_.update(); });
    tf_timer_ = nh.createTimer(ros::Duration(1.0 / params.tf_rate), &SGraphNode::OnTfTimer, this);
    worker_ = std::thread(&SGraphNode::Worker, this);
  }
  ~SGraphNode() {
    {
      std::lock_guard<std::mutex> lock(wake_mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (worker_.joinable()) worker_.join();
  }

 private:
  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
    const auto r =
        builder_.AddOdometry(msg->header.stamp.toSec(), ros_conversions::FromPose(msg->pose.pose));
    health_.OnOdometry(ros::Time::now(), !r.accepted,
                       r.verdict == common::OdometryGuard::Verdict::kBridged, r.warning);
    if (r.verdict == common::OdometryGuard::Verdict::kBridged)
      ROS_WARN("sgraph_node: %s: %s", odom_sub_.getTopic().c_str(), r.warning.c_str());
    else if (!r.warning.empty())
      ROS_WARN_THROTTLE(2.0, "sgraph_node: %s: %s", odom_sub_.getTopic().c_str(),
                        r.warning.c_str());
    if (r.reset) {
      sync_.Clear();  // clouds of the old run
      PublishAfterReset();
    }
    last_odom_stamp_ = msg->header.stamp;
    ProcessReadyClouds();
  }

  // A cloud is held (sync_) until odometry covers its sweep, then processed.
  // The layout is detected once per fields signature; each problem is warned about once.
  void OnCloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    const int missing = health_.OnCloud(ros::Time::now(), msg->header.stamp.toSec());
    if (missing > 0)
      ROS_WARN_THROTTLE(5.0,
                        "sgraph_node: %s: %ld clouds missing so far (gaps in the stamps): the "
                        "queue (cloud_queue %d) overflows when processing is slower than the "
                        "clouds come (now %.2f s behind), or the driver or network dropped them",
                        cloud_sub_.getTopic().c_str(), health_.clouds_missing(),
                        params_.cloud_queue, (ros::Time::now() - msg->header.stamp).toSec());
    std::string info;
    std::vector<std::string> warnings;
    auto scan = reader_.Read(*msg, &info, &warnings);
    const std::string topic = cloud_sub_.getTopic();
    if (!info.empty()) ROS_INFO("sgraph_node: %s: %s", topic.c_str(), info.c_str());
    for (const std::string& w : warnings) ROS_WARN("sgraph_node: %s: %s", topic.c_str(), w.c_str());
    if (!scan.ok()) {
      health_.OnCloudSkipped(scan.error());
      ROS_WARN_THROTTLE(2.0, "sgraph_node: %s: %s: skipped", topic.c_str(), scan.error().c_str());
      return;
    }
    const size_t points = static_cast<size_t>(msg->width) * msg->height;
    if (scan.value().points.empty() && points > 0) {
      health_.OnCloudSkipped("every point non-finite");
      ROS_WARN_THROTTLE(2.0, "sgraph_node: %s: all %zu points have a non-finite x, y or z: skipped",
                        topic.c_str(), points);
      return;
    }
    const auto base_T_sensor =
        tf_lookup_.LookupStatic(params_.base_frame, msg->header.frame_id, ros::Duration(0.05));
    if (!base_T_sensor.ok()) {
      health_.OnCloudSkipped("unknown frame");
      ROS_WARN_THROTTLE(2.0, "sgraph_node: %s in an unknown frame: %s: skipped", topic.c_str(),
                        base_T_sensor.error().c_str());
      return;
    }
    sync_.Push(std::move(scan.value()), base_T_sensor.value(), ros::WallTime::now().toSec());
    ProcessReadyClouds();
  }

  void ProcessReadyClouds() {
    for (auto& ready : sync_.Release(builder_.last_odometry_stamp(), ros::WallTime::now().toSec()))
      ProcessCloud(ready);
  }

  void ProcessCloud(const sgraph::PendingScan& cloud) {
    if (cloud.waited_out)
      ROS_WARN_THROTTLE(
          2.0,
          "sgraph_node: no odometry up to the end of the cloud's sweep (%.3f s) "
          "after odom_wait %.2f s: processed without it (the pose held over the rest)",
          cloud.last_firing, params_.frontend.odom_wait);
    const auto r = builder_.AddScan(cloud.scan, cloud.base_T_sensor);
    const double lag = (ros::Time::now() - ros::Time(std::max(cloud.scan.stamp, 0.0))).toSec();
    health_.OnProcessed(lag);
    if (lag > params_.max_cloud_lag)
      ROS_WARN_THROTTLE(5.0,
                        "sgraph_node: processing %.2f s behind the clouds (max_cloud_lag %.2f s): "
                        "this machine is slower than the clouds come (a bag played too fast?)",
                        lag, params_.max_cloud_lag);
    if (r.status == sgraph::SGraphBuilder::ScanStatus::kSkipped) health_.OnCloudSkipped(r.warning);
    if (r.restarted) health_.OnRestart();
    if (r.restarted)
      ROS_WARN("sgraph_node: %s", r.warning.c_str());  // never throttled away
    else if (!r.warning.empty())
      ROS_WARN_THROTTLE(2.0, "sgraph_node: %s: %s", cloud_sub_.getTopic().c_str(),
                        r.warning.c_str());
    if (r.status == sgraph::SGraphBuilder::ScanStatus::kKeyframe) {
      ROS_DEBUG("sgraph_node: keyframe %d: %d planes (%d new)", r.keyframe, r.num_segments,
                r.num_new_planes);
      wake_.notify_one();
    }
  }

  void Worker() {
    while (ros::ok()) {
      {
        std::unique_lock<std::mutex> lock(wake_mutex_);
        wake_.wait_for(lock, std::chrono::milliseconds(200),
                       [&] { return stop_ || builder_.pending_keyframes() > 0; });
        if (stop_) return;
      }
      if (builder_.pending_keyframes() <= 0) continue;
      const auto summary = builder_.Optimize();
      if (!summary.usable) {
        if (summary.num_keyframes > 0)
          ROS_WARN("sgraph_node: optimization not usable: %s", summary.message.c_str());
        continue;
      }
      ROS_DEBUG("sgraph_node: optimized %d keyframes in %.1f ms", summary.num_keyframes,
                1e3 * summary.seconds);
      Publish();
      health_.OnOptimized(summary.num_keyframes, revision_, 1e3 * summary.seconds);
    }
  }

  void Publish() {
    const sgraph::SGraph graph = builder_.Snapshot();
    const ros::Time stamp(std::max(graph.stamp, 1e-6));
    is_graphs::SGraph msg = ros_conversions::ToMsg(graph);
    msg.header.frame_id = params_.map_frame;
    msg.header.stamp = stamp;
    graph_pub_.publish(msg);
    revision_ = graph.revision;
    const ros::WallTime wall = ros::WallTime::now();
    if ((wall - last_marker_).toSec() >= 1.0) {  // what a restarted node will say it lost
      last_marker_ = wall;
      const std::string error =
          marker_.Write(std::to_string(graph.keyframes.size()) + " keyframes, revision " +
                        std::to_string(graph.revision) + ", stamp " + std::to_string(graph.stamp));
      if (!error.empty()) ROS_WARN_ONCE("sgraph_node: %s", error.c_str());
    }
    BroadcastMapToOdom(stamp);
    if (marker_pub_.getNumSubscribers() > 0) {
      auto markers = ros_markers::BuildSGraphMarkers(graph, params_.markers);
      for (auto& m : markers.markers) m.header.stamp = stamp;
      marker_pub_.publish(markers);
    }
    const ros::WallTime now = ros::WallTime::now();
    if (cloud_pub_.getNumSubscribers() > 0 &&
        (now - last_cloud_).toSec() >= params_.map_cloud_period) {
      last_cloud_ = now;
      const auto points = builder_.MapCloud(params_.map_cloud_voxel);
      std::vector<Eigen::Vector3d> out(points.size());
      for (size_t i = 0; i < points.size(); ++i) out[i] = points[i].cast<double>();
      auto cloud = ros_conversions::ToCloudMsg(out, params_.map_frame);
      cloud.header.stamp = stamp;
      cloud_pub_.publish(cloud);
    }
  }

  void PublishAfterReset() {
    ROS_WARN("sgraph_node: S-Graph reset");
    {
      std::lock_guard<std::mutex> lock(tf_mutex_);
      last_tf_stamp_ = ros::Time();
    }
    is_graphs::SGraph msg = ros_conversions::ToMsg(builder_.Snapshot());
    msg.header.frame_id = params_.map_frame;
    msg.header.stamp = ros::Time::now();
    graph_pub_.publish(msg);
  }

  void OnTfTimer(const ros::TimerEvent&) {
    ProcessReadyClouds();  // clouds whose odometry never came, once they waited odom_wait
    const std::string stopped = health_.Stopped(ros::Time::now(), params_.input_timeout);
    if (!stopped.empty())
      ROS_WARN_THROTTLE(10.0, "sgraph_node: %s (%s, %s)", stopped.c_str(),
                        cloud_sub_.getTopic().c_str(), odom_sub_.getTopic().c_str());
    if (builder_.num_keyframes() == 0 || last_odom_stamp_.isZero()) return;
    BroadcastMapToOdom(last_odom_stamp_);
  }

  void BroadcastMapToOdom(const ros::Time& stamp) {
    geometry_msgs::TransformStamped t = tf2::eigenToTransform(builder_.MapToOdom());
    t.header.frame_id = params_.map_frame;
    t.child_frame_id = params_.odom_frame;
    t.header.stamp = stamp;
    std::lock_guard<std::mutex> lock(tf_mutex_);
    if (stamp <= last_tf_stamp_) return;  // tf2 rejects repeated stamps
    last_tf_stamp_ = stamp;
    tf_broadcaster_.sendTransform(t);
  }

  SGraphNodeParams params_;
  sgraph::SGraphBuilder builder_;
  sgraph::ScanOdometrySync sync_;
  ros_conversions::LidarCloudReader reader_;  // used by the cloud callback only
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  ros_tf::TfLookup tf_lookup_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  std::mutex tf_mutex_;
  ros::Time last_tf_stamp_;
  ros::Publisher graph_pub_, marker_pub_, cloud_pub_;
  ros::Subscriber odom_sub_, cloud_sub_;
  ros::Timer tf_timer_, diagnostics_timer_;
  ros_run::RunMarker marker_;
  ros::WallTime last_marker_;
  std::atomic<unsigned> revision_{0};
  ros_sgraph::SGraphHealth health_;
  diagnostic_updater::Updater diagnostics_;
  ros::Time last_odom_stamp_;
  ros::WallTime last_cloud_;
  std::thread worker_;
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  bool stop_{false};
};

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  ros::init(argc, argv, "sgraph_node");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    const auto params = is_graphs::ros_sgraph::ReadParams(pnh);
    is_graphs::SGraphNode node(nh, params);
    ros::spin();
    return EXIT_SUCCESS;
  } catch (const is_graphs::ros_params::ParamError& e) {
    ROS_FATAL("sgraph_node: %s", e.what());
    return EXIT_FAILURE;
  }
}
