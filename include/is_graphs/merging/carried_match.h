#pragma once

#include <Eigen/Geometry>
#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/graph_match.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

/// The pose a merge held, carried over a restart of sgraph_node by the odometry (which did not
/// restart): B <- odom of the last merge and the new S-Graph's own map <- odom give B_x_M of the
/// new S-Graph.
/// Eigen: B <- map_new = bim_T_odom * (newest keyframe's pose * its odom_pose^-1)^-1.
Eigen::Isometry3d CarriedTransform(const Eigen::Isometry3d& bim_T_odom,
                                   const sgraph::SGraph& graph);

/// A match for `graph` under `bim_T_map`, a motion known otherwise (CarriedTransform): every
/// wall-grade S-plane paired with the A-surfaces of `storey` it lies along under it
/// (matching::SurfaceEvidence, the matcher's tolerances), and every S-room (not a corridor)
/// whose centre lands inside an A-room of `storey`, within centre_tolerance of its centre, paired
/// with it. UNIQUE when at least `min_planes` S-planes are paired, else NONE. It is a hypothesis,
/// not a result: the merger's own checks on a start (min_surface_inliers_without_rooms, what was
/// seen lately lying on the BIM, the solve's consistency) decide whether it holds.
matching::GraphMatch CarriedMatch(const agraph::AGraph& building, const sgraph::SGraph& graph,
                                  const Eigen::Isometry3d& bim_T_map, int storey, int min_planes,
                                  const matching::MatcherConfig& config = {});

}  // namespace merging
}  // namespace is_graphs
