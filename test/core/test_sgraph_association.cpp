#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/sgraph/plane_association.h"
#include "is_graphs/sgraph/plane_fit.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector3d;

PlaneSegment Segment(const Vector3d& n, double d, const Vector3d& start, const Vector3d& end) {
  PlaneSegment s;
  s.plane = geometry::Plane(n, d);
  s.information = Eigen::Vector3d(1e6, 1e6, 1e4).asDiagonal();  // 1 mrad, 1 cm
  s.covariance = CovarianceFromInformation(s.plane.normal, s.information);
  s.start = start;
  s.end = end;
  return s;
}

MapPlaneView Mapped(int id, const PlaneSegment& s) {
  MapPlaneView v;
  v.id = id;
  v.plane = s.plane;
  v.covariance = s.covariance;
  v.start = s.start;
  v.end = s.end;
  return v;
}

class AssociationTest : public ::testing::Test {
 protected:
  // Two walls: x = 2 seen from −x (normal −x), and y = 3 seen from −y.
  void SetUp() override {
    mapped_ = {Mapped(7, Segment(-Vector3d::UnitX(), -2.0, Vector3d(2, -1, 0), Vector3d(2, 1, 0))),
               Mapped(9, Segment(-Vector3d::UnitY(), -3.0, Vector3d(-1, 3, 0), Vector3d(1, 3, 0)))};
  }
  FrontendConfig config_;
  std::vector<MapPlaneView> mapped_;
};

TEST_F(AssociationTest, SamePlaneWithSmallErrorsMatches) {
  const Vector3d n(-std::cos(0.01), std::sin(0.01), 0.0);  // 0.6°
  const auto a =
      AssociatePlane(Segment(n, -2.03, Vector3d(2, 0.5, 0), Vector3d(2, 2, 0)), mapped_, config_);
  EXPECT_EQ(a.index, 0);
  EXPECT_LT(a.distance2, config_.association_chi2);
}

TEST_F(AssociationTest, MahalanobisOfAnOffsetIsItsWhitenedSquare) {
  // d off by the gate's floor σ_f; both planes have σ_d = 1 cm: e² / (σ_f² + 2 (0.01)²).
  const double sf = config_.association_min_sigma_d;
  const PlaneSegment s =
      Segment(-Vector3d::UnitX(), -2.0 - sf, Vector3d(2, 0, 0), Vector3d(2, 1, 0));
  EXPECT_NEAR(PlaneMahalanobis2(s, mapped_[0], config_), sf * sf / (sf * sf + 2e-4), 1e-6);
}

TEST_F(AssociationTest, ParallelPlaneHalfAMetreAwayIsNew) {
  const auto a =
      AssociatePlane(Segment(-Vector3d::UnitX(), -2.5, Vector3d(2.5, -1, 0), Vector3d(2.5, 1, 0)),
                     mapped_, config_);
  EXPECT_EQ(a.index, -1);
}

TEST_F(AssociationTest, OtherFaceOfTheWallIsNew) {
  // The same wall seen from the other side: the normal is opposite.
  const auto a = AssociatePlane(
      Segment(Vector3d::UnitX(), 2.0, Vector3d(2, -1, 0), Vector3d(2, 1, 0)), mapped_, config_);
  EXPECT_EQ(a.index, -1);
}

TEST_F(AssociationTest, CoplanarButFarAlongTheWallIsNew) {
  const auto a = AssociatePlane(
      Segment(-Vector3d::UnitX(), -2.0, Vector3d(2, 5, 0), Vector3d(2, 7, 0)), mapped_, config_);
  EXPECT_EQ(a.index, -1);
  EXPECT_NEAR(SegmentGap(Segment(-Vector3d::UnitX(), -2.0, Vector3d(2, 5, 0), Vector3d(2, 7, 0)),
                         mapped_[0]),
              4.0, 1e-9);
}

TEST_F(AssociationTest, RotatedWallsMatchTheirOwnPlane) {
  // A wall at 30°, mapped; the observation moved 2 cm along its normal.
  const Vector3d n(std::cos(M_PI / 6), std::sin(M_PI / 6), 0.0);
  const Vector3d along(-n.y(), n.x(), 0.0);
  const PlaneSegment wall = Segment(n, -4.0, -4.0 * n - along, -4.0 * n + along);
  mapped_.push_back(Mapped(11, wall));
  const auto a =
      AssociatePlane(Segment(n, -3.98, -3.98 * n, -3.98 * n + 2 * along), mapped_, config_);
  EXPECT_EQ(a.index, 2);
}

TEST(TransformSegment, MovesPlaneAndExtent) {
  PlaneSegment s = Segment(-Vector3d::UnitX(), -2.0, Vector3d(2, -1, 0), Vector3d(2, 1, 0));
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Vector3d(1, 0, 0);
  const PlaneSegment m = TransformSegment(s, t);
  EXPECT_NEAR(m.plane.d, -3.0, 1e-12);
  EXPECT_NEAR(m.start.x(), 3.0, 1e-12);
  EXPECT_LT((m.information - s.information).norm() / s.information.norm(), 1e-6);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
