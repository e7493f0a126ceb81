#pragma once

#include <string>
#include <vector>

#include "is_graphs/agraph/agraph.h"
#include "is_graphs/common/result.h"
#include "is_graphs/sim/scenario_config.h"
#include "is_graphs/sim/scene.h"

namespace is_graphs {
namespace sim {

/// How far an outside object must keep from every room of every storey (its outline), m: the
/// exterior walls stand between (0.3-0.5 m thick in the corpus).
constexpr double kOutsideClearance = 0.6;

/// The footprint of an outside object in bim (its box turned by yaw, or the tree crown's
/// 12-gon), counter-clockwise.
std::vector<Eigen::Vector2d> OutsideFootprint(const OutsideObjectConfig& object);

/// "" when the object stands clear of the building, else an error naming the field
/// ("scene.outside[2]: ...") and the room it reaches into.
std::string CheckOutside(const OutsideObjectConfig& object, const agraph::AGraph& graph,
                         const std::string& field);

/// The ground outside: the elevation of the lowest storey that has rooms (0 without any).
double GroundElevation(const agraph::AGraph& graph);

/// Adds every object of `objects` to the scene (CheckOutside first: the first error). Returns
/// a log line per object.
Result<std::vector<std::string>> AddOutsideWorld(SceneMesh* scene, const agraph::AGraph& graph,
                                                 const std::vector<OutsideObjectConfig>& objects);

}  // namespace sim
}  // namespace is_graphs
