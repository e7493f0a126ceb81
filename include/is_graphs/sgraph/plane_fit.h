#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "is_graphs/geometry/plane.h"
#include "is_graphs/sgraph/point_types.h"

namespace is_graphs {
namespace sgraph {

/// geometry::TangentBasis, under the name the S-Graph code uses.
using geometry::TangentBasis;

/// A least-squares plane with its uncertainty.
struct PlaneFit {
  geometry::Plane plane;
  Eigen::Matrix3d information{Eigen::Matrix3d::Identity()};  // minimal tangent (see above)
  Eigen::Matrix4d covariance{Eigen::Matrix4d::Identity()};   // of (nx, ny, nz, d), rank 3
  Eigen::Vector3d centroid{Eigen::Vector3d::Zero()};
};

/// Total least squares (PCA) of points[indices]; the information is Σ JᵀJ / σ² on the minimal
/// tangent with r_i = n·p_i − d, scaled down to at most `max_effective_points` independent
/// points (neighbouring LiDAR points share calibration and deskew errors). nullopt for fewer
/// than 3 points or a degenerate (collinear) set.
///
/// With `vertical_about`, the normal is held perpendicular to that (gravity's up) axis: total
/// least squares of the points' horizontal projection. A wall is vertical, and a free fit of its
/// returns tilts by degrees where a recessed window or door frame falls inside the inlier band
/// over part of its height; the information stays the data's (the tilt is then a measurement of
/// zero with the spread the points support).
std::optional<PlaneFit> FitPlane(
    const PointList& points, const std::vector<int>& indices, double point_sigma,
    int max_effective_points, const std::optional<Eigen::Vector3d>& vertical_about = std::nullopt);

/// The information of the minimal tangent as the rank-3 covariance of (n, d): G H⁻¹ Gᵀ with
/// G = diag(B, 1).
Eigen::Matrix4d CovarianceFromInformation(const Eigen::Vector3d& n,
                                          const Eigen::Matrix3d& information);

/// The 3x3 covariance on the minimal tangent at n of a (rank-3) covariance of (n, d).
Eigen::Matrix3d TangentCovariance(const Eigen::Vector3d& n, const Eigen::Matrix4d& covariance);

/// The plane's covariance after a rigid transform b_T_a (the normal rotates, d shifts by n·t).
Eigen::Matrix4d TransformPlaneCovariance(const geometry::Plane& plane_a,
                                         const Eigen::Matrix4d& covariance_a,
                                         const Eigen::Isometry3d& b_T_a);

}  // namespace sgraph
}  // namespace is_graphs
