#pragma once

#include <is_graphs/SGraph.h>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace ros_conversions {

/// The core S-Graph as the `s_graph` message (frame and stamp are set by the caller).
is_graphs::SGraph ToMsg(const sgraph::SGraph& graph);

/// The message back to the core S-Graph (what matcher and merger nodes use).
sgraph::SGraph FromMsg(const is_graphs::SGraph& msg);

}  // namespace ros_conversions
}  // namespace is_graphs
