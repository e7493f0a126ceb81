#include "is_graphs/geometry/surface_sampling.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace is_graphs {
namespace geometry {
namespace {

// Uniform in [0, 1) from one 32-bit draw of the (fully specified) Mersenne twister.
double Uniform(std::mt19937& rng) { return static_cast<double>(rng()) * (1.0 / 4294967296.0); }

}  // namespace

std::string SurfaceSamplingConfig::Validate() const {
  if (!std::isfinite(points_per_square_metre) || points_per_square_metre <= 0.0) {
    return "points_per_square_metre must be a positive number, got " +
           std::to_string(points_per_square_metre);
  }
  return "";
}

SurfaceSamples SampleSurface(const TriangleMesh& mesh, const SurfaceSamplingConfig& config) {
  std::vector<bool> excluded(mesh.object_names.size(), false);
  for (size_t i = 0; i < excluded.size(); ++i) {
    const std::string object_class = mesh.ObjectClass(static_cast<int>(i));
    excluded[i] = std::find(config.excluded_classes.begin(), config.excluded_classes.end(),
                            object_class) != config.excluded_classes.end();
  }

  std::mt19937 rng(config.seed);
  SurfaceSamples samples;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int object = mesh.triangle_object[t];
    if (excluded[object]) continue;
    const double expected = mesh.TriangleArea(static_cast<int>(t)) * config.points_per_square_metre;
    const double whole = std::floor(expected);
    const int count = static_cast<int>(whole) + (Uniform(rng) < expected - whole ? 1 : 0);
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.vertices[tri[0]];
    const Eigen::Vector3d& b = mesh.vertices[tri[1]];
    const Eigen::Vector3d& c = mesh.vertices[tri[2]];
    for (int k = 0; k < count; ++k) {
      // Uniform on the triangle: p = (1 − √u) a + √u (1 − v) b + √u v c.
      const double su = std::sqrt(Uniform(rng));
      const double v = Uniform(rng);
      samples.points.push_back((1.0 - su) * a + su * (1.0 - v) * b + su * v * c);
      samples.object.push_back(object);
    }
  }
  return samples;
}

}  // namespace geometry
}  // namespace is_graphs
