#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <optional>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// Pose odom <- base_link at an absolute time, or nullopt where odometry does not reach.
using PoseAtTime = std::function<std::optional<Eigen::Isometry3d>(double)>;

/// Removes the motion distortion of a scan: every point is moved from the sensor frame at its
/// firing time (stamp + time) to base_link at the scan stamp, using odometry:
///
///   p_base(stamp) = T_ob(stamp)^-1 · T_ob(stamp + t_i) · T_bs · p_i
///
/// The poses are sampled at `bins` times over the scan's time span and interpolated between
/// them. Non-finite points are dropped. Returns nullopt when odometry does not cover the
/// scan (the caller skips it). Scans without per-point time only get T_bs applied.
std::optional<PointList> DeskewToBase(const Scan& scan, const Eigen::Isometry3d& base_T_sensor,
                                      const PoseAtTime& odom_pose, int bins = 32);

}  // namespace sgraph
}  // namespace is_graphs
