#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// The share of `inliers` that have another point of `points` straight above them: within a
/// column of `cell` metres (horizontal, about `up`) and between `min_rise` and `max_rise` higher.
///
/// A floor is open above (only furniture and the foot of walls cover it), but a horizontal band
/// of wall returns is not: in a small room one VLP-16 ring meets the walls all around at about
/// the same height (a ring at −15° from 0.7 m reaches z ≈ 0.25 m on walls 1.7 m away), which a
/// plane-perpendicular-to-gravity RANSAC takes for a floor 0.25 m too high, and the next rings
/// hit the same walls a few centimetres above each of its points.
double FractionCoveredAbove(const PointList& points, const std::vector<int>& inliers,
                            const Eigen::Vector3d& up, double cell, double min_rise,
                            double max_rise);

}  // namespace sgraph
}  // namespace is_graphs
