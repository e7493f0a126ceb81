#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

namespace is_graphs {
namespace sgraph {

/// Ties a room's centre to one of its walls: the signed distance from the centre ρ (x, y, at
/// the fixed height z) to the wall stays at its measured value m (half the room's width for
/// the paper's four-wall room, the centroid's distance for a polygonal room):
///
///   residual (1) = ((n·(ρx, ρy, z) − d) − m) / σ
///
/// One term per wall of the room; an opposed pair fixes the centre on their mid-line.
///
/// Parameter blocks:
///   ρ  room centre (2), x and y in M
///   n  plane unit normal (3)
///   d  plane offset (1)
class RoomPlaneCost {
 public:
  RoomPlaneCost(double measured_distance, double z, double sigma)
      : measured_(measured_distance), z_(z), inv_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const rho, const T* const n, const T* const d, T* residual) const {
    const T distance = n[0] * rho[0] + n[1] * rho[1] + n[2] * T(z_) - d[0];
    residual[0] = (distance - T(measured_)) * T(inv_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(double measured_distance, double z, double sigma) {
    return new ceres::AutoDiffCostFunction<RoomPlaneCost, 1, 2, 3, 1>(
        new RoomPlaneCost(measured_distance, z, sigma));
  }

 private:
  double measured_;
  double z_;
  double inv_sigma_;
};

}  // namespace sgraph
}  // namespace is_graphs
