// matcher_node: matches each S-Graph revision (`s_graph`) against the building's A-Graph
// (`a_graph`, latched) and publishes `graph_match` (latched) and `graph_match/markers`. Thin:
// the work is in is_graphs_core (matching::GraphMatcher). Matching runs on a worker thread that
// always takes the newest S-Graph, so a slow match never piles up callbacks. Elements of either
// graph with non-finite values are left out and warned about (matching::CheckSGraph);
// health on /diagnostics. A pose hint (`initialpose`, `set_pose_hint`), `relocalize` and
// `set_storey` at run time (localization_services.h, docs/localization_services.md).
#include <diagnostic_updater/diagnostic_updater.h>
#include <is_graphs/AGraph.h>
#include <is_graphs/GraphMatch.h>
#include <is_graphs/SGraph.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "agraph_conversions.h"
#include "graph_match_conversions.h"
#include "graph_match_markers.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/pose_hint.h"
#include "localization_services.h"
#include "param_helpers.h"
#include "sgraph_conversions.h"
#include "sgraph_session.h"

namespace is_graphs {
namespace {

struct MatcherNodeParams {
  matching::MatcherConfig matcher;
  ros_markers::GraphMatchMarkerStyle markers;
  ros_conversions::HintFrames hint;
};

MatcherNodeParams ReadParams(const ros::NodeHandle& pnh) {
  MatcherNodeParams p;
  auto& c = p.matcher;
  ros_params::Read(pnh, "angle_tolerance_deg", c.angle_tolerance_deg);
  ros_params::Read(pnh, "offset_tolerance", c.offset_tolerance);
  ros_params::Read(pnh, "centre_tolerance", c.centre_tolerance);
  ros_params::Read(pnh, "pair_through_walls", c.pair_through_walls);
  ros_params::Read(pnh, "min_plane_fraction", c.min_plane_fraction);
  ros_params::Read(pnh, "yaw_tolerance_deg", c.yaw_tolerance_deg);
  ros_params::Read(pnh, "lever_arm_slack", c.lever_arm_slack);
  ros_params::Read(pnh, "quality_sigma", c.quality_sigma);
  ros_params::Read(pnh, "corridor_weight", c.corridor_weight);
  ros_params::Read(pnh, "wall_crossing_penalty", c.wall_crossing_penalty);
  ros_params::Read(pnh, "surface_evidence_weight", c.surface_evidence_weight);
  ros_params::Read(pnh, "surface_full_length", c.surface_full_length);
  ros_params::Read(pnh, "doorway_evidence_weight", c.doorway_evidence_weight);
  ros_params::Read(pnh, "doorway_tolerance", c.doorway_tolerance);
  ros_params::Read(pnh, "doorway_width_tolerance", c.doorway_width_tolerance);
  ros_params::Read(pnh, "sight_penalty", c.sight_penalty);
  ros_params::Read(pnh, "unique_min_wall_share", c.unique_min_wall_share);
  ros_params::Read(pnh, "unique_min_walls", c.unique_min_walls);
  ros_params::Read(pnh, "stair_height_tolerance", c.stair_height_tolerance);
  ros_params::Read(pnh, "storey_level_tolerance", c.storey_level_tolerance);
  ros_params::Read(pnh, "storey_level_tolerance_per_m", c.storey_level_tolerance_per_m);
  ros_params::Read(pnh, "sight_viewpoints", c.sight_viewpoints);
  ros_params::Read(pnh, "sight_door_margin", c.sight_door_margin);
  ros_params::Read(pnh, "surface_min_length", c.surface_min_length);
  ros_params::Read(pnh, "surface_min_height", c.surface_min_height);
  ros_params::Read(pnh, "outside_penalty", c.outside_penalty);
  ros_params::Read(pnh, "outside_margin", c.outside_margin);
  ros_params::Read(pnh, "door_margin", c.door_margin);
  ros_params::Read(pnh, "max_path_step", c.max_path_step);
  ros_params::Read(pnh, "proposals", c.proposals);
  ros_params::Read(pnh, "proposal_corner_reach", c.proposal_corner_reach);
  ros_params::Read(pnh, "proposal_min_walls", c.proposal_min_walls);
  ros_params::Read(pnh, "proposal_min_share", c.proposal_min_share);
  ros_params::Read(pnh, "proposal_margin", c.proposal_margin);
  ros_params::Read(pnh, "proposal_margin_share", c.proposal_margin_share);
  ros_params::Read(pnh, "proposal_crossing_penalty", c.proposal_crossing_penalty);
  ros_params::Read(pnh, "proposal_max_candidates", c.proposal_max_candidates);
  ros_params::Read(pnh, "proposal_cross_check", c.proposal_cross_check);
  ros_params::Read(pnh, "proposal_cross_check_max_rooms", c.proposal_cross_check_max_rooms);
  ros_params::Read(pnh, "scan_proposals", c.scan_proposals);
  matching::ScanSearchConfig& ss = c.scan_search;
  ros_params::Read(pnh, "scan_search_resolution", ss.resolution);
  ros_params::Read(pnh, "scan_search_sigma", ss.sigma);
  ros_params::Read(pnh, "scan_search_band_low", ss.band_low);
  ros_params::Read(pnh, "scan_search_band_high", ss.band_high);
  ros_params::Read(pnh, "scan_search_angular_step_deg", ss.angular_step_deg);
  ros_params::Read(pnh, "scan_search_margin", ss.margin);
  ros_params::Read(pnh, "scan_search_max_set", ss.max_set);
  ros_params::Read(pnh, "scan_search_min_points", ss.min_points);
  ros_params::Read(pnh, "scan_search_distinct_xy", ss.distinct_xy);
  ros_params::Read(pnh, "scan_search_distinct_yaw_deg", ss.distinct_yaw_deg);
  ros_params::Read(pnh, "scan_search_window_margin", ss.window_margin);
  ros_params::Read(pnh, "ambiguity_margin", c.ambiguity_margin);
  ros_params::Read(pnh, "doubt_centre_tolerance", c.doubt_centre_tolerance);
  ros_params::Read(pnh, "cluster_yaw_deg", c.cluster_yaw_deg);
  ros_params::Read(pnh, "cluster_translation", c.cluster_translation);
  ros_params::Read(pnh, "min_matched_rooms", c.min_matched_rooms);
  ros_params::Read(pnh, "min_matched_fraction", c.min_matched_fraction);
  ros_params::Read(pnh, "max_seeds", c.max_seeds);
  ros_params::Read(pnh, "deviation_offset", c.deviation_offset);
  ros_params::Read(pnh, "deviation_angle_deg", c.deviation_angle_deg);
  ros_params::Read(pnh, "deviation_max_offset", c.deviation_max_offset);
  ros_params::Read(pnh, "deviation_max_angle_deg", c.deviation_max_angle_deg);
  ros_params::Read(pnh, "frame_id", p.markers.frame_id);
  ros_params::Read(pnh, "marker_s_graph_lift", p.markers.s_graph_lift);
  p.hint.bim = p.markers.frame_id;
  ros_params::Read(pnh, "map_frame", p.hint.map);
  ros_params::Read(pnh, "robot_frame", p.hint.robot);
  ros_params::Read(pnh, "hint_tf_timeout", p.hint.tf_timeout);
  for (const auto& [name, value] :
       {std::pair<const char*, const std::string*>{"map_frame", &p.hint.map},
        {"robot_frame", &p.hint.robot}})
    if (value->empty())
      throw ros_params::ParamError("parameter '" + pnh.resolveName(name) + "' must not be empty");
  if (!(p.hint.tf_timeout >= 0.0 && p.hint.tf_timeout <= 10.0))
    throw ros_params::ParamError("parameter '" + pnh.resolveName("hint_tf_timeout") +
                                 "' must be within [0, 10] s");
  if (p.markers.frame_id.empty())
    throw ros_params::ParamError("parameter '" + pnh.resolveName("frame_id") +
                                 "' must not be empty");
  const std::string error = c.Validate();
  if (!error.empty())  // Validate names the field, which is the parameter's name
    throw ros_params::ParamError("parameter '" + pnh.resolveName(error.substr(0, error.find(' '))) +
                                 "': " + error);
  return p;
}

class MatcherNode {
 public:
  MatcherNode(ros::NodeHandle& nh, const MatcherNodeParams& params)
      : params_(params),
        matcher_(params.matcher),
        services_(nh, params.hint, [this](const ros_matcher::Request& r) { Submit(r); }) {
    match_pub_ = nh.advertise<is_graphs::GraphMatch>("graph_match", 1, /*latch=*/true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("graph_match/markers", 1, true);
    a_sub_ = nh.subscribe("a_graph", 1, &MatcherNode::OnAGraph, this);
    s_sub_ = nh.subscribe("s_graph", 1, &MatcherNode::OnSGraph, this);
    diagnostics_.setHardwareID("is_graphs");
    diagnostics_.add("matching", this, &MatcherNode::Diagnose);
    diagnostics_timer_ = nh.createTimer(ros::Duration(1.0),
                                        [this](const ros::TimerEvent&) { diagnostics_.update(); });
    worker_ = std::thread([this] { Work(); });
  }

  ~MatcherNode() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
  }

 private:
  void OnAGraph(const is_graphs::AGraph::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_a_ = msg;
    wake_.notify_all();
  }

  void Submit(const ros_matcher::Request& request) {
    std::lock_guard<std::mutex> lock(mutex_);
    requests_.push_back(request);
    wake_.notify_all();
  }

  /// A request from localization_services.h, on the worker thread.
  void Apply(const ros_matcher::Request& r) {
    using Kind = ros_matcher::Request::Kind;
    if (r.kind == Kind::kHint) {
      hinted_.Set(r.hint);  // checked by PoseHintFromMsg
      ROS_INFO("matcher_node: %s: in force", hinted_.Describe().c_str());
    } else if (r.kind == Kind::kRelocalize) {
      matcher_.ForgetHistory();
      hinted_.Clear();
      ++relocalizations_;
      ROS_WARN("matcher_node: relocalize: the match and any pose hint forgotten");
    } else {
      matcher_.SetStorey(r.storey);
      ++relocalizations_;
      ROS_WARN("matcher_node: set_storey: matching on %s; localizing again",
               r.storey < 0 ? "the whole building" : ("storey '" + r.storey_name + "'").c_str());
    }
  }

  void OnSGraph(const is_graphs::SGraph::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    last_s_receipt_ = ros::Time::now();
    if (pending_s_)
      ROS_DEBUG("matcher_node: S-Graph rev %u skipped (rev %u arrived)", pending_s_->revision,
                msg->revision);
    pending_s_ = msg;  // only the newest revision is kept
    wake_.notify_all();
  }

  void Work() {
    for (;;) {
      is_graphs::AGraph::ConstPtr a_msg;
      is_graphs::SGraph::ConstPtr s_msg;
      std::vector<ros_matcher::Request> requests;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] {
          return stop_ || pending_a_ || (pending_s_ && matcher_.HasAGraph()) || !requests_.empty();
        });
        if (stop_) return;
        a_msg.swap(pending_a_);
        if (matcher_.HasAGraph() || a_msg) s_msg.swap(pending_s_);
        requests.swap(requests_);
      }
      if (a_msg) SetAGraph(*a_msg);
      for (const auto& r : requests) Apply(r);
      // A request takes effect at once: the last S-Graph matched again (a copy of the pointer,
      // as in SetAGraph).
      if (!s_msg && !requests.empty() && matcher_.HasAGraph()) s_msg = last_s_;
      if (s_msg) MatchAndPublish(*s_msg);
    }
  }

  void SetAGraph(const is_graphs::AGraph& msg) {
    a_graph_ = ros_conversions::FromMsg(msg);
    for (const auto& w : matcher_.SetAGraph(a_graph_))
      ROS_WARN("matcher_node: A-Graph: %s", w.c_str());
    ROS_INFO("matcher_node: A-Graph '%s' with %zu rooms (%zu usable)", msg.building.c_str(),
             a_graph_.rooms.size(), matcher_.ARooms().size());
    services_.SetBuilding(a_graph_);
    if (matcher_.OnlyStorey() >= 0) {  // a storey id of the building before
      ROS_WARN("matcher_node: a new A-Graph: set_storey's restriction dropped");
      matcher_.SetStorey(-1);
    }
    a_loaded_ = true;
    // A new building: match the last S-Graph again. (Through a copy of the pointer: matching
    // replaces last_s_, which must not free the message being matched.)
    if (const is_graphs::SGraph::ConstPtr last = last_s_) MatchAndPublish(*last);
  }

  void MatchAndPublish(const is_graphs::SGraph& msg) {
    if (last_s_ && ros_sgraph::IsNewSession(*last_s_, msg)) {
      ROS_WARN("matcher_node: a new S-Graph (revision %u, %zu keyframes): matching from scratch",
               msg.revision, msg.keyframes.size());
      matcher_.ForgetHistory();
      if (hinted_.InForce()) ROS_WARN("matcher_node: the pose hint dropped with the old map");
      hinted_.Clear();  // its robot pose in the map is of the map gone
    }
    last_s_ = boost::make_shared<is_graphs::SGraph>(msg);
    const sgraph::SGraph s_graph = ros_conversions::FromMsg(msg);
    const matching::GraphMatch match = hinted_.Match(matcher_, s_graph);
    for (const auto& w : match.warnings) {
      if (w.rfind("pose hint rejected", 0) == 0)
        ROS_WARN("matcher_node: %s", w.c_str());  // once, never throttled away
      else
        ROS_WARN_THROTTLE(2.0, "matcher_node: %s", w.c_str());
    }
    const auto& stats = matcher_.LastStats();
    ROS_INFO(
        "matcher_node: S-Graph rev %u: %s (%u hypotheses, score %.2f, %zu room pairs), "
        "%d rooms, %d candidates (%d rooms reused), %d seeds, %.1f ms",
        msg.revision, matching::ToString(match.status), match.hypotheses, match.score,
        match.room_pairs.size(), stats.s_rooms, stats.candidates, stats.reused_rooms, stats.seeds,
        stats.milliseconds);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++matches_;
      left_out_ += static_cast<long>(match.warnings.size());
      last_status_ = matching::ToString(match.status);
      last_hint_ = match.hint;
      last_revision_ = msg.revision;
      last_ms_ = stats.milliseconds;
      max_ms_ = std::max(max_ms_, stats.milliseconds);
    }
    is_graphs::GraphMatch out = ros_conversions::ToMsg(match);
    out.relocalizations = relocalizations_;
    out.header.frame_id = params_.markers.frame_id;
    out.header.stamp = msg.header.stamp.isZero() ? ros::Time::now() : msg.header.stamp;
    match_pub_.publish(out);
    if (marker_pub_.getNumSubscribers() > 0) {
      auto markers = ros_markers::BuildGraphMatchMarkers(match, a_graph_, s_graph, params_.markers);
      for (auto& m : markers.markers) m.header.stamp = out.header.stamp;
      marker_pub_.publish(markers);
    }
  }

  void Diagnose(diagnostic_updater::DiagnosticStatusWrapper& d) {
    const bool has_a = a_loaded_;
    std::lock_guard<std::mutex> lock(mutex_);
    using diagnostic_msgs::DiagnosticStatus;
    if (!has_a)
      d.summary(DiagnosticStatus::WARN, "waiting for the A-Graph (a_graph)");
    else if (matches_ == 0)
      d.summary(DiagnosticStatus::WARN, "waiting for the S-Graph (s_graph)");
    else
      d.summaryf(DiagnosticStatus::OK, "S-Graph rev %u: %s", last_revision_, last_status_.c_str());
    d.add("matches", matches_);
    d.add("S-Graph elements left out (non-finite, malformed)", left_out_);
    d.add("last status", last_status_);
    d.add("pose hint", last_hint_.empty() ? std::string("none") : last_hint_);
    d.addf("last match [ms]", "%.1f", last_ms_);
    d.addf("slowest match [ms]", "%.1f", max_ms_);
    if (!last_s_receipt_.isZero())
      d.addf("S-Graph age [s]", "%.2f", (ros::Time::now() - last_s_receipt_).toSec());
  }

  MatcherNodeParams params_;
  matching::GraphMatcher matcher_;   // used by the worker thread only
  matching::HintedMatching hinted_;  // the worker's
  unsigned relocalizations_{0};      // the worker's: graph_match's relocalizations
  agraph::AGraph a_graph_;
  is_graphs::SGraph::ConstPtr last_s_;
  ros::Publisher match_pub_, marker_pub_;
  ros::Subscriber a_sub_, s_sub_;
  std::mutex mutex_;
  std::condition_variable wake_;
  is_graphs::AGraph::ConstPtr pending_a_;
  is_graphs::SGraph::ConstPtr pending_s_;
  bool stop_{false};
  // For /diagnostics (under mutex_; a_loaded_ set by the worker).
  diagnostic_updater::Updater diagnostics_;
  ros::Timer diagnostics_timer_;
  ros::Time last_s_receipt_;
  long matches_{0}, left_out_{0};
  std::string last_status_{"none yet"};
  std::string last_hint_;
  std::vector<ros_matcher::Request> requests_;  // from services_, for the worker
  unsigned last_revision_{0};
  double last_ms_{0.0}, max_ms_{0.0};
  std::atomic<bool> a_loaded_{false};
  ros_matcher::LocalizationServices services_;  // after the members its callbacks use
  std::thread worker_;
};

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  ros::init(argc, argv, "matcher_node");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    const auto params = is_graphs::ReadParams(pnh);
    is_graphs::MatcherNode node(nh, params);
    ros::spin();
    return EXIT_SUCCESS;
  } catch (const is_graphs::ros_params::ParamError& e) {
    ROS_FATAL("matcher_node: %s", e.what());
    return EXIT_FAILURE;
  }
}
