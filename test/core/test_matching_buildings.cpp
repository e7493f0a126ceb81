// The matcher on S-Graphs made from the project's buildings (through the real IFC converter):
// unique and correct where the building allows it, AMBIGUOUS where it does not (identical
// offices, the symmetric building), no UNIQUE for mirror images.
#include <gtest/gtest.h>

#include <random>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

using testing::MatchIsCorrect;
using testing::Noisy;
using testing::ProjectBim;
using testing::RoomByName;

std::vector<int> Rooms(const agraph::AGraph& g, const std::vector<std::string>& names) {
  std::vector<int> ids;
  for (const auto& n : names) ids.push_back(RoomByName(g, n));
  return ids;
}

GraphMatch MatchOnce(const agraph::AGraph& g, const SyntheticSGraph& s) {
  GraphMatcher matcher;
  matcher.SetAGraph(g);
  return matcher.Match(s.graph);
}

TEST(MatchingBuildings, EveryBuildingWholeIsUniqueAndCorrect) {
  for (const char* name : {"office.ifc", "rotated.ifc", "large.ifc", "symmetric.ifc"}) {
    IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim(name));
    for (int k = 0; k < 3; ++k) {
      auto c = Noisy(10 + k, -2.0 + 1.7 * k, 40.0 - 30.0 * k, -7.0 + 9.0 * k);
      const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
      const GraphMatch m = MatchOnce(*g, s);
      std::string why;
      EXPECT_EQ(m.status, MatchStatus::kUnique)
          << name << " trial " << k << " hyps " << m.hypotheses;
      EXPECT_TRUE(MatchIsCorrect(m, s, &why)) << name << " trial " << k << ": " << why;
      EXPECT_EQ(m.room_pairs.size(), s.graph.rooms.size()) << name;
      EXPECT_GT(m.surface_pairs.size(), s.graph.rooms.size()) << name;
    }
  }
}

TEST(MatchingBuildings, OfficeIdenticalOfficesAreAmbiguousTheMeetingRoomIsNot) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("office.ifc"));
  auto c = Noisy(3, 0.9, 5.0, -12.0);
  c.rooms = Rooms(*g, {"Corridor", "102", "103"});
  const GraphMatch twins = MatchOnce(*g, MakeSyntheticSGraph(*g, c));
  EXPECT_EQ(twins.status, MatchStatus::kAmbiguous);
  EXPECT_GE(twins.hypotheses, 2u);

  c.rooms = Rooms(*g, {"Corridor", "113", "Meeting"});
  const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
  const GraphMatch m = MatchOnce(*g, s);
  std::string why;
  EXPECT_EQ(m.status, MatchStatus::kUnique);
  EXPECT_TRUE(MatchIsCorrect(m, s, &why)) << why;
}

TEST(MatchingBuildings, SymmetricIsAmbiguousUntilADistinguishingRoomIsAdded) {
  IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim("symmetric.ifc"));
  auto c = Noisy(5, 2.4, -3.0, 8.0);
  // Everything with a twin under the half turn.
  c.rooms = Rooms(*g, {"Corridor", "S1", "S3", "S4", "S5", "N1", "N3", "N4", "N5"});
  const SyntheticSGraph twins = MakeSyntheticSGraph(*g, c);
  const GraphMatch ambiguous = MatchOnce(*g, twins);
  EXPECT_EQ(ambiguous.status, MatchStatus::kAmbiguous);
  EXPECT_EQ(ambiguous.hypotheses, 2u);
  // One of the two is the truth.
  bool truth_among = MatchIsCorrect(ambiguous, twins);
  for (const auto& alt : ambiguous.alternatives) {
    GraphMatch as_best = ambiguous;
    as_best.bim_T_map = alt.bim_T_map;
    as_best.room_pairs.clear();
    truth_among = truth_among || MatchIsCorrect(as_best, twins);
  }
  EXPECT_TRUE(truth_among);

  for (const char* distinguishing : {"N2a", "N2b", "S2"}) {
    auto c2 = c;
    c2.rooms.push_back(RoomByName(*g, distinguishing));
    const SyntheticSGraph s = MakeSyntheticSGraph(*g, c2);
    const GraphMatch m = MatchOnce(*g, s);
    std::string why;
    EXPECT_EQ(m.status, MatchStatus::kUnique) << "with " << distinguishing;
    EXPECT_TRUE(MatchIsCorrect(m, s, &why)) << "with " << distinguishing << ": " << why;
  }
}

TEST(MatchingBuildings, MirrorImagesAreNeverUnique) {
  for (const char* name : {"office.ifc", "rotated.ifc", "large.ifc", "symmetric.ifc"}) {
    IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim(name));
    for (int k = 0; k < 3; ++k) {
      auto c = Noisy(20 + k, 0.3 + 2.0 * k, 10.0 * k, -5.0);
      c.mirror = true;
      const GraphMatch m = MatchOnce(*g, MakeSyntheticSGraph(*g, c));
      EXPECT_NE(m.status, MatchStatus::kUnique) << name << " mirrored, trial " << k;
    }
  }
}

TEST(MatchingBuildings, MissingRoomsExtraPlanesAndRoomsAndSplitPlanes) {
  for (const char* name : {"office.ifc", "rotated.ifc", "large.ifc"}) {
    IS_GRAPHS_BUILDING_OR_SKIP(g, ProjectBim(name));
    std::mt19937_64 rng(7);
    int unique = 0;
    for (int k = 0; k < 10; ++k) {
      auto c = Noisy(100 + k, 0.0, 0.0, 0.0);
      c.bim_T_map = RandomPlanarMotion(rng, 50.0);
      c.rooms = RandomConnectedRooms(*g, static_cast<int>(g->rooms.size()) - 2, rng);  // 2 missing
      c.extra_planes = 2;
      c.extra_rooms = 1;
      c.split_probability = 0.5;
      c.bim_deviation = 0.1;
      const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
      const GraphMatch m = MatchOnce(*g, s);
      std::string why;
      if (m.status == MatchStatus::kUnique) {
        ++unique;
        EXPECT_TRUE(MatchIsCorrect(m, s, &why)) << name << " trial " << k << ": " << why;
      }
    }
    EXPECT_GE(unique, 8) << name;
  }
}

TEST(MatchingBuildings, SharedBimFiles) {
  const std::string dir = IS_GRAPHS_SHARED_BIM_DIR;
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << dir << " is not there (no third-party IFC)";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".ifc") continue;
    std::string why;
    const agraph::AGraph* g = testing::LoadBuildingOnce(entry.path().string(), &why);
    if (!g) {
      ADD_FAILURE() << why;
      continue;
    }
    ++files;
    auto c = Noisy(42, 1.1, 7.0, 3.0);
    // One floor, as an S-Graph is: the storey with the most rooms.
    std::map<int, std::vector<int>> by_storey;
    for (const auto& r : g->rooms) by_storey[r.storey].push_back(r.id);
    for (const auto& [storey, ids] : by_storey)
      if (ids.size() > c.rooms.size()) c.rooms = ids;
    const SyntheticSGraph s = MakeSyntheticSGraph(*g, c);
    const GraphMatch m = MatchOnce(*g, s);
    std::string wrong;
    std::cout << "[ shared   ] " << entry.path().filename().string() << ": " << g->rooms.size()
              << " rooms -> " << ToString(m.status) << " (" << m.hypotheses << " hypotheses)\n";
    if (m.status == MatchStatus::kUnique) {
      EXPECT_TRUE(MatchIsCorrect(m, s, &wrong)) << wrong;
    }
  }
  if (files == 0) GTEST_SKIP() << "no .ifc in " << dir;
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
