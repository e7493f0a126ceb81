#include "agraph_conversions.h"

#include <algorithm>

#include "id_conversions.h"
#include "point_conversions.h"

namespace is_graphs {
namespace ros_conversions {
is_graphs::AGraph ToMsg(const agraph::AGraph& graph) {
  is_graphs::AGraph msg;
  msg.building = graph.building;
  msg.source_file = graph.source.file;
  msg.source_sha256 = graph.source.sha256;
  msg.format_version = static_cast<uint32_t>(graph.format_version);

  for (const auto& s : graph.storeys) {
    is_graphs::Storey m;
    m.id = s.id;
    m.ifc_id = s.ifc_id;
    m.guid = s.guid;
    m.name = s.name;
    m.elevation = s.elevation;
    m.height = s.height;
    msg.storeys.push_back(m);
  }
  for (const auto& s : graph.surfaces) {
    is_graphs::WallSurface m;
    m.id = s.id;
    m.ifc_id = s.ifc_id;
    m.guid = s.guid;
    m.wall_id = static_cast<uint32_t>(std::max(s.wall, 0));
    m.storey_id = s.storey;
    m.normal.x = s.plane.normal.x();
    m.normal.y = s.plane.normal.y();
    m.normal.z = s.plane.normal.z();
    m.d = s.plane.d;
    m.orientation = static_cast<uint8_t>(s.orientation);
    m.start = ToPoint(s.start, s.z_min);
    m.end = ToPoint(s.end, s.z_min);
    m.z_min = s.z_min;
    m.z_max = s.z_max;
    m.room_ids = CastIds<uint32_t>(s.rooms);
    msg.surfaces.push_back(m);
  }
  for (const auto& w : graph.walls) {
    is_graphs::Wall m;
    m.id = w.id;
    m.ifc_id = w.ifc_id;
    m.guid = w.guid;
    m.name = w.name;
    m.storey_id = w.storey;
    m.surface_a_id = w.surface_a;
    m.surface_b_id = w.surface_b;
    m.thickness = w.thickness;
    m.start = ToPoint(w.start);
    m.center = ToPoint(w.center);
    m.length = w.length;
    m.height = w.height;
    m.external = w.external;
    msg.walls.push_back(m);
  }
  for (const auto& r : graph.rooms) {
    is_graphs::ARoom m;
    m.id = r.id;
    m.ifc_id = r.ifc_id;
    m.guid = r.guid;
    m.name = r.name;
    m.long_name = r.long_name;
    m.storey_id = r.storey;
    m.center = ToPoint(r.center);
    for (const auto& v : r.polygon) m.polygon.push_back(ToPoint(v, r.z_min));
    m.z_min = r.z_min;
    m.z_max = r.z_max;
    m.area = r.area;
    m.floor_z = r.floor_z;
    m.surface_ids = CastIds<uint32_t>(r.surfaces);
    m.wall_ids = CastIds<uint32_t>(r.walls);
    m.doorway_ids = CastIds<uint32_t>(r.doorways);
    msg.rooms.push_back(m);
  }
  for (const auto& d : graph.doorways) {
    is_graphs::Doorway m;
    m.id = d.id;
    m.ifc_id = d.ifc_id;
    m.guid = d.guid;
    m.name = d.name;
    m.storey_id = d.storey;
    m.wall_id = d.wall;
    m.position = ToPoint(d.position);
    m.width = d.width;
    m.height = d.height;
    m.room_ids = CastIds<uint32_t>(d.rooms);
    m.kind = static_cast<uint8_t>(d.kind);
    msg.doorways.push_back(m);
  }
  return msg;
}

agraph::AGraph FromMsg(const is_graphs::AGraph& msg) {
  agraph::AGraph graph;
  graph.format_version = static_cast<int>(msg.format_version);
  graph.building = msg.building;
  graph.source.file = msg.source_file;
  graph.source.sha256 = msg.source_sha256;
  for (const auto& m : msg.storeys) {
    agraph::Storey s;
    s.id = static_cast<int>(m.id);
    s.ifc_id = m.ifc_id;
    s.guid = m.guid;
    s.name = m.name;
    s.elevation = m.elevation;
    s.height = m.height;
    graph.storeys.push_back(s);
  }
  for (const auto& m : msg.surfaces) {
    agraph::WallSurface s;
    s.id = static_cast<int>(m.id);
    s.ifc_id = m.ifc_id;
    s.guid = m.guid;
    s.wall = static_cast<int>(m.wall_id);
    s.storey = static_cast<int>(m.storey_id);
    s.plane = geometry::Plane(Eigen::Vector3d(m.normal.x, m.normal.y, m.normal.z), m.d);
    s.orientation = static_cast<geometry::Orientation>(m.orientation);
    s.start = Eigen::Vector2d(m.start.x, m.start.y);
    s.end = Eigen::Vector2d(m.end.x, m.end.y);
    s.z_min = m.z_min;
    s.z_max = m.z_max;
    s.rooms = CastIds<int>(m.room_ids);
    graph.surfaces.push_back(s);
  }
  for (const auto& m : msg.walls) {
    agraph::Wall w;
    w.id = static_cast<int>(m.id);
    w.ifc_id = m.ifc_id;
    w.guid = m.guid;
    w.name = m.name;
    w.storey = static_cast<int>(m.storey_id);
    w.surface_a = static_cast<int>(m.surface_a_id);
    w.surface_b = static_cast<int>(m.surface_b_id);
    w.thickness = m.thickness;
    w.start = FromPoint(m.start);
    w.center = FromPoint(m.center);
    w.length = m.length;
    w.height = m.height;
    w.external = m.external;
    graph.walls.push_back(w);
  }
  for (const auto& m : msg.rooms) {
    agraph::Room r;
    r.id = static_cast<int>(m.id);
    r.ifc_id = m.ifc_id;
    r.guid = m.guid;
    r.name = m.name;
    r.long_name = m.long_name;
    r.storey = static_cast<int>(m.storey_id);
    r.center = FromPoint(m.center);
    for (const auto& p : m.polygon) r.polygon.emplace_back(p.x, p.y);
    r.z_min = m.z_min;
    r.z_max = m.z_max;
    r.area = m.area;
    r.floor_z = m.floor_z;
    r.surfaces = CastIds<int>(m.surface_ids);
    r.walls = CastIds<int>(m.wall_ids);
    r.doorways = CastIds<int>(m.doorway_ids);
    graph.rooms.push_back(r);
  }
  for (const auto& m : msg.doorways) {
    agraph::Doorway d;
    d.id = static_cast<int>(m.id);
    d.ifc_id = m.ifc_id;
    d.guid = m.guid;
    d.name = m.name;
    d.storey = static_cast<int>(m.storey_id);
    d.wall = m.wall_id;
    d.position = FromPoint(m.position);
    d.width = m.width;
    d.height = m.height;
    d.rooms = CastIds<int>(m.room_ids);
    d.kind = m.kind == is_graphs::Doorway::OPENING   ? agraph::DoorwayKind::kOpening
             : m.kind == is_graphs::Doorway::VIRTUAL ? agraph::DoorwayKind::kVirtual
                                                     : agraph::DoorwayKind::kDoor;
    graph.doorways.push_back(d);
  }
  return graph;
}

}  // namespace ros_conversions
}  // namespace is_graphs
