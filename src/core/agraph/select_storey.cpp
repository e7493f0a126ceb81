#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <sstream>

#include "is_graphs/agraph/agraph_queries.h"

namespace is_graphs {
namespace agraph {
namespace {

// Old id -> new id (-1 when the element is not kept).
std::vector<int> Reindex(const std::vector<bool>& keep) {
  std::vector<int> map(keep.size(), -1);
  int next = 0;
  for (size_t i = 0; i < keep.size(); ++i) {
    if (keep[i]) map[i] = next++;
  }
  return map;
}

std::vector<int> MapIds(const std::vector<int>& ids, const std::vector<int>& map) {
  std::vector<int> mapped;
  for (int id : ids) {
    if (id >= 0 && static_cast<size_t>(id) < map.size() && map[id] >= 0) mapped.push_back(map[id]);
  }
  return mapped;
}

int MapId(int id, const std::vector<int>& map) {
  return id >= 0 && static_cast<size_t>(id) < map.size() ? map[id] : -1;
}

}  // namespace

Result<int> FindStorey(const AGraph& graph, const std::string& storey) {
  for (const Storey& s : graph.storeys) {
    if (s.name == storey) return Result<int>::Ok(s.id);
  }
  errno = 0;
  char* end = nullptr;
  const long index = std::strtol(storey.c_str(), &end, 10);
  if (!storey.empty() && *end == '\0' && errno == 0 && index >= 0 &&
      static_cast<size_t>(index) < graph.storeys.size()) {
    return Result<int>::Ok(static_cast<int>(index));
  }
  std::string known;
  for (const Storey& s : graph.storeys) {
    known += (known.empty() ? "" : ", ") + std::to_string(s.id) + " \"" + s.name + "\"";
  }
  return Result<int>::Error("unknown storey \"" + storey +
                            "\" (storeys: " + (known.empty() ? "none" : known) + ")");
}

Result<AGraph> SelectStorey(const AGraph& graph, const std::string& storey) {
  const Result<int> index = FindStorey(graph, storey);
  if (!index.ok()) return Result<AGraph>::Error(index.error());
  return SelectStorey(graph, index.value());
}

Result<AGraph> SelectStorey(const AGraph& graph, int storey_index) {
  if (storey_index < 0 || static_cast<size_t>(storey_index) >= graph.storeys.size()) {
    return Result<AGraph>::Error("storey index " + std::to_string(storey_index) +
                                 " out of range (" + std::to_string(graph.storeys.size()) +
                                 " storeys)");
  }
  std::vector<bool> keep_wall(graph.walls.size()), keep_surface(graph.surfaces.size());
  std::vector<bool> keep_room(graph.rooms.size()), keep_doorway(graph.doorways.size());
  for (const Wall& w : graph.walls) keep_wall[w.id] = w.storey == storey_index;
  const std::vector<int> wall_map = Reindex(keep_wall);
  for (const WallSurface& s : graph.surfaces) {
    keep_surface[s.id] = MapId(s.wall, wall_map) >= 0;  // with its wall
  }
  for (const Room& r : graph.rooms) keep_room[r.id] = r.storey == storey_index;
  const std::vector<int> room_map = Reindex(keep_room);

  AGraph out;
  out.format_version = graph.format_version;
  out.source = graph.source;
  out.building = graph.building;
  out.mesh = graph.mesh;
  out.warnings = graph.warnings;
  for (const Doorway& d : graph.doorways) {
    keep_doorway[d.id] = d.storey == storey_index && !MapIds(d.rooms, room_map).empty();
    if (d.storey == storey_index && !keep_doorway[d.id]) {
      out.warnings.push_back("doorway " + std::to_string(d.id) + " (IfcDoor #" +
                             std::to_string(d.ifc_id) + ") dropped: none of its rooms is on " +
                             "storey \"" + graph.storeys[storey_index].name + "\"");
    }
  }
  const std::vector<int> surface_map = Reindex(keep_surface);
  const std::vector<int> doorway_map = Reindex(keep_doorway);

  Storey storey = graph.storeys[storey_index];
  storey.id = 0;
  out.storeys.push_back(storey);
  for (WallSurface s : graph.surfaces) {
    if (!keep_surface[s.id]) continue;
    s.id = surface_map[s.id];
    s.storey = 0;
    s.wall = wall_map[s.wall];
    s.rooms = MapIds(s.rooms, room_map);
    out.surfaces.push_back(s);
  }
  for (Wall w : graph.walls) {
    if (!keep_wall[w.id]) continue;
    w.id = wall_map[w.id];
    w.storey = 0;
    w.surface_a = surface_map[w.surface_a];
    w.surface_b = surface_map[w.surface_b];
    out.walls.push_back(w);
  }
  for (Room r : graph.rooms) {
    if (!keep_room[r.id]) continue;
    r.id = room_map[r.id];
    r.storey = 0;
    r.surfaces = MapIds(r.surfaces, surface_map);
    r.walls = MapIds(r.walls, wall_map);
    r.doorways = MapIds(r.doorways, doorway_map);
    out.rooms.push_back(r);
  }
  for (Doorway d : graph.doorways) {
    if (!keep_doorway[d.id]) continue;
    d.id = doorway_map[d.id];
    d.storey = 0;
    d.wall = MapId(d.wall, wall_map);
    d.rooms = MapIds(d.rooms, room_map);
    out.doorways.push_back(d);
  }
  return Result<AGraph>::Ok(std::move(out));
}

double StoreyFloor(const agraph::AGraph& building, int storey) {
  constexpr double kMaxStep = 0.6;  // m: a split level; more is another storey (or a bad floor)
  const double elevation = building.storeys[storey].elevation;
  double lowest = elevation;
  for (const agraph::Room& r : building.rooms)
    if (r.storey == building.storeys[storey].id && r.floor_z >= elevation - kMaxStep)
      lowest = std::min(lowest, r.floor_z);
  return lowest;
}

int StoreyAtHeight(const agraph::AGraph& building, double z) {
  int best = -1;
  double best_floor = 0.0;
  for (size_t i = 0; i < building.storeys.size(); ++i) {
    const double floor = StoreyFloor(building, static_cast<int>(i));
    if (floor > z + 0.05) continue;
    if (best < 0 || floor > best_floor) best = static_cast<int>(i), best_floor = floor;
  }
  return best < 0 ? -1 : building.storeys[best].id;
}

std::string HeightOutsideStoreys(const agraph::AGraph& building, double z, double margin) {
  if (building.storeys.empty()) return "";
  constexpr double kDefaultStoreyHeight = 3.0;  // m, where the IFC gives no height
  double lowest = StoreyFloor(building, 0), top = building.storeys.front().elevation;
  for (size_t i = 0; i < building.storeys.size(); ++i) {
    const agraph::Storey& s = building.storeys[i];
    lowest = std::min(lowest, StoreyFloor(building, static_cast<int>(i)));
    top = std::max(top, s.elevation + (s.height > 0.0 ? s.height : kDefaultStoreyHeight));
  }
  if (z >= lowest - margin && z <= top + margin) return "";
  std::ostringstream out;
  out.precision(3);
  out << "the robot is at z = " << z << " m in the BIM, " << (z < lowest ? "below" : "above")
      << " every storey (" << lowest << " to " << top
      << " m): it left the building's storeys, or its height in the BIM is wrong";
  return out.str();
}

}  // namespace agraph
}  // namespace is_graphs
