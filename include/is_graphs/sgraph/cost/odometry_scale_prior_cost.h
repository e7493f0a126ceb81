#pragma once

#include <ceres/autodiff_cost_function.h>

namespace is_graphs {
namespace sgraph {

/// The prior that odometry measures distance right: the scale factor s of OdometryCost stays
/// near 1 unless the planes say otherwise.
///
///   residual (1) = (s − 1) / σ
///
/// Parameter blocks:
///   s  odometry scale factor (1)
class OdometryScalePriorCost {
 public:
  explicit OdometryScalePriorCost(double sigma) : inverse_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const scale, T* residual) const {
    residual[0] = (scale[0] - T(1.0)) * T(inverse_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(double sigma) {
    return new ceres::AutoDiffCostFunction<OdometryScalePriorCost, 1, 1>(
        new OdometryScalePriorCost(sigma));
  }

 private:
  double inverse_sigma_;
};

}  // namespace sgraph
}  // namespace is_graphs
