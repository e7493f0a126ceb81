#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"

namespace is_graphs {
namespace sim {

/// Index of the room of `storey` whose `name` or `long_name` is `name`; the error lists the
/// rooms there are.
Result<int> FindRoom(const agraph::AGraph& graph, int storey, const std::string& name);

/// A room anywhere in the building (routes across storeys, issue 22): "name @ storey" (the
/// storey by name or index) on that storey; else `name` on `preferred_storey`, else on the one
/// other storey that has it (an error names the storeys when several do).
Result<int> FindRoomInBuilding(const agraph::AGraph& graph, int preferred_storey,
                               const std::string& name);

/// Convex hull of points (counter-clockwise, no repeated or collinear points).
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points);

/// A point well inside the room's polygon: its centroid when that is inside and at least
/// `margin` from the edges, else the interior grid point farthest from the edges.
Eigen::Vector2d RoomInteriorPoint(const agraph::Room& room, double margin = 0.6);

/// The floor something at p on `storey` stands on: the floor_z of the room it stands in when that
/// lies more than 5 cm from `floor_z` (the start's floor: a split level), else floor_z (a few mm
/// of finishes keep a storey's objects on one floor).
double FloorUnder(const agraph::AGraph& graph, int storey, const Eigen::Vector2d& p,
                  double floor_z);

/// True when p is inside the (simple) polygon.
bool PointInPolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);
/// Distance from p to the polygon's boundary.
double DistanceToPolygonEdges(const std::vector<Eigen::Vector2d>& polygon,
                              const Eigen::Vector2d& p);

}  // namespace sim
}  // namespace is_graphs
