#pragma once

#include <Eigen/Core>
#include <istream>
#include <string>
#include <vector>

#include "is_graphs/common/result.h"

namespace is_graphs {
namespace geometry {

/// A triangle mesh whose triangles belong to named objects, as in the converter's OBJ
/// (docs/agraph_format.md): one object per IFC element, named "<IfcClass>#<step id>".
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // 0-based vertex indices
  std::vector<int> triangle_object;        // per triangle: index into object_names
  std::vector<std::string> object_names;   // "IfcWall#1234"; "" for faces before any `o`

  /// "IfcWall" of "IfcWall#1234" (the name up to '#', all of it when there is none).
  std::string ObjectClass(int object) const;
  double TriangleArea(int triangle) const;
  double TotalArea() const;
};

/// Reads a Wavefront OBJ: `o name`, `v x y z`, `f a b c` (also `f a/b/c`, `f a//c`, negative
/// (relative) indices, and polygons, fan-triangulated). Other statements (vn, vt, g, s, usemtl,
/// mtllib, comments) are ignored. Errors name the file and the line: "b.obj:12: ...".
Result<TriangleMesh> LoadObj(const std::string& path);
/// As LoadObj, from a stream; `name` prefixes errors.
Result<TriangleMesh> ParseObj(std::istream& input, const std::string& name);

}  // namespace geometry
}  // namespace is_graphs
