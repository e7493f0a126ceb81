#include "is_graphs/sim/movers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "is_graphs/sim/route_planner.h"
#include "is_graphs/sim/simulation.h"

namespace is_graphs {
namespace sim {
namespace {

constexpr double kPersonRadius = 0.25, kPersonHeight = 1.75;
constexpr double kCartLength = 1.0, kCartWidth = 0.6, kCartHeight = 1.0;
constexpr double kDoorThickness = 0.04, kDoorMaxHeight = 2.0;
constexpr double kRobotClearance = 0.8;  // m a mover keeps from the robot's centre
constexpr double kMaxHoldBack = 5.0;     // m a mover is held back along its path at most

std::string Xy(const Eigen::Vector2d& p) {
  std::ostringstream out;
  out.precision(2);
  out << std::fixed << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

bool InPolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d &a = polygon[j], &b = polygon[i];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside;
}

bool Named(const agraph::Room& room, const std::string& name) {
  return room.name == name || (!room.long_name.empty() && room.long_name == name);
}

// The doorway of `storey` a door config names, or an error naming the field.
Result<int> FindDoorway(const agraph::AGraph& g, int storey, const SwingingDoorConfig& c,
                        const std::string& f) {
  for (const agraph::Doorway& d : g.doorways) {
    if (d.storey != storey || !d.InWall()) continue;
    if (!c.doorway.empty() && (d.name == c.doorway || d.guid == c.doorway))
      return Result<int>::Ok(d.id);
    if (c.between.size() == 2 && d.rooms.size() == 2) {
      const agraph::Room &a = g.rooms[d.rooms[0]], &b = g.rooms[d.rooms[1]];
      if ((Named(a, c.between[0]) && Named(b, c.between[1])) ||
          (Named(a, c.between[1]) && Named(b, c.between[0])))
        return Result<int>::Ok(d.id);
    }
  }
  return Result<int>::Error(c.doorway.empty() ? f + ".between: no door or opening joins '" +
                                                    c.between[0] + "' and '" + c.between[1] +
                                                    "' on storey '" + g.storeys[storey].name + "'"
                                              : f + ".doorway: no door or opening '" + c.doorway +
                                                    "' on storey '" + g.storeys[storey].name + "'");
}

// A ray against a vertical cylinder's side: the entry distance, or +inf.
double HitCylinder(const MovingBody& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                   Eigen::Vector3d* normal) {
  const Eigen::Vector2d o2 = o.head<2>() - b.centre, d2 = d.head<2>();
  const double a = d2.squaredNorm();
  if (a < 1e-12) return std::numeric_limits<double>::infinity();
  const double half_b = o2.dot(d2), c = o2.squaredNorm() - b.radius * b.radius;
  const double disc = half_b * half_b - a * c;
  if (disc < 0.0 || c <= 0.0) return std::numeric_limits<double>::infinity();  // miss, inside
  const double t = (-half_b - std::sqrt(disc)) / a;
  const double z = o.z() + t * d.z();
  if (t <= 0.0 || z < b.base_z || z > b.base_z + b.size.z())
    return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d n = (o2 + t * d2) / b.radius;
  *normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
  return t;
}

// A ray against a box turned by yaw: the entry distance, or +inf.
double HitBox(const MovingBody& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
              Eigen::Vector3d* normal) {
  const double c = std::cos(b.yaw), s = std::sin(b.yaw);
  const Eigen::Vector3d p(o.x() - b.centre.x(), o.y() - b.centre.y(),
                          o.z() - (b.base_z + 0.5 * b.size.z()));
  const Eigen::Vector3d lo(c * p.x() + s * p.y(), -s * p.x() + c * p.y(), p.z());
  const Eigen::Vector3d ld(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
  double t_in = -std::numeric_limits<double>::infinity();
  double t_out = std::numeric_limits<double>::infinity();
  int axis = -1;
  for (int k = 0; k < 3; ++k) {
    const double half = 0.5 * b.size[k];
    if (std::abs(ld[k]) < 1e-12) {
      if (std::abs(lo[k]) > half) return std::numeric_limits<double>::infinity();
      continue;
    }
    double t0 = (-half - lo[k]) / ld[k], t1 = (half - lo[k]) / ld[k];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_in) t_in = t0, axis = k;
    t_out = std::min(t_out, t1);
  }
  if (axis < 0 || t_in > t_out || t_in <= 0.0) return std::numeric_limits<double>::infinity();
  Eigen::Vector3d n_local = Eigen::Vector3d::Zero();
  n_local[axis] = ld[axis] > 0.0 ? -1.0 : 1.0;
  *normal = Eigen::Vector3d(c * n_local.x() - s * n_local.y(), s * n_local.x() + c * n_local.y(),
                            n_local.z());
  return t_in;
}

}  // namespace

bool IntersectBodies(const std::vector<MovingBody>& bodies, const Ray& ray, float max_distance,
                     float* distance, Eigen::Vector3f* normal, float* reflectivity) {
  const Eigen::Vector3d o = ray.origin.cast<double>(), d = ray.direction.cast<double>();
  double best = max_distance;
  bool hit = false;
  for (const MovingBody& b : bodies) {
    Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
    const double t = b.box ? HitBox(b, o, d, &n) : HitCylinder(b, o, d, &n);
    if (t < best) {
      best = t, hit = true;
      *normal = n.cast<float>();
      *reflectivity = b.reflectivity;
    }
  }
  if (hit) *distance = static_cast<float>(best);
  return hit;
}

Eigen::Vector2d Movers::AlongPath(const std::vector<Eigen::Vector2d>& path, double s,
                                  Eigen::Vector2d* heading) {
  double total = 0.0;
  for (size_t i = 1; i < path.size(); ++i) total += (path[i] - path[i - 1]).norm();
  *heading = Eigen::Vector2d::UnitX();
  if (path.size() < 2 || total < 1e-9) return path.empty() ? Eigen::Vector2d::Zero() : path[0];
  double u = std::fmod(std::max(0.0, s), 2.0 * total);
  const bool back = u > total;
  if (back) u = 2.0 * total - u;
  for (size_t i = 1; i < path.size(); ++i) {
    const Eigen::Vector2d leg = path[i] - path[i - 1];
    const double length = leg.norm();
    if (length < 1e-9) continue;
    if (u <= length || i + 1 == path.size()) {
      *heading = (back ? -leg : leg) / length;
      return path[i - 1] + std::min(u, length) / length * leg;
    }
    u -= length;
  }
  return path.back();
}

Result<Movers> Movers::Create(const std::vector<MoverConfig>& people,
                              const std::vector<SwingingDoorConfig>& doors,
                              const agraph::AGraph& graph, int storey, double floor_z,
                              const EmbreeScene& scene, RobotAt robot) {
  using R = Result<Movers>;
  Movers out;
  out.floor_z_ = floor_z;
  out.robot_ = std::move(robot);
  for (size_t i = 0; i < people.size(); ++i) {
    const MoverConfig& c = people[i];
    const std::string f = "scene.people[" + std::to_string(i) + "]";
    Person p{c, {}};
    if (!c.rooms.empty()) {
      TrajectoryConfig walk;
      walk.rooms = c.rooms;
      walk.doorway_clearance = 0.5;
      const Result<Route> route = PlanRoute(graph, storey, walk, f);
      if (!route.ok()) return R::Error(route.error());
      p.path.push_back(route.value().start.head<2>());
      for (const PlanarWaypoint& w : route.value().waypoints) p.path.push_back(w.position);
    } else {
      for (size_t j = 0; j < c.waypoints.size(); ++j) {
        const bool in_a_room =
            std::any_of(graph.rooms.begin(), graph.rooms.end(), [&](const agraph::Room& room) {
              return room.storey == storey && room.polygon.size() >= 3 &&
                     InPolygon(room.polygon, c.waypoints[j]);
            });
        if (!in_a_room)
          return R::Error(f + ".waypoints[" + std::to_string(j) + "]: " + Xy(c.waypoints[j]) +
                          " is in no room of storey '" + graph.storeys[storey].name + "'");
      }
      p.path = c.waypoints;
    }
    for (size_t j = 1; j < p.path.size(); ++j) {
      const std::string blocked = CheckWalkable(scene, p.path[j - 1], p.path[j], floor_z);
      if (!blocked.empty())
        return R::Error(f + (c.rooms.empty() ? ".waypoints" : ".rooms") + ": the walk from " +
                        Xy(p.path[j - 1]) + " to " + Xy(p.path[j]) + " is " + blocked +
                        " in the scene as built");
    }
    double length = 0.0;
    for (size_t j = 1; j < p.path.size(); ++j) length += (p.path[j] - p.path[j - 1]).norm();
    out.log_.push_back(f + ": a " + c.type + " walking " + std::to_string(length).substr(0, 5) +
                       " m back and forth from " + Xy(p.path.front()));
    out.people_.push_back(std::move(p));
  }
  for (size_t i = 0; i < doors.size(); ++i) {
    const std::string f = "scene.doors[" + std::to_string(i) + "]";
    const Result<int> found = FindDoorway(graph, storey, doors[i], f);
    if (!found.ok()) return R::Error(found.error());
    const agraph::Doorway& d = graph.doorways[found.value()];
    Door door;
    door.config = doors[i];
    door.middle = d.position.head<2>();
    door.width = d.width > 0.2 ? d.width : 0.9;
    door.height = std::min(kDoorMaxHeight, d.height > 0.5 ? d.height : kDoorMaxHeight);
    Eigen::Vector2d along = Eigen::Vector2d::Zero();
    if (d.wall >= 0 && d.wall < static_cast<int>(graph.walls.size()))
      along = (graph.walls[d.wall].center - graph.walls[d.wall].start).head<2>();
    if (along.norm() < 1e-6 && d.rooms.size() == 2) {
      const Eigen::Vector2d across =
          (graph.rooms[d.rooms[1]].center - graph.rooms[d.rooms[0]].center).head<2>();
      along = Eigen::Vector2d(-across.y(), across.x());
    }
    if (along.norm() < 1e-6) return R::Error(f + ": the doorway's wall has no direction");
    door.along = along.normalized();
    door.hinge = door.middle - 0.5 * door.width * door.along;
    out.log_.push_back(f + ": doorway '" + d.name + "' at " + Xy(door.middle) + " swinging every " +
                       std::to_string(door.config.period).substr(0, 5) + " s");
    out.doors_.push_back(door);
  }
  return R::Ok(std::move(out));
}

std::vector<MovingBody> Movers::BodiesAt(double t) const {
  std::vector<MovingBody> bodies;
  if (empty()) return bodies;
  const Eigen::Vector2d robot = robot_ ? robot_(t) : Eigen::Vector2d(1e9, 1e9);
  for (const Person& p : people_) {
    const bool cart = p.config.type == "cart";
    const double speed = p.config.speed > 0.0 ? p.config.speed : (cart ? 0.8 : 1.3);
    // Keeps clear of the robot: held back along its own path (in the free space it was checked
    // walkable in) to the last point at least kRobotClearance from the robot, as someone who
    // waits for the robot to pass.
    Eigen::Vector2d heading;
    double s = speed * (t + p.config.start);
    Eigen::Vector2d at = AlongPath(p.path, s, &heading);
    for (double back = 0.0; (at - robot).norm() < kRobotClearance && back < kMaxHoldBack;) {
      back += 0.05;
      at = AlongPath(p.path, s - back, &heading);
    }
    MovingBody b;
    b.box = cart;
    b.centre = at;
    b.yaw = std::atan2(heading.y(), heading.x());
    b.radius = kPersonRadius;
    b.size = cart ? Eigen::Vector3d(kCartLength, kCartWidth, kCartHeight)
                  : Eigen::Vector3d(0.0, 0.0, kPersonHeight);
    b.base_z = floor_z_;
    b.reflectivity = static_cast<float>(p.config.reflectivity > 0.0 ? p.config.reflectivity
                                                                    : (cart ? 0.5 : 0.3));
    bodies.push_back(b);
  }
  for (const Door& d : doors_) {
    const SwingingDoorConfig& c = d.config;
    double angle = 0.5 * c.open_deg * (1.0 - std::cos(2.0 * M_PI * (t / c.period + c.phase)));
    if ((robot - d.middle).norm() < c.hold_distance) angle = c.open_deg;
    const double a = angle * M_PI / 180.0;
    const Eigen::Vector2d u(std::cos(a) * d.along.x() - std::sin(a) * d.along.y(),
                            std::sin(a) * d.along.x() + std::cos(a) * d.along.y());
    MovingBody b;
    b.box = true;
    b.centre = d.hinge + 0.5 * d.width * u;
    b.yaw = std::atan2(u.y(), u.x());
    b.size = Eigen::Vector3d(d.width - 0.02, kDoorThickness, d.height);
    b.base_z = floor_z_;
    b.reflectivity = 0.5f;
    bodies.push_back(b);
  }
  return bodies;
}

}  // namespace sim
}  // namespace is_graphs
