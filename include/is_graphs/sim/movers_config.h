#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace is_graphs {
namespace sim {

/// Someone or something that walks its own path through the storey while the robot records (a
/// scenario's `scene.people`, sim/movers.h): a person (a vertical cylinder 0.5 m wide, 1.75 m
/// tall) or a cart (a box 1.0 x 0.6 x 1.0 m turned along its way). The path goes room to room
/// through the doorways (`rooms`, planned as the robot's route) or along `waypoints`, walked at
/// `speed` back and forth for the whole bag, `start` s ahead along it at the bag's start. A mover
/// keeps 0.8 m from the robot's centre: held back along its own path, as someone who waits.
struct MoverConfig {
  std::string type{"person"};              // person | cart
  std::vector<std::string> rooms;          // room names (two or more), or
  std::vector<Eigen::Vector2d> waypoints;  // in bim (two or more)
  double speed{0.0};                       // m/s; 0 = the kind's (person 1.3, cart 0.8)
  double start{0.0};                       // s walked before the bag's start
  double reflectivity{0.0};                // 0 = the kind's (person 0.3, cart 0.5)

  /// "" when valid, else "<field>.<key>: ..." (`field`: "scene.people[i]").
  std::string Validate(const std::string& field) const;
};

/// A door that swings open and shut (a scenario's `scene.doors`): a leaf the doorway's width,
/// up to 2.0 m high and 0.04 m thick, hinged at one side of the doorway, turning between shut (0)
/// and `open_deg` and back every `period` s (`phase`: where in the cycle at the bag's start,
/// 0..1; 0: shut). It stays open while the robot is within `hold_distance` of the doorway (a
/// robot does not walk through a shut door). The doorway: between the two rooms of `between`, or
/// by its name or GlobalId (`doorway`).
struct SwingingDoorConfig {
  std::vector<std::string> between;  // two room names of the storey, or
  std::string doorway;               // a doorway's name or GlobalId
  double period{20.0};               // s
  double phase{0.0};                 // 0..1
  double open_deg{90.0};
  double hold_distance{2.5};  // m

  /// "" when valid, else "<field>.<key>: ..." (`field`: "scene.doors[i]").
  std::string Validate(const std::string& field) const;
};

}  // namespace sim
}  // namespace is_graphs
