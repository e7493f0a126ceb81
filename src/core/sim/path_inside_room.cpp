// PathInsideRoom (route_planner.h): a walk inside one room's polygon around its stair footprints.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "is_graphs/sim/room_geometry.h"
#include "is_graphs/sim/route_planner.h"
#include "shortest_path.h"

namespace is_graphs {
namespace sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using Polygons = std::vector<std::vector<Eigen::Vector2d>>;

// True when the segment's samples (away from its ends) lie inside the polygon with clearance,
// and outside each obstacle by the clearance.
bool Visible(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& a,
             const Eigen::Vector2d& b, double clearance, const Polygons& obstacles = {}) {
  const double length = (b - a).norm();
  const int n = std::max(2, static_cast<int>(std::ceil(length / 0.05)));
  for (int i = 1; i < n; ++i) {
    const double s = length * i / n;
    if (s < clearance || length - s < clearance) continue;  // the ends may be near a doorway
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / n);
    if (!PointInPolygon(poly, p) || DistanceToPolygonEdges(poly, p) < clearance) return false;
    for (const auto& o : obstacles) {
      if (PointInPolygon(o, p) || DistanceToPolygonEdges(o, p) < clearance) return false;
    }
  }
  return true;
}

// The unit bisector at corner i of a counter-clockwise polygon, pointing inward; zero where
// the corner is degenerate.
Eigen::Vector2d InwardBisector(const std::vector<Eigen::Vector2d>& polygon, std::size_t i) {
  const std::size_t m = polygon.size();
  const Eigen::Vector2d prev = (polygon[i] - polygon[(i + m - 1) % m]).normalized();
  const Eigen::Vector2d next = (polygon[(i + 1) % m] - polygon[i]).normalized();
  // Counter-clockwise polygon: the inward normal of an edge direction e is (-e.y, e.x).
  const Eigen::Vector2d bisector =
      Eigen::Vector2d(-prev.y(), prev.x()) + Eigen::Vector2d(-next.y(), next.x());
  return bisector.norm() < 1e-6 ? Eigen::Vector2d::Zero() : bisector.normalized();
}

// Each corner of a polygon moved `inset` along its bisector (inward for a counter-clockwise
// polygon and positive inset; outward with a negative one).
std::vector<Eigen::Vector2d> InsetCorners(const std::vector<Eigen::Vector2d>& polygon,
                                          double inset) {
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d bisector = InwardBisector(polygon, i);
    if (!bisector.isZero()) out.push_back(polygon[i] + inset * bisector);
  }
  return out;
}

}  // namespace

std::vector<Eigen::Vector2d> PathInsideRoom(const std::vector<Eigen::Vector2d>& polygon,
                                            const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                            double clearance, const Polygons& obstacles) {
  if (polygon.size() < 3 || Visible(polygon, a, b, clearance, obstacles)) return {b};
  // Nodes: a, b, and each polygon corner moved inward along its bisector.
  std::vector<Eigen::Vector2d> nodes{a, b};
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d bisector = InwardBisector(polygon, i);
    if (bisector.isZero()) continue;
    for (double inset : {2.0 * clearance + 0.3, 4.0 * clearance + 0.3}) {
      const Eigen::Vector2d p = polygon[i] + inset * bisector;
      if (PointInPolygon(polygon, p)) nodes.push_back(p);
    }
  }
  for (const auto& o : obstacles) {  // around an obstacle: its corners pushed outward
    for (double outset : {-(1.5 * clearance + 0.1), -(3.0 * clearance + 0.3)}) {
      for (const Eigen::Vector2d& p : InsetCorners(o, outset)) {
        if (PointInPolygon(polygon, p)) nodes.push_back(p);
      }
    }
  }
  const std::vector<int> path = Dijkstra(static_cast<int>(nodes.size()), 0, 1, [&](int u, int v) {
    return Visible(polygon, nodes[u], nodes[v], clearance, obstacles) ? (nodes[u] - nodes[v]).norm()
                                                                      : kInf;
  });
  if (path.empty()) return {b};  // no better idea: walk straight (the caller's scene decides)
  std::vector<Eigen::Vector2d> out;
  for (int v : path) out.push_back(nodes[v]);
  return out;
}

}  // namespace sim
}  // namespace is_graphs
