// The certified scan-to-BIM search (ScanSearch): a simulated slice found at its true pose from
// any B_x_M, both poses of a building of two identical units kept, the branch-and-bound's bound
// a true upper bound and its best the brute force's, the statuses with their numbers, and the
// certificate (every pose outside the set scores below best - margin).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "is_graphs/matching/scan_grid.h"
#include "is_graphs/matching/scan_search.h"
#include "is_graphs/matching/synthetic_slice.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

/// A storey (id `storey`, at `elevation`) of the given closed polygons' edges as wall-surfaces
/// from z_min to z_max (absolute).
void AddPolygons(agraph::AGraph* g, int storey, const std::vector<Polygon>& polygons,
                 double z_min = 0.0, double z_max = 2.8) {
  for (const Polygon& poly : polygons)
    for (size_t k = 0; k < poly.size(); ++k) {
      const Eigen::Vector2d a = poly[k], b = poly[(k + 1) % poly.size()];
      const Eigen::Vector2d n = Eigen::Vector2d(-(b - a).y(), (b - a).x()).normalized();
      const int id = static_cast<int>(g->surfaces.size());
      g->surfaces.push_back(testing::MakeSurface(id, id, storey, a, b, n));
      g->surfaces.back().z_min = z_min, g->surfaces.back().z_max = z_max;
    }
}

agraph::AGraph Building(const std::vector<Polygon>& polygons) {
  agraph::AGraph g;
  g.storeys.push_back({});
  AddPolygons(&g, 0, polygons);
  return g;
}

// An L-shaped room with a pillar: no turn of it fits itself.
Polygon LRoom(const Pose2& place = {}) {
  Polygon p{{0, 0}, {9, 0}, {9, 3.5}, {4, 3.5}, {4, 6}, {0, 6}};
  for (auto& v : p) v = place.Apply(v);
  return p;
}
Polygon Pillar() { return {{6.5, 1.2}, {7.1, 1.2}, {7.1, 1.8}, {6.5, 1.8}}; }

const Pose2 kTruth{137.0 * M_PI / 180.0, {25.0, -13.0}};
const Pose2 kRobot{0.3, {2.0, 2.0}};

std::vector<Eigen::Vector2d> Slice(const agraph::AGraph& g, const Pose2& truth = kTruth,
                                   std::uint64_t seed = 5) {
  return SimulatedSlice(g, 0, kRobot, truth, 720, 20.0, 0.02, seed);
}

Eigen::Vector2d Centroid(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : points) c += p;
  return c / static_cast<double>(points.size());
}

// Whether `pose` is `truth` within `xy` m at the points' centroid and `yaw` rad.
bool Near(const Pose2& pose, const Pose2& truth, const Eigen::Vector2d& c, double xy, double yaw) {
  return (pose.Apply(c) - truth.Apply(c)).norm() <= xy && AngleDistance(pose.yaw, truth.yaw) <= yaw;
}

TEST(ScanSearch, FindsTheTruthInAnAsymmetricBuilding) {
  const agraph::AGraph g = Building({LRoom(), Pillar()});
  const ScanSearch search(g, {});
  ASSERT_TRUE(search.HasWalls(0));
  const auto points = Slice(g);
  const auto r = search.Search(points, 0);
  ASSERT_EQ(r.status, ScanSearchResult::Status::kOk) << r.reason;
  std::printf("[ ScanSearch ] best %.3f, %zu poses, %ld nodes, %.1f ms\n", r.best, r.set.size(),
              r.nodes, r.milliseconds);
  ASSERT_EQ(r.set.size(), 1u);
  const double step = search.Problem(points, 0)->yaw_step();
  EXPECT_TRUE(Near(r.set[0].bim_T_map, kTruth, Centroid(points), 2 * search.config().resolution,
                   step + 1e-9))
      << "yaw " << r.set[0].bim_T_map.yaw << " t " << r.set[0].bim_T_map.t.transpose();
  EXPECT_DOUBLE_EQ(r.best, r.set[0].score);
  EXPECT_GT(r.best, 0.8);
  EXPECT_DOUBLE_EQ(r.margin, search.config().margin);
  EXPECT_GT(r.nodes, 0);
}

TEST(ScanSearch, KeepsBothPosesOfTwoIdenticalUnits) {
  // Unit B is unit A turned half round about (10.5, 3): x' = 21 - x, y' = 6 - y.
  const Pose2 half{M_PI, {21.0, 6.0}};
  const agraph::AGraph g = Building({LRoom(), LRoom(half)});
  const ScanSearch search(g, {});
  const auto points = Slice(g);
  const auto r = search.Search(points, 0);
  ASSERT_EQ(r.status, ScanSearchResult::Status::kOk) << r.reason;
  ASSERT_EQ(r.set.size(), 2u);
  const Pose2 other{kTruth.yaw + M_PI, half.Apply(kTruth.t)};
  const Eigen::Vector2d c = Centroid(points);
  const double deg = M_PI / 180.0;
  for (const Pose2& truth : {kTruth, other}) {
    int found = 0;
    for (const ScanPose& p : r.set) found += Near(p.bim_T_map, truth, c, 0.1, deg);
    EXPECT_EQ(found, 1) << "truth yaw " << truth.yaw << " t " << truth.t.transpose();
  }
  EXPECT_NEAR(r.set[0].score, r.set[1].score, r.margin);
}

TEST(ScanSearch, TheBoundIsAnUpperBoundAndTheBestIsTheBruteForceBest) {
  ScanSearchConfig config;
  config.resolution = 0.2;
  config.sigma = 0.2;
  config.window_margin = 1.0;
  const agraph::AGraph g = Building({LRoom(), Pillar()});
  const ScanSearch search(g, config);
  const auto points = Slice(g);
  const auto problem = search.Problem(points, 0);
  ASSERT_TRUE(problem);
  const ScanProblem& p = *problem;
  Eigen::Vector2i first, last;
  ASSERT_TRUE(search.TranslationCells(0, &first, &last));

  // Brute force over every leaf of the search's discretization.
  double brute = -1.0;
  for (int yaw = 0; yaw < p.yaw_steps(); ++yaw)
    for (int y = first.y(); y <= last.y(); ++y)
      for (int x = first.x(); x <= last.x(); ++x) brute = std::max(brute, p.Bound({x, y, yaw, 0}));
  const auto r = search.Search(points, 0);
  ASSERT_EQ(r.status, ScanSearchResult::Status::kOk) << r.reason;
  EXPECT_DOUBLE_EQ(r.best, brute);

  // Random nodes, half of them over the truth: the bound is at least every leaf's exact score.
  const std::uint64_t seed = testing::CampaignSeed(2024);
  std::printf("[ ScanSearch ] bound check seed %llu\n", static_cast<unsigned long long>(seed));
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  const Eigen::Vector2d truth_cell = (kTruth.Apply(Centroid(points)) / config.resolution);
  for (int trial = 0; trial < 40; ++trial) {
    const int level = 1 + static_cast<int>(rng() % std::min(4, p.max_level()));
    const int size = 1 << level, yaws = 1 << p.yaw_level(level);
    ScanProblem::Node node;
    node.level = level;
    if (trial % 2 == 0) {
      node.x = static_cast<int>(std::floor(truth_cell.x())) - static_cast<int>(rng() % size);
      node.y = static_cast<int>(std::floor(truth_cell.y())) - static_cast<int>(rng() % size);
      const int yaw = static_cast<int>(std::lround(kTruth.yaw / p.yaw_step())) % p.yaw_steps();
      node.yaw = yaw / yaws * yaws;
    } else {
      node.x = first.x() + static_cast<int>(rng() % (last.x() - first.x() + 1));
      node.y = first.y() + static_cast<int>(rng() % (last.y() - first.y() + 1));
      node.yaw = static_cast<int>(rng() % p.yaw_steps()) / yaws * yaws;
    }
    const double bound = p.Bound(node);
    double best_leaf = 0.0;
    for (int yaw = node.yaw; yaw < std::min(node.yaw + yaws, p.yaw_steps()); ++yaw)
      for (int y = node.y; y < node.y + size; ++y)
        for (int x = node.x; x < node.x + size; ++x) {
          const double exact = search.Score(points, p.LeafPose(x, y, yaw), 0);
          best_leaf = std::max(best_leaf, exact);
          if (x == node.x && y == node.y) {
            EXPECT_NEAR(exact, p.Bound({x, y, yaw, 0}), 1e-12);
          }
        }
    // Cut short against a threshold, still an upper bound.
    EXPECT_GE(p.Bound(node, 0.9), best_leaf) << "trial " << trial;
    EXPECT_GE(bound, best_leaf) << "trial " << trial << " node " << node.x << " " << node.y
                                << " yaw " << node.yaw << " level " << level;
  }
}

TEST(ScanSearch, StatusesSayWhyWithTheirNumbers) {
  // Storey 1 at 3 m: its walls end at 3.5 m, below the band's 3.9 m.
  agraph::AGraph g = Building({LRoom(), Pillar()});
  g.storeys.push_back({});
  g.storeys.back().id = 1, g.storeys.back().elevation = 3.0;
  AddPolygons(&g, 1, {LRoom()}, 3.0, 3.5);
  ScanSearchConfig config;
  const ScanSearch search(g, config);
  EXPECT_FALSE(search.HasWalls(1));
  const auto points = Slice(g);
  auto r = search.Search(points, 1);
  EXPECT_EQ(r.status, ScanSearchResult::Status::kNoWalls);
  EXPECT_NE(r.reason.find("storey 1"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("3.9"), std::string::npos) << r.reason;
  EXPECT_TRUE(r.set.empty());
  EXPECT_EQ(search.Search(points, 7).status, ScanSearchResult::Status::kNoWalls);

  const std::vector<Eigen::Vector2d> few(points.begin(), points.begin() + 30);
  r = search.Search(few, 0);
  EXPECT_EQ(r.status, ScanSearchResult::Status::kTooFewPoints);
  EXPECT_NE(r.reason.find("min_points 60"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("30 given"), std::string::npos) << r.reason;

  // Eight identical 4 m x 3 m rooms in a row: each fits twice (turned half round too).
  std::vector<Polygon> rooms;
  for (int i = 0; i < 8; ++i)
    rooms.push_back({{4.15 * i, 0}, {4.15 * i + 4, 0}, {4.15 * i + 4, 3}, {4.15 * i, 3}});
  const agraph::AGraph row = Building(rooms);
  config.max_set = 4;
  const ScanSearch in_row(row, config);
  const Pose2 robot{0.2, {4.15 * 3 + 1.3, 1.1}};
  r = in_row.Search(SimulatedSlice(row, 0, robot, kTruth, 720, 20.0, 0.02, 9), 0);
  EXPECT_EQ(r.status, ScanSearchResult::Status::kTooMany);
  EXPECT_NE(r.reason.find("16 distinct poses"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("max_set 4"), std::string::npos) << r.reason;
  EXPECT_TRUE(r.set.empty());
  // A margin so wide that most of the storey is within it: the search gives up, it never guesses.
  config.margin = 0.9;
  r = ScanSearch(g, config).Search(points, 0);
  EXPECT_EQ(r.status, ScanSearchResult::Status::kTooMany);
  EXPECT_NE(r.reason.find("gave up after"), std::string::npos) << r.reason;
  config.margin = ScanSearchConfig{}.margin;
  config.max_set = 32;
  r = ScanSearch(row, config).Search(SimulatedSlice(row, 0, robot, kTruth, 720, 20.0, 0.02, 9), 0);
  ASSERT_EQ(r.status, ScanSearchResult::Status::kOk) << r.reason;
  EXPECT_EQ(r.set.size(), 16u);
}

TEST(ScanSearch, ValidateNamesTheBadKey) {
  EXPECT_EQ(ScanSearchConfig{}.Validate(), "");
  ScanSearchConfig c;
  c.resolution = 0.0;
  EXPECT_NE(c.Validate().find("scan_search_resolution 0 out of range"), std::string::npos)
      << c.Validate();
  c = {};
  c.band_high = c.band_low;
  EXPECT_NE(c.Validate().find("band_high"), std::string::npos) << c.Validate();
  c = {};
  c.max_set = 0;
  EXPECT_NE(c.Validate().find("max_set"), std::string::npos) << c.Validate();
  c = {};
  c.sigma = std::nan("");
  EXPECT_NE(c.Validate().find("sigma"), std::string::npos) << c.Validate();
  c = {};
  c.distinct_yaw_deg = 200.0;
  EXPECT_NE(c.Validate().find("distinct_yaw_deg"), std::string::npos) << c.Validate();
}

TEST(ScanSearch, IsDeterministic) {
  const agraph::AGraph g = Building({LRoom(), LRoom({M_PI, {21.0, 6.0}})});
  const ScanSearch search(g, {});
  const auto points = Slice(g);
  const auto a = search.Search(points, 0), b = search.Search(points, 0);
  ASSERT_EQ(a.set.size(), b.set.size());
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.best, b.best);
  for (size_t k = 0; k < a.set.size(); ++k) {
    EXPECT_EQ(a.set[k].score, b.set[k].score);
    EXPECT_EQ(a.set[k].bim_T_map.yaw, b.set[k].bim_T_map.yaw);
    EXPECT_EQ(a.set[k].bim_T_map.t, b.set[k].bim_T_map.t);
  }
}

TEST(ScanSearch, EveryPoseOutsideTheSetScoresBelowTheMargin) {
  const agraph::AGraph g = Building({LRoom(), LRoom({M_PI, {21.0, 6.0}}), Pillar()});
  const ScanSearch search(g, {});
  const auto points = Slice(g);
  const auto r = search.Search(points, 0);
  ASSERT_EQ(r.status, ScanSearchResult::Status::kOk) << r.reason;
  for (const ScanPose& p : r.set) {
    EXPECT_GE(search.Score(points, p.bim_T_map, 0), r.best - r.margin);
    EXPECT_NEAR(search.Score(points, p.bim_T_map, 0), p.score, 1e-12);
  }
  // Poses anywhere over the storey, turned anyhow, 1 m or 10 deg from every pose of the set.
  const std::uint64_t seed = testing::CampaignSeed(77);
  std::printf("[ ScanSearch ] certificate seed %llu\n", static_cast<unsigned long long>(seed));
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(-2.0, 23.0), y(-2.0, 8.0), yaw(-M_PI, M_PI);
  const Eigen::Vector2d c = Centroid(points);
  int sampled = 0;
  while (sampled < 2000) {
    Pose2 pose;
    pose.yaw = yaw(rng);
    pose.t = Eigen::Vector2d(x(rng), y(rng)) - pose.R() * c;
    bool far = true;
    for (const ScanPose& p : r.set)
      far = far && !Near(pose, p.bim_T_map, c, 1.0, 10.0 * M_PI / 180.0);
    if (!far) continue;
    ++sampled;
    EXPECT_LT(search.Score(points, pose, 0), r.best - r.margin)
        << "yaw " << pose.yaw << " t " << pose.t.transpose();
  }
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
