#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "is_graphs/geometry/plane.h"

namespace is_graphs {
namespace sgraph {

/// A keyframe's observation of a mapped plane. The plane (n, d) in M, brought into the
/// keyframe's frame by its pose (R, t) (map <- base_link):
///
///   n_k = Rᵀ n,  d_k = d − n·t
///
/// is compared with the measured local plane (n_m, d_m) on its minimal tangent:
///
///   residual (3) = Σ^{-1/2} [ Bᵀ n_k ; d_k − d_m ]
///
/// with B the 3x2 tangent basis at n_m (sgraph::TangentBasis, the basis of
/// PlaneObservation::information).
///
/// Parameter blocks:
///   t  keyframe position (3)
///   q  keyframe orientation (4), Eigen order (x, y, z, w)
///   n  plane unit normal (3), on ceres::SphereManifold<3>
///   d  plane offset (1)
class KeyframePlaneCost {
 public:
  KeyframePlaneCost(const geometry::Plane& measured, const Eigen::Matrix<double, 3, 2>& basis,
                    const Eigen::Matrix3d& sqrt_information)
      : measured_d_(measured.d), basis_(basis), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* const t, const T* const q, const T* const normal, const T* const d,
                  T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vector3T> position(t), n(normal);
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(q);
    const Vector3T n_k = rotation.conjugate() * n;
    Vector3T e;
    e.template head<2>() = basis_.transpose().template cast<T>() * n_k;
    e(2) = (d[0] - n.dot(position)) - T(measured_d_);
    Eigen::Map<Vector3T> r(residual);
    r = sqrt_information_.template cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* Create(const geometry::Plane& measured,
                                     const Eigen::Matrix<double, 3, 2>& basis,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<KeyframePlaneCost, 3, 3, 4, 3, 1>(
        new KeyframePlaneCost(measured, basis, sqrt_information));
  }

 private:
  double measured_d_;
  Eigen::Matrix<double, 3, 2> basis_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace sgraph
}  // namespace is_graphs
