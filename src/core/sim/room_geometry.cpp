#include "is_graphs/sim/room_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace is_graphs {
namespace sim {

Result<int> FindRoom(const agraph::AGraph& graph, int storey, const std::string& name) {
  int found = -1;
  for (const agraph::Room& room : graph.rooms) {
    if (room.storey != storey) continue;
    if (room.name == name || room.long_name == name) {
      if (found >= 0 && graph.rooms[found].name != room.name) {
        return Result<int>::Error("room '" + name + "' is ambiguous (rooms '" +
                                  graph.rooms[found].name + "' and '" + room.name + "')");
      }
      if (found < 0) found = room.id;
    }
  }
  if (found >= 0) return Result<int>::Ok(found);
  std::string list;
  for (const agraph::Room& room : graph.rooms) {
    if (room.storey != storey) continue;
    list += (list.empty() ? "" : ", ") + ("'" + room.name + "'");
    if (!room.long_name.empty() && room.long_name != room.name) {
      list += " ('" + room.long_name + "')";
    }
  }
  return Result<int>::Error("no room named '" + name + "' on storey " + std::to_string(storey) +
                            " (rooms: " + (list.empty() ? "none" : list) + ")");
}

bool PointInPolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

double DistanceToPolygonEdges(const std::vector<Eigen::Vector2d>& polygon,
                              const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + s * ab - p).norm());
  }
  return best;
}

Eigen::Vector2d RoomInteriorPoint(const agraph::Room& room, double margin) {
  const std::vector<Eigen::Vector2d>& poly = room.polygon;
  const Eigen::Vector2d centroid = room.center.head<2>();
  if (poly.size() < 3) return centroid;
  if (PointInPolygon(poly, centroid) && DistanceToPolygonEdges(poly, centroid) >= margin) {
    return centroid;
  }
  Eigen::Vector2d lo = poly[0], hi = poly[0];
  for (const Eigen::Vector2d& v : poly) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // Grid search (deterministic): the interior point farthest from the edges, ties broken by
  // closeness to the centroid.
  const int n = 60;
  Eigen::Vector2d best = centroid;
  double best_score = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector2d p(lo.x() + (hi.x() - lo.x()) * i / n,
                              lo.y() + (hi.y() - lo.y()) * j / n);
      if (!PointInPolygon(poly, p)) continue;
      const double clearance = std::min(DistanceToPolygonEdges(poly, p), 1.5);
      const double score = clearance - 1e-3 * (p - centroid).norm();
      if (score > best_score) {
        best_score = score;
        best = p;
      }
    }
  }
  return best;
}

}  // namespace sim
}  // namespace is_graphs
