#pragma once
// Internal to the core: A-Graph <-> JSON, element by element (docs/agraph_format.md).

#include <nlohmann/json.hpp>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace agraph {
namespace internal {

/// Fills `graph` from the file's top-level object, checking types, finiteness and unit normals
/// per element; throws FormatError naming the element. `mesh` is left as written.
void AGraphFromJson(const nlohmann::json& root, AGraph* graph);

nlohmann::json AGraphToJson(const AGraph& graph);

}  // namespace internal
}  // namespace agraph
}  // namespace is_graphs
