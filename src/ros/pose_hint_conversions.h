// A pose hint from ROS (matcher_node's `initialpose` topic and `set_pose_hint` service): the
// message checked and turned into the core's matching::PoseHint, with the robot's pose in the
// map at the hint's stamp from tf. Every error names what is wrong; docs/localization_services.md.
#pragma once

#include <geometry_msgs/PoseWithCovarianceStamped.h>

#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/matching/pose_hint.h"
#include "tf_lookup.h"

namespace is_graphs {
namespace ros_conversions {

struct HintFrames {
  std::string bim{"bim"};          // the hint's frame (another is turned into it by tf)
  std::string map{"map"};          // the S-Graph's frame
  std::string robot{"base_link"};  // the frame the hint places
  double tf_timeout{0.5};          // s to wait for tf at the hint's stamp
};

/// The storey id of `storey` (a name, or an index as agraph::FindStorey reads it; "": -1, any).
Result<int> HintStorey(const agraph::AGraph& building, const std::string& storey);

/// The hint `msg` says: the robot in frames.bim at its stamp (zero: the latest tf) with the x,
/// y, yaw block of its covariance, in another frame turned into bim by tf (or an error naming
/// the frame); the robot's pose in frames.map at the same stamp from tf; checked by
/// matching::CheckPoseHint (NaN, a covariance not positive definite).
Result<matching::PoseHint> PoseHintFromMsg(const geometry_msgs::PoseWithCovarianceStamped& msg,
                                           int storey, const ros_tf::TfLookup& tf,
                                           const HintFrames& frames);

}  // namespace ros_conversions
}  // namespace is_graphs
