#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

namespace is_graphs {
namespace merging {

/// A matched S-corridor (two opposed walls) and A-room: only the component across the corridor
/// counts, as the corridor's centre is free along its axis. With u the unit direction across
/// the corridor in M (a wall's horizontal normal):
///
///   residual (1) = (R_2(yaw) u) · (R_2(yaw) ρ + (x, y) − (α_x, α_y)) / σ
///
/// Parameter blocks:
///   ξ  B_x_M (3): x, y, yaw
///   ρ  S-corridor centre (2)
///   α  A-room centre (3)
class CorridorMatchCost {
 public:
  CorridorMatchCost(const Eigen::Vector2d& across, double sigma)
      : across_(across.normalized()), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const xi, const T* const rho, const T* const alpha, T* residual) const {
    using std::cos;
    using std::sin;
    const T c = cos(xi[2]), s = sin(xi[2]);
    const T ux = c * T(across_.x()) - s * T(across_.y());
    const T uy = s * T(across_.x()) + c * T(across_.y());
    const T ex = c * rho[0] - s * rho[1] + xi[0] - alpha[0];
    const T ey = s * rho[0] + c * rho[1] + xi[1] - alpha[1];
    residual[0] = (ux * ex + uy * ey) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector2d& across, double sigma) {
    return new ceres::AutoDiffCostFunction<CorridorMatchCost, 1, 3, 2, 3>(
        new CorridorMatchCost(across, sigma));
  }

 private:
  Eigen::Vector2d across_;
  double inv_sigma_;
};

}  // namespace merging
}  // namespace is_graphs
