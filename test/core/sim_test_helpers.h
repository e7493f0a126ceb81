#pragma once

// Small synthetic worlds for the sim tests (no files, no converter).

#include <Eigen/Core>
#include <sstream>
#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/sim/scan_simulator.h"
#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {
namespace testing {

/// Field by field: LidarPoint has padding after `ring`, whose bytes are indeterminate, so a
/// memcmp of whole points can differ on identical points (it did with gcc 14).
inline bool SamePoint(const LidarPoint& p, const LidarPoint& q) {
  return p.x == q.x && p.y == q.y && p.z == q.z && p.intensity == q.intensity && p.ring == q.ring &&
         p.time == q.time && p.column == q.column;
}

inline bool SameScan(const LidarScan& a, const LidarScan& b) {
  if (a.stamp != b.stamp || a.points.size() != b.points.size()) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (!SamePoint(a.points[i], b.points[i])) return false;
  return true;
}

/// The scene BuildScene makes of an inline OBJ (one storey, no rooms, seed 1) under `config`.
inline Result<SceneMesh> SceneOfObj(const std::string& obj_text, const SceneConfig& config) {
  std::istringstream obj(obj_text);
  const auto mesh = geometry::ParseObj(obj, "inline.obj");
  if (!mesh.ok()) return Result<SceneMesh>::Error(mesh.error());
  agraph::AGraph graph;
  graph.storeys.push_back({});
  return BuildScene(mesh.value(), graph, 0, 0.0, config, 1);
}

/// A closed box room [0, sx] x [0, sy] x [0, sz]: floor, ceiling and four walls (0.2 m thick,
/// outside the interval), as a scene. Its inner surfaces are the planes x=0, x=sx, y=0, y=sy,
/// z=0, z=sz.
inline SceneMesh BoxRoom(double sx, double sy, double sz) {
  SceneMesh m;
  const double t = 0.2;
  m.AddBox({0.5 * sx, 0.5 * sy}, -t, {sx + 2 * t, sy + 2 * t, t}, 0.0, 0.3f);  // floor
  m.AddBox({0.5 * sx, 0.5 * sy}, sz, {sx + 2 * t, sy + 2 * t, t}, 0.0, 0.3f);  // ceiling
  m.AddBox({-0.5 * t, 0.5 * sy}, 0.0, {t, sy, sz}, 0.0, 0.5f);                 // x = 0
  m.AddBox({sx + 0.5 * t, 0.5 * sy}, 0.0, {t, sy, sz}, 0.0, 0.5f);             // x = sx
  m.AddBox({0.5 * sx, -0.5 * t}, 0.0, {sx + 2 * t, t, sz}, 0.0, 0.5f);         // y = 0
  m.AddBox({0.5 * sx, sy + 0.5 * t}, 0.0, {sx + 2 * t, t, sz}, 0.0, 0.5f);     // y = sy
  return m;
}

/// Distance from p to the nearest inner surface of BoxRoom(sx, sy, sz).
inline double DistanceToBoxRoom(const Eigen::Vector3d& p, double sx, double sy, double sz) {
  return std::min({std::abs(p.x()), std::abs(p.x() - sx), std::abs(p.y()), std::abs(p.y() - sy),
                   std::abs(p.z()), std::abs(p.z() - sz)});
}

inline agraph::Room MakeRoom(int id, const std::string& name, double x0, double y0, double x1,
                             double y1) {
  agraph::Room r;
  r.id = id;
  r.name = name;
  r.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  r.center = Eigen::Vector3d(0.5 * (x0 + x1), 0.5 * (y0 + y1), 1.25);
  r.z_max = 2.5;
  r.area = (x1 - x0) * (y1 - y0);
  return r;
}

/// Three 4 x 4 m rooms A, B, C in a row along x, separated by 0.2 m x-walls at x = 4.1 and
/// x = 8.3 with doorways (A-B at y = 2, B-C at y = 1), and a room D north of A with no door.
inline agraph::AGraph ThreeRoomsInARow() {
  agraph::AGraph g;
  g.storeys.push_back({0, -1, "", "Ground", 0.0, 2.5});
  g.rooms = {MakeRoom(0, "A", 0.0, 0.0, 4.0, 4.0), MakeRoom(1, "B", 4.2, 0.0, 8.2, 4.0),
             MakeRoom(2, "C", 8.4, 0.0, 12.4, 4.0), MakeRoom(3, "D", 0.0, 4.2, 4.0, 8.2)};
  for (int i = 0; i < 2; ++i) {
    const double x = i == 0 ? 4.1 : 8.3;
    agraph::WallSurface a, b;
    a.id = 2 * i;
    b.id = 2 * i + 1;
    a.wall = b.wall = i;
    a.plane = geometry::Plane(Eigen::Vector3d::UnitX(), x + 0.1);
    b.plane = geometry::Plane(-Eigen::Vector3d::UnitX(), -(x - 0.1));
    g.surfaces.push_back(a);
    g.surfaces.push_back(b);
    agraph::Wall w;
    w.id = i;
    w.name = i == 0 ? "wAB" : "wBC";
    w.surface_a = a.id;
    w.surface_b = b.id;
    w.thickness = 0.2;
    g.walls.push_back(w);
    agraph::Doorway d;
    d.id = i;
    d.name = i == 0 ? "dAB" : "dBC";
    d.wall = i;
    d.position = Eigen::Vector3d(x, i == 0 ? 2.0 : 1.0, 0.0);
    d.width = 0.9;
    d.height = 2.1;
    d.rooms = {i, i + 1};
    g.doorways.push_back(d);
  }
  g.rooms[0].doorways = {0};
  g.rooms[1].doorways = {0, 1};
  g.rooms[2].doorways = {1};
  return g;
}

}  // namespace testing
}  // namespace sim
}  // namespace is_graphs
