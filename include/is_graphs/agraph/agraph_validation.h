#pragma once

#include <string>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace agraph {

/// "wall_surfaces[3] (IfcWall #1234)": how errors and warnings name an element. The IFC part is
/// left out when ifc_id < 0.
std::string ElementLabel(const char* array_name, int index, const char* ifc_class, long ifc_id);

/// Structural checks of a graph (what the per-element parser cannot see): ids equal to their
/// index, every reference in range, walls with two distinct surfaces that refer back to them,
/// doorways with one or two distinct rooms, rooms with ≥ 3 polygon vertices, unit normals.
/// Returns "" when valid, else the first problem, prefixed by the element's label.
std::string ValidateAGraph(const AGraph& graph);

}  // namespace agraph
}  // namespace is_graphs
