#pragma once

// A simulated horizontal LiDAR slice, ROS-free, for the tests and the bench of ScanSearch.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/matching/rigid_fit.h"

namespace is_graphs {
namespace matching {

/// `rays` rays over the full turn from `robot_in_bim` (the first along the robot's heading)
/// against every wall-surface segment of `storey` (the nearest hit within `max_range`; a ray
/// hitting nothing gives no point), each range with Gaussian noise of `noise_sigma` (seeded by
/// `seed`), the hits expressed in M: bim_T_map⁻¹ applied.
std::vector<Eigen::Vector2d> SimulatedSlice(const agraph::AGraph& g, int storey,
                                            const Pose2& robot_in_bim, const Pose2& bim_T_map,
                                            int rays, double max_range, double noise_sigma,
                                            std::uint64_t seed);

}  // namespace matching
}  // namespace is_graphs
