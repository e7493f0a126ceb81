#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/sim/scenario_config.h"
#include "is_graphs/sim/stair_paths.h"
#include "is_graphs/sim/trajectory.h"

namespace is_graphs {
namespace sim {

/// A planned route: the start pose (x, y, yaw) in bim and the waypoints after it.
struct Route {
  Eigen::Vector3d start{Eigen::Vector3d::Zero()};
  std::vector<PlanarWaypoint> waypoints;
  std::vector<std::string> description;  // one line per leg, for the log
  int stairs_taken{0};                   // stair paths walked (up or down)
  int end_storey{-1};                    // the storey of the last room (-1: waypoints)
};

/// Plans the trajectory's route from a room of `storey` of the A-Graph.
///
/// With `config.rooms`: the rooms are visited in order along the shortest path in the doorway
/// graph (rooms are nodes, doorways joining two rooms of one storey are edges, and each of
/// `stairs` joins its lower and upper room: routes across storeys, issue 22). A room is looked
/// up on the storey of the room before it, else on the one other storey that has it; "name @
/// storey" picks the storey (FindRoomInBuilding). Within a room the
/// robot walks from its interior point to a point `doorway_clearance` in front of the doorway's
/// wall face, crosses the doorway straight along the wall normal to the point as far on the
/// other side, and walks on to the next room's interior point; in non-convex rooms it goes
/// around corners through inset polygon vertices. A stair is walked from its foot over its
/// treads and landings to its head (or down the other way), straight from and to the doorways
/// around it, and on each storey it joins the walk inside a room keeps clear of its footprint
/// (the flight, or the opening in the floor above it). `stairs` are used only when the rooms
/// span storeys: a route on one storey is planned as before stairs were known. With
/// `config.waypoints` the waypoints are used as given. Errors name the field under `field` (the
/// YAML section the route comes from): "trajectory.rooms[2] ('Kitchen'): not reachable from 'Hall'
/// through the doorways of storey 0".
Result<Route> PlanRoute(const agraph::AGraph& graph, int storey, const TrajectoryConfig& config,
                        const std::string& field = "trajectory",
                        const std::vector<StairPath>& stairs = {});

/// Shortest path inside a room's polygon from a to b keeping `clearance` from the edges where
/// possible (straight when visible, else through inset polygon corners), and outside the convex
/// `obstacles` by `clearance` (around their outset corners). Includes b, not a.
std::vector<Eigen::Vector2d> PathInsideRoom(
    const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
    double clearance = 0.3, const std::vector<std::vector<Eigen::Vector2d>>& obstacles = {});

}  // namespace sim
}  // namespace is_graphs
