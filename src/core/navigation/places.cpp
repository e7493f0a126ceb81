#include "is_graphs/navigation/places.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <set>

#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/sim/room_geometry.h"

namespace is_graphs {
namespace navigation {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

std::string Lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return row[b.size()];
}

double Yaw(const Eigen::Vector2d& direction) { return std::atan2(direction.y(), direction.x()); }

Place Base(const agraph::AGraph& graph, Place::Kind kind, int id, int storey) {
  Place p;
  p.kind = kind;
  p.id = id;
  p.storey = storey;
  if (storey >= 0 && storey < static_cast<int>(graph.storeys.size())) {
    p.storey_name = graph.storeys[storey].name;
    p.position.z() = graph.storeys[storey].elevation;
  }
  return p;
}

bool InsideRoom(const agraph::AGraph& graph, int room, const Eigen::Vector2d& p) {
  return room >= 0 && room < static_cast<int>(graph.rooms.size()) &&
         SignedDistanceToPolygon(graph.rooms[room].polygon, p) > 0.0;
}

// The floor under p on `storey`: its room's floor_z (split levels), else `otherwise`.
double FloorUnder(const agraph::AGraph& graph, int storey, const Eigen::Vector2d& p,
                  double otherwise) {
  for (const auto& r : graph.rooms)
    if (r.storey == storey && r.polygon.size() >= 3 && SignedDistanceToPolygon(r.polygon, p) > 0.0)
      return r.floor_z;
  return otherwise;
}

Place DoorPlace(const agraph::AGraph& graph, const agraph::Doorway& d, const PlaceConfig& c) {
  Place place = Base(graph, Place::Kind::kDoor, d.id, d.storey);
  place.name = d.name;
  place.guid = d.guid;
  Eigen::Vector2d door = d.position.head<2>();
  std::vector<Eigen::Vector2d> candidates;
  if (d.wall >= 0 && d.wall < static_cast<int>(graph.walls.size()) &&
      graph.walls[d.wall].surface_a >= 0) {
    const auto& wall = graph.walls[d.wall];
    const auto& a = graph.surfaces[wall.surface_a];
    const Eigen::Vector2d n = a.plane.normal.head<2>().normalized();
    door -= n * (n.dot(door) - (a.plane.d - 0.5 * wall.thickness));  // onto the mid-plane
    candidates = {door + c.door_standoff * n, door - c.door_standoff * n};
  } else if (!d.rooms.empty()) {  // a virtual separation: from its first room's centre
    const Eigen::Vector2d u = (door - graph.rooms[d.rooms[0]].center.head<2>()).normalized();
    candidates = {door - c.door_standoff * u, door + c.door_standoff * u};
  } else {
    candidates = {door - c.door_standoff * Eigen::Vector2d::UnitX()};
  }
  Eigen::Vector2d chosen = candidates[0];
  bool found = false;
  for (int room : d.rooms)
    for (const auto& q : candidates)
      if (!found && InsideRoom(graph, room, q)) chosen = q, found = true;
  place.position.head<2>() = chosen;
  place.faced = door;
  place.yaw = Yaw(door - chosen);
  return place;
}

Place WallPlace(const agraph::AGraph& graph, const agraph::Wall& w, const PlaceConfig& c) {
  Place place = Base(graph, Place::Kind::kWall, w.id, w.storey);
  place.name = w.name;
  place.guid = w.guid;
  int face = w.surface_a;
  for (int sid : {w.surface_a, w.surface_b})
    if (sid >= 0 && !graph.surfaces[sid].rooms.empty()) {
      face = sid;
      break;
    }
  if (face < 0) {
    place.position.head<2>() = place.faced = w.center.head<2>();
    return place;
  }
  const auto& s = graph.surfaces[face];
  const Eigen::Vector2d n = s.plane.normal.head<2>().normalized();  // out of the wall
  place.faced = 0.5 * (s.start + s.end);
  place.position.head<2>() = place.faced + c.wall_standoff * n;
  place.yaw = Yaw(-n);
  return place;
}

}  // namespace

const char* ToString(Place::Kind kind) {
  switch (kind) {
    case Place::Kind::kRoom:
      return "room";
    case Place::Kind::kDoor:
      return "door";
    case Place::Kind::kWall:
      return "wall";
  }
  return "?";
}

std::string PlaceConfig::Validate() const {
  if (!(door_standoff >= 0.0)) return "door_standoff: must be >= 0";
  if (!(wall_standoff >= 0.0)) return "wall_standoff: must be >= 0";
  if (!(precision > 0.0)) return "precision: must be > 0";
  return "";
}

double SignedDistanceToPolygon(const Polygon& polygon, const Eigen::Vector2d& p) {
  const double d = sim::DistanceToPolygonEdges(polygon, p);
  return sim::PointInPolygon(polygon, p) ? d : -d;
}

Eigen::Vector2d FarthestFromEdges(const Polygon& polygon, double precision, double* distance) {
  Eigen::Vector2d lo = polygon.at(0), hi = polygon.at(0);
  for (const auto& p : polygon) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  struct Cell {
    Eigen::Vector2d c;
    double h, d, max;
  };
  const auto make = [&](const Eigen::Vector2d& c, double h) {
    const double d = SignedDistanceToPolygon(polygon, c);
    return Cell{c, h, d, d + h * std::sqrt(2.0)};
  };
  const auto less = [](const Cell& a, const Cell& b) { return a.max < b.max; };
  std::priority_queue<Cell, std::vector<Cell>, decltype(less)> queue(less);
  const double size = std::max(1e-9, std::min(hi.x() - lo.x(), hi.y() - lo.y()));
  for (double x = lo.x(); x < hi.x(); x += size)
    for (double y = lo.y(); y < hi.y(); y += size)
      queue.push(make(Eigen::Vector2d(x + size / 2, y + size / 2), size / 2));
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : polygon) centroid += p;
  Cell best = make(centroid / polygon.size(), 0.0);
  while (!queue.empty()) {
    const Cell cell = queue.top();
    queue.pop();
    if (cell.d > best.d) best = cell;
    if (cell.max - best.d <= precision) continue;
    const double h = cell.h / 2;
    for (const auto& o : {Eigen::Vector2d(-h, -h), Eigen::Vector2d(h, -h), Eigen::Vector2d(-h, h),
                          Eigen::Vector2d(h, h)})
      queue.push(make(cell.c + o, h));
  }
  if (distance) *distance = best.d;
  return best.c;
}

PlaceIndex::PlaceIndex(const agraph::AGraph& graph, const PlaceConfig& config) {
  for (const auto& s : graph.storeys) storey_names_.push_back(s.name);
  for (const auto& r : graph.rooms) {
    Place p = Base(graph, Place::Kind::kRoom, r.id, r.storey);
    p.name = r.name, p.long_name = r.long_name, p.guid = r.guid;
    p.position.head<2>() = r.polygon.size() >= 3 ? FarthestFromEdges(r.polygon, config.precision)
                                                 : Eigen::Vector2d(r.center.head<2>());
    places_.push_back(p);
  }
  for (const auto& d : graph.doorways) places_.push_back(DoorPlace(graph, d, config));
  for (const auto& w : graph.walls) places_.push_back(WallPlace(graph, w, config));
  for (Place& p : places_)  // on the floor of the room the place stands in (split levels)
    p.position.z() = FloorUnder(graph, p.storey, p.position.head<2>(), p.position.z());
}

Result<std::vector<Place>> PlaceIndex::Locate(const std::string& query,
                                              const std::string& storey) const {
  int only = -1;
  if (!storey.empty()) {
    agraph::AGraph storeys;  // FindStorey reads names only
    for (const auto& n : storey_names_)
      storeys.storeys.push_back(
          agraph::Storey{static_cast<int>(storeys.storeys.size()), -1, "", n});
    const auto found = agraph::FindStorey(storeys, storey);
    if (!found.ok()) return Result<std::vector<Place>>::Error(found.error());
    only = found.value();
  }
  const auto names = [](const Place& p, bool rooms_only_names) {
    std::vector<std::string> n;
    if (p.kind == Place::Kind::kRoom) n = {p.name, p.long_name};
    if (!rooms_only_names || p.kind != Place::Kind::kRoom) n.push_back(p.guid);
    return n;
  };
  std::vector<Place> found;
  for (const bool fold : {false, true}) {
    const std::string q = fold ? Lower(query) : query;
    for (const auto& p : places_) {
      if (only >= 0 && p.storey != only) continue;
      for (const auto& n : names(p, false))
        if (!n.empty() && (fold ? Lower(n) : n) == q) {
          found.push_back(p);
          break;
        }
    }
    if (!found.empty() || query.empty()) break;
  }
  if (!found.empty()) return Result<std::vector<Place>>::Ok(found);
  // The closest names (rooms' names and long names, and GlobalIds), by edit distance.
  std::multimap<size_t, std::string> closest;
  std::set<std::string> seen;
  for (const auto& p : places_) {
    if (only >= 0 && p.storey != only) continue;
    for (const auto& n : names(p, query.size() != 22)) {  // an IFC GlobalId has 22 characters
      if (n.empty() || !seen.insert(n).second) continue;
      closest.emplace(EditDistance(Lower(n), Lower(query)), n);
    }
  }
  std::string message = "no room, door or wall named '" + query + "'";
  if (only >= 0) message += " on storey '" + storey_names_[only] + "'";
  message += "; closest:";
  int shown = 0;
  for (auto it = closest.begin(); it != closest.end() && shown < 5; ++it, ++shown)
    message += (shown ? ", '" : " '") + it->second + "'";
  if (shown == 0) message += " (none: the building has no rooms, doors or walls)";
  return Result<std::vector<Place>>::Error(message);
}

}  // namespace navigation
}  // namespace is_graphs
