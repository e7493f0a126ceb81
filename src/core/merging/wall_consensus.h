#pragma once

// Private to wall_deviations.cpp: the small motion of B_x_M that puts the seen walls back on the
// plan by consensus (a robust prior that plans are mostly right).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace is_graphs {
namespace merging {
namespace detail {

/// An A-surface's S-plane: `offset` (m) along the A-normal `normal` at `at` (the surface's
/// middle), turned `angle` (rad); `weight` its share (overlap length, m).
struct SeenSurface {
  Eigen::Vector2d normal;
  Eigen::Vector2d at;
  double offset{0.0}, angle{0.0}, weight{1.0};
};

/// The correction C (in B: about z, then along x-y) that minimises the Cauchy-robust sum over
/// the surfaces of ((offset after C) / offset_scale)^2 + ((angle after C) / angle_scale)^2, by
/// iteratively reweighted least squares from C = identity, damped towards it (a direction the
/// surfaces do not fix stays). Deterministic. Apply to the S-Graph placed in B: C * bim_T_map.
Eigen::Isometry3d ConsensusCorrection(const std::vector<SeenSurface>& surfaces, double offset_scale,
                                      double angle_scale);

}  // namespace detail
}  // namespace merging
}  // namespace is_graphs
