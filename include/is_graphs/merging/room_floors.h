#pragma once

#include <Eigen/Core>
#include <optional>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/sgraph/sgraph.h"

namespace is_graphs {
namespace merging {

/// M's height in B (z_B = z_M + it) from the floors the robot stood on: split levels, steps and
/// ramps inside a storey, where the storey's elevation is the floor of some of its rooms only
/// (or of none: a storey set at its lowest slab's bottom).
///
/// The newest keyframes on `level` that stand on flat ground (within `flat` m in height of the
/// keyframes before and after them: not on a step or a ramp) inside an A-room of `storey` (the
/// keyframe's x, y taken to B by `bim_x_map`) each give the room's floor_z less the height in M
/// of the floor they observed under them (an upward-facing S-Graph plane within 0.2 m of their
/// height less `standing`, the body's height above the floor); the median of the newest `count`.
/// Without such keyframes, the floor's height is taken as theirs less `standing`.
/// A keyframe whose value lies more than `max_step` from `storey_z` (the height from the storey's
/// elevation) does not stand on its room's floor: a stair's landing, a keyframe of another
/// storey above the room. None when no keyframe qualifies.
std::optional<double> HeightOfMapFromRoomFloors(const agraph::AGraph& a_graph, int storey,
                                                const sgraph::SGraph& s_graph, int level,
                                                const Eigen::Vector3d& bim_x_map, double standing,
                                                double storey_z, double max_step = 0.65,
                                                double flat = 0.03, int count = 9);

}  // namespace merging
}  // namespace is_graphs
