#pragma once
// The covariance of the robot's pose in the BIM frame, from the merge's B_x_M covariance.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "is_graphs/merging/input_watchdog.h"
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

/// `covariance` (as RobotPoseCovariance's) grown by the odometry's error over `distance` [m]
/// walked since the newest S-Graph revision (the DEGRADED pose): + (degraded_sigma_per_m d)² on
/// x and y, + (degraded_yaw_sigma_deg_per_m d)² on yaw.
Eigen::Matrix<double, 6, 6> GrowWithOdometry(const Eigen::Matrix<double, 6, 6>& covariance,
                                             double distance, const WatchdogConfig& config);

}  // namespace merging
}  // namespace is_graphs
