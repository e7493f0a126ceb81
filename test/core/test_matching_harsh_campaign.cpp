// The harsh randomized campaign: as the campaign, and worse. Walls of the walked rooms moved by
// 25-35 cm, turned by up to 15 deg, or missing; up to six clutter planes; rooms the BIM lacks;
// walls of the next rooms seen through doorways (planes of no S-room, part of their length);
// and the walked path as keyframes, noisy, sometimes through a wall the plan has (an opening it
// lacks), so the path evidence is weighed in every trial; the doorways found on the walk, some
// missed, some where the BIM has none; the keyframes that saw the planes of no room, some
// through an interior wall of the plan that was not built. Zero wrong UNIQUE matches; the share
// matched is printed with the seed (fixed, IS_GRAPHS_SEED changes it).
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <random>
#include <set>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/matching/graph_matcher.h"
#include "is_graphs/matching/synthetic_sgraph.h"
#include "matching_test_helpers.h"

namespace is_graphs {
namespace matching {
namespace {

SyntheticSGraphConfig HarshTrial(const agraph::AGraph& g, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto count = [&](double p, int max) {
    return unit(rng) < p ? std::uniform_int_distribution<int>(1, max)(rng) : 0;
  };
  SyntheticSGraphConfig c;
  c.seed = rng();
  c.bim_T_map = RandomPlanarMotion(rng, 100.0);
  const int max_rooms = std::min<int>(10, static_cast<int>(g.rooms.size()));
  c.rooms = RandomConnectedRooms(g, std::uniform_int_distribution<int>(2, max_rooms)(rng), rng);
  c.normal_noise_deg = 3.0 * unit(rng);
  c.offset_noise = 0.05 * unit(rng);
  c.centre_noise = 0.3 * unit(rng);
  c.bim_deviation = 0.15 * unit(rng);
  c.moved_walls = count(0.4, 2);
  c.turned_walls = count(0.3, 1);
  c.missing_walls = count(0.3, 2);
  c.extra_planes = count(0.6, 6);
  c.extra_rooms = count(0.3, 1);
  c.split_probability = unit(rng) < 0.3 ? 0.5 : 0.0;
  c.walk = true;
  c.walk_noise = 0.1 * unit(rng);
  c.through_walls = count(0.2, 1);
  // Rooms next to those taken, seen through their doorways (each with probability 1/2): walls
  // mapped in no S-room. Drawn from the trial's own stream: the trials above are unchanged.
  std::mt19937_64 seen(c.seed ^ 0x5EE9ull);
  std::set<int> taken(c.rooms.begin(), c.rooms.end()), next;
  for (int r : c.rooms)
    for (int d : g.rooms[r].doorways)
      if (d >= 0 && d < static_cast<int>(g.doorways.size()))
        for (int other : g.doorways[d].rooms)
          if (other >= 0 && !taken.count(other)) next.insert(other);
  for (int r : next)
    if (unit(seen) < 0.5) c.seen_rooms.push_back(r);
  // Doorways found on the walk, in three trials of ten half of them missed, in three of ten
  // one or two where the BIM has none.
  c.doorways = true;
  c.missing_doorway_share = unit(seen) < 0.3 ? 0.5 : 0.0;
  c.extra_doorways = unit(seen) < 0.3 ? (unit(seen) < 0.5 ? 1 : 2) : 0;
  // The keyframes that saw each plane of no room (sight lines), in two trials of ten through an
  // interior wall of the plan that was not built.
  c.observations = true;
  c.unbuilt_walls = unit(seen) < 0.2 ? 1 : 0;
  return c;
}

/// Trial `trial` of the harsh campaign with `seed`, as the campaign makes it; its building's
/// index into `buildings` in *building.
SyntheticSGraph ReplayTrial(
    const std::vector<std::pair<std::string, const agraph::AGraph*>>& buildings, std::uint64_t seed,
    int trial, size_t* building) {
  std::mt19937_64 rng(seed);
  for (int k = 0;; ++k) {
    *building = std::uniform_int_distribution<size_t>(0, buildings.size() - 1)(rng);
    const SyntheticSGraphConfig c = HarshTrial(*buildings[*building].second, rng);
    if (k == trial) return MakeSyntheticSGraph(*buildings[*building].second, c);
  }
}

TEST(MatchingHarshCampaign, ThousandHarshTrialsWithoutAWrongUniqueMatch) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.empty()) GTEST_SKIP() << "no building could be loaded (converter missing?)";
  const std::uint64_t seed = testing::CampaignSeed(20261124ull);
  std::cout << "[ harsh ] seed " << seed << " (set IS_GRAPHS_SEED to change)" << std::endl;
  RecordProperty("seed", std::to_string(seed));
  std::mt19937_64 rng(seed);
  const int kTrials = 1000;
  std::vector<GraphMatcher> matchers(buildings.size());
  for (size_t b = 0; b < buildings.size(); ++b) matchers[b].SetAGraph(*buildings[b].second);
  testing::CampaignTally tally;
  int keyframes = 0, with_opening = 0, seen_rooms = 0, doorways = 0, extra_doorways = 0;
  int observations = 0, unbuilt = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int trial = 0; trial < kTrials; ++trial) {
    const size_t b = std::uniform_int_distribution<size_t>(0, buildings.size() - 1)(rng);
    const agraph::AGraph& g = *buildings[b].second;
    const SyntheticSGraphConfig c = HarshTrial(g, rng);
    const SyntheticSGraph s = MakeSyntheticSGraph(g, c);
    keyframes += static_cast<int>(s.graph.keyframes.size());
    with_opening += c.through_walls > 0;
    seen_rooms += static_cast<int>(c.seen_rooms.size());
    doorways += static_cast<int>(s.graph.doorways.size());
    extra_doorways += c.extra_doorways;
    observations += static_cast<int>(s.graph.observations.size());
    unbuilt += static_cast<int>(s.unbuilt.size());
    tally.Add(buildings[b].first, matchers[b].Match(s.graph), s,
              "trial " + std::to_string(trial) + " (" + buildings[b].first + ", " +
                  std::to_string(c.rooms.size()) + " rooms, moved " +
                  std::to_string(c.moved_walls) + ", turned " + std::to_string(c.turned_walls) +
                  ", missing " + std::to_string(c.missing_walls) + ", through walls " +
                  std::to_string(c.through_walls) + ", S-Graph seed " + std::to_string(c.seed) +
                  ")",
              &g);
  }
  tally.Print("harsh", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              " (" + std::to_string(keyframes) + " keyframes, " + std::to_string(with_opening) +
                  " walks through a plan wall, " + std::to_string(seen_rooms) +
                  " rooms seen through doorways, " + std::to_string(doorways) +
                  " S-doorways of which " + std::to_string(extra_doorways) + " not in the BIM, " +
                  std::to_string(observations) + " observations of loose planes, " +
                  std::to_string(unbuilt) + " interior walls not built)");
  RecordProperty("unique_share", std::to_string(static_cast<double>(tally.unique) / kTrials));
  EXPECT_EQ(tally.wrong, 0);
  EXPECT_GT(keyframes, 10 * kTrials);  // the walk is there to be weighed
  EXPECT_GT(seen_rooms, kTrials / 2);  // ... and the walls seen beyond the rooms
  EXPECT_GT(doorways, kTrials);        // ... and the doorways walked through
  EXPECT_GT(observations, kTrials);    // ... and the sight lines to the loose planes
  EXPECT_GT(unbuilt, kTrials / 10);
}

// Where clutter moves a room's centre out of the strict gate, the true hypothesis is missing and
// a lone wrong one would stand: the doubter (a second look with a lenient centre gate) finds the
// truth and the answer is AMBIGUOUS. Trial 941 of the harsh campaign with seed 2 (rotated.ifc):
// without the doubt (and the wall planes) it is a wrong UNIQUE. (The trials are drawn from the
// campaign's stream, which the buildings' doorways shape: when the converter changes them, the
// replayed trials move; they were found again by scanning the stream for the case each test is
// about: trial 946 before converter 2.)
TEST(MatchingHarshCampaign, ALoneHypothesisIsDoubtedWhereTheTruthMissedTheCentreGate) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.size() < 10) GTEST_SKIP() << "needs the ten campaign buildings";
  size_t b = 0;
  const SyntheticSGraph s = ReplayTrial(buildings, 2, 941, &b);
  ASSERT_EQ(buildings[b].first, "rotated.ifc");
  // The wall planes are weighed apart: here they tell the truth from the lone wrong fit too,
  // and the doubt is tested on its own (as the room pairs alone would have it).
  MatcherConfig pairs_only;
  pairs_only.surface_evidence_weight = 0.0;
  pairs_only.proposals = false;            // they weigh every wall plane
  pairs_only.unique_min_wall_share = 0.0;  // so does the gate on the walls seen (it alone
                                           // turns the lone wrong fit AMBIGUOUS: 2026-11-26)
  MatcherConfig strict = pairs_only;
  strict.doubt_centre_tolerance = 0.0;
  GraphMatcher alone(strict), doubting(pairs_only), with_walls;
  with_walls.SetAGraph(*buildings[b].second);
  alone.SetAGraph(*buildings[b].second);
  doubting.SetAGraph(*buildings[b].second);
  std::string why;
  const GraphMatch m = alone.Match(s.graph);
  EXPECT_EQ(m.status, MatchStatus::kUnique);
  EXPECT_FALSE(testing::MatchIsCorrect(m, s, &why)) << "the case the doubt is for";
  const GraphMatch d = doubting.Match(s.graph);
  EXPECT_EQ(d.status, MatchStatus::kAmbiguous);
  EXPECT_GE(d.alternatives.size(), 1u);
  const GraphMatch w = with_walls.Match(s.graph);
  EXPECT_TRUE(w.status != MatchStatus::kUnique || testing::MatchIsCorrect(w, s, &why)) << why;
  // The gate on the walls seen (issue 22) alone: the lone wrong fit explains too little of them.
  MatcherConfig gated = strict;
  gated.unique_min_wall_share = MatcherConfig().unique_min_wall_share;
  GraphMatcher gate(gated);
  gate.SetAGraph(*buildings[b].second);
  const GraphMatch g = gate.Match(s.graph);
  EXPECT_EQ(g.status, MatchStatus::kAmbiguous);
  bool said = false;
  for (const auto& warning : g.warnings)
    said = said || warning.find("fits only") != std::string::npos;
  EXPECT_TRUE(said) << "the gate names why the fit is not UNIQUE";
}

// The doubter weighs the walked path only against its own best; a doubt of another motion that
// walks through walls must pay for them before it competes with the main matcher's best. Trial
// 110 of the harsh campaign (default seed; the office, 8 rooms; trial 205 in FZK-Haus before
// converter 2): a doubt whose crossings were left uncounted holds the true answer at AMBIGUOUS
// (as on H1's short bag, which never localized).
TEST(MatchingHarshCampaign, ADoubtPaysForTheWallsItWalksThrough) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.size() < 10) GTEST_SKIP() << "needs the ten campaign buildings";
  size_t b = 0;
  const SyntheticSGraph s = ReplayTrial(buildings, 20261124ull, 110, &b);
  ASSERT_EQ(buildings[b].first, "office.ifc");
  GraphMatcher matcher;
  matcher.SetAGraph(*buildings[b].second);
  const GraphMatch m = matcher.Match(s.graph);
  std::string why;
  EXPECT_EQ(m.status, MatchStatus::kUnique) << m.hypotheses << " hypotheses";
  EXPECT_TRUE(m.status != MatchStatus::kUnique || testing::MatchIsCorrect(m, s, &why)) << why;
}

// Walls seen through doorways cannot lie behind a wall: trial 631 of the harsh campaign (default
// seed; the office, 2 rooms; trial 211 before converter 2) is AMBIGUOUS without the sight lines
// (the twin explains the pairs and the planes as well) and UNIQUE and right with them: under the
// twin, planes the robot saw through a doorway lie behind an interior wall of the plan.
TEST(MatchingHarshCampaign, APlaneSeenThroughADoorwayCannotLieBehindTheTwinsWall) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.size() < 10) GTEST_SKIP() << "needs the ten campaign buildings";
  size_t b = 0;
  const SyntheticSGraph s = ReplayTrial(buildings, 20261124ull, 631, &b);
  ASSERT_EQ(buildings[b].first, "office.ifc");
  ASSERT_FALSE(s.graph.observations.empty());
  MatcherConfig blind;
  blind.sight_penalty = 0.0;
  GraphMatcher without(blind), with;
  without.SetAGraph(*buildings[b].second);
  with.SetAGraph(*buildings[b].second);
  EXPECT_EQ(without.Match(s.graph).status, MatchStatus::kAmbiguous);
  const GraphMatch m = with.Match(s.graph);
  std::string why;
  EXPECT_EQ(m.status, MatchStatus::kUnique);
  EXPECT_TRUE(testing::MatchIsCorrect(m, s, &why)) << why;
}

// The rooms' answer checked against the wall planes (proposal_cross_check). Two trials whose
// room pairs alone gave a wrong UNIQUE answer, the walls seen preferring the truth:
//  - seed 17 trial 778 (the office, 3 rooms: the corridor, an office with one wall moved and
//    one turned, the meeting room with a wall missing): the pairs fit the next office along the
//    corridor (3.5 m off); the true office's pair fails under its moved wall, so the truth is
//    no room hypothesis; corners of the walls propose it and it explains more of them;
//  - seed 21 trial 769 (AC11, 3 rooms, an opening the plan lacks): a twin wing 21 m away fits
//    the rooms' pairs and the walk, the truth explains 2.5 m more of the walls seen but its
//    walk goes through that wall; both kinds of evidence disagree: AMBIGUOUS.
TEST(MatchingHarshCampaign, TheRoomsAnswerIsCheckedAgainstTheWallsSeen) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.size() < 10) GTEST_SKIP() << "needs the ten campaign buildings";
  const struct {
    std::uint64_t seed;
    int trial;
    const char* building;
  } cases[] = {{17, 778, "office.ifc"}, {21, 769, "AC11-Institute-Var-2-IFC.ifc"}};
  for (const auto& c : cases) {
    SCOPED_TRACE("seed " + std::to_string(c.seed) + " trial " + std::to_string(c.trial));
    size_t b = 0;
    const SyntheticSGraph s = ReplayTrial(buildings, c.seed, c.trial, &b);
    ASSERT_EQ(buildings[b].first, c.building);
    MatcherConfig unchecked;
    unchecked.proposal_cross_check = false;
    GraphMatcher without(unchecked), with;
    without.SetAGraph(*buildings[b].second);
    with.SetAGraph(*buildings[b].second);
    std::string why;
    const GraphMatch w = without.Match(s.graph);
    EXPECT_EQ(w.status, MatchStatus::kUnique) << "the case the check is for";
    EXPECT_FALSE(testing::MatchIsCorrect(w, s, &why));
    const GraphMatch m = with.Match(s.graph);
    EXPECT_EQ(m.status, MatchStatus::kAmbiguous);
    bool said = false;
    for (const auto& warning : m.warnings)
      said = said || warning.find("disagree") != std::string::npos;
    EXPECT_TRUE(said) << "the warning names the disagreement";
    // The walls' best is offered as the competitor; in the office it is the truth.
    ASSERT_GE(m.alternatives.size(), 1u);
    if (c.seed == 17) {
      const Eigen::Vector3d alt = geometry::ToXYYaw(m.alternatives.back().bim_T_map);
      const Eigen::Vector3d truth = geometry::ToXYYaw(s.bim_T_map);
      EXPECT_LT((alt.head<2>() - truth.head<2>()).norm(), 0.5);
    }
  }
}

// Walls a hypothesis puts outside the building (outside_penalty) take competitors away. When
// first tried (branch d8-early, before the cross-check with the walls seen and the rooms paired
// through their planes) they left a wrong best alone in two harsh trials, both in rotated.ifc:
// seed 5 trial 275 and seed 21 trial 34. A guard: neither may be a wrong UNIQUE, with the
// penalty or without.
TEST(MatchingHarshCampaign, WallsOutsideTheBuildingLeaveNoWrongBestAlone) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.size() < 10) GTEST_SKIP() << "needs the ten campaign buildings";
  const std::pair<std::uint64_t, int> cases[] = {{5, 275}, {21, 34}};
  for (const auto& [seed, trial] : cases) {
    size_t b = 0;
    const SyntheticSGraph s = ReplayTrial(buildings, seed, trial, &b);
    ASSERT_EQ(buildings[b].first, "rotated.ifc");
    MatcherConfig off;
    off.outside_penalty = 0.0;
    for (const MatcherConfig& config : {MatcherConfig{}, off}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " trial " + std::to_string(trial) +
                   ", outside_penalty " + std::to_string(config.outside_penalty));
      GraphMatcher matcher(config);
      matcher.SetAGraph(*buildings[b].second);
      const GraphMatch m = matcher.Match(s.graph);
      std::string why;
      EXPECT_TRUE(m.status != MatchStatus::kUnique || testing::MatchIsCorrect(m, s, &why)) << why;
    }
  }
}

// A room the BIM lacks, placed by the campaign at random, twice in 40 000 harsh trials stood on
// a BIM room (its centre 0.34 and 0.19 m off, its walls 0.09-0.34 m off: that room built off
// the plan, as the campaign builds others) and was paired with it under the right motion. The
// campaigns count such a pair right (testing::StandsOnTheARoom); the same room a metre off, or
// paired with another room of the storey, stays wrong.
TEST(MatchingHarshCampaign, ARoomTheBimLacksStandingOnABimRoomIsThatRoom) {
  const auto buildings = testing::CampaignBuildings();
  if (buildings.size() < 8) GTEST_SKIP() << "the campaign's buildings are not all there";
  for (const auto& [seed, trial] : {std::pair<std::uint64_t, int>{17, 348}, {28, 319}}) {
    SCOPED_TRACE("seed " + std::to_string(seed) + " trial " + std::to_string(trial));
    size_t b = 0;
    const SyntheticSGraph s = ReplayTrial(buildings, seed, trial, &b);
    const agraph::AGraph& g = *buildings[b].second;
    GraphMatcher matcher;
    matcher.SetAGraph(g);
    const GraphMatch m = matcher.Match(s.graph);
    ASSERT_EQ(m.status, MatchStatus::kUnique);
    std::string why;
    EXPECT_TRUE(testing::MatchIsCorrect(m, s, &why, &g)) << why;
    EXPECT_FALSE(testing::MatchIsCorrect(m, s)) << "without the building: the extra room's pair";
    int extra = 0;
    for (const auto& p : m.room_pairs) {
      if (s.room_truth.count(p.s_id)) continue;
      ++extra;
      EXPECT_TRUE(testing::StandsOnTheARoom(s, p.s_id, g, p.a_id));
      SyntheticSGraph moved = s;  // the same room a metre off
      moved.bim_T_map.pretranslate(Eigen::Vector3d(1.0, 0.0, 0.0));
      EXPECT_FALSE(testing::StandsOnTheARoom(moved, p.s_id, g, p.a_id));
      int storey = -1;
      for (const auto& a : g.rooms)
        if (a.id == p.a_id) storey = a.storey;
      for (const auto& other : g.rooms)  // nor any other room of its storey (KIT's repeat)
        if (other.id != p.a_id && other.storey == storey) {
          EXPECT_FALSE(testing::StandsOnTheARoom(s, p.s_id, g, other.id)) << "A" << other.id;
        }
    }
    EXPECT_EQ(extra, 1);
  }
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
