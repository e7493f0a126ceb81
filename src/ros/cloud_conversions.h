#pragma once

#include <sensor_msgs/PointCloud2.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace is_graphs {
namespace ros_conversions {

/// Points as an x/y/z float32 PointCloud2 in `frame_id` (unordered: height 1).
sensor_msgs::PointCloud2 ToCloudMsg(const std::vector<Eigen::Vector3d>& points,
                                    const std::string& frame_id);

/// The finite x/y/z of a PointCloud2 with float32 x, y, z fields.
std::vector<Eigen::Vector3d> FromCloudMsg(const sensor_msgs::PointCloud2& cloud);

}  // namespace ros_conversions
}  // namespace is_graphs
