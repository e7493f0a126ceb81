#pragma once

#include <geometry_msgs/Point.h>

#include <Eigen/Core>

namespace is_graphs {
namespace ros_conversions {

inline geometry_msgs::Point ToPoint(const Eigen::Vector3d& p) {
  geometry_msgs::Point out;
  out.x = p.x();
  out.y = p.y();
  out.z = p.z();
  return out;
}

inline geometry_msgs::Point ToPoint(const Eigen::Vector2d& p, double z) {
  return ToPoint(Eigen::Vector3d(p.x(), p.y(), z));
}

inline Eigen::Vector3d FromPoint(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }

}  // namespace ros_conversions
}  // namespace is_graphs
