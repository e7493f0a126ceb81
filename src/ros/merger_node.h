#pragma once
// merger_node (src/ros/merger_node.cpp, merger_node_health.cpp): on a UNIQUE graph_match,
// merges the A-Graph and the S-Graph into the iS-Graph and publishes the robot in the BIM.
// merger_node.cpp: the graph callbacks, the worker that merges, main; merger_node_health.cpp:
// odometry (guarded) and the pose, the watchdog, localization_status and /diagnostics.
#include <diagnostic_updater/diagnostic_updater.h>
#include <is_graphs/AGraph.h>
#include <is_graphs/GraphMatch.h>
#include <is_graphs/SGraph.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "is_graphs/common/odometry_guard.h"
#include "is_graphs/merging/input_watchdog.h"
#include "is_graphs/merging/merge_state.h"
#include "is_graphs/merging/merger.h"
#include "merger_diagnostics.h"
#include "merger_params.h"
#include "rate_meter.h"
#include "tf_lookup.h"

namespace is_graphs {
namespace ros_merger {

class MergerNode {
 public:
  MergerNode(ros::NodeHandle& nh, const MergerNodeParams& params);
  ~MergerNode();

 private:
  // --- callbacks: store the newest input and wake the worker ---
  void OnAGraph(const is_graphs::AGraph::ConstPtr& msg);
  void OnSGraph(const is_graphs::SGraph::ConstPtr& msg);
  void OnMatch(const is_graphs::GraphMatch::ConstPtr& msg);
  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  // --- watchdog: the inputs' ages against the clock ---
  void OnWatchdogTimer();
  // LOCALIZED -> DEGRADED -> LOST as inputs fall behind; DEGRADED -> LOCALIZED once every input
  // is fresh again (the merge holds: LOST needs a new match). True when the state changed.
  bool ApplyWatchdogLocked(const merging::InputWatchdog::Report& report);
  // --- state (mutex_ held) ---
  void ResetLocked(const std::string& why);
  void PublishStatus();
  // --- /diagnostics ---
  MergerHealthSnapshot Snapshot();
  void DiagnoseLocalization(diagnostic_updater::DiagnosticStatusWrapper& d);
  void DiagnoseInputs(diagnostic_updater::DiagnosticStatusWrapper& d);
  // --- worker ---
  void Work();
  void SetAGraph(const is_graphs::AGraph::ConstPtr& msg);
  // The carried merge checked on the new S-Graph revision (a start like a match's).
  struct Carry;
  void TryCarried(const Carry& carry, const is_graphs::SGraph& s_msg,
                  const sgraph::SGraph& s_graph);
  // `s_graph`: `s_msg` converted (once, in OnSGraph).
  void Apply(const merging::MergeOutput& out, const is_graphs::SGraph& s_msg,
             const sgraph::SGraph& s_graph);

  MergerNodeParams params_;
  merging::Merger merger_;                      // the worker's
  is_graphs::AGraph::ConstPtr a_msg_;           // the worker's
  is_graphs::GraphMatch::ConstPtr last_match_;  // the worker's
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  ros_tf::TfLookup tf_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Publisher pose_pub_, status_pub_, is_graph_pub_, marker_pub_;
  ros::Subscriber a_sub_, s_sub_, match_sub_, odom_sub_;
  ros::Timer status_timer_, watchdog_timer_, diagnostics_timer_;
  diagnostic_updater::Updater diagnostics_;
  MergerHealthSnapshot snapshot_;  // the diagnostics' (timer callbacks)
  long skipped_reported_{0};       // the diagnostics'
  ros_diagnostics::RateMeter odometry_rate_;
  std::atomic<long> poses_{0}, nonfinite_poses_{0};

  std::mutex mutex_;  // guards everything below
  std::condition_variable wake_;
  is_graphs::AGraph::ConstPtr pending_a_;
  is_graphs::SGraph::ConstPtr latest_s_;
  std::shared_ptr<const sgraph::SGraph> latest_s_graph_;  // latest_s_ converted
  bool new_s_{false};
  is_graphs::GraphMatch::ConstPtr pending_match_;
  ros::WallTime pending_match_since_;
  bool reset_merger_{false};
  unsigned session_revision_{0};  // the first S-Graph revision of the current S-Graph
  bool stop_{false};
  bool localized_{false};
  bool status_dirty_{false};
  Eigen::Isometry3d bim_T_map_{Eigen::Isometry3d::Identity()};
  merging::OdometryAnchor anchor_;  // the pose: anchor_.Pose(odom_T_base)
  Eigen::Matrix3d covariance_{Eigen::Matrix3d::Identity()};
  merging::MergeState state_;
  // The merge before sgraph_node restarted, carried by the odometry (B <- odom of the readings).
  struct Carry {
    Eigen::Isometry3d bim_T_odom{Eigen::Isometry3d::Identity()};
    int storey{0};
  };
  std::optional<Carry> carry_;
  std::optional<Eigen::Isometry3d> last_bim_T_odom_;  // of the last merge (corrected readings)
  int last_storey_{0};
  common::OdometryGuard guard_;
  merging::InputWatchdog watchdog_;
  merging::InputWatchdog::Report last_report_;
  long odometry_received_{0}, odometry_skipped_{0}, odometry_bridged_{0};
  std::string last_odometry_problem_;
  long sgraph_revisions_{0}, sgraph_rejected_{0}, matches_{0};
  double last_merge_ms_{0.0}, max_merge_ms_{0.0};
  ros::Time last_odom_stamp_;
  ros::Time last_tf_stamp_;
  std::string hint_;                         // graph_match's pose hint (localization_status)
  std::optional<uint32_t> relocalizations_;  // graph_match's, last seen
  std::thread worker_;
};

}  // namespace ros_merger
}  // namespace is_graphs
