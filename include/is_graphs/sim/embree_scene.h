#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "is_graphs/common/result.h"
#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {

struct Ray {
  Eigen::Vector3f origin;
  Eigen::Vector3f direction;  // unit
  float t_max;
};

struct RayHit {
  float distance;          // +inf when nothing was hit
  Eigen::Vector3f normal;  // unit geometric normal of the hit triangle (either side)
  int triangle;            // -1 when nothing was hit
};

/// RAII owner of an Embree (3 or 4) device and a committed static triangle scene; casts batches of
/// rays (rtcIntersect1M on Embree 3, rtcIntersect1 on 4). The BVH is built single-threaded with high quality so that the
/// same triangles always give the same hits. Intersect is const and thread-compatible.
class EmbreeScene {
 public:
  static Result<std::unique_ptr<EmbreeScene>> Create(const SceneMesh& mesh);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// hits->size() becomes rays.size(); hit i answers ray i.
  void Intersect(const std::vector<Ray>& rays, std::vector<RayHit>* hits) const;
  /// One ray; convenience for queries (floor height, route checks).
  RayHit Intersect(const Ray& ray) const;

 private:
  struct Impl;
  explicit EmbreeScene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sim
}  // namespace is_graphs
