#pragma once

#include <set>
#include <string>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"

namespace is_graphs {
namespace agraph {

/// Index of the storey named `storey`, or, when no storey has that name, `storey` read as a
/// numeric index. The error lists the storeys there are.
Result<int> FindStorey(const AGraph& graph, const std::string& storey);

/// The lowest floor of storey index `storey`: its elevation, or a room's floor_z below it by up
/// to 0.6 m (a split level, a sunken room).
double StoreyFloor(const AGraph& graph, int storey);

/// The storey (id) a robot whose base is at height `z` in B stands on: the one with the highest
/// lowest floor (StoreyFloor) at or below z (+ 5 cm for rounding); -1 when z lies below every
/// storey. A match on another storey is a wrong match, however well x, y and yaw agree (floors
/// of one plan).
int StoreyAtHeight(const AGraph& graph, double z);

/// "" when a robot whose base is at height `z` in B stands within the building's storeys: from
/// `margin` below the lowest elevation to `margin` above the top storey's ceiling (its height;
/// 3 m where the IFC gives none). Otherwise what is wrong, with z and the storeys' span (a
/// robot that left the building, or a wrong height in B). "" for a graph without storeys.
std::string HeightOutsideStoreys(const AGraph& graph, double z, double margin = 1.0);

/// The sub-graph of one storey (by index), with ids re-indexed densely and references to
/// elements outside the storey dropped: walls of the storey with their surfaces, its rooms and
/// its doorways (a doorway left without rooms is dropped, with a warning). The result has one
/// storey (id 0).
Result<AGraph> SelectStorey(const AGraph& graph, int storey_index);
/// As above, the storey given by name or numeric index (see FindStorey).
Result<AGraph> SelectStorey(const AGraph& graph, const std::string& storey);

/// The storeys a wall-surface stands on: its own and those of the rooms it bounds (a wall
/// modelled on one storey may stand up through the next). Room ids out of range are skipped.
std::set<int> StoreysOfSurface(const AGraph& graph, const WallSurface& surface);

/// Area of a simple polygon (positive when counter-clockwise).
double SignedArea(const std::vector<Eigen::Vector2d>& polygon);

/// A multi-line human summary: building and source, then per storey the counts of surfaces
/// (x / y / other), walls, rooms (with names and areas) and doorways; the number of warnings.
std::string Summarize(const AGraph& graph);

}  // namespace agraph
}  // namespace is_graphs
