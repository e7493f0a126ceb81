#include "cloud_conversions.h"

#include <sensor_msgs/point_cloud2_iterator.h>

#include <cmath>

namespace is_graphs {
namespace ros_conversions {

sensor_msgs::PointCloud2 ToCloudMsg(const std::vector<Eigen::Vector3d>& points,
                                    const std::string& frame_id) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = frame_id;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(points.size());
  cloud.height = 1;
  cloud.width = static_cast<uint32_t>(points.size());
  cloud.is_dense = true;
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  for (const auto& p : points) {
    *x = static_cast<float>(p.x());
    *y = static_cast<float>(p.y());
    *z = static_cast<float>(p.z());
    ++x;
    ++y;
    ++z;
  }
  return cloud;
}

std::vector<Eigen::Vector3d> FromCloudMsg(const sensor_msgs::PointCloud2& cloud) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<size_t>(cloud.width) * cloud.height);
  sensor_msgs::PointCloud2ConstIterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  for (; x != x.end(); ++x, ++y, ++z) {
    if (std::isfinite(*x) && std::isfinite(*y) && std::isfinite(*z))
      points.emplace_back(*x, *y, *z);
  }
  return points;
}

}  // namespace ros_conversions
}  // namespace is_graphs
