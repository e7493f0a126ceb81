#pragma once

#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"

namespace is_graphs {
namespace agraph {

/// The `format` string and the newest `version` of docs/agraph_format.md this reader knows.
inline constexpr char kAGraphFormatName[] = "is_graphs.agraph";
inline constexpr int kAGraphFormatVersion = 1;

/// Reads and validates an A-Graph file (docs/agraph_format.md). On failure the error names the
/// file and the element, e.g.
///   "b.agraph.json: wall_surfaces[3] (IfcWall #1234): normal is not a unit vector (|n| = 0.5)".
/// Normals within 1e-3 of unit length are renormalized; a missing `orientation` is classified
/// from the normal; `mesh` is resolved to an absolute path against the file's folder.
Result<AGraph> LoadAGraph(const std::string& path);

/// As LoadAGraph, from JSON text; `path` names the source in errors and anchors `mesh`.
Result<AGraph> ParseAGraph(const std::string& json_text, const std::string& path);

/// Writes `graph` in the same format (mesh written relative to the output's folder). Returns ""
/// on success, else an error naming the file.
std::string SaveAGraph(const AGraph& graph, const std::string& path);

/// The JSON text SaveAGraph writes, with `mesh` as given.
std::string ToJsonText(const AGraph& graph);

}  // namespace agraph
}  // namespace is_graphs
