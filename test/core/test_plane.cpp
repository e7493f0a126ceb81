#include <gtest/gtest.h>

#include "is_graphs/geometry/plane.h"
#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace geometry {
namespace {

TEST(Plane, ConstructorNormalizes) {
  // 2x = 6 is the plane x = 3.
  const Plane plane(Eigen::Vector3d(2.0, 0.0, 0.0), 6.0);
  EXPECT_NEAR((plane.normal - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(plane.d, 3.0);
}

TEST(Plane, ClosestPointRoundTrip) {
  const Eigen::Vector3d pi(1.0, -2.0, 2.0);  // |Π| = 3
  const Plane plane = Plane::FromClosestPoint(pi);
  EXPECT_DOUBLE_EQ(plane.d, 3.0);
  EXPECT_NEAR((plane.normal - Eigen::Vector3d(1.0, -2.0, 2.0) / 3.0).norm(), 0.0, 1e-12);
  EXPECT_NEAR((plane.ClosestPoint() - pi).norm(), 0.0, 1e-12);
  EXPECT_NEAR(plane.SignedDistance(pi), 0.0, 1e-12);
}

TEST(Plane, ZeroOffsetKeepsTheNormal) {
  // Through the origin: Π = 0 loses the normal, the (normal, d) pair does not.
  const Plane plane = Plane::FromPointNormal(Eigen::Vector3d(0.0, 5.0, 1.0),
                                             Eigen::Vector3d(0, 0, 0) + Eigen::Vector3d::UnitX());
  EXPECT_DOUBLE_EQ(plane.d, 0.0);
  EXPECT_TRUE(plane.ClosestPoint().isZero());
  EXPECT_NEAR((plane.normal - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);
  // From Π = 0 alone only the default plane can be returned.
  const Plane lost = Plane::FromClosestPoint(Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(lost.d, 0.0);
  EXPECT_TRUE(lost.normal.allFinite());
}

TEST(Plane, SignedDistanceAndProjection) {
  const Plane plane(Eigen::Vector3d::UnitY(), 2.0);  // y = 2
  EXPECT_DOUBLE_EQ(plane.SignedDistance(Eigen::Vector3d(7.0, 5.0, 1.0)), 3.0);
  EXPECT_NEAR((plane.Project(Eigen::Vector3d(7.0, 5.0, 1.0)) - Eigen::Vector3d(7, 2, 1)).norm(),
              0.0, 1e-12);
  const Plane flipped = plane.Flipped();
  EXPECT_DOUBLE_EQ(flipped.d, -2.0);
  EXPECT_DOUBLE_EQ(flipped.SignedDistance(Eigen::Vector3d(7.0, 5.0, 1.0)), -3.0);
}

TEST(Plane, Transformed) {
  // Plane x = 1 in A; B = A rotated by +90° about z, then shifted by (10, 0, 0).
  const Plane plane_a(Eigen::Vector3d::UnitX(), 1.0);
  const Eigen::Isometry3d b_T_a = IsometryFromXYYaw(10.0, 0.0, M_PI / 2.0);
  const Plane plane_b = plane_a.Transformed(b_T_a);
  // x̂ maps to ŷ; the point (1, 0, 0) maps to (10, 1, 0): the plane y = 1.
  EXPECT_NEAR((plane_b.normal - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(plane_b.d, 1.0, 1e-12);
  // Any point of the plane in A maps onto the plane in B.
  const Eigen::Vector3d p_a(1.0, -4.0, 2.5);
  EXPECT_NEAR(plane_b.SignedDistance(b_T_a * p_a), 0.0, 1e-12);
  // And back.
  const Plane back = plane_b.Transformed(b_T_a.inverse());
  EXPECT_NEAR((back.normal - plane_a.normal).norm(), 0.0, 1e-12);
  EXPECT_NEAR(back.d, plane_a.d, 1e-12);
}

TEST(Plane, TransformedThroughOrigin) {
  const Plane plane_a(Eigen::Vector3d::UnitY(), 0.0);  // y = 0
  const Plane plane_b = plane_a.Transformed(IsometryFromXYYaw(0.0, 3.0, 0.0));
  EXPECT_NEAR(plane_b.d, 3.0, 1e-12);  // y = 3
  EXPECT_NEAR((plane_b.normal - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
}

TEST(Plane, ClassifyOrientation) {
  EXPECT_EQ(ClassifyOrientation(Eigen::Vector3d(-1, 0, 0)), Orientation::kX);
  EXPECT_EQ(ClassifyOrientation(Eigen::Vector3d(0, 2, 0)), Orientation::kY);
  EXPECT_EQ(ClassifyOrientation(Eigen::Vector3d(0, 0, -1)), Orientation::kHorizontal);
  const double a = 30.0 * M_PI / 180.0;
  EXPECT_EQ(ClassifyOrientation(Eigen::Vector3d(std::cos(a), std::sin(a), 0)), Orientation::kOther);
  const double b = 9.0 * M_PI / 180.0;  // within the 10° tolerance
  EXPECT_EQ(ClassifyOrientation(Eigen::Vector3d(std::cos(b), std::sin(b), 0)), Orientation::kX);
  EXPECT_EQ(ClassifyOrientation(Eigen::Vector3d(std::sin(b), -std::cos(b), 0)), Orientation::kY);
}

TEST(Plane, OrientationStrings) {
  EXPECT_STREQ(ToString(Orientation::kX), "x");
  EXPECT_STREQ(ToString(Orientation::kOther), "other");
  for (Orientation o :
       {Orientation::kX, Orientation::kY, Orientation::kOther, Orientation::kHorizontal}) {
    EXPECT_EQ(OrientationFromString(ToString(o)), o);
  }
  EXPECT_FALSE(OrientationFromString("z").has_value());
}

TEST(Se3, YawHelpers) {
  const Eigen::Isometry3d pose = IsometryFromXYYaw(1.0, 2.0, 0.5, 3.0);
  EXPECT_NEAR(Yaw(pose), 0.5, 1e-12);
  const Eigen::Vector3d xy_yaw = ToXYYaw(pose);
  EXPECT_NEAR((xy_yaw - Eigen::Vector3d(1.0, 2.0, 0.5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(NormalizeAngle(3.0 * M_PI / 2.0), -M_PI / 2.0, 1e-12);
  EXPECT_NEAR(NormalizeAngle(-3.0 * M_PI / 2.0), M_PI / 2.0, 1e-12);
  const Eigen::Vector3d p =
      TransformPointXYYaw(1.0, 2.0, 3.0, M_PI / 2.0, Eigen::Vector3d(1, 0, 0));
  EXPECT_NEAR((p - Eigen::Vector3d(1.0, 3.0, 3.0)).norm(), 0.0, 1e-12);
  // Roll and pitch are dropped, yaw kept.
  Eigen::Isometry3d tilted = pose;
  tilted.linear() = pose.linear() * Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()).matrix();
  EXPECT_NEAR(Yaw(ProjectToYawOnly(tilted)), 0.5, 1e-12);
}

}  // namespace
}  // namespace geometry
}  // namespace is_graphs
