#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "is_graphs/matching/graph_match.h"
#include "is_graphs/matching/rigid_fit.h"

namespace is_graphs {
namespace sgraph {
struct SGraph;
}
namespace matching {

class GraphMatcher;

/// chi² with 3 degrees of freedom (x, y, yaw) at 99 %: the hint's gate.
constexpr double kHintGateChi2 = 11.345;

/// A pose hint (rviz's "2D Pose Estimate", `initialpose`): the robot (base_link) in B at one
/// instant, with its x, y, yaw covariance, and the robot's pose in M at the same instant (the
/// caller knows it: the node from tf map -> base_link at the hint's stamp, the replay from
/// map -> odom and the odometry). Together they give the hint on B_x_M.
struct PoseHint {
  Pose2 bim_T_base;                                         // the robot in B (x, y, yaw)
  Pose2 map_T_base;                                         // the robot in M at the same instant
  Eigen::Matrix3d covariance{Eigen::Matrix3d::Identity()};  // x, y, yaw of bim_T_base (m², rad²)
  int storey{-1};           // A-Graph storey id the robot is on, -1: any
  std::string description;  // for messages: where the hint came from
};

/// "" when `hint` is usable, else why not: a non-finite value, or a covariance that is not
/// symmetric positive definite.
std::string CheckPoseHint(const PoseHint& hint);

/// The hint as a gate on hypotheses: the robot pose a hypothesis B_x_M implies,
/// B_x_M * map_T_base, must lie within the hint's covariance (squared Mahalanobis distance in
/// x, y, yaw at most kHintGateChi2) and on its storey.
class HintGate {
 public:
  explicit HintGate(const PoseHint& hint);  // `hint` must pass CheckPoseHint
  /// Squared Mahalanobis distance of the robot pose `bim_T_map` implies from the hint.
  double Distance2(const Pose2& bim_T_map) const;
  bool Inside(const Pose2& bim_T_map, int storey) const;
  const PoseHint& hint() const { return hint_; }

 private:
  PoseHint hint_;
  Eigen::Matrix3d information_;
};

/// x, y, yaw of `pose` (z, roll and pitch dropped).
Pose2 PlanarPose(const Eigen::Isometry3d& pose);

/// The robot pose (x, y, yaw) that `bim_T_map` implies for a robot at `map_T_base`.
Pose2 ImpliedRobotPose(const Pose2& bim_T_map, const Pose2& map_T_base);

/// Matching with a pose hint held until it is cleared, replaced or rejected. The hint is a
/// gate, never evidence: each S-Graph revision is matched as without it first; a UNIQUE answer
/// inside the gate stands (the hint agrees), one outside it rejects the hint (the evidence
/// alone names another pose: a warning says where and how far; that answer is returned, as
/// without the hint). Otherwise the revision is matched again with every hypothesis (room
/// hypotheses, the doubter's, the corner proposals) outside the gate left out: UNIQUE when
/// exactly one acceptable hypothesis cluster lies inside it, every absolute check of the
/// matcher applied (min rooms, walls seen on the BIM, doubt, walls' cross-check).
class HintedMatching {
 public:
  /// Replaces the hint; "" or why it is unusable (then nothing changes).
  std::string Set(const PoseHint& hint);
  void Clear() { gate_.reset(); }
  bool InForce() const { return gate_.has_value(); }
  /// What the hint in force is ("" without one).
  std::string Describe() const;

  /// One S-Graph revision matched (see the class comment). GraphMatch::hint says what the hint
  /// did; a rejection is also in GraphMatch::warnings.
  GraphMatch Match(GraphMatcher& matcher, const sgraph::SGraph& graph);

 private:
  std::optional<HintGate> gate_;
};

}  // namespace matching
}  // namespace is_graphs
