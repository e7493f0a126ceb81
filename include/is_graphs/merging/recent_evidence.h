#pragma once

#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/merging/is_graph_problem.h"
#include "is_graphs/merging/merger_config.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

/// What the robot saw lately, against the BIM under a merge. The match pairs of a merge stay
/// consistent when the robot is carried elsewhere (its old rooms do not move); only the walls
/// it sees now tell: moved into B through their keyframes' merged poses, they should lie on
/// wall-surfaces of the A-Graph.
struct RecentEvidence {
  int planes{0};     // distinct wall planes observed in the newest keyframes
  int supported{0};  // of which lying on an A-Graph wall-surface
  bool contradicts{false};
  std::string message;
};

/// Looks at the wall planes (at least config.recent_min_length long) observed in the newest
/// config.recent_keyframes keyframes; a plane is supported by a wall-surface whose normal is
/// within config.gate_angle_deg, whose plane is within config.gate_offset of the plane's
/// middle, and whose extent (grown by 1 m) the middle falls in. Contradicts when at least
/// config.recent_min_planes are seen and fewer than config.recent_min_support of them are
/// supported.
RecentEvidence CheckRecentEvidence(const agraph::AGraph& a_graph, const sgraph::SGraph& s_graph,
                                   const MergeSolution& solution, const MergerConfig& config);

}  // namespace merging
}  // namespace is_graphs
