#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <memory>

#include "cost_test_util.h"
#include "is_graphs/agraph/cost/wall_centre_cost.h"

namespace is_graphs {
namespace agraph {
namespace {

using Eigen::Vector3d;

struct XWall {
  // Faces x = 4.1 (+x) and x = 3.9 (−x), w_s = (4.3, 2, 0.5): the centre is (4, 2, 0.5).
  Vector3d n_a{Vector3d::UnitX()};
  double d_a{4.1};
  Vector3d n_b{-Vector3d::UnitX()};
  double d_b{-3.9};
  Vector3d w_s{4.3, 2.0, 0.5};
};

TEST(WallCentreCost, ZeroAtTheWallCentre) {
  const XWall wall;
  std::unique_ptr<ceres::CostFunction> cost(
      WallCentreCost::Create(wall.w_s, Eigen::Matrix3d::Identity()));
  const Vector3d centre(4.0, 2.0, 0.5);
  const Eigen::VectorXd r = testing::Residual(
      *cost, {centre.data(), wall.n_a.data(), &wall.d_a, wall.n_b.data(), &wall.d_b});
  EXPECT_LT(r.norm(), 1e-12);
}

TEST(WallCentreCost, WeightedOffset) {
  const XWall wall;
  const Eigen::Matrix3d sqrt_info = Eigen::Vector3d(10.0, 20.0, 5.0).asDiagonal();
  std::unique_ptr<ceres::CostFunction> cost(WallCentreCost::Create(wall.w_s, sqrt_info));
  const Vector3d centre(4.2, 1.9, 0.5);  // 0.2 m off in x, −0.1 m in y
  const Eigen::VectorXd r = testing::Residual(
      *cost, {centre.data(), wall.n_a.data(), &wall.d_a, wall.n_b.data(), &wall.d_b});
  EXPECT_NEAR(r[0], 2.0, 1e-12);
  EXPECT_NEAR(r[1], -2.0, 1e-12);
  EXPECT_NEAR(r[2], 0.0, 1e-12);
}

TEST(WallCentreCost, MovingOneFaceMovesTheCentreByHalf) {
  XWall wall;
  wall.d_a = 4.3;  // face a moved out by 0.2: the expected centre moves by 0.1 to x = 4.1
  std::unique_ptr<ceres::CostFunction> cost(
      WallCentreCost::Create(wall.w_s, Eigen::Matrix3d::Identity()));
  const Vector3d centre(4.0, 2.0, 0.5);
  const Eigen::VectorXd r = testing::Residual(
      *cost, {centre.data(), wall.n_a.data(), &wall.d_a, wall.n_b.data(), &wall.d_b});
  EXPECT_NEAR(r[0], -0.1, 1e-12);
  EXPECT_NEAR(r[1], 0.0, 1e-12);
}

TEST(WallCentreCost, JacobiansMatchNumericDifferentiation) {
  const Vector3d n_a = Vector3d(0.9, 0.3, 0.1).normalized();
  const Vector3d n_b = -Vector3d(1.0, 0.2, -0.1).normalized();
  const double d_a = 1.3, d_b = -1.1;
  const Vector3d w_s(1.2, -0.7, 0.4), centre(1.25, -0.6, 0.35);
  Eigen::Matrix3d sqrt_info;
  sqrt_info << 5, 1, 0, 0, 4, 0.5, 0, 0, 3;
  std::unique_ptr<ceres::CostFunction> autodiff(WallCentreCost::Create(w_s, sqrt_info));
  ceres::NumericDiffCostFunction<WallCentreCost, ceres::CENTRAL, 3, 3, 3, 1, 3, 1> numeric(
      new WallCentreCost(w_s, sqrt_info));
  testing::ExpectSameEvaluation(*autodiff, numeric,
                                {centre.data(), n_a.data(), &d_a, n_b.data(), &d_b});
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
