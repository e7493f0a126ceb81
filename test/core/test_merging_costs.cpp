// The merger's cost functors: residuals on hand-computed values, autodiff vs numeric Jacobians.
#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "cost_test_util.h"
#include "is_graphs/geometry/plane.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/cost/corridor_match_cost.h"
#include "is_graphs/merging/cost/room_match_cost.h"
#include "is_graphs/merging/cost/surface_match_cost.h"
#include "is_graphs/merging/cost/transform_prior_cost.h"

namespace is_graphs {
namespace merging {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
constexpr double kDeg = M_PI / 180.0;

TEST(SurfaceMatchCost, ZeroWhenTheMovedPlaneIsTheASurface) {
  const Vector3d xi(2.0, -1.0, 30.0 * kDeg);
  const double z = 0.4;
  const geometry::Plane s_plane(Vector3d(1, 0, 0), 3.0);  // x = 3 in M
  const geometry::Plane a_plane =
      s_plane.Transformed(geometry::IsometryFromXYYaw(xi.x(), xi.y(), xi.z(), z));
  std::unique_ptr<ceres::CostFunction> cost(
      SurfaceMatchCost::Create(a_plane.normal, z, Eigen::Matrix3d::Identity()));
  const double ds = s_plane.d, da = a_plane.d;
  const Vector3d ns = s_plane.normal, na = a_plane.normal;
  EXPECT_LT(testing::Residual(*cost, {xi.data(), ns.data(), &ds, na.data(), &da}).norm(), 1e-12);
}

TEST(SurfaceMatchCost, HandComputedOffsetAndAngle) {
  // Identity transform except x = 0.1: the plane x = 3 (normal +x) moves to x = 3.1.
  const Vector3d xi(0.1, 0.0, 0.0);
  const Vector3d n(1, 0, 0);
  const double ds = 3.0, da = 3.0;
  std::unique_ptr<ceres::CostFunction> cost(
      SurfaceMatchCost::Create(n, 0.0, Eigen::Vector3d(1.0, 1.0, 1.0 / 0.05).asDiagonal()));
  Eigen::VectorXd r = testing::Residual(*cost, {xi.data(), n.data(), &ds, n.data(), &da});
  EXPECT_NEAR(r(2), 0.1 / 0.05, 1e-12);  // 10 cm at σ 5 cm: 2σ
  EXPECT_NEAR(r.head<2>().norm(), 0.0, 1e-12);
  // A yaw of 1° rotates the normal by 1°: the tangent residual is sin(1°); with d the
  // offset along the rotated normal of the translation (zero here).
  const Vector3d xi_yaw(0.0, 0.0, 1.0 * kDeg);
  r = testing::Residual(*cost, {xi_yaw.data(), n.data(), &ds, n.data(), &da});
  EXPECT_NEAR(r.head<2>().norm(), std::sin(1.0 * kDeg), 1e-12);
  EXPECT_NEAR(r(2), 0.0, 1e-12);
}

TEST(SurfaceMatchCost, AutodiffMatchesNumericJacobian) {
  const Vector3d an = Vector3d(0.6, 0.8, 0.02).normalized();
  const Eigen::Matrix3d sqrt_info = Eigen::Vector3d(50, 40, 20).asDiagonal();
  std::unique_ptr<ceres::CostFunction> autodiff(SurfaceMatchCost::Create(an, 0.3, sqrt_info));
  ceres::NumericDiffCostFunction<SurfaceMatchCost, ceres::CENTRAL, 3, 3, 3, 1, 3, 1> numeric(
      new SurfaceMatchCost(an, 0.3, sqrt_info));
  const Vector3d xi(1.2, -0.7, 0.4);
  const Vector3d ns = Vector3d(0.2, 0.95, 0.01).normalized(), na = an;
  const double ds = 2.1, da = 3.3;
  testing::ExpectSameEvaluation(*autodiff, numeric, {xi.data(), ns.data(), &ds, na.data(), &da},
                                1e-6);
}

TEST(RoomMatchCost, HandComputed) {
  std::unique_ptr<ceres::CostFunction> cost(RoomMatchCost::Create(0.1));
  const Vector3d xi(1.0, 2.0, M_PI / 2);  // rotate by 90°, then translate
  const Vector2d rho(1.0, 0.0);           // -> (0, 1) + (1, 2) = (1, 3)
  Vector3d alpha(1.0, 3.0, 7.0);          // the height is not used
  EXPECT_LT(testing::Residual(*cost, {xi.data(), rho.data(), alpha.data()}).norm(), 1e-12);
  alpha = Vector3d(1.05, 2.9, 0.0);
  const Eigen::VectorXd r = testing::Residual(*cost, {xi.data(), rho.data(), alpha.data()});
  EXPECT_NEAR(r(0), -0.5, 1e-12);
  EXPECT_NEAR(r(1), 1.0, 1e-12);
}

TEST(RoomMatchCost, AutodiffMatchesNumericJacobian) {
  std::unique_ptr<ceres::CostFunction> autodiff(RoomMatchCost::Create(0.2));
  ceres::NumericDiffCostFunction<RoomMatchCost, ceres::CENTRAL, 2, 3, 2, 3> numeric(
      new RoomMatchCost(0.2));
  const Vector3d xi(0.3, -1.0, 2.0), alpha(4.0, 1.0, 1.4);
  const Vector2d rho(1.5, -2.5);
  testing::ExpectSameEvaluation(*autodiff, numeric, {xi.data(), rho.data(), alpha.data()}, 1e-6);
}

TEST(CorridorMatchCost, OnlyTheComponentAcrossCounts) {
  // A corridor along y in M (walls facing ±x), identity transform.
  std::unique_ptr<ceres::CostFunction> cost(CorridorMatchCost::Create(Vector2d(1, 0), 0.1));
  const Vector3d xi(0, 0, 0);
  const Vector2d rho(0, 0);
  Vector3d alpha(0.0, 5.0, 0.0);  // 5 m along the corridor: free
  EXPECT_NEAR(testing::Residual(*cost, {xi.data(), rho.data(), alpha.data()})(0), 0.0, 1e-12);
  alpha = Vector3d(0.2, 5.0, 0.0);  // 20 cm across: 2σ
  EXPECT_NEAR(testing::Residual(*cost, {xi.data(), rho.data(), alpha.data()})(0), -2.0, 1e-12);
  // Yawed by 90°, the across direction becomes y in B.
  const Vector3d xi_yaw(0, 0, M_PI / 2);
  alpha = Vector3d(3.0, 0.1, 0.0);
  EXPECT_NEAR(testing::Residual(*cost, {xi_yaw.data(), rho.data(), alpha.data()})(0), -1.0, 1e-12);
}

TEST(CorridorMatchCost, AutodiffMatchesNumericJacobian) {
  const Vector2d across = Vector2d(0.6, -0.8);
  std::unique_ptr<ceres::CostFunction> autodiff(CorridorMatchCost::Create(across, 0.1));
  ceres::NumericDiffCostFunction<CorridorMatchCost, ceres::CENTRAL, 1, 3, 2, 3> numeric(
      new CorridorMatchCost(across, 0.1));
  const Vector3d xi(0.3, -1.0, 2.0), alpha(4.0, 1.0, 1.4);
  const Vector2d rho(1.5, -2.5);
  testing::ExpectSameEvaluation(*autodiff, numeric, {xi.data(), rho.data(), alpha.data()}, 1e-6);
}

TEST(TransformPriorCost, HandComputedWithYawWrap) {
  std::unique_ptr<ceres::CostFunction> cost(
      TransformPriorCost::Create(Vector3d(1.0, 2.0, M_PI - 0.1), 0.5, 0.1));
  const Vector3d xi(1.5, 1.0, -M_PI + 0.1);  // 0.2 rad past the prior, across ±π
  const Eigen::VectorXd r = testing::Residual(*cost, {xi.data()});
  EXPECT_NEAR(r(0), 1.0, 1e-12);
  EXPECT_NEAR(r(1), -2.0, 1e-12);
  EXPECT_NEAR(r(2), 2.0, 1e-9);
  ceres::NumericDiffCostFunction<TransformPriorCost, ceres::CENTRAL, 3, 3> numeric(
      new TransformPriorCost(Vector3d(1.0, 2.0, M_PI - 0.1), 0.5, 0.1));
  const Vector3d xi2(1.5, 1.0, 0.3);
  testing::ExpectSameEvaluation(*cost, numeric, {xi2.data()}, 1e-6);
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
