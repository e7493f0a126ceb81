#pragma once

#include <ceres/autodiff_cost_function.h>

namespace is_graphs {
namespace merging {

/// The plan is mostly right: a prior at zero on an A-wall's as-built deviation (issue 21),
///
///   residual (2) = [ δ / σ_offset ; θ / σ_angle ]
///
/// SolveMerge puts it under a Cauchy loss: a wall within a few σ of the plan stays there, one
/// built 30 cm off costs only the logarithm of its distance, and its S-planes then move it
/// instead of the robot's pose. (The loss is not convex: the match must be able to pull harder
/// than the prior's steepest slope, 1 / (2σ), for a wall to leave the plan; docs/merging.md.)
///
/// Parameter block:
///   deviation (2): δ [m] along the wall's plan normal (its surface_a's) at its centre, and θ
///                  [rad] anticlockwise about z (see DeviatedSurfaceMatchCost)
class WallDeviationPriorCost {
 public:
  WallDeviationPriorCost(double offset_sigma, double angle_sigma)
      : inverse_offset_sigma_(1.0 / offset_sigma), inverse_angle_sigma_(1.0 / angle_sigma) {}

  template <typename T>
  bool operator()(const T* const deviation, T* residual) const {
    residual[0] = deviation[0] * T(inverse_offset_sigma_);
    residual[1] = deviation[1] * T(inverse_angle_sigma_);
    return true;
  }

  /// σ must be positive (MergerConfig::Validate checks them); +infinity: no prior on that part
  /// (its residual is 0; SolveMerge's walls seen turned).
  static ceres::CostFunction* Create(double offset_sigma, double angle_sigma) {
    return new ceres::AutoDiffCostFunction<WallDeviationPriorCost, 2, 2>(
        new WallDeviationPriorCost(offset_sigma, angle_sigma));
  }

 private:
  double inverse_offset_sigma_;
  double inverse_angle_sigma_;
};

}  // namespace merging
}  // namespace is_graphs
