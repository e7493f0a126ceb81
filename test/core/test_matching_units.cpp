// Unit tests of the matcher's parts: config, rigid fit, pairwise consistency, descriptors,
// local candidates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/candidate_graph.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/pairwise_consistency.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/matching/room_descriptor.h"

namespace is_graphs {
namespace matching {
namespace {

const double kDeg = M_PI / 180.0;

/// A rectangular room [x0, x1] × [y0, y1] as a descriptor (normals pointing inside).
RoomDescriptor Rectangle(double x0, double y0, double x1, double y1, const Pose2& pose = {},
                         bool mirror = false) {
  RoomDescriptor r;
  const Eigen::Vector2d c(0.5 * (x0 + x1), 0.5 * (y0 + y1));
  const std::pair<Eigen::Vector2d, double> faces[] = {
      {{1, 0}, x0}, {{-1, 0}, -x1}, {{0, 1}, y0}, {{0, -1}, -y1}};
  int id = 0;
  for (const auto& [n0, d0] : faces) {
    Eigen::Vector2d n = pose.Rotate(n0);
    double d = d0 + n.dot(pose.t);
    if (mirror) n.x() = -n.x();
    PlaneFeature f;
    f.id = id++;
    f.normal = n;
    f.d = d;
    r.planes.push_back(f);
  }
  r.centre = pose.Apply(c);
  if (mirror) r.centre.x() = -r.centre.x();
  for (auto& f : r.planes) f.r = f.normal.dot(r.centre) - f.d;
  r.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return r;
}

TEST(MatcherConfig, DefaultsAreValidAndBadValuesNamed) {
  MatcherConfig config;
  EXPECT_EQ(config.Validate(), "");
  config.offset_tolerance = -1.0;
  EXPECT_NE(config.Validate().find("offset_tolerance"), std::string::npos);
  config = MatcherConfig{};
  config.ambiguity_margin = std::nan("");
  EXPECT_NE(config.Validate().find("ambiguity_margin"), std::string::npos);
  config = MatcherConfig{};
  config.min_matched_rooms = 0;
  EXPECT_NE(config.Validate().find("min_matched_rooms"), std::string::npos);
}

TEST(RigidFit, RecoversYawAndTranslationFromPlanesAndCentres) {
  const Pose2 truth{0.7, {3.0, -2.0}};
  std::vector<PlaneCorrespondence> planes;
  for (double a : {0.0, 1.2, 2.5}) {
    const Eigen::Vector2d n_s(std::cos(a), std::sin(a));
    const double d_s = 1.0 + a;
    const Eigen::Vector2d n_a = truth.Rotate(n_s);
    planes.push_back({n_s, d_s, n_a, d_s + n_a.dot(truth.t), {5.0, 5.0}});
  }
  const std::vector<PointCorrespondence> points{{{1, 1}, truth.Apply({1, 1}), 0.3},
                                                {{4, 0}, truth.Apply({4, 0}), 0.3}};
  const RigidFit fit = FitYawTranslation(planes, points);
  EXPECT_TRUE(fit.translation_determined);
  EXPECT_TRUE(fit.planes_determine_translation);
  EXPECT_NEAR(fit.pose.yaw, truth.yaw, 1e-9);
  EXPECT_LT((fit.pose.t - truth.t).norm(), 1e-9);
  for (const auto& c : planes) EXPECT_NEAR(PlaneResidual(c, fit.pose), 0.0, 1e-9);
}

TEST(RigidFit, NeverFitsAReflection) {
  // Points mirrored (x -> -x): the best proper motion leaves large residuals.
  std::vector<PointCorrespondence> points;
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(4, 0), Eigen::Vector2d(0, 2)})
    points.push_back({p, Eigen::Vector2d(-p.x(), p.y()), 0.3});
  const RigidFit fit = FitYawTranslation({}, points);
  double worst = 0.0;
  for (const auto& p : points)
    worst = std::max(worst, (fit.pose.Apply(p.s_point) - p.a_point).norm());
  EXPECT_GT(worst, 1.0);
  EXPECT_NEAR(fit.pose.ToIsometry().linear().determinant(), 1.0, 1e-12);
}

TEST(RigidFit, ParallelPlanesLeaveTheAxisOpen) {
  std::vector<PlaneCorrespondence> planes{{{1, 0}, 1.0, {1, 0}, 3.0, {0, 0}},
                                          {{-1, 0}, 1.0, {-1, 0}, -1.0, {0, 0}}};
  const RigidFit fit = FitYawTranslation(planes, {});
  EXPECT_FALSE(fit.planes_determine_translation);
  EXPECT_NEAR(fit.pose.t.x(), 2.0, 1e-9);
}

TEST(PairwiseConsistency, RoomPairsKeepDistanceAndTurn) {
  MatcherConfig config;
  const Pose2 motion{1.0, {2.0, 3.0}};
  RoomCorrespondence a{{0, 0}, motion.Apply({0, 0}), motion.yaw, false, {1, 0}};
  RoomCorrespondence b{{6, 2}, motion.Apply({6, 2}), motion.yaw, false, {1, 0}};
  EXPECT_NEAR(RoomPairConsistency(a, b, config), 1.0, 1e-9);
  // The mirror image keeps the distance (CLIPPER's invariant) but turns the other way.
  RoomCorrespondence b_mirror = b;
  b_mirror.a_centre = motion.Apply({6, -2});
  EXPECT_EQ(RoomPairConsistency(a, b_mirror, config), 0.0);
  // A different yaw is inconsistent too.
  RoomCorrespondence b_turned = b;
  b_turned.yaw += 0.5;
  EXPECT_EQ(RoomPairConsistency(a, b_turned, config), 0.0);
  // A corridor's centre is free along its axis.
  RoomCorrespondence corridor{
      {6, 2}, motion.Apply({9, 2}), motion.yaw, true, motion.Rotate({1, 0})};
  EXPECT_GT(RoomPairConsistency(a, corridor, config), 0.9);
}

// The matcher asks only whether two pairs agree (SurfacePairsAgree, RoomPairsAgree: no exp, no
// atan2); that must be exactly whether their consistency weight is above 0, on any input.
TEST(PairwiseConsistency, AgreeIsWhetherTheWeightIsPositive) {
  const std::uint64_t seed = 20261125;
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), coord(-6.0, 6.0), jitter(-0.4, 0.4);
  auto unit = [](double a) { return Eigen::Vector2d(std::cos(a), std::sin(a)); };
  MatcherConfig config;
  int agree_s = 0, agree_r = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    // Surface pairs: the A side a moved copy of the S side, then disturbed (some far, most near
    // the tolerances, where a shortcut would differ).
    const Pose2 motion{angle(rng), {coord(rng), coord(rng)}};
    const double a1 = angle(rng), a2 = angle(rng);
    const PointNormal s1{{coord(rng), coord(rng)}, unit(a1)},
        s2{{coord(rng), coord(rng)}, unit(a2)};
    const double scale = trial % 3 == 0 ? 1.0 : 0.3;
    const PointNormal t1{motion.Apply(s1.point), unit(a1 + motion.yaw + scale * jitter(rng))};
    const PointNormal t2{motion.Apply(s2.point) + scale * Eigen::Vector2d(jitter(rng), jitter(rng)),
                         unit(a2 + motion.yaw + scale * jitter(rng))};
    const double tol_angle = 0.28, tol_distance = 0.5;
    const bool agree = SurfacePairsAgree(s1, s2, t1, t2, std::cos(tol_angle), tol_distance);
    ASSERT_EQ(agree, SurfacePairConsistency(s1, s2, t1, t2, tol_angle, tol_distance) > 0.0)
        << "surface trial " << trial;
    agree_s += agree;
    // Room pairs likewise.
    RoomCorrespondence i{
        {coord(rng), coord(rng)}, {}, motion.yaw, trial % 5 == 0, unit(angle(rng))};
    i.a_centre = motion.Apply(i.s_centre);
    RoomCorrespondence j{{coord(rng), coord(rng)},
                         {},
                         motion.yaw + scale * jitter(rng),
                         trial % 7 == 0,
                         unit(angle(rng))};
    j.a_centre = motion.Apply(j.s_centre) + 4.0 * scale * Eigen::Vector2d(jitter(rng), jitter(rng));
    const bool agree_rooms = RoomPairsAgree(i, j, config);
    ASSERT_EQ(agree_rooms, RoomPairConsistency(i, j, config) > 0.0) << "room trial " << trial;
    agree_r += agree_rooms;
  }
  // Both answers occur often (the test is not one-sided).
  EXPECT_GT(agree_s, 20000);
  EXPECT_LT(agree_s, 180000);
  EXPECT_GT(agree_r, 20000);
  EXPECT_LT(agree_r, 180000);
}

TEST(PairwiseConsistency, SurfacePairsAreSigned) {
  const PointNormal s1{{1, 0}, {1, 0}}, s2{{0, 1}, {0, 1}};
  const PointNormal a1{{1, 0}, {1, 0}}, a2{{0, 1}, {0, 1}};
  const PointNormal a2_mirror{{0, -1}, {0, -1}};
  EXPECT_NEAR(SurfacePairConsistency(s1, s2, a1, a2, 0.1, 0.2), 1.0, 1e-12);
  EXPECT_EQ(SurfacePairConsistency(s1, s2, a1, a2_mirror, 0.1, 0.2), 0.0);
}

TEST(RoomDescriptor, PolygonDistanceIsSigned) {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_NEAR(SignedDistanceToPolygon(square, {1, 1}), -1.0, 1e-12);
  EXPECT_NEAR(SignedDistanceToPolygon(square, {3, 1}), 1.0, 1e-12);
}

TEST(CandidateGraph, ARectangleHasTwoYawsAndTheRightMotion) {
  MatcherConfig config;
  const std::vector<RoomDescriptor> a_rooms{Rectangle(0, 0, 3, 5), Rectangle(10, 0, 17, 5)};
  const Pose2 map_T_bim{-0.4, {1.0, 2.0}};
  const RoomDescriptor s = Rectangle(0, 0, 3, 5, map_T_bim);
  const auto candidates = GenerateRoomCandidates(s, 0, a_rooms, config);
  ASSERT_EQ(candidates.size(), 2u);  // the 3 × 5 room, upright or turned half a turn
  for (const auto& c : candidates) {
    EXPECT_EQ(c.a_room, 0);
    EXPECT_TRUE(c.full_rank);
    EXPECT_GT(c.quality, 0.95);
  }
  const double true_yaw = -map_T_bim.yaw;
  EXPECT_TRUE(AngleDistance(candidates[0].pose.yaw, true_yaw) < 1e-6 ||
              AngleDistance(candidates[1].pose.yaw, true_yaw) < 1e-6);
}

// A room with one wall built 25 cm off the plan keeps its pair through its other walls: the
// quality is the mean of the planes' Gaussians, so the off wall costs its share (3 + 0.11) / 4;
// a Gaussian of the RMS made it 0.58 and let the whole room sink.
TEST(CandidateGraph, OneWallOffThePlanCostsItsShareOnly) {
  MatcherConfig config;
  const RoomDescriptor a = Rectangle(0, 0, 4, 5);
  const RoomDescriptor s = Rectangle(0, 0, 4.25, 5);  // the east wall 25 cm out
  const auto tol = EvaluationTolerances::From(config);
  const PairEvaluation off = EvaluatePair(s, a, Pose2{}, true, tol);
  ASSERT_TRUE(off.ok);
  EXPECT_EQ(off.surfaces.size(), 4u);
  EXPECT_NEAR(off.rms, 0.125, 1e-9);
  const double g = std::exp(-0.5 * std::pow(0.25 / config.quality_sigma, 2));
  EXPECT_NEAR(off.quality, (3.0 + g) / 4.0, 1e-9);
  EXPECT_GT(off.quality, 0.75);
  // Every wall 10 cm off: each costs the same, as before.
  const RoomDescriptor all_off = Rectangle(-0.1, -0.1, 4.1, 5.1);
  const PairEvaluation uniform = EvaluatePair(all_off, a, Pose2{}, true, tol);
  ASSERT_TRUE(uniform.ok);
  EXPECT_NEAR(uniform.quality, std::exp(-0.5 * std::pow(0.1 / config.quality_sigma, 2)), 1e-9);
}

TEST(CandidateGraph, AMirroredTrapezoidIsNoFullMatch) {
  MatcherConfig config;
  RoomDescriptor trapezoid = Rectangle(0, 0, 4, 4);
  trapezoid.planes[1].normal = Eigen::Vector2d(-1, -0.5).normalized();  // slanted east wall
  trapezoid.planes[1].d = trapezoid.planes[1].normal.dot(Eigen::Vector2d(4, 0));
  for (auto& f : trapezoid.planes) f.r = f.normal.dot(trapezoid.centre) - f.d;
  RoomDescriptor mirrored = trapezoid;
  for (auto& f : mirrored.planes) f.normal.x() = -f.normal.x();
  mirrored.centre.x() = -mirrored.centre.x();
  const auto upright = GenerateRoomCandidates(trapezoid, 0, {trapezoid}, config);
  ASSERT_FALSE(upright.empty());
  EXPECT_GT(upright.front().quality, 0.95);
  // The mirror image can at best pass as a partial view (some walls unexplained).
  for (const auto& c : GenerateRoomCandidates(mirrored, 0, {trapezoid}, config))
    EXPECT_LT(c.quality, 0.8);
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
