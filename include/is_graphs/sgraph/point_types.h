#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace is_graphs {
namespace sgraph {

/// One LiDAR return as the VLP-16 driver gives it (XYZIRT), in the sensor frame at its own
/// firing time. `time` is seconds after the scan's stamp.
struct ScanPoint {
  float x{0.0f};
  float y{0.0f};
  float z{0.0f};
  float intensity{0.0f};
  std::uint16_t ring{0};
  float time{0.0f};
};

/// A whole scan: the core's view of a sensor_msgs/PointCloud2 (converted at the ROS edge).
struct Scan {
  double stamp{0.0};     // seconds, the first firing
  std::string frame_id;  // the sensor frame the points are in
  bool has_time{true};   // false when the cloud carried no per-point time (no deskew)
  std::vector<ScanPoint> points;
};

/// Points without attributes (the filtered, deskewed cloud of a keyframe).
using PointList = std::vector<Eigen::Vector3f>;

}  // namespace sgraph
}  // namespace is_graphs
