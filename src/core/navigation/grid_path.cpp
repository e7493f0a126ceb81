#include "is_graphs/navigation/grid_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace is_graphs {
namespace navigation {

std::vector<Eigen::Vector2i> FindPath(const OccupancyGrid& grid, const Eigen::Vector2i& start,
                                      const Eigen::Vector2i& goal) {
  const auto free = [&](int x, int y) {
    return grid.Contains(x, y) && grid.At(x, y) == OccupancyGrid::kFree;
  };
  if (!free(start.x(), start.y()) || !free(goal.x(), goal.y())) return {};
  const auto index = [&](int x, int y) { return static_cast<size_t>(y) * grid.width + x; };
  const auto heuristic = [&](int x, int y) {  // octile distance: admissible for 8 neighbours
    const int dx = std::abs(x - goal.x()), dy = std::abs(y - goal.y());
    return std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy);
  };
  std::vector<double> cost(grid.cells.size(), std::numeric_limits<double>::infinity());
  std::vector<int> parent(grid.cells.size(), -1);
  using Entry = std::pair<double, int>;  // f, cell index
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[index(start.x(), start.y())] = 0.0;
  open.push({heuristic(start.x(), start.y()), static_cast<int>(index(start.x(), start.y()))});
  const size_t target = index(goal.x(), goal.y());
  while (!open.empty()) {
    const auto [f, i] = open.top();
    open.pop();
    const int x = i % grid.width, y = i / grid.width;
    if (f > cost[i] + heuristic(x, y) + 1e-9) continue;  // stale entry
    if (static_cast<size_t>(i) == target) break;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !free(x + dx, y + dy)) continue;
        if (dx != 0 && dy != 0 && (!free(x + dx, y) || !free(x, y + dy))) continue;
        const size_t j = index(x + dx, y + dy);
        const double g = cost[i] + ((dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0);
        if (g >= cost[j]) continue;
        cost[j] = g;
        parent[j] = i;
        open.push({g + heuristic(x + dx, y + dy), static_cast<int>(j)});
      }
    }
  }
  if (!std::isfinite(cost[target])) return {};
  std::vector<Eigen::Vector2i> path;
  for (int i = static_cast<int>(target); i >= 0; i = parent[i])
    path.emplace_back(i % grid.width, i / grid.width);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace navigation
}  // namespace is_graphs
