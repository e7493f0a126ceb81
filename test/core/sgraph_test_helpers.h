#pragma once
// Synthetic clouds for the S-Graph tests: points sampled on known planes, with noise.

#include <Eigen/Core>
#include <random>
#include <vector>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace testing {

/// A vertical wall from a to b (x, y), z in [z0, z1], sampled every `step` with Gaussian noise
/// along its normal.
inline void AddWall(sgraph::PointList& points, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    double z0, double z1, double step, double noise, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, noise);
  const Eigen::Vector2d dir = (b - a).normalized();
  const Eigen::Vector2d n(-dir.y(), dir.x());
  const double length = (b - a).norm();
  for (double s = 0.0; s <= length; s += step)
    for (double z = z0; z <= z1; z += step) {
      const Eigen::Vector2d p = a + s * dir + gauss(rng) * n;
      points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                          static_cast<float>(z));
    }
}

/// A horizontal patch at height z over [x0, x1] x [y0, y1].
inline void AddFloor(sgraph::PointList& points, double x0, double x1, double y0, double y1,
                     double z, double step, double noise, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, noise);
  for (double x = x0; x <= x1; x += step)
    for (double y = y0; y <= y1; y += step)
      points.emplace_back(static_cast<float>(x), static_cast<float>(y),
                          static_cast<float>(z + gauss(rng)));
}

/// The walls of a closed polygon (counter-clockwise corners), floor at 0, 2.5 m high.
inline sgraph::PointList PolygonRoom(const std::vector<Eigen::Vector2d>& corners, double step,
                                     double noise, std::mt19937& rng) {
  sgraph::PointList points;
  for (size_t i = 0; i < corners.size(); ++i)
    AddWall(points, corners[i], corners[(i + 1) % corners.size()], 0.0, 2.5, step, noise, rng);
  return points;
}

}  // namespace testing
}  // namespace is_graphs
