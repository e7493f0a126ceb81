#include "is_graphs/merging/pose_covariance.h"

#include <algorithm>
#include <cmath>

namespace is_graphs {
namespace merging {

Eigen::Matrix<double, 6, 6> RobotPoseCovariance(const Eigen::Matrix3d& xi_covariance,
                                                const Eigen::Isometry3d& bim_T_map,
                                                const Eigen::Vector3d& p_map,
                                                const MergerConfig& c) {
  const Eigen::Vector3d rp = bim_T_map.linear() * p_map;  // R p: the lever arm of a yaw error
  Eigen::Matrix3d j = Eigen::Matrix3d::Identity();        // d(x, y, yaw of the robot) / d xi
  j(0, 2) = -rp.y();
  j(1, 2) = rp.x();
  const Eigen::Matrix3d planar = j * xi_covariance * j.transpose();
  Eigen::Matrix<double, 6, 6> cov = Eigen::Matrix<double, 6, 6>::Zero();
  const int index[3] = {0, 1, 5};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) cov(index[r], index[k]) = planar(r, k);
  const double deg = M_PI / 180.0;
  cov(0, 0) += c.pose_sigma_xy * c.pose_sigma_xy;
  cov(1, 1) += c.pose_sigma_xy * c.pose_sigma_xy;
  cov(2, 2) += c.pose_sigma_z * c.pose_sigma_z;
  cov(3, 3) += std::pow(c.pose_sigma_roll_pitch_deg * deg, 2);
  cov(4, 4) += std::pow(c.pose_sigma_roll_pitch_deg * deg, 2);
  cov(5, 5) += std::pow(c.pose_sigma_yaw_deg * deg, 2);
  return cov;
}

Eigen::Matrix<double, 6, 6> GrowWithOdometry(const Eigen::Matrix<double, 6, 6>& covariance,
                                             double distance, const WatchdogConfig& config) {
  Eigen::Matrix<double, 6, 6> out = covariance;
  const double d = std::max(distance, 0.0);
  const double s_xy = config.degraded_sigma_per_m * d;
  const double s_yaw = config.degraded_yaw_sigma_deg_per_m * M_PI / 180.0 * d;
  out(0, 0) += s_xy * s_xy;
  out(1, 1) += s_xy * s_xy;
  out(5, 5) += s_yaw * s_yaw;
  return out;
}

}  // namespace merging
}  // namespace is_graphs
