// A storey from the stairs alone (issue 22): the heights walked between S-Graph levels leave
// only the storeys with storeys as far above or below.
#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "is_graphs/matching/storeys_walked.h"

namespace is_graphs {
namespace matching {
namespace {

constexpr double kTolerance = 0.15, kPerMetre = 0.03;

// ../shared/bim's duplex: T/FDN, Level 1, Level 2, Roof; up its stair with the odometry's rise
// 2 % long (M6): 3.16 m from a level at 0.54 m.
const std::map<int, double> kDuplex = {{0, -1.25}, {1, 0.0}, {2, 3.1}, {3, 6.0}};

TEST(StoreysFittingLevels, UpTheDuplexStairIsLevelTwo) {
  const std::map<int, double> levels = {{0, 0.54}, {1, 3.70}};
  EXPECT_EQ(StoreysFittingLevels(kDuplex, levels, 1, kTolerance, kPerMetre), std::vector<int>({2}));
  // Below: the storey with one 3.16 m above (the roof is 2.9 m above Level 2: out of bounds).
  EXPECT_EQ(StoreysFittingLevels(kDuplex, levels, 0, kTolerance, kPerMetre), std::vector<int>({1}));
  // Looser, the roof too: Level 2 could be the level below it.
  EXPECT_EQ(StoreysFittingLevels(kDuplex, levels, 1, 0.3, kPerMetre), std::vector<int>({2, 3}));
}

TEST(StoreysFittingLevels, FloorsOfOneHeightLeaveTheUpperOnes) {
  // The tower: 3 m storeys. One flight up, the robot is on the first or the second floor.
  const std::map<int, double> tower = {{0, 0.0}, {1, 3.0}, {2, 6.0}};
  const std::map<int, double> levels = {{0, 0.5}, {1, 3.56}};
  EXPECT_EQ(StoreysFittingLevels(tower, levels, 1, kTolerance, kPerMetre),
            std::vector<int>({1, 2}));
  // Two flights up from the first level: the top floor only.
  const std::map<int, double> three = {{0, 0.5}, {1, 3.56}, {2, 6.5}};
  EXPECT_EQ(StoreysFittingLevels(tower, three, 2, kTolerance, kPerMetre), std::vector<int>({2}));
}

TEST(StoreysFittingLevels, NoHeightToGoByIsAnyStorey) {
  const std::map<int, double> tower = {{0, 0.0}, {1, 3.0}, {2, 6.0}};
  // One level walked.
  EXPECT_TRUE(StoreysFittingLevels(tower, {{0, 0.5}}, 0, kTolerance, kPerMetre).empty());
  // A walk off the building's storeys (10 m up a 6 m building).
  EXPECT_TRUE(StoreysFittingLevels(tower, {{0, 0.5}, {1, 10.5}}, 1, kTolerance, kPerMetre).empty());
  // A current level the graph does not have.
  EXPECT_TRUE(StoreysFittingLevels(tower, {{0, 0.5}, {1, 3.5}}, 4, kTolerance, kPerMetre).empty());
}

TEST(StoreysFittingLevels, ALandingTakenForALevelRulesOutNothing) {
  // A long landing half-way (1.5 m) fits no storey; the level below still tells.
  const std::map<int, double> tower = {{0, 0.0}, {1, 3.0}, {2, 6.0}};
  const std::map<int, double> levels = {{0, 0.5}, {1, 2.0}, {2, 3.5}};
  EXPECT_EQ(StoreysFittingLevels(tower, levels, 2, kTolerance, kPerMetre),
            std::vector<int>({1, 2}));
}

// AC11: Keller -3, Erdgeschoss 0, 1. and 2. Obergeschoss (twins) 3 and 6, Dachgeschoss 9.
const std::map<int, double> kAc11 = {{0, -3.0}, {1, 0.0}, {2, 3.0}, {3, 6.0}, {4, 9.0}};

TEST(StoreysFromKnownLevels, UpFromAStoreyMatchedTheNextFollowsFromTheHeight) {
  // Localized on the ground floor (level 0 matched on storey 1), up 3.06 m (2 % long): only the
  // first floor, though every storey but the top has one 3 m above.
  const std::map<int, double> levels = {{0, 0.03}, {1, 3.09}};
  EXPECT_EQ(StoreysFittingLevels(kAc11, levels, 1, kTolerance, kPerMetre),
            std::vector<int>({1, 2, 3, 4}));
  const auto known = StoreysFromKnownLevels(kAc11, levels, {{0, 1}}, 1, kTolerance, kPerMetre);
  ASSERT_TRUE(known.has_value());
  EXPECT_EQ(*known, std::vector<int>({2}));
  // Down again from the first floor matched there (level 1 on storey 2): the ground floor.
  const auto down = StoreysFromKnownLevels(kAc11, levels, {{1, 2}}, 0, kTolerance, kPerMetre);
  ASSERT_TRUE(down.has_value());
  EXPECT_EQ(*down, std::vector<int>({1}));
}

TEST(StoreysFromKnownLevels, NoLevelKnownIsNoConstraintAndNoStoreyThereIsEmpty) {
  const std::map<int, double> levels = {{0, 0.03}, {1, 2.05}};
  EXPECT_FALSE(StoreysFromKnownLevels(kAc11, levels, {}, 1, kTolerance, kPerMetre).has_value());
  // Only the current level known (its own match): no constraint from another.
  EXPECT_FALSE(
      StoreysFromKnownLevels(kAc11, levels, {{1, 2}}, 1, kTolerance, kPerMetre).has_value());
  // A landing 2 m up from the ground floor: no storey there.
  const auto landing = StoreysFromKnownLevels(kAc11, levels, {{0, 1}}, 1, kTolerance, kPerMetre);
  ASSERT_TRUE(landing.has_value());
  EXPECT_TRUE(landing->empty());
  // Two levels known agree on the third (both constrain it).
  const std::map<int, double> three = {{0, 0.0}, {1, 3.0}, {2, 6.05}};
  EXPECT_EQ(*StoreysFromKnownLevels(kAc11, three, {{0, 1}, {1, 2}}, 2, kTolerance, kPerMetre),
            std::vector<int>({3}));
  // ... and a wrong one known on level 1 leaves nothing rather than a wrong storey.
  EXPECT_TRUE(
      StoreysFromKnownLevels(kAc11, three, {{0, 1}, {1, 3}}, 2, kTolerance, kPerMetre)->empty());
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
