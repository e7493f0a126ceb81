#include "is_graphs/sim/scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "is_graphs/sim/clutter.h"
#include "is_graphs/sim/outside_world.h"
#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace sim {

void SceneMesh::AddTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c, float refl) {
  const int base = static_cast<int>(vertices.size());
  vertices.push_back(a.cast<float>());
  vertices.push_back(b.cast<float>());
  vertices.push_back(c.cast<float>());
  triangles.emplace_back(base, base + 1, base + 2);
  reflectivity.push_back(refl);
}

void SceneMesh::AddBox(const Eigen::Vector2d& center, double base_z, const Eigen::Vector3d& size,
                       double yaw, float refl) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  auto corner = [&](int i) {  // bit 0: x, bit 1: y, bit 2: z
    const double lx = ((i & 1) ? 0.5 : -0.5) * size.x();
    const double ly = ((i & 2) ? 0.5 : -0.5) * size.y();
    return Eigen::Vector3d(center.x() + c * lx - s * ly, center.y() + s * lx + c * ly,
                           base_z + ((i & 4) ? size.z() : 0.0));
  };
  static const int kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : kFaces) {
    AddTriangle(corner(f[0]), corner(f[1]), corner(f[2]), refl);
    AddTriangle(corner(f[0]), corner(f[2]), corner(f[3]), refl);
  }
}

void SceneMesh::AddCylinder(const Eigen::Vector2d& center, double base_z, double radius,
                            double height, float refl, int segments) {
  const Eigen::Vector3d bottom(center.x(), center.y(), base_z);
  const Eigen::Vector3d top = bottom + Eigen::Vector3d(0, 0, height);
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2.0 * M_PI * i / segments, a1 = 2.0 * M_PI * (i + 1) / segments;
    const Eigen::Vector3d p0 = bottom + radius * Eigen::Vector3d(std::cos(a0), std::sin(a0), 0);
    const Eigen::Vector3d p1 = bottom + radius * Eigen::Vector3d(std::cos(a1), std::sin(a1), 0);
    const Eigen::Vector3d up(0, 0, height);
    AddTriangle(p0, p1, p1 + up, refl);
    AddTriangle(p0, p1 + up, p0 + up, refl);
    AddTriangle(top, p0 + up, p1 + up, refl);
    AddTriangle(bottom, p1, p0, refl);
  }
}

namespace {

long IfcIdOfObject(const std::string& name) {
  const std::size_t hash = name.find('#');
  if (hash == std::string::npos) return -1;
  try {
    return std::stol(name.substr(hash + 1));
  } catch (...) {
    return -1;
  }
}

/// close_doorway: the doorway `ref` (by id, or by name unique on the storey; a door or an
/// opening in a wall) filled by a box across its width (+2 cm into the jambs), the wall's
/// thickness (at least 5 cm), `height` tall (0: to the storey's height).
Result<std::string> CloseDoorway(const agraph::AGraph& graph, int storey, const WallRef& ref,
                                 double height, double floor_z, float reflectivity,
                                 const std::string& field, SceneMesh* scene) {
  using R = Result<std::string>;
  int found = -1;
  for (const agraph::Doorway& d : graph.doorways) {
    if (ref.id >= 0 ? d.id != ref.id : (d.storey != storey || d.name != ref.name)) continue;
    if (found >= 0) return R::Error(field + ": doorway name '" + ref.name + "' is not unique");
    found = d.id;
  }
  if (found < 0)
    return R::Error(field + ": no doorway " +
                    (ref.id >= 0 ? "with A-Graph id " + std::to_string(ref.id)
                                 : "named '" + ref.name + "' on storey " + std::to_string(storey)));
  const agraph::Doorway& d = graph.doorways[found];
  const agraph::Wall* wall = nullptr;
  for (const agraph::Wall& w : graph.walls)
    if (w.id == d.wall) wall = &w;
  const int surface = wall ? (wall->surface_a >= 0 ? wall->surface_a : wall->surface_b) : -1;
  if (!d.InWall() || surface < 0 || d.width <= 0.0)
    return R::Error(field + ": doorway '" + d.name + "' is not an opening in a wall");
  const Eigen::Vector3d n = graph.surfaces[surface].plane.normal;
  scene->AddBox(d.position.head<2>(), floor_z,
                {d.width + 0.02, std::max(wall->thickness, 0.05), height},
                std::atan2(n.x(), -n.y()), reflectivity);
  return R::Ok("closed doorway '" + d.name + "' (" + std::to_string(d.width) + " m, " +
               std::to_string(height) + " m high)");
}

Result<int> ResolveWall(const agraph::AGraph& graph, int storey, const WallRef& ref,
                        const std::string& field) {
  if (ref.id >= 0) {
    if (ref.id >= static_cast<int>(graph.walls.size())) {
      return Result<int>::Error(field + ": no wall with A-Graph id " + std::to_string(ref.id) +
                                " (the building has " + std::to_string(graph.walls.size()) +
                                " walls)");
    }
    return Result<int>::Ok(ref.id);
  }
  int found = -1;
  for (const agraph::Wall& w : graph.walls) {
    if (w.storey != storey || w.name != ref.name) continue;
    if (found >= 0) {
      return Result<int>::Error(field + ": wall name '" + ref.name +
                                "' is not unique on the storey; use the A-Graph wall id");
    }
    found = w.id;
  }
  if (found < 0) {
    return Result<int>::Error(field + ": no wall named '" + ref.name + "' on storey " +
                              std::to_string(storey));
  }
  return Result<int>::Ok(found);
}

}  // namespace

Result<SceneMesh> BuildScene(const geometry::TriangleMesh& bim, const agraph::AGraph& graph,
                             int storey, double floor_z, const SceneConfig& config,
                             std::uint64_t seed, SceneReport* report) {
  using R = Result<SceneMesh>;
  SceneReport local;
  SceneReport& log = report ? *report : local;
  const double storey_height =
      (storey < static_cast<int>(graph.storeys.size()) && graph.storeys[storey].height > 0.5)
          ? graph.storeys[storey].height
          : 2.7;

  // Per IFC id: offset to apply (move_wall), turn about a vertical (rotate_wall: centre, angle)
  // or removal (remove_wall).
  std::map<long, Eigen::Vector3d> moved;
  std::map<long, std::pair<Eigen::Vector3d, double>> turned;
  std::set<long> removed;
  SceneMesh scene;
  for (std::size_t i = 0; i < config.deviations.size(); ++i) {
    const DeviationConfig& d = config.deviations[i];
    const std::string field = "scene.deviations[" + std::to_string(i) + "]";
    if (d.type == DeviationConfig::Type::kAddWall) {
      const Eigen::Vector2d dir = d.end - d.start;
      const double height = d.height > 0.0 ? d.height : storey_height;
      scene.AddBox(0.5 * (d.start + d.end), floor_z, {dir.norm(), d.thickness, height},
                   std::atan2(dir.y(), dir.x()), static_cast<float>(config.wall_reflectivity));
      log.lines.push_back(field + ": added a " + std::to_string(dir.norm()) + " m partition");
      continue;
    }
    if (d.type == DeviationConfig::Type::kCloseDoorway) {
      const Result<std::string> closed =
          CloseDoorway(graph, storey, d.doorway, d.height > 0.0 ? d.height : storey_height, floor_z,
                       static_cast<float>(config.wall_reflectivity), field + ".doorway", &scene);
      if (!closed.ok()) return R::Error(closed.error());
      log.lines.push_back(field + ": " + closed.value());
      continue;
    }
    const Result<int> wall = ResolveWall(graph, storey, d.wall, field + ".wall");
    if (!wall.ok()) return R::Error(wall.error());
    const agraph::Wall& w = graph.walls[wall.value()];
    if (d.type == DeviationConfig::Type::kRemoveWall) {
      removed.insert(w.ifc_id);
      log.lines.push_back(field + ": removed wall '" + w.name + "'");
    } else if (d.type == DeviationConfig::Type::kRotateWall) {
      turned[w.ifc_id] = {w.center, d.angle_deg * M_PI / 180.0};
      log.lines.push_back(field + ": turned wall '" + w.name + "' by " +
                          std::to_string(d.angle_deg) + " deg");
    } else {
      const Eigen::Vector3d n =
          w.surface_a >= 0 ? graph.surfaces[w.surface_a].plane.normal : Eigen::Vector3d::UnitX();
      moved[w.ifc_id] = d.offset * Eigen::Vector3d(n.x(), n.y(), 0.0).normalized();
      log.lines.push_back(field + ": moved wall '" + w.name + "' by " + std::to_string(d.offset) +
                          " m");
    }
  }

  const std::set<std::string> drop(config.drop_classes.begin(), config.drop_classes.end());
  if (config.glass.enabled)
    scene.glass.assign(scene.triangles.size(), 0);  // walls added: not glass
  if (config.polished_floor) scene.polished.assign(scene.triangles.size(), 0);
  std::set<long> seen_walls;
  for (std::size_t t = 0; t < bim.triangles.size(); ++t) {
    const int object = bim.triangle_object.empty() ? -1 : bim.triangle_object[t];
    std::string cls;
    long ifc_id = -1;
    if (object >= 0) {
      cls = bim.ObjectClass(object);
      ifc_id = IfcIdOfObject(bim.object_names[object]);
    }
    // IFC4's "...StandardCase" subtypes (IfcDoorStandardCase) are dropped with their class.
    const std::string suffix = "StandardCase";
    const bool standard_case = cls.size() > suffix.size() &&
                               cls.compare(cls.size() - suffix.size(), suffix.size(), suffix) == 0;
    if (drop.count(cls) || (standard_case && drop.count(cls.substr(0, cls.size() - suffix.size()))))
      continue;
    const bool is_wall = cls.rfind("IfcWall", 0) == 0;
    if (is_wall && removed.count(ifc_id)) continue;
    Eigen::Vector3d shift = Eigen::Vector3d::Zero();
    if (is_wall && moved.count(ifc_id)) shift = moved[ifc_id];
    const auto turn = is_wall ? turned.find(ifc_id) : turned.end();
    auto built = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
      if (turn == turned.end()) return p + shift;
      const Eigen::Vector3d& c = turn->second.first;
      const Eigen::Vector3d q =
          c + Eigen::AngleAxisd(turn->second.second, Eigen::Vector3d::UnitZ()) *
                  Eigen::Vector3d(p.x() - c.x(), p.y() - c.y(), 0.0);
      return Eigen::Vector3d(q.x(), q.y(), p.z()) + shift;
    };
    if (is_wall) seen_walls.insert(ifc_id);
    // Floors: slabs (with IFC4's IfcSlabStandardCase / ElementedCase), the site, and the floors
    // the converter makes from space footprints where a storey has no slab.
    const bool is_floor =
        cls.rfind("IfcSlab", 0) == 0 || cls == "IfcSite" || cls == "FloorFromSpace";
    const float refl = static_cast<float>(is_wall    ? config.wall_reflectivity
                                          : is_floor ? config.floor_reflectivity
                                                     : 0.4);
    const Eigen::Vector3i& tri = bim.triangles[t];
    if (config.glass.enabled) scene.glass.push_back(config.glass.IsGlass(cls) ? 1 : 0);
    if (config.polished_floor) scene.polished.push_back(is_floor && cls != "IfcSite" ? 1 : 0);
    scene.AddTriangle(built(bim.vertices[tri[0]]), built(bim.vertices[tri[1]]),
                      built(bim.vertices[tri[2]]), refl);
  }
  std::set<long> deviated;
  for (const auto& kv : moved) deviated.insert(kv.first);
  for (const auto& kv : turned) deviated.insert(kv.first);
  for (long id : deviated) {
    if (!seen_walls.count(id)) {
      return R::Error("scene.deviations: the wall with IFC id " + std::to_string(id) +
                      " has no triangles in the mesh");
    }
  }

  for (std::size_t i = 0; i < config.clutter.size(); ++i) {
    const ClutterConfig& c = config.clutter[i];
    Eigen::Vector2d xy = c.offset;
    if (c.position) {
      xy += *c.position;
    } else {
      const Result<int> room = FindRoom(graph, storey, c.room);
      if (!room.ok()) {
        return R::Error("scene.clutter[" + std::to_string(i) + "].room: " + room.error());
      }
      xy += RoomInteriorPoint(graph.rooms[room.value()]);
    }
    AddClutter(&scene, ClutterShapeOf(c, storey_height), xy, FloorUnder(graph, storey, xy, floor_z),
               c.yaw_deg * M_PI / 180.0);
  }

  // Random clutter, kept off the walls, the doorways and the robot's paths (room interior point
  // to each doorway).
  if (config.random_clutter.count > 0) {
    const Result<int> placed = PlaceRandomClutter(&scene, graph, storey, floor_z, storey_height,
                                                  config.random_clutter, seed);
    if (!placed.ok()) return R::Error(placed.error());
    log.lines.push_back("scene.random_clutter: placed " + std::to_string(placed.value()) + " of " +
                        std::to_string(config.random_clutter.count) + " objects");
  }
  if (scene.triangles.empty()) return R::Error("scene: no triangles left (empty mesh?)");
  const auto outside = AddOutsideWorld(&scene, graph, config.outside);
  if (!outside.ok()) return R::Error(outside.error());
  log.lines.insert(log.lines.end(), outside.value().begin(), outside.value().end());
  if (config.polished_floor) {
    scene.polished.resize(scene.triangles.size(), 0);  // clutter: matt
    const long n = std::count(scene.polished.begin(), scene.polished.end(), 1);
    log.lines.push_back("scene.polished_floor: " + std::to_string(n) + " of " +
                        std::to_string(scene.triangles.size()) + " triangles are polished floor");
  }
  if (config.glass.enabled) {
    scene.glass.resize(scene.triangles.size(), 0);  // clutter: not glass
    const long panes = std::count(scene.glass.begin(), scene.glass.end(), 1);
    if (panes == 0) {
      std::string names;
      for (const std::string& c : config.glass.classes) names += (names.empty() ? "" : ", ") + c;
      return R::Error("scene.glass.classes: no object of " + names +
                      " in the mesh: no glass to see through");
    }
    log.lines.push_back("scene.glass: " + std::to_string(panes) + " of " +
                        std::to_string(scene.triangles.size()) + " triangles are glass");
  }
  return R::Ok(std::move(scene));
}

}  // namespace sim
}  // namespace is_graphs
