#include "pose_hint_conversions.h"

#include <cmath>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace ros_conversions {

Result<int> HintStorey(const agraph::AGraph& building, const std::string& storey) {
  if (storey.empty()) return Result<int>::Ok(-1);
  const Result<int> index = agraph::FindStorey(building, storey);
  if (!index.ok()) return index;
  return Result<int>::Ok(building.storeys[index.value()].id);
}

Result<matching::PoseHint> PoseHintFromMsg(const geometry_msgs::PoseWithCovarianceStamped& msg,
                                           int storey, const ros_tf::TfLookup& tf,
                                           const HintFrames& frames) {
  using R = Result<matching::PoseHint>;
  const auto& p = msg.pose.pose;
  const Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  const Eigen::Vector3d t(p.position.x, p.position.y, p.position.z);
  if (!t.allFinite() || !q.coeffs().allFinite())
    return R::Error("the hint's pose is not finite (NaN or inf)");
  if (std::abs(q.norm() - 1.0) > 1e-3)
    return R::Error("the hint's orientation is not a unit quaternion (norm " +
                    std::to_string(q.norm()) + ")");
  const std::string frame = msg.header.frame_id;
  if (frame.empty()) return R::Error("the hint has no frame_id (expected '" + frames.bim + "')");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.toRotationMatrix();
  pose.translation() = t;
  // x, y, yaw of the 6x6 row-major covariance (x y z roll pitch yaw).
  Eigen::Matrix3d covariance;
  const int idx[3] = {0, 1, 5};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) covariance(r, c) = msg.pose.covariance[6 * idx[r] + idx[c]];
  if (frame != frames.bim) {
    const auto bim_T_frame =
        tf.Lookup(frames.bim, frame, msg.header.stamp, ros::Duration(frames.tf_timeout));
    if (!bim_T_frame.ok())
      return R::Error("the hint is in frame '" + frame + "', which tf cannot turn into '" +
                      frames.bim + "': " + bim_T_frame.error());
    pose = bim_T_frame.value() * pose;
    Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();  // x, y turn with the frame's yaw
    turn.topLeftCorner<2, 2>() =
        Eigen::Rotation2Dd(geometry::Yaw(bim_T_frame.value())).toRotationMatrix();
    covariance = turn * covariance * turn.transpose();
  }
  const auto map_T_robot =
      tf.Lookup(frames.map, frames.robot, msg.header.stamp, ros::Duration(frames.tf_timeout));
  if (!map_T_robot.ok())
    return R::Error("the robot's pose in the map at the hint's stamp is unknown: " +
                    map_T_robot.error());
  matching::PoseHint hint;
  hint.bim_T_base = matching::PlanarPose(pose);
  hint.map_T_base = matching::PlanarPose(map_T_robot.value());
  hint.covariance = covariance;
  hint.storey = storey;
  hint.description = "from '" + frame + "'";
  if (const std::string why = matching::CheckPoseHint(hint); !why.empty()) return R::Error(why);
  return R::Ok(hint);
}

}  // namespace ros_conversions
}  // namespace is_graphs
