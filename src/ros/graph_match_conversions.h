#pragma once

#include <is_graphs/GraphMatch.h>

#include "is_graphs/matching/graph_match.h"

namespace is_graphs {
namespace ros_conversions {

/// The core match result as the `graph_match` message (header set by the caller). Warnings and
/// alternatives are not part of the message.
is_graphs::GraphMatch ToMsg(const matching::GraphMatch& match);

/// The message back to the core result (what the merger uses).
matching::GraphMatch FromMsg(const is_graphs::GraphMatch& msg);

}  // namespace ros_conversions
}  // namespace is_graphs
