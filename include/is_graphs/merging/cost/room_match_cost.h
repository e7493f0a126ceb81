#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace merging {

/// A matched pair of rooms: the S-room centre ρ (x, y in M), moved into B by the gravity-aligned
/// B_x_M = (x, y, yaw), equals the A-room centre α (in B) in the horizontal plane:
///
///   residual (2) = (R_2(yaw) ρ + (x, y) − (α_x, α_y)) / σ
///
/// Parameter blocks:
///   ξ  B_x_M (3): x, y, yaw
///   ρ  S-room centre (2)
///   α  A-room centre (3); its height is not used (rooms' heights differ between the graphs)
class RoomMatchCost {
 public:
  explicit RoomMatchCost(double sigma) : inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const xi, const T* const rho, const T* const alpha, T* residual) const {
    using std::cos;
    using std::sin;
    const T c = cos(xi[2]), s = sin(xi[2]);
    residual[0] = (c * rho[0] - s * rho[1] + xi[0] - alpha[0]) * T(inv_sigma_);
    residual[1] = (s * rho[0] + c * rho[1] + xi[1] - alpha[1]) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(double sigma) {
    return new ceres::AutoDiffCostFunction<RoomMatchCost, 2, 3, 2, 3>(new RoomMatchCost(sigma));
  }

 private:
  double inv_sigma_;
};

}  // namespace merging
}  // namespace is_graphs
