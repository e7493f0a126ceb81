#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// Keeps the finite points whose distance from `origin` is in [min_range, max_range].
PointList RangeFilter(const PointList& points, const Eigen::Vector3f& origin, double min_range,
                      double max_range);

/// A hash key of a voxel's integer index (21 bits a coordinate: ±2^20 voxels).
std::uint64_t VoxelKey(const Eigen::Vector3i& voxel);

/// Voxel-grid downsampling: the centroid of the points in each occupied voxel (in first-seen
/// order).
PointList VoxelFilter(const PointList& points, double voxel_size);

}  // namespace sgraph
}  // namespace is_graphs
