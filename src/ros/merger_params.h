#pragma once
// merger_node's parameters: the core's MergerConfig and the node's own, read and validated once.
#include <ros/node_handle.h>

#include <string>

#include "is_graphs/common/odometry_guard.h"
#include "is_graphs/merging/input_watchdog.h"
#include "is_graphs/merging/merger_config.h"
#include "merger_markers.h"

namespace is_graphs {
namespace ros_merger {

struct MergerNodeParams {
  merging::MergerConfig merger;
  std::string bim_frame{"bim"}, map_frame{"map"}, odom_frame{"odom"};
  double match_wait{2.0};   // s: a match for an S-Graph revision not seen yet waits this long
  double status_rate{1.0};  // Hz
  common::OdometryGuardConfig odometry_guard;  // config/odometry_guard.yaml, as sgraph_node's
  merging::WatchdogConfig watchdog;
  double watchdog_rate{20.0};  // Hz: the inputs' ages are checked this often
  // A restarted sgraph_node (a new process: revisions start over) while localized: the merge is
  // carried over by the odometry and checked against the new S-Graph's planes (CarriedMatch)
  // until a UNIQUE match comes or the robot walked carry_max_distance [m].
  bool carry_over_restart{true};
  double carry_max_distance{10.0};
  ros_markers::MergerMarkerStyle markers;
};

/// The parameters from `pnh` (private), validated; a bad one throws ros_params::ParamError
/// naming it.
MergerNodeParams ReadParams(const ros::NodeHandle& pnh);

}  // namespace ros_merger
}  // namespace is_graphs
