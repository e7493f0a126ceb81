// The certified scan search (scan_search.h) on the project's real office (the synthetic
// buildings: test_matching_scan_search.cpp): the truth in the set, the
// set's certificate (no pose outside it scores within the margin of the best), twins kept
// together, and every way it declines to answer.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/pose_hint.h"
#include "is_graphs/matching/scan_search.h"
#include "is_graphs/matching/synthetic_first_view.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

const agraph::AGraph* Office() {
  std::string why;
  return testing::LoadBuildingOnce(testing::ProjectBim("office.ifc"), &why);
}

/// The slice of `view`'s keyframe in M.
std::vector<Eigen::Vector2d> SliceInMap(const SyntheticSGraph& view) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& k : view.graph.keyframes)
    for (const auto& p : k.slice) out.push_back((k.pose * p.cast<double>()).head<2>());
  return out;
}

Pose2 Truth(const SyntheticSGraph& view) { return PlanarPose(view.bim_T_map); }

bool Near(const Pose2& a, const Pose2& b, const std::vector<Eigen::Vector2d>& points, double m) {
  if (std::abs(std::remainder(a.yaw - b.yaw, 2.0 * M_PI)) > 2.0 * M_PI / 180.0) return false;
  for (const auto& p : points)
    if ((a.Apply(p) - b.Apply(p)).norm() > m) return false;
  return true;
}

/// A view from the office's room `name` under a fixed motion, noise 0.02 m.
SyntheticSGraph OfficeView(const agraph::AGraph& g, const std::string& name, std::uint64_t seed) {
  FirstViewConfig c;
  c.room = testing::RoomByName(g, name);
  c.bim_T_map = Eigen::Translation3d(-31.0, 12.5, 0.0) *
                Eigen::AngleAxisd(137.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ());
  c.seed = seed;
  return MakeFirstView(g, c);
}

TEST(ScanSearch, TheTruthIsInTheSetAndTheSetIsCertified) {
  const agraph::AGraph* g = Office();
  if (!g) GTEST_SKIP() << "office.ifc could not be loaded";
  const ScanSearch search(*g, ScanSearchConfig{});
  const SyntheticSGraph view = OfficeView(*g, "101", 3);
  ASSERT_FALSE(view.graph.keyframes.empty());
  const auto points = SliceInMap(view);
  const int storey = g->rooms[testing::RoomByName(*g, "101")].storey;
  const ScanSearchResult r = search.Search(points, storey);
  ASSERT_EQ(r.status, ScanSearchResult::Status::kOk) << r.reason;
  ASSERT_FALSE(r.set.empty());
  std::cout << "[ scan search ] office 101: " << r.set.size() << " poses, best " << r.best << ", "
            << r.nodes << " nodes, " << r.milliseconds << " ms" << std::endl;
  const std::vector<Eigen::Vector2d> probe = {points.front(), points[points.size() / 2]};
  bool truth_in = false;
  for (const ScanPose& p : r.set) {
    truth_in = truth_in || Near(p.bim_T_map, Truth(view), probe, 0.15);
    EXPECT_GE(p.score, r.best - r.margin - 1e-9);
  }
  EXPECT_TRUE(truth_in) << "the truth is not in the set";
  EXPECT_GE(search.Score(points, Truth(view), storey), r.best - r.margin);
  // The certificate: poses far from every pose of the set score below best - margin (a
  // continuous pose's cells round differently from the search's lattice: 0.01 of slack).
  const std::uint64_t seed = testing::CampaignSeed(7);
  std::cout << "[ scan search ] certificate probes, seed " << seed << std::endl;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int probes = 0;
  for (int k = 0; k < 3000; ++k) {
    Pose2 p = Truth(view);
    p.yaw += 2.0 * M_PI * unit(rng);
    p.t += Eigen::Vector2d(60.0 * unit(rng) - 30.0, 60.0 * unit(rng) - 30.0);
    bool near_set = false;
    for (const ScanPose& s : r.set) near_set = near_set || Near(s.bim_T_map, p, probe, 1.0);
    if (near_set) continue;
    ++probes;
    EXPECT_LT(search.Score(points, p, storey), r.best - r.margin + 0.01)
        << "a pose outside the set scores within the margin";
  }
  EXPECT_GT(probes, 2000);
}

TEST(ScanSearch, KeepsBothTwinsOfABuildingRepeatedUnderAHalfTurn) {
  const agraph::AGraph* office = Office();
  if (!office) GTEST_SKIP() << "office.ifc could not be loaded";
  // The office and its copy turned by 180 deg about (50, 0): two units the scans cannot tell.
  agraph::AGraph g = *office;
  const Eigen::Rotation2Dd half(M_PI);
  const Eigen::Vector2d pivot(50.0, 0.0);
  const size_t n = g.surfaces.size();
  for (size_t i = 0; i < n; ++i) {
    agraph::WallSurface s = g.surfaces[i];
    s.id = static_cast<int>(g.surfaces.size());
    s.start = pivot + half * (s.start - pivot);
    s.end = pivot + half * (s.end - pivot);
    g.surfaces.push_back(s);
  }
  const ScanSearch search(g, ScanSearchConfig{});
  const SyntheticSGraph view = OfficeView(*office, "101", 3);  // seen in the original unit
  const auto points = SliceInMap(view);
  const int storey = office->rooms[testing::RoomByName(*office, "101")].storey;
  const ScanSearchResult r = search.Search(points, storey);
  ASSERT_EQ(r.status, ScanSearchResult::Status::kOk) << r.reason;
  Pose2 twin = Truth(view);
  twin.yaw += M_PI;
  twin.t = pivot + half * (twin.t - pivot);
  const std::vector<Eigen::Vector2d> probe = {points.front(), points[points.size() / 2]};
  bool truth_in = false, twin_in = false;
  for (const ScanPose& p : r.set) {
    truth_in = truth_in || Near(p.bim_T_map, Truth(view), probe, 0.15);
    twin_in = twin_in || Near(p.bim_T_map, twin, probe, 0.15);
  }
  EXPECT_TRUE(truth_in);
  EXPECT_TRUE(twin_in) << "the twin unit's pose is missing from the set";
  // A set bound of one: too many to decide on, never a guess.
  ScanSearchConfig one;
  one.max_set = 1;
  const ScanSearchResult t = ScanSearch(g, one).Search(points, storey);
  EXPECT_EQ(t.status, ScanSearchResult::Status::kTooMany);
  EXPECT_TRUE(t.set.empty());
  EXPECT_NE(t.reason.find("> max_set 1"), std::string::npos) << t.reason;
}

TEST(ScanSearch, DeclinesWithAReason) {
  const agraph::AGraph* office = Office();
  if (!office) GTEST_SKIP() << "office.ifc could not be loaded";
  const int storey = office->rooms.front().storey;
  // Walls lower than the slice: no wall in the grid.
  agraph::AGraph low = *office;
  for (auto& s : low.surfaces) s.z_max = s.z_min + 0.5;
  const ScanSearchResult none = ScanSearch(low, ScanSearchConfig{}).Search({{0.0, 0.0}}, storey);
  EXPECT_EQ(none.status, ScanSearchResult::Status::kNoWalls);
  EXPECT_NE(none.reason.find("no wall-surface"), std::string::npos) << none.reason;
  // Too few points.
  const ScanSearch search(*office, ScanSearchConfig{});
  const ScanSearchResult few = search.Search({{0.0, 0.0}, {1.0, 0.0}, {2.0, 0.0}}, storey);
  EXPECT_EQ(few.status, ScanSearchResult::Status::kTooFewPoints);
  EXPECT_NE(few.reason.find("< min_points"), std::string::npos) << few.reason;
  EXPECT_FALSE(search.HasWalls(99));
  EXPECT_EQ(search.Search({{0.0, 0.0}}, 99).status, ScanSearchResult::Status::kNoWalls);
  // Bad configuration values are named.
  EXPECT_TRUE(ScanSearchConfig{}.Validate().empty());
  ScanSearchConfig bad;
  bad.margin = -0.1;
  EXPECT_NE(bad.Validate().find("scan_search_margin"), std::string::npos) << bad.Validate();
  bad = ScanSearchConfig{};
  bad.resolution = 0.0;
  EXPECT_NE(bad.Validate().find("scan_search_resolution"), std::string::npos);
  bad = ScanSearchConfig{};
  bad.band_high = bad.band_low;
  EXPECT_NE(bad.Validate().find("scan_search_band"), std::string::npos);
  MatcherConfig matcher;
  matcher.scan_search.max_set = 0;
  EXPECT_NE(matcher.Validate().find("scan_search_max_set"), std::string::npos);
}

TEST(ScanSearch, IsDeterministic) {
  const agraph::AGraph* g = Office();
  if (!g) GTEST_SKIP() << "office.ifc could not be loaded";
  const ScanSearch search(*g, ScanSearchConfig{});
  const SyntheticSGraph view = OfficeView(*g, "Corridor", 5);
  ASSERT_FALSE(view.graph.keyframes.empty());
  const auto points = SliceInMap(view);
  const int storey = g->rooms.front().storey;
  const ScanSearchResult a = search.Search(points, storey), b = search.Search(points, storey);
  ASSERT_EQ(a.set.size(), b.set.size());
  EXPECT_EQ(a.nodes, b.nodes);
  for (size_t i = 0; i < a.set.size(); ++i) {
    EXPECT_EQ(a.set[i].score, b.set[i].score);
    EXPECT_EQ(a.set[i].bim_T_map.t, b.set[i].bim_T_map.t);
    EXPECT_EQ(a.set[i].bim_T_map.yaw, b.set[i].bim_T_map.yaw);
  }
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
