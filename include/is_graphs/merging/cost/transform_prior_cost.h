#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace merging {

/// A weak prior on B_x_M = (x, y, yaw) at a guess (the matcher's bim_T_map) ξ₀:
///
///   residual (3) = [ (x − x₀) / σ_t ; (y − y₀) / σ_t ; wrap(yaw − yaw₀) / σ_yaw ]
///
/// Parameter blocks:
///   ξ  B_x_M (3): x, y, yaw
class TransformPriorCost {
 public:
  TransformPriorCost(const Eigen::Vector3d& prior, double sigma_translation, double sigma_yaw)
      : prior_(prior), inv_sigma_t_(1.0 / sigma_translation), inv_sigma_yaw_(1.0 / sigma_yaw) {}

  template <typename T>
  bool operator()(const T* const xi, T* residual) const {
    residual[0] = (xi[0] - T(prior_.x())) * T(inv_sigma_t_);
    residual[1] = (xi[1] - T(prior_.y())) * T(inv_sigma_t_);
    residual[2] = geometry::NormalizeAngle(xi[2] - T(prior_.z())) * T(inv_sigma_yaw_);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& prior, double sigma_translation,
                                     double sigma_yaw) {
    return new ceres::AutoDiffCostFunction<TransformPriorCost, 3, 3>(
        new TransformPriorCost(prior, sigma_translation, sigma_yaw));
  }

 private:
  Eigen::Vector3d prior_;  // x, y, yaw
  double inv_sigma_t_;
  double inv_sigma_yaw_;
};

}  // namespace merging
}  // namespace is_graphs
