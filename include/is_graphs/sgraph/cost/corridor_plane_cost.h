#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

namespace is_graphs {
namespace sgraph {

/// Ties a two-wall corridor's centre to one of its walls. Across the corridor, as a room wall
/// (the signed distance from the centre to the wall stays at m); along it, where the walls
/// say nothing, a weak pull to where the centre was found (ρ₀, along the axis a):
///
///   residual (2) = [ ((n·(ρx, ρy, z) − d) − m) / σ ;  a·(ρ − ρ₀) / σ_along ]
///
/// Parameter blocks:
///   ρ  corridor centre (2), x and y in M
///   n  plane unit normal (3)
///   d  plane offset (1)
class CorridorPlaneCost {
 public:
  CorridorPlaneCost(double measured_distance, double z, const Eigen::Vector2d& axis,
                    const Eigen::Vector2d& initial_center, double sigma, double sigma_along)
      : measured_(measured_distance),
        z_(z),
        axis_(axis.normalized()),
        initial_center_(initial_center),
        inv_sigma_(1.0 / sigma),
        inv_sigma_along_(1.0 / sigma_along) {}

  template <typename T>
  bool operator()(const T* const rho, const T* const n, const T* const d, T* residual) const {
    const T distance = n[0] * rho[0] + n[1] * rho[1] + n[2] * T(z_) - d[0];
    residual[0] = (distance - T(measured_)) * T(inv_sigma_);
    residual[1] = (T(axis_.x()) * (rho[0] - T(initial_center_.x())) +
                   T(axis_.y()) * (rho[1] - T(initial_center_.y()))) *
                  T(inv_sigma_along_);
    return true;
  }

  static ceres::CostFunction* Create(double measured_distance, double z,
                                     const Eigen::Vector2d& axis,
                                     const Eigen::Vector2d& initial_center, double sigma,
                                     double sigma_along) {
    return new ceres::AutoDiffCostFunction<CorridorPlaneCost, 2, 2, 3, 1>(
        new CorridorPlaneCost(measured_distance, z, axis, initial_center, sigma, sigma_along));
  }

 private:
  double measured_;
  double z_;
  Eigen::Vector2d axis_;
  Eigen::Vector2d initial_center_;
  double inv_sigma_;
  double inv_sigma_along_;
};

}  // namespace sgraph
}  // namespace is_graphs
