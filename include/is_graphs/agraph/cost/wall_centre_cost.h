#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

#include "is_graphs/agraph/wall_centre.h"

namespace is_graphs {
namespace agraph {

/// Ties a wall centre to the two planes of its faces and the (constant) wall point w_s:
///
///   residual (3) = Σ^{-1/2} (c − WallCentre(n_a, d_a, n_b, d_b, w_s))
///
/// Parameter blocks:
///   c    wall centre (3)
///   n_a  surface a unit normal (3), on ceres::SphereManifold<3>
///   d_a  surface a offset (1)
///   n_b  surface b unit normal (3), on ceres::SphereManifold<3>
///   d_b  surface b offset (1)
///
/// The planes are parametrized as a unit normal on the sphere plus an offset rather than in
/// closest-point form Π = d n, because Π is singular at d = 0 (the normal is lost), and IFC
/// origins at a wall corner put many planes through the origin.
class WallCentreCost {
 public:
  WallCentreCost(const Eigen::Vector3d& wall_point, const Eigen::Matrix3d& sqrt_information)
      : wall_point_(wall_point), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* const centre, const T* const normal_a, const T* const d_a,
                  const T* const normal_b, const T* const d_b, T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vector3T> c(centre);
    const Eigen::Map<const Vector3T> n_a(normal_a);
    const Eigen::Map<const Vector3T> n_b(normal_b);
    const Vector3T expected =
        WallCentre<T>(n_a, d_a[0], n_b, d_b[0], wall_point_.template cast<T>());
    Eigen::Map<Vector3T> r(residual);
    r = sqrt_information_.template cast<T>() * (c - expected);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& wall_point,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<WallCentreCost, 3, 3, 3, 1, 3, 1>(
        new WallCentreCost(wall_point, sqrt_information));
  }

 private:
  Eigen::Vector3d wall_point_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace agraph
}  // namespace is_graphs
