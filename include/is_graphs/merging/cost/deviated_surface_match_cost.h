#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>

#include "is_graphs/geometry/plane.h"
#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace merging {

/// SurfaceMatchCost against an A-wall-surface moved by its wall's as-built deviation (issue 21):
/// the wall turns by θ about the vertical through its centre c and shifts by δ along its plan
/// normal m (the normal of its surface_a, horizontal). The A-surface (n_a, d_a), {p : n·p = d},
/// becomes
///
///   n_a' = R_z(θ) n_a,   d_a' = d_a + (n_a' − n_a)·c + δ (n_a'·m)
///
/// (both faces of a wall move together: for its surface_b, n_a ≈ −m). The S-plane (n_s, d_s)
/// in M moved into B by B_x_M = (x, y, yaw) at the height z of M,
///
///   n_b = R_z(yaw) n_s,   d_b = d_s + n_b·(x, y, z)
///   residual (3) = Σ^{-1/2} [ Bᵀ R_z(−θ)(n_b − n_a') ; d_b − d_a' ]
///
/// B (3x2) is an orthonormal basis of the tangent plane at the planned normal; turned with the
/// wall, R_z(θ)B is the tangent basis at n_a', so the first two are the normal difference in rad.
/// With δ = θ = 0 this is SurfaceMatchCost.
///
/// Parameter blocks:
///   ξ          B_x_M (3): x, y, yaw
///   n_s        S-plane unit normal (3), on ceres::SphereManifold<3>
///   d_s        S-plane offset (1)
///   n_a        A-surface unit normal (3), on ceres::SphereManifold<3>
///   d_a        A-surface offset (1)
///   deviation  the wall's (δ [m], θ [rad]) (2)
class DeviatedSurfaceMatchCost {
 public:
  /// `a_normal`: the surface's planned normal; `wall_centre` (x, y) and `wall_normal` (x, y,
  /// unit): its wall's centre and plan normal in B; `z`: the height of M in B.
  DeviatedSurfaceMatchCost(const Eigen::Vector3d& a_normal, const Eigen::Vector2d& wall_centre,
                           const Eigen::Vector2d& wall_normal, double z,
                           const Eigen::Matrix3d& sqrt_information)
      : centre_(wall_centre.x(), wall_centre.y(), 0.0),
        wall_normal_(wall_normal.x(), wall_normal.y(), 0.0),
        z_(z),
        sqrt_information_(sqrt_information) {
    basis_ = geometry::TangentBasis(a_normal);
  }

  template <typename T>
  bool operator()(const T* const xi, const T* const normal_s, const T* const d_s,
                  const T* const normal_a, const T* const d_a, const T* const deviation,
                  T* residual) const {
    using Vector3T = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vector3T> n_s(normal_s), n_a(normal_a);
    const Eigen::Matrix<T, 3, 3> turn = geometry::RotationZ(deviation[1]);
    const Vector3T n_a_built = turn * n_a;
    const T d_a_built = d_a[0] + (n_a_built - n_a).dot(centre_.cast<T>()) +
                        deviation[0] * n_a_built.dot(wall_normal_.cast<T>());
    const Vector3T n_b = geometry::RotationZ(xi[2]) * n_s;
    const T d_b = d_s[0] + n_b.dot(Vector3T(xi[0], xi[1], T(z_)));
    Vector3T e;
    e.template head<2>() =
        basis_.transpose().template cast<T>() * (turn.transpose() * (n_b - n_a_built));
    e(2) = d_b - d_a_built;
    Eigen::Map<Vector3T> r(residual);
    r = sqrt_information_.template cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& a_normal,
                                     const Eigen::Vector2d& wall_centre,
                                     const Eigen::Vector2d& wall_normal, double z,
                                     const Eigen::Matrix3d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<DeviatedSurfaceMatchCost, 3, 3, 3, 1, 3, 1, 2>(
        new DeviatedSurfaceMatchCost(a_normal, wall_centre, wall_normal, z, sqrt_information));
  }

 private:
  Eigen::Vector3d centre_;
  Eigen::Vector3d wall_normal_;
  double z_;
  Eigen::Matrix3d sqrt_information_;
  Eigen::Matrix<double, 3, 2> basis_;
};

}  // namespace merging
}  // namespace is_graphs
