#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/sim/scenario_config.h"

namespace is_graphs {
namespace sim {

/// The scene as built: triangles in bim with a diffuse reflectivity (0..1) each.
struct SceneMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<float> reflectivity;     // per triangle
  std::vector<std::uint8_t> glass;     // per triangle, 1: a pane (GlassConfig); empty: no glass
  std::vector<std::uint8_t> polished;  // per triangle, 1: a polished floor; empty: none

  void AddTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   float reflectivity);
  /// An oriented box standing on z = base_z: centre (x, y), size (sx, sy, sz), yaw.
  void AddBox(const Eigen::Vector2d& center, double base_z, const Eigen::Vector3d& size, double yaw,
              float reflectivity);
  /// A vertical cylinder (closed, `segments` sides) standing on z = base_z.
  void AddCylinder(const Eigen::Vector2d& center, double base_z, double radius, double height,
                   float reflectivity, int segments = 16);
  std::size_t size() const { return triangles.size(); }
};

/// What BuildScene did, for the log: one line per deviation and clutter object.
struct SceneReport {
  std::vector<std::string> lines;
};

/// Builds the as-built scene: the BIM mesh without `drop_classes` objects, with the deviations
/// applied (walls moved/removed by their IFC id, partitions added) and the clutter placed on the
/// storey's floor at `floor_z`. `graph` is the planned A-Graph of the whole building (rooms and
/// walls are looked up on `storey`); random clutter uses `seed`. Errors name the config field.
Result<SceneMesh> BuildScene(const geometry::TriangleMesh& bim_mesh, const agraph::AGraph& graph,
                             int storey, double floor_z, const SceneConfig& config,
                             std::uint64_t seed, SceneReport* report = nullptr);

}  // namespace sim
}  // namespace is_graphs
