#include "is_graphs/sgraph/floor_check.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace is_graphs {
namespace sgraph {

double FractionCoveredAbove(const PointList& points, const std::vector<int>& inliers,
                            const Eigen::Vector3d& up_in, double cell, double min_rise,
                            double max_rise) {
  if (inliers.empty() || points.empty() || !(cell > 0.0)) return 0.0;
  const Eigen::Vector3d up = up_in.normalized();
  // A horizontal frame (e1, e2) orthogonal to up.
  const Eigen::Vector3d e1 = up.unitOrthogonal();
  const Eigen::Vector3d e2 = up.cross(e1);
  auto key = [&](const Eigen::Vector3d& p) {
    const auto i = static_cast<std::int64_t>(std::floor(e1.dot(p) / cell));
    const auto j = static_cast<std::int64_t>(std::floor(e2.dot(p) / cell));
    return (i << 32) ^ (j & 0xffffffffLL);
  };
  // Per column, the heights of its points.
  std::unordered_map<std::int64_t, std::vector<float>> columns;
  columns.reserve(points.size());
  for (const auto& q : points) {
    const Eigen::Vector3d p = q.cast<double>();
    columns[key(p)].push_back(static_cast<float>(up.dot(p)));
  }
  int covered = 0;
  for (int i : inliers) {
    const Eigen::Vector3d p = points[i].cast<double>();
    const double h = up.dot(p);
    const auto it = columns.find(key(p));
    if (it == columns.end()) continue;
    for (float z : it->second)
      if (z > h + min_rise && z < h + max_rise) {
        ++covered;
        break;
      }
  }
  return static_cast<double>(covered) / inliers.size();
}

}  // namespace sgraph
}  // namespace is_graphs
