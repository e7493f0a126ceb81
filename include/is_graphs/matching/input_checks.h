#pragma once

#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

// Bad input the matcher survives: each problem is one warning line naming the element; the
// matcher then leaves the element out (a room without usable surfaces is never matched).

/// No rooms; ids that are not the dense index; non-finite planes or centres; a room with no
/// surfaces or naming a surface that does not exist.
std::vector<std::string> CheckAGraph(const agraph::AGraph& graph);

/// Neither rooms nor planes; duplicate plane or room ids; non-finite planes or centres; a room with
/// no planes or naming a plane that does not exist.
std::vector<std::string> CheckSGraph(const sgraph::SGraph& graph);

}  // namespace matching
}  // namespace is_graphs
