#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// Splits the inliers of one plane into coplanar but disjoint segments: the points are ordered
/// by their coordinate along `direction` (a unit vector in the plane, horizontal for walls) and
/// cut wherever two neighbours are more than `gap` apart. Returns index lists into `points`,
/// ordered along `direction`.
std::vector<std::vector<int>> SplitCoplanarSegments(const PointList& points,
                                                    const std::vector<int>& inliers,
                                                    const Eigen::Vector3d& direction, double gap);

}  // namespace sgraph
}  // namespace is_graphs
