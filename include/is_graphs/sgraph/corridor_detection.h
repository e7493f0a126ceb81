#pragma once

#include <optional>
#include <vector>

#include "is_graphs/sgraph/room_detection.h"

namespace is_graphs {
namespace sgraph {

/// A two-wall corridor around `position`: two opposed parallel walls facing each other with
/// the position between them, at most corridor_max_width apart, each covering a large sector,
/// and the rays that escape running along the corridor (within 35° of its axis). Centred on
/// the mid-line, at the middle of the walls' common extent. nullopt otherwise.
std::optional<RoomCandidate> DetectCorridor(const std::vector<Wall2D>& walls,
                                            const Eigen::Vector2d& position, const RayFan& fan,
                                            const FrontendConfig& config);

}  // namespace sgraph
}  // namespace is_graphs
