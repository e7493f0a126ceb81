#include "is_graphs/sgraph/deskew.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "is_graphs/sgraph/odometry_buffer.h"

namespace is_graphs {
namespace sgraph {

std::optional<PointList> DeskewToBase(const Scan& scan, const Eigen::Isometry3d& base_T_sensor,
                                      const PoseAtTime& odom_pose, int bins) {
  PointList out;
  out.reserve(scan.points.size());
  const Eigen::Isometry3f bs = base_T_sensor.cast<float>();
  auto finite = [](const ScanPoint& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  };
  if (!scan.has_time) {
    for (const auto& p : scan.points)
      if (finite(p)) out.push_back(bs * Eigen::Vector3f(p.x, p.y, p.z));
    return out;
  }
  float t_min = 0.0f;
  float t_max = 0.0f;
  for (const auto& p : scan.points) {
    if (!std::isfinite(p.time)) continue;
    t_min = std::min(t_min, p.time);
    t_max = std::max(t_max, p.time);
  }
  const auto reference = odom_pose(scan.stamp);
  if (!reference) return std::nullopt;
  bins = std::max(bins, 1);
  // Transforms base(stamp) <- sensor(t) at bin edges; interpolated linearly between them.
  std::vector<Eigen::Isometry3d> edges(bins + 1);
  const Eigen::Isometry3d reference_inv = reference->inverse();
  for (int b = 0; b <= bins; ++b) {
    const double t = t_min + (t_max - t_min) * b / bins;
    const auto pose = odom_pose(scan.stamp + t);
    if (!pose) return std::nullopt;
    edges[b] = reference_inv * *pose * base_T_sensor;
  }
  std::vector<Eigen::Isometry3f> bin_transforms(bins);
  for (int b = 0; b < bins; ++b)
    bin_transforms[b] = Interpolate(edges[b], edges[b + 1], 0.5).cast<float>();
  const float span = std::max(t_max - t_min, 1e-6f);
  for (const auto& p : scan.points) {
    if (!finite(p)) continue;
    const float t = std::isfinite(p.time) ? p.time : 0.0f;
    const int b = std::clamp(static_cast<int>((t - t_min) / span * bins), 0, bins - 1);
    out.push_back(bin_transforms[b] * Eigen::Vector3f(p.x, p.y, p.z));
  }
  return out;
}

}  // namespace sgraph
}  // namespace is_graphs
