#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

namespace is_graphs {
namespace agraph {

/// Keeps a point (room centre, doorway position) near its BIM value p_m:
///
///   residual (3) = Σ^{-1/2} (p − p_m)
///
/// Parameter blocks:
///   p  the point (3)
class PointPriorCost {
 public:
  PointPriorCost(const Eigen::Vector3d& measured, const Eigen::Matrix3d& sqrt_information)
      : measured_(measured), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* const point, T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vector3T> p(point);
    Eigen::Map<Vector3T> r(residual);
    r = sqrt_information_.template cast<T>() * (p - measured_.template cast<T>());
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& measured,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<PointPriorCost, 3, 3>(
        new PointPriorCost(measured, sqrt_information));
  }

 private:
  Eigen::Vector3d measured_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace agraph
}  // namespace is_graphs
