// merger_node: on a UNIQUE graph_match, merges the A-Graph (`a_graph`) and the S-Graph
// (`s_graph`) into the iS-Graph and publishes the robot in the BIM: tf bim -> map, `pose_bim`
// (at odometry rate), `localization_status`, `is_graph` and `is_graph/markers`. Thin: the work
// is in is_graphs_core (merging::Merger). Solves run on a worker thread that takes the newest
// S-Graph and match, so a slow solve never piles up callbacks; no pose before the first merge
// holds, and none after it was contradicted (LOST) until a new UNIQUE match merges.
// Odometry passes the same guard as sgraph_node's (NaN, glitches, lasting steps; config/
// odometry_guard.yaml); a watchdog over odometry, tf map -> odom and the S-Graph's revisions
// turns LOCALIZED into DEGRADED and then LOST (docs/faults.md); health on /diagnostics.
#include "merger_node.h"

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <is_graphs/ISGraph.h>
#include <is_graphs/LocalizationStatus.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cstdlib>

#include "agraph_conversions.h"
#include "graph_match_conversions.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/carried_match.h"
#include "is_graphs/sgraph/finite_checks.h"
#include "merger_markers.h"
#include "param_helpers.h"
#include "pose_conversions.h"
#include "sgraph_conversions.h"
#include "sgraph_session.h"
#include "wall_state_conversions.h"

namespace is_graphs {
namespace ros_merger {

MergerNode::MergerNode(ros::NodeHandle& nh, const MergerNodeParams& params)
    : params_(params),
      merger_(params.merger),
      tf_buffer_(ros::Duration(30.0)),
      tf_listener_(tf_buffer_),
      tf_(tf_buffer_),
      guard_(params.odometry_guard),
      watchdog_(params.watchdog) {
  pose_pub_ = nh.advertise<geometry_msgs::PoseWithCovarianceStamped>("pose_bim", 10);
  status_pub_ = nh.advertise<is_graphs::LocalizationStatus>("localization_status", 1, true);
  is_graph_pub_ = nh.advertise<is_graphs::ISGraph>("is_graph", 1, true);
  marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("is_graph/markers", 1, true);
  a_sub_ = nh.subscribe("a_graph", 1, &MergerNode::OnAGraph, this);
  s_sub_ = nh.subscribe("s_graph", 1, &MergerNode::OnSGraph, this);
  match_sub_ = nh.subscribe("graph_match", 10, &MergerNode::OnMatch, this);
  odom_sub_ = nh.subscribe("odom", 100, &MergerNode::OnOdometry, this);
  status_timer_ = nh.createTimer(ros::Duration(1.0 / params_.status_rate),
                                 [this](const ros::TimerEvent&) { PublishStatus(); });
  watchdog_timer_ = nh.createTimer(ros::Duration(1.0 / params_.watchdog_rate),
                                   [this](const ros::TimerEvent&) { OnWatchdogTimer(); });
  diagnostics_.setHardwareID("is_graphs");
  diagnostics_.add("localization", this, &MergerNode::DiagnoseLocalization);
  diagnostics_.add("inputs", this, &MergerNode::DiagnoseInputs);
  diagnostics_timer_ =
      nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { diagnostics_.update(); });
  PublishStatus();
  worker_ = std::thread([this] { Work(); });
}

MergerNode::~MergerNode() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void MergerNode::OnAGraph(const is_graphs::AGraph::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_a_ = msg;
  wake_.notify_all();
}

void MergerNode::OnSGraph(const is_graphs::SGraph::ConstPtr& msg) {
  // Converted once here (the finiteness check needs it) and handed to the worker with the message.
  auto graph = std::make_shared<const sgraph::SGraph>(ros_conversions::FromMsg(*msg));
  const std::string bad = sgraph::FirstNonFinite(*graph);
  std::unique_lock<std::mutex> lock(mutex_);
  if (!bad.empty()) {
    ++sgraph_rejected_;
    ROS_WARN_THROTTLE(2.0, "merger_node: %s revision %u: non-finite %s: revision ignored",
                      s_sub_.getTopic().c_str(), msg->revision, bad.c_str());
    return;
  }
  ++sgraph_revisions_;
  watchdog_.OnSGraph(state_.distance_walked());
  const bool new_session = latest_s_ && ros_sgraph::IsNewSession(*latest_s_, *msg);
  if (new_session) {
    ROS_WARN(
        "merger_node: a new S-Graph (revision %u after %u, %zu keyframes after %zu: "
        "sgraph_node restarted or lost track): merge reset, matching again",
        msg->revision, latest_s_->revision, msg->keyframes.size(), latest_s_->keyframes.size());
    const bool was_localized = localized_ || state_.state() == merging::LocalizationState::kLost;
    // A new process counts its revisions from 1; a track loss keeps counting (and may be a
    // kidnap: nothing is carried over it).
    const bool restarted = msg->revision < latest_s_->revision;
    const bool carry = params_.carry_over_restart && restarted && localized_ && last_bim_T_odom_;
    if (carry) carry_ = Carry{*last_bim_T_odom_ * guard_.correction(), last_storey_};
    // The new sgraph_node's guard starts over: so does this one (the same readings' frame).
    if (restarted) guard_.Reset();
    ResetLocked("the S-Graph restarted");
    // A robot that was localized and no longer is, is LOST (not "not yet localized").
    if (was_localized)
      state_.SetLost(carry ? "sgraph_node restarted: its S-Graph is lost; checking the merge "
                             "carried over by the odometry against the new one"
                           : "the S-Graph restarted (track lost): matching again");
    session_revision_ = msg->revision;
  }
  latest_s_ = msg;
  latest_s_graph_ = std::move(graph);
  new_s_ = true;
  wake_.notify_all();
  lock.unlock();
  if (new_session) PublishStatus();  // the change at once, not at the next status tick
}

void MergerNode::OnMatch(const is_graphs::GraphMatch::ConstPtr& msg) {
  bool publish = false;  // localization_status at once: a relocalize, a hint taken or dropped
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++matches_;
    const auto in_force = [](const std::string& h) { return h.rfind("in force", 0) == 0; };
    publish = in_force(hint_) != in_force(msg->hint) ||
              (hint_ != msg->hint && msg->hint.rfind("rejected", 0) == 0);
    status_dirty_ = status_dirty_ || hint_ != msg->hint;
    hint_ = msg->hint;  // the pose hint, for localization_status
    if (relocalizations_ && msg->relocalizations > *relocalizations_) {
      // matcher_node's relocalize or set_storey service: the match is forgotten, localize again.
      // (Only a count that grows: a respawned matcher_node counts from 0 again, and keeps the
      // merge as before.)
      ROS_WARN("merger_node: relocalize requested (matcher_node): merge reset");
      ResetLocked("relocalize requested");
      carry_.reset();
      last_bim_T_odom_.reset();
      pending_match_.reset();
      publish = true;
    }
    relocalizations_ = msg->relocalizations;
    // A pending UNIQUE match is not replaced by a later non-UNIQUE one.
    if (!(pending_match_ && pending_match_->status == is_graphs::GraphMatch::UNIQUE &&
          msg->status != is_graphs::GraphMatch::UNIQUE)) {
      pending_match_ = msg;
      pending_match_since_ = ros::WallTime::now();
      wake_.notify_all();
    }
  }
  if (publish) PublishStatus();
}

void MergerNode::Work() {
  for (;;) {
    is_graphs::AGraph::ConstPtr a_msg;
    is_graphs::GraphMatch::ConstPtr match_msg;
    is_graphs::SGraph::ConstPtr s_msg;
    std::shared_ptr<const sgraph::SGraph> s_graph;  // s_msg converted
    bool reset = false, solve_s = false;
    std::optional<Carry> carry;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait_for(lock, std::chrono::milliseconds(200));
      if (stop_) return;
      a_msg.swap(pending_a_);
      reset = reset_merger_;
      reset_merger_ = false;
      s_msg = latest_s_;
      s_graph = latest_s_graph_;
      if (pending_match_) {
        const unsigned seen = latest_s_ ? latest_s_->revision : 0;
        if (pending_match_->s_graph_revision < session_revision_) {
          ROS_WARN(
              "merger_node: graph_match for S-Graph revision %u, from before the S-Graph "
              "restarted (revision %u): ignored",
              pending_match_->s_graph_revision, session_revision_);
          pending_match_.reset();
        } else if (latest_s_ && pending_match_->s_graph_revision <= seen) {
          match_msg.swap(pending_match_);
        } else if ((ros::WallTime::now() - pending_match_since_).toSec() > params_.match_wait) {
          ROS_WARN(
              "merger_node: graph_match for S-Graph revision %u, newer than any seen (%u): "
              "ignored",
              pending_match_->s_graph_revision, seen);
          pending_match_.reset();
        }
      }
      solve_s = new_s_ && !match_msg;
      if (!match_msg) new_s_ = false;
      if (carry_ && state_.distance_walked() > params_.carry_max_distance) {
        ROS_WARN(
            "merger_node: the merge carried over sgraph_node's restart expired after %.1f m "
            "(carry_max_distance): waiting for a unique match",
            state_.distance_walked());
        carry_.reset();
      }
      carry = carry_;
    }
    if (reset) merger_.Reset();
    if (a_msg) SetAGraph(a_msg);
    if (!s_msg || !merger_.HasAGraph()) continue;
    if (match_msg) {
      last_match_ = match_msg;
      const matching::GraphMatch match = ros_conversions::FromMsg(*match_msg);
      if (match.a_graph_sha256 != merger_.a_graph_sha256()) {
        ROS_WARN_THROTTLE(5.0,
                          "merger_node: graph_match for an A-Graph not loaded here "
                          "(sha256 %s, have %s): ignored",
                          match.a_graph_sha256.c_str(), merger_.a_graph_sha256().c_str());
        continue;
      }
      Apply(merger_.OnMatch(match, *s_graph), *s_msg, *s_graph);
    } else if (solve_s && merger_.merged()) {
      Apply(merger_.OnSGraph(*s_graph), *s_msg, *s_graph);
    } else if (solve_s && carry) {
      TryCarried(*carry, *s_msg, *s_graph);
    }
  }
}

void MergerNode::TryCarried(const Carry& carry, const is_graphs::SGraph& s_msg,
                            const sgraph::SGraph& s_graph) {
  const Eigen::Isometry3d bim_T_map = merging::CarriedTransform(carry.bim_T_odom, s_graph);
  // Walls seen 1.5 m tall count (the matcher's 1.9 m keeps cupboards out of a blind search; a
  // fresh S-Graph has seen its walls partly, and the carried pose is no blind search).
  matching::MatcherConfig walls;
  walls.surface_min_height = 1.5;
  matching::GraphMatch match =
      merging::CarriedMatch(merger_.a_graph(), s_graph, bim_T_map, carry.storey,
                            params_.merger.min_surface_inliers, walls);  // the start checks more
  if (match.status != matching::MatchStatus::kUnique) return;            // too few planes yet
  merging::MergeOutput out = merger_.OnMatch(match, s_graph);
  if (!out.merged) {  // the checks refused it (yet): no pose, the next revision tries again
    ROS_DEBUG("merger_node: the carried merge not (yet) confirmed: %s", out.message.c_str());
    merger_.Reset();
    return;
  }
  out.message =
      "the merge from before sgraph_node restarted, carried over by the odometry and "
      "checked on the new S-Graph: " +
      out.message;
  Apply(out, s_msg, s_graph);
}

void MergerNode::SetAGraph(const is_graphs::AGraph::ConstPtr& msg) {
  if (merger_.HasAGraph() && msg->source_sha256 == merger_.a_graph_sha256()) return;  // re-latched
  const bool had = merger_.HasAGraph();
  const std::string error = merger_.SetAGraph(ros_conversions::FromMsg(*msg));
  a_msg_ = msg;
  if (had) {
    ROS_WARN("merger_node: a new A-Graph ('%s', sha256 %s): the building changed, merge reset",
             msg->building.c_str(), msg->source_sha256.c_str());
    {
      std::lock_guard<std::mutex> lock(mutex_);
      localized_ = false;
      carry_.reset();
      last_bim_T_odom_.reset();
      state_.Reset("the building changed; waiting for a unique match");
      status_dirty_ = true;
    }
    PublishStatus();  // the change at once, not at the next status tick
  }
  if (!error.empty())
    ROS_ERROR("merger_node: unusable A-Graph: %s", error.c_str());
  else
    ROS_INFO("merger_node: A-Graph '%s' with %zu rooms", msg->building.c_str(), msg->rooms.size());
}

void MergerNode::Apply(const merging::MergeOutput& out, const is_graphs::SGraph& s_msg,
                       const sgraph::SGraph& s_graph) {
  using merging::MergeEvent;
  const auto& sol = out.solution;
  const Eigen::Vector3d xi = geometry::ToXYYaw(out.bim_T_map);
  switch (out.event) {
    case MergeEvent::kNone:
      return;
    case MergeEvent::kRejected:
      ROS_WARN("merger_node: %s", out.message.c_str());
      break;
    case MergeEvent::kLost:
      ROS_WARN("merger_node: LOST: %s", out.message.c_str());
      break;
    case MergeEvent::kLocalized:
      ROS_INFO(
          "merger_node: LOCALIZED at S-Graph rev %u: B_x_M = (%.3f m, %.3f m, %.2f deg), "
          "%s, %d iterations, %.1f ms",
          s_msg.revision, xi.x(), xi.y(), xi.z() * 180 / M_PI, out.message.c_str(), sol.iterations,
          sol.seconds * 1e3);
      break;
    case MergeEvent::kUpdated:
      ROS_DEBUG("merger_node: rev %u: B_x_M = (%.3f, %.3f, %.2f deg), %s, %.1f ms", s_msg.revision,
                xi.x(), xi.y(), xi.z() * 180 / M_PI, out.message.c_str(), sol.seconds * 1e3);
      break;
  }
  for (const std::string& warning : out.warnings)
    ROS_WARN_THROTTLE(10.0, "merger_node: %s", warning.c_str());
  bool publish_status = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (reset_merger_) return;  // reset meanwhile: this result is stale
    const double stamp = s_msg.header.stamp.toSec();
    last_merge_ms_ = sol.seconds * 1e3;
    max_merge_ms_ = std::max(max_merge_ms_, last_merge_ms_);
    if (out.merged) {
      if (!localized_) watchdog_.Arm(ros::Time::now().toSec(), state_.distance_walked());
      last_bim_T_odom_ = out.bim_T_odom;
      if (last_match_ && last_match_->storey_id >= 0) last_storey_ = last_match_->storey_id;
      carry_.reset();
      localized_ = true;
      bim_T_map_ = out.bim_T_map;
      anchor_ = out.anchor;
      covariance_ = out.covariance;
      // Not back from DEGRADED while an input is late (the watchdog says when they are fresh).
      const bool fresh = watchdog_.Check(ros::Time::now().toSec()).health ==
                         merging::InputWatchdog::Health::kFresh;
      if ((!state_.localized() && (fresh || !state_.has_pose())) ||
          out.event == MergeEvent::kLocalized) {
        state_.SetLocalized(stamp, "localized: " + out.message);
        publish_status = true;
      }
    } else if (out.event == MergeEvent::kLost) {
      localized_ = false;
      state_.SetLost("lost: " + out.message + "; matching again");
      publish_status = true;
    }
    publish_status = publish_status || status_dirty_;
  }
  if (publish_status) PublishStatus();
  if (!out.merged) return;
  if (is_graph_pub_.getNumSubscribers() > 0 && a_msg_) {
    is_graphs::ISGraph msg;
    msg.header.stamp = s_msg.header.stamp;
    msg.header.frame_id = params_.bim_frame;
    msg.a_graph = *a_msg_;
    msg.s_graph = s_msg;
    if (last_match_) msg.match = *last_match_;
    msg.bim_T_map = ros_conversions::ToPose(out.bim_T_map);
    msg.wall_states = ros_conversions::ToMsg(sol.walls);
    is_graph_pub_.publish(msg);
  }
  if (marker_pub_.getNumSubscribers() > 0) {
    auto markers = ros_markers::BuildMergerMarkers(merger_.a_graph(), s_graph, merger_.pairs(),
                                                   out.bim_T_map, params_.markers);
    for (auto& m : markers.markers) m.header.stamp = s_msg.header.stamp;
    marker_pub_.publish(markers);
  }
}

}  // namespace ros_merger
}  // namespace is_graphs

int main(int argc, char** argv) {
  ros::init(argc, argv, "merger_node");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    const auto params = is_graphs::ros_merger::ReadParams(pnh);
    is_graphs::ros_merger::MergerNode node(nh, params);
    ros::AsyncSpinner spinner(2);  // odometry keeps flowing while graphs are converted
    spinner.start();
    ros::waitForShutdown();
    return EXIT_SUCCESS;
  } catch (const is_graphs::ros_params::ParamError& e) {
    ROS_FATAL("merger_node: %s", e.what());
    return EXIT_FAILURE;
  }
}
