#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/pose_hint.h"
#include "is_graphs/merging/merger.h"
#include "is_graphs/sgraph/sgraph_builder.h"

namespace is_graphs {
namespace pipeline {

/// The configuration of every stage (each validated by its own Validate()).
struct PipelineConfig {
  sgraph::FrontendConfig frontend;
  sgraph::BackendConfig backend;
  matching::MatcherConfig matcher;
  merging::MergerConfig merger;

  /// "" when valid, else "<stage>: <what is wrong>".
  std::string Validate() const;
};

/// Milliseconds spent in each stage, one entry per call that did work.
struct StageTimes {
  std::vector<double> scan;  // a whole scan (every scan, keyframe or not)
  std::vector<double> preprocess, extraction, association, rooms;  // keyframe scans
  std::vector<double> optimization;  // S-Graph back end, after each keyframe
  std::vector<int> optimization_keyframes;
  std::vector<double> matching;  // one S-Graph revision
  std::vector<double> merging;   // one merge solve (match or revision)
};

/// One thing that happened (a match decision, a merge event), for logs and the evaluation.
struct PipelineEvent {
  double stamp{0.0};
  unsigned revision{0};
  std::string kind;  // "match", "localized", "updated", "rejected", "lost"
  matching::MatchStatus status{matching::MatchStatus::kNone};
  Eigen::Isometry3d bim_T_map{Eigen::Isometry3d::Identity()};
  int storey{-1};                      // a match's A-Graph storey id
  int hypotheses{0};                   // a match's hypotheses scored
  std::vector<int> competing_storeys;  // a match's other storeys that fit as well
  std::string message;
};

/// The whole localization, synchronous and without ROS: S-Graph front end and back end after
/// each keyframe, matching of each S-Graph revision, merging of each UNIQUE match and revision.
/// The nodes run the same stages asynchronously; this is what the benchmark and the offline
/// evaluation replay a bag through (deterministic: same input, same output).
class LocalizationPipeline {
 public:
  explicit LocalizationPipeline(const PipelineConfig& config);

  /// "" or why the A-Graph is unusable.
  std::string SetAGraph(const agraph::AGraph& graph);

  /// Feeds odometry; returns the robot's pose in B when localized.
  std::optional<Eigen::Isometry3d> AddOdometry(double stamp, const Eigen::Isometry3d& odom_T_base);
  /// Feeds a scan; a keyframe runs the back end, the matcher and the merger.
  sgraph::SGraphBuilder::ScanResult AddScan(const sgraph::Scan& scan,
                                            const Eigen::Isometry3d& base_T_sensor);

  /// A pose hint (matching::HintedMatching), held until replaced, rejected or the S-Graph
  /// restarts; "" or why it is unusable (nothing changes then). An event "hint" records it; the
  /// last S-Graph is matched again at once (as matcher_node does).
  std::string SetPoseHint(double stamp, const matching::PoseHint& hint);
  bool HintInForce() const { return hinted_.InForce(); }

  bool localized() const { return merger_.merged(); }
  const StageTimes& times() const { return times_; }
  const std::vector<PipelineEvent>& events() const { return events_; }
  /// Every UNIQUE match (events() keeps only changes of the match status), for the evaluation.
  const std::vector<PipelineEvent>& unique_matches() const { return unique_matches_; }
  /// Every match, whatever its status (the replay's scenario contracts check each one).
  const std::vector<PipelineEvent>& matches() const { return matches_; }
  sgraph::SGraph Snapshot() const { return builder_.Snapshot(); }
  const sgraph::SGraphBuilder& builder() const { return builder_; }
  const merging::Merger& merger() const { return merger_; }
  /// B <- odom of the current merge (identity before it).
  const Eigen::Isometry3d& bim_T_odom() const { return bim_T_odom_; }
  /// B_x_M of the current merge (identity before it).
  const Eigen::Isometry3d& bim_T_map() const { return bim_T_map_; }

 private:
  void Record(double stamp, unsigned revision, const merging::MergeOutput& out);
  /// Matches `graph` (with the pose hint) and merges a UNIQUE match, or the revision when merged.
  void MatchAndMerge(double stamp, const sgraph::SGraph& graph);

  PipelineConfig config_;
  sgraph::SGraphBuilder builder_;
  matching::GraphMatcher matcher_;
  matching::HintedMatching hinted_;
  merging::Merger merger_;
  Eigen::Isometry3d bim_T_odom_{Eigen::Isometry3d::Identity()};
  merging::OdometryAnchor anchor_;  // the published pose: anchor_.Pose(odom_T_base)
  Eigen::Isometry3d bim_T_map_{Eigen::Isometry3d::Identity()};
  StageTimes times_;
  std::vector<PipelineEvent> events_;
  std::vector<PipelineEvent> unique_matches_;
  std::vector<PipelineEvent> matches_;
};

}  // namespace pipeline
}  // namespace is_graphs
