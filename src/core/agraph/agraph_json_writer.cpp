#include "agraph_json.h"
#include "is_graphs/agraph/agraph_io.h"

namespace is_graphs {
namespace agraph {
namespace internal {
namespace {

using nlohmann::json;

json ToJson(const Eigen::Vector2d& v) { return json::array({v.x(), v.y()}); }
json ToJson(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

template <typename Element_t>
json Header(const Element_t& e) {
  return json{{"id", e.id}, {"ifc_id", e.ifc_id}, {"guid", e.guid}};
}

json ToJson(const Storey& s) {
  json j = Header(s);
  j["name"] = s.name;
  j["elevation"] = s.elevation;
  j["height"] = s.height;
  return j;
}

json ToJson(const WallSurface& s) {
  json j = Header(s);
  j["wall"] = s.wall;
  j["storey"] = s.storey;
  j["normal"] = ToJson(s.plane.normal);
  j["d"] = s.plane.d;
  j["orientation"] = geometry::ToString(s.orientation);
  j["start"] = ToJson(s.start);
  j["end"] = ToJson(s.end);
  j["z_min"] = s.z_min;
  j["z_max"] = s.z_max;
  j["rooms"] = s.rooms;
  return j;
}

json ToJson(const Wall& w) {
  json j = Header(w);
  j["name"] = w.name;
  j["storey"] = w.storey;
  j["surfaces"] = json::array({w.surface_a, w.surface_b});
  j["thickness"] = w.thickness;
  j["start"] = ToJson(w.start);
  j["center"] = ToJson(w.center);
  j["length"] = w.length;
  j["height"] = w.height;
  j["external"] = w.external;
  return j;
}

json ToJson(const Room& r) {
  json j = Header(r);
  j["name"] = r.name;
  j["long_name"] = r.long_name;
  j["storey"] = r.storey;
  json polygon = json::array();
  for (const Eigen::Vector2d& p : r.polygon) polygon.push_back(ToJson(p));
  j["polygon"] = polygon;
  j["z_min"] = r.z_min;
  j["z_max"] = r.z_max;
  j["floor_z"] = r.floor_z;
  j["floor_source"] = r.floor_source;
  j["center"] = ToJson(r.center);
  j["area"] = r.area;
  j["surfaces"] = r.surfaces;
  j["walls"] = r.walls;
  j["doorways"] = r.doorways;
  return j;
}

json ToJson(const Doorway& d) {
  json j = Header(d);
  j["kind"] = ToString(d.kind);
  j["name"] = d.name;
  j["storey"] = d.storey;
  j["wall"] = d.wall;
  j["position"] = ToJson(d.position);
  j["width"] = d.width;
  j["height"] = d.height;
  j["rooms"] = d.rooms;
  return j;
}

template <typename Element_t>
json ArrayToJson(const std::vector<Element_t>& elements) {
  json array = json::array();
  for (const Element_t& e : elements) array.push_back(ToJson(e));
  return array;
}

}  // namespace

json AGraphToJson(const AGraph& graph) {
  json root;
  root["format"] = kAGraphFormatName;
  root["version"] = kAGraphFormatVersion;
  root["source"] = json{{"file", graph.source.file},
                        {"sha256", graph.source.sha256},
                        {"schema", graph.source.schema},
                        {"application", graph.source.application},
                        {"length_unit_m", graph.source.length_unit_m},
                        {"converter_version", graph.source.converter_version}};
  root["building"] = graph.building;
  root["mesh"] = graph.mesh;
  root["storeys"] = ArrayToJson(graph.storeys);
  root["wall_surfaces"] = ArrayToJson(graph.surfaces);
  root["walls"] = ArrayToJson(graph.walls);
  root["rooms"] = ArrayToJson(graph.rooms);
  root["doorways"] = ArrayToJson(graph.doorways);
  root["warnings"] = graph.warnings;
  json report = json::array();
  for (const Storey& s : graph.storeys) {
    json dropped = json::array();
    for (const ConversionDrop& d : graph.dropped)
      if (d.storey == s.id)
        dropped.push_back({{"ifc_class", d.ifc_class}, {"reason", d.reason}, {"count", d.count}});
    report.push_back({{"storey", s.id}, {"name", s.name}, {"dropped", dropped}});
  }
  root["report"] = report;
  return root;
}

}  // namespace internal
}  // namespace agraph
}  // namespace is_graphs
