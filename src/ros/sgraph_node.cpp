// sgraph_node: builds the Situational Graph online from `velodyne_points` and `odom` (+ tf
// base_link <- sensor) and publishes `s_graph`, tf map -> odom, `s_graph/markers` and
// `s_graph/map_cloud`. Thin: the work is in is_graphs_core (sgraph::SGraphBuilder). A cloud is
// held until odometry covers its sweep (sgraph::ScanOdometrySync, at most odom_wait) and then
// processed in the callback; the optimization runs on a worker thread and never blocks them.
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
#include "param_helpers.h"
#include "pose_conversions.h"
#include "sgraph_conversions.h"
#include "sgraph_markers.h"
#include "tf_lookup.h"
#include "velodyne_conversions.h"

namespace is_graphs {
namespace {

struct SGraphNodeParams {
  std::string map_frame{"map"}, odom_frame{"odom"}, base_frame{"base_link"};
  double map_cloud_period{2.0};  // s between map cloud publications (when subscribed)
  double map_cloud_voxel{0.1};
  double tf_rate{20.0};
  sgraph::FrontendConfig frontend;
  sgraph::BackendConfig backend;
  ros_markers::SGraphMarkerStyle markers;
};

SGraphNodeParams ReadParams(const ros::NodeHandle& pnh) {
  using ros_params::Read;
  SGraphNodeParams p;
  Read(pnh, "map_frame", p.map_frame);
  Read(pnh, "odom_frame", p.odom_frame);
  Read(pnh, "base_frame", p.base_frame);
  Read(pnh, "map_cloud_period", p.map_cloud_period);
  Read(pnh, "map_cloud_voxel", p.map_cloud_voxel);
  Read(pnh, "tf_rate", p.tf_rate);
  Read(pnh, "marker_layer_spacing", p.markers.layer_spacing);
  for (const auto* name : {"map_frame", "odom_frame", "base_frame"}) {
    std::string v;
    if (pnh.getParam(name, v) && v.empty())
      throw ros_params::ParamError("parameter '" + pnh.resolveName(name) + "' must not be empty");
  }
  if (!(p.map_cloud_period > 0.0))
    throw ros_params::ParamError("parameter '" + pnh.resolveName("map_cloud_period") +
                                 "' must be > 0");
  if (!(p.map_cloud_voxel > 0.0))
    throw ros_params::ParamError("parameter '" + pnh.resolveName("map_cloud_voxel") +
                                 "' must be > 0");
  if (!(p.tf_rate > 0.0))
    throw ros_params::ParamError("parameter '" + pnh.resolveName("tf_rate") + "' must be > 0");
  auto& f = p.frontend;
  Read(pnh, "keyframe_distance", f.keyframe_distance);
  Read(pnh, "keyframe_angle_deg", f.keyframe_angle_deg);
  Read(pnh, "max_odom_gap", f.max_odom_gap);
  Read(pnh, "max_odom_extrapolation", f.max_odom_extrapolation);
  Read(pnh, "odom_wait", f.odom_wait);
  Read(pnh, "time_reset_threshold", f.time_reset_threshold);
  Read(pnh, "min_range", f.min_range);
  Read(pnh, "max_range", f.max_range);
  Read(pnh, "voxel_size", f.voxel_size);
  Read(pnh, "map_voxel_size", f.map_voxel_size);
  Read(pnh, "plane_distance_threshold", f.plane_distance_threshold);
  Read(pnh, "plane_max_angle_deg", f.plane_max_angle_deg);
  Read(pnh, "ransac_iterations", f.ransac_iterations);
  Read(pnh, "min_plane_points", f.min_plane_points);
  Read(pnh, "max_planes", f.max_planes);
  Read(pnh, "min_segment_length", f.min_segment_length);
  Read(pnh, "min_segment_height", f.min_segment_height);
  Read(pnh, "wall_min_rise", f.wall_min_rise);
  Read(pnh, "sensor_max_elevation_deg", f.sensor_max_elevation_deg);
  Read(pnh, "segment_gap", f.segment_gap);
  Read(pnh, "wall_normal_cell", f.wall_normal_cell);
  Read(pnh, "wall_normal_max_angle_deg", f.wall_normal_max_angle_deg);
  Read(pnh, "point_sigma", f.point_sigma);
  Read(pnh, "max_effective_points", f.max_effective_points);
  Read(pnh, "extract_floor", f.extract_floor);
  Read(pnh, "floor_max_covered", f.floor_max_covered);
  Read(pnh, "floor_cover_height", f.floor_cover_height);
  Read(pnh, "association_chi2", f.association_chi2);
  Read(pnh, "association_min_sigma_d", f.association_min_sigma_d);
  Read(pnh, "association_min_sigma_angle_deg", f.association_min_sigma_angle_deg);
  Read(pnh, "association_max_gap", f.association_max_gap);
  Read(pnh, "association_coplanar_tolerance", f.association_coplanar_tolerance);
  Read(pnh, "detect_rooms", f.detect_rooms);
  Read(pnh, "detect_track_loss", f.detect_track_loss);
  Read(pnh, "track_loss_min_keyframes", f.track_loss_min_keyframes);
  Read(pnh, "track_loss_min_walls", f.track_loss_min_walls);
  Read(pnh, "track_loss_new_share", f.track_loss_new_share);
  Read(pnh, "track_check_period", f.track_check_period);
  Read(pnh, "room_max_range", f.room_max_range);
  Read(pnh, "room_min_width", f.room_min_width);
  Read(pnh, "room_max_width", f.room_max_width);
  Read(pnh, "corridor_max_width", f.corridor_max_width);
  Read(pnh, "room_gap_margin", f.room_gap_margin);
  Read(pnh, "room_opening_band", f.room_opening_band);
  Read(pnh, "room_rays", f.room_rays);
  Read(pnh, "room_rectangle_share", f.room_rectangle_share);
  Read(pnh, "room_max_opening", f.room_max_opening);
  Read(pnh, "doorway_detect", f.doorways.detect);
  Read(pnh, "doorway_max_step", f.doorways.max_step);
  Read(pnh, "doorway_min_wall_height", f.doorways.min_wall_height);
  Read(pnh, "doorway_extent_margin", f.doorways.extent_margin);
  Read(pnh, "doorway_max_width", f.doorways.max_width);
  Read(pnh, "doorway_merge_distance", f.doorways.merge_distance);
  Read(pnh, "doorway_wall_band", f.doorways.wall_band);
  Read(pnh, "doorway_band_low", f.doorways.band_low);
  Read(pnh, "doorway_band_high", f.doorways.band_high);
  auto& b = p.backend;
  Read(pnh, "max_iterations", b.max_iterations);
  Read(pnh, "max_solver_time", b.max_solver_time);
  Read(pnh, "num_threads", b.num_threads);
  Read(pnh, "odom_sigma_translation", b.odom_sigma_translation);
  Read(pnh, "odom_sigma_rotation", b.odom_sigma_rotation);
  Read(pnh, "odom_sigma_z", b.odom_sigma_z);
  Read(pnh, "odom_sigma_roll_pitch", b.odom_sigma_roll_pitch);
  Read(pnh, "odometry_scale_sigma", b.odometry_scale_sigma);
  Read(pnh, "odometry_scale_max_error", b.odometry_scale_max_error);
  Read(pnh, "plane_huber", b.plane_huber);
  Read(pnh, "room_cauchy", b.room_cauchy);
  Read(pnh, "room_sigma", b.room_sigma);
  Read(pnh, "corridor_along_sigma", b.corridor_along_sigma);
  Read(pnh, "floor_sigma", b.floor_sigma);
  Read(pnh, "polygon_room_sigma", b.polygon_room_sigma);
  // The configs name the field; the parameter carries the same name under the node.
  const std::string ns = pnh.getNamespace() + "/";
  for (const std::string& e : {f.Validate(), b.Validate()}) {
    if (e.empty()) continue;
    const size_t space = e.find(' ');  // "<field> <what>"
    throw ros_params::ParamError("parameter '" + ns + e.substr(0, space) + "'" +
                                 (space == std::string::npos ? "" : e.substr(space)));
  }
  p.markers.frame_id = p.map_frame;
  return p;
}

class SGraphNode {
 public:
  SGraphNode(ros::NodeHandle& nh, const SGraphNodeParams& params)
      : params_(params),
        builder_(params.frontend, params.backend),
        sync_(params.frontend.odom_wait),
        tf_listener_(tf_buffer_),
        tf_lookup_(tf_buffer_) {
    graph_pub_ = nh.advertise<is_graphs::SGraph>("s_graph", 2, /*latch=*/true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("s_graph/markers", 2);
    cloud_pub_ = nh.advertise<sensor_msgs::PointCloud2>("s_graph/map_cloud", 1);
    odom_sub_ = nh.subscribe("odom", 200, &SGraphNode::OnOdometry, this);
    cloud_sub_ = nh.subscribe("velodyne_points", 5, &SGraphNode::OnCloud, this);
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
    if (!r.warning.empty()) ROS_WARN_THROTTLE(2.0, "sgraph_node: %s", r.warning.c_str());
    if (r.reset) {
      sync_.Clear();  // clouds of the old run
      PublishAfterReset();
    }
    last_odom_stamp_ = msg->header.stamp;
    ProcessReadyClouds();
  }

  // A cloud is held (sync_) until odometry covers its sweep, then processed.
  void OnCloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
    auto scan = ros_conversions::FromVelodyneMsg(*msg);
    if (!scan.ok()) {
      ROS_WARN_THROTTLE(2.0, "sgraph_node: velodyne_points: %s: skipped", scan.error().c_str());
      return;
    }
    if (!scan.value().has_time)
      ROS_WARN_ONCE("sgraph_node: velodyne_points has no float32 'time' field: no deskewing");
    const auto base_T_sensor =
        tf_lookup_.LookupStatic(params_.base_frame, msg->header.frame_id, ros::Duration(0.05));
    if (!base_T_sensor.ok()) {
      ROS_WARN_THROTTLE(2.0, "sgraph_node: velodyne_points in an unknown frame: %s: skipped",
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
    if (r.restarted)
      ROS_WARN("sgraph_node: %s", r.warning.c_str());  // never throttled away
    else if (!r.warning.empty())
      ROS_WARN_THROTTLE(2.0, "sgraph_node: velodyne_points: %s", r.warning.c_str());
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
    }
  }

  void Publish() {
    const sgraph::SGraph graph = builder_.Snapshot();
    const ros::Time stamp(std::max(graph.stamp, 1e-6));
    is_graphs::SGraph msg = ros_conversions::ToMsg(graph);
    msg.header.frame_id = params_.map_frame;
    msg.header.stamp = stamp;
    graph_pub_.publish(msg);
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
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  ros_tf::TfLookup tf_lookup_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  std::mutex tf_mutex_;
  ros::Time last_tf_stamp_;
  ros::Publisher graph_pub_, marker_pub_, cloud_pub_;
  ros::Subscriber odom_sub_, cloud_sub_;
  ros::Timer tf_timer_;
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
    const auto params = is_graphs::ReadParams(pnh);
    is_graphs::SGraphNode node(nh, params);
    ros::spin();
    return EXIT_SUCCESS;
  } catch (const is_graphs::ros_params::ParamError& e) {
    ROS_FATAL("sgraph_node: %s", e.what());
    return EXIT_FAILURE;
  }
}
