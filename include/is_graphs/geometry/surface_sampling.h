#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "is_graphs/geometry/triangle_mesh.h"

namespace is_graphs {
namespace geometry {

struct SurfaceSamplingConfig {
  double points_per_square_metre{100.0};      // expected density on every triangle
  std::uint32_t seed{42};                     // std::mt19937 seed: same mesh + config, same points
  std::vector<std::string> excluded_classes;  // object classes left out, e.g. {"IfcDoor"}

  /// "" when valid, else what is wrong, naming the parameter.
  std::string Validate() const;
};

struct SurfaceSamples {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> object;  // per point: index into the mesh's object_names
};

/// Uniform random points on the mesh surface: each triangle of area A gets floor(A ρ) points
/// plus one more with probability frac(A ρ), uniformly distributed on it. Deterministic: the
/// random numbers come from std::mt19937(seed) turned into doubles without the (implementation-
/// defined) standard distributions, so results are identical across standard libraries.
SurfaceSamples SampleSurface(const TriangleMesh& mesh, const SurfaceSamplingConfig& config);

}  // namespace geometry
}  // namespace is_graphs
