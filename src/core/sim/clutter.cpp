#include "is_graphs/sim/clutter.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "is_graphs/sim/random.h"
#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace sim {
namespace {

// Thin poles and rails of a scaffolding bay: centre, size (length x depth x height), yaw.
void AddScaffolding(SceneMesh* mesh, const Eigen::Vector2d& center, double base_z,
                    const Eigen::Vector3d& size, double yaw, float refl) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  auto at = [&](double lx, double ly) {
    return Eigen::Vector2d(center.x() + c * lx - s * ly, center.y() + s * lx + c * ly);
  };
  const double pole = 0.05;
  const int bays = std::max(1, static_cast<int>(std::ceil(size.x() / 1.5)));
  for (int i = 0; i <= bays; ++i) {
    const double lx = -0.5 * size.x() + size.x() * i / bays;
    for (double ly : {-0.5 * size.y(), 0.5 * size.y()}) {
      mesh->AddBox(at(lx, ly), base_z, {pole, pole, size.z()}, yaw, refl);
    }
  }
  for (double z = 1.0; z < size.z() + 1e-6; z += 1.0) {
    for (double ly : {-0.5 * size.y(), 0.5 * size.y()}) {
      mesh->AddBox(at(0.0, ly), base_z + z - pole, {size.x(), pole, pole}, yaw, refl);
    }
  }
  // Working platform (planks) at the top.
  mesh->AddBox(at(0.0, 0.0), base_z + size.z() - 0.05, {size.x(), size.y(), 0.04}, yaw, refl);
}

}  // namespace

ClutterShape ClutterShapeOf(const ClutterConfig& c, double storey_height) {
  ClutterShape s;
  auto pick = [](double given, double fallback) { return given > 0.0 ? given : fallback; };
  if (c.type == "cylinder" || c.type == "person") {
    const bool person = c.type == "person";
    s.cylinder = true;
    const double r = pick(c.radius, person ? 0.25 : 0.3);
    s.size = {2 * r, 2 * r, pick(c.height, person ? 1.75 : 1.0)};
    s.reflectivity = static_cast<float>(pick(c.reflectivity, person ? 0.3 : 0.5));
    return s;
  }
  Eigen::Vector3d def(0.6, 0.4, 0.5);
  double refl = 0.5;
  if (c.type == "pallet") def = {1.2, 0.8, 0.15}, refl = 0.35;
  if (c.type == "column") def = {0.4, 0.4, storey_height}, refl = 0.45;
  if (c.type == "scaffolding") def = {2.5, 0.8, 2.0}, refl = 0.6, s.scaffolding = true;
  for (int k = 0; k < 3; ++k) s.size[k] = pick(c.size[k], def[k]);
  s.reflectivity = static_cast<float>(pick(c.reflectivity, refl));
  return s;
}

void AddClutter(SceneMesh* mesh, const ClutterShape& shape, const Eigen::Vector2d& xy,
                double base_z, double yaw) {
  if (shape.cylinder) {
    mesh->AddCylinder(xy, base_z, 0.5 * shape.size.x(), shape.size.z(), shape.reflectivity);
  } else if (shape.scaffolding) {
    AddScaffolding(mesh, xy, base_z, shape.size, yaw, shape.reflectivity);
  } else {
    mesh->AddBox(xy, base_z, shape.size, yaw, shape.reflectivity);
  }
}

Result<int> PlaceRandomClutter(SceneMesh* scene, const agraph::AGraph& graph, int storey,
                               double floor_z, double storey_height, const RandomClutterConfig& rc,
                               std::uint64_t seed) {
  std::vector<int> rooms;
  for (const std::string& name : rc.rooms) {
    const Result<int> room = FindRoom(graph, storey, name);
    if (!room.ok()) return Result<int>::Error("scene.random_clutter.rooms: " + room.error());
    rooms.push_back(room.value());
  }
  if (rc.rooms.empty()) {
    for (const agraph::Room& r : graph.rooms) {
      if (r.storey == storey) rooms.push_back(r.id);
    }
  }
  if (rooms.empty()) return Result<int>::Error("scene.random_clutter: the storey has no rooms");
  std::mt19937_64 rng(StreamSeed(seed, kStreamClutter));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int placed = 0;
  for (int k = 0; k < rc.count; ++k) {
    const agraph::Room& room =
        graph.rooms[rooms[static_cast<std::size_t>(unit(rng) * rooms.size()) % rooms.size()]];
    ClutterConfig c;
    c.type = rc.types[static_cast<std::size_t>(unit(rng) * rc.types.size()) % rc.types.size()];
    const ClutterShape shape = ClutterShapeOf(c, storey_height);
    const double yaw = unit(rng) * M_PI;
    const double half = 0.5 * std::hypot(shape.size.x(), shape.size.y());
    Eigen::Vector2d lo = room.polygon[0], hi = room.polygon[0];
    for (const Eigen::Vector2d& v : room.polygon) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const Eigen::Vector2d inner = RoomInteriorPoint(room);
    for (int attempt = 0; attempt < 50; ++attempt) {
      const Eigen::Vector2d p(lo.x() + unit(rng) * (hi.x() - lo.x()),
                              lo.y() + unit(rng) * (hi.y() - lo.y()));
      if (!PointInPolygon(room.polygon, p) ||
          DistanceToPolygonEdges(room.polygon, p) < rc.wall_margin + half) {
        continue;
      }
      bool blocks = (p - inner).norm() < half + 0.9;
      for (int d : room.doorways) {
        const Eigen::Vector2d door = graph.doorways[d].position.head<2>();
        const Eigen::Vector2d seg = door - inner;
        const double s =
            std::clamp((p - inner).dot(seg) / std::max(seg.squaredNorm(), 1e-9), 0.0, 1.0);
        blocks = blocks || (inner + s * seg - p).norm() < half + 0.9;
      }
      if (blocks) continue;
      AddClutter(scene, shape, p, FloorUnder(graph, storey, p, floor_z), yaw);
      ++placed;
      break;
    }
  }
  return Result<int>::Ok(placed);
}

}  // namespace sim
}  // namespace is_graphs
