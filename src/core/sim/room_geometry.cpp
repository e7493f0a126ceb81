#include "is_graphs/sim/room_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "is_graphs/agraph/agraph_queries.h"

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

Result<int> FindRoomInBuilding(const agraph::AGraph& graph, int preferred_storey,
                               const std::string& name) {
  const std::size_t at = name.rfind(" @ ");
  if (at != std::string::npos) {
    const Result<int> storey = agraph::FindStorey(graph, name.substr(at + 3));
    if (!storey.ok()) return Result<int>::Error("'" + name + "': " + storey.error());
    return FindRoom(graph, storey.value(), name.substr(0, at));
  }
  const Result<int> here = FindRoom(graph, preferred_storey, name);
  if (here.ok()) return here;
  std::vector<int> found;
  std::string storeys;
  for (const agraph::Storey& s : graph.storeys) {
    if (s.id == preferred_storey) continue;
    const Result<int> there = FindRoom(graph, s.id, name);
    if (!there.ok()) continue;
    found.push_back(there.value());
    storeys += (storeys.empty() ? "'" : ", '") + s.name + "'";
  }
  if (found.size() == 1) return Result<int>::Ok(found.front());
  if (found.size() > 1) {
    return Result<int>::Error("room '" + name + "' is on storeys " + storeys + ": name one as '" +
                              name + " @ <storey>'");
  }
  return Result<int>::Error(here.error() + ", nor on any other storey");
}

std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 1e-12) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {  // upper hull
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 1e-12) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
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

double FloorUnder(const agraph::AGraph& graph, int storey, const Eigen::Vector2d& p,
                  double floor_z) {
  constexpr double kSameFloor = 0.05;  // m
  for (const agraph::Room& r : graph.rooms) {
    if (r.storey != storey || r.polygon.size() < 3 || !PointInPolygon(r.polygon, p)) continue;
    return std::abs(r.floor_z - floor_z) > kSameFloor ? r.floor_z : floor_z;
  }
  return floor_z;
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
