#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/geometry/triangle_mesh.h"

namespace is_graphs {
namespace sim {

/// How stairs are found in a building's mesh for routes across storeys (issue 22).
struct StairPathConfig {
  double min_tread_area{0.05};  // m²: smaller upward faces (nosings, handrail tops) are ignored
  double max_rise{0.3};         // m: the most between two treads walked one after the other
  double max_gap{0.3};  // m: the most between two treads' outlines in x-y (one tread between)
  double floor_clearance{0.8};   // m: the approach and exit points this far off the end treads
  double storey_tolerance{0.4};  // m: a flight's foot / head this near a storey's floor is on it
  double min_width{0.9};         // m: a narrower stair (a spiral, a ladder) is not walked
  std::string Validate() const;
};

/// A walkable way up a stair: from a point on the lower storey's floor in front of the bottom
/// tread, over the treads and landings (their centres), to a point on the upper storey's floor
/// past the top one. Walked in either direction.
struct StairPath {
  std::string name;  // the mesh objects: "IfcStair#123" or "IfcStairFlight#1+IfcStairFlight#2"
  int lower_storey{-1}, upper_storey{-1};
  int lower_room{-1}, upper_room{-1};      // the A-Graph rooms the end points stand in
  std::vector<Eigen::Vector3d> points;     // approach, tread / landing centres where it turns, exit
  std::vector<Eigen::Vector2d> footprint;  // convex hull of its treads in x-y (counter-clockwise)
  double width{0.0};                       // m: the narrowest tread across the walking direction
  double Length() const;                   // m, in x-y
};

/// The stairs of `mesh` (objects of class IfcStair or IfcStairFlight; the flights of one stair
/// joined where their treads meet) that join two storeys of `graph` with rooms at both ends.
/// Stairs that do not (too narrow, an end off every storey or outside every room, a rise
/// between treads beyond `max_rise`) are left out with a line in `skipped` naming why.
std::vector<StairPath> FindStairPaths(const geometry::TriangleMesh& mesh,
                                      const agraph::AGraph& graph,
                                      const StairPathConfig& config = StairPathConfig(),
                                      std::vector<std::string>* skipped = nullptr);

}  // namespace sim
}  // namespace is_graphs
