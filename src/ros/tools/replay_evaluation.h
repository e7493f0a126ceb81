// replay_pipeline's evaluation outputs (what `make evaluate`, scripts/evaluate.py, reads besides
// the poses): every UNIQUE match against the true B_x_M, the map cloud against the BIM's
// wall-surfaces, and the S-Graph's own trajectory. ROS-free; the measures are in the core
// (is_graphs/pipeline/evaluation.h).
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/pipeline/evaluation.h"
#include "is_graphs/pipeline/localization_pipeline.h"
#include "is_graphs/sgraph/evaluation.h"

namespace is_graphs {
namespace bag_replay {

inline nlohmann::json XYYawDeg(const Eigen::Isometry3d& t) {
  const Eigen::Vector3d xi = geometry::ToXYYaw(t);
  return {xi.x(), xi.y(), xi.z() * 180.0 / M_PI};
}

/// Classifies each UNIQUE match when it is made: its B_x_M against the true one of the S-Graph
/// revision it matched (the keyframes aligned to the ground truth received so far, in x, y and
/// yaw: sgraph::EvaluateTrajectory), wrong when off by > 0.5 m on the map or > 5 deg, or on
/// another storey than the one the robot stands on (from the truth's height).
class MatchAudit {
 public:
  explicit MatchAudit(const agraph::AGraph& building) : building_(building) {}

  /// Call after each scan: audits the UNIQUE matches made since the last call.
  void Update(const pipeline::LocalizationPipeline& localization,
              const std::vector<sgraph::StampedPose>& truth, double first_stamp) {
    const auto& matches = localization.unique_matches();
    if (matches.size() == seen_) return;
    const sgraph::SGraph graph = localization.Snapshot();
    const auto traj = sgraph::EvaluateTrajectory(graph, truth);
    std::vector<Eigen::Vector3d> keyframes;
    for (const auto& k : graph.keyframes) keyframes.push_back(k.pose.translation());
    for (; seen_ < matches.size(); ++seen_) {
      const auto& m = matches[seen_];
      const auto e = pipeline::CompareTransforms(m.bim_T_map, traj.bim_T_map_gravity, keyframes);
      const int true_storey =
          truth.empty() ? -1
                        : agraph::StoreyAtHeight(building_, truth.back().pose.translation().z());
      const bool wrong_storey = m.storey >= 0 && true_storey >= 0 && m.storey != true_storey;
      const bool wrong = pipeline::IsWrongMatch(e) || wrong_storey;
      wrong_ += wrong;
      wrong_storeys_ += wrong_storey;
      json_.push_back({{"t", m.stamp - first_stamp},
                       {"revision", m.revision},
                       {"bim_x_map", XYYawDeg(m.bim_T_map)},
                       {"true_bim_x_map", XYYawDeg(traj.bim_T_map_gravity)},
                       {"keyframes_with_truth", traj.keyframes},
                       {"xy_error_m", e.xy_m},
                       {"yaw_error_deg", e.yaw_deg},
                       {"storey", m.storey},
                       {"true_storey", true_storey},
                       {"wrong_storey", wrong_storey},
                       {"wrong", wrong}});
    }
  }
  int wrong() const { return wrong_; }
  int wrong_storeys() const { return wrong_storeys_; }
  const nlohmann::json& json() const { return json_; }

 private:
  const agraph::AGraph& building_;
  size_t seen_{0};
  int wrong_{0};
  int wrong_storeys_{0};
  nlohmann::json json_ = nlohmann::json::array();
};

/// The map cloud (keyframe clouds at their optimized poses, 10 cm voxels) put in B with the
/// final merged B_x_M, against the A-Graph's wall-surfaces; null before any merge.
inline nlohmann::json MapCloudError(const pipeline::LocalizationPipeline& localization,
                                    const agraph::AGraph& building, bool ever_merged) {
  if (!ever_merged) return nullptr;
  const pipeline::CloudErrorConfig config;
  std::vector<Eigen::Vector3f> cloud = localization.builder().MapCloud(0.1);
  const Eigen::Isometry3f bim_T_map = localization.bim_T_map().cast<float>();
  for (auto& p : cloud) p = bim_T_map * p;
  const auto e = pipeline::CloudAgainstWallSurfaces(cloud, building, config);
  return {{"points", e.points},
          {"used", e.used},
          {"used_share", e.UsedShare()},
          {"rmse_m", e.rmse},
          {"median_m", e.median},
          {"max_m", e.max},
          {"merged_at_end", localization.localized()},
          {"voxel_m", 0.1},
          {"max_distance_m", config.max_distance},
          {"edge_margin_m", config.edge_margin}};
}

/// One TUM line: stamp x y z qx qy qz qw.
inline void WriteTum(std::FILE* f, double t, const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d p = pose.translation();
  std::fprintf(f, "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", t, p.x(), p.y(), p.z(), q.x(), q.y(),
               q.z(), q.w());
}

/// The S-Graph's optimized keyframe poses (map <- base_link) as a TUM file.
inline bool WriteKeyframesTum(const sgraph::SGraph& graph, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return false;
  for (const auto& k : graph.keyframes) WriteTum(f, k.stamp, k.pose);
  return std::fclose(f) == 0;
}

}  // namespace bag_replay
}  // namespace is_graphs
