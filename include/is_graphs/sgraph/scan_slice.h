#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// A keyframe's slice: the points of `cloud` (base_link) whose height along `up` (the gravity
/// direction in base_link) lies in [slice_low, slice_high], one per slice_cell square of the
/// plane normal to `up` (the first in scan order), at most slice_max_points (every k-th when
/// more). Deterministic. What the scan search scores against the BIM's walls: what stands in
/// that band is mostly walls, columns and tall clutter.
std::vector<Eigen::Vector3f> ScanSlice(const PointList& cloud, const Eigen::Vector3d& up,
                                       const FrontendConfig& config);

}  // namespace sgraph
}  // namespace is_graphs
