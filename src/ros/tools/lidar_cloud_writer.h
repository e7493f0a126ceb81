// make_bag's LiDAR output: each simulated model published as its real ROS driver does (topic,
// frames, PointCloud2 fields), so a recording from that driver could replace the bag.
#pragma once

#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>

#include <string>

#include "is_graphs/sim/lidar_model.h"
#include "is_graphs/sim/scan_simulator.h"

namespace is_graphs {
namespace sim_ros {

/// Where a model's driver publishes: the cloud topic, the mount frame (tf_static base_link ->
/// it) and the clouds' frame (the mount frame itself, or a child of it: ouster-ros' os_lidar).
struct LidarDriver {
  std::string topic;
  std::string mount_frame;
  std::string points_frame;
};
LidarDriver DriverFor(sim::LidarModelKind model);

/// The scan as the model's driver publishes it; `scan_start` is the scan's first firing in bag
/// time.
///  - vlp16, velodyne_pointcloud XYZIRT: x y z intensity float32, ring uint16, time float32 (s
///    after the stamp = the scan start); point_step 22, unorganized, dense.
///  - os1_64, ouster-ros (os_point.h): x y z intensity float32 (at 0 4 8 16), t uint32 (ns after
///    the stamp = the first column), reflectivity uint16, ring uint16 (the row), ambient uint16,
///    range uint32 (mm); point_step 48; organized rows x columns (64 x 1024), a pixel without a
///    return has NaN x y z and range 0 (is_dense false).
///  - hesai_xt32, Hesai ROS driver (PointXYZIT): x y z intensity float32 (at 0 4 8 16), timestamp
///    float64 (absolute s) at 24, ring uint16 at 32; point_step 48, unorganized, dense; the stamp
///    is the first point's time.
sensor_msgs::PointCloud2 ToCloud(const sim::LidarScan& scan, const sim::LidarModel& model,
                                 const ros::Time& scan_start);

}  // namespace sim_ros
}  // namespace is_graphs
