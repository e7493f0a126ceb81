#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/matching/surface_evidence.h"
#include "is_graphs/matching/wall_crossings.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

/// A wall plane and the keyframe positions (in M) it was observed from.
struct SeenWall {
  WallSegment wall;
  std::vector<Eigen::Vector2d> from;  // at most max_viewpoints, spread over its observations
};

/// The keyframes each of `walls` was observed from (graph.observations), at most
/// `max_viewpoints` per wall, evenly spread in observation order. Walls observed from no keyframe
/// with a finite position are left out.
std::vector<SeenWall> SeenFrom(const sgraph::SGraph& graph, const std::vector<WallSegment>& walls,
                               int max_viewpoints);

/// Free space against the BIM's walls: a wall plane the robot saw was in its line of sight.
/// Under a wrong motion a plane seen through a doorway can land behind a BIM wall, where the
/// robot could not have seen it. A point along a plane (every 0.3 m, at most 16, taken 0.2 m in
/// front of it) is hidden under `pose` when the sight line to it from each of the plane's
/// viewpoints goes through an interior BIM wall outside the doorways (WallCrossings::Blocks;
/// exterior walls never block: windows). Returns Σ over planes of min(1, length / full_length)
/// x the share of its points hidden. Under the truth every part of a plane was seen from some
/// keyframe (its extent is the union of what was seen), so with enough viewpoints nothing is
/// hidden, unless a wall of the plan was not built, or an interior wall has a glass pane or an
/// opening the A-Graph lacks: callers weigh it, they do not veto on it.
double HiddenWalls(const std::vector<SeenWall>& walls, const WallCrossings& crossings,
                   const Pose2& pose, int storey, double full_length);

}  // namespace matching
}  // namespace is_graphs
