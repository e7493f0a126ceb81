#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "is_graphs/sim/scenario_config.h"

namespace is_graphs {
namespace sim {

/// What a LiDAR's data sheet and its ROS driver fix (not configurable in a scenario): the beams
/// in firing order, the rings the driver gives them, the pulse spacing, the intensity scale and
/// where the driver's point frame sits on the sensor.
struct LidarSpec {
  std::vector<double> elevation_deg;  // per laser id, in firing order within a column
  std::vector<std::uint16_t> ring;    // the driver's `ring` of each laser id
  double laser_interval{0.0};         // s between two lasers of one column (0: all at once)
  double intensity_scale{100.0};      // the driver's intensity for reflectivity 1 head-on
  /// The frame the driver's points are in, relative to the mounted sensor frame (identity but
  /// for the Ouster: os_sensor -> os_lidar, turned 180 deg about z, 36.18 mm up).
  Eigen::Isometry3d mount_T_points{Eigen::Isometry3d::Identity()};
};

/// The model's beams and driver conventions:
///  - vlp16 (velodyne_pointcloud): 16 lasers at -15..+15 deg, 2 deg apart, data-sheet order
///    (-15, +1, -13, +3, ...), 2.304 us apart; ring 0 = the lowest beam.
///  - os1_64 (ouster-ros): 64 beams evenly from +22.5 to -22.5 deg, all of a column at once;
///    ring = the image row, 0 = the highest beam.
///  - hesai_xt32 (Hesai ROS driver): 32 channels from +15 to -16 deg, 1 deg apart, 1.512 us
///    apart; ring = the channel, 0 = the highest beam.
LidarSpec SpecFor(LidarModelKind model);

}  // namespace sim
}  // namespace is_graphs
