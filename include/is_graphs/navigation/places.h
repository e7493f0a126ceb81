#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/navigation/occupancy_grid.h"

namespace is_graphs {
namespace navigation {

/// Where `locate` sends the robot (docs/navigation.md); agraph_node's `locate_*` parameters.
struct PlaceConfig {
  double door_standoff{0.8};  // m in front of a door (from its wall's mid-plane)
  double wall_standoff{0.8};  // m in front of a wall's face
  double precision{0.01};     // m: a room's point farthest from its walls, found to this

  std::string Validate() const;
};

/// A goal in B: a room (its interior point farthest from its walls, yaw 0), a door (in front of
/// it on the side of its first room, facing it) or a wall (in front of its face's middle, on
/// the side of a room it bounds, facing it); z is the floor of the room it stands in (its floor_z:
/// split levels), else the storey's elevation.
struct Place {
  enum class Kind { kRoom, kDoor, kWall };
  Kind kind{Kind::kRoom};
  int id{-1};  // the room's, doorway's or wall's A-Graph id
  std::string name;
  std::string long_name;
  std::string guid;
  int storey{0};
  std::string storey_name;
  Eigen::Vector3d position{Eigen::Vector3d::Zero()};
  double yaw{0.0};
  Eigen::Vector2d faced{Eigen::Vector2d::Zero()};  // a door's or wall's point the yaw faces
  // false: SnapToFree found no free cell of the storey's map near it (not a goal a planner can
  // reach on that map); true until then.
  bool on_free_cell{true};
};

/// "room", "door", "wall".
const char* ToString(Place::Kind kind);

/// The interior point of a simple polygon farthest from its edges (a pole of inaccessibility,
/// by quad-tree refinement to `precision`), and that distance.
Eigen::Vector2d FarthestFromEdges(const std::vector<Eigen::Vector2d>& polygon, double precision,
                                  double* distance = nullptr);

/// Signed distance from `p` to the polygon's outline: > 0 inside.
double SignedDistanceToPolygon(const std::vector<Eigen::Vector2d>& polygon,
                               const Eigen::Vector2d& p);

/// Every room, door (and opening) and wall of a building as a goal, computed once; Locate then
/// looks a name up.
class PlaceIndex {
 public:
  PlaceIndex(const agraph::AGraph& graph, const PlaceConfig& config);

  /// The places whose room name, room long name, or door, wall or room IFC GlobalId is `query`
  /// (exactly; else ignoring case), on storey `storey` (name or index; "" any). More than one:
  /// ambiguous, all are returned. None: an error naming the closest names; an unknown storey:
  /// an error naming the storeys.
  Result<std::vector<Place>> Locate(const std::string& query, const std::string& storey = "") const;

  /// Moves each place of storey `storey` (of the `graph` given to the constructor) whose cell
  /// of `grid` (that storey's map) is not free to the nearest free cell within `radius` m, inside
  /// its room (a room) or inside a room of the storey (a door, a wall: then facing what it
  /// faced). Returns how many moved and how many found no free cell (left where they were,
  /// on_free_cell false).
  Eigen::Vector2i SnapToFree(int storey, const OccupancyGrid& grid, const agraph::AGraph& graph,
                             double radius = 1.5);

  const std::vector<Place>& places() const { return places_; }

 private:
  std::vector<Place> places_;
  std::vector<std::string> storey_names_;
};

}  // namespace navigation
}  // namespace is_graphs
