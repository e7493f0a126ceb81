#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/graph_match.h"
#include "is_graphs/merging/consistency_check.h"
#include "is_graphs/merging/is_graph_problem.h"
#include "is_graphs/merging/merger_config.h"
#include "is_graphs/merging/odometry_extrapolation.h"
#include "is_graphs/merging/recent_evidence.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

enum class MergeEvent {
  kNone,       // nothing merged (no merge yet and no UNIQUE match)
  kLocalized,  // a first (or new, after LOST) merge holds
  kUpdated,    // the merge was re-solved and still holds
  kRejected,   // a UNIQUE match did not survive its own merge: still not localized
  kLost,       // the merge was contradicted and dropped
};

const char* ToString(MergeEvent event);

struct MergeOutput {
  MergeEvent event{MergeEvent::kNone};
  bool merged{false};                                          // a pose may be published
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};  // B_x_M (gravity-aligned)
  /// B <- odom for the S-Graph revision merged: B_x_M composed with the merged (BIM-corrected)
  /// pose of the newest keyframe and that keyframe's odometry, so that B <- base_link is
  /// bim_T_odom * odom_T_base for any later odometry reading. Anchored on the revision's own
  /// keyframe, it does not depend on the map -> odom of a newer revision.
  Eigen::Isometry3d bim_T_odom{Eigen::Isometry3d::Identity()};
  /// The same keyframe, with the odometry's scale and yaw bias estimated from the revision's
  /// steps (CalibrateOdometry): anchor.Pose(odom_T_base) is the published pose. With too few
  /// steps the calibration is the identity and the pose is bim_T_odom * odom_T_base.
  OdometryAnchor anchor;
  Eigen::Matrix3d covariance{Eigen::Matrix3d::Identity()};  // of (x, y, yaw)
  MergeSolution solution;
  ConsistencyReport consistency;
  RecentEvidence evidence;
  std::string message;
  std::vector<std::string> warnings;  // about the merged pose (e.g. a height outside the storeys)
};

/// The merger's core: keeps the A-Graph, the match pairs gathered from UNIQUE matches and the
/// current B_x_M; merges each new match or S-Graph revision into the iS-Graph (SolveMerge),
/// checks it (CheckConsistency, and new UNIQUE matches against the merged B_x_M) and drops the
/// merge when contradicted. Not thread-safe: one worker calls it.
class Merger {
 public:
  explicit Merger(const MergerConfig& config) : config_(config) {}

  /// A new building: "" or why it is unusable (then no A-Graph is held). Resets the merge.
  std::string SetAGraph(const agraph::AGraph& graph);
  bool HasAGraph() const { return has_a_graph_; }
  const agraph::AGraph& a_graph() const { return a_graph_; }
  const std::string& a_graph_sha256() const { return a_graph_.source.sha256; }

  /// A match (UNIQUE starts or extends the merge; others re-solve a merge with its pairs),
  /// merged with the newest S-Graph (ids are stable across revisions).
  MergeOutput OnMatch(const matching::GraphMatch& match, const sgraph::SGraph& s_graph);
  /// A new S-Graph revision: re-solves the merge (if any) with the pairs gathered so far.
  MergeOutput OnSGraph(const sgraph::SGraph& s_graph);
  /// Drops the merge (pairs and B_x_M).
  void Reset();

  bool merged() const { return merged_; }
  const MatchPairs& pairs() const { return pairs_; }
  const Eigen::Vector3d& bim_x_map() const { return xi_; }

 private:
  MergeOutput SolveAndCheck(const sgraph::SGraph& s_graph, bool starting);
  double HeightOfMap(const sgraph::SGraph& s_graph, double fallback) const;
  /// The A-Graph storey under the newest keyframe, by its height in B (-1: none).
  int StoreyWalked(const sgraph::SGraph& s_graph) const;

  MergerConfig config_;
  agraph::AGraph a_graph_;
  bool has_a_graph_{false};
  bool merged_{false};
  MatchPairs pairs_;
  Eigen::Vector3d xi_{Eigen::Vector3d::Zero()};     // B_x_M: x, y, yaw
  Eigen::Vector3d prior_{Eigen::Vector3d::Zero()};  // the last UNIQUE match's guess
  std::map<int, Eigen::Vector2d> deviations_;       // the last solve's wall deviation states
  double match_z_{0.0};
};

/// The newest keyframe's position in M (the origin when there is none).
Eigen::Vector2d NewestKeyframePosition(const sgraph::SGraph& s_graph);

}  // namespace merging
}  // namespace is_graphs
