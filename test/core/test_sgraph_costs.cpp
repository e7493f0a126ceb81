#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "cost_test_util.h"
#include "is_graphs/sgraph/cost/corridor_plane_cost.h"
#include "is_graphs/sgraph/cost/floor_room_cost.h"
#include "is_graphs/sgraph/cost/keyframe_plane_cost.h"
#include "is_graphs/sgraph/cost/odometry_cost.h"
#include "is_graphs/sgraph/cost/odometry_scale_prior_cost.h"
#include "is_graphs/sgraph/cost/room_plane_cost.h"
#include "is_graphs/sgraph/plane_fit.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

Eigen::Quaterniond Yaw(double a) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(a, Vector3d::UnitZ()));
}

TEST(OdometryCost, ZeroWhenTheRelativePoseMatches) {
  Eigen::Isometry3d z = Eigen::Isometry3d::Identity();
  z.linear() = Yaw(0.3).toRotationMatrix();
  z.translation() = Vector3d(1.0, 0.2, 0.0);
  std::unique_ptr<ceres::CostFunction> cost(OdometryCost::Create(z, Matrix6d::Identity()));
  const Vector3d ti(2, 3, 0.5);
  const Eigen::Quaterniond qi = Yaw(1.0);
  const Vector3d tj = ti + qi * z.translation();
  const Eigen::Quaterniond qj = qi * Yaw(0.3);
  const double one = 1.0;
  EXPECT_LT(
      testing::Residual(*cost, {ti.data(), qi.coeffs().data(), tj.data(), qj.coeffs().data(), &one})
          .norm(),
      1e-12);
}

TEST(OdometryCost, TheScaleStretchesTheMeasuredTranslationOnly) {
  // Odometry read 1.0 m and a 0.3 rad turn; the keyframes are 1.06 m apart with that turn:
  // zero at s = 1.06, and at s = 1 the translation error is 0.06 m along the step.
  Eigen::Isometry3d z = Eigen::Isometry3d::Identity();
  z.linear() = Yaw(0.3).toRotationMatrix();
  z.translation() = Vector3d(1.0, 0.0, 0.0);
  std::unique_ptr<ceres::CostFunction> cost(OdometryCost::Create(z, Matrix6d::Identity()));
  const Vector3d ti(2, 3, 0.5);
  const Eigen::Quaterniond qi = Yaw(1.0);
  const Vector3d tj = ti + qi * Vector3d(1.06, 0.0, 0.0);
  const Eigen::Quaterniond qj = qi * Yaw(0.3);
  const double right = 1.06, unit = 1.0;
  EXPECT_LT(testing::Residual(
                *cost, {ti.data(), qi.coeffs().data(), tj.data(), qj.coeffs().data(), &right})
                .norm(),
            1e-12);
  const Eigen::VectorXd r = testing::Residual(
      *cost, {ti.data(), qi.coeffs().data(), tj.data(), qj.coeffs().data(), &unit});
  // t_E = R_Z⁻¹ (0.06, 0, 0): the error seen in the measured end frame (turned by 0.3).
  EXPECT_NEAR(r(0), 0.06 * std::cos(0.3), 1e-12);
  EXPECT_NEAR(r(1), -0.06 * std::sin(0.3), 1e-12);
  EXPECT_NEAR(r.tail<4>().norm(), 0.0, 1e-12);
}

TEST(OdometryScalePriorCost, HandComputed) {
  std::unique_ptr<ceres::CostFunction> cost(OdometryScalePriorCost::Create(0.05));
  const double s = 1.06, one = 1.0;
  EXPECT_NEAR(testing::Residual(*cost, {&s})(0), 1.2, 1e-12);
  EXPECT_NEAR(testing::Residual(*cost, {&one})(0), 0.0, 1e-15);
}

TEST(OdometryCost, HandComputedTranslationAndRotationErrors) {
  Matrix6d sqrt_info = Matrix6d::Identity();
  sqrt_info(0, 0) = 10.0;  // σ_x = 0.1 m
  std::unique_ptr<ceres::CostFunction> cost(
      OdometryCost::Create(Eigen::Isometry3d::Identity(), sqrt_info));
  const Vector3d ti(0, 0, 0), tj(0.1, 0, 0);
  const Eigen::Quaterniond qi = Eigen::Quaterniond::Identity(), qj = Yaw(0.02);
  const double one = 1.0;
  const Eigen::VectorXd r = testing::Residual(
      *cost, {ti.data(), qi.coeffs().data(), tj.data(), qj.coeffs().data(), &one});
  // t_E = 0.1 x (whitened by 10), rotation error 2 sin(0.01) about z.
  EXPECT_NEAR(r(0), 1.0, 1e-12);
  EXPECT_NEAR(r(5), 2.0 * std::sin(0.01), 1e-12);
  EXPECT_NEAR(r.segment<4>(1).norm(), 0.0, 1e-12);
}

TEST(OdometryCost, JacobiansMatchNumericDifferentiation) {
  Eigen::Isometry3d z = Eigen::Isometry3d::Identity();
  z.linear() = Yaw(0.2).toRotationMatrix();
  z.translation() = Vector3d(0.8, -0.1, 0.01);
  Eigen::Matrix<double, 6, 1> diagonal;
  diagonal << 10, 20, 30, 40, 50, 60;  // (Eigen 3.3 has no six-argument constructor)
  const Matrix6d s = diagonal.asDiagonal();
  std::unique_ptr<ceres::CostFunction> autodiff(OdometryCost::Create(z, s));
  ceres::NumericDiffCostFunction<OdometryCost, ceres::CENTRAL, 6, 3, 4, 3, 4, 1> numeric(
      new OdometryCost(z, s));
  const double scale = 0.97;
  const Vector3d ti(1, 2, 0.5), tj(1.7, 2.3, 0.52);
  const Eigen::Quaterniond qi = Yaw(0.4), qj = Yaw(0.65) * Eigen::Quaterniond(Eigen::AngleAxisd(
                                                               0.01, Vector3d::UnitX()));
  testing::ExpectSameEvaluation(
      *autodiff, numeric, {ti.data(), qi.coeffs().data(), tj.data(), qj.coeffs().data(), &scale},
      1e-6);
}

TEST(KeyframePlaneCost, HandComputedOffsetAndRotation) {
  // Map plane x = 3 (normal +x); keyframe at (1, 0, 0): locally x = 2.
  const geometry::Plane measured(Vector3d::UnitX(), 2.0);
  const Eigen::Matrix3d s = Vector3d(100, 100, 10).asDiagonal();
  std::unique_ptr<ceres::CostFunction> cost(
      KeyframePlaneCost::Create(measured, TangentBasis(measured.normal), s));
  const Vector3d t(1, 0, 0), n = Vector3d::UnitX();
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  double d = 3.0;
  EXPECT_LT(testing::Residual(*cost, {t.data(), q.coeffs().data(), n.data(), &d}).norm(), 1e-12);
  d = 3.1;  // 10 cm further: whitened by 10
  EXPECT_NEAR(testing::Residual(*cost, {t.data(), q.coeffs().data(), n.data(), &d})(2), 1.0, 1e-12);
  // The keyframe turned by 0.01 rad: the local normal turns by −0.01; |Bᵀ n_k| = sin 0.01.
  d = 3.0;
  const Eigen::Quaterniond turned = Yaw(0.01);
  const Eigen::VectorXd r =
      testing::Residual(*cost, {t.data(), turned.coeffs().data(), n.data(), &d});
  EXPECT_NEAR(r.head<2>().norm(), 100.0 * std::sin(0.01), 1e-9);
  EXPECT_NEAR(r(2), 0.0, 1e-12);
}

TEST(KeyframePlaneCost, JacobiansMatchNumericDifferentiation) {
  const geometry::Plane measured(Vector3d(0.6, 0.8, 0.0), -1.5);
  const Eigen::Matrix3d s = Vector3d(30, 40, 20).asDiagonal();
  const auto basis = TangentBasis(measured.normal);
  std::unique_ptr<ceres::CostFunction> autodiff(KeyframePlaneCost::Create(measured, basis, s));
  ceres::NumericDiffCostFunction<KeyframePlaneCost, ceres::CENTRAL, 3, 3, 4, 3, 1> numeric(
      new KeyframePlaneCost(measured, basis, s));
  const Vector3d t(0.5, -1, 0.5), n = Vector3d(0.5, 0.86, 0.02).normalized();
  const Eigen::Quaterniond q = Yaw(0.1);
  const double d = -1.0;
  testing::ExpectSameEvaluation(*autodiff, numeric, {t.data(), q.coeffs().data(), n.data(), &d},
                                1e-6);
}

TEST(RoomPlaneCost, HandComputed) {
  std::unique_ptr<ceres::CostFunction> cost(RoomPlaneCost::Create(1.5, 0.0, 0.1));
  const Vector2d rho(1, 2);
  const Vector3d n = Vector3d::UnitX();
  const double d = -1.0;  // distance 1 − (−1) = 2, measured 1.5, σ 0.1
  EXPECT_NEAR(testing::Residual(*cost, {rho.data(), n.data(), &d})(0), 5.0, 1e-12);
  ceres::NumericDiffCostFunction<RoomPlaneCost, ceres::CENTRAL, 1, 2, 3, 1> numeric(
      new RoomPlaneCost(1.5, 0.3, 0.1));
  std::unique_ptr<ceres::CostFunction> autodiff(RoomPlaneCost::Create(1.5, 0.3, 0.1));
  const Vector3d n2 = Vector3d(0.6, -0.8, 0.01).normalized();
  testing::ExpectSameEvaluation(*autodiff, numeric, {rho.data(), n2.data(), &d});
}

TEST(CorridorPlaneCost, HandComputedAcrossAndAlong) {
  // Wall y = 0 facing +y; centre measured 1 m in front; axis x, found at x = 0.
  std::unique_ptr<ceres::CostFunction> cost(
      CorridorPlaneCost::Create(1.0, 0.0, Vector2d::UnitX(), Vector2d(0, 1), 0.1, 2.0));
  const Vector2d rho(3.0, 1.2);
  const Vector3d n = Vector3d::UnitY();
  const double d = 0.0;
  const Eigen::VectorXd r = testing::Residual(*cost, {rho.data(), n.data(), &d});
  EXPECT_NEAR(r(0), 2.0, 1e-12);  // 0.2 / 0.1
  EXPECT_NEAR(r(1), 1.5, 1e-12);  // 3 / 2
  ceres::NumericDiffCostFunction<CorridorPlaneCost, ceres::CENTRAL, 2, 2, 3, 1> numeric(
      new CorridorPlaneCost(1.0, 0.0, Vector2d::UnitX(), Vector2d(0, 1), 0.1, 2.0));
  testing::ExpectSameEvaluation(*cost, numeric, {rho.data(), n.data(), &d});
}

TEST(FloorRoomCost, HandComputed) {
  std::unique_ptr<ceres::CostFunction> cost(FloorRoomCost::Create(Vector2d(1.0, 0.5), 0.5));
  const Vector2d f(0, 0), rho(1, 1);
  const Eigen::VectorXd r = testing::Residual(*cost, {f.data(), rho.data()});
  EXPECT_NEAR(r(0), 0.0, 1e-12);
  EXPECT_NEAR(r(1), 1.0, 1e-12);
  ceres::NumericDiffCostFunction<FloorRoomCost, ceres::CENTRAL, 2, 2, 2> numeric(
      new FloorRoomCost(Vector2d(1.0, 0.5), 0.5));
  testing::ExpectSameEvaluation(*cost, numeric, {f.data(), rho.data()});
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
