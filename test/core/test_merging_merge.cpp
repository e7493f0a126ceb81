// The merge on synthetic graphs: an S-Graph made from the A-Graph under a known B_x_M (with
// keyframes observing its planes), merged with the true match; B_x_M recovered, wrong matches and
// contradictions detected; the localization state's bookkeeping; the config's validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "is_graphs/merging/carried_match.h"
#include "is_graphs/merging/consistency_check.h"
#include "is_graphs/merging/merge_state.h"
#include "is_graphs/merging/merger.h"
#include "is_graphs/merging/recent_evidence.h"
#include "is_graphs/sgraph/plane_fit.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The synthetic S-Graph with a keyframe at each room centre (chained by exact odometry) that
// observes the room's planes exactly, and a floor 0.5 m below M's origin in B's storey.
struct SyntheticCase {
  matching::SyntheticSGraph s;
  matching::GraphMatch match;
};

SyntheticCase MakeCase(const agraph::AGraph& building, const Eigen::Isometry3d& bim_T_map,
                       double noise, std::uint64_t seed = 7) {
  matching::SyntheticSGraphConfig config;
  config.bim_T_map = bim_T_map;
  config.normal_noise_deg = noise > 0 ? 0.3 : 0.0;
  config.offset_noise = noise;
  config.centre_noise = noise;
  config.seed = seed;
  SyntheticCase c;
  c.s = matching::MakeSyntheticSGraph(building, config);
  sgraph::SGraph& g = c.s.graph;
  int previous = -1;
  Eigen::Isometry3d previous_pose = Eigen::Isometry3d::Identity();
  for (const auto& room : g.rooms) {
    sgraph::Keyframe k;
    k.id = static_cast<int>(g.keyframes.size());
    k.stamp = k.id;
    k.pose = geometry::IsometryFromXYYaw(room.center.x(), room.center.y(), 0.3 * k.id, 0.0);
    k.odom_pose = k.pose;
    k.previous = previous;
    if (previous >= 0) k.relative_odom = previous_pose.inverse() * k.pose;
    k.odom_information = Eigen::Matrix<double, 6, 6>::Identity() * 1e4;
    for (int plane_id : room.planes) {
      for (const auto& p : g.planes) {
        if (p.id != plane_id) continue;
        sgraph::PlaneObservation o;
        o.keyframe = k.id;
        o.plane = p.id;
        o.local = p.plane.Transformed(k.pose.inverse());
        o.information = Eigen::Matrix3d::Identity() * 1e4;
        g.observations.push_back(o);
      }
    }
    previous = k.id;
    previous_pose = k.pose;
    g.keyframes.push_back(k);
  }
  sgraph::Floor floor;
  floor.height = building.storeys.front().elevation - bim_T_map.translation().z();
  for (const auto& r : g.rooms) floor.rooms.push_back(r.id);
  g.floors.push_back(floor);

  c.match.status = matching::MatchStatus::kUnique;
  c.match.a_graph_sha256 = building.source.sha256;
  for (const auto& [s, a] : c.s.room_truth) c.match.room_pairs.push_back({a, s, 1.0});
  for (const auto& [s, a] : c.s.plane_truth) c.match.surface_pairs.push_back({a, s, 1.0});
  // The matcher's guess: off by 0.2 m and 2°.
  c.match.bim_T_map = geometry::IsometryFromXYYaw(bim_T_map.translation().x() + 0.2,
                                                  bim_T_map.translation().y() - 0.1,
                                                  geometry::Yaw(bim_T_map) + 2.0 * kDeg, 0.0);
  return c;
}

agraph::AGraph TwoRooms() {
  auto loaded = agraph::LoadAGraph(testing::TwoRoomsPath());
  EXPECT_TRUE(loaded.ok()) << loaded.error();
  return loaded.value();
}

void ExpectRecovered(const MergeOutput& out, const Eigen::Isometry3d& truth, double tolerance_m,
                     double tolerance_deg) {
  ASSERT_TRUE(out.merged) << out.message;
  const Eigen::Vector3d xi = geometry::ToXYYaw(out.bim_T_map);
  EXPECT_NEAR(xi.x(), truth.translation().x(), tolerance_m);
  EXPECT_NEAR(xi.y(), truth.translation().y(), tolerance_m);
  EXPECT_NEAR(out.bim_T_map.translation().z(), truth.translation().z(), 1e-9);
  EXPECT_LT(std::abs(geometry::NormalizeAngle(xi.z() - geometry::Yaw(truth))) / kDeg,
            tolerance_deg);
}

TEST(Merge, RecoversAKnownTransformExactly) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  const SyntheticCase c = MakeCase(building, truth, 0.0);
  ASSERT_GE(c.match.room_pairs.size(), 2u);
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(out.event, MergeEvent::kLocalized) << out.message;
  ExpectRecovered(out, truth, 1e-3, 0.05);
  EXPECT_TRUE(out.solution.covariance_ok);
  EXPECT_GT(out.covariance(0, 0), 0.0);
  // (σ_x grows a little when the walls may deviate: 0.051 m with a 5 cm prior.)
  EXPECT_LT(std::sqrt(out.covariance(0, 0)), 0.06);
  EXPECT_LT(std::sqrt(out.covariance(2, 2)) / kDeg, 1.0);
  EXPECT_TRUE(out.consistency.consistent) << out.consistency.message;
  // With no drift, B <- odom puts the newest keyframe's odometry pose where B_x_M puts it.
  const sgraph::Keyframe& newest = c.s.graph.keyframes.back();
  EXPECT_LT(((out.bim_T_odom * newest.odom_pose).matrix() - (truth * newest.pose).matrix()).norm(),
            1e-3);
  // The next revision keeps the merge.
  const MergeOutput again = merger.OnSGraph(c.s.graph);
  EXPECT_EQ(again.event, MergeEvent::kUpdated) << again.message;
  ExpectRecovered(again, truth, 1e-3, 0.05);
}

// A polygonal room's centre is the centroid of the part seen (a corridor's T-junction pulls it
// into the crossing corridor): the S-Graph publishes a looser information on it, and the merge
// weighs the room-centre match by it. The same 0.3 m error pulls B_x_M far less then.
TEST(Merge, ALooseRoomCentreBarelyPullsTheTransform) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  ASSERT_FALSE(c.s.graph.rooms.empty());
  sgraph::Room& room = c.s.graph.rooms.front();
  room.center.head<2>() += Eigen::Vector2d(0.3, 0.0);
  auto error = [&](double centre_sigma) {
    room.information = Eigen::Matrix3d::Identity() / (centre_sigma * centre_sigma);
    Merger merger{MergerConfig()};
    EXPECT_EQ(merger.SetAGraph(building), "");
    const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
    EXPECT_TRUE(out.merged) << out.message;
    return (out.bim_T_map.translation() - truth.translation()).head<2>().norm();
  };
  const double tight = error(0.1), loose = error(1.0);
  std::printf("B_x_M error: centre sigma 0.1 m %.4f m, 1.0 m %.4f m\n", tight, loose);
  EXPECT_GT(tight, 0.004);
  EXPECT_LT(loose, 0.25 * tight);
  // An information that is not set (zeros, as in a message without it) is the merge's room_sigma.
  EXPECT_NEAR(error(std::numeric_limits<double>::infinity()), error(MergerConfig().room_sigma),
              1e-9);
}

TEST(Merge, RecoversAKnownTransformWithoutOptimizingTheSGraph) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(-7.0, 1.5, -120.0 * kDeg, 0.5);
  const SyntheticCase c = MakeCase(building, truth, 0.0);
  MergerConfig config;
  config.optimize_sgraph = false;
  Merger merger(config);
  ASSERT_EQ(merger.SetAGraph(building), "");
  // The rooms' centres leave a residual (cost 0.026) even here; with walls free to deviate a
  // little it moves B_x_M by 1.5 mm, so 2 mm.
  ExpectRecovered(merger.OnMatch(c.match, c.s.graph), truth, 2e-3, 0.05);
}

TEST(Merge, RecoversAKnownTransformFromNoisyGraphs) {
  const agraph::AGraph building = TwoRooms();
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Eigen::Isometry3d truth =
        geometry::IsometryFromXYYaw(1.0 * seed, -0.5 * seed, 25.0 * seed * kDeg, 0.5);
    const SyntheticCase c = MakeCase(building, truth, 0.02, seed);
    Merger merger{MergerConfig()};
    ASSERT_EQ(merger.SetAGraph(building), "");
    const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
    EXPECT_EQ(out.event, MergeEvent::kLocalized) << out.message;
    ExpectRecovered(out, truth, 0.05, 0.5);
  }
}

TEST(Merge, RecoversAKnownTransformInAProjectBuilding) {
  std::string why;
  const agraph::AGraph* building =
      testing::LoadBuildingOnce(testing::ProjectBim("rotated.ifc"), &why);
  if (!building) GTEST_SKIP() << why;
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(12.0, 4.0, 200.0 * kDeg, 0.5);
  const SyntheticCase c = MakeCase(*building, truth, 0.0);
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(*building), "");
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(out.event, MergeEvent::kLocalized) << out.message;
  ExpectRecovered(out, truth, 1e-3, 0.05);
}

TEST(Merge, AWindowHoldsTheOlderKeyframesAsPublished) {
  std::string why;
  const agraph::AGraph* building =
      testing::LoadBuildingOnce(testing::ProjectBim("rotated.ifc"), &why);
  if (!building) GTEST_SKIP() << why;
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(-3.0, 6.0, 75.0 * kDeg, 0.5);
  const SyntheticCase c = MakeCase(*building, truth, 0.02, 11);
  const auto& keyframes = c.s.graph.keyframes;
  ASSERT_GE(keyframes.size(), 5u);
  const int window = 2;
  const size_t held = keyframes.size() - window;
  // The largest move of keyframes [1, held) from their published poses (0 is the gauge).
  auto moved_most = [&](const MergeOutput& out) {
    double most = 0.0;
    for (size_t i = 1; i < held; ++i)
      most = std::max(
          most, (out.solution.keyframes.at(keyframes[i].id).matrix() - keyframes[i].pose.matrix())
                    .norm());
    return most;
  };
  MergerConfig config;
  config.window_keyframes = window;
  Merger windowed(config);
  ASSERT_EQ(windowed.SetAGraph(*building), "");
  const MergeOutput out = windowed.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(out.event, MergeEvent::kLocalized) << out.message;
  ExpectRecovered(out, truth, 0.05, 0.5);
  EXPECT_LT(moved_most(out), 1e-12);  // as published, up to the quaternion normalization
  // The newest keyframes still move with B_x_M (the noise is corrected there).
  EXPECT_GT(
      (out.solution.keyframes.at(keyframes.back().id).matrix() - keyframes.back().pose.matrix())
          .norm(),
      1e-6);
  // Without the window the same keyframes move: the window is what held them.
  config.window_keyframes = 0;
  Merger all(config);
  ASSERT_EQ(all.SetAGraph(*building), "");
  const MergeOutput free = all.OnMatch(c.match, c.s.graph);
  ExpectRecovered(free, truth, 0.05, 0.5);
  EXPECT_GT(moved_most(free), 1e-6);
}

TEST(Merge, AWrongMatchIsRejected) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  ASSERT_EQ(c.match.room_pairs.size(), 2u);
  // Swap the rooms, and pair every plane with a surface of the other room.
  std::swap(c.match.room_pairs[0].a_id, c.match.room_pairs[1].a_id);
  std::mt19937 rng(3);
  for (auto& p : c.match.surface_pairs) p.a_id = static_cast<int>(rng() % building.surfaces.size());
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(out.event, MergeEvent::kRejected) << out.message;
  EXPECT_FALSE(out.merged);
  EXPECT_FALSE(merger.merged());
}

TEST(Merge, AContradictingUniqueMatchDropsTheMerge) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  ASSERT_TRUE(merger.OnMatch(c.match, c.s.graph).merged);
  c.match.bim_T_map = geometry::IsometryFromXYYaw(5.0, -2.0, 40.0 * kDeg, 0.0);  // 2 m away
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(out.event, MergeEvent::kLost) << out.message;
  EXPECT_FALSE(merger.merged());
}

TEST(Merge, AKidnappedRobotsGraphDropsTheMerge) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  ASSERT_TRUE(merger.OnMatch(c.match, c.s.graph).merged);
  // The second room (and what the robot sees in it) now lies 1.5 m off: what a robot carried
  // elsewhere would map. Its pairs no longer fit the merge.
  sgraph::SGraph moved = c.s.graph;
  const Eigen::Isometry3d shift = geometry::IsometryFromXYYaw(1.5, 0.0, 0.0, 0.0);
  sgraph::Room& room = moved.rooms.back();
  room.center = shift * room.center;
  for (auto& p : moved.planes)
    if (std::count(room.planes.begin(), room.planes.end(), p.id))
      p.plane = p.plane.Transformed(shift);
  for (auto& k : moved.keyframes)
    if (k.id == static_cast<int>(moved.keyframes.size()) - 1) k.pose = shift * k.pose;
  const MergeOutput out = merger.OnSGraph(moved);
  EXPECT_EQ(out.event, MergeEvent::kLost) << out.message;
}

TEST(Merge, BimToOdomFollowsTheOdometryFrameOfTheMergedRevision) {
  // The odometry frame is offset from M (the S-Graph corrected drift): B <- odom must put each
  // keyframe's odometry pose where B_x_M puts its pose in M, whatever map -> odom is.
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(-1.0, 4.0, -70.0 * kDeg, 0.0);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  const Eigen::Isometry3d odom_T_map = geometry::IsometryFromXYYaw(0.7, -0.3, 3.0 * kDeg, 0.0);
  for (auto& k : c.s.graph.keyframes) k.odom_pose = odom_T_map * k.pose;
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  ASSERT_TRUE(out.merged) << out.message;
  for (const auto& k : c.s.graph.keyframes)
    EXPECT_LT(((out.bim_T_odom * k.odom_pose).matrix() - (truth * k.pose).matrix()).norm(), 2e-3)
        << "keyframe " << k.id;
}

TEST(Merge, BimToOdomPutsTheNewestKeyframeAtItsHeightUnderATiltedOdometry) {
  // Odometry's frame is tilted 0.5 deg from M's about y and its origin 30 m away (a long walk
  // with a little roll/pitch left between the S-Graph and odometry). B <- odom is gravity-aligned
  // (yaw only), so it cannot hold the tilt: it must lose it at the newest keyframe, not carry it
  // over the 30 m lever arm into z (0.26 m; AC11's second floor showed it).
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(-1.0, 4.0, 20.0 * kDeg, 6.0);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  Eigen::Isometry3d odom_T_map = geometry::IsometryFromXYYaw(30.0, 0.0, 0.0, 0.0);
  odom_T_map.linear() = Eigen::AngleAxisd(0.5 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (auto& k : c.s.graph.keyframes) k.odom_pose = odom_T_map * k.pose;
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  ASSERT_TRUE(out.merged) << out.message;
  const sgraph::Keyframe& newest = c.s.graph.keyframes.back();
  const Eigen::Vector3d at = (out.bim_T_odom * newest.odom_pose).translation();
  const Eigen::Vector3d want = (truth * newest.pose).translation();
  std::printf("newest keyframe under the tilted odometry: off by %.4f m in z, %.4f m in x-y\n",
              std::abs(at.z() - want.z()), (at - want).head<2>().norm());
  EXPECT_NEAR(at.z(), want.z(), 2e-3);
  EXPECT_LT((at - want).head<2>().norm(), 2e-3);
  EXPECT_NEAR(geometry::Yaw(out.bim_T_odom * newest.odom_pose), geometry::Yaw(truth * newest.pose),
              1e-3);
}

// Issue 22: a merged pose beyond every storey's height (a robot that climbed out of the
// building, or a wrong height in B) comes with a warning naming it.
TEST(Merge, APoseAboveEveryStoreyIsWarnedAbout) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  const MergeOutput inside = merger.OnMatch(c.match, c.s.graph);
  ASSERT_TRUE(inside.merged) << inside.message;
  EXPECT_TRUE(inside.warnings.empty()) << inside.warnings.front();
  // The same walls seen 10 m higher up in M (vertical planes: the observations still hold).
  for (auto& k : c.s.graph.keyframes) {
    k.pose.translation().z() += 10.0;
    k.odom_pose.translation().z() += 10.0;
  }
  const MergeOutput above = merger.OnSGraph(c.s.graph);
  ASSERT_TRUE(above.merged) << above.message;
  ASSERT_EQ(above.warnings.size(), 1u);
  EXPECT_NE(above.warnings.front().find("above every storey"), std::string::npos)
      << above.warnings.front();
}

// `building` with a second storey 3 m up of the same plan (floors of one plan): copies of its
// surfaces, walls and rooms with ids after the originals.
agraph::AGraph StackedTwice(const agraph::AGraph& building) {
  agraph::AGraph out = building;
  agraph::Storey up = building.storeys.front();
  up.id = static_cast<int>(building.storeys.size());
  up.elevation += 3.0;
  up.name = "upstairs";
  out.storeys.push_back(up);
  const int ns = static_cast<int>(building.surfaces.size());
  const int nw = static_cast<int>(building.walls.size());
  const int nr = static_cast<int>(building.rooms.size());
  for (auto s : building.surfaces) {
    s.id += ns, s.storey = up.id, s.z_min += 3.0, s.z_max += 3.0;
    if (s.wall >= 0) s.wall += nw;
    for (int& r : s.rooms) r += nr;
    out.surfaces.push_back(s);
  }
  for (auto w : building.walls) {
    w.id += nw, w.storey = up.id;
    if (w.surface_a >= 0) w.surface_a += ns;
    if (w.surface_b >= 0) w.surface_b += ns;
    out.walls.push_back(w);
  }
  for (auto r : building.rooms) {
    r.id += nr, r.storey = up.id, r.z_min += 3.0, r.z_max += 3.0;
    for (int& x : r.surfaces) x += ns;
    for (int& x : r.walls) x += nw;
    r.doorways.clear();
    out.rooms.push_back(r);
  }
  return out;
}

TEST(Merge, AUniqueMatchOnAnotherStoreyOfOnePlanIsIgnored) {
  // Merged on the ground floor, the robot still there: the same motion matched on the floor of
  // the same plan above (issue 22) must not move the pose to it.
  const agraph::AGraph one = TwoRooms();
  const agraph::AGraph building = StackedTwice(one);
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.0);
  SyntheticCase c = MakeCase(one, truth, 0.0);
  c.match.storey = 0;
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  ASSERT_TRUE(merger.OnMatch(c.match, c.s.graph).merged);
  matching::GraphMatch upstairs = c.match;
  upstairs.storey = 1;
  for (auto& p : upstairs.room_pairs) p.a_id += static_cast<int>(one.rooms.size());
  for (auto& p : upstairs.surface_pairs) p.a_id += static_cast<int>(one.surfaces.size());
  const MergeOutput out = merger.OnMatch(upstairs, c.s.graph);
  EXPECT_TRUE(out.merged) << out.message;
  EXPECT_NE(out.message.find("ignored"), std::string::npos) << out.message;
  ExpectRecovered(out, truth, 1e-3, 0.05);
  EXPECT_NEAR(out.bim_T_map.translation().z(), 0.0, 1e-9) << "still on the ground floor";
  // The same match on the ground floor is taken as usual.
  const MergeOutput again = merger.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(again.event, MergeEvent::kUpdated) << again.message;
  EXPECT_EQ(again.message.find("ignored"), std::string::npos) << again.message;
}

TEST(RecentEvidence, WallsSeenNowMustLieOnTheBim) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(2.0, 1.0, 30.0 * kDeg, 0.0);
  const SyntheticCase c = MakeCase(building, truth, 0.0);
  MergerConfig config;
  config.recent_keyframes = 100;  // every keyframe of the synthetic graph
  MergeSolution solution;
  const Eigen::Vector3d xi = geometry::ToXYYaw(truth);
  solution.bim_x_map = xi;
  const RecentEvidence right = CheckRecentEvidence(building, c.s.graph, solution, config);
  ASSERT_GE(right.planes, config.recent_min_planes) << right.message;
  EXPECT_EQ(right.supported, right.planes) << right.message;
  EXPECT_FALSE(right.contradicts);
  // The same walls put 1.7 m and 20 degrees off (a robot carried elsewhere keeps its old merge).
  solution.bim_x_map = xi + Eigen::Vector3d(1.7, -0.4, 20.0 * kDeg);
  const RecentEvidence wrong = CheckRecentEvidence(building, c.s.graph, solution, config);
  EXPECT_EQ(wrong.planes, right.planes);
  EXPECT_LT(wrong.supported, config.recent_min_support * wrong.planes) << wrong.message;
  EXPECT_TRUE(wrong.contradicts) << wrong.message;
}

TEST(Merge, MatchesForAnotherAGraphAreIgnored) {
  const agraph::AGraph building = TwoRooms();
  SyntheticCase c = MakeCase(building, Eigen::Isometry3d::Identity(), 0.0);
  c.match.a_graph_sha256 = "not-this-one";
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(out.event, MergeEvent::kNone);
  EXPECT_FALSE(out.merged);
}

// A merge carried over a restart of sgraph_node by the odometry: under the carried B_x_M the
// new S-Graph's wall planes are paired with the A-surfaces they lie along, its rooms with the
// A-rooms their centres land in, and the merger's own
// start checks accept it and recover the truth; a motion 1.5 m or 20 deg off pairs too little to
// start (NONE), so a stale carry publishes nothing.
TEST(CarriedMatch, PairsThePlanesUnderTheCarriedMotionAndTheMergerChecksIt) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  SyntheticCase c = MakeCase(building, truth, 0.01);
  // The new S-Graph's map is its odometry frame turned and moved (its own optimization).
  const Eigen::Isometry3d map_T_odom = geometry::IsometryFromXYYaw(0.4, -0.3, 3.0 * kDeg);
  for (auto& k : c.s.graph.keyframes) k.odom_pose = map_T_odom.inverse() * k.pose;
  const Eigen::Isometry3d bim_T_odom = truth * map_T_odom;  // what the last merge knew
  const Eigen::Isometry3d carried = CarriedTransform(bim_T_odom, c.s.graph);
  EXPECT_LT((carried.matrix() - truth.matrix()).norm(), 1e-9);

  const matching::GraphMatch match = CarriedMatch(building, c.s.graph, carried, 0, 4);
  ASSERT_EQ(match.status, matching::MatchStatus::kUnique);
  ASSERT_EQ(match.room_pairs.size(), c.s.room_truth.size());
  for (const auto& p : match.room_pairs) EXPECT_EQ(c.s.room_truth.at(p.s_id), p.a_id);
  int right = 0;
  for (const auto& p : match.surface_pairs) {
    const auto truth_pair = c.s.plane_truth.find(p.s_id);
    ASSERT_NE(truth_pair, c.s.plane_truth.end()) << "S-plane " << p.s_id << " is clutter";
    // A plane along collinear A-surfaces is paired with each: its true one among them.
    right += truth_pair->second == p.a_id;
  }
  EXPECT_GE(right, static_cast<int>(c.s.plane_truth.size()) - 1);
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  ExpectRecovered(merger.OnMatch(match, c.s.graph), truth, 0.02, 0.5);

  for (const Eigen::Isometry3d& off : {geometry::IsometryFromXYYaw(1.5, 0.0, 0.0),
                                       geometry::IsometryFromXYYaw(0.0, 0.0, 20 * kDeg)}) {
    const matching::GraphMatch wrong = CarriedMatch(building, c.s.graph, off * truth, 0, 4);
    EXPECT_EQ(wrong.status, matching::MatchStatus::kNone)
        << wrong.surface_pairs.size() << " pairs under a motion 1.5 m or 20 deg off";
  }
}

TEST(MergeState, TracksTimeAndDistanceToLocalize) {
  MergeState state;
  EXPECT_EQ(state.state(), LocalizationState::kNotLocalized);
  state.AddOdometry(10.0, Eigen::Vector3d(0, 0, 0));
  state.AddOdometry(11.0, Eigen::Vector3d(3, 4, 0.1));
  state.SetLocalized(15.0, "ok");
  EXPECT_TRUE(state.localized());
  EXPECT_DOUBLE_EQ(state.seconds_to_localize(), 5.0);
  EXPECT_DOUBLE_EQ(state.distance_to_localize(), 5.0);
  EXPECT_DOUBLE_EQ(state.localized_since(), 15.0);
  state.AddOdometry(12.0, Eigen::Vector3d(3, 5, 0));
  state.SetLocalized(16.0, "still");
  EXPECT_DOUBLE_EQ(state.localized_since(), 15.0);
  state.SetLost("contradicted");
  EXPECT_EQ(state.state(), LocalizationState::kLost);
  state.SetLocalized(20.0, "again");
  EXPECT_DOUBLE_EQ(state.localized_since(), 20.0);
  EXPECT_DOUBLE_EQ(state.distance_to_localize(), 5.0);  // the first localization's
  state.Reset("new building");
  EXPECT_EQ(state.state(), LocalizationState::kNotLocalized);
  EXPECT_DOUBLE_EQ(state.distance_walked(), 0.0);
}

TEST(MergeState, DegradedKeepsThePoseAndGoesBackWithoutANewLocalization) {
  MergeState state;
  state.SetDegraded("late before localizing");  // nothing to degrade
  EXPECT_EQ(state.state(), LocalizationState::kNotLocalized);
  state.SetLocalized(15.0, "ok");
  state.SetDegraded("no tf map -> odom for 1.2 s");
  EXPECT_EQ(state.state(), LocalizationState::kDegraded);
  EXPECT_TRUE(state.has_pose());
  EXPECT_FALSE(state.localized());
  EXPECT_EQ(state.message(), "no tf map -> odom for 1.2 s");
  state.SetLocalized(17.0, "fresh again");
  EXPECT_EQ(state.state(), LocalizationState::kLocalized);
  EXPECT_DOUBLE_EQ(state.localized_since(), 15.0);
  state.SetDegraded("late");
  state.SetLost("stopped");
  EXPECT_FALSE(state.has_pose());
  state.SetDegraded("late again");
  EXPECT_EQ(state.state(), LocalizationState::kLost);
  EXPECT_STREQ(ToString(LocalizationState::kDegraded), "DEGRADED");
}

// Four surface pairs on the BIM and the one room pair off by 1 m (an S-room redrawn from a
// worse view): a new merge is refused, a merge already made keeps going without that room.
TEST(ConsistencyCheck, ARoomTurningOutlierDropsTheRoomNotTheMerge) {
  MergerConfig config;
  MergeSolution solution;
  solution.usable = true;
  for (int i = 0; i < 4; ++i) {
    PairResidual s;
    s.s_id = i;
    s.angle_deg = 0.2;
    s.offset = 0.01;
    s.chi2 = 1.0;
    s.dof = 2;
    solution.surfaces.push_back(s);
  }
  PairResidual room;
  room.s_id = 7;
  room.distance = 1.0;
  room.chi2 = 50.0;
  room.dof = 2;
  solution.rooms.push_back(room);
  ASSERT_GT(room.distance, config.gate_room);
  const ConsistencyReport start = CheckConsistency(solution, config, true);
  EXPECT_FALSE(start.consistent);
  EXPECT_EQ(start.message.rfind("too few room inliers", 0), 0u) << start.message;
  const ConsistencyReport later = CheckConsistency(solution, config, false);
  EXPECT_TRUE(later.consistent) << later.message;
  EXPECT_EQ(later.outlier_rooms, std::vector<int>{7});
  // Surfaces still decide: with two of them off the BIM too the merge goes.
  solution.surfaces[0].offset = solution.surfaces[1].offset = 0.8;
  EXPECT_FALSE(CheckConsistency(solution, config, false).consistent);
}

// A match from wall planes alone (the matcher's proposals, before any room is closed): the merge
// starts on enough surface inliers, the height of M from the storey of the surfaces.
TEST(Merge, StartsFromSurfacePairsAlone) {
  const agraph::AGraph building = TwoRooms();
  const Eigen::Isometry3d truth = geometry::IsometryFromXYYaw(3.0, -2.0, 40.0 * kDeg, 0.5);
  SyntheticCase c = MakeCase(building, truth, 0.0);
  c.match.room_pairs.clear();
  ASSERT_GE(c.match.surface_pairs.size(), 6u);
  Merger merger{MergerConfig()};
  ASSERT_EQ(merger.SetAGraph(building), "");
  const MergeOutput out = merger.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(out.event, MergeEvent::kLocalized) << out.message;
  ExpectRecovered(out, truth, 1e-3, 0.05);
  // Too few of them: refused, naming why.
  MergerConfig strict;
  strict.min_surface_inliers_without_rooms = static_cast<int>(c.match.surface_pairs.size()) + 1;
  Merger refusing{strict};
  ASSERT_EQ(refusing.SetAGraph(building), "");
  const MergeOutput refused = refusing.OnMatch(c.match, c.s.graph);
  EXPECT_EQ(refused.event, MergeEvent::kRejected);
  EXPECT_NE(refused.message.find("too few surface inliers for a match without rooms"),
            std::string::npos)
      << refused.message;
}

TEST(MergerConfig, ValidateNamesTheField) {
  EXPECT_EQ(MergerConfig().Validate(), "");
  MergerConfig c;
  c.room_sigma = -1.0;
  EXPECT_EQ(c.Validate().rfind("room_sigma", 0), 0u) << c.Validate();
  c = MergerConfig();
  c.min_inlier_fraction = 1.5;
  EXPECT_EQ(c.Validate().rfind("min_inlier_fraction", 0), 0u);
  c = MergerConfig();
  c.max_iterations = 0;
  EXPECT_EQ(c.Validate().rfind("max_iterations", 0), 0u);
  for (double bad : {0.0, -1e-5, 1.0, std::nan("")}) {
    c = MergerConfig();
    c.function_tolerance = bad;
    EXPECT_EQ(c.Validate().rfind("function_tolerance", 0), 0u) << bad;
  }
  c = MergerConfig();
  c.window_keyframes = -1;
  EXPECT_EQ(c.Validate().rfind("window_keyframes", 0), 0u) << c.Validate();
  c = MergerConfig();
  c.min_surface_inliers_without_rooms = -1;
  EXPECT_EQ(c.Validate().rfind("min_surface_inliers_without_rooms", 0), 0u) << c.Validate();
  // A deviation prior steeper than a match can pull: no wall could ever leave the plan.
  c = MergerConfig();
  c.wall_deviation_offset_sigma = 0.02;
  EXPECT_EQ(c.Validate().rfind("wall_deviation_offset_sigma", 0), 0u) << c.Validate();
  c.estimate_wall_deviations = false;
  EXPECT_EQ(c.Validate(), "");
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
