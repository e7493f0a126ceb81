#include "is_graphs/merging/room_centre_shift.h"

#include <cmath>
#include <map>

namespace is_graphs {
namespace merging {
namespace {

constexpr double kOnSurface = 0.1;      // m: an edge's midpoint this near a surface lies on it
constexpr double kParallelCos = 0.985;  // cos 10°: an edge runs along a surface

Eigen::Vector2d Left(const Eigen::Vector2d& v) { return Eigen::Vector2d(-v.y(), v.x()); }

// The surface of `room` its polygon edge (midpoint m, inward unit normal n) lies on, or -1.
int SurfaceUnder(const agraph::AGraph& a_graph, const agraph::Room& room, const Eigen::Vector2d& m,
                 const Eigen::Vector2d& n) {
  for (int id : room.surfaces) {
    if (id < 0 || id >= static_cast<int>(a_graph.surfaces.size())) continue;
    const agraph::WallSurface& s = a_graph.surfaces[id];
    const Eigen::Vector2d n_s = s.plane.normal.head<2>();
    if (n_s.norm() < 1e-9 || n_s.normalized().dot(n) < kParallelCos) continue;
    const Eigen::Vector2d along = s.end - s.start;
    const double length = along.norm();
    if (length < 1e-9) continue;
    const double t = (m - s.start).dot(along) / length;
    const double across = std::abs((m - s.start).dot(n_s.normalized()));
    if (across < kOnSurface && t > -kOnSurface && t < length + kOnSurface) return id;
  }
  return -1;
}

}  // namespace

std::vector<RoomCentreShift> RoomCentreShifts(const agraph::AGraph& a_graph,
                                              const agraph::Room& room) {
  const std::vector<Eigen::Vector2d>& p = room.polygon;
  const size_t k = p.size();
  if (k < 3) return {};
  double twice_area = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < k; ++i) {
    const double cross = p[i].x() * p[(i + 1) % k].y() - p[(i + 1) % k].x() * p[i].y();
    twice_area += cross;
    centroid += cross * (p[i] + p[(i + 1) % k]);
  }
  if (std::abs(twice_area) < 1e-6) return {};
  centroid /= 3.0 * twice_area;
  const double area = 0.5 * std::abs(twice_area);
  const double inward = twice_area > 0.0 ? 1.0 : -1.0;  // counter-clockwise: the left is inside

  std::map<int, Eigen::Vector2d> by_wall;
  for (size_t i = 0; i < k; ++i) {
    const Eigen::Vector2d edge = p[(i + 1) % k] - p[i];
    const double length = edge.norm();
    if (length < 1e-6) continue;
    const Eigen::Vector2d m = 0.5 * (p[i] + p[(i + 1) % k]);
    const Eigen::Vector2d n = inward * Left(edge / length);
    const int surface = SurfaceUnder(a_graph, room, m, n);
    if (surface < 0) continue;
    const int wall = a_graph.surfaces[surface].wall;
    if (wall < 0 || wall >= static_cast<int>(a_graph.walls.size())) continue;
    const agraph::Wall& w = a_graph.walls[wall];
    if (w.surface_a < 0 || w.surface_a >= static_cast<int>(a_graph.surfaces.size())) continue;
    Eigen::Vector2d n_w = a_graph.surfaces[w.surface_a].plane.normal.head<2>();
    n_w = n_w.norm() > 1e-9 ? Eigen::Vector2d(n_w.normalized()) : Eigen::Vector2d::UnitX();
    const Eigen::Vector2d n_s = a_graph.surfaces[surface].plane.normal.head<2>().normalized();
    // The edge moves δ (n_w·n_s) into the room: ΔC = −δ (n_w·n_s) L (m − C) / A.
    const Eigen::Vector2d g = -n_w.dot(n_s) * length / area * (m - centroid);
    auto [it, added] = by_wall.try_emplace(wall, g);
    if (!added) it->second += g;
  }
  std::vector<RoomCentreShift> out;
  for (const auto& [wall, g] : by_wall) out.push_back({wall, g});
  return out;
}

}  // namespace merging
}  // namespace is_graphs
