// The Ceres compatibility layer (common/ceres_compat.h): the unit-sphere and unit-quaternion
// parameterizations give the same maps whichever Ceres (1.14 to 2.2) the build found.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>

#include "is_graphs/common/ceres_compat.h"

namespace is_graphs {
namespace {

using ceres_compat::Parameterization;

TEST(CeresCompat, UnitSphereSizes) {
  std::unique_ptr<Parameterization> sphere(ceres_compat::NewUnitSphere3());
  EXPECT_EQ(ceres_compat::AmbientSize(*sphere), 3);
  EXPECT_EQ(ceres_compat::TangentSize(*sphere), 2);
}

TEST(CeresCompat, UnitSpherePlusOfZeroIsTheSamePoint) {
  std::unique_ptr<Parameterization> sphere(ceres_compat::NewUnitSphere3());
  const Eigen::Vector3d x = Eigen::Vector3d(0.3, -0.4, 0.866).normalized();
  const double delta[2] = {0.0, 0.0};
  Eigen::Vector3d y;
  ASSERT_TRUE(ceres_compat::Plus(*sphere, x.data(), delta, y.data()));
  EXPECT_NEAR((y - x).norm(), 0.0, 1e-15);
}

// Known value: at the pole (0, 0, 1) the Householder reflection is the identity up to the sign
// of the last coordinate, so x ⊞ δ = (sin(|δ|/2) δ/|δ|, cos(|δ|/2)) up to that sign convention:
// the angle between x and x ⊞ δ is |δ|/2 on both Ceres APIs, and the result stays unit.
TEST(CeresCompat, UnitSpherePlusTurnsByHalfTheStepAndStaysUnit) {
  std::unique_ptr<Parameterization> sphere(ceres_compat::NewUnitSphere3());
  for (const Eigen::Vector3d& start :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.6, 0.0, -0.8)}) {
    const double delta[2] = {0.03, -0.04};  // |δ| = 0.05
    Eigen::Vector3d y;
    ASSERT_TRUE(ceres_compat::Plus(*sphere, start.data(), delta, y.data()));
    EXPECT_NEAR(y.norm(), 1.0, 1e-14);
    EXPECT_NEAR(std::acos(std::clamp(y.dot(start), -1.0, 1.0)), 0.025, 1e-12)
        << "start " << start.transpose();
  }
}

TEST(CeresCompat, UnitSphereJacobianSpansTheTangentPlane) {
  std::unique_ptr<Parameterization> sphere(ceres_compat::NewUnitSphere3());
  const Eigen::Vector3d x = Eigen::Vector3d(0.2, 0.5, -0.7).normalized();
  Eigen::Matrix<double, 3, 2, Eigen::RowMajor> j;
  ASSERT_TRUE(ceres_compat::PlusJacobian(*sphere, x.data(), j.data()));
  EXPECT_NEAR((x.transpose() * j).norm(), 0.0, 1e-14);  // tangent to the sphere at x
  // Columns of length 1/2 (the half-angle map), orthogonal to each other.
  const Eigen::Matrix2d gram = j.transpose() * j;
  EXPECT_NEAR(gram(0, 0), 0.25, 1e-14);
  EXPECT_NEAR(gram(1, 1), 0.25, 1e-14);
  EXPECT_NEAR(gram(0, 1), 0.0, 1e-14);
}

TEST(CeresCompat, EigenQuaternionPlusIsALeftRotation) {
  std::unique_ptr<Parameterization> quaternion(ceres_compat::NewEigenQuaternion());
  EXPECT_EQ(ceres_compat::AmbientSize(*quaternion), 4);
  EXPECT_EQ(ceres_compat::TangentSize(*quaternion), 3);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d delta(0.01, -0.02, 0.03);
  Eigen::Quaterniond out;
  ASSERT_TRUE(ceres_compat::Plus(*quaternion, q.coeffs().data(), delta.data(),
                                 out.coeffs().data()));
  // Known value: exp(δ) ⊗ q with Ceres' exp(δ) = [cos|δ|, sin|δ| δ/|δ|], the rotation by 2|δ|
  // about δ/|δ| (δ is half the rotation vector, in 1.14's parameterization and 2.x's manifold).
  const Eigen::Quaterniond expected =
      Eigen::Quaterniond(Eigen::AngleAxisd(2.0 * delta.norm(), delta.normalized())) * q;
  EXPECT_NEAR((out.coeffs() - expected.coeffs()).norm(), 0.0, 1e-14);
}

TEST(CeresCompat, ProblemQueriesSeeTheParameterization) {
  ceres::Problem problem;
  double normal[3] = {0.0, 0.0, 1.0};
  double offset = 2.0;
  problem.AddParameterBlock(normal, 3);
  problem.AddParameterBlock(&offset, 1);
  EXPECT_EQ(ceres_compat::GetParameterization(problem, normal), nullptr);
  EXPECT_EQ(ceres_compat::TangentSize(problem, normal), 3);
  ceres_compat::SetParameterization(problem, normal, ceres_compat::NewUnitSphere3());
  EXPECT_NE(ceres_compat::GetParameterization(problem, normal), nullptr);
  EXPECT_EQ(ceres_compat::TangentSize(problem, normal), 2);
  EXPECT_EQ(ceres_compat::TangentSize(problem, &offset), 1);
}

}  // namespace
}  // namespace is_graphs
