#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/navigation/occupancy_grid.h"

namespace is_graphs {
namespace navigation {

/// A* over the free cells of `grid` (8-connected, no corner cutting past an occupied or unknown
/// cell): the cells from `start` to `goal`, both included; empty when either is not free or no
/// path joins them.
std::vector<Eigen::Vector2i> FindPath(const OccupancyGrid& grid, const Eigen::Vector2i& start,
                                      const Eigen::Vector2i& goal);

}  // namespace navigation
}  // namespace is_graphs
