#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "cost_test_util.h"
#include "is_graphs/agraph/cost/plane_prior_cost.h"

namespace is_graphs {
namespace agraph {
namespace {

using Eigen::Vector3d;

const Eigen::Matrix3d kSqrtInfo = Vector3d(1.0 / 0.01, 1.0 / 0.01, 1.0 / 0.05).asDiagonal();

TEST(PlanePriorCost, TangentBasisIsOrthonormalAndTangent) {
  for (const Vector3d& n :
       {Vector3d(1.0, 0.0, 0.0), Vector3d(-0.6, 0.8, 0.0), Vector3d(0.0, 0.0, 1.0)}) {
    const PlanePriorCost cost(geometry::Plane(n, 1.0), kSqrtInfo);
    const Eigen::Matrix<double, 3, 2>& b = cost.tangent_basis();
    EXPECT_LT((b.transpose() * b - Eigen::Matrix2d::Identity()).norm(), 1e-12);
    EXPECT_LT((b.transpose() * n).norm(), 1e-12);
  }
}

TEST(PlanePriorCost, ZeroAtTheMeasurement) {
  const geometry::Plane measured(Vector3d::UnitX(), 2.0);
  std::unique_ptr<ceres::CostFunction> cost(PlanePriorCost::Create(measured, kSqrtInfo));
  const double d = 2.0;
  EXPECT_LT(testing::Residual(*cost, {measured.normal.data(), &d}).norm(), 1e-12);
}

TEST(PlanePriorCost, RotatedAndShiftedPlane) {
  const geometry::Plane measured(Vector3d::UnitX(), 2.0);
  std::unique_ptr<ceres::CostFunction> cost(PlanePriorCost::Create(measured, kSqrtInfo));
  // Normal rotated by 0.01 rad about z, offset 0.1 m further.
  const Vector3d n(std::cos(0.01), std::sin(0.01), 0.0);
  const double d = 2.1;
  const Eigen::VectorXd r = testing::Residual(*cost, {n.data(), &d});
  // The tangent part is sin(0.01) / 0.01 in length, whatever the basis; the offset 0.1 / 0.05.
  EXPECT_NEAR(r.head<2>().norm(), 0.99998333341666645, 1e-12);
  EXPECT_NEAR(r[2], 2.0, 1e-9);
}

TEST(PlanePriorCost, TiltIsSeenToo) {
  const geometry::Plane measured(Vector3d::UnitY(), 0.0);  // through the origin
  std::unique_ptr<ceres::CostFunction> cost(
      PlanePriorCost::Create(measured, Eigen::Matrix3d::Identity()));
  const Vector3d n(0.0, std::cos(0.2), std::sin(0.2));  // tilted 0.2 rad towards z
  const double d = 0.0;
  const Eigen::VectorXd r = testing::Residual(*cost, {n.data(), &d});
  EXPECT_NEAR(r.head<2>().norm(), std::sin(0.2), 1e-12);
  EXPECT_NEAR(r[2], 0.0, 1e-12);
}

TEST(PlanePriorCost, JacobiansMatchNumericDifferentiation) {
  const geometry::Plane measured(Vector3d(0.8, -0.6, 0.0), -1.5);
  Eigen::Matrix3d sqrt_info = kSqrtInfo;
  sqrt_info(0, 2) = 3.0;
  std::unique_ptr<ceres::CostFunction> autodiff(PlanePriorCost::Create(measured, sqrt_info));
  ceres::NumericDiffCostFunction<PlanePriorCost, ceres::CENTRAL, 3, 3, 1> numeric(
      new PlanePriorCost(measured, sqrt_info));
  const Vector3d n = Vector3d(0.79, -0.62, 0.05).normalized();
  const double d = -1.45;
  testing::ExpectSameEvaluation(*autodiff, numeric, {n.data(), &d}, 1e-6);
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
