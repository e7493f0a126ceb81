#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace matching {

/// Node type for the categorical check: an S-Graph corridor (two opposed planes, centre known
/// only across its axis) or a room. A-Graph rooms are all kRoom; whether one can host an
/// S-corridor is decided by its geometry (two opposed surfaces as far apart as the corridor's).
enum class RoomKind { kRoom = 0, kCorridor = 1 };

/// A wall-surface as a point-normal in the horizontal plane: a vertical plane n·p = d with its
/// horizontal unit normal pointing into the room, and r = n·centre - d, how far the room centre
/// lies in front of it (invariant under rigid motions: the room-to-surface affinity).
struct PlaneFeature {
  int id{0};  // A-Graph wall-surface id or S-Graph plane id (for coplanar A pieces: the longest)
  Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};
  double d{0.0};
  double r{0.0};
  double length{0.0};  // horizontal extent; 0 when unknown
  // A-Graph: the ids of every coplanar wall-surface merged into this feature (a face split by
  // the converter, a corridor wall split by doorways), `id` among them; empty for S-planes.
  std::vector<int> pieces;
};

/// A room of either graph, reduced to what matching uses, in its own frame (B or M).
struct RoomDescriptor {
  int id{0};  // A-Graph or S-Graph room id
  RoomKind kind{RoomKind::kRoom};
  int storey{0};  // A-Graph storey id (an S-Graph is one floor: a hypothesis keeps to one storey)
  Eigen::Vector2d centre{Eigen::Vector2d::Zero()};
  std::vector<PlaneFeature> planes;
  std::vector<Eigen::Vector2d> polygon;  // A-Graph footprint; empty for S-Graph rooms
};

/// Descriptors of the A-Graph's rooms that have at least one usable vertical surface (others,
/// already reported by CheckAGraph, are left out). Coplanar surfaces of one room (a face split
/// by the converter) become one feature.
std::vector<RoomDescriptor> DescribeARooms(const agraph::AGraph& graph);

/// Descriptors of the S-Graph's rooms with at least one usable vertical plane (the first of a
/// duplicated id; non-finite elements left out).
std::vector<RoomDescriptor> DescribeSRooms(const sgraph::SGraph& graph);

/// Distance from p to the polygon's boundary, negative inside.
double SignedDistanceToPolygon(const std::vector<Eigen::Vector2d>& polygon,
                               const Eigen::Vector2d& p);

/// True when the room's planes span two directions at least `min_angle_rad` apart.
bool PlanesSpanTwoDirections(const std::vector<PlaneFeature>& planes, double min_angle_rad);
/// The same with the angle as its cosine (computed once by a caller testing many rooms).
bool PlanesSpanTwoDirectionsCos(const std::vector<PlaneFeature>& planes, double max_abs_cos);

}  // namespace matching
}  // namespace is_graphs
