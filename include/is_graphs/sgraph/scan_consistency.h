#pragma once

#include <vector>

#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/plane_association.h"
#include "is_graphs/sgraph/plane_extraction.h"

namespace is_graphs {
namespace sgraph {

/// What ContradictedWalls found.
struct ScanConsistency {
  std::vector<int> contradicted;  // indices into the scan's segments, ascending
  int support{0};                 // walls that agree with the rotation below
  double yaw{0.0};                // rad: the keyframe's heading error most walls agree on
};

/// The walls of one keyframe whose association its other associated walls contradict.
///
/// Each associated wall (a vertical segment, in M, matched to a mapped plane that at least
/// config.consistency_min_keyframes keyframes observed) says how far the keyframe's heading is
/// off: the yaw between its normal and the mapped normal. Odometry drift turns every wall alike;
/// the rotation most walls agree with is the keyframe's heading error. A wall off that rotation
/// by more than its tolerance has turned since it was mapped — a door leaf swung a few degrees
/// off its wall, which the association gate (wide enough for drift) lets through and which
/// would pull the keyframe. Tolerance: config.consistency_angle_deg plus
/// consistency_angle_deg_per_m per metre walked since the plane was last observed (drift between
/// the two observations), and at least 3 sigma of the two planes' heading uncertainty. Planes
/// observed by fewer keyframes are left out: their heading is their first fit's, and an
/// observation contradicting it is as likely right. Nothing is contradicted unless at least
/// config.consistency_min_walls walls take part and at least two, more than half, agree.
ScanConsistency ContradictedWalls(const std::vector<PlaneSegment>& observed_in_map,
                                  const std::vector<MapPlaneView>& mapped,
                                  const std::vector<Association>& associations,
                                  const FrontendConfig& config);

}  // namespace sgraph
}  // namespace is_graphs
