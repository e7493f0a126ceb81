#pragma once

#include <is_graphs/AGraph.h>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace ros_conversions {

/// The core A-Graph as the `a_graph` message (frame and stamp are set by the caller).
is_graphs::AGraph ToMsg(const agraph::AGraph& graph);

/// The message back to the core A-Graph (what matcher and merger nodes use).
agraph::AGraph FromMsg(const is_graphs::AGraph& msg);

}  // namespace ros_conversions
}  // namespace is_graphs
