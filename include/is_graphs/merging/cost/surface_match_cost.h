#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

#include "is_graphs/geometry/plane.h"
#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace merging {

/// A matched pair of planes: the S-Graph plane (n_s, d_s) in M, moved into B by the
/// gravity-aligned B_x_M = (x, y, yaw) (and the constant height z of M in B), equals the
/// A-Graph wall-surface (n_a, d_a) in B:
///
///   n_b = R_z(yaw) n_s,  d_b = d_s + n_b · (x, y, z)
///   residual (3) = Σ^{-1/2} [ Bᵀ (n_b − n_a) ; d_b − d_a ]
///
/// B (3x2) is an orthonormal basis of the tangent plane of the sphere at the A-surface's BIM
/// normal, so Bᵀ(n_b − n_a) is the normal difference in that tangent plane (≈ the angles in
/// rad); Σ is the covariance of (angle_1, angle_2, offset). Both normals point into the room.
///
/// Parameter blocks:
///   ξ    B_x_M (3): x, y, yaw
///   n_s  S-plane unit normal (3), on ceres::SphereManifold<3>
///   d_s  S-plane offset (1)
///   n_a  A-surface unit normal (3), on ceres::SphereManifold<3>
///   d_a  A-surface offset (1)
class SurfaceMatchCost {
 public:
  SurfaceMatchCost(const Eigen::Vector3d& a_normal, double z,
                   const Eigen::Matrix3d& sqrt_information)
      : z_(z), sqrt_information_(sqrt_information) {
    basis_ = geometry::TangentBasis(a_normal);
  }

  template <typename T>
  bool operator()(const T* const xi, const T* const normal_s, const T* const d_s,
                  const T* const normal_a, const T* const d_a, T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vector3T> n_s(normal_s), n_a(normal_a);
    const Vector3T n_b = geometry::RotationZ(xi[2]) * n_s;
    const T d_b = d_s[0] + n_b.dot(Vector3T(xi[0], xi[1], T(z_)));
    Vector3T e;
    e.template head<2>() = basis_.transpose().template cast<T>() * (n_b - n_a);
    e(2) = d_b - d_a[0];
    Eigen::Map<Vector3T> r(residual);
    r = sqrt_information_.template cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& a_normal, double z,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<SurfaceMatchCost, 3, 3, 3, 1, 3, 1>(
        new SurfaceMatchCost(a_normal, z, sqrt_information));
  }

  const Eigen::Matrix<double, 3, 2>& tangent_basis() const { return basis_; }

 private:
  double z_;
  Eigen::Matrix3d sqrt_information_;
  Eigen::Matrix<double, 3, 2> basis_;
};

}  // namespace merging
}  // namespace is_graphs
