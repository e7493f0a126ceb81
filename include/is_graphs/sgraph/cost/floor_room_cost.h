#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

namespace is_graphs {
namespace sgraph {

/// Ties a room (or corridor) centre to the floor centre: their offset stays at its measured
/// value m:
///
///   residual (2) = ((ρ − f) − m) / σ
///
/// Parameter blocks:
///   f  floor centre (2), x and y in M
///   ρ  room centre (2)
class FloorRoomCost {
 public:
  FloorRoomCost(const Eigen::Vector2d& measured_offset, double sigma)
      : measured_(measured_offset), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const f, const T* const rho, T* residual) const {
    residual[0] = ((rho[0] - f[0]) - T(measured_.x())) * T(inv_sigma_);
    residual[1] = ((rho[1] - f[1]) - T(measured_.y())) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector2d& measured_offset, double sigma) {
    return new ceres::AutoDiffCostFunction<FloorRoomCost, 2, 2, 2>(
        new FloorRoomCost(measured_offset, sigma));
  }

 private:
  Eigen::Vector2d measured_;
  double inv_sigma_;
};

}  // namespace sgraph
}  // namespace is_graphs
