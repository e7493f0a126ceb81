#include "is_graphs/sgraph/cloud_filter.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace is_graphs {
namespace sgraph {

PointList RangeFilter(const PointList& points, const Eigen::Vector3f& origin, double min_range,
                      double max_range) {
  PointList out;
  out.reserve(points.size());
  const float lo2 = static_cast<float>(min_range * min_range);
  const float hi2 = static_cast<float>(max_range * max_range);
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    const float r2 = (p - origin).squaredNorm();
    if (r2 >= lo2 && r2 <= hi2) out.push_back(p);
  }
  return out;
}

std::uint64_t VoxelKey(const Eigen::Vector3i& voxel) {
  const auto part = [](int v) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(v) + (1 << 20)) & 0x1FFFFF;
  };
  return (part(voxel.x()) << 42) | (part(voxel.y()) << 21) | part(voxel.z());
}

PointList VoxelFilter(const PointList& points, double voxel_size) {
  // A hash grid (PCL's VoxelGrid needs a copy into pcl::PointCloud and overflows its index
  // on large extents; this is equivalent and allocation-light).
  struct Cell {
    Eigen::Vector3f sum{Eigen::Vector3f::Zero()};
    int count{0};
  };
  const float inv = static_cast<float>(1.0 / voxel_size);
  std::unordered_map<std::uint64_t, Cell> cells;
  cells.reserve(points.size() / 2 + 1);
  std::vector<std::uint64_t> order;
  order.reserve(points.size() / 2 + 1);
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    const std::uint64_t k = VoxelKey((p * inv).array().floor().cast<int>());
    auto [it, inserted] = cells.try_emplace(k);
    if (inserted) order.push_back(k);
    it->second.sum += p;
    ++it->second.count;
  }
  PointList out;
  out.reserve(order.size());
  for (std::uint64_t k : order) {
    const Cell& c = cells[k];
    out.push_back(c.sum / static_cast<float>(c.count));
  }
  return out;
}

}  // namespace sgraph
}  // namespace is_graphs
