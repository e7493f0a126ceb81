// The wall-deviation functors of the merge (issue 21): residuals on hand-computed values, the
// deviated match against SurfaceMatchCost, autodiff vs numeric Jacobians.
#include <ceres/numeric_diff_cost_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "cost_test_util.h"
#include "is_graphs/geometry/plane.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/cost/deviated_surface_match_cost.h"
#include "is_graphs/merging/cost/surface_match_cost.h"
#include "is_graphs/merging/cost/wall_deviation_prior_cost.h"

namespace is_graphs {
namespace merging {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
constexpr double kDeg = M_PI / 180.0;

// A 20 cm wall along y from (3, 0) to (3, 10): surface_a at x = 3.2 (normal +x), surface_b at
// x = 3.0 (normal −x), centre (3.1, 5), plan normal m = +x.
const Vector2d kCentre(3.1, 5.0);
const Vector2d kWallNormal(1.0, 0.0);

// The face of that wall through `point` with planned normal `normal`, built δ along m and
// turned θ about the centre (the definition DeviatedSurfaceMatchCost inverts).
geometry::Plane BuiltFace(const Vector3d& point, const Vector3d& normal, double delta,
                          double theta) {
  const Vector3d c(kCentre.x(), kCentre.y(), point.z());
  const Vector3d moved =
      c + geometry::RotationZ(theta) * (point - c) + delta * Vector3d(kWallNormal.x(), 0, 0);
  return geometry::Plane::FromPointNormal(moved, geometry::RotationZ(theta) * normal);
}

TEST(WallDeviationPriorCost, HandComputed) {
  std::unique_ptr<ceres::CostFunction> cost(WallDeviationPriorCost::Create(0.05, 2.0 * kDeg));
  const Vector2d deviation(0.1, -1.0 * kDeg);
  const Eigen::VectorXd r = testing::Residual(*cost, {deviation.data()});
  EXPECT_NEAR(r(0), 2.0, 1e-12);   // 10 cm at σ 5 cm
  EXPECT_NEAR(r(1), -0.5, 1e-12);  // −1° at σ 2°
  const Vector2d zero(0.0, 0.0);
  EXPECT_LT(testing::Residual(*cost, {zero.data()}).norm(), 1e-15);
}

// A wall seen turned keeps its offset prior and has none on its turn (σ = +infinity).
TEST(WallDeviationPriorCost, AnInfiniteSigmaIsNoPrior) {
  std::unique_ptr<ceres::CostFunction> cost(
      WallDeviationPriorCost::Create(0.05, std::numeric_limits<double>::infinity()));
  const Vector2d deviation(0.1, 4.0 * kDeg);
  const Eigen::VectorXd r = testing::Residual(*cost, {deviation.data()});
  EXPECT_NEAR(r(0), 2.0, 1e-12);
  EXPECT_EQ(r(1), 0.0);
}

TEST(DeviatedSurfaceMatchCost, ZeroDeviationIsSurfaceMatchCost) {
  const Vector3d an = Vector3d(0.6, 0.8, 0.02).normalized();
  const Eigen::Matrix3d sqrt_info = Vector3d(50, 40, 20).asDiagonal();
  std::unique_ptr<ceres::CostFunction> plain(SurfaceMatchCost::Create(an, 0.3, sqrt_info));
  std::unique_ptr<ceres::CostFunction> deviated(
      DeviatedSurfaceMatchCost::Create(an, kCentre, kWallNormal, 0.3, sqrt_info));
  const Vector3d xi(1.2, -0.7, 0.4);
  const Vector3d ns = Vector3d(0.2, 0.95, 0.01).normalized();
  const double ds = 2.1, da = 3.3;
  const Vector2d zero(0.0, 0.0);
  const Eigen::VectorXd r_plain =
      testing::Residual(*plain, {xi.data(), ns.data(), &ds, an.data(), &da});
  const Eigen::VectorXd r_deviated =
      testing::Residual(*deviated, {xi.data(), ns.data(), &ds, an.data(), &da, zero.data()});
  EXPECT_LT((r_plain - r_deviated).norm(), 1e-12);
}

TEST(DeviatedSurfaceMatchCost, ZeroOnBothFacesOfTheBuiltWall) {
  // The robot's map M is B turned by 30° and shifted: an S-plane is a built face seen from M.
  const Vector3d xi(2.0, -1.0, 30.0 * kDeg);
  const double z = 0.4;
  const Eigen::Isometry3d b_T_m = geometry::IsometryFromXYYaw(xi.x(), xi.y(), xi.z(), z);
  const double delta = 0.30, theta = 15.0 * kDeg;
  const Vector2d deviation(delta, theta);
  for (const auto& [point, normal] :
       {std::pair<Vector3d, Vector3d>{{3.2, 5, 1}, {1, 0, 0}}, {{3.0, 5, 1}, {-1, 0, 0}}}) {
    const geometry::Plane planned = geometry::Plane::FromPointNormal(point, normal);
    const geometry::Plane seen =
        BuiltFace(point, normal, delta, theta).Transformed(b_T_m.inverse());
    std::unique_ptr<ceres::CostFunction> cost(DeviatedSurfaceMatchCost::Create(
        planned.normal, kCentre, kWallNormal, z, Eigen::Matrix3d::Identity()));
    const Vector3d ns = seen.normal, na = planned.normal;
    const double ds = seen.d, da = planned.d;
    EXPECT_LT(
        testing::Residual(*cost, {xi.data(), ns.data(), &ds, na.data(), &da, deviation.data()})
            .norm(),
        1e-12)
        << "face with normal " << normal.transpose();
    // Against the plan (no deviation) the normals are 15° apart: the tangent residual is the
    // difference's part across the planned normal, sin 15°.
    const Vector2d zero(0.0, 0.0);
    const Eigen::VectorXd r =
        testing::Residual(*cost, {xi.data(), ns.data(), &ds, na.data(), &da, zero.data()});
    EXPECT_NEAR(r.head<2>().norm(), std::sin(theta), 1e-9);
  }
}

TEST(DeviatedSurfaceMatchCost, HandComputedShift) {
  // The face x = 3.2 seen where planned (ξ = 0): with the wall shifted δ = 0.1 along +x the
  // match says the plane is 10 cm short of the built face: offset residual −0.1 / σ.
  const Vector3d xi(0.0, 0.0, 0.0), n(1, 0, 0);
  const double ds = 3.2, da = 3.2;
  std::unique_ptr<ceres::CostFunction> cost(DeviatedSurfaceMatchCost::Create(
      n, kCentre, kWallNormal, 0.0, Vector3d(1.0, 1.0, 1.0 / 0.05).asDiagonal()));
  const Vector2d shift(0.1, 0.0);
  Eigen::VectorXd r =
      testing::Residual(*cost, {xi.data(), n.data(), &ds, n.data(), &da, shift.data()});
  EXPECT_NEAR(r(2), -0.1 / 0.05, 1e-12);
  EXPECT_NEAR(r.head<2>().norm(), 0.0, 1e-12);
  // Surface_b (normal −x, n·p = −3.0) moves the same way: its offset −3.0 becomes −3.1.
  const Vector3d nb(-1, 0, 0);
  const double dsb = -3.0, dab = -3.0;
  std::unique_ptr<ceres::CostFunction> cost_b(DeviatedSurfaceMatchCost::Create(
      nb, kCentre, kWallNormal, 0.0, Vector3d(1.0, 1.0, 1.0 / 0.05).asDiagonal()));
  r = testing::Residual(*cost_b, {xi.data(), nb.data(), &dsb, nb.data(), &dab, shift.data()});
  EXPECT_NEAR(r(2), 0.1 / 0.05, 1e-12);
}

TEST(DeviatedSurfaceMatchCost, AutodiffMatchesNumericJacobian) {
  const Vector3d an = Vector3d(0.6, 0.8, 0.02).normalized();
  const Eigen::Matrix3d sqrt_info = Vector3d(50, 40, 20).asDiagonal();
  const Vector2d centre(1.5, -2.0), wall_normal = Vector2d(0.6, 0.8);
  std::unique_ptr<ceres::CostFunction> autodiff(
      DeviatedSurfaceMatchCost::Create(an, centre, wall_normal, 0.3, sqrt_info));
  ceres::NumericDiffCostFunction<DeviatedSurfaceMatchCost, ceres::CENTRAL, 3, 3, 3, 1, 3, 1, 2>
      numeric(new DeviatedSurfaceMatchCost(an, centre, wall_normal, 0.3, sqrt_info));
  const Vector3d xi(1.2, -0.7, 0.4);
  const Vector3d ns = Vector3d(0.2, 0.95, 0.01).normalized(), na = an;
  const double ds = 2.1, da = 3.3;
  const Vector2d deviation(0.12, 4.0 * kDeg);
  testing::ExpectSameEvaluation(
      *autodiff, numeric, {xi.data(), ns.data(), &ds, na.data(), &da, deviation.data()}, 1e-6);
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
