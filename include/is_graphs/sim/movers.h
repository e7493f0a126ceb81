#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/movers_config.h"

namespace is_graphs {
namespace sim {

/// A body standing on the floor at one instant: a vertical cylinder (a person) or a box turned
/// by `yaw` about its centre (a cart, a door leaf).
struct MovingBody {
  bool box{false};
  Eigen::Vector2d centre{Eigen::Vector2d::Zero()};
  double yaw{0.0};
  double radius{0.0};                             // cylinder
  Eigen::Vector3d size{Eigen::Vector3d::Zero()};  // box (along yaw, across, up)
  double base_z{0.0};
  float reflectivity{0.3};
};

/// The nearest point where `ray` meets one of `bodies` before `max_distance`: true and the
/// distance, the unit normal (facing the ray) and the reflectivity set, else false.
bool IntersectBodies(const std::vector<MovingBody>& bodies, const Ray& ray, float max_distance,
                     float* distance, Eigen::Vector3f* normal, float* reflectivity);

/// People, carts and doors that move while the robot records (`scene.people`, `scene.doors`;
/// sim/movers_config.h). Their paths and doorways are found once; BodiesAt(t) places them at a
/// time. Deterministic: no random numbers.
class Movers {
 public:
  /// The robot's position in bim at a time (s after the trajectory's start): movers step aside
  /// from it, doors stay open near it.
  using RobotAt = std::function<Eigen::Vector2d(double)>;

  Movers() = default;
  /// Plans each mover's path on `storey` (rooms through the doorways, as the robot's route, or
  /// the waypoints given, each in a room of the storey) and checks it walkable in `scene` at
  /// `floor_z`; finds each door's doorway. Errors name the field: "scene.people[1].waypoints:
  /// the walk from (x, y) to (x, y) is blocked at (x, y) ...".
  static Result<Movers> Create(const std::vector<MoverConfig>& people,
                               const std::vector<SwingingDoorConfig>& doors,
                               const agraph::AGraph& graph, int storey, double floor_z,
                               const EmbreeScene& scene, RobotAt robot);

  bool empty() const { return people_.empty() && doors_.empty(); }
  /// Every mover and door leaf at time t.
  std::vector<MovingBody> BodiesAt(double t) const;
  /// One line per mover and door, for the log.
  const std::vector<std::string>& log() const { return log_; }

  /// Where along a path (polyline, walked back and forth) a mover is after walking `s` m, and
  /// the direction it walks (unit).
  static Eigen::Vector2d AlongPath(const std::vector<Eigen::Vector2d>& path, double s,
                                   Eigen::Vector2d* heading);

 private:
  struct Person {
    MoverConfig config;
    std::vector<Eigen::Vector2d> path;
  };
  struct Door {
    SwingingDoorConfig config;
    Eigen::Vector2d hinge, along, middle;  // hinge, unit direction to the other jamb, centre
    double width{0.9}, height{2.0};
  };
  std::vector<Person> people_;
  std::vector<Door> doors_;
  double floor_z_{0.0};
  RobotAt robot_;
  std::vector<std::string> log_;
};

}  // namespace sim
}  // namespace is_graphs
