#pragma once

#include <vector>

#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace sgraph {

/// The floor over the rooms: its centre is the mean of the room centres (at `height`), its
/// rooms all of them. Id 0 (one storey).
Floor MakeFloor(const std::vector<Room>& rooms, double height);

}  // namespace sgraph
}  // namespace is_graphs
