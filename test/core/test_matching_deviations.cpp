// Walls built off the plan (issue 25): a room whose wall stands 25-35 cm off or turned keeps its
// pair through its other walls, and that wall is reported in GraphMatch::deviations with how far
// it stands and how much it is turned; walls on the plan are not reported.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace {

const double kDeg = M_PI / 180.0;

const matching::SurfaceDeviation* Find(const matching::GraphMatch& m, int s_id, int a_id) {
  for (const auto& d : m.deviations)
    if (d.s_id == s_id && d.a_id == a_id) return &d;
  return nullptr;
}

TEST(SurfaceDeviations, WallsBuiltOffThePlanAreMarkedWithTheirOffsetAndTurn) {
  std::string why;
  const agraph::AGraph* office = testing::LoadBuildingOnce(testing::ProjectBim("office.ifc"), &why);
  if (!office) GTEST_SKIP() << why;
  matching::GraphMatcher matcher;
  matcher.SetAGraph(*office);
  int moved_checked = 0, turned_checked = 0, unique = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
    matching::SyntheticSGraphConfig c;
    std::mt19937_64 rng(seed);
    c.rooms = matching::RandomConnectedRooms(*office, 4, rng);
    c.bim_T_map = matching::RandomPlanarMotion(rng, 20.0);
    c.moved_walls = 1;
    c.turned_walls = 1;
    c.turned_wall_deg = 15.0;
    c.corridor_aspect = 0.0;
    c.seed = seed;
    const matching::SyntheticSGraph s = matching::MakeSyntheticSGraph(*office, c);
    matcher.ForgetHistory();
    const matching::GraphMatch m = matcher.Match(s.graph);
    if (m.status != matching::MatchStatus::kUnique) continue;
    ASSERT_TRUE(testing::MatchIsCorrect(m, s)) << "seed " << seed;
    ++unique;
    std::set<int> paired_a_rooms;
    for (const auto& p : m.room_pairs) paired_a_rooms.insert(p.a_id);
    auto in_paired_room = [&](int surface) {
      for (int r : office->surfaces[surface].rooms)
        if (paired_a_rooms.count(r)) return true;
      return false;
    };
    std::map<int, int> plane_of;  // A-surface -> S-plane
    for (const auto& [plane, surface] : s.plane_truth) plane_of[surface] = plane;
    for (const auto& [surface, metres] : s.moved) {
      if (!in_paired_room(surface) || !plane_of.count(surface)) continue;
      const auto* d = Find(m, plane_of[surface], surface);
      ASSERT_NE(d, nullptr) << "seed " << seed << ": surface " << surface << " moved " << metres
                            << " m is not reported";
      EXPECT_NEAR(d->offset, metres, 0.03) << "seed " << seed;
      EXPECT_NEAR(d->angle, 0.0, 0.5 * kDeg) << "seed " << seed;
      ++moved_checked;
    }
    for (const auto& [surface, radians] : s.turned) {
      // A face turned about its middle stands metres off at the far rooms of a long corridor
      // face: only partitions of a room or two are checked.
      if (!in_paired_room(surface) || !plane_of.count(surface) || std::abs(radians) < 5.0 * kDeg ||
          office->surfaces[surface].Length() > 6.0)
        continue;
      const auto* d = Find(m, plane_of[surface], surface);
      ASSERT_NE(d, nullptr) << "seed " << seed << ": surface " << surface << " turned "
                            << radians / kDeg << " deg is not reported";
      EXPECT_NEAR(d->angle, radians, 0.5 * kDeg) << "seed " << seed;
      ++turned_checked;
    }
    // Nothing else: every other wall stands on the plan (no noise here).
    for (const auto& d : m.deviations) {
      const auto t = s.plane_truth.find(d.s_id);
      ASSERT_NE(t, s.plane_truth.end()) << "seed " << seed << ": plane " << d.s_id;
      EXPECT_TRUE(s.moved.count(t->second) || s.turned.count(t->second))
          << "seed " << seed << ": surface " << t->second << " on the plan reported " << d.offset
          << " m, " << d.angle / kDeg << " deg off";
    }
  }
  std::printf("%d UNIQUE; %d moved and %d turned walls checked\n", unique, moved_checked,
              turned_checked);
  EXPECT_GE(unique, 20);
  EXPECT_GE(moved_checked, 10);
  EXPECT_GE(turned_checked, 5);
}

TEST(SurfaceDeviations, NoneWhenTheBuildingIsAsPlanned) {
  std::string why;
  const agraph::AGraph* office = testing::LoadBuildingOnce(testing::ProjectBim("office.ifc"), &why);
  if (!office) GTEST_SKIP() << why;
  matching::GraphMatcher matcher;
  matcher.SetAGraph(*office);
  matching::SyntheticSGraphConfig c;
  c.bim_T_map = geometry::IsometryFromXYYaw(3.0, -2.0, 0.7);
  c.offset_noise = 0.01;
  c.normal_noise_deg = 0.3;
  const matching::SyntheticSGraph s = matching::MakeSyntheticSGraph(*office, c);
  const matching::GraphMatch m = matcher.Match(s.graph);
  ASSERT_EQ(m.status, matching::MatchStatus::kUnique);
  EXPECT_TRUE(m.deviations.empty())
      << m.deviations.size() << " deviations, the first: plane " << m.deviations.front().s_id << " "
      << m.deviations.front().offset << " m";
}

}  // namespace
}  // namespace is_graphs
