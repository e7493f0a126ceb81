#pragma once

// Private to wall_deviations.cpp and doorway_status.cpp: the S-Graph's planes, path and sight lines
// in the BIM frame.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {
namespace detail {

/// A vertical S-plane in B, horizontally: {x : normal . x = d}, its extent and its viewpoints.
struct PlaneInB {
  int id{0};
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};  // unit, towards the side it was seen from
  double d{0.0};
  Eigen::Vector2d start{Eigen::Vector2d::Zero()}, end{Eigen::Vector2d::Zero()};
  double height{0.0};                 // z_max - z_min seen
  double offset_variance{0.0};        // m^2, of d (the S-Graph's covariance)
  int views{0};                       // keyframes that observed it
  std::vector<Eigen::Vector2d> from;  // keyframe positions it was observed from (at most 8)
  double Length() const { return (end - start).norm(); }
};

/// The S-Graph's vertical planes (|n_z| < 0.3) under bim_T_map.
std::vector<PlaneInB> PlanesInB(const sgraph::SGraph& graph, const Eigen::Isometry3d& bim_T_map);

using PathStep = std::pair<Eigen::Vector2d, Eigen::Vector2d>;
/// Keyframe to previous keyframe, in B; steps over 2 m (a gap in the scans) left out.
std::vector<PathStep> WalkedPathInB(const sgraph::SGraph& graph,
                                    const Eigen::Isometry3d& bim_T_map);

/// An opening along a wall where sight lines and steps pass: within `reach` of `at`.
struct Gap {
  Eigen::Vector2d at;
  double reach;
};

/// Whether segment p-q crosses the segment s-e (a wall's mid-line, or an opening in it) strictly
/// between p and q, 0.1 m or more from s and e, and farther than each gap's reach from its point.
bool Through(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& s,
             const Eigen::Vector2d& e, const std::vector<Gap>& gaps);

/// The robot's median keyframe height in B: the storey walked on.
double RobotHeight(const sgraph::SGraph& graph, const Eigen::Isometry3d& bim_T_map);

/// How often the robot's sight or path went through the segment start-end (a wall's mid-line)
/// outside `gaps` and 0.1 m from its ends: each walked step across it, and each point along an
/// S-plane (every 0.3 m, at most 16, 0.2 m in front of it) that at least half of the plane's
/// viewpoints see through it (the plane's extent is the union of what was seen; a wall standing
/// between most viewpoints and the plane would itself have been seen and matched).
int RaysThrough(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                const std::vector<Gap>& gaps, const std::vector<PlaneInB>& planes,
                const std::vector<PathStep>& path);

}  // namespace detail
}  // namespace merging
}  // namespace is_graphs
