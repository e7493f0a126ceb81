// The pose between S-Graph revisions: CalibrateOdometry recovers a known scale error and yaw bias
// from keyframe steps (optimized poses = the truth, odometry = the truth with those errors), and
// OdometryAnchor::Pose with it puts a later odometry reading where the truth is; with too few
// steps it is the identity (the pose as before), with a few it is shrunk towards it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/odometry_extrapolation.h"

namespace is_graphs {
namespace merging {
namespace {

// The truth walks a wavy path; the odometry integrates each true step with the distance times
// (1 + scale_error) and a heading error of yaw_per_m per metre.
struct Walk {
  sgraph::SGraph graph;
  std::vector<Eigen::Isometry3d> truth, odom;
};

Walk MakeWalk(int n, double scale_error, double yaw_per_m, double step = 0.8) {
  Walk w;
  Eigen::Vector3d t(0.0, 0.0, 0.0), o(0.0, 0.0, 0.0);  // x, y, yaw
  for (int i = 0; i < n; ++i) {
    sgraph::Keyframe k;
    k.id = i;
    k.previous = i - 1;
    k.pose = geometry::IsometryFromXYYaw(t.x(), t.y(), t.z());
    k.odom_pose = geometry::IsometryFromXYYaw(o.x(), o.y(), o.z());
    w.graph.keyframes.push_back(k);
    w.truth.push_back(k.pose);
    w.odom.push_back(k.odom_pose);
    const double turn = 0.3 * std::sin(0.7 * i);
    // The true step in the body frame, then the odometry's version of it.
    const Eigen::Vector2d body(step * std::cos(0.5 * turn), step * std::sin(0.5 * turn));
    t.head<2>() += Eigen::Rotation2Dd(t.z()) * body;
    t.z() += turn;
    const double heading_error = yaw_per_m * step;
    o.head<2>() += Eigen::Rotation2Dd(o.z()) *
                   (Eigen::Rotation2Dd(0.5 * heading_error) * ((1.0 + scale_error) * body));
    o.z() += turn + heading_error;
  }
  return w;
}

TEST(OdometryCalibration, RecoversAScaleErrorAndAYawBias) {
  const Walk w = MakeWalk(30, 0.06, 0.006);
  OdometryCalibrationConfig exact;
  exact.prior_weight = 0.0;  // the least squares alone
  const OdometryCalibration c = CalibrateOdometry(w.graph, {}, exact);
  EXPECT_EQ(c.steps, 29);
  EXPECT_NEAR(c.scale, 1.0 / 1.06, 1e-9);
  EXPECT_NEAR(c.yaw_per_m, -0.006 / 1.06, 1e-9);  // per metre of odometry
  // Merged poses replace the S-Graph's own: with the odometry's own poses there is no error.
  std::map<int, Eigen::Isometry3d> as_odometry;
  for (const auto& k : w.graph.keyframes) as_odometry[k.id] = k.odom_pose;
  const OdometryCalibration none = CalibrateOdometry(w.graph, as_odometry);
  EXPECT_NEAR(none.scale, 1.0, 1e-12);
  EXPECT_NEAR(none.yaw_per_m, 0.0, 1e-12);
  // With the prior (the default), 29 steps of 0.8 m keep 18.56 / 19.06 of the correction.
  const OdometryCalibration shrunk = CalibrateOdometry(w.graph, {});
  EXPECT_NEAR(shrunk.scale - 1.0, (1.0 / 1.06 - 1.0) * 18.56 / 19.06, 2e-4);
}

// Right after a merge starts (the matcher's proposals: 2-4 keyframes), three steps already
// calibrate most of a 6 % scale error, and halve the pose's error 1.6 m on.
TEST(OdometryCalibration, AFewStepsCalibrateInPart) {
  const Walk w = MakeWalk(6, 0.06, 0.006);
  sgraph::SGraph upto;
  upto.keyframes.assign(w.graph.keyframes.begin(), w.graph.keyframes.begin() + 4);
  const OdometryCalibration c = CalibrateOdometry(upto, {});
  EXPECT_EQ(c.steps, 3);
  EXPECT_LT(c.scale, 1.0 - 0.7 * (1.0 - 1.0 / 1.06));  // most of the way
  EXPECT_GT(c.scale, 1.0 / 1.06);                      // never past the truth
  OdometryAnchor anchor;
  anchor.odom_T_keyframe = w.odom[3];
  anchor.bim_T_keyframe = w.truth[3];
  const double raw = (anchor.Pose(w.odom[5]).translation() - w.truth[5].translation()).norm();
  anchor.calibration = c;
  const double calibrated =
      (anchor.Pose(w.odom[5]).translation() - w.truth[5].translation()).norm();
  EXPECT_LT(calibrated, 0.5 * raw) << "raw " << raw;
}

TEST(OdometryCalibration, TooFewStepsShortStepsAndClampsLeaveItSafe) {
  EXPECT_EQ(CalibrateOdometry(MakeWalk(2, 0.06, 0.006).graph, {}).steps, 0);  // 1 < 2 steps
  const OdometryCalibration c = CalibrateOdometry(MakeWalk(2, 0.06, 0.006).graph, {});
  EXPECT_EQ(c.scale, 1.0);
  EXPECT_EQ(c.yaw_per_m, 0.0);
  // Turns on the spot (steps of 0.1 m) are left out.
  EXPECT_EQ(CalibrateOdometry(MakeWalk(30, 0.06, 0.006, 0.1).graph, {}).steps, 0);
  // A wild estimate is clamped.
  const OdometryCalibration wild = CalibrateOdometry(MakeWalk(30, 0.5, 0.2).graph, {});
  EXPECT_NEAR(wild.scale, 0.85, 1e-12);
  EXPECT_NEAR(wild.yaw_per_m, -0.02, 1e-12);
}

TEST(OdometryAnchor, TheCalibratedOdometryLandsOnTheTruth) {
  const Walk w = MakeWalk(40, 0.06, 0.006);
  sgraph::SGraph upto;  // the revision: keyframes 0..29
  upto.keyframes.assign(w.graph.keyframes.begin(), w.graph.keyframes.begin() + 30);
  OdometryAnchor anchor;
  anchor.odom_T_keyframe = w.odom[29];
  anchor.bim_T_keyframe = w.truth[29];
  const Eigen::Isometry3d later_odom = w.odom[31], later_truth = w.truth[31];  // 1.6 m on
  const double raw = (anchor.Pose(later_odom).translation() - later_truth.translation()).norm();
  anchor.calibration = CalibrateOdometry(upto, {});
  const Eigen::Isometry3d p = anchor.Pose(later_odom);
  const double calibrated = (p.translation() - later_truth.translation()).norm();
  EXPECT_GT(raw, 0.09);  // 6 % of 1.6 m
  EXPECT_LT(calibrated, 0.01) << "raw " << raw;
  EXPECT_LT(std::abs(geometry::NormalizeAngle(geometry::Yaw(p) - geometry::Yaw(later_truth))),
            0.002);
  // At the keyframe itself the pose is the keyframe's.
  EXPECT_TRUE(anchor.Pose(w.odom[29]).isApprox(w.truth[29], 1e-12));
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
