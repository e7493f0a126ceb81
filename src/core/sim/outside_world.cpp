#include "is_graphs/sim/outside_world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace sim {
namespace {

Eigen::Vector3d BoxSize(const OutsideObjectConfig& o) {
  Eigen::Vector3d d = o.type == "car"    ? Eigen::Vector3d(4.5, 1.8, 1.5)
                      : o.type == "wall" ? Eigen::Vector3d(10.0, 0.3, 2.0)
                                         : Eigen::Vector3d(20.0, 10.0, 9.0);
  for (int k = 0; k < 3; ++k)
    if (o.size[k] > 0.0) d[k] = o.size[k];
  return d;
}

double CrownRadius(const OutsideObjectConfig& o) { return o.radius > 0.0 ? o.radius : 1.5; }
double CrownHeight(const OutsideObjectConfig& o) { return o.height > 0.0 ? o.height : 3.0; }

float Reflectivity(const OutsideObjectConfig& o) {
  if (o.reflectivity > 0.0) return static_cast<float>(o.reflectivity);
  return o.type == "tree" ? 0.2f : o.type == "car" ? 0.3f : 0.4f;
}

// Shortest distance between two polygons' outlines (vertices to the other's edges).
double OutlineDistance(const std::vector<Eigen::Vector2d>& a,
                       const std::vector<Eigen::Vector2d>& b) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& p : a) d = std::min(d, DistanceToPolygonEdges(b, p));
  for (const auto& p : b) d = std::min(d, DistanceToPolygonEdges(a, p));
  return d;
}

}  // namespace

std::vector<Eigen::Vector2d> OutsideFootprint(const OutsideObjectConfig& o) {
  std::vector<Eigen::Vector2d> out;
  if (o.type == "tree") {
    const double r = CrownRadius(o);
    for (int k = 0; k < 12; ++k) {
      const double a = 2.0 * M_PI * k / 12.0;
      out.push_back(o.position + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    return out;
  }
  const Eigen::Vector3d s = BoxSize(o);
  const double yaw = o.yaw_deg * M_PI / 180.0;
  const Eigen::Vector2d u(std::cos(yaw), std::sin(yaw)), v(-std::sin(yaw), std::cos(yaw));
  for (const auto& [a, b] : {std::pair<double, double>{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    out.push_back(o.position + 0.5 * a * s.x() * u + 0.5 * b * s.y() * v);
  return out;
}

std::string CheckOutside(const OutsideObjectConfig& o, const agraph::AGraph& graph,
                         const std::string& field) {
  const std::vector<Eigen::Vector2d> foot = OutsideFootprint(o);
  for (const agraph::Room& room : graph.rooms) {
    if (room.polygon.size() < 3) continue;
    bool inside =
        std::any_of(foot.begin(), foot.end(),
                    [&](const Eigen::Vector2d& p) { return PointInPolygon(room.polygon, p); }) ||
        std::any_of(room.polygon.begin(), room.polygon.end(),
                    [&](const Eigen::Vector2d& p) { return PointInPolygon(foot, p); });
    const double gap = OutlineDistance(foot, room.polygon);
    if (!inside && gap >= kOutsideClearance) continue;
    const bool known = room.storey >= 0 && room.storey < static_cast<int>(graph.storeys.size());
    std::ostringstream e;
    e.precision(3);
    e << field << ": the " << o.type << " at (" << o.position.x() << ", " << o.position.y()
      << ") stands " << (inside ? "inside the building" : "against the building") << " (room '"
      << room.name << (room.long_name.empty() ? "" : " (" + room.long_name + ")") << "' of storey '"
      << (known ? graph.storeys[room.storey].name : std::to_string(room.storey)) << "'";
    if (!inside) e << ", " << gap << " m from it";
    e << "; it must keep " << kOutsideClearance << " m outside every room)";
    return e.str();
  }
  return "";
}

double GroundElevation(const agraph::AGraph& graph) {
  double ground = std::numeric_limits<double>::infinity();
  for (const agraph::Room& room : graph.rooms)
    if (room.storey >= 0 && room.storey < static_cast<int>(graph.storeys.size()))
      ground = std::min(ground, graph.storeys[room.storey].elevation);
  return std::isfinite(ground) ? ground : 0.0;
}

Result<std::vector<std::string>> AddOutsideWorld(SceneMesh* scene, const agraph::AGraph& graph,
                                                 const std::vector<OutsideObjectConfig>& objects) {
  using R = Result<std::vector<std::string>>;
  std::vector<std::string> log;
  const double ground = GroundElevation(graph);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const OutsideObjectConfig& o = objects[i];
    const std::string field = "scene.outside[" + std::to_string(i) + "]";
    const std::string error = CheckOutside(o, graph, field);
    if (!error.empty()) return R::Error(error);
    const double z = o.base_z ? *o.base_z : ground;
    const double yaw = o.yaw_deg * M_PI / 180.0;
    std::ostringstream line;
    line.precision(3);
    if (o.type == "tree") {
      scene->AddCylinder(o.position, z, 0.15, 2.5, Reflectivity(o), 8);
      scene->AddCylinder(o.position, z + 2.5, CrownRadius(o), CrownHeight(o), Reflectivity(o));
      line << field << ": a tree at (" << o.position.x() << ", " << o.position.y() << ")";
    } else {
      const Eigen::Vector3d s = BoxSize(o);
      scene->AddBox(o.position, z, s, yaw, Reflectivity(o));
      line << field << ": a " << o.type << " " << s.x() << " x " << s.y() << " x " << s.z()
           << " m at (" << o.position.x() << ", " << o.position.y() << ")";
    }
    log.push_back(line.str());
  }
  return R::Ok(std::move(log));
}

}  // namespace sim
}  // namespace is_graphs
