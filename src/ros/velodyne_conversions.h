#pragma once

#include <sensor_msgs/PointCloud2.h>

#include "is_graphs/common/result.h"
#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace ros_conversions {

/// A VLP-16 driver cloud (XYZIRT: x, y, z, intensity float32, ring uint16, time float32 after
/// the header stamp) as the core's scan. x, y, z float32 are required; intensity, ring and
/// time are optional (a cloud without time gets has_time = false: no deskew). Non-finite
/// points are kept (the core drops and counts them). An error names what is malformed.
Result<sgraph::Scan> FromVelodyneMsg(const sensor_msgs::PointCloud2& msg);

}  // namespace ros_conversions
}  // namespace is_graphs
