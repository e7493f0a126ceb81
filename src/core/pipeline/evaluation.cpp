#include "is_graphs/pipeline/evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace pipeline {

TransformError CompareTransforms(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                 const std::vector<Eigen::Vector3d>& points) {
  TransformError e;
  e.yaw_deg = std::abs(geometry::NormalizeAngle(geometry::Yaw(estimate) - geometry::Yaw(truth))) *
              180.0 / M_PI;
  const std::vector<Eigen::Vector3d> origin{Eigen::Vector3d::Zero()};
  for (const auto& p : points.empty() ? origin : points)
    e.xy_m = std::max(e.xy_m, (estimate * p - truth * p).head<2>().norm());
  return e;
}

CloudError CloudAgainstWallSurfaces(const std::vector<Eigen::Vector3f>& points_in_bim,
                                    const agraph::AGraph& building,
                                    const CloudErrorConfig& config) {
  CloudError out;
  out.points = static_cast<int>(points_in_bim.size());
  std::vector<double> errors;
  errors.reserve(points_in_bim.size());
  for (const Eigen::Vector3f& pf : points_in_bim) {
    const Eigen::Vector3d p = pf.cast<double>();
    double best = std::numeric_limits<double>::infinity();
    for (const auto& s : building.surfaces) {
      const double distance = std::abs(s.plane.SignedDistance(p));
      if (distance > config.max_distance || distance >= best) continue;
      const double length = s.Length();
      const double along = (p.head<2>() - s.start).dot((s.end - s.start) / std::max(length, 1e-9));
      if (along < config.edge_margin || along > length - config.edge_margin) continue;
      if (p.z() < s.z_min + config.edge_margin || p.z() > s.z_max - config.edge_margin) continue;
      best = distance;
    }
    if (std::isfinite(best)) errors.push_back(best);
  }
  out.used = static_cast<int>(errors.size());
  if (errors.empty()) return out;
  double sum = 0.0;
  for (double e : errors) sum += e * e;
  out.rmse = std::sqrt(sum / errors.size());
  std::sort(errors.begin(), errors.end());
  out.median = errors[errors.size() / 2];
  out.max = errors.back();
  return out;
}

}  // namespace pipeline
}  // namespace is_graphs
