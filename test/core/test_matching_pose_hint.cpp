// The pose hint (rviz's "2D Pose Estimate") as a gate on the matcher's hypotheses
// (matching/pose_hint.h): the gate's arithmetic, bad hints, and HintedMatching on synthetic
// S-Graphs of the project's buildings: twins decided by the hint, a hint the evidence
// contradicts rejected, a hint never making a pose the checks do not accept.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/pose_hint.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

using testing::MatchIsCorrect;
using testing::Noisy;
using testing::ProjectBim;
using testing::RoomByName;

constexpr double kDeg = M_PI / 180.0;

/// A hint at the robot pose `bim_T_map` implies for a robot at `map_T_base`, moved by (dx, dy,
/// dyaw), with sigma_xy, sigma_yaw.
PoseHint HintAt(const Pose2& bim_T_map, const Pose2& map_T_base, double dx, double dy, double dyaw,
                double sigma_xy = 1.0, double sigma_yaw = 20.0 * kDeg) {
  PoseHint h;
  h.map_T_base = map_T_base;
  h.bim_T_base = ImpliedRobotPose(bim_T_map, map_T_base);
  h.bim_T_base.t += Eigen::Vector2d(dx, dy);
  h.bim_T_base.yaw += dyaw;
  h.covariance =
      Eigen::Vector3d(sigma_xy * sigma_xy, sigma_xy * sigma_xy, sigma_yaw * sigma_yaw).asDiagonal();
  return h;
}

TEST(PoseHint, GateIsTheMahalanobisDistanceOfTheImpliedRobotPose) {
  const Pose2 bim_T_map{0.8, {3.0, -2.0}};
  const Pose2 map_T_base{-0.3, {1.5, 4.0}};
  const HintGate at(HintAt(bim_T_map, map_T_base, 0.0, 0.0, 0.0, 0.5, 10.0 * kDeg));
  EXPECT_NEAR(at.Distance2(bim_T_map), 0.0, 1e-12);
  // The robot 1 sigma (0.5 m) off in x, in y, 1 sigma (10 deg) off in yaw.
  EXPECT_NEAR(
      HintGate(HintAt(bim_T_map, map_T_base, 0.5, 0.0, 0.0, 0.5, 10 * kDeg)).Distance2(bim_T_map),
      1.0, 1e-9);
  EXPECT_NEAR(
      HintGate(HintAt(bim_T_map, map_T_base, 0.3, 0.4, 0.0, 0.5, 10 * kDeg)).Distance2(bim_T_map),
      1.0, 1e-9);
  EXPECT_NEAR(HintGate(HintAt(bim_T_map, map_T_base, 0.0, 0.0, -10 * kDeg, 0.5, 10 * kDeg))
                  .Distance2(bim_T_map),
              1.0, 1e-9);
  // Yaw wraps: a hint at 179 deg and a robot at -179 deg are 2 deg apart.
  const HintGate wrap(HintAt({179 * kDeg, {0, 0}}, {}, 0, 0, 0, 1.0, 1.0 * kDeg));
  EXPECT_NEAR(wrap.Distance2({-179 * kDeg, {0, 0}}), 4.0, 1e-9);
  // The gate: chi2(3) at 99 %, 3.37 sigma.
  EXPECT_TRUE(at.Inside({0.8, {3.0 + 0.5 * 3.3, -2.0}}, 1));
  EXPECT_FALSE(at.Inside({0.8, {3.0 + 0.5 * 3.4, -2.0}}, 1));
  // A hypothesis turned by 10 deg turns the map about M's origin: the robot, 4.27 m from it,
  // moves 2 sin(5 deg) 4.27 m = 0.745 m as well as turning 10 deg.
  const double moved = 2.0 * std::sin(5 * kDeg) * map_T_base.t.norm();
  EXPECT_NEAR(at.Distance2({0.8 + 10 * kDeg, {3.0, -2.0}}), std::pow(moved / 0.5, 2) + 1.0, 1e-9);
  // Its storey.
  PoseHint on_storey = HintAt(bim_T_map, map_T_base, 0, 0, 0);
  on_storey.storey = 2;
  EXPECT_TRUE(HintGate(on_storey).Inside(bim_T_map, 2));
  EXPECT_FALSE(HintGate(on_storey).Inside(bim_T_map, 1));
}

TEST(PoseHint, BadHintsAreNamedAndChangeNothing) {
  const PoseHint good = HintAt({0.0, {1.0, 2.0}}, {}, 0, 0, 0);
  EXPECT_EQ(CheckPoseHint(good), "");
  PoseHint nan_pose = good;
  nan_pose.bim_T_base.t.x() = std::nan("");
  EXPECT_NE(CheckPoseHint(nan_pose).find("not finite"), std::string::npos);
  PoseHint nan_yaw = good;
  nan_yaw.bim_T_base.yaw = std::numeric_limits<double>::infinity();
  EXPECT_NE(CheckPoseHint(nan_yaw), "");
  PoseHint nan_cov = good;
  nan_cov.covariance(1, 1) = std::nan("");
  EXPECT_NE(CheckPoseHint(nan_cov).find("covariance is not finite"), std::string::npos);
  PoseHint zero = good;
  zero.covariance(2, 2) = 0.0;  // rviz's yaw variance left out, say
  EXPECT_NE(CheckPoseHint(zero).find("not positive definite"), std::string::npos);
  PoseHint negative = good;
  negative.covariance(0, 1) = negative.covariance(1, 0) = 2.0;  // |corr| > 1
  EXPECT_NE(CheckPoseHint(negative).find("not positive definite"), std::string::npos);
  PoseHint skew = good;
  skew.covariance(0, 1) = 0.5;
  EXPECT_NE(CheckPoseHint(skew).find("not symmetric"), std::string::npos);

  HintedMatching hinted;
  EXPECT_EQ(hinted.Set(good), "");
  const std::string before = hinted.Describe();
  EXPECT_NE(hinted.Set(zero), "");
  EXPECT_TRUE(hinted.InForce());
  EXPECT_EQ(hinted.Describe(), before) << "a bad hint replaces nothing";
}

// symmetric.ifc walked in rooms whose twins (the plan turned a half turn) the walls cannot tell
// apart.
SyntheticSGraph SymmetricTwins(const agraph::AGraph& g) {
  auto c = Noisy(5, 2.4, -3.0, 8.0);
  for (const char* n : {"Corridor", "S1", "S3", "S4", "S5", "N1", "N3", "N4", "N5"})
    c.rooms.push_back(RoomByName(g, n));
  return MakeSyntheticSGraph(g, c);
}

TEST(PoseHint, TheHintDecidesBetweenTwinsTheEvidenceCannotTellApart) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("symmetric.ifc"));
  const SyntheticSGraph s = SymmetricTwins(*g);
  const Pose2 truth = PlanarPose(s.bim_T_map), robot{0.4, {2.0, 1.0}};

  GraphMatcher matcher;
  matcher.SetAGraph(*g);
  HintedMatching hinted;
  const GraphMatch free = hinted.Match(matcher, s.graph);
  ASSERT_EQ(free.status, MatchStatus::kAmbiguous);
  ASSERT_EQ(free.alternatives.size(), 1u);
  EXPECT_EQ(free.hint, "");
  // The twin: whichever of the two is not the truth.
  const Pose2 best = PlanarPose(free.bim_T_map);
  const Pose2 twin =
      (best.t - truth.t).norm() < 0.5 ? PlanarPose(free.alternatives[0].bim_T_map) : best;
  ASSERT_GT((twin.t - truth.t).norm(), 5.0);

  // In the walked half, 0.7 m and 8 deg off: UNIQUE and right.
  ASSERT_EQ(hinted.Set(HintAt(truth, robot, 0.5, -0.5, 8 * kDeg)), "");
  const GraphMatch right = hinted.Match(matcher, s.graph);
  std::string why;
  EXPECT_EQ(right.status, MatchStatus::kUnique);
  EXPECT_TRUE(MatchIsCorrect(right, s, &why)) << why;
  EXPECT_EQ(right.hint.rfind("in force", 0), 0u) << right.hint;
  EXPECT_TRUE(hinted.InForce());

  // In the twin half: the evidence cannot tell, the hint decides (the twin's pose, UNIQUE).
  ASSERT_EQ(hinted.Set(HintAt(twin, robot, -0.5, 0.3, -5 * kDeg)), "");
  const GraphMatch other = hinted.Match(matcher, s.graph);
  EXPECT_EQ(other.status, MatchStatus::kUnique);
  EXPECT_LT((PlanarPose(other.bim_T_map).t - twin.t).norm(), 0.3);
  EXPECT_FALSE(MatchIsCorrect(other, s));

  // Outside the building: nothing inside the gate (NONE), said so; the hint holds (the
  // evidence alone names no pose that contradicts it). (8 m off, the corner proposals still
  // find AMBIGUOUS places inside the gate in this building of repeated rooms.)
  ASSERT_EQ(hinted.Set(HintAt(truth, robot, 40.0, 40.0, 0.0)), "");
  const GraphMatch nowhere = hinted.Match(matcher, s.graph);
  EXPECT_EQ(nowhere.status, MatchStatus::kNone);
  bool said = false;
  for (const auto& w : nowhere.warnings) said = said || w.find("inside the pose hint") != w.npos;
  EXPECT_TRUE(said) << ToString(nowhere.status) << " " << nowhere.hypotheses << " "
                    << (nowhere.warnings.empty() ? "" : nowhere.warnings[0]);
  EXPECT_TRUE(hinted.InForce());

  // Cleared: as without it.
  hinted.Clear();
  EXPECT_EQ(hinted.Match(matcher, s.graph).status, MatchStatus::kAmbiguous);

  // SetStorey (the set_storey service): hypotheses on other storeys are left out.
  matcher.SetStorey(free.storey);
  EXPECT_EQ(matcher.Match(s.graph).status, MatchStatus::kAmbiguous);
  matcher.SetStorey(free.storey + 1);  // a storey the twins are not on
  const GraphMatch elsewhere = matcher.Match(s.graph);
  EXPECT_NE(elsewhere.status, MatchStatus::kUnique);
  EXPECT_TRUE(elsewhere.room_pairs.empty());
  matcher.SetStorey(-1);
  EXPECT_EQ(matcher.Match(s.graph).status, MatchStatus::kAmbiguous);
}

TEST(PoseHint, AHintNeverMakesAPoseTheChecksDoNotAccept) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("symmetric.ifc"));
  const SyntheticSGraph s = SymmetricTwins(*g);
  HintedMatching hinted;
  ASSERT_EQ(hinted.Set(HintAt(PlanarPose(s.bim_T_map), {}, 0.0, 0.0, 0.0)), "");
  GraphMatcher plain;
  plain.SetAGraph(*g);
  ASSERT_EQ(hinted.Match(plain, s.graph).status, MatchStatus::kUnique);
  // A room answer must pair min_matched_rooms rooms (the corner proposals, which do not count
  // rooms, off): more than the S-Graph has, and the hint inside the truth's gate makes no
  // UNIQUE answer.
  MatcherConfig strict;
  strict.min_matched_rooms = 12;
  strict.proposals = false;
  GraphMatcher matcher(strict);
  matcher.SetAGraph(*g);
  const GraphMatch m = hinted.Match(matcher, s.graph);
  EXPECT_NE(m.status, MatchStatus::kUnique);
  EXPECT_TRUE(hinted.InForce());
}

TEST(PoseHint, AHintTheEvidenceContradictsIsRejectedAndChangesNothing) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("office.ifc"));
  auto c = Noisy(3, 0.9, 5.0, -12.0);
  for (const char* n : {"Corridor", "113", "Meeting"}) c.rooms.push_back(RoomByName(*g, n));
  const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
  GraphMatcher plain;
  plain.SetAGraph(*g);
  const GraphMatch without = plain.Match(s.graph);
  ASSERT_EQ(without.status, MatchStatus::kUnique);

  GraphMatcher matcher;
  matcher.SetAGraph(*g);
  HintedMatching hinted;
  const Pose2 robot{-1.0, {1.0, 0.5}};
  ASSERT_EQ(hinted.Set(HintAt(PlanarPose(s.bim_T_map), robot, 10.0, 0.0, 0.0)), "");
  const GraphMatch m = hinted.Match(matcher, s.graph);
  EXPECT_EQ(m.status, MatchStatus::kUnique);
  EXPECT_TRUE(m.bim_T_map.isApprox(without.bim_T_map, 1e-9)) << "as without the hint";
  EXPECT_EQ(m.hint.rfind("rejected", 0), 0u) << m.hint;
  bool warned = false;
  for (const auto& w : m.warnings)
    warned = warned || (w.find("pose hint rejected") != w.npos && w.find("sigma") != w.npos);
  EXPECT_TRUE(warned);
  EXPECT_FALSE(hinted.InForce());

  // Where the evidence agrees, the hint stays in force and changes nothing.
  ASSERT_EQ(hinted.Set(HintAt(PlanarPose(s.bim_T_map), robot, 0.3, 0.0, 0.0)), "");
  const GraphMatch agrees = hinted.Match(matcher, s.graph);
  EXPECT_TRUE(agrees.bim_T_map.isApprox(without.bim_T_map, 1e-9));
  EXPECT_EQ(agrees.hint.rfind("in force", 0), 0u);
  EXPECT_TRUE(hinted.InForce());
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
