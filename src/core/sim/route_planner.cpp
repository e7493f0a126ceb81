#include "is_graphs/sim/route_planner.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "is_graphs/sim/room_geometry.h"
#include "shortest_path.h"

namespace is_graphs {
namespace sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using Polygons = std::vector<std::vector<Eigen::Vector2d>>;

// A doorway's crossing: the point in front of it on each side of its wall.
struct Crossing {
  int doorway;
  int room_a, room_b;
  Eigen::Vector2d side_a, side_b;  // approach points in room_a / room_b
};

Crossing MakeCrossing(const agraph::AGraph& g, const agraph::Doorway& d, double clearance) {
  Crossing c{d.id, d.rooms[0], d.rooms[1], {}, {}};
  const Eigen::Vector2d door = d.position.head<2>();
  const Eigen::Vector2d inner_a = RoomInteriorPoint(g.rooms[c.room_a]);
  const Eigen::Vector2d inner_b = RoomInteriorPoint(g.rooms[c.room_b]);
  Eigen::Vector2d n = (inner_b - inner_a).normalized();
  double half_thickness = 0.1;
  if (d.wall >= 0 && d.wall < static_cast<int>(g.walls.size())) {
    const agraph::Wall& w = g.walls[d.wall];
    half_thickness = 0.5 * w.thickness;
    if (w.surface_a >= 0) n = g.surfaces[w.surface_a].plane.normal.head<2>().normalized();
  }
  // Orient n from room a to room b: a's side is the one its interior point is on.
  if ((inner_a - door).dot(n) > 0.0) n = -n;
  const double offset = half_thickness + clearance;
  c.side_a = door - offset * n;
  c.side_b = door + offset * n;
  return c;
}

}  // namespace

Result<Route> PlanRoute(const agraph::AGraph& g, int storey, const TrajectoryConfig& config,
                        const std::string& field, const std::vector<StairPath>& all_stairs) {
  using R = Result<Route>;
  Route route;
  const TrajectoryConfig& c = config;

  if (!c.waypoints.empty()) {
    for (const WaypointConfig& w : c.waypoints)
      route.waypoints.push_back({w.position, w.yaw, true});
    if (c.start.pose) {
      route.start = *c.start.pose;
    } else if (!c.start.room.empty()) {
      const Result<int> room = FindRoom(g, storey, c.start.room);
      if (!room.ok()) return R::Error(field + ".start.room: " + room.error());
      route.start.head<2>() = RoomInteriorPoint(g.rooms[room.value()]);
    } else {
      route.start.head<2>() = route.waypoints.front().position;
      route.start.z() = route.waypoints.front().yaw.value_or(0.0);
      route.waypoints.erase(route.waypoints.begin());
    }
    if (!c.start.pose && !route.waypoints.empty()) {
      const Eigen::Vector2d d = route.waypoints.front().position - route.start.head<2>();
      if (d.norm() > 1e-3) route.start.z() = std::atan2(d.y(), d.x());
    }
    route.description.push_back("explicit waypoints: " + std::to_string(c.waypoints.size()));
    return R::Ok(route);
  }

  // Rooms to visit, as ids; the start room first. Each is looked up from the storey before it.
  std::vector<int> targets;
  std::vector<std::string> fields;
  int on_storey = storey;
  if (!c.start.room.empty()) {
    const Result<int> room = FindRoom(g, storey, c.start.room);
    if (!room.ok()) return R::Error(field + ".start.room: " + room.error());
    targets.push_back(room.value());
    fields.push_back(field + ".start.room ('" + c.start.room + "')");
  }
  for (std::size_t i = 0; i < c.rooms.size(); ++i) {
    const std::string f = field + ".rooms[" + std::to_string(i) + "]";
    const Result<int> room = targets.empty() ? FindRoom(g, storey, c.rooms[i])
                                             : FindRoomInBuilding(g, on_storey, c.rooms[i]);
    if (!room.ok()) return R::Error(f + ": " + room.error());
    on_storey = g.rooms[room.value()].storey;
    if (!targets.empty() && targets.back() == room.value() && targets.size() == 1 && i == 0) {
      continue;  // the start room named again first
    }
    targets.push_back(room.value());
    fields.push_back(f + " ('" + c.rooms[i] + "')");
  }
  Eigen::Vector2d position = RoomInteriorPoint(g.rooms[targets.front()]);
  if (c.start.pose) {
    position = c.start.pose->head<2>();
    if (!PointInPolygon(g.rooms[targets.front()].polygon, position)) {
      return R::Error(field + ".start.pose: not inside the first room '" +
                      g.rooms[targets.front()].name + "'");
    }
  }

  // Stairs only for a route whose rooms span storeys (one storey's routes are as they were).
  bool across = false;
  for (int t : targets) across = across || g.rooms[t].storey != g.rooms[targets.front()].storey;
  const std::vector<StairPath> no_stairs;
  const std::vector<StairPath>& stairs = across ? all_stairs : no_stairs;

  // Doorway graph of the building: doorways join rooms of one storey, stairs rooms of two.
  std::vector<Crossing> crossings;
  for (const agraph::Doorway& d : g.doorways) {
    if (d.rooms.size() != 2 || d.rooms[0] == d.rooms[1]) continue;
    if (g.rooms[d.rooms[0]].storey != g.rooms[d.rooms[1]].storey) continue;
    crossings.push_back(MakeCrossing(g, d, c.doorway_clearance));
  }
  const int n_rooms = static_cast<int>(g.rooms.size());
  auto edge = [&](int u, int v) {  // cheapest crossing between rooms u and v
    double best = kInf;
    for (const Crossing& x : crossings) {
      if ((x.room_a == u && x.room_b == v) || (x.room_a == v && x.room_b == u)) {
        const Eigen::Vector2d pu = x.room_a == u ? x.side_a : x.side_b;
        const Eigen::Vector2d pv = x.room_a == u ? x.side_b : x.side_a;
        best = std::min(best, (RoomInteriorPoint(g.rooms[u]) - pu).norm() + (pu - pv).norm() +
                                  (pv - RoomInteriorPoint(g.rooms[v])).norm());
      }
    }
    return best;
  };
  std::vector<std::vector<double>> cost(n_rooms, std::vector<double>(n_rooms, kInf));
  for (const Crossing& x : crossings) {
    cost[x.room_a][x.room_b] = cost[x.room_b][x.room_a] = edge(x.room_a, x.room_b);
  }
  for (const StairPath& st : stairs) {
    const double length =
        (RoomInteriorPoint(g.rooms[st.lower_room]) - st.points.front().head<2>()).norm() +
        st.Length() +
        (st.points.back().head<2>() - RoomInteriorPoint(g.rooms[st.upper_room])).norm();
    double& e = cost[st.lower_room][st.upper_room];
    e = cost[st.upper_room][st.lower_room] = std::min(e, length);
  }
  // The stair footprints a walk inside a room on a storey keeps clear of.
  std::map<int, Polygons> obstacles;  // by storey, gathered once
  for (const StairPath& st : stairs) {
    if (st.footprint.size() < 3) continue;
    obstacles[st.lower_storey].push_back(st.footprint);
    obstacles[st.upper_storey].push_back(st.footprint);
  }
  auto obstacles_on = [&](int on) -> const Polygons& { return obstacles[on]; };
  // Whether a room's interior point is clear of its storey's stairs (a stairwell's may lie on
  // a flight or over the opening: a room passed through is then crossed without it).
  auto centre_clear = [&](int room) {
    const Eigen::Vector2d p = RoomInteriorPoint(g.rooms[room]);
    for (const auto& o : obstacles_on(g.rooms[room].storey)) {
      if (PointInPolygon(o, p) || DistanceToPolygonEdges(o, p) < 0.3) return false;
    }
    return true;
  };
  // The stair between rooms u and v (the shortest), or nullptr.
  auto stair_between = [&](int u, int v) -> const StairPath* {
    const StairPath* best = nullptr;
    for (const StairPath& st : stairs) {
      if (!((st.lower_room == u && st.upper_room == v) ||
            (st.lower_room == v && st.upper_room == u)))
        continue;
      if (!best || st.Length() < best->Length()) best = &st;
    }
    return best;
  };

  route.start = Eigen::Vector3d(position.x(), position.y(), c.start.pose ? c.start.pose->z() : 0.0);
  auto walk_to = [&](int room, const Eigen::Vector2d& goal, bool pause) {
    const agraph::Room& r = g.rooms[room];
    const std::vector<Eigen::Vector2d> path =
        PathInsideRoom(r.polygon, position, goal, 0.3, obstacles_on(r.storey));
    for (std::size_t i = 0; i < path.size(); ++i) {
      route.waypoints.push_back({path[i], std::nullopt, pause && i + 1 == path.size()});
    }
    position = goal;
  };
  for (std::size_t i = 1; i < targets.size(); ++i) {
    if (targets[i] == targets[i - 1]) continue;
    const std::vector<int> rooms =
        Dijkstra(n_rooms, targets[i - 1], targets[i], [&](int u, int v) { return cost[u][v]; });
    if (rooms.empty()) {
      const int from = g.rooms[targets[i - 1]].storey, to = g.rooms[targets[i]].storey;
      std::string why;
      if (from != to && stairs.empty()) {
        why =
            ": no walkable stair was found in the building's mesh (IfcStair / IfcStairFlight "
            "with treads; make_bag's 'stairs: not walked' lines say why)";
      } else if (from != to) {
        why = " (storey '" + g.storeys[from].name + "' to '" + g.storeys[to].name + "')";
      }
      return R::Error(fields[i] + ": not reachable from '" + g.rooms[targets[i - 1]].name +
                      "' through the doorways" + (stairs.empty() ? "" : " and stairs") +
                      " of the building (from storey " + std::to_string(from) + ")" + why);
    }
    int current = targets[i - 1];
    std::string leg = g.rooms[current].name;
    for (std::size_t k = 0; k < rooms.size(); ++k) {
      const int next = rooms[k];
      // Into the next room's interior point when it is a room to visit, or when the walk goes on
      // through a doorway; on to a stair (or off one) straight.
      const bool via_centre =
          next == targets[i] ||
          (g.rooms[next].storey == g.rooms[current].storey && centre_clear(next) &&
           (k + 1 == rooms.size() || g.rooms[rooms[k + 1]].storey == g.rooms[next].storey));
      if (g.rooms[next].storey != g.rooms[current].storey) {
        const StairPath& st = *stair_between(current, next);
        std::vector<Eigen::Vector3d> steps = st.points;
        if (st.lower_room != current) std::reverse(steps.begin(), steps.end());
        walk_to(current, steps.front().head<2>(), false);
        for (std::size_t j = 1; j < steps.size(); ++j)
          route.waypoints.push_back({steps[j].head<2>(), std::nullopt, false});
        position = steps.back().head<2>();
        ++route.stairs_taken;
        leg += std::string(" -> [") + (st.lower_room == current ? "up " : "down ") + st.name +
               "] -> " + g.rooms[next].name + " (" + g.storeys[g.rooms[next].storey].name + ")";
      } else {
        const Crossing* best = nullptr;
        double best_cost = kInf;
        for (const Crossing& x : crossings) {
          if (!((x.room_a == current && x.room_b == next) ||
                (x.room_a == next && x.room_b == current))) {
            continue;
          }
          const Eigen::Vector2d near = x.room_a == current ? x.side_a : x.side_b;
          const double cst = (near - position).norm();
          if (cst < best_cost) best_cost = cst, best = &x;
        }
        const Eigen::Vector2d near = best->room_a == current ? best->side_a : best->side_b;
        const Eigen::Vector2d far = best->room_a == current ? best->side_b : best->side_a;
        walk_to(current, near, false);
        route.waypoints.push_back({far, std::nullopt, false});  // straight through the doorway
        position = far;
        leg += " -> [" + g.doorways[best->doorway].name + "] -> " + g.rooms[next].name;
      }
      if (via_centre) walk_to(next, RoomInteriorPoint(g.rooms[next]), next == targets[i]);
      current = next;
    }
    route.description.push_back(leg);
  }
  route.end_storey = g.rooms[targets.back()].storey;
  if (!route.waypoints.empty() && !c.start.pose) {
    const Eigen::Vector2d d = route.waypoints.front().position - route.start.head<2>();
    if (d.norm() > 1e-3) route.start.z() = std::atan2(d.y(), d.x());
  }
  return R::Ok(route);
}

}  // namespace sim
}  // namespace is_graphs
