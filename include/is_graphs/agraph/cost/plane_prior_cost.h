#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

#include "is_graphs/geometry/plane.h"

namespace is_graphs {
namespace agraph {

/// Keeps a plane near its BIM measurement (n_m, d_m):
///
///   residual (3) = Σ^{-1/2} [ B^T n ; d − d_m ]
///
/// where B = [b_1 b_2] (3x2) is an orthonormal basis of the tangent plane of the sphere at n_m,
/// so B^T n is the normal difference n − n_m expressed in that tangent plane (≈ the rotation
/// angle, in rad, for small differences). Σ is the 3x3 covariance of (angle_1, angle_2, d).
/// The normal term vanishes also at n = −n_m: the prior assumes n stays in the hemisphere of
/// n_m, which a unit normal on ceres::SphereManifold<3> started at n_m does.
///
/// Parameter blocks:
///   n  plane unit normal (3), on ceres::SphereManifold<3>
///   d  plane offset (1)
class PlanePriorCost {
 public:
  PlanePriorCost(const geometry::Plane& measured, const Eigen::Matrix3d& sqrt_information)
      : measured_d_(measured.d), sqrt_information_(sqrt_information) {
    tangent_basis_ = geometry::TangentBasis(measured.normal);
  }

  template <typename T>
  bool operator()(const T* const normal, const T* const d, T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vector3T> n(normal);
    Vector3T error;
    error.template head<2>() = tangent_basis_.transpose().template cast<T>() * n;
    error(2) = d[0] - T(measured_d_);
    Eigen::Map<Vector3T> r(residual);
    r = sqrt_information_.template cast<T>() * error;
    return true;
  }

  static ceres::CostFunction* Create(const geometry::Plane& measured,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<PlanePriorCost, 3, 3, 1>(
        new PlanePriorCost(measured, sqrt_information));
  }

  /// The tangent basis B (for tests and for callers that build Σ in it).
  const Eigen::Matrix<double, 3, 2>& tangent_basis() const { return tangent_basis_; }

 private:
  double measured_d_;
  Eigen::Matrix3d sqrt_information_;
  Eigen::Matrix<double, 3, 2> tangent_basis_;
};

}  // namespace agraph
}  // namespace is_graphs
