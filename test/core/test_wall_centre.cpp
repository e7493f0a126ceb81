#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/agraph/wall_centre.h"

namespace is_graphs {
namespace agraph {
namespace {

using Eigen::Vector3d;

void ExpectNear(const Vector3d& actual, const Vector3d& expected, double tolerance = 1e-12) {
  EXPECT_LT((actual - expected).norm(), tolerance)
      << "actual   " << actual.transpose() << "\nexpected " << expected.transpose();
}

TEST(WallCentre, XWall) {
  // Faces x = 4.1 (normal +x, d = 4.1) and x = 3.9 (normal −x, d = −3.9); w_s off the mid-plane.
  const Vector3d c =
      WallCentre<double>(Vector3d::UnitX(), 4.1, -Vector3d::UnitX(), -3.9, Vector3d(4.3, 2.0, 0.5));
  // q_a = (4.1, 2, 0.5), q_b = (3.9, 2, 0.5); the paper: c_x = (d_a − d_b) / 2 = 4.0.
  ExpectNear(c, Vector3d(4.0, 2.0, 0.5));
}

TEST(WallCentre, YWall) {
  const Vector3d c =
      WallCentre<double>(Vector3d::UnitY(), 1.0, -Vector3d::UnitY(), -0.8, Vector3d(3.0, 0.0, 0.0));
  ExpectNear(c, Vector3d(3.0, 0.9, 0.0));
}

TEST(WallCentre, RotatedThirtyDegrees) {
  // Mid-plane through (1, 2, 0) with normal m = (cos 30°, sin 30°, 0), thickness 0.3.
  const Vector3d m(std::sqrt(3.0) / 2.0, 0.5, 0.0);
  const Vector3d t(-0.5, std::sqrt(3.0) / 2.0, 0.0);
  const Vector3d p0(1.0, 2.0, 0.0);
  const double mid = m.dot(p0);  // √3/2 + 1
  // w_s two metres along the wall and 0.1 m off the mid-plane.
  const Vector3d w_s = p0 + 2.0 * t + 0.1 * m;
  const Vector3d c = WallCentre<double>(m, mid + 0.15, -m, -(mid - 0.15), w_s);
  // p0 + 2t = (1 − 1, 2 + √3, 0).
  ExpectNear(c, Vector3d(0.0, 2.0 + std::sqrt(3.0), 0.0));
}

TEST(WallCentre, NonParallelFacesStayFinite) {
  const Vector3d n_b = -Vector3d(1.0, 0.2, 0.0).normalized();
  const Vector3d c = WallCentre<double>(Vector3d::UnitX(), 0.1, n_b, 0.1, Vector3d(0.0, 3.0, 1.0));
  EXPECT_TRUE(c.allFinite());
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
