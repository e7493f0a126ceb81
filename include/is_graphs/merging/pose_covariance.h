#pragma once
// The covariance of the robot's pose in the BIM frame, from the merge's B_x_M covariance.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "is_graphs/merging/merger_config.h"

namespace is_graphs {
namespace merging {

/// The 6x6 covariance (x, y, z, roll, pitch, yaw) of the robot in B: B_x_M's (x, y, yaw)
/// covariance `xi_covariance` moved to the robot's position `p_map` in M (a yaw error moves the
/// robot by its lever arm R p), plus the floors pose_sigma_* of `config` on the diagonal.
Eigen::Matrix<double, 6, 6> RobotPoseCovariance(const Eigen::Matrix3d& xi_covariance,
                                                const Eigen::Isometry3d& bim_T_map,
                                                const Eigen::Vector3d& p_map,
                                                const MergerConfig& config);

}  // namespace merging
}  // namespace is_graphs
