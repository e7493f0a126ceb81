#pragma once
// sgraph_node's parameters: the core's FrontendConfig / BackendConfig, how clouds are read
// (cloud_layout) and the node's own, read and validated once.
#include <ros/node_handle.h>

#include <string>

#include "is_graphs/sgraph/backend_config.h"
#include "is_graphs/sgraph/frontend_config.h"
#include "lidar_conversions.h"
#include "sgraph_markers.h"

namespace is_graphs {
namespace ros_sgraph {

struct SGraphNodeParams {
  std::string map_frame{"map"}, odom_frame{"odom"}, base_frame{"base_link"};
  double map_cloud_period{2.0};  // s between map cloud publications (when subscribed)
  double map_cloud_voxel{0.1};
  double tf_rate{20.0};
  int cloud_queue{5};         // the cloud subscriber's queue: older clouds dropped (counted)
  double input_timeout{2.0};  // s of the clock: clouds or odometry stopped, said once a while
  double max_cloud_lag{1.0};  // s: processing this far behind the clouds' stamps is a warning
  ros_conversions::LidarCloudConfig cloud;  // cloud_layout, cloud_max_sweep_period
  sgraph::FrontendConfig frontend;
  sgraph::BackendConfig backend;
  ros_markers::SGraphMarkerStyle markers;
};

/// The parameters from `pnh` (private), validated; a bad one throws ros_params::ParamError
/// naming it.
SGraphNodeParams ReadParams(const ros::NodeHandle& pnh);

}  // namespace ros_sgraph
}  // namespace is_graphs
