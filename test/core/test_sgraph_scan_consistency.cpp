#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/sgraph/plane_fit.h"
#include "is_graphs/sgraph/scan_consistency.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector3d;
constexpr double kDeg = M_PI / 180.0;

// A wall of normal angle `heading` (in the plan) through point p, 1 mrad / 1 cm certain.
PlaneSegment Wall(double heading, const Vector3d& p) {
  PlaneSegment s;
  const Vector3d n(std::cos(heading), std::sin(heading), 0.0);
  s.plane = geometry::Plane(n, n.dot(p));
  s.information = Vector3d(1e6, 1e6, 1e4).asDiagonal();
  s.covariance = CovarianceFromInformation(s.plane.normal, s.information);
  const Vector3d along(-n.y(), n.x(), 0.0);
  s.start = p - 0.5 * along;
  s.end = p + 0.5 * along;
  return s;
}

class ScanConsistencyTest : public ::testing::Test {
 protected:
  // Four mapped walls (the sides of a room) and a fifth, a wall with a door in it.
  void SetUp() override {
    const double headings[] = {0.0, M_PI / 2, M_PI, -M_PI / 2, M_PI};
    const Vector3d points[] = {{-2, 0, 1}, {0, -3, 1}, {2, 0, 1}, {0, 3, 1}, {2, 2, 1}};
    for (int i = 0; i < 5; ++i) {
      MapPlaneView v;
      v.id = i;
      const PlaneSegment w = Wall(headings[i], points[i]);
      v.plane = w.plane;
      v.covariance = w.covariance;
      v.start = w.start;
      v.end = w.end;
      v.num_keyframes = 5;
      v.walked_since = 0.8;
      mapped_.push_back(v);
      headings_.push_back(headings[i]);
      points_.push_back(points[i]);
      associations_.push_back({i, 1.0});
    }
  }
  // The five walls as a keyframe sees them with its heading `drift` off; wall 4 turned by `turn`.
  std::vector<PlaneSegment> Seen(double drift, double turn = 0.0) const {
    std::vector<PlaneSegment> out;
    for (size_t i = 0; i < headings_.size(); ++i)
      out.push_back(Wall(headings_[i] - drift - (i == 4 ? turn : 0.0), points_[i]));
    return out;
  }
  FrontendConfig config_;
  std::vector<MapPlaneView> mapped_;
  std::vector<double> headings_;
  std::vector<Vector3d> points_;
  std::vector<Association> associations_;
};

TEST_F(ScanConsistencyTest, ADoorLeafTurnedOffItsWallIsContradicted) {
  const ScanConsistency c =
      ContradictedWalls(Seen(0.5 * kDeg, 7.5 * kDeg), mapped_, associations_, config_);
  ASSERT_EQ(c.contradicted.size(), 1u);
  EXPECT_EQ(c.contradicted[0], 4);
  EXPECT_EQ(c.support, 4);
  EXPECT_NEAR(c.yaw, 0.5 * kDeg, 1e-3);
}

TEST_F(ScanConsistencyTest, DriftTurnsEveryWallAlikeAndContradictsNone) {
  const ScanConsistency c = ContradictedWalls(Seen(2.5 * kDeg), mapped_, associations_, config_);
  EXPECT_TRUE(c.contradicted.empty());
  EXPECT_EQ(c.support, 5);
  EXPECT_NEAR(c.yaw, 2.5 * kDeg, 1e-3);
}

TEST_F(ScanConsistencyTest, ToleranceGrowsWithThePathWalkedSinceThePlaneWasSeen) {
  mapped_[4].walked_since = 15.0;  // 1.5 + 0.5 * 15 = 9 deg
  EXPECT_TRUE(ContradictedWalls(Seen(0.0, 7.5 * kDeg), mapped_, associations_, config_)
                  .contradicted.empty());
  mapped_[4].walked_since = 1.0;  // 2 deg
  EXPECT_EQ(ContradictedWalls(Seen(0.0, 2.5 * kDeg), mapped_, associations_, config_).contradicted,
            std::vector<int>{4});
  EXPECT_TRUE(ContradictedWalls(Seen(0.0, 1.5 * kDeg), mapped_, associations_, config_)
                  .contradicted.empty());
}

TEST_F(ScanConsistencyTest, APlaneSeenByFewKeyframesNeitherVotesNorIsContradicted) {
  mapped_[4].num_keyframes = config_.consistency_min_keyframes - 1;  // its heading: one fit's
  EXPECT_TRUE(ContradictedWalls(Seen(0.0, 7.5 * kDeg), mapped_, associations_, config_)
                  .contradicted.empty());
}

TEST_F(ScanConsistencyTest, UncertainPlanesGetWiderTolerance) {
  std::vector<PlaneSegment> seen = Seen(0.0, 7.5 * kDeg);
  seen[4].information = Vector3d(20.0, 20.0, 1e4).asDiagonal();  // sigma 0.22 rad: 3 sigma 38 deg
  seen[4].covariance = CovarianceFromInformation(seen[4].plane.normal, seen[4].information);
  EXPECT_TRUE(ContradictedWalls(seen, mapped_, associations_, config_).contradicted.empty());
}

TEST_F(ScanConsistencyTest, NoMajorityNoVerdict) {
  // Two walls at 0, two turned 6 deg: no rotation has more than half.
  std::vector<PlaneSegment> seen = Seen(0.0);
  seen.pop_back();
  associations_.pop_back();
  seen[2] = Wall(headings_[2] - 6.0 * kDeg, points_[2]);
  seen[3] = Wall(headings_[3] - 6.0 * kDeg, points_[3]);
  EXPECT_TRUE(ContradictedWalls(seen, mapped_, associations_, config_).contradicted.empty());
}

TEST_F(ScanConsistencyTest, TooFewWallsOrCheckOffNoVerdict) {
  std::vector<PlaneSegment> seen = Seen(0.0, 7.5 * kDeg);
  for (int i : {0, 1, 2}) associations_[i].index = -1;  // new planes do not take part
  EXPECT_TRUE(ContradictedWalls(seen, mapped_, associations_, config_).contradicted.empty());
  associations_[0].index = 0;
  associations_[1].index = 1;
  associations_[2].index = 2;
  config_.consistency_min_walls = 0;
  EXPECT_TRUE(ContradictedWalls(seen, mapped_, associations_, config_).contradicted.empty());
}

TEST_F(ScanConsistencyTest, FloorsNeverTakePart) {
  std::vector<PlaneSegment> seen = Seen(0.0, 7.5 * kDeg);
  seen[4].horizontal = true;
  EXPECT_TRUE(ContradictedWalls(seen, mapped_, associations_, config_).contradicted.empty());
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
