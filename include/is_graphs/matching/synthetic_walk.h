#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "is_graphs/agraph/agraph.h"

namespace is_graphs {
namespace matching {

/// A walk a robot could have made through `rooms` (A-room ids, in the order it entered them;
/// for the synthetic S-Graph): a tour from the first room's centre that enters each next room
/// through a doorway it shares with a room entered before, sampled every `spacing` metres, in
/// the BIM frame. Legs that would cross a wall-surface under the BIM itself (a centre outside
/// its L-shaped room, a room reached without a doorway) are left out: each chain of the result
/// is one piece walked without a gap. With `through_walls` > 0, that many extra chains walk
/// from a room's centre straight through a wall it shares with a walked neighbour (an opening
/// built where the plan has none, or a wall not built yet): the truth crosses a BIM wall there.
std::vector<std::vector<Eigen::Vector2d>> SyntheticWalk(const agraph::AGraph& building,
                                                        const std::vector<int>& rooms,
                                                        double spacing, int through_walls,
                                                        std::mt19937_64& rng);

}  // namespace matching
}  // namespace is_graphs
