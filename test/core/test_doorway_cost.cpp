#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <memory>

#include "cost_test_util.h"
#include "is_graphs/agraph/cost/doorway_cost.h"

namespace is_graphs {
namespace agraph {
namespace {

using Eigen::Vector3d;

// The door of test/data/two_rooms.agraph.json: doorway (4, 2, 0), room A centre (1.95, 2, 1.4).
const Vector3d kDoorway(4.0, 2.0, 0.0);
const Vector3d kRoom(1.95, 2.0, 1.4);
const Vector3d kOffset(-2.05, 0.0, 1.4);  // room − doorway

TEST(DoorwayRoomCost, ZeroAtTheMeasuredOffset) {
  std::unique_ptr<ceres::CostFunction> cost(
      DoorwayRoomCost::Create(kOffset, Eigen::Matrix3d::Identity()));
  EXPECT_LT(testing::Residual(*cost, {kDoorway.data(), kRoom.data()}).norm(), 1e-12);
}

TEST(DoorwayRoomCost, WeightedResidual) {
  std::unique_ptr<ceres::CostFunction> cost(
      DoorwayRoomCost::Create(kOffset, Eigen::Matrix3d::Identity() / 0.05));
  const Vector3d room = kRoom + Vector3d(0.1, 0.0, 0.0);
  Eigen::VectorXd r = testing::Residual(*cost, {kDoorway.data(), room.data()});
  EXPECT_NEAR(r[0], 2.0, 1e-9);  // 0.1 / 0.05
  EXPECT_NEAR(r[1], 0.0, 1e-12);
  EXPECT_NEAR(r[2], 0.0, 1e-12);
  const Vector3d doorway = kDoorway + Vector3d(0.0, 0.1, 0.0);  // the offset shrinks in y
  r = testing::Residual(*cost, {doorway.data(), kRoom.data()});
  EXPECT_NEAR(r[0], 0.0, 1e-12);
  EXPECT_NEAR(r[1], -2.0, 1e-9);
  EXPECT_NEAR(r[2], 0.0, 1e-12);
}

TEST(DoorwayRoomCost, TranslatingBothKeepsItZero) {
  std::unique_ptr<ceres::CostFunction> cost(
      DoorwayRoomCost::Create(kOffset, Eigen::Matrix3d::Identity()));
  const Vector3d shift(0.3, -0.2, 0.1);
  const Vector3d doorway = kDoorway + shift, room = kRoom + shift;
  EXPECT_LT(testing::Residual(*cost, {doorway.data(), room.data()}).norm(), 1e-12);
}

TEST(DoorwayRoomCost, JacobiansMatchNumericDifferentiation) {
  Eigen::Matrix3d sqrt_info;
  sqrt_info << 20, 1, 0, 0, 20, 2, 0, 0, 10;
  std::unique_ptr<ceres::CostFunction> autodiff(DoorwayRoomCost::Create(kOffset, sqrt_info));
  ceres::NumericDiffCostFunction<DoorwayRoomCost, ceres::CENTRAL, 3, 3, 3> numeric(
      new DoorwayRoomCost(kOffset, sqrt_info));
  const Vector3d doorway(4.1, 1.8, 0.1), room(2.0, 2.3, 1.2);
  testing::ExpectSameEvaluation(*autodiff, numeric, {doorway.data(), room.data()});
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
