#include "is_graphs/geometry/triangle_mesh.h"

#include <Eigen/Geometry>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace is_graphs {
namespace geometry {
namespace {

// Parses the vertex index of a face corner "a", "a/b", "a//c" or "a/b/c" (1-based, negative:
// relative to the end) into a 0-based index; false when malformed or out of range.
bool ParseCorner(const std::string& token, int vertex_count, int* index, std::string* error) {
  const std::string head = token.substr(0, token.find('/'));
  errno = 0;
  char* end = nullptr;
  const long value = std::strtol(head.c_str(), &end, 10);
  if (head.empty() || *end != '\0' || errno != 0) {
    *error = "bad face vertex \"" + token + "\"";
    return false;
  }
  const long resolved = value > 0 ? value - 1 : vertex_count + value;
  if (value == 0 || resolved < 0 || resolved >= vertex_count) {
    *error = "face vertex " + std::to_string(value) + " out of range (" +
             std::to_string(vertex_count) + " vertices so far)";
    return false;
  }
  *index = static_cast<int>(resolved);
  return true;
}

}  // namespace

std::string TriangleMesh::ObjectClass(int object) const {
  const std::string& name = object_names[object];
  return name.substr(0, name.find('#'));
}

double TriangleMesh::TriangleArea(int triangle) const {
  const Eigen::Vector3i& t = triangles[triangle];
  return 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
}

double TriangleMesh::TotalArea() const {
  double area = 0.0;
  for (size_t i = 0; i < triangles.size(); ++i) area += TriangleArea(static_cast<int>(i));
  return area;
}

Result<TriangleMesh> ParseObj(std::istream& input, const std::string& name) {
  TriangleMesh mesh;
  int current_object = -1;
  std::string line;
  for (int line_number = 1; std::getline(input, line); ++line_number) {
    const auto fail = [&](const std::string& detail) {
      return Result<TriangleMesh>::Error(name + ":" + std::to_string(line_number) + ": " + detail);
    };
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream tokens(line);
    std::string keyword;
    if (!(tokens >> keyword) || keyword[0] == '#') continue;
    if (keyword == "o") {
      std::string object_name;
      std::getline(tokens >> std::ws, object_name);
      mesh.object_names.push_back(object_name);
      current_object = static_cast<int>(mesh.object_names.size()) - 1;
    } else if (keyword == "v") {
      Eigen::Vector3d v;
      if (!(tokens >> v.x() >> v.y() >> v.z()) || !v.allFinite()) {
        return fail("vertex needs three finite numbers: \"" + line + "\"");
      }
      mesh.vertices.push_back(v);
    } else if (keyword == "f") {
      std::vector<int> corners;
      std::string token, error;
      const int vertex_count = static_cast<int>(mesh.vertices.size());
      while (tokens >> token) {
        int index = 0;
        if (!ParseCorner(token, vertex_count, &index, &error)) return fail(error);
        corners.push_back(index);
      }
      if (corners.size() < 3) return fail("face needs at least 3 vertices: \"" + line + "\"");
      if (current_object < 0) {
        mesh.object_names.emplace_back();
        current_object = static_cast<int>(mesh.object_names.size()) - 1;
      }
      for (size_t k = 1; k + 1 < corners.size(); ++k) {  // fan triangulation
        mesh.triangles.emplace_back(corners[0], corners[k], corners[k + 1]);
        mesh.triangle_object.push_back(current_object);
      }
    }
    // vn, vt, g, s, usemtl, mtllib, l, p...: not needed here.
  }
  if (input.bad()) return Result<TriangleMesh>::Error(name + ": read error");
  return Result<TriangleMesh>::Ok(std::move(mesh));
}

Result<TriangleMesh> LoadObj(const std::string& path) {
  std::ifstream file(path);
  if (!file) return Result<TriangleMesh>::Error(path + ": cannot open mesh file");
  return ParseObj(file, path);
}

}  // namespace geometry
}  // namespace is_graphs
