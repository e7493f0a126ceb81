#pragma once

#include <Eigen/Core>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// Keeps the finite points whose distance from `origin` is in [min_range, max_range].
PointList RangeFilter(const PointList& points, const Eigen::Vector3f& origin, double min_range,
                      double max_range);

/// Voxel-grid downsampling: the centroid of the points in each occupied voxel (in first-seen
/// order).
PointList VoxelFilter(const PointList& points, double voxel_size);

}  // namespace sgraph
}  // namespace is_graphs
