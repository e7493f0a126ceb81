// The matcher on bad input (warnings, no crash, no match claimed), its determinism and its
// incremental reuse when the S-Graph grows.
#include <gtest/gtest.h>

#include <limits>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/input_checks.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

bool AnyContains(const std::vector<std::string>& lines, const std::string& part) {
  for (const auto& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

SyntheticSGraph Office3(const agraph::AGraph& g) {
  SyntheticSGraphConfig c;
  c.rooms = {testing::RoomByName(g, "Corridor"), testing::RoomByName(g, "113"),
             testing::RoomByName(g, "Meeting")};
  c.bim_T_map = geometry::IsometryFromXYYaw(3.0, 4.0, 0.5);
  c.normal_noise_deg = 0.5;
  c.offset_noise = 0.02;
  return MakeSyntheticSGraph(g, c);
}

TEST(MatchingInput, EmptyGraphs) {
  GraphMatcher matcher;
  const GraphMatch no_a = matcher.Match(sgraph::SGraph{});
  EXPECT_EQ(no_a.status, MatchStatus::kNone);
  EXPECT_FALSE(no_a.warnings.empty());

  const auto a_warnings = matcher.SetAGraph(agraph::AGraph{});
  EXPECT_TRUE(AnyContains(a_warnings, "no rooms"));
  const GraphMatch none = matcher.Match(sgraph::SGraph{});
  EXPECT_EQ(none.status, MatchStatus::kNone);
  EXPECT_TRUE(AnyContains(none.warnings, "no rooms"));
}

TEST(MatchingInput, MalformedSGraphsWarnAndClaimNothing) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, testing::ProjectBim("office.ifc"));
  GraphMatcher matcher;
  EXPECT_TRUE(matcher.SetAGraph(*g).empty());
  const SyntheticSGraph good = Office3(*g);
  ASSERT_EQ(matcher.Match(good.graph).status, MatchStatus::kUnique);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* what;
    std::function<void(sgraph::SGraph&)> spoil;
    const char* warning;
  } cases[] = {
      {"NaN normals",
       [&](sgraph::SGraph& s) {
         for (auto& p : s.planes) p.plane.normal.x() = nan;
       },
       "non-finite"},
      {"NaN d",
       [&](sgraph::SGraph& s) {
         for (auto& p : s.planes) p.plane.d = nan;
       },
       "non-finite"},
      {"NaN centres",
       [&](sgraph::SGraph& s) {
         for (auto& r : s.rooms) r.center.y() = nan;
       },
       "non-finite centre"},
      {"rooms without planes",
       [&](sgraph::SGraph& s) {
         for (auto& r : s.rooms) r.planes.clear();
       },
       "no planes"},
      {"unknown planes",
       [&](sgraph::SGraph& s) {
         for (auto& r : s.rooms) r.planes = {999999};
       },
       "does not exist"},
      {"duplicate room ids",
       [&](sgraph::SGraph& s) {
         for (auto& r : s.rooms) r.id = 1;
       },
       "duplicate id"},
      {"duplicate plane ids",
       [&](sgraph::SGraph& s) {
         for (auto& p : s.planes) p.id = 5;
       },
       "duplicate plane id"},
  };
  for (const auto& c : cases) {
    sgraph::SGraph s = good.graph;
    c.spoil(s);
    GraphMatcher fresh;
    fresh.SetAGraph(*g);
    const GraphMatch m = fresh.Match(s);
    EXPECT_NE(m.status, MatchStatus::kUnique) << c.what;
    EXPECT_TRUE(AnyContains(m.warnings, c.warning)) << c.what;
  }
}

TEST(MatchingInput, MalformedAGraphWarns) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, testing::ProjectBim("office.ifc"));
  agraph::AGraph bad = *g;
  bad.rooms[0].surfaces.clear();
  bad.rooms[1].surfaces.push_back(100000);
  bad.rooms[2].id = 1;
  bad.surfaces[0].plane.d = std::numeric_limits<double>::quiet_NaN();
  GraphMatcher matcher;
  const auto warnings = matcher.SetAGraph(bad);
  EXPECT_TRUE(AnyContains(warnings, "no wall-surfaces"));
  EXPECT_TRUE(AnyContains(warnings, "does not exist"));
  EXPECT_TRUE(AnyContains(warnings, "duplicate"));
  EXPECT_TRUE(AnyContains(warnings, "non-finite"));
  matcher.Match(Office3(*g).graph);  // no crash
}

TEST(MatchingInput, DeterministicAcrossRunsAndMatchers) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, testing::ProjectBim("large.ifc"));
  SyntheticSGraphConfig c;
  std::mt19937_64 rng(11);
  c.rooms = RandomConnectedRooms(*g, 6, rng);
  c.bim_T_map = RandomPlanarMotion(rng, 30.0);
  c.normal_noise_deg = 1.0;
  c.offset_noise = 0.03;
  const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
  EXPECT_EQ(MakeSyntheticSGraph(*g, c).graph.planes.size(), s.graph.planes.size());
  GraphMatcher a, b;
  a.SetAGraph(*g);
  b.SetAGraph(*g);
  const GraphMatch first = a.Match(s.graph);
  // A fresh matcher gives the very same answer; the same one again (now with its incremental
  // state) the same answer up to rounding.
  for (const GraphMatch& again : {b.Match(s.graph), b.Match(s.graph)}) {
    EXPECT_EQ(again.status, first.status);
    EXPECT_EQ(again.hypotheses, first.hypotheses);
    EXPECT_NEAR(again.score, first.score, 1e-9);
    ASSERT_EQ(again.room_pairs.size(), first.room_pairs.size());
    for (size_t i = 0; i < first.room_pairs.size(); ++i) {
      EXPECT_EQ(again.room_pairs[i].a_id, first.room_pairs[i].a_id);
      EXPECT_EQ(again.room_pairs[i].s_id, first.room_pairs[i].s_id);
    }
    EXPECT_TRUE(again.bim_T_map.isApprox(first.bim_T_map, 1e-9));
  }
  GraphMatcher c2;
  c2.SetAGraph(*g);
  const GraphMatch fresh = c2.Match(s.graph);
  EXPECT_EQ(fresh.score, first.score);
  EXPECT_TRUE(fresh.bim_T_map.isApprox(first.bim_T_map, 0.0));
}

TEST(MatchingInput, IncrementalGrowthReusesCandidatesAndReachesUnique) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, testing::ProjectBim("office.ifc"));
  // The robot walks the corridor and looks into the offices, the meeting room last.
  const std::vector<std::string> walk{"Corridor", "101", "102", "103", "Meeting"};
  SyntheticSGraphConfig c;
  c.bim_T_map = geometry::IsometryFromXYYaw(-20.0, 6.0, -1.3);
  c.normal_noise_deg = 0.5;
  c.offset_noise = 0.02;
  GraphMatcher matcher;
  matcher.SetAGraph(*g);
  MatchStatus last = MatchStatus::kNone;
  for (size_t k = 1; k <= walk.size(); ++k) {
    c.rooms.push_back(testing::RoomByName(*g, walk[k - 1]));
    SyntheticSGraph s = MakeSyntheticSGraph(*g, c);  // same seed: the earlier rooms unchanged
    s.graph.revision = static_cast<unsigned>(k);
    const GraphMatch m = matcher.Match(s.graph);
    EXPECT_EQ(m.s_graph_revision, k);
    EXPECT_EQ(matcher.LastStats().reused_rooms, static_cast<int>(k) - 1) << "revision " << k;
    if (k < walk.size()) {
      EXPECT_NE(m.status, MatchStatus::kUnique) << "revision " << k;
    }
    std::string why;
    if (m.status == MatchStatus::kUnique) {
      EXPECT_TRUE(testing::MatchIsCorrect(m, s, &why)) << why;
    }
    last = m.status;
  }
  EXPECT_EQ(last, MatchStatus::kUnique);
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
