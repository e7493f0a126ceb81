#pragma once

#include <is_graphs/SGraph.h>

namespace is_graphs {
namespace ros_sgraph {

/// Whether `next` starts a new S-Graph (sgraph_node reset its graph: a restarted bag or node,
/// or a track loss): within one run keyframe 0 never changes and the keyframes never shrink.
inline bool IsNewSession(const is_graphs::SGraph& previous, const is_graphs::SGraph& next) {
  if (next.revision < previous.revision) return true;
  if (next.keyframes.size() < previous.keyframes.size()) return true;
  return !previous.keyframes.empty() && !next.keyframes.empty() &&
         next.keyframes.front().stamp != previous.keyframes.front().stamp;
}

}  // namespace ros_sgraph
}  // namespace is_graphs
