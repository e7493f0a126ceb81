#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/sim/scenario_config.h"
#include "is_graphs/sim/trajectory.h"

namespace is_graphs {
namespace sim {

/// A planned route: the start pose (x, y, yaw) in bim and the waypoints after it.
struct Route {
  Eigen::Vector3d start{Eigen::Vector3d::Zero()};
  std::vector<PlanarWaypoint> waypoints;
  std::vector<std::string> description;  // one line per leg, for the log
};

/// Plans the trajectory's route on one storey of the A-Graph.
///
/// With `config.rooms`: the rooms are visited in order along the shortest path in the doorway
/// graph (rooms are nodes, doorways joining two rooms of the storey are edges). Within a room the
/// robot walks from its interior point to a point `doorway_clearance` in front of the doorway's
/// wall face, crosses the doorway straight along the wall normal to the point as far on the
/// other side, and walks on to the next room's interior point; in non-convex rooms it goes
/// around corners through inset polygon vertices. With `config.waypoints` the waypoints are
/// used as given. Errors name the field under `field` (the YAML section the route comes from):
/// "trajectory.rooms[2] ('Kitchen'): not reachable from 'Hall' through the doorways of storey 0".
Result<Route> PlanRoute(const agraph::AGraph& graph, int storey, const TrajectoryConfig& config,
                        const std::string& field = "trajectory");

/// Shortest path inside a room's polygon from a to b keeping `clearance` from the edges where
/// possible (straight when visible, else through inset polygon corners). Includes b, not a.
std::vector<Eigen::Vector2d> PathInsideRoom(const std::vector<Eigen::Vector2d>& polygon,
                                            const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                            double clearance = 0.3);

}  // namespace sim
}  // namespace is_graphs
