#pragma once

#include <Eigen/Core>
#include <vector>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace merging {

/// How an A-room's centre moves when one of its walls is built off the plan (issue 21): by
/// `per_offset` times the wall's offset δ (its deviation state's first part, along its plan
/// normal; DeviatedSurfaceMatchCost).
struct RoomCentreShift {
  int wall{-1};
  Eigen::Vector2d per_offset{Eigen::Vector2d::Zero()};  // ∂(centre x, y) / ∂δ
};

/// One entry per wall bounding `room`, from its polygon: an edge (length L, midpoint m) lying on
/// a wall-surface of the room, with normal n_s into the room, moved by δ along the wall's plan
/// normal n_w, takes the strip (n_w·n_s) δ L from the room's area A, so the centroid C moves by
/// −(n_w·n_s) δ L (m − C) / A. A rectangle's wall moved by δ moves C by δ/2, as the S-Graph's
/// centre of four planes moves. Turns are left out: about the wall's centre a turn θ moves C
/// along the wall by θ L³ / (12 A), tens of cm for a long external wall from a turn a single
/// poor S-plane can show (docs/merging.md). Edges on no surface of the room (an opening, a
/// virtual boundary) add nothing; a room of fewer than 3 corners or no area has no entry.
std::vector<RoomCentreShift> RoomCentreShifts(const agraph::AGraph& a_graph,
                                              const agraph::Room& room);

}  // namespace merging
}  // namespace is_graphs
