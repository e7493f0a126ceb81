#include "is_graphs/matching/room_descriptor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace is_graphs {
namespace matching {
namespace {

constexpr double kCoplanarCos = 0.99985;  // 1°
constexpr double kCoplanarOffset = 0.02;  // m

/// The horizontal trace of a vertical plane at height z; false for a (near) horizontal plane.
bool Horizontal(const geometry::Plane& plane, double z, Eigen::Vector2d* n, double* d) {
  if (!plane.normal.allFinite() || !std::isfinite(plane.d)) return false;
  const Eigen::Vector2d nh = plane.normal.head<2>();
  const double norm = nh.norm();
  if (norm < 0.7) return false;  // more than ~45° from vertical: floor, ceiling, ramp
  *n = nh / norm;
  *d = (plane.d - plane.normal.z() * z) / norm;
  return true;
}

/// Adds a feature, merging it into a coplanar one already there (the longer keeps its id).
void AddMerged(std::vector<PlaneFeature>& planes, const PlaneFeature& f) {
  for (auto& p : planes) {
    if (p.normal.dot(f.normal) > kCoplanarCos && std::abs(p.d - f.d) < kCoplanarOffset) {
      if (f.length > p.length) p.id = f.id;
      p.length += f.length;
      p.pieces.insert(p.pieces.end(), f.pieces.begin(), f.pieces.end());
      return;
    }
  }
  planes.push_back(f);
}

}  // namespace

std::vector<RoomDescriptor> DescribeARooms(const agraph::AGraph& graph) {
  std::vector<RoomDescriptor> out;
  for (const auto& room : graph.rooms) {
    if (!room.center.allFinite()) continue;
    RoomDescriptor desc;
    desc.id = room.id;
    desc.storey = room.storey;
    desc.centre = room.center.head<2>();
    desc.polygon = room.polygon;
    std::set<int> seen;
    for (int sid : room.surfaces) {
      if (sid < 0 || sid >= static_cast<int>(graph.surfaces.size()) || !seen.insert(sid).second)
        continue;
      const auto& s = graph.surfaces[sid];
      PlaneFeature f;
      if (!Horizontal(s.plane, room.center.z(), &f.normal, &f.d)) continue;
      f.id = s.id;
      f.pieces = {s.id};
      f.r = f.normal.dot(desc.centre) - f.d;
      f.length = std::isfinite(s.Length()) ? s.Length() : 0.0;
      AddMerged(desc.planes, f);
    }
    if (!desc.planes.empty()) out.push_back(std::move(desc));
  }
  return out;
}

std::vector<RoomDescriptor> DescribeSRooms(const sgraph::SGraph& graph) {
  std::map<int, const sgraph::Plane*> planes;
  for (const auto& p : graph.planes) planes.emplace(p.id, &p);  // first of a duplicate id wins
  std::vector<RoomDescriptor> out;
  std::set<int> room_ids;
  for (const auto& room : graph.rooms) {
    if (!room_ids.insert(room.id).second || !room.center.allFinite()) continue;
    RoomDescriptor desc;
    desc.id = room.id;
    desc.kind = room.type == sgraph::RoomType::kCorridor ? RoomKind::kCorridor : RoomKind::kRoom;
    desc.centre = room.center.head<2>();
    std::set<int> seen;
    for (int pid : room.planes) {
      const auto it = planes.find(pid);
      if (it == planes.end() || !seen.insert(pid).second) continue;
      const sgraph::Plane& p = *it->second;
      PlaneFeature f;
      if (!Horizontal(p.plane, room.center.z(), &f.normal, &f.d)) continue;
      f.id = p.id;
      f.r = f.normal.dot(desc.centre) - f.d;
      f.length = (p.end - p.start).allFinite() ? (p.end - p.start).norm() : 0.0;
      desc.planes.push_back(f);
    }
    if (!desc.planes.empty()) out.push_back(std::move(desc));
  }
  return out;
}

double SignedDistanceToPolygon(const std::vector<Eigen::Vector2d>& polygon,
                               const Eigen::Vector2d& p) {
  if (polygon.size() < 3) return std::numeric_limits<double>::infinity();
  double best = std::numeric_limits<double>::infinity();
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[j];
    const Eigen::Vector2d& b = polygon[i];
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double u = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + u * ab - p).norm());
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside ? -best : best;
}

bool PlanesSpanTwoDirections(const std::vector<PlaneFeature>& planes, double min_angle_rad) {
  return PlanesSpanTwoDirectionsCos(planes, std::cos(min_angle_rad));
}

bool PlanesSpanTwoDirectionsCos(const std::vector<PlaneFeature>& planes, double max_abs_cos) {
  for (size_t i = 0; i < planes.size(); ++i)
    for (size_t j = i + 1; j < planes.size(); ++j)
      if (std::abs(planes[i].normal.dot(planes[j].normal)) < max_abs_cos) return true;
  return false;
}

}  // namespace matching
}  // namespace is_graphs
