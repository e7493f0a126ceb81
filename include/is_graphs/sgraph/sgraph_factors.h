#pragma once

#include <ceres/problem.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>

#include "is_graphs/sgraph/backend_config.h"
#include "is_graphs/sgraph/sgraph.h"
#include "is_graphs/sgraph/sgraph_backend.h"

namespace is_graphs {
namespace sgraph {

/// The S-Graph's parameter blocks and factors, for any ceres::Problem: the S-Graph back end
/// solves them alone, the merger together with the A-Graph and the match constraints.
/// Blocks: keyframe poses (t, q on EigenQuaternionManifold), plane normals (SphereManifold<3>)
/// and offsets, room/corridor and floor centres in the plane, the odometry's distance scale
/// (under OdometryScalePriorCost; held at its value where BackendConfig::odometry_scale_sigma is
/// 0). Factors: odometry, keyframe–plane
/// (Huber), room–plane and corridor–plane (Cauchy), floor–room. The first keyframe is held
/// fixed (the gauge). The ceres::Problem must own costs, losses and manifolds (Ceres' default)
/// and must not outlive this object, which holds the blocks (not copyable).
struct SGraphFactors {
  struct PoseBlock {
    Eigen::Vector3d t;
    Eigen::Quaterniond q;
  };
  struct PlaneBlock {
    Eigen::Vector3d n;
    double d{0.0};
    bool observed{false};  // has a keyframe–plane factor
  };

  /// The blocks at the problem's values; nothing is added to any ceres::Problem yet.
  explicit SGraphFactors(const BackendProblem& problem);
  SGraphFactors(const SGraphFactors&) = delete;
  SGraphFactors& operator=(const SGraphFactors&) = delete;

  /// Adds the blocks and the factors of `problem` (the one given to the constructor).
  void AddTo(const BackendProblem& problem, const BackendConfig& config,
             ceres::Problem& ceres_problem);
  /// Writes the estimates back into `problem`.
  void WriteBack(BackendProblem& problem) const;

  std::map<int, PoseBlock> poses;
  std::map<int, PlaneBlock> planes;
  std::map<int, Eigen::Vector2d> centres;  // every room's, a block only where it has factors
  Eigen::Vector2d floor_centre{Eigen::Vector2d::Zero()};
  double odometry_scale{1.0};  // a block where there are odometry edges
};

/// A published S-Graph as a back-end problem: the snapshot is the S-Graph's own solution, so
/// its room–plane distances and floor–room offsets are taken as the measurements.
BackendProblem BackendProblemFromSnapshot(const SGraph& graph);

/// The horizontal unit normal of a room's first vertical plane (across a corridor), or zero.
Eigen::Vector2d CorridorAcross(const SGraph& graph, const Room& room);

}  // namespace sgraph
}  // namespace is_graphs
