// The geometry of one room pair shared by its evaluation (EvaluatePair) and the candidates'
// fits (GenerateRoomCandidates): internal to the matching core, not installed.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "is_graphs/matching/pairwise_consistency.h"
#include "is_graphs/matching/rigid_fit.h"
#include "is_graphs/matching/room_descriptor.h"

namespace is_graphs {
namespace matching {
namespace room_pair {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kSpanAngle = 20.0 * kDegToRad;  // planes this far apart fix a translation
inline const double kSpanCos = std::cos(kSpanAngle);
// A plane standing in a room (centre_off) spans at most this share of the room's width.
constexpr double kMaxSpan = 0.8;

/// The S-planes a pair must match of `n`: the `fraction`, at least two (or all of fewer).
int NeededPlanes(int n, double fraction);

/// The foot of `plane` (the point nearest the room's centre) and its normal.
PointNormal Foot(const RoomDescriptor& room, int plane);

/// Whether S-plane `left` could be a plane standing in the room bounded by the S-planes
/// `others` (indices): two of them face each other across it (normals at right angles to its
/// own) and it spans at most kMaxSpan of the width between them. A wall across the whole room
/// bounds a smaller room: another room, not this one with a plane standing in it.
bool SpansLessThanTheRoom(const RoomDescriptor& s, const std::vector<int>& others, int left,
                          double min_cos);

/// For a pair whose centres disagree: the S-planes all paired (`surfaces`) but one, at least
/// three, the one left over spanning less than the room (SpansLessThanTheRoom) and lying inside
/// the A-room by more than `offset` under `pose` (its foot, the point nearest the S-centre): a
/// plane standing in the room, not a wall beyond it or across it.
bool OnePlaneInside(const RoomDescriptor& s, const RoomDescriptor& a, const Pose2& pose,
                    const std::vector<std::pair<int, int>>& surfaces, double min_cos,
                    double offset);

}  // namespace room_pair
}  // namespace matching
}  // namespace is_graphs
