// A room whose S-centre a plane standing in it moved (AC11's entrance hall: the stair's side,
// 1.5 m inside the hall's north wall, taken for the room's bound): paired through its other
// planes (PairEvaluation::centre_off), found by the candidates leaving one pair out, its centre
// no point correspondence. And the limits: one plane left over, inside the A-room, not across
// it, at least three paired with two facing each other across it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "is_graphs/matching/candidate_graph.h"
#include "is_graphs/matching/candidate_index.h"
#include "is_graphs/matching/matcher_config.h"
#include "is_graphs/matching/room_descriptor.h"

namespace is_graphs {
namespace matching {
namespace {

/// A room of the given planes (normal into the room, offset d: n.x = d) in the frame `pose`
/// takes the BIM frame to; its centre the middle of [x0, x1] x [y0, y1] (as the S-Graph puts it:
/// between the planes bounding it), its footprint that rectangle.
RoomDescriptor Room(const std::vector<std::pair<Eigen::Vector2d, double>>& planes, double x0,
                    double y0, double x1, double y1, const Pose2& pose = {}) {
  RoomDescriptor r;
  int id = 0;
  for (const auto& [n0, d0] : planes) {
    PlaneFeature f;
    f.id = id++;
    f.normal = pose.Rotate(n0);
    f.d = d0 + f.normal.dot(pose.t);
    r.planes.push_back(f);
  }
  r.centre = pose.Apply(Eigen::Vector2d(0.5 * (x0 + x1), 0.5 * (y0 + y1)));
  for (auto& f : r.planes) f.r = f.normal.dot(r.centre) - f.d;
  r.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return r;
}

// The hall as planned: 5.4 m x 15.4 m.
RoomDescriptor Hall() {
  return Room({{{1, 0}, 0.0}, {{-1, 0}, -5.4}, {{0, 1}, 0.0}, {{0, -1}, -15.4}}, 0, 0, 5.4, 15.4);
}

// The hall as seen: its north bound the stair's side at `north` (15.4 on the plan); with
// `west` its west bound there too.
RoomDescriptor Seen(double north, double west = 0.0, const Pose2& pose = {}) {
  return Room({{{1, 0}, west}, {{-1, 0}, -5.4}, {{0, 1}, 0.0}, {{0, -1}, -north}}, west, 0, 5.4,
              north, pose);
}

TEST(CentreOff, APlaneStandingInTheRoomLeavesItsPairThroughTheOthers) {
  const MatcherConfig config;
  const auto tol = EvaluationTolerances::From(config);
  const RoomDescriptor a = Hall();
  // The stair's side 1.54 m inside: the S-centre 0.77 m off the A-centre (tolerance 0.6).
  const PairEvaluation e = EvaluatePair(Seen(13.86), a, Pose2{}, true, tol);
  ASSERT_TRUE(e.ok);
  EXPECT_TRUE(e.centre_off);
  EXPECT_EQ(e.surfaces.size(), 3u);
  EXPECT_NEAR(e.rms, 0.0, 1e-9);
  // 3 of 4 planes, the A-room's north wall unseen (lengths unknown here: each counts 1):
  // (3/4) (1/2 + 1/2 x 3/4).
  EXPECT_NEAR(e.quality, 0.75 * (0.5 + 0.5 * 0.75), 1e-9);
  // Off (pair_through_walls false): no pair, no candidate.
  MatcherConfig off;
  off.pair_through_walls = false;
  EXPECT_FALSE(EvaluatePair(Seen(13.86), a, Pose2{}, true, EvaluationTolerances::From(off)).ok);
  EXPECT_TRUE(GenerateRoomCandidates(Seen(13.86), 0, {a}, off).empty());
  // Within the centre tolerance nothing changes: an ordinary pair.
  const PairEvaluation near = EvaluatePair(Seen(14.4), a, Pose2{}, true, tol);
  ASSERT_TRUE(near.ok);
  EXPECT_FALSE(near.centre_off);
}

TEST(CentreOff, OnlyOnePlaneInsideTheRoomAndThreePairedOfWhichTwoFaceEachOther) {
  const MatcherConfig config;
  const auto tol = EvaluationTolerances::From(config);
  const RoomDescriptor a = Hall();
  // The plane left over beyond the A-room's wall (the S-room larger than the plan's room): a
  // wall not built, or another room: no pair.
  const RoomDescriptor beyond =
      Room({{{1, 0}, 0.0}, {{-1, 0}, -5.4}, {{0, 1}, 0.0}, {{0, -1}, -16.94}}, 0, 0, 5.4, 16.94);
  EXPECT_FALSE(EvaluatePair(beyond, a, Pose2{}, true, tol).ok);
  // Two planes off (the north and the west bound): no consensus of the others.
  EXPECT_FALSE(EvaluatePair(Seen(13.86, 1.5), a, Pose2{}, true, tol).ok);
  // Three planes, one off: two paired, too few to fix the room without its centre.
  const RoomDescriptor three =
      Room({{{1, 0}, 0.0}, {{0, 1}, 0.0}, {{0, -1}, -13.86}}, 0, 0, 5.4, 13.86);
  EXPECT_FALSE(EvaluatePair(three, a, Pose2{}, true, tol).ok);
  // Four planes whose paired three do not face each other: one corner and a plane along.
  const RoomDescriptor corner =
      Room({{{1, 0}, 0.0}, {{0, 1}, 0.0}, {{0, 1}, 0.02}, {{0, -1}, -13.86}}, 0, 0, 5.4, 13.86);
  EXPECT_FALSE(EvaluatePair(corner, a, Pose2{}, true, tol).ok);
  // The plane left over spanning more than 0.8 of the width between the walls facing each
  // other across it: a wall across the room, bounding a smaller room (the tower's entrance hall
  // on the ground floor against the larger room above it): no pair.
  RoomDescriptor across = Seen(13.86);
  for (auto& f : across.planes) f.length = 1.0;
  across.planes[3].length = 4.5;  // of 5.4
  EXPECT_FALSE(EvaluatePair(across, a, Pose2{}, true, tol).ok);
  across.planes[3].length = 2.9;  // the stair's side
  EXPECT_TRUE(EvaluatePair(across, a, Pose2{}, true, tol).ok);
  // The moved S-centre outside the A-room: no pair (the cheap gate).
  EXPECT_FALSE(EvaluatePair(Seen(13.86), a, Pose2{0.0, {0.0, 9.0}}, true, tol).ok);
}

TEST(CentreOff, TheCandidatesFindTheRoomByLeavingThePlaneOut) {
  const MatcherConfig config;
  const Pose2 map_T_bim{0.6, {-3.0, 4.0}};
  const std::vector<RoomDescriptor> a_rooms{Hall()};
  const RoomDescriptor s = Seen(13.86, 0.0, map_T_bim);
  const auto candidates = GenerateRoomCandidates(s, 0, a_rooms, config);
  // The hall upright and half turned, each with the plane by the north wall (the truth) or by
  // the south wall (the S-room's south bound taken for the plane in the room, the motion 1.54 m
  // along): the room alone cannot tell.
  ASSERT_EQ(candidates.size(), 4u);
  const Pose2 truth{-map_T_bim.yaw, -(map_T_bim.R().transpose() * map_T_bim.t)};
  int right = 0;
  for (const auto& c : candidates) {
    EXPECT_TRUE(c.full_rank);
    EXPECT_TRUE(c.centre_off);
    EXPECT_GT(c.quality, 0.65);
    if (AngleDistance(c.pose.yaw, truth.yaw) < 1e-6 && (c.pose.t - truth.t).norm() < 0.1) {
      ++right;
      EXPECT_NEAR((c.pose.t - truth.t).norm(), 0.0, 1e-6);
      // The correspondence pairs the S-centre with where the motion puts it, not the A-centre.
      const RoomCorrespondence corr = ToCorrespondence(c, s, a_rooms[0]);
      EXPECT_NEAR((corr.a_centre - Eigen::Vector2d(2.7, 6.93)).norm(), 0.0, 1e-6);
      EXPECT_GT((corr.a_centre - a_rooms[0].centre).norm(), 0.7);
    }
  }
  EXPECT_EQ(right, 1);
  // A centre_off candidate is looked up where its motion puts the S-centre, ordinary ones (six
  // copies with the flag off) near their A-centre.
  std::vector<std::vector<RoomCandidate>> per_s_room{candidates};
  for (int k = 0; k < 6; ++k) {
    per_s_room[0].push_back(candidates[0]);
    per_s_room[0].back().centre_off = false;
  }
  const CandidateIndex index(per_s_room, a_rooms, 1.0);
  std::vector<int> near;
  index.Near(0, Eigen::Vector2d(100.0, 100.0), 0.1, &near);
  EXPECT_TRUE(near.empty());
  index.Near(0, a_rooms[0].centre, 0.1, &near);
  EXPECT_EQ(near.size(), 6u);  // the ordinary ones: no centre_off candidate's S-centre is there
  for (int k = 0; k < 4; ++k) {
    index.Near(0, candidates[k].at, 0.1, &near);
    EXPECT_NE(std::find(near.begin(), near.end(), k), near.end());
    EXPECT_LE(near.size(), 2u);  // it, and the half-turned variant putting the S-centre there
  }
}

}  // namespace
}  // namespace matching
}  // namespace is_graphs
