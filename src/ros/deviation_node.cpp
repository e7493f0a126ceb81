// deviation_node: as-built against as-planned (issue 21). In: is_graph (merger_node's iS-Graph:
// the A-Graph, the S-Graph and B_x_M of each merge). Out: `deviations` (latched,
// msg/WallDeviations.msg: every wall of the storey walked, keyed by IFC GlobalId, the EXTRA
// planes, and every door and opening present or closed), `deviations/markers` (latched). Params
// (~, config/deviations.yaml): those of merging::WallDeviationConfig, those of
// merging::DoorwayDeviationConfig prefixed `doorway_`, `heat_max` (m, the offset drawn full red).
#include <diagnostic_updater/diagnostic_updater.h>
#include <is_graphs/ISGraph.h>
#include <ros/ros.h>

#include <set>

#include "agraph_conversions.h"
#include "deviation_conversions.h"
#include "is_graphs/sgraph/finite_checks.h"
#include "param_helpers.h"
#include "pose_conversions.h"
#include "sgraph_conversions.h"

namespace is_graphs {
namespace {

class DeviationNode {
 public:
  DeviationNode(ros::NodeHandle& nh, const merging::WallDeviationConfig& config,
                const merging::DoorwayDeviationConfig& doors, double heat_max)
      : config_(config), doors_(doors), heat_max_(heat_max) {
    pub_ = nh.advertise<is_graphs::WallDeviations>("deviations", 1, true);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("deviations/markers", 1, true);
    sub_ = nh.subscribe("is_graph", 1, &DeviationNode::OnISGraph, this);
    diagnostics_.setHardwareID("is_graphs");
    diagnostics_.add("deviations", [this](diagnostic_updater::DiagnosticStatusWrapper& d) {
      using diagnostic_msgs::DiagnosticStatus;
      if (last_off_ < 0)
        d.summary(DiagnosticStatus::OK, "waiting for the iS-Graph (is_graph: not localized yet)");
      else
        d.summaryf(DiagnosticStatus::OK, "%d walls off the plan, %d doors closed", last_off_,
                   last_closed_);
      d.add("iS-Graphs classified", classified_);
      d.add("iS-Graphs ignored (non-finite)", rejected_);
    });
    diagnostics_timer_ = nh.createTimer(ros::Duration(1.0),
                                        [this](const ros::TimerEvent&) { diagnostics_.update(); });
  }

 private:
  void OnISGraph(const is_graphs::ISGraph::ConstPtr& msg) {
    if (msg->a_graph.source_sha256 != sha_) {
      sha_ = msg->a_graph.source_sha256;
      a_graph_ = ros_conversions::FromMsg(msg->a_graph);
      std::set<int> unnamed;
      for (const auto& w : a_graph_.walls)
        if (w.guid.empty()) unnamed.insert(w.id);
      if (!unnamed.empty())  // once per A-Graph
        ROS_WARN(
            "deviation_node: %zu walls of '%s' have no IFC GlobalId (e.g. A-Graph wall %d): "
            "they are reported by A-Graph id",
            unnamed.size(), msg->a_graph.building.c_str(), *unnamed.begin());
    }
    const sgraph::SGraph s_graph = ros_conversions::FromMsg(msg->s_graph);
    const Eigen::Isometry3d bim_T_map = ros_conversions::FromPose(msg->bim_T_map);
    std::string bad = sgraph::FirstNonFinite(s_graph);
    if (bad.empty() && !bim_T_map.matrix().allFinite()) bad = "bim_T_map";
    if (!bad.empty()) {
      ++rejected_;
      ROS_WARN_THROTTLE(2.0, "deviation_node: %s: non-finite %s: ignored", sub_.getTopic().c_str(),
                        bad.c_str());
      return;
    }
    ++classified_;
    const auto walls = merging::ClassifyWalls(a_graph_, s_graph, bim_T_map, config_);
    const auto doors = merging::ClassifyDoorways(a_graph_, s_graph, bim_T_map, config_, doors_);
    is_graphs::WallDeviations out;
    out.header = msg->header;
    out.a_graph_sha256 = sha_;
    out.s_graph_revision = msg->s_graph.revision;
    int off = 0;
    for (const auto& w : walls) {
      out.walls.push_back(ros_conversions::ToMsg(w));
      off +=
          w.status != merging::WallStatus::kAsPlanned && w.status != merging::WallStatus::kNotSeen;
    }
    int closed = 0;
    for (const auto& d : doors) {
      out.doorways.push_back(ros_conversions::ToMsg(d));
      closed += d.status == merging::DoorwayStatus::kClosed;
    }
    pub_.publish(out);
    auto markers = ros_conversions::DeviationMarkers(walls, doors, msg->header.frame_id, heat_max_);
    for (auto& m : markers.markers) m.header.stamp = msg->header.stamp;
    marker_pub_.publish(markers);
    if (off != last_off_ || closed != last_closed_)
      ROS_INFO(
          "deviation_node: S-Graph rev %u: %d of %zu walls off the plan (MOVED, NOT_BUILT, "
          "EXTRA), %d of %zu doors and openings CLOSED",
          msg->s_graph.revision, off, walls.size(), closed, doors.size());
    last_off_ = off, last_closed_ = closed;
  }

  merging::WallDeviationConfig config_;
  merging::DoorwayDeviationConfig doors_;
  double heat_max_;
  std::string sha_;
  agraph::AGraph a_graph_;
  int last_off_{-1}, last_closed_{-1};
  long classified_{0}, rejected_{0};
  ros::Publisher pub_, marker_pub_;
  ros::Subscriber sub_;
  diagnostic_updater::Updater diagnostics_;
  ros::Timer diagnostics_timer_;
};

}  // namespace
}  // namespace is_graphs

int main(int argc, char** argv) {
  ros::init(argc, argv, "deviation_node");
  ros::NodeHandle nh, pnh("~");
  try {
    is_graphs::merging::WallDeviationConfig c;
    double heat_max = 0.35;
    is_graphs::ros_params::Read(pnh, "planned_offset", c.planned_offset);
    is_graphs::ros_params::Read(pnh, "planned_angle_deg", c.planned_angle_deg);
    is_graphs::ros_params::Read(pnh, "max_offset", c.max_offset);
    is_graphs::ros_params::Read(pnh, "max_angle_deg", c.max_angle_deg);
    is_graphs::ros_params::Read(pnh, "min_overlap", c.min_overlap);
    is_graphs::ros_params::Read(pnh, "extra_min_length", c.extra_min_length);
    is_graphs::ros_params::Read(pnh, "extra_min_height", c.extra_min_height);
    is_graphs::ros_params::Read(pnh, "extra_min_views", c.extra_min_views);
    is_graphs::ros_params::Read(pnh, "door_margin", c.door_margin);
    is_graphs::ros_params::Read(pnh, "not_built_min_rays", c.not_built_min_rays);
    is_graphs::merging::DoorwayDeviationConfig d;
    is_graphs::ros_params::Read(pnh, "doorway_default_width", d.default_width);
    is_graphs::ros_params::Read(pnh, "doorway_walk_margin", d.walk_margin);
    is_graphs::ros_params::Read(pnh, "doorway_view_distance", d.view_distance);
    is_graphs::ros_params::Read(pnh, "doorway_present_min_rays", d.present_min_rays);
    is_graphs::ros_params::Read(pnh, "doorway_closed_min_cover", d.closed_min_cover);
    is_graphs::ros_params::Read(pnh, "doorway_closed_max_offset", d.closed_max_offset);
    is_graphs::ros_params::Read(pnh, "doorway_closed_min_height", d.closed_min_height);
    is_graphs::ros_params::Read(pnh, "doorway_closed_min_views", d.closed_min_views);
    is_graphs::ros_params::Read(pnh, "heat_max", heat_max);
    if (!(heat_max > 0.0))
      throw is_graphs::ros_params::ParamError("parameter '" + pnh.resolveName("heat_max") +
                                              "' must be > 0");
    for (const std::string& e :
         {c.Validate(), d.Validate().empty() ? "" : "doorway_" + d.Validate()})
      if (!e.empty())
        throw is_graphs::ros_params::ParamError("parameter '" +
                                                pnh.resolveName(e.substr(0, e.find(':'))) + "'" +
                                                e.substr(e.find(':')));
    is_graphs::DeviationNode node(nh, c, d, heat_max);
    ros::spin();
    return EXIT_SUCCESS;
  } catch (const is_graphs::ros_params::ParamError& e) {
    ROS_FATAL("deviation_node: %s", e.what());
    return EXIT_FAILURE;
  }
}
