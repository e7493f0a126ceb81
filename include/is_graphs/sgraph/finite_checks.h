#pragma once

#include <string>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// The first non-finite value of `graph` a merge would use, named ("keyframe 12: pose"), or ""
/// when every keyframe pose, odometry pose, plane, observation, room and floor is finite. A
/// graph with one is rejected whole by its readers: a NaN in one factor poisons a solve.
std::string FirstNonFinite(const SGraph& graph);

}  // namespace sgraph
}  // namespace is_graphs
