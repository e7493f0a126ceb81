#pragma once

#include <vector>

#include "is_graphs/sgraph/backend_config.h"
#include "is_graphs/sgraph/sgraph.h"
#include "is_graphs/sgraph/sgraph_backend.h"

namespace is_graphs {
namespace sgraph {

/// The part of the S-Graph one windowed optimization solves (BackendConfig::window_keyframes),
/// so that its cost stays bounded however long the run:
///   - moved: the newest window_keyframes keyframes, every plane they observe, every room or
///     corridor on such a plane, the floor when a room moves;
///   - held at their values: the keyframe before the window (its odometry edge ties the window to
///     the past: the gauge), the newest window_plane_anchors older keyframes observing each moved
///     plane (a plane re-observed after a loop is pulled by the old map, not only by the window),
///     the other planes of a moved room, the other rooms of a moved floor;
///   - left out: the rest (old keyframes, and what only they saw, tie nothing that moves).
/// Old keyframes are never moved again: a drift corrected at a loop moves the window and the
/// planes it sees, not the past trajectory (the merge holds all but its newest keyframes anyway).
///
/// `keyframes` in the order added (ids increasing), `observations` all of the graph's; the
/// problem's planes, rooms and floor are already set (all of them). Fills problem.keyframes,
/// problem.observations and the constant sets. Without a window (0), or with no more keyframes
/// than it: every keyframe and observation, nothing held (the whole graph).
void SelectWindow(const std::vector<Keyframe>& keyframes,
                  const std::vector<PlaneObservation>& observations, const BackendConfig& config,
                  BackendProblem& problem);

}  // namespace sgraph
}  // namespace is_graphs
