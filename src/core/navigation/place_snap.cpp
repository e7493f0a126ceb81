// PlaceIndex::SnapToFree: goals moved off what the map has occupied (a column, a shaft, a
// built-in) or unknown (a wall's front in a room narrower than the standoff).
#include <algorithm>
#include <cmath>

#include "is_graphs/navigation/places.h"

namespace is_graphs {
namespace navigation {
namespace {

bool InRoom(const agraph::AGraph& graph, int room, const Eigen::Vector2d& p) {
  return room >= 0 && room < static_cast<int>(graph.rooms.size()) &&
         graph.rooms[room].polygon.size() >= 3 &&
         SignedDistanceToPolygon(graph.rooms[room].polygon, p) > 0.0;
}

bool InAnyRoom(const agraph::AGraph& graph, int storey, const Eigen::Vector2d& p) {
  for (const auto& r : graph.rooms)
    if (r.storey == storey && InRoom(graph, r.id, p)) return true;
  return false;
}

}  // namespace

Eigen::Vector2i PlaceIndex::SnapToFree(int storey, const OccupancyGrid& grid,
                                       const agraph::AGraph& graph, double radius) {
  Eigen::Vector2i counts = Eigen::Vector2i::Zero();
  const int n = static_cast<int>(std::ceil(radius / grid.resolution));
  std::vector<Eigen::Vector2i> offsets;  // nearest first
  for (int dy = -n; dy <= n; ++dy)
    for (int dx = -n; dx <= n; ++dx)
      if (std::hypot(dx, dy) * grid.resolution <= radius) offsets.emplace_back(dx, dy);
  std::stable_sort(offsets.begin(), offsets.end(),
                   [](const auto& a, const auto& b) { return a.squaredNorm() < b.squaredNorm(); });
  for (auto& place : places_) {
    if (place.storey != storey) continue;
    const Eigen::Vector2i c = grid.CellOf(place.position.head<2>());
    if (grid.Contains(c.x(), c.y()) && grid.At(c.x(), c.y()) == OccupancyGrid::kFree) {
      place.on_free_cell = true;
      continue;
    }
    bool found = false;
    Eigen::Vector2d best = place.position.head<2>();
    for (const auto& o : offsets) {
      const int x = c.x() + o.x(), y = c.y() + o.y();
      if (!grid.Contains(x, y) || grid.At(x, y) != OccupancyGrid::kFree) continue;
      const Eigen::Vector2d q = grid.CentreOf(x, y);
      if (place.kind == Place::Kind::kRoom ? !InRoom(graph, place.id, q)
                                           : !InAnyRoom(graph, storey, q))
        continue;
      best = q, found = true;
      break;
    }
    place.on_free_cell = found;
    if (!found) {
      ++counts[1];
      continue;
    }
    ++counts[0];
    place.position.head<2>() = best;
    if (place.kind != Place::Kind::kRoom && (place.faced - best).norm() > 1e-6)
      place.yaw = std::atan2(place.faced.y() - best.y(), place.faced.x() - best.x());
  }
  return counts;
}

}  // namespace navigation
}  // namespace is_graphs
