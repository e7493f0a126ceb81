// What D1 (FZK-Haus) taught the S-Graph: a ring of wall returns is not a floor, a recessed
// window neither tilts a wall nor joins it, and a 6-DoF alignment of a flat walk tilts.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "is_graphs/sgraph/evaluation.h"
#include "is_graphs/sgraph/floor_check.h"
#include "is_graphs/sgraph/plane_association.h"
#include "is_graphs/sgraph/plane_fit.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector3d;
using Eigen::Vector3f;

// A square room 3.4 m wide around the origin, walls sampled as a VLP-16 sees them from 0.7 m:
// rings every 2° from −15° to +15°, every 1° of azimuth.
PointList RingsOnWalls(double half_width, double sensor_z) {
  PointList points;
  for (int ring = -15; ring <= 15; ring += 2)
    for (int a = 0; a < 360; ++a) {
      const double az = a * M_PI / 180.0, el = ring * M_PI / 180.0;
      const Vector3d dir(std::cos(az), std::sin(az), 0.0);
      const double t = half_width / std::max(std::abs(dir.x()), std::abs(dir.y()));
      const double z = sensor_z + t * std::tan(el);
      if (z > 0.0) points.emplace_back(t * dir.x(), t * dir.y(), z);
    }
  return points;
}

TEST(FloorCheck, WallRingIsCoveredFloorIsOpen) {
  // Room: the lowest ring meets the walls at 0.7 − 1.7 tan 15° ≈ 0.24 m.
  PointList points = RingsOnWalls(1.7, 0.7);
  std::vector<int> band;
  for (size_t i = 0; i < points.size(); ++i)
    if (points[i].z() < 0.3) band.push_back(static_cast<int>(i));
  ASSERT_GT(band.size(), 100u);
  EXPECT_GT(FractionCoveredAbove(points, band, Vector3d::UnitZ(), 0.08, 0.04, 0.6), 0.8);
  // A floor disc 3–5 m out with nothing above it but the far wall's foot.
  std::vector<int> floor;
  for (int r = 30; r <= 50; r += 2)
    for (int a = 0; a < 360; a += 2) {
      floor.push_back(static_cast<int>(points.size()));
      points.emplace_back(0.1 * r * std::cos(a * M_PI / 180.0),
                          0.1 * r * std::sin(a * M_PI / 180.0), 0.0f);
    }
  EXPECT_LT(FractionCoveredAbove(points, floor, Vector3d::UnitZ(), 0.08, 0.04, 0.6), 0.1);
}

// A wall x = 2 (facing −x), 3 m long and 2.5 m high, with a window 12 cm behind it between
// 1 and 2 m height over its middle metre: within a 5 cm band only its lower sill part
// (points 0–4 cm behind) and the wall. Points in the band over part of the height tilt a free fit.
TEST(VerticalFit, WindowBandDoesNotTiltAWall) {
  PointList points;
  std::vector<int> indices;
  for (int i = 0; i <= 30; ++i)
    for (int k = 0; k <= 25; ++k) {
      const double y = -1.5 + 0.1 * i, z = 0.1 * k;
      const double x = (std::abs(y) < 0.5 && z > 1.0 && z < 2.0) ? 2.0 + 0.04 * (z - 1.0) : 2.0;
      indices.push_back(static_cast<int>(points.size()));
      points.emplace_back(x, y, z);
    }
  const auto free_fit = FitPlane(points, indices, 0.03, 150);
  const auto vertical = FitPlane(points, indices, 0.03, 150, Vector3d::UnitZ());
  ASSERT_TRUE(free_fit && vertical);
  EXPECT_GT(std::abs(free_fit->plane.normal.z()), 1e-3);  // the free fit tilts
  EXPECT_LT(std::abs(vertical->plane.normal.z()), 1e-9);
  EXPECT_NEAR(std::abs(vertical->plane.normal.x()), 1.0, 1e-6);
  EXPECT_TRUE(vertical->information.allFinite());
}

PlaneSegment Segment(double x, double y0, double y1) {
  PlaneSegment s;
  s.plane = geometry::Plane(-Vector3d::UnitX(), -x);
  s.information = Vector3d(1e6, 1e6, 1e4).asDiagonal();
  s.covariance = CovarianceFromInformation(s.plane.normal, s.information);
  s.start = Vector3d(x, y0, 1.0);
  s.end = Vector3d(x, y1, 1.0);
  return s;
}

TEST(AssociateScan, ParallelSegmentsOfOneScanTakeDifferentPlanes) {
  MapPlaneView wall;
  const PlaneSegment mapped = Segment(2.0, -2.0, 2.0);
  wall.id = 4;
  wall.plane = mapped.plane;
  wall.covariance = mapped.covariance;
  wall.start = mapped.start;
  wall.end = mapped.end;
  FrontendConfig config;
  // Alone, the window 12 cm behind the wall passes the drift-widened gate.
  const PlaneSegment window = Segment(2.12, -0.5, 0.5);
  EXPECT_EQ(AssociatePlane(window, {wall}, config).index, 0);
  // With the wall in the same scan, the wall keeps the plane, the window becomes a new one.
  const auto both = AssociateScan({window, Segment(2.01, -2.0, -0.6)}, {wall}, config);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0].index, -1);
  EXPECT_EQ(both[1].index, 0);
  // Two coplanar pieces of the wall (a gap at a doorway) both take it.
  const auto pieces =
      AssociateScan({Segment(2.0, -2.0, -0.6), Segment(2.01, 0.6, 2.0)}, {wall}, config);
  EXPECT_EQ(pieces[0].index, 0);
  EXPECT_EQ(pieces[1].index, 0);
}

TEST(AlignPositionsYaw, FlatWalkWithBobStaysLevel) {
  // An L-shaped walk with a 2 cm gait bob, the estimate 1 cm lower at the far end: a 6-DoF
  // alignment tilts to fit, the yaw-only one does not.
  std::vector<Vector3d> truth, estimate;
  const Eigen::Isometry3d motion(Eigen::Translation3d(4, 5, 0) *
                                 Eigen::AngleAxisd(0.3, Vector3d::UnitZ()));
  for (int i = 0; i < 40; ++i) {
    const Vector3d p = i < 20 ? Vector3d(0.25 * i, 0, 0.52) : Vector3d(5, 0.25 * (i - 20), 0.52);
    const Vector3d bob(0, 0, 0.02 * std::sin(i));
    truth.push_back(motion * (p + bob));
    estimate.push_back(p + bob - Vector3d(0, 0, 0.01 * i / 40.0 * (i < 20 ? 0 : 1)));
  }
  const Eigen::Isometry3d yaw = AlignPositionsYaw(estimate, truth);
  EXPECT_NEAR((yaw.linear() * Vector3d::UnitZ()).z(), 1.0, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(yaw.linear()).angle(), 0.3, 1e-3);
  EXPECT_NEAR((yaw.translation() - Vector3d(4, 5, 0)).norm(), 0.0, 0.02);
}

// A robot that has not walked yet (one keyframe, or turning on the spot): the positions do not
// fix the yaw, the headings do. replay_pipeline's audit called D9's right first match (at the
// first keyframe, from the hall alone) wrong by 58 deg: it took yaw 0 for the truth.
TEST(AlignPositionsYaw, StandingStillTakesTheYawFromTheHeadings) {
  const Eigen::Isometry3d motion(Eigen::Translation3d(-2.7, 0.7, 0) *
                                 Eigen::AngleAxisd(1.0, Vector3d::UnitZ()));
  std::vector<Vector3d> estimate{Vector3d(0.1, 0.0, 0.5)}, truth{motion * estimate[0]};
  const std::vector<double> estimate_yaw{0.2}, truth_yaw{1.2};
  EXPECT_NEAR(Eigen::AngleAxisd(AlignPositionsYaw(estimate, truth).linear()).angle(), 0.0, 1e-12);
  const Eigen::Isometry3d t = AlignPositionsYaw(estimate, truth, estimate_yaw, truth_yaw);
  EXPECT_NEAR(Eigen::AngleAxisd(t.linear()).angle(), 1.0, 1e-12);
  EXPECT_NEAR((t * estimate[0] - truth[0]).norm(), 0.0, 1e-12);
  // Turning on the spot, 3 cm of sway: still the headings.
  estimate.push_back(Vector3d(0.13, 0.02, 0.5));
  truth.push_back(motion * estimate[1]);
  const Eigen::Isometry3d turned = AlignPositionsYaw(estimate, truth, {0.2, 1.7}, {1.2, 2.7});
  EXPECT_NEAR(Eigen::AngleAxisd(turned.linear()).angle(), 1.0, 1e-9);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
