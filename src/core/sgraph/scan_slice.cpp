#include "is_graphs/sgraph/scan_slice.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace is_graphs {
namespace sgraph {

std::vector<Eigen::Vector3f> ScanSlice(const PointList& cloud, const Eigen::Vector3d& up,
                                       const FrontendConfig& config) {
  std::vector<Eigen::Vector3f> out;
  if (config.slice_keyframes <= 0 || up.norm() < 1e-9) return out;
  const Eigen::Vector3f u = up.normalized().cast<float>();
  // Two horizontal axes normal to `up`.
  const Eigen::Vector3f e1 =
      (std::abs(u.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY())
          .cross(u)
          .normalized();
  const Eigen::Vector3f e2 = u.cross(e1);
  const double cell = config.slice_cell;
  std::unordered_set<std::uint64_t> taken;
  for (const Eigen::Vector3f& p : cloud) {
    const double h = p.dot(u);
    if (!(h >= config.slice_low && h <= config.slice_high)) continue;
    const auto i = static_cast<std::int64_t>(std::floor(p.dot(e1) / cell));
    const auto j = static_cast<std::int64_t>(std::floor(p.dot(e2) / cell));
    const std::uint64_t key = (static_cast<std::uint64_t>(i + (1 << 30)) << 32) ^
                              static_cast<std::uint64_t>(j + (1 << 30));
    if (taken.insert(key).second) out.push_back(p);
  }
  const size_t cap = static_cast<size_t>(config.slice_max_points);
  if (out.size() > cap) {
    std::vector<Eigen::Vector3f> thinned;
    thinned.reserve(cap);
    for (size_t k = 0; k < cap; ++k) thinned.push_back(out[k * out.size() / cap]);
    out.swap(thinned);
  }
  return out;
}

}  // namespace sgraph
}  // namespace is_graphs
