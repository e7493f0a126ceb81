#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <memory>

#include "cost_test_util.h"
#include "is_graphs/agraph/cost/point_prior_cost.h"

namespace is_graphs {
namespace agraph {
namespace {

using Eigen::Vector3d;

TEST(PointPriorCost, WeightedDifference) {
  const Vector3d measured(6.05, 2.0, 1.4);
  std::unique_ptr<ceres::CostFunction> cost(
      PointPriorCost::Create(measured, Vector3d(20.0, 10.0, 1.0).asDiagonal()));
  const Vector3d p(6.10, 1.9, 1.4);
  const Eigen::VectorXd r = testing::Residual(*cost, {p.data()});
  EXPECT_NEAR(r[0], 1.0, 1e-9);   // 0.05 · 20
  EXPECT_NEAR(r[1], -1.0, 1e-9);  // −0.1 · 10
  EXPECT_NEAR(r[2], 0.0, 1e-12);
  EXPECT_LT(testing::Residual(*cost, {measured.data()}).norm(), 1e-12);
}

TEST(PointPriorCost, JacobiansMatchNumericDifferentiation) {
  Eigen::Matrix3d sqrt_info;
  sqrt_info << 3, 1, 0, 0, 2, 1, 1, 0, 4;
  const Vector3d measured(1.0, 2.0, 3.0), p(1.5, 1.0, 2.0);
  std::unique_ptr<ceres::CostFunction> autodiff(PointPriorCost::Create(measured, sqrt_info));
  ceres::NumericDiffCostFunction<PointPriorCost, ceres::CENTRAL, 3, 3> numeric(
      new PointPriorCost(measured, sqrt_info));
  testing::ExpectSameEvaluation(*autodiff, numeric, {p.data()});
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
